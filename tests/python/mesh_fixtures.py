"""Surfaces for the grid and mesh tests and the mesh bench: analytic hulls made here, and the
one real hull through example_hull_surface() (repoint it when the example hulls change)."""

import pathlib
import time

import numpy as np

import fairlines as fl

WIGLEY = dict(L=100.0, B=10.0, T=6.25, D=9.0)


EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "container_ship.json"
EXAMPLE_DRAFT = 11.0  # m, the design draft of the example ship


def example_hull():
    """The real whole ship of the mesh tests and bench (an fl.Hull)."""
    return fl.Hull.from_json(EXAMPLE)


def example_hull_surface():
    """The real bare hull used by the mesh bench."""
    return example_hull().bare_hull_surface()


_COMPOSED = {}


def composed_example_hull():
    """The whole ship composed: bare hull + bulb + blend, transom stern (built once per run)."""
    if "c" not in _COMPOSED:
        _COMPOSED["c"] = example_hull().composed_hull()
    return _COMPOSED["c"]


def cruiser_stern_ship():
    """A whole ship with a cruiser stern (its aft edge on the centre plane), from particulars."""
    return fl.design_hull(lpp=120, breadth=20, draft=5, depth=9, cb=0.6, lcb=58.8, stern="cruiser")


def wigley_surface(rows=41, cols=21, aft="cruiser", rake_deg=0.0):
    """Wigley hull y = B/2 (1 - (2 xi / L)^2) (1 - ((T - z) / T)^2), u along x from the aft end, v
    from the keel to the deck D. aft="cruiser": the whole hull, both ends on y = 0;
    "transom": cut at x = L / 4 (aft end in the plane x = L / 4 + (z - T) tan(rake_deg))."""
    L, B, T, D = (WIGLEY[k] for k in "LBTD")
    z = np.linspace(0.0, D, cols)[None, :]
    if aft == "cruiser":
        x = np.linspace(0.0, L, rows)[:, None] + 0 * z
    else:
        x0 = L / 4 + (z - T) * np.tan(np.radians(rake_deg))
        x = x0 + (L - x0) * np.linspace(0.0, 1.0, rows)[:, None]
    y = 0.5 * B * (1 - (2 * (x - L / 2) / L) ** 2) * (1 - ((T - z) / T) ** 2)
    grid = np.stack([x, y, np.broadcast_to(z, x.shape)], axis=-1)
    return fl.fit_surface(grid, n_control_u=16, n_control_v=10).surface


def bilge_patch(length=20.0):
    """A bicubic bilge-like patch: flat bottom into a turn of bilge whose radius grows from 2 m
    to 3.5 m along x, up to the vertical side."""
    nx, ns = 9, 9
    pts = np.zeros((nx, ns, 3))
    for i in range(nx):
        x = length * i / (nx - 1)
        r = 2.0 + 1.5 * i / (nx - 1)
        t = 0.5 * np.pi * np.arange(ns) / (ns - 1)
        pts[i] = np.column_stack([np.full(ns, x), 4.0 - r + r * np.sin(t), r - r * np.cos(t)])
    return fl.fit_surface(pts, n_control_u=6, n_control_v=6).surface


def forebody_surface(rows=41, cols=25):
    """The composition tests' Wigley-type forebody (Panamax particulars)."""
    L, B, D = 244.8, 32.25, 19.0
    r = np.arange(rows)[:, None]
    c = np.arange(cols)[None, :]
    x = 0.5 * L + 0.5 * L * (1 - np.cos(np.pi * 0.5 * r / (rows - 1))) + 0 * c
    z = D * (1 - np.cos(np.pi * 0.5 * c / (cols - 1))) + 0 * r
    xi = (x - 0.5 * L) / (0.5 * L)
    y = 0.5 * B * (1 - xi**4) * (1 - (1 - z / D) ** 6)
    return fl.fit_surface(np.stack([x, y, z], axis=-1), n_control_u=16, n_control_v=12).surface


FOREBODY_SHIP = dict(lpp=244.8, beam=32.25, draft_fp=11.0, midship_area=0.97 * 32.25 * 11.0,
                     displacement_volume=0.65 * 244.8 * 32.25 * 11.0)


