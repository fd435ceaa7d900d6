"""SHA-1 fingerprints of what the installed fairlines computes on real inputs, one line per
item, to hold a refactor bit for bit: run it with the build before and the build after and
compare the two outputs (every line must match).

    python tools/fingerprint.py > before.txt        # e.g. with main's .venv
    python tools/fingerprint.py > after.txt         # with this checkout's .venv
    diff before.txt after.txt                        # prints nothing when nothing changed

    python tools/fingerprint.py form errors          # only some sections (see SECTIONS)

Inputs: examples/container_ship.json, six designed ships (a skeg and a sonar dome among them),
1 500 seeded random form-curve requests and 28 refused ones, infeasible particulars, two bulbs
the hull refuses, the lines plan, the Series 60 and KCS imports (../shared/data) and the
command line's help texts. Each line hashes arrays byte for byte and messages character for
character.
"""

import contextlib
import hashlib
import io
import json
import pathlib
import sys

import numpy as np

import fairlines as fl

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "container_ship.json"
DATA = ROOT.parent / "shared" / "data"
#: Random form-curve requests (seeded) and the seed.
FORM_REQUESTS = 1500
FORM_SEED = 12345


def digest(*objs) -> str:
    """SHA-1 (16 hex digits) of arrays (dtype, shape, bytes), numbers, strings, containers and
    the public non-callable attributes of anything else (NURBS, engine results)."""
    s = hashlib.sha1()

    def feed(o):
        if isinstance(o, np.ndarray):
            a = np.ascontiguousarray(o)
            s.update(f"{a.dtype}{a.shape}".encode())
            s.update(a.tobytes())
        elif isinstance(o, dict):
            for k in sorted(o, key=str):
                feed(str(k))
                feed(o[k])
        elif isinstance(o, (list, tuple)):
            s.update(b"[")
            for x in o:
                feed(x)
            s.update(b"]")
        elif isinstance(o, float):
            s.update(np.float64(o).tobytes())
        elif isinstance(o, fl.NurbsSurface):
            feed([o.control_points, o.knots_u, o.knots_v, o.weights])
        elif isinstance(o, fl.NurbsCurve):
            feed([o.control_points, o.knots, o.weights])
        elif isinstance(o, (int, str, bool, type(None), np.integer, np.floating, bytes)):
            s.update(repr(o).encode())
        elif hasattr(o, "__array__"):
            feed(np.asarray(o))
        else:
            fields = {}
            for k in dir(o):
                if k.startswith("_"):
                    continue
                try:
                    v = getattr(o, k)
                except Exception as exc:  # a property that refuses is part of the result
                    v = ("raises", type(exc).__name__)
                if not callable(v):
                    fields[k] = v
            if not fields:
                raise TypeError(f"cannot fingerprint a {type(o).__name__}")
            s.update(type(o).__name__.encode())
            feed(fields)

    for o in objs:
        feed(o)
    return s.hexdigest()[:16]


def show(name, *objs) -> None:
    print(f"{name:40s} {digest(*objs)}", flush=True)


def outcome(call):
    """call()'s result, or its exception's class and message."""
    try:
        return ("ok", call())
    except Exception as exc:
        return (type(exc).__name__, str(exc))


def fields_of(result) -> dict:
    return {k: getattr(result, k) for k in dir(result) if not k.startswith("_") and not callable(getattr(result, k))}


