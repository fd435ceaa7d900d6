"""CAD exchange of the exact geometry through OpenCASCADE: STEP (AP214, AP242), IGES (trimmed
NURBS surfaces, entities 144 / 128) and Rhino .3dm (rhino3dm).

What is written:

* ``what="surfaces"``: every NURBS surface as it is, one face each (untrimmed).
* ``what="solid"``: the hull closed into one solid -- its surfaces as faces (trimmed by their
  loops for a composed hull), with planar cap faces built in OpenCASCADE from the hull's free
  edges on the centre plane y = 0 (half ship only), the deck plane and the aft cut (upright or
  a raked transom's plane, found from the surfaces' edge curves), sewn into one closed shell;
  ``full=True`` mirrors the half in y = 0 first (full ship).

Every file can be read back with :func:`read_cad` and compared with :func:`verify`: surface
points, the shell's closure and validity (BRepCheck) and its volume. OpenCASCADE comes from the
optional ``cad`` extra (``pip install fairlines[cad]``: the ``cadquery-ocp-novtk`` wheel, OCP 8),
rhino3dm likewise; a missing one raises ImportError naming the package.
"""

from __future__ import annotations

import pathlib
from typing import Sequence

import numpy as np

from ._native import InvalidInput, NurbsSurface

__all__ = ["occ_surface", "hull_solid", "export_cad", "read_cad", "verify", "write_3dm", "read_3dm",
           "SEW_TOLERANCE", "FORMATS"]

#: Sewing tolerance (m): trimming loops are polylines in (u, v) that meet the neighbouring
#: subdomain's boundary within about 0.1 mm between their vertices.
SEW_TOLERANCE = 1e-3
#: Tolerance (relative to the hull's size) for an edge lying on a cap plane.
PLANE_TOLERANCE = 1e-6
#: Edge tolerance (m) of faces built from (u, v) trimming loops.
FACE_TOLERANCE = 1e-7
#: A trimming-loop vertex is looked for on an edge (exactly, by projection) only when within
#: this distance (m) of the edge's sample polyline.
COARSE_NEAR = 0.5
#: Between two trimming-loop vertices on an edge of a face already built, the image of the
#: (u, v) chord's midpoint may stray from that edge by this fraction of the chord: the loop
#: is a chordal polygon of the seam (centimetres off it between vertices on a whole ship).
CHORD_STRAY = 0.25
#: A trimming loop turning more than this (degrees) at a vertex starts a new edge there.
CORNER_DEG = 30.0
#: Linear deflection (m) of the triangulation on which verify() measures the volume: OCCT's
#: Gauss integration over faces trimmed by polygonal p-curves was found up to 1 % off here,
#: its triangulation at 1 cm within 0.02 % (0.01 % on untrimmed faces).
VOLUME_DEFLECTION = 0.01
#: File formats by suffix.
FORMATS = {".step": "step", ".stp": "step", ".iges": "iges", ".igs": "iges", ".3dm": "3dm"}


def _occ():
    try:
        import OCP  # noqa: F401
        from OCP.Message import Message, Message_Gravity
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("CAD exchange needs OpenCASCADE: pip install fairlines[cad] (cadquery-ocp-novtk)") from exc
    # OCCT's transfer statistics go to stdout; keep only its failures.
    for k in range(1, Message.DefaultMessenger_s().Printers().Size() + 1):
        Message.DefaultMessenger_s().Printers().Value(k).SetTraceLevel(Message_Gravity.Message_Fail)


