"""`make demo`: run every example step of the pipeline that exists and write its outputs.

    python examples/demo.py --out out/
"""

import argparse
import pathlib
import runpy
import shutil
import sys

HERE = pathlib.Path(__file__).resolve().parent

# Pipeline steps in order; each is a script in examples/ taking --out.
STEPS = [
    ("NURBS core: fit a surface to hull offsets", "fit_wigley_surface.py"),
    ("Form-parameter curves: Area and yC families (Kim, Shin & Kim 2002, Figs. 3-4)", "form_curve_families.py"),
    ("Pre-processor: form parameters and faired surfaces of the reference hulls", "import_reference_hulls.py"),
    ("Hull designer: whole ships from particulars (container ship, tanker, ferry, coaster)", "design_ship.py"),
    ("Bulbous bow, blend and Boolean composition into a watertight hull (container ship)", "compose_ship.py"),
    ("Lines plan, curves of form and CAD files (container ship)", "lines_plan.py"),
]
# Pictures for the README written straight to docs/ (their scripts take the picture's path).
PICTURES = [("Quad-dominant solver mesh of the whole ship", "mesh_picture.py", "hull_mesh.png"),
            ("Fairness of the whole ship's lines: curvature combs", "fairness_combs.py", "fairness_combs.png")]
SWEEP_STUDY = HERE / "sweep_study.toml"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out", help="output folder (default: out)")
    args = ap.parse_args()
    out = pathlib.Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    for title, script in STEPS:
        print(f"\n== {title} ({script}) ==", flush=True)
        sys.argv = [script, "--out", str(out)]
        try:
            runpy.run_path(str(HERE / script), run_name="__main__")
        except SystemExit as e:  # a step ending with sys.exit(0) must not end the demo
            if e.code not in (None, 0):
                raise
    for title, script, png in PICTURES:
        print(f"\n== {title} ({script}) ==", flush=True)
        sys.argv = [script, str(HERE.parent / "docs" / png)]
        runpy.run_path(str(HERE / script), run_name="__main__")
    print("\n== Real ships imported as whole-ship designs: fidelity and lines (tools/import_lines.py) ==", flush=True)
    sys.argv = ["import_lines.py", "--out", str(HERE.parent / "docs")]
    try:
        runpy.run_path(str(HERE.parent / "tools" / "import_lines.py"), run_name="__main__")
    except SystemExit as e:
        if e.code not in (None, 0):
            raise
    print(f"\n== Design-space sweep on a local Dask cluster ({SWEEP_STUDY.name}) ==", flush=True)
    from fairlines.cli import main as fairlines_main

    (out / "sweep").mkdir(parents=True, exist_ok=True)  # the command line refuses a missing output folder
    code = fairlines_main(["sweep", str(SWEEP_STUDY), "-o", str(out / "sweep" / "study.parquet"), "--fresh",
                           "--plot", str(out / "sweep" / "sweep_study.png")])
    if code != 0:
        raise SystemExit(f"the sweep failed (exit status {code})")
    shutil.copy(out / "sweep" / "sweep_study.png", HERE.parent / "docs" / "sweep_study.png")
    compact_pictures()
    print(f"\nOutputs are in {out}")


#: README pictures written by `make demo` (the Blender renders by `make blender-demo` before it).
DOCS_PICTURES = ("designed_ships.png", "lines_plan.png", "hull_mesh.png", "sweep_study.png", "ship.png",
                 "ship_zebra.png", "fairness_combs.png", "imported_wigley_table.png", "imported_series60.png",
                 "imported_kcs.png", "imported_dtmb5415.png")


def compact_pictures(docs=HERE.parent / "docs"):
    """Store the README pictures with a 256-colour palette (dithered): a third to a tenth of the
    size, so the repository does not grow by megabytes each time they are regenerated."""
    from PIL import Image

    for name in DOCS_PICTURES:
        path = docs / name
        if path.exists():
            Image.open(path).convert("RGB").quantize(256, dither=Image.Dither.FLOYDSTEINBERG).save(path, optimize=True)


if __name__ == "__main__":
    main()