def ship():
    """The container ship: bare hull, hydrostatics, composition, bulb, intersections, Kracht,
    plane cuts, hull mesh and grid."""
    hull = fl.Hull.from_json(EXAMPLE)
    bare = hull.bare_hull_surface()
    show("ship.bare", bare)
    show("ship.hydro", fields_of(fl.hydrostatics(bare, 11.0)))
    show("ship.hydro_mid", fields_of(fl.hydrostatics(bare, 7.0, midship_x=100.0)))
    c = hull.composed_hull()
    show("ship.composed.mesh", c.mesh.vertices, c.mesh.faces)
    show("ship.composed.curves", c.intersection_curves)
    show("ship.composed.props", c.volume, c.blend_note, c.blend_continuity, c.seam_vertices, c.face_part, c.x_aft,
         c.z_deck)
    show("ship.composed.full", c.full_mesh().vertices, c.full_mesh().faces)
    show("ship.composed.trimmed", c.trimmed_surfaces)
    show("ship.composed.blend", c.blend)
    bare_c = fl.compose([bare])
    show("ship.compose_bare", bare_c.mesh.vertices, bare_c.mesh.faces, bare_c.volume)
    sp = hull.ship_particulars()
    bulb = fl.BulbousBow.from_dict({"kracht": {}, "shape": {}}, sp)
    show("ship.bulb", bulb.surface)
    for step in (0.0, 4.0, 2.0):
        show(f"ship.intersect.step{step:g}", outcome(lambda: fl.intersect_surfaces(bare, bulb.surface, step=step)))
    kracht = {k: sp[k] for k in ("lpp", "beam", "draft_fp", "midship_area", "displacement_volume")}
    show("ship.kracht", fl.measure_kracht(c.mesh, x_fp=sp.get("x_fp", sp["lpp"]), **kracht))
    show("ship.mesh_hydro", fields_of(fl.mesh_hydrostatics(c.mesh, 11.0)))
    for z in (2.0, 11.0, 17.0):
        show(f"ship.plane_cut_z{z:g}", fl.plane_cut(bare, "z", z))
    m = fl.mesh_hull(c, size=6.0)
    show("ship.mesh_hull6", m.vertices, m.faces, m.face_part)
    show("ship.grid", fl.grids.surface_grid(bare, 21, 15).points)


#: Particulars of the designed ships: the container ship with its bulb, a cruiser stern, a full
#: tanker, a small ship with a bulb, a single screw behind a skeg, a frigate with a sonar dome.
PARTICULARS = [
    dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True),
    dict(lpp=120, breadth=20, draft=5, depth=9, cb=0.6, lcb=58.8, stern="cruiser"),
    dict(lpp=170, breadth=28, draft=9.5, depth=14, cb=0.8, lcb=88.0),
    dict(lpp=80, breadth=13, draft=4.5, depth=7, cb=0.55, lcb=39.0, bulb=True),
    dict(lpp=200, breadth=32, draft=12, depth=18, cb=0.72, lcb=102.0, skeg=True),
    dict(lpp=142, breadth=19, draft=6.2, depth=11, cb=0.5, lcb=70.0, sonar_dome=True),
]


def designs():
    for i, p in enumerate(PARTICULARS):
        hull = fl.design_hull(**p)
        show(f"design{i}.json", hull.to_json())
        show(f"design{i}.bare", hull.bare_hull_surface())
        show(f"design{i}.hydro", fields_of(hull.hydrostatics()))
        if p.get("bulb"):
            c = hull.composed_hull()
            show(f"design{i}.composed", c.mesh.vertices, c.mesh.faces, c.volume, c.blend_note)