def occ_surface(s: NurbsSurface):
    """The surface as an OpenCASCADE Geom_BSplineSurface (same degrees, knots, poles, weights)."""
    _occ()
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt
    from OCP.OCP.collections import Array1_double, Array1_int, Array2_double, Array2_gp_Pnt

    P = np.asarray(s.control_points, float)
    W = np.asarray(s.weights, float)
    nu, nv = P.shape[:2]
    poles = Array2_gp_Pnt(1, nu, 1, nv)
    weights = Array2_double(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            poles.SetValue(i + 1, j + 1, gp_Pnt(*P[i, j]))
            weights.SetValue(i + 1, j + 1, float(W[i, j]))

    def knots(kv):
        vals, mults = np.unique(np.asarray(kv, float), return_counts=True)
        a, m = Array1_double(1, len(vals)), Array1_int(1, len(vals))
        for k, (v, c) in enumerate(zip(vals, mults)):
            a.SetValue(k + 1, float(v))
            m.SetValue(k + 1, int(c))
        return a, m

    ku, mu = knots(s.knots_u)
    kv, mv = knots(s.knots_v)
    return Geom_BSplineSurface(poles, weights, ku, kv, mu, mv, s.degree_u, s.degree_v, False, False)


def _patches(hull):
    if isinstance(hull, NurbsSurface):
        return [(hull, None)]
    if hasattr(hull, "trimmed_surfaces"):
        return [(s, [np.asarray(l, float) for l in loops]) for s, loops in hull.trimmed_surfaces]
    out = [(s, None) if isinstance(s, NurbsSurface) else (s[0], s[1]) for s in hull]
    if not out or not all(isinstance(s, NurbsSurface) for s, _ in out):
        raise InvalidInput("hull is not a NurbsSurface, a ComposedHull or a list of them; expected one of those")
    return out


def _pcurve(run):
    """Degree-1 B-spline through the (u, v) points (the exact polygon), chord-length knots."""
    from OCP.Geom2d import Geom2d_BSplineCurve
    from OCP.gp import gp_Pnt2d
    from OCP.OCP.collections import Array1_double, Array1_gp_Pnt2d, Array1_int
    n = len(run)
    poles = Array1_gp_Pnt2d(1, n)
    for k, (u, v) in enumerate(run):
        poles.SetValue(k + 1, gp_Pnt2d(float(u), float(v)))
    s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(run, axis=0).T))]
    knots, mults = Array1_double(1, n), Array1_int(1, n)
    for k in range(n):
        knots.SetValue(k + 1, float(s[k]))
        mults.SetValue(k + 1, 2 if k in (0, n - 1) else 1)
    return Geom2d_BSplineCurve(poles, knots, mults, 1)


def _on_polyline(points, line):
    """Distance (m) of each point (k, 3) from the polyline ``line`` (n, 3)."""
    a, b = line[:-1], line[1:]
    ab = b - a
    w = np.clip(np.einsum("pkj,kj->pk", points[:, None, :] - a[None], ab) / np.maximum(np.einsum("kj,kj->k", ab, ab), 1e-300), 0, 1)
    return np.min(np.linalg.norm(points[:, None, :] - (a[None] + w[..., None] * ab[None]), axis=2), axis=1)


def _loop_vertices(a):
    """A closed (u, v) polygon's distinct vertices (repeats and the closing point dropped)."""
    a = a[np.r_[True, np.hypot(*np.diff(a, axis=0).T) > 1e-12]]
    return a[:-1] if len(a) > 1 and np.hypot(*(a[-1] - a[0])) <= 1e-12 else a


def _corners(a):
    """Indices of the vertices of a closed polygon where it turns more than CORNER_DEG."""
    d = np.roll(a, -1, axis=0) - a
    d_in = np.roll(d, 1, axis=0)
    cosang = np.einsum("ij,ij->i", d, d_in) / (np.hypot(*d.T) * np.hypot(*d_in.T))
    return set(np.flatnonzero(cosang < np.cos(np.radians(CORNER_DEG))).tolist())


