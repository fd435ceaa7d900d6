"""fl.plane_cut on a plane that holds one of the surface's own edges (a transom)."""

import numpy as np

import fairlines as fl


def _transom_like_surface():
    """Bicubic patch whose aft edge (v = 0) lies in the plane x = 0 exactly, bulging aft of it
    nowhere: x grows along v, y and z vary across u."""
    nu, nv = 5, 6
    cp = np.zeros((nu, nv, 3))
    for i in range(nu):
        for j in range(nv):
            cp[i, j] = (2.0 * j, 3.0 + i + 0.3 * j * (nu - 1 - i), 10.0 - 2.0 * i + 0.1 * j * j)
    knots_u = [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
    knots_v = [0, 0, 0, 0, 1 / 3, 2 / 3, 1, 1, 1, 1]
    return fl.NurbsSurface(3, 3, knots_u, knots_v, cp)


def test_a_cut_on_the_surfaces_own_edge_plane_stays_on_it():
    s = _transom_like_surface()
    cut = fl.plane_cut(s, 0, 0.0, 201)
    p = np.asarray(cut.points)
    edge = np.asarray(s.evaluate_grid(np.linspace(*s.domain_u, 201), [s.domain_v[0]])).reshape(-1, 3)
    assert len(p) >= 100
    assert np.abs(p[:, 0]).max() <= 1e-12
    # every point lies on the edge curve itself (the only part of the surface in that plane)
    d = np.min(np.linalg.norm(p[:, None, 1:] - edge[None, :, 1:], axis=2), axis=1)
    assert d.max() <= 0.05
