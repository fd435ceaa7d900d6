"""Lines plan, curves of form and (optionally) CAD files of the example ship: the whole Panamax
container ship of examples/container_ship.json, its bulb and blend composed.

    python examples/lines_plan.py --out out/ [--cad] [--docs docs/]

Writes out/lines/: lines_plan.{png,pdf,svg,dxf} (the whole ship on A3), lines_plan_bow.png and
lines_plan_stern.png (close-ups), curves_of_form.{csv,png} (upright and 2 m by the stern) and
sac.png; docs/lines_plan.png for the README. With --cad (needs pip install fairlines[cad]):
ship.step (AP242) and ship.iges (closed solid of the full ship), each read back and checked,
and ship.3dm.
"""

import argparse
import pathlib

import numpy as np

import fairlines as fl
from fairlines.curves_of_form import curves_of_form, highest_draft
from fairlines.lines_plan import closeup, lines_plan

HERE = pathlib.Path(__file__).resolve().parent
NAME = "Panamax container ship"
#: Trims of the curves of form (m by the stern).
TRIMS = (0.0, 2.0)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out")
    ap.add_argument("--docs", default=str(HERE.parent / "docs"), help="where lines_plan.png for the README goes ('' for none)")
    ap.add_argument("--cad", action="store_true", help="also write STEP, IGES and 3dm and read them back")
    args = ap.parse_args()
    out = pathlib.Path(args.out) / "lines"
    out.mkdir(parents=True, exist_ok=True)
    hull = fl.Hull.from_json(str(HERE / "container_ship.json"))
    pr = hull.description.principal
    part = dict(lpp=pr.lpp, beam=pr.breadth, draft=pr.draft, depth=pr.depth)
    bare, composed = hull.bare_hull_surface(), hull.composed_hull()
    print(composed.blend_note)
    plan = lines_plan(composed, **part, name=NAME)
    for suffix in (".png", ".pdf", ".svg", ".dxf"):
        plan.save(out / f"lines_plan{suffix}")
    if args.docs:
        plan.save(pathlib.Path(args.docs) / "lines_plan.png", dpi=150)
    for end in ("bow", "stern"):
        closeup(composed, end, **part, name=NAME).save(out / f"lines_plan_{end}.png")
    print(f"lines plan at 1:{plan.scale:g} (body plan 1:{plan.body_scale:g}) on A3: {out}/lines_plan.(png|pdf|svg|dxf), "
          "lines_plan_bow.png, lines_plan_stern.png")
    # whole metres up to the highest draft at which the trimmed waterplane stays below the deck
    top = min(highest_draft(bare, part["depth"], part["lpp"], t) for t in TRIMS)
    cof = curves_of_form(bare, np.arange(1.0, np.floor(top) + 0.5, 1.0), lpp=part["lpp"], beam=part["beam"],
                         depth=part["depth"], trims=TRIMS, design_draft=part["draft"])
    cof.write_csv(out / "curves_of_form.csv")
    cof.plot(out / "curves_of_form.png", f"{NAME} (bare hull)")
    cof.plot_sac(out / "sac.png", hull.basic_curves["sac"], NAME)
    d = plan.hydrostatics
    print(f"at T = {part['draft']} m (with bulb): volume {d['volume']:.1f} m3, Cb {d['cb']:.4f}, KMt {d['kmt']:.3f} m, "
          f"KMl {d['kml']:.2f} m, TPC {d['tpc']:.2f} t/cm, MCT1cm {d['mct1cm']:.1f} t m/cm, S {d['wetted_surface']:.0f} m2")
    if args.cad:
        write_cad(composed, out)


def write_cad(composed, out):
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
