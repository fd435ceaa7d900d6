"""Exact geometry and invariants through the Python API."""

import math
import pickle

import numpy as np
import pytest

import fairlines as fl
from conftest import random_clamped_knots


def test_circle_radius_error_below_1e12():
    c = fl.circle((0.3, -1.2, 4.0), 7.5, normal=(0.2, -0.5, 1.0))
    pts = c.evaluate(np.linspace(0.0, 1.0, 10_000))
    assert np.abs(np.linalg.norm(pts - (0.3, -1.2, 4.0), axis=1) - 7.5).max() <= 1e-12
    # a 2-D centre gives a 2-D circle
    c2 = fl.circle((1.0, 2.0), 0.5)
    assert c2.dim == 2
    assert np.abs(np.linalg.norm(c2.evaluate(np.linspace(0, 1, 1000)) - (1, 2), axis=1) - 0.5).max() <= 1e-12


def test_arc_endpoints_and_ellipse():
    a = fl.arc((0, 0, 0), 2.0, 0.0, math.radians(250))
    assert np.allclose(a.evaluate(0.0), (2, 0, 0), atol=1e-14)
    assert np.allclose(a.evaluate(1.0), (2 * math.cos(math.radians(250)), 2 * math.sin(math.radians(250)), 0), atol=1e-12)
    e = fl.ellipse((0, 0), (3.0, 0.0), (0.0, 1.0))
    p = e.evaluate(np.linspace(0, 1, 2000))
    assert np.abs((p[:, 0] / 3) ** 2 + p[:, 1] ** 2 - 1).max() <= 1e-12


def test_partition_of_unity_and_derivatives_sum_to_zero(rng):
    for p in range(1, 6):
        knots = random_clamped_knots(rng, p + 8, p)
        t = np.linspace(0, 1, 501)
        B = fl.basis_functions(knots, p, t, order=2)
        assert B.shape == (501, 3, p + 8)
        assert np.abs(B[:, 0, :].sum(axis=1) - 1).max() <= 1e-14
        assert (B[:, 0, :] >= -1e-15).all()
        assert np.abs(B[:, 1, :].sum(axis=1)).max() <= 1e-9


def test_curve_derivatives_match_finite_differences(rng):
    c = fl.NurbsCurve(3, random_clamped_knots(rng, 9, 3), rng.uniform(-2, 2, (9, 3)), rng.uniform(0.5, 2, 9))
    t = np.array([0.21, 0.48, 0.83])
    h = 1e-6
    d = c.derivatives(t, 2)
    fd1 = (c.evaluate(t + h) - c.evaluate(t - h)) / (2 * h)
    fd2 = (c.evaluate(t + h) - 2 * c.evaluate(t) + c.evaluate(t - h)) / h**2
    assert np.abs(d[:, 1] - fd1).max() <= 1e-6 * (1 + np.abs(fd1).max())
    assert np.abs(d[:, 2] - fd2).max() <= 1e-3 * (1 + np.abs(fd2).max())


def test_knot_insertion_and_degree_elevation_change_nothing(rng):
    t = np.linspace(0, 1, 3001)
    c = fl.NurbsCurve(3, random_clamped_knots(rng, 10, 3), rng.uniform(-5, 5, (10, 3)), rng.uniform(0.3, 3, 10))
    for other in (c.insert_knot(0.4321, 2), c.refine_knots([0.1, 0.1, 0.55, 0.9]), c.elevate_degree(2)):
        assert np.abs(other.evaluate(t) - c.evaluate(t)).max() <= 1e-12
    assert c.elevate_degree(1).degree == 4
    s = fl.NurbsSurface(3, 2, random_clamped_knots(rng, 7, 3), random_clamped_knots(rng, 6, 2),
                        rng.uniform(-5, 5, (7, 6, 3)), rng.uniform(0.3, 3, (7, 6)))
    us = np.linspace(0, 1, 60)
    ref = s.evaluate_grid(us, us)
    for other in (s.insert_knot("u", 0.3, 2), s.insert_knot("v", 0.77), s.elevate_degree("u", 1), s.elevate_degree("v", 2)):
        assert np.abs(other.evaluate_grid(us, us) - ref).max() <= 1e-12


def test_weights_pull_curve_and_edits_are_in_place():
    pts = np.array([[0, 0], [1, 2], [2, 0]], float)
    c = fl.NurbsCurve(2, [0, 0, 0, 1, 1, 1], pts)
    y0 = c.evaluate(0.5)[1]
    c.set_weight(1, 4.0)
    assert c.is_rational
    assert c.evaluate(0.5)[1] > y0  # w up pulls the curve toward the point
    c.set_control_point(1, (1.0, 3.0))
    assert c.control_points[1, 1] == 3.0
    with pytest.raises(ValueError, match="weight"):
        c.set_weight(1, 0.0)