def _distance_to_edge(p, edge) -> float:
    """Distance (m) from the point p (3,) to the edge's 3D curve (its ends included)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.Extrema import Extrema_ExtPC
    from OCP.gp import gp_Pnt
    c = BRepAdaptor_Curve(edge)
    ends = [c.Value(t) for t in (c.FirstParameter(), c.LastParameter())]
    best = min(np.linalg.norm(p - [q.X(), q.Y(), q.Z()]) for q in ends)
    ext = Extrema_ExtPC(gp_Pnt(*map(float, p)), c)
    if ext.IsDone():
        best = min([best] + [np.sqrt(ext.SquareDistance(i + 1)) for i in range(ext.NbExt())])
    return float(best)


def _shared_segments(s, a, known):
    """For each segment a[i] -> a[i+1] of a closed (u, v) polygon on ``s``, the index into
    ``known`` of the edge it runs along (both vertices on it within SEW_TOLERANCE, the chord's
    midpoint within CHORD_STRAY of the chord), else None."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve  # noqa: F401 - OpenCASCADE present
    P = np.asarray(s.evaluate(a[:, 0], a[:, 1]))
    mid_uv = 0.5 * (a + np.roll(a, -1, axis=0))
    M = np.asarray(s.evaluate(mid_uv[:, 0], mid_uv[:, 1]))
    near = []
    for p in P:
        near.append({k for k, (e, samples) in enumerate(known)
                     if _on_polyline(p[None], samples)[0] <= COARSE_NEAR and _distance_to_edge(p, e) <= SEW_TOLERANCE})
    out = []
    for i in range(len(a)):
        j = (i + 1) % len(a)
        chord = np.linalg.norm(P[j] - P[i])
        common = [k for k in near[i] & near[j] if _distance_to_edge(M[i], known[k][0]) <= max(SEW_TOLERANCE, CHORD_STRAY * chord)]
        out.append(common[0] if common else None)
    return out, P


def _loop_pieces(s, loop, known):
    """A closed (u, v) polygon on ``s`` as pieces in order: ("shared", edge) for a run of
    segments along one whole edge of a face already built (from one end of it to the other),
    ("own", (k, 2) run) for the rest, split at corners so that each piece lies on one plane or
    one seam."""
    a = _loop_vertices(np.asarray(loop, float))
    seg, P = _shared_segments(s, a, known)
    for i, k in enumerate(seg):  # a shared run must span its edge end to end
        if k is None:
            continue
        ends = known[k][1][[0, -1]]
        lo, hi = i, i
        while seg[(lo - 1) % len(a)] == k and (lo - 1) % len(a) != i:
            lo -= 1
        while seg[(hi + 1) % len(a)] == k and (hi + 1) % len(a) != i:
            hi += 1
        first, last = P[lo % len(a)], P[(hi + 1) % len(a)]
        if min(np.linalg.norm(first - ends[0]) + np.linalg.norm(last - ends[1]),
               np.linalg.norm(first - ends[1]) + np.linalg.norm(last - ends[0])) > 2 * SEW_TOLERANCE:
            seg[i] = None
    n = len(a)
    # a corner inside a shared run is the edge's own: the run takes that whole edge once
    inside_shared = {i for i in range(n) if seg[i] is not None and seg[i] == seg[i - 1]}
    breaks = (_corners(a) - inside_shared) | {i for i in range(n) if seg[i] != seg[i - 1]}
    start = min(breaks) if breaks else 0
    pieces, run = [], [start]
    for step in range(1, n + 1):
        i = (start + step) % n
        run.append(i)
        if i in breaks or step == n:
            k = seg[run[0]]
            pieces.append(("shared", known[k][0]) if k is not None else ("own", a[run]))
            run = [i]
    return pieces