def edge_census(faces):
    """(open, non-manifold, misoriented) edge counts of a quad / triangle list (-1 pads a
    triangle), by numpy alone."""
    f = np.asarray(faces)
    edges = []
    for row in f:
        k = 3 if row[3] < 0 else 4
        edges += [(row[i], row[(i + 1) % k]) for i in range(k)]
    d = np.array(edges)
    und = np.sort(d, axis=1)
    _, counts = np.unique(und, axis=0, return_counts=True)
    _, dcounts = np.unique(d, axis=0, return_counts=True)
    return int((counts == 1).sum()), int((counts > 2).sum()), int((dcounts > 1).sum())


def closed_volume(vertices, faces):
    """Enclosed volume of a closed mesh (quads split by a diagonal), numpy only."""
    v = np.asarray(vertices)
    tris = []
    for row in np.asarray(faces):
        k = 3 if row[3] < 0 else 4
        tris += [(row[0], row[i], row[i + 1]) for i in range(1, k - 1)]
    t = v[np.array(tris)]
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0)


def knupp_scaled_jacobians(vertices, faces):
    """Scaled Jacobian of every element (Knupp 2000) by numpy alone: the least over its corners
    of (e_next x e_prev) . n / (|e_next| |e_prev|), n the quad's diagonal cross product or the
    triangle's normal, triangles times 2 / sqrt(3); <= 0 is an inverted element."""
    v, f = np.asarray(vertices), np.asarray(faces)
    out = np.empty(len(f))
    for i, row in enumerate(f):
        p = v[row[row >= 0]]
        n = np.cross(p[2] - p[0], p[3] - p[1]) if len(p) == 4 else np.cross(p[1] - p[0], p[2] - p[0])
        n = n / np.linalg.norm(n)
        e1, e2 = np.roll(p, -1, axis=0) - p, np.roll(p, 1, axis=0) - p
        s = np.cross(e1, e2) @ n / (np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1))
        out[i] = s.min() * (2 / np.sqrt(3) if len(p) == 3 else 1.0)
    return out


def quad_corner_angles(vertices, faces):
    """Every quadrilateral corner's angle (deg) between its two sides, by numpy alone."""
    v, f = np.asarray(vertices), np.asarray(faces)
    p = v[f[f[:, 3] >= 0]]  # (quads, 4, 3)
    e1, e2 = np.roll(p, -1, axis=1) - p, np.roll(p, 1, axis=1) - p
    cos = np.sum(e1 * e2, axis=2) / (np.linalg.norm(e1, axis=2) * np.linalg.norm(e2, axis=2))
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))).ravel()


def composed_wetted_hydrostatics(composed, draft):
    """(volume m^3 both sides, lcb m) of the example's composed ship at `draft`: NURBS quadrature
    of the bare hull (fl.hydrostatics) plus what the bulb and blend add below the draft (volume and
    x-moment), from the composition's own meshes."""
    surface = example_hull_surface()
    bare = fl.hydrostatics(surface, draft)
    comp, alone = fl.mesh_hydrostatics(composed.mesh, draft), fl.mesh_hydrostatics(fl.compose([surface]).mesh, draft)
    added = comp.volume - alone.volume
    added_moment = comp.volume * comp.lcb - alone.volume * alone.lcb
    return bare.volume + added, (bare.volume * bare.lcb + added_moment) / (bare.volume + added)


GMSH_CURVATURE = 12  # gmsh's elements per 2 pi of curvature at its common setting
# gmsh has no chordal tolerance: its curvature sizing is raised along this ladder until its mesh
# meets ours, so that both sides are compared at the same size and the same accuracy
GMSH_CURVATURE_LADDER = (12, 16, 24, 32, 40, 48, 56, 64, 72, 96, 128)


