"""Evaluation agrees with geomdl (an independent pure-Python NURBS library) on random
rational curves and surfaces to 1e-10."""

import numpy as np
from geomdl import NURBS

import fairlines as fl
from conftest import random_clamped_knots


def test_random_rational_curves_match_geomdl(rng):
    for p, n, dim in [(2, 6, 2), (3, 9, 3), (4, 12, 3), (5, 8, 2)]:
        knots = random_clamped_knots(rng, n, p)
        pts = rng.uniform(-5, 5, (n, dim))
        w = rng.uniform(0.3, 3.0, n)
        ours = fl.NurbsCurve(p, knots, pts, w)
        ref = NURBS.Curve()
        ref.degree = p
        ref.ctrlpts = pts.tolist()
        ref.weights = w.tolist()
        ref.knotvector = knots.tolist()
        t = np.linspace(0.0, 1.0, 257)
        expected = np.array(ref.evaluate_list(t.tolist()))
        assert np.abs(ours.evaluate(t) - expected).max() <= 1e-10
        # first and second derivatives too
        for tk in (0.123, 0.5, 0.871):
            d_ref = np.array(ref.derivatives(tk, order=2))
            assert np.abs(ours.derivatives(tk, 2) - d_ref).max() <= 1e-8 * (1 + np.abs(d_ref).max())


def test_random_rational_surfaces_match_geomdl(rng):
    # (8, 2) exercises the general path above the fixed-size fast kernels
    for pu, pv, nu, nv in [(3, 3, 8, 9), (2, 3, 6, 7), (4, 2, 9, 5), (8, 2, 10, 5)]:
        ku = random_clamped_knots(rng, nu, pu)
        kv = random_clamped_knots(rng, nv, pv)
        net = rng.uniform(-5, 5, (nu, nv, 3))
        w = rng.uniform(0.3, 3.0, (nu, nv))
        ours = fl.NurbsSurface(pu, pv, ku, kv, net, w)
        ref = NURBS.Surface()
        ref.degree_u, ref.degree_v = pu, pv
        # geomdl takes weighted points (w x, w y, w z, w), flat index i * nv + j as ours
        ref.ctrlpts_size_u, ref.ctrlpts_size_v = nu, nv
        pw = np.concatenate([net * w[..., None], w[..., None]], axis=2)
        ref.ctrlptsw = pw.reshape(-1, 4).tolist()
        ref.knotvector_u = ku.tolist()
        ref.knotvector_v = kv.tolist()
        u = rng.uniform(0, 1, 300)
        v = rng.uniform(0, 1, 300)
        expected = np.array([ref.evaluate_single((a, b)) for a, b in zip(u, v)])
        assert np.abs(ours.evaluate(u, v) - expected).max() <= 1e-10
        grid = ours.evaluate_grid(u[:20], v[:15])
        exp_grid = np.array([[ref.evaluate_single((a, b)) for b in v[:15]] for a in u[:20]])
        assert np.abs(grid - exp_grid).max() <= 1e-10