def _trimmed_face(s, geom, loops, known):
    """A face of ``geom`` bounded by (u, v) polygons. A run of a loop along a whole edge of a
    face already built (a seam with that subdomain) uses that very edge, with a p-curve on
    this surface added by projection, so the two faces share it exactly (the polygon is only
    a chordal approximation of the seam); the other runs get their own degree-1 p-curves."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
    from OCP.BRepLib import BRepLib
    from OCP.ShapeFix import ShapeFix_Edge, ShapeFix_Face
    from OCP.TopLoc import TopLoc_Location

    face = None
    for loop in loops:
        wire = BRepBuilderAPI_MakeWire()
        for kind, piece in _loop_pieces(s, loop, known):
            if kind == "shared":
                edge = piece
                ShapeFix_Edge().FixAddPCurve(edge, geom, TopLoc_Location(), False, FACE_TOLERANCE)
            else:
                edge = BRepBuilderAPI_MakeEdge(_pcurve(piece), geom).Edge()
                BRepLib.BuildCurves3d_s(edge)
            wire.Add(edge)
        if face is None:
            face = BRepBuilderAPI_MakeFace(geom, wire.Wire(), True)
        else:
            face.Add(wire.Wire())
    fix = ShapeFix_Face(face.Face())
    fix.Perform()
    return fix.Face()


def _whole_domain(s, loops) -> bool:
    """Untrimmed: no loops, or one loop that is the parameter rectangle itself."""
    if loops is None:
        return True
    if len(loops) != 1:
        return False
    a = _loop_vertices(np.asarray(loops[0], float))
    box = np.array([[u, v] for u in s.domain_u for v in s.domain_v])
    return len(a) == 4 and all(np.min(np.hypot(*(box - p).T)) <= 1e-12 for p in a)


def _faces(patches):
    """Faces of the patches: untrimmed ones (whose edges are exact iso-curves) first, then the
    trimmed ones, which take over the edges they share with those built before them (see
    _trimmed_face); returned in the patches' order."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    out: dict = {}
    known = []
    for k in sorted(range(len(patches)), key=lambda k: not _whole_domain(*patches[k])):
        s, loops = patches[k]
        g = occ_surface(s)
        whole = _whole_domain(s, loops)
        out[k] = BRepBuilderAPI_MakeFace(g, FACE_TOLERANCE).Face() if whole else _trimmed_face(s, g, loops, known)
        known += [(e, _edge_points(e, 201)) for e in _edges(out[k])]
    return [out[k] for k in range(len(patches))]


def _sew(shapes, tol=SEW_TOLERANCE):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing
    sew = BRepBuilderAPI_Sewing(tol)
    for sh in shapes:
        sew.Add(sh)
    sew.Perform()
    return sew.SewedShape()


def _sub_shapes(shape, kind: str):
    """The sub-shapes of one kind ("EDGE", "FACE", "SHELL") of ``shape``, down-cast."""
    from OCP import TopAbs
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    ex = TopExp_Explorer(shape, getattr(TopAbs, f"TopAbs_{kind}"))
    cast = getattr(TopoDS, kind.capitalize())
    out = []
    while ex.More():
        out.append(cast(ex.Current()))
        ex.Next()
    return out


def _edges(shape):
    return _sub_shapes(shape, "EDGE")


def _edge_points(edge, n=9):
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    c = BRepAdaptor_Curve(edge)
    ts = np.linspace(c.FirstParameter(), c.LastParameter(), n)
    return np.array([[c.Value(t).X(), c.Value(t).Y(), c.Value(t).Z()] for t in ts])


