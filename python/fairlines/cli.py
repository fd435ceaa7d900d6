"""The `fairlines` command line.

    fairlines version
    fairlines fit POINTS.csv [--degree 3] [--n-control N] [--parameterization chord] -o curve.json
    fairlines import TABLE --lpp L --beam B --draft T [--format auto] [--stations 20] [--depth D] [--analysis] -o hull.json
    fairlines build hull.json -o OUTDIR
    fairlines design --lpp L --breadth B --draft T --depth D --cb CB --lcb LCB [--bulb] -o hull.json
    fairlines export | lines | hydrostatics ...   (see fairlines.cli_output)
    fairlines mesh HULL.json --size 2.0 [--draft T] [--open] [--full] [--format gdf] -o mesh.msh
    fairlines sweep STUDY.toml [--scheduler tcp://host:8786] [--workers N] [-o table.parquet] [--fresh]
"""

from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np

from . import __version__, fit_curve
from .io import save_json
from .meshing import MAX_MESH_ELEMENTS


def _fit(args) -> int:
    try:
        pts = np.loadtxt(args.points, delimiter=",", ndmin=2)
    except (OSError, ValueError) as exc:
        print(f"fairlines fit: cannot read {args.points}: {exc}", file=sys.stderr)
        return 2
    fit = fit_curve(pts, degree=args.degree, n_control=args.n_control, parameterization=args.parameterization,
                    knots=args.knots)
    print(f"{len(pts)} points, {fit.curve.n_control} control points, degree {fit.curve.degree}: "
          f"max deviation {fit.max_deviation:.6g}, rms {fit.rms_deviation:.6g} (units of the input)")
    if args.output:
        save_json(fit.curve, args.output)
        print(f"wrote {args.output}")
    return 0


def _progress(msg):
    print(f"  .. {msg}", file=sys.stderr, flush=True)


def _import(args) -> int:
    import json
    import pathlib

    from .offsets import read_hull_data
    data = read_hull_data(args.table, args.lpp, args.beam, args.draft, fmt=args.format, n_stations=args.stations)
    if not args.analysis:
        return _import_design(data, args)
    from .preprocess import import_hull
    doc = import_hull(data, progress=_progress)
    h, fp = doc["hydrostatics_input"], doc["form_parameters"]
    print(f"{data.name}: Lpp {data.lpp:g} m, B {data.beam:g} m, T {data.draft:g} m; "
          f"{len(data.sections)} sections, {len(data.grids)} grids")
    for note in data.notes:
        print(f"note: {note}")
    print(f"input ({h['method']}): volume {h['volume']:.6g} m3, LCB {h['lcb_pct']:+.3f} % Lpp, "
          f"Cb {h['cb']:.4f}, Cp {h['cp']:.4f}, Cm {h['cm']:.4f}, Cwp {h['cwp']:.4f}")
    def span(d):
        return "none" if d["x_aft"] is None else f"x {d['x_aft']:.4g}..{d['x_fwd']:.4g} m"
    print(f"form parameters: flat of side {span(fp['FOS'])}, flat of bottom {span(fp['FOB'])}, "
          f"DWL entrance half-angle {fp['DWL']['entrance_angle_deg']:.1f} deg, bow feature: {fp['bow']['kind']}")
    pathlib.Path(args.output).write_text(json.dumps(doc, indent=1))
    print(f"wrote {args.output}")
    return 0


def _import_design(data, args) -> int:
    import json
    import pathlib

    from .import_design import import_design
    desc = import_design(data, depth=args.depth, progress=_progress)
    for note in data.notes:
        print(f"note: {note}")
    bc = desc["basic_curves"]["sac"]
    print(f"{data.name}: whole-ship description, Lpp {data.lpp:g} m, B {data.beam:g} m, T {data.draft:g} m, "
          f"D {desc['principal']['D']:.4g} m, ends {desc['ends']['aft']:.4g} .. {desc['ends']['fore']:.4g} m; "
          f"SAC volume {bc.get('volume', float('nan')):.6g} m3, LCB {bc.get('lcb', float('nan')):.6g} m")
    print(f"notes: {desc['notes']}")
    pathlib.Path(args.output).write_text(json.dumps(desc, indent=1))
    print(f"wrote {args.output} (fl.Hull.from_json builds it)")
    return 0


