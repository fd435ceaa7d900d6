"""On the real hull (the whole container ship of examples/container_ship.json with
the bulb of its "bulb" section): bulb + blend + composition at the default resolution (goal
<= 30 ms), against manifold3d (PyPI) doing the mesh union of the same two tessellated solids
(full bare hull and full bulb) in the same run. Timed two ways: with the blend boundaries as
fixed inputs (as a designer's parameters would be: bulb + blend surface + composition), and
end to end (compose_with_blend: union seam, boundaries from it, blend, composition)."""

import sys

import common  # noqa: F401  (sets single-thread BLAS before numpy loads)
import numpy as np

import fairlines as fl
from common import median_time, report

GOAL_MS = 30.0
EXAMPLE = __import__("pathlib").Path(__file__).resolve().parents[1] / "examples" / "container_ship.json"


def bulb_solid(surface, nu=40, nv=24):
    """Closed full bulb: the half surface on a grid, mirrored, welded on y = 0, the nose a
    single pole vertex and the aft end capped by a fan."""
    us = np.linspace(0, 1, nu + 1)[:-1]  # nose pole added separately
    vs = np.linspace(0, 1, nv + 1)
    P = surface.evaluate(np.repeat(us, nv + 1), np.tile(vs, nu)).reshape(nu, nv + 1, 3)
    ring = np.concatenate([P[:, :, :], P[:, -2:0:-1, :] * [1, -1, 1]], axis=1)  # around, 2 nv
    m = ring.shape[1]
    verts = [ring.reshape(-1, 3), surface.evaluate(1.0, 0.5)[None, :], ring[0].mean(axis=0)[None, :]]
    V = np.concatenate(verts)
    pole, centre = nu * m, nu * m + 1
    F = []
    for i in range(nu - 1):
        for j in range(m):
            a, b, c, d = i * m + j, i * m + (j + 1) % m, (i + 1) * m + (j + 1) % m, (i + 1) * m + j
            F += [[a, b, c], [a, c, d]]
    for j in range(m):
        F.append([(nu - 1) * m + j, (nu - 1) * m + (j + 1) % m, pole])
        F.append([centre, (j + 1) % m, j])
    F = np.array(F)
    if fl.mesh_volume(V, F) < 0:
        F = F[:, ::-1]
    return V, F


def main():
    try:
        import manifold3d
    except ImportError:  # pragma: no cover - listed in requirements-dev.txt
        sys.exit("manifold3d is not installed: pip install -r requirements-dev.txt")
    desc = fl.Hull.from_json(EXAMPLE)
    hull = desc.bare_hull_surface()
    ship = desc.ship_particulars()
    kw = {**desc.description.bulb.kracht, **desc.description.bulb.shape}

    def make_bulb():
        return fl.BulbousBow(**ship, **kw)

    def ours():
        return fl.compose([hull, make_bulb()])

    t_union = median_time(ours)
    t_bulb = median_time(make_bulb)
    c = ours()
    bulb = make_bulb()
    placement = fl.seam_blend_placement(hull, bulb)
    on_hull, on_bulb, hull_s = placement.boundary_a, placement.boundary_b, placement.hull

    def ours_blended():
        b = make_bulb()
        # compose() re-skins the blend at the mesh resolution and measures its continuity
        bl = fl.blend_surface(hull_s, on_hull, b.surface, on_bulb, tension=0.6, check_samples=2)
        return fl.compose([hull_s, b, bl])

    t_ours = median_time(ours_blended)
    t_end = median_time(lambda: fl.compose_with_blend(hull, make_bulb()))
    t_blend = median_time(lambda: fl.blend_surface(hull_s, on_hull, bulb.surface, on_bulb, tension=0.6))
    cb = ours_blended()
    report("bulb (Kracht -> skinned NurbsSurface)", 1e3 * t_bulb, "ms")
    report("blend_surface (61 sections + 2 x 200-point continuity check)", 1e3 * t_blend, "ms")
    report("bulb + union (no blend) -> closed half-hull mesh", 1e3 * t_union, "ms", f"{len(c.mesh.faces)} faces")
    report("bulb + blend + composition -> closed half-hull mesh", 1e3 * t_ours, "ms",
           f"goal <= {GOAL_MS:.0f} ms: {'met' if 1e3 * t_ours <= GOAL_MS else 'MISSED'}; {len(cb.mesh.faces)} faces; "
           f"max blend normal angle {max(d['max_angle_deg'] for d in cb.blend_continuity):.3f} deg")
    report("end to end: bulb + union seam + blend + composition", 1e3 * t_end, "ms",
           f"goal <= {GOAL_MS:.0f} ms: {'met' if 1e3 * t_end <= GOAL_MS else 'MISSED'}")

    full_hull = fl.compose([hull]).full_mesh()
    bv, bf = bulb_solid(make_bulb().surface)
    mh = manifold3d.Manifold(manifold3d.Mesh(vert_properties=full_hull.vertices.astype(np.float32),
                                             tri_verts=full_hull.faces.astype(np.uint32)))
    mb = manifold3d.Manifold(manifold3d.Mesh(vert_properties=bv.astype(np.float32), tri_verts=bf.astype(np.uint32)))
    if mh.status() != manifold3d.Error.NoError or mb.status() != manifold3d.Error.NoError:
        sys.exit(f"manifold3d rejected the input meshes: {mh.status()}, {mb.status()}")

    def peer():
        return (mh + mb).to_mesh()

    t_peer = median_time(peer)
    out = (mh + mb)
    report("manifold3d union of the tessellated full hull + full bulb", 1e3 * t_peer, "ms",
           f"{out.num_tri()} triangles in, {len(full_hull.faces) + len(bf)} triangles")
    report("ratio ours (bulb + blend + composition) / manifold3d union", t_ours / t_peer, "x")
    report("ratio ours end to end / manifold3d union", t_end / t_peer, "x")
    report("ratio ours (bulb + exact-seam union, no blend) / manifold3d union", t_union / t_peer, "x")
    report("half-hull volume ours / half of manifold3d full volume", c.volume / (0.5 * out.volume()), "")


if __name__ == "__main__":
    main()