def _free_edges(shape, tol):
    """Edges of ``shape`` bounding one face only (degenerate edges left out)."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
    from OCP.TopExp import TopExp
    from OCP.TopoDS import TopoDS
    from OCP.OCP.collections import IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as Map
    m = Map()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs_EDGE, TopAbs_FACE, m)
    out = []
    for k in range(1, m.Extent() + 1):
        e = TopoDS.Edge(m.FindKey(k))
        if m.FindFromIndex(k).Size() == 1 and not BRep_Tool.Degenerated_s(e):
            p = _edge_points(e, 3)
            if np.linalg.norm(p[-1] - p[0]) + np.linalg.norm(p[1] - p[0]) > tol:
                out.append(e)
    return out


def _chain_edges(edges, tol):
    """Edges ordered into chains by their end points: lists of (edge, start, end)."""
    ends = [(e, _edge_points(e, 2)) for e in edges]
    items = [(e, p[0], p[-1]) for e, p in ends]
    chains = []
    while items:
        chain = [items.pop(0)]
        grown = True
        while grown:
            grown = False
            for k, (e, a, b) in enumerate(items):
                head, tail = chain[0][1], chain[-1][2]
                if np.linalg.norm(a - tail) <= tol:
                    chain.append((e, a, b))
                elif np.linalg.norm(b - tail) <= tol:
                    chain.append((e, b, a))
                elif np.linalg.norm(b - head) <= tol:
                    chain.insert(0, (e, a, b))
                elif np.linalg.norm(a - head) <= tol:
                    chain.insert(0, (e, b, a))
                else:
                    continue
                items.pop(k)
                grown = True
                break
        chains.append(chain)
    return chains


def _on(plane, p, tol) -> bool:
    """Whether point p (or every row of an (n, 3) array of points) lies on ``plane`` (unit
    normal n, offset c: n . p = c) within tol."""
    n, c = plane
    return bool(np.all(np.abs(np.atleast_2d(p) @ n - c) <= tol))


def _cap(plane, edges, planes, size):
    """Planar face on ``plane`` (n, c) bounded by ``edges`` (one chain) and straight lines from
    its end back to its start, routed through the corner the end planes make with it."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
    from OCP.gp import gp_Pnt

    chains = _chain_edges(edges, SEW_TOLERANCE)
    if len(chains) != 1:
        raise InvalidInput(f"the free edges on the plane {_plane_name(plane)} form {len(chains)} chains; "
                           "expected one (the hull's edge on that plane must be connected)")
    mk = BRepBuilderAPI_MakeWire()
    for e, _, _ in chains[0]:
        mk.Add(e)
    a, b = chains[0][-1][2], chains[0][0][1]  # close from the chain's end back to its start
    tol = max(PLANE_TOLERANCE * size, SEW_TOLERANCE)
    if np.linalg.norm(a - b) > SEW_TOLERANCE:
        on_a = [k for k, p in enumerate(planes) if p is not plane and _on(p, a, tol)]
        on_b = [k for k, p in enumerate(planes) if p is not plane and _on(p, b, tol)]
        route = [a]
        if on_a and on_b and not set(on_a) & set(on_b):
            three = [plane, planes[on_a[0]], planes[on_b[0]]]  # the corner where the three planes meet
            route.append(np.linalg.solve(np.array([n for n, _ in three]), np.array([c for _, c in three])))
        route.append(b)
        for p, q in zip(route[:-1], route[1:]):
            if np.linalg.norm(q - p) > SEW_TOLERANCE:
                mk.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(*p), gp_Pnt(*q)).Edge())
    return BRepBuilderAPI_MakeFace(mk.Wire(), True).Face()


def _plane_name(plane) -> str:
    n, c = plane
    k = int(np.argmax(np.abs(n)))
    if abs(abs(n[k]) - 1.0) <= 1e-12:
        return f"{'xyz'[k]} = {c * np.sign(n[k]):.6g} m"
    return f"{n[0]:.4g} x + {n[1]:.4g} y + {n[2]:.4g} z = {c:.6g} m"


def _axis_plane(axis: int, value: float):
    n = np.zeros(3)
    n[axis] = 1.0
    return n, float(value)


def _aft_plane(patches, size, x_least):
    """The plane of the hull's aft cut: of the surfaces' four edge curves, those lying in one
    plane x = a + b z (a transom, upright or raked: its normal has no y part) over some height,
    the one furthest aft; x = x_least (the hull's least x) when none does (checked when the caps
    are sewn)."""
    found = []
    for s, _ in patches:
        us, vs = np.linspace(*s.domain_u, 33), np.linspace(*s.domain_v, 33)
        for u, v in ((us, s.domain_v[:1]), (us, s.domain_v[1:]), (s.domain_u[:1], vs), (s.domain_u[1:], vs)):
            pts = np.asarray(s.evaluate_grid(u, v)).reshape(-1, 3)
            if np.ptp(pts[:, 2]) <= PLANE_TOLERANCE * size:
                continue  # level (a deck edge): no x = a + b z to fit
            A = np.c_[np.ones(len(pts)), pts[:, 2]]
            (a, b), *_ = np.linalg.lstsq(A, pts[:, 0], rcond=None)
            if np.abs(A @ (a, b) - pts[:, 0]).max() <= PLANE_TOLERANCE * size:
                found.append((float(pts[:, 0].mean()), a, b))
    if not found:
        return _axis_plane(0, x_least)
    _, a, b = min(found)
    if abs(b) <= PLANE_TOLERANCE:
        return _axis_plane(0, float(a))
    return np.array([1.0, 0.0, -b]) / np.hypot(1.0, b), float(a / np.hypot(1.0, b))  # x - b z = a


