"""The ``fairlines export``, ``fairlines lines`` and ``fairlines hydrostatics`` subcommands.

    fairlines export HULL -o hull.step [--what solid|surfaces] [--full] [--schema AP214|AP242]
    fairlines lines HULL -o lines.pdf [--closeup bow|stern] [--lpp L --beam B --draft T --depth D]
    fairlines hydrostatics HULL -o curves.csv [--drafts 1:19:1] [--trims 0,1] [--plot curves.png]

HULL is a surface JSON written by ``fairlines.io.save_json`` (or several, one per subdomain)
or a hull description JSON (``fl.Hull.from_json``). A description with a bulbous bow is the ship
composed (bare hull, bulb and blend: ``Hull.composed_hull``) unless ``--bare`` asks for its bare
hull alone; ``--compose`` composes one without a bulb too (its bare hull closed by deck, transom
and centre plane). Principal particulars come from the description's ``principal`` section
unless given.
"""

from __future__ import annotations

import json
import pathlib

import numpy as np

from ._native import InvalidInput, NurbsSurface

__all__ = ["add_parsers", "run", "COMMANDS"]

COMMANDS = ("export", "lines", "hydrostatics")


def _hull_arg(p):
    p.add_argument("hull", nargs="+", help="surface JSON file(s) or a hull description JSON")
    which = p.add_mutually_exclusive_group()
    which.add_argument("--compose", action="store_true",
                       help="description: the composed hull (the default with a bulb; closes one without a bulb)")
    which.add_argument("--bare", action="store_true", help="description: the bare hull alone, without its bulb")
    for k, h in (("lpp", "length between perpendiculars (m), AP at x = 0"), ("beam", "moulded breadth B (m)"),
                 ("draft", "design draft T (m)"), ("depth", "depth D (m)")):
        p.add_argument(f"--{k}", type=float, help=h)


def add_parsers(sub) -> None:
    """Register the three subcommands on an argparse subparsers object."""
    e = sub.add_parser("export", help="write the hull as STEP / IGES / Rhino 3dm (OpenCASCADE, rhino3dm)")
    _hull_arg(e)
    e.add_argument("-o", "--output", required=True, help="file: .step/.stp, .iges/.igs or .3dm")
    e.add_argument("--what", default="solid", choices=["solid", "surfaces"])
    e.add_argument("--full", action="store_true", help="full ship (mirrored) instead of the half")
    e.add_argument("--schema", default="AP214", choices=["AP214", "AP242"])
    e.add_argument("--verify", action="store_true", help="read the file back with OpenCASCADE and report")
    ln = sub.add_parser("lines", help="lines plan: profile, half-breadth and body plan (SVG, PDF, PNG, DXF)")
    _hull_arg(ln)
    ln.add_argument("-o", "--output", required=True, nargs="+", help="file(s): .svg, .pdf, .png, .dxf")
    ln.add_argument("--closeup", choices=["bow", "stern"], help="a close-up of one end")
    ln.add_argument("--name", default=None, help="ship name for the title block")
    hy = sub.add_parser("hydrostatics", help="curves of form over drafts (and trims): CSV and plots")
    _hull_arg(hy)
    hy.add_argument("-o", "--output", required=True, help="CSV table")
    hy.add_argument("--drafts", default=None, help="FROM:TO:STEP or a comma list (m); default 19 from T/10 up to the deck (at every trim)")
    hy.add_argument("--trims", default="0", help="comma list of trims by the stern (m)")
    hy.add_argument("--plot", help="curves-of-form plot (.png/.pdf/.svg)")
    hy.add_argument("--sac-plot", help="SAC at the design draft (against the description's SAC when known)")


def _read_json(path: str) -> dict:
    """One HULL file's JSON object. Raises InvalidInput naming the file when it cannot be read
    or is not a JSON object."""
    try:
        doc = json.loads(pathlib.Path(path).read_text(encoding="utf-8"))
    except OSError as e:
        raise InvalidInput(f"hull file {path!r} cannot be read: {e.strerror}; expected a hull description or "
                           "surface JSON file") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise InvalidInput(f"hull file {path!r} is not valid JSON: {e}") from None
    if not isinstance(doc, dict):
        raise InvalidInput(f"hull file {path!r} holds a JSON {type(doc).__name__}; expected a JSON object")
    return doc


def _load(args):
    """(hull, particulars, name, description Hull or None) from the HULL argument(s)."""
    from . import io
    docs = [_read_json(p) for p in args.hull]
    part, name, hull_obj = {}, "", None
    if len(docs) == 1 and "principal" in docs[0]:
        from .hull import Hull
        hull_obj = Hull.from_json(docs[0])
        pr = docs[0]["principal"]
        part = dict(lpp=pr.get("Lpp"), beam=pr.get("B"), draft=pr.get("T"), depth=pr.get("D"))
        name = docs[0].get("name", "")
        hull = _description_hull(hull_obj, args)
    else:
        for p, d in zip(args.hull, docs):
            if "type" not in d:
                raise InvalidInput(f"hull file {p!r} has neither 'principal' nor 'type'; expected a hull description "
                                   "or surface JSON file")
        surfaces = [io.from_dict(d) for d in docs]
        if not all(isinstance(s, NurbsSurface) for s in surfaces):
            raise InvalidInput(f"{args.hull} are not all surface JSON files; expected surfaces or one hull description")
        hull = surfaces[0] if len(surfaces) == 1 else surfaces
        name = pathlib.Path(args.hull[0]).stem
    for k in ("lpp", "beam", "draft", "depth"):
        if getattr(args, k) is not None:
            part[k] = getattr(args, k)
    return hull, part, name, hull_obj