def test_sphere_cylinder_revolve():
    s = fl.sphere((1, 2, 3), 2.0)
    g = s.evaluate_grid(np.linspace(0, 1, 80), np.linspace(0, 1, 80))
    assert np.abs(np.linalg.norm(g - (1, 2, 3), axis=2) - 2.0).max() <= 1e-12
    K, H = s.curvature(np.array([0.3, 0.6]), np.array([0.4, 0.7]))
    assert np.allclose(K, 0.25, atol=1e-9) and np.allclose(np.abs(H), 0.5, atol=1e-9)
    cyl = fl.cylinder((0, 0, 0), (0, 0, 1), 1.5, 4.0)
    g = cyl.evaluate_grid(np.linspace(0, 1, 50), np.linspace(0, 1, 5))
    assert np.abs(np.hypot(g[..., 0], g[..., 1]) - 1.5).max() <= 1e-12
    # a cone by revolving a line: radius linear in height
    line = fl.NurbsCurve(1, [0, 0, 1, 1], [[1, 0, 0], [0, 0, 2]])
    cone = fl.revolve(line, (0, 0, 0), (0, 0, 1), math.pi)
    g = cone.evaluate_grid(np.linspace(0, 1, 40), np.linspace(0, 1, 9))
    assert np.abs(np.hypot(g[..., 0], g[..., 1]) - (1 - g[..., 2] / 2)).max() <= 1e-12
    assert g[..., 1].min() >= -1e-12  # half turn only


def test_surface_normal_and_closest_point_on_sphere(rng):
    s = fl.sphere((0, 0, 0), 3.0)
    u, v = rng.uniform(0.05, 0.95, 40), rng.uniform(0.05, 0.95, 40)
    p = s.evaluate(u, v)
    n = s.normal(u, v)
    assert np.abs(np.abs(np.sum(n * p / 3.0, axis=1)) - 1).max() <= 1e-12
    for d in rng.normal(size=(10, 3)):
        d /= np.linalg.norm(d)
        uu, vv, q = s.closest_point(4.0 * d)
        assert np.linalg.norm(q - 3.0 * d) <= 1e-8


def test_helix_curvature_and_torsion_from_fit():
    r, c = 2.0, 0.5
    s = np.linspace(0, 4 * np.pi, 400)
    pts = np.c_[r * np.cos(s), r * np.sin(s), c * s]
    fit = fl.fit_curve(pts, degree=5)
    t = np.linspace(0.2, 0.8, 7)
    assert np.abs(fit.curve.curvature(t) - r / (r * r + c * c)).max() <= 1e-6
    assert np.abs(fit.curve.torsion(t) - c / (r * r + c * c)).max() <= 1e-5


def test_volume_trilinear_identity():
    k = [0, 0, 1, 1]
    grid = np.zeros((2, 2, 2, 3))
    for i in range(2):
        for j in range(2):
            for m in range(2):
                grid[i, j, m] = (2 * i, 3 * j, 4 * m)
    vol = fl.NurbsVolume((1, 1, 1), (k, k, k), grid)
    out = vol.evaluate([0.25, 0.5], [0.5, 1.0], [0.75, 0.1])
    assert np.allclose(out, [[0.5, 1.5, 3.0], [1.0, 3.0, 0.4]], atol=1e-15)


def test_pickle_round_trip(rng):
    c = fl.NurbsCurve(3, random_clamped_knots(rng, 7, 3), rng.uniform(-1, 1, (7, 2)), rng.uniform(0.5, 2, 7))
    s = fl.sphere((0, 0, 0), 1.0)
    c2, s2 = pickle.loads(pickle.dumps((c, s)))
    t = np.linspace(0, 1, 50)
    assert np.array_equal(c2.evaluate(t), c.evaluate(t))
    assert np.array_equal(s2.evaluate(t, t), s.evaluate(t, t))


def test_batch_surface_derivatives_match_single_calls(rng):
    s = fl.NurbsSurface(3, 3, random_clamped_knots(rng, 7, 3), random_clamped_knots(rng, 6, 3),
                        rng.uniform(-2, 2, (7, 6, 3)), rng.uniform(0.5, 2, (7, 6)))
    u, v = rng.random(5), rng.random(5)
    batch = s.derivatives(u, v, 2)
    assert batch.shape == (5, 3, 3, 3)
    for k in range(5):
        assert np.array_equal(batch[k], s.derivatives(float(u[k]), float(v[k]), 2))
    h = 1e-6
    fd_u = (s.evaluate(u + h, v) - s.evaluate(u - h, v)) / (2 * h)
    assert np.abs(batch[:, 1, 0] - fd_u).max() <= 1e-6 * (1 + np.abs(fd_u).max())
    # order 1 takes the allocation-free kernel; it must agree with the general routine
    first = s.derivatives(u, v, 1)
    assert first.shape == (5, 2, 2, 3)
    assert np.abs(first[:, :2, :2] - np.stack([d[:2, :2] for d in batch]) * [[[1], [1]], [[1], [0]]]).max() <= 1e-11
    with pytest.raises(ValueError, match="not finite"):
        s.derivatives([np.nan], [0.5], 1)


def test_rational_volume_jacobian_matches_finite_differences(rng):
    ks = [random_clamped_knots(rng, 5, 2), random_clamped_knots(rng, 4, 2), random_clamped_knots(rng, 4, 3)]
    vol = fl.NurbsVolume((2, 2, 3), ks, rng.uniform(-1, 1, (5, 4, 4, 3)), rng.uniform(0.5, 2, (5, 4, 4)))
    s, t, r = rng.uniform(0.1, 0.9, (3, 6))
    D = vol.derivatives(s, t, r)
    assert np.abs(D[:, 0] - vol.evaluate(s, t, r)).max() <= 1e-14
    h = 1e-6
    for axis, arrs in enumerate([(s + h, t, r, s - h, t, r), (s, t + h, r, s, t - h, r), (s, t, r + h, s, t, r - h)]):
        fd = (vol.evaluate(*arrs[:3]) - vol.evaluate(*arrs[3:])) / (2 * h)
        assert np.abs(D[:, axis + 1] - fd).max() <= 1e-6 * (1 + np.abs(fd).max())
