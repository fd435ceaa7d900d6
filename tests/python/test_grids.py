"""Structured surface grids: distributions, arc-length layout, grid control, quality.

Truths used: the requested end spacings and ratio limits themselves, straight lines (arc length
= distance), a rational quarter circle (arc length pi R / 2), the closed-form Moebius map of the
reparameterisation, the original surface evaluated before grid control, analytic plane grids,
and gmsh's transfinite 'Progression' on the same B-spline edge in the same run.
"""

import math

import numpy as np
import pytest

import fairlines as fl
from fairlines import grids
from mesh_fixtures import bilge_patch, composed_example_hull, wigley_surface

SPACING_TOL = 0.01   # end spacings within 1 % (the engine meets them to round-off)
SURFACE_TOL = 1e-10  # grid control moves no surface point (m)


def spacings(x):
    return np.diff(np.asarray(x))


@pytest.mark.parametrize("kind, first, last", [("sinh", 0.01, 0.0), ("sinh", 0.0, 0.02), ("tanh", 0.005, 0.0),
                                               ("tanh", 0.0, 0.05), ("tanh_two_sided", 0.002, 0.4),
                                               ("tanh_two_sided", 0.3, 0.3), ("tanh_two_sided", 2.0, 3.0)])
def test_distribution_hits_its_end_spacings(kind, first, last):
    x = fl.grids.distribute(10.0, kind, 41, first=first, last=last)
    ds = spacings(x)
    assert x[0] == 0.0 and x[-1] == 10.0 and np.all(ds > 0)
    if first:
        assert ds[0] == pytest.approx(first, rel=SPACING_TOL)
    if last:
        assert ds[-1] == pytest.approx(last, rel=SPACING_TOL)


def test_geometric_growth_keeps_its_ratio_limit_with_the_fewest_points():
    x = fl.grids.distribute(50.0, "geometric", 0, first=0.01, max_ratio=1.15)
    ds = spacings(x)
    r = ds[1:] / ds[:-1]
    assert ds[0] == pytest.approx(0.01, rel=SPACING_TOL)
    assert r.max() <= 1.15 + 1e-12 and np.ptp(r) < 1e-9  # one constant ratio
    fewer = np.sum(0.01 * 1.15 ** np.arange(len(ds) - 1))  # one point fewer at the limit ratio cannot fill 50 m
    assert fewer < 50.0


def test_infeasible_spacings_are_refused():
    with pytest.raises(fl.InfeasibleFormParameters, match="uniform spacing"):
        fl.grids.distribute(1.0, "sinh", 11, first=0.2)
    with pytest.raises(fl.InfeasibleFormParameters, match="max_ratio"):
        fl.grids.distribute(100.0, "geometric", 10, first=0.01, max_ratio=1.2)
    with pytest.raises(fl.InvalidInput, match="exactly one"):
        fl.grids.distribute(1.0, "tanh", 11, first=0.01, last=0.01)
    with pytest.raises(fl.InvalidInput, match="kind is 'cosh'"):
        fl.grids.distribute(1.0, "cosh", 11)
    with pytest.raises(fl.InvalidInput, match="length is -1"):
        fl.grids.distribute(-1.0, "uniform", 11)


def straight_bspline():
    """A straight edge from (0,0,0) to (10,0,0) whose control points crowd its start: speed varies
    along it, so equal parameter steps are not equal lengths."""
    pts = np.array([[0, 0, 0], [0.2, 0, 0], [1.0, 0, 0], [6.0, 0, 0], [10.0, 0, 0]], float)
    return fl.NurbsCurve(3, [0, 0, 0, 0, 0.5, 1, 1, 1, 1], pts), pts


def test_distribution_is_laid_out_in_arc_length_not_in_the_parameter():
    c, _ = straight_bspline()
    d = fl.grids.distribute(fl.arc_length(c), "geometric", 30, first=0.05, max_ratio=1.2)
    t = fl._native.parameters_at_arc_length(c, d)
    xs = np.asarray(c.evaluate(t))[:, 0]
    ds = spacings(xs)
    assert np.allclose(ds[1:] / ds[:-1], ds[1] / ds[0], rtol=1e-9)
    assert ds[0] == pytest.approx(0.05, rel=SPACING_TOL)