def _form_request(rng):
    """A random request: plane curves with end conditions, area and centroid (some with points,
    bounds or fairness weights), 3-D curves with tangents, and mostly infeasible unit curves."""
    kind = rng.integers(0, 5)
    L = float(rng.uniform(0.5, 200))
    p = {}
    if kind in (0, 1, 2):
        p.update(xB=0.0, yB=float(rng.uniform(0, 0.3) * L), xE=L, yE=float(rng.uniform(0, 0.5) * L))
        if rng.random() < 0.6:
            p["alphaB"] = float(rng.uniform(-80, 80))
        if rng.random() < 0.6:
            p["alphaE"] = float(rng.uniform(-100, 10))
        if rng.random() < 0.3:
            p["CAB"] = float(rng.uniform(-3, 1) / L)
        if rng.random() < 0.3:
            p["CAE"] = float(rng.uniform(-3, 1) / L)
        if rng.random() < 0.7:
            p["Area"] = float(rng.uniform(0.05, 0.6) * L * L)
        if "Area" in p and rng.random() < 0.6:
            p["xC"] = float(rng.uniform(0.3, 0.7) * L)
        if "Area" in p and rng.random() < 0.3:
            p["yC"] = float(rng.uniform(0.05, 0.3) * L)
        kw = {}
        if kind == 1:
            xs = np.sort(rng.uniform(0.1, 0.9, int(rng.integers(1, 4)))) * L
            kw["points"] = [([float(x), float(rng.uniform(0.05, 0.5) * L)],
                             float("inf") if rng.random() < 0.5 else float(rng.uniform(0.1, 10))) for x in xs]
        if kind == 2:
            kw["bounds"] = rng.choice([False, None, {"monotone": "y"}, {"y_nonnegative": False}, {"min_end_speed": 0.05}])
            kw["fairness"] = rng.choice([None, {"e1": 0.1, "e2": 1.0}, {"e3": 1.0}, {"e2": 1.0, "length": 0.5}])
        if rng.random() < 0.1:
            kw["multistart"] = 2
        return p, int(rng.integers(6, 14)), kw
    if kind == 3:
        p.update(xB=0.0, yB=0.0, zB=0.0, xE=L, yE=float(rng.uniform(0, 0.3) * L), zE=float(rng.uniform(0, 0.3) * L))
        kw = {"tangent_start": rng.uniform(-1, 1, 3).tolist() if rng.random() < 0.5 else None,
              "tangent_end": rng.uniform(-1, 1, 3).tolist() if rng.random() < 0.5 else None}
        if rng.random() < 0.5:
            kw["points"] = [([L * 0.5, float(rng.uniform(0, 0.3) * L), float(rng.uniform(0, 0.3) * L)], float("inf"))]
        return p, int(rng.integers(5, 12)), kw
    p.update(xB=0.0, yB=1.0, xE=1.0, yE=0.0, Area=float(rng.uniform(-0.5, 2.0)))
    if rng.random() < 0.5:
        p["xC"] = float(rng.uniform(-0.5, 1.5))
    if rng.random() < 0.5:
        p["alphaB"] = float(rng.uniform(-180, 180))
    return p, int(rng.integers(4, 10)), {}


def form():
    rng = np.random.default_rng(FORM_SEED)
    acc, kinds = hashlib.sha1(), {}
    for _ in range(FORM_REQUESTS):
        p, n, kw = _form_request(rng)
        kind, r = outcome(lambda: fl.design_curve(p, n, **kw))
        kinds[kind] = kinds.get(kind, 0) + 1
        item = r if kind != "ok" else (r.curve, r.residuals, r.achieved, r.fairness, r.iterations, r.converged,
                                       r.objective, r.continuation_steps, r.point_parameters, r.point_residuals)
        acc.update(digest(kind, item).encode())
    print(f"{'form_curves ' + json.dumps(kinds, sort_keys=True):40s} {acc.hexdigest()[:16]}", flush=True)


def errors():
    """The messages of refused requests: form-curve checks, infeasible particulars, bulbs the
    hull refuses."""
    nan, inf = float("nan"), float("inf")
    base = dict(xB=0.0, yB=1.0, xE=1.0, yE=0.0)
    cases = [
        (dict(base), dict(n_control=8, dim=4)), (dict(base), dict(degree=1)), (dict(base), dict(n_control=3)),
        ({"Aera": 1.0}, {}), (dict(base, zB=0.0), dict(dim=2)), (dict(base), dict(tangent_start=[1, 0, 0], dim=2)),
        (dict(base), dict(tangent_start=[0, 0, 0], dim=3)), (dict(base), dict(points=[[0.5, 0.5, 0.5]])),
        (dict(base), dict(points=[([0.5, nan], inf)])), (dict(base), dict(points=[([0.5, 1e12], inf)])),
        (dict(base), dict(points=[([0.5, 0.5], 0.0)])), (dict(base), dict(fairness={"e1": -1.0})),
        (dict(base), dict(fairness={"e1": 0.0, "e2": 0.0, "e3": 0.0})),
        (dict(base), dict(bounds={"min_end_speed": 2.0})), (dict(base), dict(tolerance=1e-2)),
        (dict(base, alphaB=0.0, alphaE=-90.0, CAB=0.0, CAE=0.0, Area=0.5, xC=0.4, yC=0.3), dict(n_control=6)),
        (dict(base), dict(initial_control_points=[[0, 0]])), (dict(base, xB=nan), {}), (dict(base, xB=1e12), {}),
        (dict(base, alphaB=1000.0), {}), ({}, {}), (dict(base, Area=-0.5), {}), (dict(base, Area=2.0), {}),
        (dict(base, Area=0.5, xC=2.0), {}), (dict(base, Area=0.5, yC=-1.0), {}), (dict(base, yB=-1.0), {}),
        (dict(base, xE=-1.0), {}), (dict(base, Area=0.5, yC=0.9), {}),
    ]
    show("errors.form_curve", [outcome(lambda: fl.design_curve(p, **kw).curve) for p, kw in cases])
    small = dict(lpp=120, breadth=20, draft=5, depth=9, cb=0.6, lcb=58.8)
    for name, change in (("cb_high", dict(cb=0.97)), ("lcb_far", dict(lcb=90.0)), ("cm", dict(cm=0.5)),
                         ("cwp", dict(cwp=0.55))):
        show(f"errors.design.{name}", outcome(lambda: fl.design_hull(**dict(small, **change)).to_json()))
    hull = fl.Hull.from_json(EXAMPLE)
    bare, sp = hull.bare_hull_surface(), hull.ship_particulars()
    for name, shape in (("short", {"aft_length": 0.5}), ("high", {"nose_height_shift": 8.0})):
        def composed():
            c = fl.compose_with_blend(bare, fl.BulbousBow.from_dict({"kracht": {}, "shape": shape}, sp))
            return c.mesh.vertices, c.blend_note
        show(f"errors.compose.{name}", outcome(composed))