def _description_hull(hull_obj, args):
    """The composed hull (asked, or by default for a description with a bulb) or the bare hull's surface."""
    if args.compose or (hull_obj.description.bulb is not None and not args.bare):
        composed = hull_obj.composed_hull()
        print("hull: " + ("bare hull, bulbous bow and blend composed (--bare: the bare hull alone)"
                          if hull_obj.description.bulb is not None else "bare hull closed (no bulb)")
              + (f"; {composed.blend_note}" if composed.blend_note else ""))
        return composed
    return hull_obj.bare_hull_surface()


def _need(part, keys):
    missing = [k for k in keys if part.get(k) is None]
    if missing:
        raise InvalidInput(f"principal particulars {missing} are not known; expected --{' --'.join(missing)}")


def _export(args) -> int:
    from . import cad
    hull, _, _, _ = _load(args)
    cad.export_cad(hull, args.output, what=args.what, full=args.full, schema=args.schema)
    print(f"wrote {args.output}")
    if args.verify and not args.output.lower().endswith(".3dm"):
        v = cad.verify(cad.read_cad(args.output))
        print(f"read back: {v['faces']} faces, valid {v['valid']}, closed {v['closed']}, volume {v['volume']:.6g} m3")
    return 0


def _lines(args) -> int:
    from .lines_plan import closeup, lines_plan
    hull, part, name, _ = _load(args)
    _need(part, ("lpp", "beam", "draft", "depth"))
    kw = dict(lpp=part["lpp"], beam=part["beam"], draft=part["draft"], depth=part["depth"],
              name=args.name if args.name is not None else name)
    plan = closeup(hull, args.closeup, **kw) if args.closeup else lines_plan(hull, **kw)
    for out in args.output:
        plan.save(out)
        print(f"wrote {out} (scale 1:{plan.scale:g} on A3)")
    return 0


#: Most values a FROM:TO:STEP range may expand to.
MAX_RANGE_VALUES = 10000


def _floats(text: str, option: str) -> np.ndarray:
    """The values of a FROM:TO:STEP range or a comma list. Raises InvalidInput naming the option."""
    try:
        if ":" in text:
            a, b, s = (float(v) for v in text.split(":"))
            if not (s > 0 and b >= a and (b - a) / s < MAX_RANGE_VALUES):
                raise ValueError
            return np.arange(a, b + 0.5 * s, s)
        return np.array([float(v) for v in text.split(",")])
    except ValueError:
        raise InvalidInput(f"{option} is {text!r}; expected FROM:TO:STEP (STEP > 0, at most {MAX_RANGE_VALUES} values) "
                           "or a comma list of numbers (m)") from None


def _hydrostatics(args) -> int:
    from .curves_of_form import curves_of_form, highest_draft
    hull, part, name, hull_obj = _load(args)
    if isinstance(hull, list):
        raise InvalidInput("curves of form need one hull; expected a single surface or a hull description")
    _need(part, ("lpp", "beam"))
    depth = part.get("depth")
    trims = _floats(args.trims, "--trims")
    if args.drafts:
        drafts = _floats(args.drafts, "--drafts")
    else:
        _need(part, ("draft", "depth"))
        surface = hull if isinstance(hull, NurbsSurface) else hull.trimmed_surfaces[0][0]  # a composed hull's bare hull
        tops = {t: highest_draft(surface, depth, part["lpp"], t) for t in trims}
        trim, top = min(tops.items(), key=lambda kv: kv[1])
        if not top > 0.1 * part["draft"]:
            raise InvalidInput(f"--trims holds {trim:g} m, at which the deck dips below T/10 = "
                               f"{0.1 * part['draft']:.3g} m (the highest draft that keeps the deck dry there is "
                               f"{top:.3g} m); expected trims by the stern (m) that leave the deck above the water, "
                               "or --drafts")
        drafts = np.linspace(0.1 * part["draft"], top, 19)
    cof = curves_of_form(hull, drafts, lpp=part["lpp"], beam=part["beam"], depth=depth, trims=trims,
                         design_draft=part.get("draft"))
    cof.write_csv(args.output)
    print(f"wrote {args.output}: {len(cof.rows)} rows")
    if args.plot:
        cof.plot(args.plot, name)
        print(f"wrote {args.plot}")
    if args.sac_plot:
        basic = hull_obj.basic_curves["sac"] if hull_obj is not None else None
        cof.plot_sac(args.sac_plot, basic, name)
        print(f"wrote {args.sac_plot}")
    return 0


def run(args) -> int:
    """Run one of :data:`COMMANDS` (argparse namespace from :func:`add_parsers`)."""
    return {"export": _export, "lines": _lines, "hydrostatics": _hydrostatics}[args.command](args)