def test_arc_length_of_a_rational_quarter_circle():
    w = math.sqrt(0.5)
    c = fl.NurbsCurve(2, [0, 0, 0, 1, 1, 1], np.array([[3.0, 0, 0], [3.0, 3.0, 0], [0, 3.0, 0]]), [1, w, 1])
    assert fl.arc_length(c) == pytest.approx(1.5 * math.pi, rel=1e-12)


def test_gmsh_progression_on_the_same_edge_is_not_geometric_in_length():
    gmsh = pytest.importorskip("gmsh")
    _, pts = straight_bspline()
    gmsh.initialize(["-nt", "1"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        tags = [gmsh.model.geo.addPoint(*p) for p in pts]
        line = gmsh.model.geo.addBSpline(tags)
        gmsh.model.geo.mesh.setTransfiniteCurve(line, 21, "Progression", 1.08)
        gmsh.model.geo.synchronize()
        gmsh.model.mesh.generate(1)
        _, xyz, _ = gmsh.model.mesh.getNodes(1, line, includeBoundary=True)
    finally:
        gmsh.finalize()
    x = np.sort(np.asarray(xyz).reshape(-1, 3)[:, 0])
    r_gmsh = spacings(x)[1:] / spacings(x)[:-1]
    c, _ = straight_bspline()
    length = fl.arc_length(c)
    # ours: the same 21 points, the first spacing of an exact 1.08 progression
    first = length * 0.08 / (1.08**20 - 1)
    ours = np.asarray(c.evaluate(fl._native.parameters_at_arc_length(c, fl.grids.distribute(
        length, "geometric", 21, first=first, max_ratio=1.1))))[:, 0]
    r_ours = spacings(ours)[1:] / spacings(ours)[:-1]
    assert np.allclose(r_ours, 1.08, rtol=1e-9)
    assert np.ptp(r_gmsh) > 0.02  # gmsh spaces in the parameter


def test_surface_grid_boundaries_hit_their_spacings_in_metres():
    s = wigley_surface()
    g = fl.grids.surface_grid(s, u=dict(kind="tanh_two_sided", points=61, first=0.2, last=0.5),
                              v=dict(kind="geometric", points=25, first=0.05, max_ratio=1.3))
    p = g.points
    for j in (0, -1):  # boundaries v = v0, v = v1 (the keel line is a pole on y = 0: still a line)
        ds = np.linalg.norm(np.diff(p[:, j], axis=0), axis=1)  # chords; arc length is longer by O(ds^3)
        assert ds[0] == pytest.approx(0.2, rel=SPACING_TOL) and ds[-1] == pytest.approx(0.5, rel=SPACING_TOL)
    for i in (0, -1):
        ds = np.linalg.norm(np.diff(p[i, :], axis=0), axis=1)
        if ds.max() > 0:
            assert ds[0] == pytest.approx(0.05, rel=SPACING_TOL)
            assert (ds[1:] / ds[:-1]).max() <= 1.3 * (1 + SPACING_TOL)


def test_surface_grid_points_lie_on_the_surface():
    s = bilge_patch()
    g = fl.grids.surface_grid(s, 15, dict(kind="tanh", points=12, first=0.05))
    flat = g.points.reshape(-1, 3)[::7]
    gap = [np.linalg.norm(s.closest_point(q)[2] - q) for q in flat]
    assert max(gap) < 1e-8


def sample_params(s, n=200, seed=3):
    rng = np.random.default_rng(seed)
    (u0, u1), (v0, v1) = s.domain_u, s.domain_v
    return u0 + (u1 - u0) * rng.random(n), v0 + (v1 - v0) * rng.random(n)


def test_knot_insertion_clusters_the_knot_grid_and_moves_no_surface_point():
    s = bilge_patch()
    c = fl.grids.cluster_by_knots(s, "v", at=0.5, spacing=0.01, count=7)
    u, v = sample_params(s)
    assert np.abs(np.asarray(c.evaluate(u, v)) - np.asarray(s.evaluate(u, v))).max() < SURFACE_TOL
    before, after = fl.grids.knot_grid(s), fl.grids.knot_grid(c)
    vb, va = before.params[0, :, 1], after.params[0, :, 1]
    assert len(va) == len(vb) + 7
    assert np.sum(np.abs(va - 0.5) < 0.05) >= 7 > np.sum(np.abs(vb - 0.5) < 0.05)


@pytest.mark.parametrize("direction, ratio", [("u", 4.0), ("v", 0.2)])
def test_weights_reparameterise_without_moving_the_surface(direction, ratio):
    s = bilge_patch()
    c = fl.grids.cluster_by_weights(s, direction, ratio)
    assert np.allclose(c.control_points, s.control_points)
    sig_u, sig_v = sample_params(s)
    r = math.sqrt(ratio)
    f = lambda x: x / (x + r * (1 - x))  # noqa: E731  the Moebius map on the unit domain
    u, v = (f(sig_u), sig_v) if direction == "u" else (sig_u, f(sig_v))
    assert np.abs(np.asarray(c.evaluate(sig_u, sig_v)) - np.asarray(s.evaluate(u, v))).max() < SURFACE_TOL


def test_weights_cluster_a_uniform_grid_on_a_plane_as_the_map_says():
    plane = fl.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1],
                            np.array([[[0, 0, 0], [0, 5.0, 0]], [[10.0, 0, 0], [10.0, 5.0, 0]]]))
    c = fl.grids.cluster_by_weights(plane, "u", 9.0)
    n = 11
    g = fl.grids.parameter_grid(c, np.linspace(0, 1, n), np.linspace(0, 1, 3))
    ds = spacings(g.points[:, 0, 0])
    sig = np.linspace(0, 1, n)
    assert np.allclose(ds, 10.0 * spacings(sig / (sig + 3.0 * (1 - sig))), rtol=1e-12)
    assert ds[-1] / ds[0] > 0.5 * 9.0  # clustered at the start