def grids():
    for kind, a in (("sinh", dict(first=0.01)), ("tanh_two_sided", dict(first=0.002, last=0.4)),
                    ("geometric", dict(first=0.01, max_ratio=1.15))):
        show(f"grids.distribute.{kind}", fl.grids.distribute(10.0, kind, 0 if kind == "geometric" else 41, **a))


def lines():
    """The container ship's lines plan: its primitives, model lines, hydrostatics and close-ups."""
    from fairlines.lines_plan import closeup, lines_plan
    hull = fl.Hull.from_json(EXAMPLE)
    pr = hull.description.principal
    part = dict(lpp=pr.lpp, beam=pr.breadth, draft=pr.draft, depth=pr.depth)
    composed = hull.composed_hull()
    plan = lines_plan(composed, **part, name="CS")
    show("lines.primitives", [(type(p).__name__, vars(p)) for p in plan.primitives])
    show("lines.model", plan.stations, plan.waterlines, plan.buttocks, plan.diagonals, plan.knuckles, plan.outline,
         plan.particulars, plan.scale, plan.body_scale, plan.offsets, plan.factors)
    show("lines.hydro", {k: (fields_of(v) if hasattr(v, "volume") else v) for k, v in (plan.hydrostatics or {}).items()})
    for end in ("bow", "stern"):
        show(f"lines.closeup.{end}", [(type(p).__name__, vars(p)) for p in closeup(composed, end, **part, name="CS").primitives])


def imports():
    """The documents `fairlines import --analysis` writes for the Series 60 and the KCS."""
    from fairlines.offsets import read_hull_data
    from fairlines.preprocess.files import import_hull
    ships = (("series60", lambda: read_hull_data(DATA / "series60_cb080_offsets.csv", lpp=121.92, beam=16.256,
                                                 draft=6.5024)),
             ("kcs", lambda: read_hull_data(DATA / "kcs")))
    for name, data in ships:
        doc = import_hull(data())
        show(f"import.{name}.form_parameters", json.dumps(doc["form_parameters"], sort_keys=True))
        show(f"import.{name}.doc", json.dumps(doc, sort_keys=True, default=str))


def cli():
    """The help text of `fairlines` and of each sub-command, and `fairlines version`."""
    from fairlines import cli as command_line
    for argv in [["--help"], ["version"]] + [[c, "--help"] for c in
                                             ("fit", "import", "build", "mesh", "sweep", "design", "fairness")]:
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                rc = command_line.main(argv)
            except SystemExit as exc:
                rc = ("exit", exc.code)
        show("cli." + "_".join(argv), rc, out.getvalue(), err.getvalue())


SECTIONS = dict(ship=ship, designs=designs, form=form, errors=errors, grids=grids, lines=lines, imports=imports,
                cli=cli)

if __name__ == "__main__":
    for section in sys.argv[1:] or list(SECTIONS):
        SECTIONS[section]()