def _cap_planes(patches, full):
    pts = np.concatenate([np.asarray(s.evaluate_grid(np.linspace(*s.domain_u, 17), np.linspace(*s.domain_v, 17))).reshape(-1, 3)
                          for s, _ in patches])
    size = float(np.ptp(pts, axis=0).max())
    planes = [_aft_plane(patches, size, float(pts[:, 0].min())), _axis_plane(2, float(pts[:, 2].max())), _axis_plane(1, 0.0)]
    return (planes[:2] if full else planes), planes, size


def hull_solid(hull, *, full: bool = False):
    """The hull as one closed OpenCASCADE solid (TopoDS_Solid): surface faces (trimmed for a
    composed hull) and planar caps on the deck, the aft cut and (half ship) the centre plane,
    sewn; ``full`` mirrors the half in y = 0 (no centre-plane cap). Raises InvalidInput when
    the faces do not close into one shell."""
    _occ()
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Trsf
    from OCP.TopAbs import TopAbs_SOLID

    patches = _patches(hull)
    faces = _faces(patches)
    open_shell = _sew(faces)
    planes, routing, size = _cap_planes(patches, full)
    free = _free_edges(open_shell, SEW_TOLERANCE)
    tol = PLANE_TOLERANCE * size
    caps = []
    for plane in planes:
        on = [e for e in free if _on(plane, _edge_points(e), max(tol, 10 * SEW_TOLERANCE))]
        if on:
            caps.append(_cap(plane, on, routing, size))
    parts = [open_shell] + caps
    if full:
        t = gp_Trsf()
        t.SetMirror(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0)))
        parts += [BRepBuilderAPI_Transform(p, t, True).Shape() for p in parts]
    solid = _solid_if_closed(_sew(parts))
    if solid.ShapeType() != TopAbs_SOLID:
        raise InvalidInput("the hull's faces and caps do not sew into one closed shell; expected a hull whose edges "
                           "lie on the centre plane, one deck plane z = const and one aft plane "
                           "(x = const, or a raked transom's)")
    return solid


def _surfaces_compound(patches):
    from OCP.BRep import BRep_Builder
    from OCP.TopoDS import TopoDS_Compound
    comp = TopoDS_Compound()
    b = BRep_Builder()
    b.MakeCompound(comp)
    for f in _faces([(s, None) for s, _ in patches]):
        b.Add(comp, f)
    return comp


def export_cad(hull, path, *, what: str = "solid", full: bool = False, schema: str = "AP214") -> None:
    """Write the hull to ``path``; the suffix picks the format (.step/.stp, .iges/.igs, .3dm).

    hull    NurbsSurface, list of surfaces / (surface, loops), or a ComposedHull.
    what    "solid" (closed shell, see the module docstring) or "surfaces" (each surface whole).
    full    solid of the full ship (mirrored) instead of the half (y >= 0).
    schema  STEP schema "AP214" or "AP242".
    A .3dm file holds the surfaces (rhino3dm cannot trim), plus the composed hull's closed mesh.
    Raises InvalidInput for an unknown suffix, ``what`` or schema.
    """
    path = pathlib.Path(path)
    fmt = FORMATS.get(path.suffix.lower())
    if fmt is None:
        raise InvalidInput(f"path suffix is {path.suffix!r}; expected one of {sorted(FORMATS)}")
    if what not in ("solid", "surfaces"):
        raise InvalidInput(f"what is {what!r}; expected 'solid' or 'surfaces'")
    if schema not in ("AP214", "AP242"):
        raise InvalidInput(f"schema is {schema!r}; expected 'AP214' or 'AP242'")
    patches = _patches(hull)
    if fmt == "3dm":
        write_3dm([s for s, _ in patches], path, mesh=getattr(hull, "mesh", None))
        return
    shape = hull_solid(hull, full=full) if what == "solid" else _surfaces_compound(patches)
    if fmt == "step":
        _write_step(shape, path, schema)
    else:
        _write_iges(shape, path)