def _build(args) -> int:
    from .preprocess import build_hull, comparison_table
    report = build_hull(args.hull, args.output, progress=_progress)
    print(report["name"])
    print(comparison_table(report))
    print(f"wrote {args.output}/report.json and one surface JSON/OBJ per subdomain")
    return 0


def _mesh(args) -> int:
    import pathlib
    import time

    from .hull import Hull
    from .meshing import mesh_hull
    from .mesh_io import write_gdf, write_mar, write_mesh
    t0 = time.perf_counter()
    _progress(f"reading {args.hull}")
    hull = Hull.from_json(args.hull)
    _progress("composing the hull (bare hull, bulb and blend when the description has a bulb)")
    composed = hull.composed_hull()
    if composed.blend_note:
        _progress(composed.blend_note)

    def report(done, total, name):
        _progress(f"meshed face {done}/{total}: {name}")
    m = mesh_hull(composed, size=args.size, draft=args.draft, lids=not args.open, full=args.full, progress=report,
                  max_elements=args.max_elements, chordal_tolerance=args.tolerance, all_quad=args.all_quad)
    q = m.quality()
    out = pathlib.Path(args.output)
    fmt = args.format or out.suffix.lstrip(".").lower()
    _progress(f"writing {out} ({fmt})")
    if fmt == "gdf":
        write_gdf(m, out)
    elif fmt == "mar":
        write_mar(m, out)
    else:
        write_mesh(m, out, None if args.format is None else args.format)
    print(f"{len(m.vertices)} nodes, {q['quads']} quads, {q['triangles']} triangles ({100 * q['quad_fraction']:.1f} % "
          f"quads); scaled Jacobian min {q['min_scaled_jacobian']:.3f} mean {q['mean_scaled_jacobian']:.3f}; "
          f"{q['inverted']} inverted; {q['open_edges']} open edges; parts {', '.join(m.parts)}; "
          f"{time.perf_counter() - t0:.2f} s")
    print(f"wrote {out}")
    return 0


def _add_fit_parser(sub) -> None:
    f = sub.add_parser("fit", help="fit a B-spline curve to points (CSV, one point per row)")
    f.add_argument("points")
    f.add_argument("--degree", type=int, default=3)
    f.add_argument("--n-control", type=int, default=None, help="control points (default: interpolate)")
    f.add_argument("--parameterization", default="chord", choices=["chord", "centripetal", "uniform"])
    f.add_argument("--knots", default="average", choices=["average", "hartley_judd"])
    f.add_argument("-o", "--output", help="write the curve as JSON")


def _add_import_parsers(sub) -> None:
    """``import`` (hull data -> description) and ``build`` (analysis -> faired surfaces)."""
    im = sub.add_parser("import", help="read offsets / section points / a point grid; write the whole-ship description")
    im.add_argument("table", help="offsets CSV, x,y,z section CSV, Tecplot point grid in metres (x from the AP, "
                                  "y >= 0, z up; .dat), or a DTMB 5415 / KCS grid folder")
    im.add_argument("--lpp", type=float, help="length between perpendiculars, m")
    im.add_argument("--beam", type=float, help="moulded beam, m")
    im.add_argument("--draft", type=float, help="design draft, m")
    im.add_argument("--format", default="auto", choices=["auto", "offsets", "sections", "tecplot", "dtmb5415", "kcs"])
    im.add_argument("--stations", type=int, default=20,
                    help="station intervals between the perpendiculars in a normalised table (default 20)")
    im.add_argument("--depth", type=float, help="depth D, m (default: the top of the data)")
    im.add_argument("--analysis", action="store_true",
                    help="write the form-parameter analysis that 'fairlines build' reads instead of the design")
    im.add_argument("-o", "--output", required=True, help="whole-ship hull description JSON to write")
    b = sub.add_parser("build", help="rebuild the faired hull of an imported description; report deviation and "
                                     "hydrostatics")
    b.add_argument("hull", help="analysis JSON written by 'fairlines import --analysis'")
    b.add_argument("-o", "--output", required=True, help="output folder")


