"""Writing the hull out of the tool (the whole Panamax container ship of examples/container_ship.json,
bare and composed with its bulb and blend): lines plan (geometry, then each format), curves
of form, and the CAD formats through OpenCASCADE / rhino3dm with their read-back figures.
Medians of repeated runs; OpenCASCADE and rhino3dm are optional (skipped when missing)."""

import pathlib
import sys
import tempfile

import common  # noqa: F401  (sets single-thread BLAS before numpy loads)
import numpy as np

import fairlines as fl
from common import median_time, report
from fairlines.curves_of_form import curves_of_form
from fairlines.lines_plan import lines_plan

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "container_ship.json"
PART = dict(lpp=244.8, beam=32.25, draft=11.0, depth=19.0)


def main():
    hull = fl.Hull.from_json(str(EXAMPLE))
    bare = hull.bare_hull_surface()
    composed = hull.composed_hull()
    out = pathlib.Path(tempfile.mkdtemp())
    print("Lines plan (A3), median of 3-7 runs, this 2-core machine shared with other work")
    for name, h in (("bare hull", bare), ("composed (bulb + blend)", composed)):
        t = median_time(lambda: lines_plan(h, **PART), repeat=3, min_time=0.0)
        report(f"lines plan geometry + layout, {name}", 1e3 * t, "ms")
    plan = lines_plan(composed, **PART)
    for suffix in (".svg", ".pdf", ".png", ".dxf"):
        t = median_time(lambda: plan.save(out / f"lines{suffix}", dpi=150), repeat=3, min_time=0.0)
        report(f"write {suffix} (composed)", 1e3 * t, "ms", f"{(out / f'lines{suffix}').stat().st_size / 1024:.0f} KiB")
    drafts = np.arange(1.0, 19.01, 1.0)
    t = median_time(lambda: curves_of_form(bare, drafts, **{k: PART[k] for k in ("lpp", "beam", "depth")}),
                    repeat=5, min_time=0.0)
    report("curves of form, 19 drafts (bare hull)", 1e3 * t, "ms")
    try:
        from fairlines import cad
    except ImportError:
        print("  OpenCASCADE not installed: CAD figures skipped")
        return
    print("CAD exchange: write (median of 3), then read back with OpenCASCADE")
    surfaces = [s for s, _ in cad._patches(composed)]
    for name, h, what, full in (("bare, solid, half", bare, "solid", False), ("bare, solid, full", bare, "solid", True),
                                ("composed, surfaces", composed, "surfaces", False),
                                ("composed, solid, full", composed, "solid", True)):
        for suffix in (".step", ".iges", ".3dm"):
            if suffix == ".3dm" and what == "solid" and name.startswith("bare"):
                continue
            path = out / f"h{suffix}"
            try:
                t = median_time(lambda: cad.export_cad(h, path, what=what, full=full), repeat=3, min_time=0.0)
            except ImportError as exc:
                print(f"  {name} {suffix}: {exc}")
                continue
            extra = f"{path.stat().st_size / 1024:.0f} KiB"
            if suffix != ".3dm":
                v = cad.verify(cad.read_cad(path), surfaces if what == "surfaces" else [], samples=7)
                extra += f"; faces {v['faces']}, valid {v['valid']}, closed {v['closed']}, volume {v['volume']:.1f} m3"
                if "max_deviation" in v:
                    extra += f", max deviation {v['max_deviation']:.1e} m"
            report(f"{name} {suffix}", 1e3 * t, "ms", extra)
    print(f"  reference volumes: bare half {fl.hydrostatics(bare, 19.0).volume / 2:.1f} m3 (quadrature); "
          f"composed half {fl.hydrostatics(bare, 19.0).volume / 2 + composed.volume - fl.compose([bare]).volume:.1f} m3 "
          "(quadrature + what the bulb and blend add on the meshes)")


if __name__ == "__main__":
    sys.exit(main())