def _write_step(shape, path, schema):
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
    w = STEPControl_Writer()
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS" if schema == "AP214" else "AP242DIS")
    Interface_Static.SetCVal_s("write.step.unit", "M")
    w.Transfer(shape, STEPControl_AsIs)
    if w.Write(str(path)) != IFSelect_RetDone:
        raise OSError(f"OpenCASCADE could not write {path}")


def _write_iges(shape, path):
    from OCP.IGESControl import IGESControl_Writer
    from OCP.Interface import Interface_Static
    Interface_Static.SetIVal_s("write.iges.brep.mode", 0)  # faces: trimmed surfaces (144) of 128
    w = IGESControl_Writer("M", 0)
    w.AddShape(shape)
    w.ComputeModel()
    if not w.Write(str(path)):
        raise OSError(f"OpenCASCADE could not write {path}")


def read_cad(path, sew: bool = True):
    """Read a STEP or IGES file back with OpenCASCADE: its shape (TopoDS_Shape). IGES trimmed
    surfaces carry no shared edges: with ``sew`` they are sewn (SEW_TOLERANCE) and a closed
    shell becomes a solid, as a CAD system does on import.
    Raises InvalidInput for an unknown file type, OSError when OpenCASCADE cannot read the file, ImportError without OpenCASCADE."""
    _occ()
    path = pathlib.Path(path)
    fmt = FORMATS.get(path.suffix.lower())
    if fmt == "step":
        from OCP.STEPControl import STEPControl_Reader
        r = STEPControl_Reader()
    elif fmt == "iges":
        from OCP.IGESControl import IGESControl_Reader
        r = IGESControl_Reader()
    else:
        raise InvalidInput(f"path suffix is {path.suffix!r}; expected .step/.stp or .iges/.igs")
    from OCP.IFSelect import IFSelect_RetDone
    if r.ReadFile(str(path)) != IFSelect_RetDone:
        raise OSError(f"OpenCASCADE could not read {path}")
    r.TransferRoots()
    shape = r.OneShape()
    if fmt == "iges" and sew:
        shape = _solid_if_closed(_sew([shape]))
    return shape


def _solid_if_closed(shape):
    """The one shell of ``shape`` as a solid when it has no free edge, else ``shape``."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeSolid
    from OCP.BRepLib import BRepLib
    shells = _sub_shapes(shape, "SHELL")
    if len(shells) != 1 or _free_edges(shells[0], SEW_TOLERANCE):
        return shape
    solid = BRepBuilderAPI_MakeSolid(shells[0]).Solid()
    BRepLib.OrientClosedSolid_s(solid)
    return solid


def _faces_of(shape):
    return _sub_shapes(shape, "FACE")


def surface_deviation(shape, surfaces: Sequence[NurbsSurface], samples: int = 11) -> float:
    """Largest distance (m) from points of ``surfaces`` (samples x samples each, interior) to the
    nearest non-planar face of ``shape``, by OpenCASCADE's point-to-surface projection."""
    from OCP.BRep import BRep_Tool
    from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
    from OCP.gp import gp_Pnt
    geoms = [BRep_Tool.Surface_s(f) for f in _faces_of(shape)]
    geoms = [g for g in geoms if g.DynamicType().Name() != "Geom_Plane"]
    worst = 0.0
    for s in surfaces:
        t = np.linspace(0.02, 0.98, samples)
        us = s.domain_u[0] + t * np.ptp(s.domain_u)
        vs = s.domain_v[0] + t * np.ptp(s.domain_v)
        for p in np.asarray(s.evaluate_grid(us, vs)).reshape(-1, 3):
            best = np.inf
            for g in geoms:
                proj = GeomAPI_ProjectPointOnSurf(gp_Pnt(*p), g)
                if proj.NbPoints():
                    best = min(best, proj.LowerDistance())
            worst = max(worst, best)
    return worst