def gmsh_mesh(surface, size, curvature=GMSH_CURVATURE):
    """gmsh's Blossom-recombined quad mesh of the same B-spline surface, `curvature` elements per
    2 pi of surface curvature: (vertices, faces), (wall, CPU) seconds of its mesh generation."""
    import gmsh
    gmsh.initialize(["-nt", "1"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        P = np.asarray(surface.control_points)  # (nu, nv, 3)
        nu, nv = surface.shape
        # gmsh wants the u index running fastest
        order = [gmsh.model.occ.addPoint(*P[i, j]) for j in range(nv) for i in range(nu)]
        ku, mu = np.unique(np.asarray(surface.knots_u), return_counts=True)
        kv, mv = np.unique(np.asarray(surface.knots_v), return_counts=True)
        w = np.asarray(surface.weights)
        gmsh.model.occ.addBSplineSurface(
            order, nu, degreeU=surface.degree_u, degreeV=surface.degree_v,
            weights=[float(w[i, j]) for j in range(nv) for i in range(nu)], knotsU=list(map(float, ku)),
            knotsV=list(map(float, kv)), multiplicitiesU=list(map(int, mu)), multiplicitiesV=list(map(int, mv)))
        gmsh.model.occ.remove([(0, t) for t in order])  # control points are not part of the surface
        gmsh.model.occ.synchronize()
        gmsh.model.mesh.setSize(gmsh.model.getEntities(0), size)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", size / 20)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", curvature)
        # default Frontal-Delaunay: "Frontal-Delaunay for quads" (8) ignores MeshSizeMax once recombined
        gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)  # Blossom
        gmsh.option.setNumber("Mesh.RecombineAll", 1)
        t0, c0 = time.perf_counter(), time.process_time()
        gmsh.model.mesh.generate(2)
        dt = (time.perf_counter() - t0, time.process_time() - c0)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        index = {int(t): k for k, t in enumerate(tags)}
        V = np.asarray(xyz).reshape(-1, 3)
        faces = []
        for etype, _, nodes in zip(*gmsh.model.mesh.getElements(2)):
            k = 3 if etype == 2 else 4
            for row in np.asarray(nodes, int).reshape(-1, k):
                faces.append([index[n] for n in row] + ([-1] if k == 3 else []))
        return V, np.array(faces), dt
    finally:
        gmsh.finalize()


def chordal(surface, V, F, samples=400):
    """Largest distance (m) from an element centroid to the surface, over about `samples` elements."""
    F = F[:: max(1, len(F) // samples)]
    c = np.array([V[f[f >= 0]].mean(axis=0) for f in F])
    return max(np.linalg.norm(surface.closest_point(p)[2] - p) for p in c)


def gmsh_meeting(surface, size, tol):
    """(curvature, first mesh) of the first rung of GMSH_CURVATURE_LADDER whose gmsh mesh keeps its
    element centroids within tol of the surface; None when no rung does."""
    for n in GMSH_CURVATURE_LADDER:
        run = gmsh_mesh(surface, size, n)
        if chordal(surface, run[0], run[1]) <= tol:
            return n, run
    return None


def _segments_cross_triangles(a, b, t, eps=1e-9):
    """Vectorised Moller-Trumbore: does segment a[k]-b[k] cross the interior of triangle
    t[k] (k, 3, 3)?"""
    e1, e2, d = t[:, 1] - t[:, 0], t[:, 2] - t[:, 0], b - a
    h = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, h)
    scale = np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1) * np.linalg.norm(d, axis=1)
    ok = np.abs(det) > eps * scale
    det = np.where(ok, det, 1.0)
    s = a - t[:, 0]
    u = np.einsum("ij,ij->i", s, h) / det
    q = np.cross(s, e1)
    v = np.einsum("ij,ij->i", d, q) / det
    w = np.einsum("ij,ij->i", e2, q) / det
    return ok & (u > eps) & (v > eps) & (u + v < 1 - eps) & (w > eps) & (w < 1 - eps)


def self_intersections(mesh):
    """Pairs of faces sharing no vertex whose triangles cross: candidate pairs by bounding-box
    overlap (sorted on min x), then an edge-through-triangle test both ways (enough for
    triangles that are not coplanar)."""
    V, F = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    T = V[F]
    lo, hi = T.min(axis=1), T.max(axis=1)
    order = np.argsort(lo[:, 0])
    lo, hi, T, F = lo[order], hi[order], T[order], F[order]
    ends = np.searchsorted(lo[:, 0], hi[:, 0], side="right")
    I = np.repeat(np.arange(len(F)), ends - np.arange(len(F)) - 1)
    J = np.concatenate([np.arange(i + 1, e) for i, e in enumerate(ends)]) if len(I) else np.zeros(0, int)
    keep = np.all(lo[J] <= hi[I], axis=1) & np.all(lo[I] <= hi[J], axis=1)
    I, J = I[keep], J[keep]
    shared = (F[I][:, :, None] == F[J][:, None, :]).any(axis=(1, 2))
    I, J = I[~shared], J[~shared]
    hit = np.zeros(len(I), bool)
    for k in range(3):
        hit |= _segments_cross_triangles(T[I, k], T[I, (k + 1) % 3], T[J])
        hit |= _segments_cross_triangles(T[J, k], T[J, (k + 1) % 3], T[I])
    return list(zip(order[I[hit]].tolist(), order[J[hit]].tolist()))
