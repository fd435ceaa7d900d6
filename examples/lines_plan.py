"""Lines plan, curves of form and CAD files of the example ship (the Panamax container ship of
examples/container_ship.json with its bulb and blend composed).

    python examples/lines_plan.py --out out/

Writes out/lines/: lines_plan.{png,pdf,svg,dxf} (the whole hull), lines_plan_bow.png (bow
close-up), curves_of_form.{csv,png}, sac.png, and -- when OpenCASCADE / rhino3dm are
installed (pip install fairlines[cad]) -- ship.step (AP242), ship.iges (closed solid
of the full ship) and ship.3dm, each read back and checked.
"""

import argparse
import json
import pathlib

import numpy as np

import fairlines as fl
from fairlines.curves_of_form import curves_of_form
from fairlines.lines_plan import closeup, lines_plan

HERE = pathlib.Path(__file__).resolve().parent


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out")
    out = pathlib.Path(ap.parse_args().out) / "lines"
    out.mkdir(parents=True, exist_ok=True)
    description = json.loads((HERE / "container_ship.json").read_text())
    pr = description["principal"]
    part = dict(lpp=pr["Lpp"], beam=pr["B"], draft=pr["T"], depth=pr["D"])
    hull = fl.Hull.from_json(description)
    bare = hull.bare_hull_surface()
    composed = fl.compose_with_blend(bare, hull.bulbous_bow())
    plan = lines_plan(composed, **part, name="Panamax container ship")
    for suffix in (".png", ".pdf", ".svg", ".dxf"):
        plan.save(out / f"lines_plan{suffix}")
    closeup(composed, "bow", **part, name="Panamax container ship").save(out / "lines_plan_bow.png")
    print(f"lines plan at 1:{plan.scale:g} on A3: {out}/lines_plan.(png|pdf|svg|dxf), lines_plan_bow.png")
    cof = curves_of_form(bare, np.arange(1.0, part["depth"] - 1.5, 1.0), lpp=part["lpp"], beam=part["beam"],
                         depth=part["depth"], trims=(0.0, 2.0), design_draft=part["draft"])
    cof.write_csv(out / "curves_of_form.csv")
    cof.plot(out / "curves_of_form.png", "Panamax container ship (bare hull)")
    cof.plot_sac(out / "sac.png", hull.basic_curves["sac"], "Panamax container ship")
    d = cof.design
    print(f"at T = {part['draft']} m: volume {d['volume']:.1f} m3, KMt {d['kmt']:.3f} m, KMl {d['kml']:.2f} m, "
          f"TPC {d['tpc']:.2f} t/cm, MCT1cm {d['mct1cm']:.1f} t m/cm")
    try:
        from fairlines import cad
        for name, kw in (("ship.step", dict(schema="AP242")), ("ship.iges", {})):
            cad.export_cad(composed, out / name, what="solid", full=True, **kw)
            v = cad.verify(cad.read_cad(out / name))
            print(f"{name}: {v['faces']} faces, valid {v['valid']}, closed {v['closed']}, volume {v['volume']:.1f} m3")
        cad.export_cad(composed, out / "ship.3dm")
        print("ship.3dm: the three surfaces and the closed mesh")
    except ImportError as exc:
        print(f"CAD files skipped: {exc}")


if __name__ == "__main__":
    main()