def verify(shape, surfaces: Sequence[NurbsSurface] = (), samples: int = 11) -> dict:
    """Figures of a shape read back: ``valid`` (BRepCheck_Analyzer), ``closed`` (no free edges),
    ``volume`` (m^3, of its solids, on a triangulation with VOLUME_DEFLECTION), ``faces``, and
    ``max_deviation`` (m) of ``surfaces`` from its faces."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    BRepMesh_IncrementalMesh(shape, VOLUME_DEFLECTION, False, 0.05, True)
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, False, False, True)
    out = dict(valid=bool(BRepCheck_Analyzer(shape).IsValid()),
               closed=len(_free_edges(shape, SEW_TOLERANCE)) == 0,
               volume=abs(float(props.Mass())), faces=len(_faces_of(shape)))
    if surfaces:
        out["max_deviation"] = surface_deviation(shape, surfaces, samples)
    return out


def write_3dm(surfaces: Sequence[NurbsSurface], path, mesh=None) -> None:
    """Rhino .3dm (rhino3dm): each surface as a Rhino NURBS surface, metres; ``mesh`` (a
    fairlines Mesh) as a Rhino mesh when given.
    Raises ImportError without rhino3dm, OSError when the file cannot be written."""
    try:
        import rhino3dm
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("Rhino export needs rhino3dm: pip install fairlines[cad]") from exc
    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = rhino3dm.UnitSystem.Meters
    for s in surfaces:
        model.Objects.AddSurface(_rhino_surface(rhino3dm, s))
    if mesh is not None:
        m = rhino3dm.Mesh()
        for v in np.asarray(mesh.vertices, float):
            m.Vertices.Add(*map(float, v))
        for f in np.asarray(mesh.faces):
            m.Faces.AddFace(*map(int, f))
        model.Objects.AddMesh(m)
    if not model.Write(str(path), 7):
        raise OSError(f"rhino3dm could not write {path}")


def _rhino_surface(rhino3dm, s):
    P = np.asarray(s.control_points, float)
    W = np.asarray(s.weights, float)
    nu, nv = P.shape[:2]
    r = rhino3dm.NurbsSurface.Create(3, bool(s.is_rational), s.degree_u + 1, s.degree_v + 1, nu, nv)
    for i in range(nu):
        for j in range(nv):
            w = float(W[i, j])
            r.Points[i, j] = rhino3dm.Point4d(*(P[i, j] * w), w)  # homogeneous
    for k, t in enumerate(np.asarray(s.knots_u)[1:-1]):
        r.KnotsU[k] = float(t)
    for k, t in enumerate(np.asarray(s.knots_v)[1:-1]):
        r.KnotsV[k] = float(t)
    return r


def read_3dm(path) -> list[NurbsSurface]:
    """The NURBS surfaces of a .3dm file as fairlines surfaces.
    Raises ImportError without rhino3dm, OSError when the file cannot be read."""
    import rhino3dm
    model = rhino3dm.File3dm.Read(str(path))
    if model is None:
        raise OSError(f"rhino3dm could not read {path}")
    out = []
    for obj in model.Objects:
        g = obj.Geometry
        if isinstance(g, rhino3dm.Brep):
            g = g.Faces[0].UnderlyingSurface()
        if not isinstance(g, rhino3dm.NurbsSurface):
            if isinstance(g, rhino3dm.Surface):
                g = g.ToNurbsSurface()
            else:
                continue
        nu, nv = g.Points.CountU, g.Points.CountV
        P = np.empty((nu, nv, 3))
        W = np.empty((nu, nv))
        for i in range(nu):
            for j in range(nv):
                q = g.Points[i, j]
                W[i, j] = q.W
                P[i, j] = (q.X / q.W, q.Y / q.W, q.Z / q.W)
        ku = [g.KnotsU[k] for k in range(len(g.KnotsU))]
        kv = [g.KnotsV[k] for k in range(len(g.KnotsV))]
        out.append(NurbsSurface(g.OrderU - 1, g.OrderV - 1, [ku[0]] + ku + [ku[-1]], [kv[0]] + kv + [kv[-1]], P, W))
    return out