def _add_mesh_parser(sub) -> None:
    me = sub.add_parser("mesh", help="quad-dominant mesh of a hull description's composed hull (CFD / BEM files)")
    me.add_argument("hull", help="hull description JSON (bare hull, and bulb if it has a 'bulb' section)")
    me.add_argument("--size", type=float, required=True, help="maximum element edge length, m")
    me.add_argument("--tolerance", type=float, default=0.0, help="chordal tolerance, m (default size / 100)")
    me.add_argument("--draft", type=float, default=None, help="mesh only the wetted part below this draft, m")
    me.add_argument("--open", action="store_true", help="no lids: leave the waterplane (and centre plane) open, "
                                                       "as a BEM code wants")
    me.add_argument("--full", action="store_true", help="mirror into the full hull")
    me.add_argument("--all-quad", action="store_true", help="quadrilaterals only")
    me.add_argument("--max-elements", type=int, default=MAX_MESH_ELEMENTS,
                    help=f"most elements asked for (area / size^2); default {MAX_MESH_ELEMENTS}")
    me.add_argument("--format", default=None, help="gdf (WAMIT), mar (Nemoh) or a meshio format name; default from "
                                                   "the output suffix (.msh .vtu .stl .obj .med ...)")
    me.add_argument("-o", "--output", required=True, help="mesh file to write")


def _parser() -> argparse.ArgumentParser:
    """The command line: one sub-command per task (the design, fairness, output and sweep
    commands add their own parsers from their modules)."""
    from . import cli_design, cli_fairness, cli_output, sweep_cli
    ap = argparse.ArgumentParser(prog="fairlines", description="Fair parametric hull design.")
    sub = ap.add_subparsers(dest="command", required=True)
    sub.add_parser("version", help="print the version")
    _add_fit_parser(sub)
    _add_import_parsers(sub)
    cli_output.add_parsers(sub)
    cli_design.add_parser(sub)
    cli_fairness.add_parser(sub)
    _add_mesh_parser(sub)
    sweep_cli.add_parser(sub)
    return ap


def _run(args) -> int:
    """Runs the parsed command; its exit status."""
    from . import cli_design, cli_fairness, cli_output, sweep_cli
    if args.command == "version":
        print(__version__)
        return 0
    if args.command == "import":
        return _import(args)
    if args.command == "build":
        return _build(args)
    if args.command == cli_design.COMMAND:
        return cli_design.run(args)
    if args.command == cli_fairness.COMMAND:
        return cli_fairness.run(args)
    if args.command in cli_output.COMMANDS:
        return cli_output.run(args)
    if args.command == "mesh":
        return _mesh(args)
    if args.command == "sweep":
        return sweep_cli.run(args)
    return _fit(args)


#: The sub-commands' options that name a file to write.
OUTPUT_OPTIONS = ("output", "table", "plot", "sac_plot")
#: Sub-commands whose output is a folder they create, parents too.
CREATES_OUTPUT_FOLDER = ("build",)


def _output_folder_missing(args) -> str | None:
    """The folder of the command's output file when it does not exist (checked before the work,
    so a long mesh or sweep is not lost to a mistyped path)."""
    if args.command in CREATES_OUTPUT_FOLDER:
        return None
    for option in OUTPUT_OPTIONS:
        value = getattr(args, option, None)
        for out in value if isinstance(value, list) else [value]:  # lines writes several files
            if isinstance(out, str) and out and not pathlib.Path(out).expanduser().parent.is_dir():
                return str(pathlib.Path(out).expanduser().parent)
    return None


def main(argv=None) -> int:
    args = _parser().parse_args(argv)
    if (folder := _output_folder_missing(args)) is not None:
        print(f"fairlines {args.command}: the output's folder {folder!r} does not exist; expected an existing folder",
              file=sys.stderr)
        return 2
    try:
        return _run(args)
    except ValueError as exc:  # bad input: a one-line message, no traceback
        print(f"fairlines {args.command}: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # a file that cannot be read or written (a missing folder, no permission)
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"fairlines {args.command}: {where}{exc.strerror or exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