def test_grid_quality_of_analytic_plane_grids():
    x, y = np.meshgrid(np.array([0, 1, 3, 7.0]), np.array([0, 0.5, 1.0]), indexing="ij")
    rect = np.stack([x, y, 0 * x], axis=-1)
    q = fl.grids.grid_quality(rect)
    assert q["first_min"] == pytest.approx(1.0) and q["last_max"] == pytest.approx(4.0)
    assert q["max_stretching"] == pytest.approx(2.0) and q["max_orthogonality_deg"] == pytest.approx(0.0, abs=1e-12)
    assert q["max_aspect_ratio"] == pytest.approx(8.0) and q["max_skewness"] == pytest.approx(0.0, abs=1e-12)
    sheared = rect + np.stack([np.tan(np.radians(20)) * y, 0 * y, 0 * y], axis=-1)
    q = fl.grids.grid_quality(sheared)
    assert q["max_orthogonality_deg"] == pytest.approx(20.0) and q["max_skewness"] == pytest.approx(20 / 90)


def test_grids_on_the_whole_ship_surfaces(tmp_path):
    grids_ = fl.grids.hull_grids(composed_example_hull(), u=dict(kind="tanh_two_sided", points=81, first=0.3, last=0.3),
                                 v=31)
    assert {"hull", "bulb", "blend"} <= set(grids_)
    for g in grids_.values():
        assert np.isfinite(g.points).all() and g.quality()["max_stretching"] < 50
    grids_["hull"].write_plot3d(tmp_path / "hull.xyz")
    back = fl.read_plot3d(tmp_path / "hull.xyz")[0]
    assert np.allclose(back, grids_["hull"].points)


def test_bad_grid_input_is_refused():
    s = bilge_patch()
    with pytest.raises(fl.InvalidInput, match="at is 2"):
        fl.grids.cluster_by_knots(s, "u", at=2.0, spacing=0.01, count=3)
    with pytest.raises(fl.InvalidInput, match="ratio is 0"):
        fl.grids.cluster_by_weights(s, "u", 0.0)
    with pytest.raises(fl.InvalidInput, match="us"):
        fl.grids.parameter_grid(s, [0.5, 0.2], [0, 1])
    with pytest.raises(fl.InvalidInput, match="option 'spacing'"):
        fl.grids.distribution("uniform", 5, spacing=3)
