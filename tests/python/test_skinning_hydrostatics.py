"""Fair skinning and hydrostatics against analytic truth and independent computations.

Truths used: the Wigley hull y = (B/2)(1 - (2x/L)^2)(1 - (zeta/T)^2) (zeta depth below the
waterline) has Cb = 4/9, Cm = Cwp = Cp = 2/3, LCB at midships and KB = 5T/8, and closed-form
volume and waterplane area at any draft; a box has Cb = Cm = 1; the E2-least interpolating
cubic is the natural cubic spline (scipy's CubicSpline, a different computation path); and a
dense triangle mesh of the surface gives volume and wetted area by a second method.
"""

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

import fairlines as fl

L, B, T = 100.0, 10.0, 6.25


def wigley_y(x, z):
    """Half-breadth of the Wigley hull, x from AP (midships at L/2), z above base."""
    xm = x - L / 2
    return B / 2 * (1 - (2 * xm / L) ** 2) * (1 - ((T - z) / T) ** 2)


def wigley_section(x, top=1.0):
    """The section at x from z = top*T down to the keel, exactly (a quadratic Bezier in z)."""
    def f(t):
        z = top * T * (1 - t)
        return np.array([x, wigley_y(x, z), z])

    p0, p2 = f(0.0), f(1.0)
    p1 = 2 * f(0.5) - (p0 + p2) / 2
    return fl.NurbsCurve(2, [0, 0, 0, 1, 1, 1], np.array([p0, p1, p2]))


@pytest.fixture(scope="module")
def wigley():
    sections = [wigley_section(x) for x in np.linspace(0, L, 41)]
    return fl.fair_skin(sections, n_control=8)


def mesh_volume_area(surface, n=400):
    """Volume (int y n_y dA on flat triangles, exact per triangle) and area of a dense mesh."""
    u0, u1 = surface.domain_u if not callable(surface.domain_u) else surface.domain_u()
    v0, v1 = surface.domain_v if not callable(surface.domain_v) else surface.domain_v()
    us, vs = np.linspace(u0, u1, n), np.linspace(v0, v1, n)
    P = surface.evaluate_grid(us, vs).reshape(n, n, 3)
    a, b, c, d = P[:-1, :-1], P[1:, :-1], P[1:, 1:], P[:-1, 1:]
    vol = area = 0.0
    for p, q, r in ((a, b, c), (a, c, d)):
        cr = np.cross(q - p, r - p) / 2
        area += np.linalg.norm(cr, axis=-1).sum()
        vol += ((p[..., 1] + q[..., 1] + r[..., 1]) / 3 * cr[..., 1]).sum()
    return 2 * abs(vol), 2 * area


def wigley_dense_wetted(n=1500):
    """Wetted surface of the analytic Wigley hull (both sides) from a dense triangle mesh."""
    x, z = np.meshgrid(np.linspace(0, L, n), np.linspace(0, T, n), indexing="ij")
    P = np.stack([x, wigley_y(x, z), z], axis=-1)
    a, b, c, d = P[:-1, :-1], P[1:, :-1], P[1:, 1:], P[:-1, 1:]
    area = sum(np.linalg.norm(np.cross(q - p, r - p), axis=-1).sum() / 2 for p, q, r in ((a, b, c), (a, c, d)))
    return 2 * area


def test_wigley_rebuilt_from_sections(wigley):
    h = fl.hydrostatics(wigley.surface, T, length=L, breadth=B, midship_x=L / 2)
    assert h.cb == pytest.approx(4 / 9, rel=1e-3)
    assert h.volume == pytest.approx(4 / 9 * L * B * T, rel=1e-3)
    for coef in (h.cm, h.cwp, h.cp):
        assert coef == pytest.approx(2 / 3, rel=1e-3)
    assert h.lcb == pytest.approx(L / 2, abs=1e-6 * L)
    assert h.lcf == pytest.approx(L / 2, abs=1e-6 * L)
    assert h.vcb == pytest.approx(5 * T / 8, rel=1e-3)
    assert h.wetted_surface == pytest.approx(wigley_dense_wetted(), rel=5e-3)
    # x_min / x_max: the submerged extent is the whole length.
    assert h.x_min == pytest.approx(0, abs=1e-9) and h.x_max == pytest.approx(L, rel=1e-12)


def test_wigley_partial_draft_closed_form(wigley):
    d = T / 2
    depth_int = d - (T**3 - (T - d) ** 3) / (3 * T**2)  # int_0^d (1 - ((T - z)/T)^2) dz
    volume = 2 * (B / 2) * (2 * L / 3) * depth_int
    awp = 2 * (B / 2) * (2 * L / 3) * (1 - ((T - d) / T) ** 2)
    h = fl.hydrostatics(wigley.surface, d)
    assert h.volume == pytest.approx(volume, rel=1e-3)
    assert h.waterplane_area == pytest.approx(awp, rel=1e-3)
    # The SAC at mid draft: A(x) = 2 (B/2)(1 - (2 xm/L)^2) depth_int.
    xm = h.sac_x - L / 2
    expected = 2 * (B / 2) * (1 - (2 * xm / L) ** 2) * depth_int
    assert np.max(np.abs(h.sac_area - expected)) < 2e-3 * expected.max()


def test_wigley_section_area_and_centroid(wigley):
    for x in (10.0, 37.5, 50.0, 81.0):
        area, zc = fl.section_area(wigley.surface, x, T)
        c = B / 2 * (1 - (2 * (x - L / 2) / L) ** 2)
        assert area == pytest.approx(2 * c * 2 * T / 3, rel=1e-3)
        assert zc == pytest.approx(5 * T / 8, rel=1e-3)


def test_hydrostatics_match_dense_mesh_of_the_same_surface():
    sections = [wigley_section(x, top=1.0) for x in np.linspace(0, L, 15)]
    surf = fl.fair_skin(sections, n_control=10).surface
    vol, area = mesh_volume_area(surf)
    h = fl.hydrostatics(surf, T)
    assert h.volume == pytest.approx(vol, rel=2e-4)
    assert h.wetted_surface == pytest.approx(area, rel=2e-4)


def test_box_is_exact():
    """A degree-1 box half hull: Cb = Cm = Cwp = 1, KB = d/2, wetted = L (2d + B)."""
    Lb, Bb, Db, d = 20.0, 4.0, 3.0, 1.7
    P = np.array([[[0, Bb / 2, Db], [Lb, Bb / 2, Db]],
                  [[0, Bb / 2, 0], [Lb, Bb / 2, 0]],
                  [[0, 0, 0], [Lb, 0, 0]]], dtype=float)
    box = fl.NurbsSurface(1, 1, [0, 0, 0.5, 1, 1], [0, 0, 1, 1], P)
    h = fl.hydrostatics(box, d)
    assert h.volume == pytest.approx(Lb * Bb * d, rel=1e-12)
    assert h.cb == pytest.approx(1, rel=1e-12) and h.cm == pytest.approx(1, rel=1e-12)
    assert h.cwp == pytest.approx(1, rel=1e-12)
    assert h.vcb == pytest.approx(d / 2, rel=1e-12)
    assert h.lcb == pytest.approx(Lb / 2, rel=1e-12) and h.lcf == pytest.approx(Lb / 2, rel=1e-12)
    assert h.wetted_surface == pytest.approx(Lb * (2 * d + Bb), rel=1e-12)
    full = fl.hydrostatics(box, d, half_hull=False)
    assert full.volume == pytest.approx(h.volume / 2, rel=1e-12)


def test_barge_with_raked_ends_is_exact_though_its_rows_climb_the_whole_depth():
    """A degree-1 barge whose keel rises to the deck at both ends (over e at each): its keel's
    and bilge's rows span the whole depth, as a cruiser-sterned hull's rows do, more than its
    end sections. The waterline runs along the bilge's row over the midbody, so the waterplane
    must clip the girth lines, not the rows (clipping the rows it lay between two Gauss lines:
    2.2 % off here, 1.6 % on a designed cruiser-sterned hull). With d = D/2 the waterline ends at the
    columns x = e/2 and L - e/2 (knots), so every Gauss count is exact: volume below d
    (B/2) (d (L - 2e) + d e / 2) a side, waterplane area L - e times B, LCB at L/2."""
    Lb, Bb, Db, e = 60.0, 12.0, 8.0, 10.0
    d = Db / 2
    xs, zk = [0.0, e / 2, e, Lb - e, Lb - e / 2, Lb], [Db, d, 0.0, 0.0, d, Db]
    P = np.array([[[x, Bb / 2, Db] for x in xs],
                  [[x, Bb / 2, z] for x, z in zip(xs, zk)],
                  [[x, 0.0, z] for x, z in zip(xs, zk)]])
    barge = fl.NurbsSurface(1, 1, [0, 0, 0.5, 1, 1], [0, 0, 0.1, 0.2, 0.8, 0.9, 1, 1], P)
    for gauss in (2, 4, 8):
        h = fl.hydrostatics(barge, d, gauss=gauss)
        assert h.volume == pytest.approx(Bb * (d * (Lb - 2 * e) + d * e / 2), rel=1e-12), gauss
        assert h.waterplane_area == pytest.approx((Lb - e) * Bb, rel=1e-12), gauss
        assert h.lcb == pytest.approx(Lb / 2, rel=1e-12), gauss


def test_sections_are_iso_curves_and_rows_are_natural_splines(wigley):
    surf = wigley.surface
    v = wigley.section_params
    # Station parameterization: v proportional to x.
    assert np.allclose(v, np.linspace(0, 1, 41), atol=1e-12)
    xs = np.linspace(0, L, 41)
    for d in (0, 7, 20, 40):
        sec = wigley_section(xs[d])
        iso = surf.iso_curve("v", v[d])
        ts = np.linspace(0, 1, 60)
        pts = iso.evaluate(ts)
        assert np.allclose(pts[:, 0], xs[d], atol=1e-9)
        # Every iso-curve point lies on the exact section: y = wigley_y(x, z).
        assert np.max(np.abs(pts[:, 1] - wigley_y(xs[d], pts[:, 2]))) < 5 * wigley.section_fit_max + 1e-9
    # Each longitudinal control row is the natural cubic spline through the row data.
    nu, nv = 8, surf.control_points.shape[1]
    row_curves = [surf.iso_curve("u", 0.3)]  # a generic u-line, checked below through rows
    assert row_curves[0].degree == 3
    cps = surf.control_points  # (nu, nv, 3)
    knots_v = surf.knots_v
    for i in (1, 4):
        row = fl.NurbsCurve(3, knots_v, cps[i])
        data = row.evaluate(v)
        spline = CubicSpline(v, data, bc_type="natural")
        tt = np.linspace(0, 1, 333)
        assert np.max(np.abs(row.evaluate(tt) - spline(tt))) < 1e-9
    assert wigley.longitudinal_max < 1e-10
    assert wigley.row_e2.shape == (nu,)


def test_parallel_end_meets_a_cylinder_with_c1():
    # A forebody-like set: identical midship sections at the start, narrowing forward.
    xs = np.linspace(50, 100, 11)
    secs = [wigley_section(x) for x in xs]
    r = fl.fair_skin(secs, n_control=8, start="parallel")
    for u in np.linspace(0.05, 0.95, 7):
        sv = r.surface.derivatives(u, 0.0, 1)[0, 1]  # dS/dv
        assert abs(sv[1]) < 1e-9 and abs(sv[2]) < 1e-9 and sv[0] > 0
    free = fl.fair_skin(secs, n_control=8)
    assert abs(free.surface.derivatives(0.5, 0.0, 1)[0, 1][1]) > 1e-3
    # The parallel start is still an interpolation of all sections.
    assert r.longitudinal_max < 1e-10


def test_c1_joint_and_approximate_mode():
    xs = np.linspace(0, L, 21)
    secs = [wigley_section(x) for x in xs]
    r = fl.fair_skin(secs, n_control=8, c1_sections=[10])
    kv = r.surface.knots_v
    assert np.sum(np.isclose(kv, 0.5)) == 2
    assert r.longitudinal_max < 1e-10
    a = fl.fair_skin(secs, n_control=8, mode="approximate", smoothing=1e-2)
    i = fl.fair_skin(secs, n_control=8)
    assert 0 < a.longitudinal_max < 0.05
    assert a.row_e2.sum() < i.row_e2.sum()


def _kinked_sections(xs, x_kink):
    """Midship Wigley sections at `xs`, their half-breadths scaled by a breadth factor that
    rises linearly to 1 at `x_kink` and stays 1 forward of it (a knuckle along the hull)."""
    out = []
    for x in xs:
        c = wigley_section(L / 2)
        p = c.control_points.copy()
        p[:, 0], p[:, 1] = x, p[:, 1] * (0.2 + 0.8 * min(1.0, x / x_kink))
        out.append(fl.NurbsCurve(2, [0, 0, 0, 1, 1, 1], p))
    return out


def test_c0_sections_keep_a_knuckle_without_ringing():
    """Across the C0 station the skin follows the piecewise-linear breadth exactly (straight
    aft of it, constant forward); a C2 skin through the same rows rings on both sides."""
    xs = np.linspace(0.0, 40.0, 21)
    secs = _kinked_sections(xs, 10.0)
    kinked = fl.fair_skin(secs, params="station", c0_sections=[5])
    smooth = fl.fair_skin(secs, params="station")
    assert np.sum(np.isclose(kinked.surface.knots_v, 0.25)) == 3
    v = np.linspace(0.0, 1.0, 161)
    exact = wigley_y(L / 2, T) * (0.2 + 0.8 * np.minimum(1.0, 40.0 * v / 10.0))
    err = lambda r: np.max(np.abs(r.surface.evaluate(np.zeros_like(v), v)[:, 1] - exact))
    assert err(kinked) < 1e-9
    assert err(smooth) > 1e-3


def test_c0_sections_rule_the_skin_between_them():
    """Between consecutive C0 stations every point of the skin is on the straight line between
    the two sections' points (least E2 through two rows): even over curved data."""
    xs = np.linspace(0.0, L, 21)
    r = fl.fair_skin([wigley_section(x) for x in xs], n_control=8, params="station", c0_sections=[1, 2, 3])
    for u in (0.1, 0.5, 0.9):
        a, b, mid = r.surface.evaluate([u, u, u], [0.05, 0.1, 0.075])
        assert np.allclose(mid, (a + b) / 2, atol=1e-9)
    assert r.longitudinal_max < 1e-10


def _cubic_rows(xs):
    """Sections whose half-breadths follow a cubic in x: y = B/2 (0.3 + 0.2 s + 0.9 s^2 - 0.6 s^3), s = x / L."""
    out = []
    for x in xs:
        p = wigley_section(L / 2).control_points.copy()
        sx = x / L
        p[:, 0], p[:, 1] = x, p[:, 1] * (0.3 + 0.2 * sx + 0.9 * sx ** 2 - 0.6 * sx ** 3)
        out.append(fl.NurbsCurve(2, [0, 0, 0, 1, 1, 1], p))
    return out


def test_not_a_knot_ends_reproduce_a_cubic_the_natural_ends_bend():
    """Interpolating rows that vary as a cubic along the hull, not-a-knot ends at both ends give
    that cubic exactly (de Boor); natural ('free') ends force zero curvature at the end sections
    and miss it; a not-a-knot start alone meets it near the start, not near the free end."""
    xs = np.array([0.0, 7.0, 19.0, 30.0, 46.0, 58.0, 71.0, 85.0, 100.0])
    secs = _cubic_rows(xs)
    v = np.linspace(0.0, 1.0, 201)
    exact = wigley_y(L / 2, T) * (0.3 + 0.2 * v + 0.9 * v ** 2 - 0.6 * v ** 3)
    err = lambda r, sl=slice(None): np.max(np.abs(r.surface.evaluate(np.zeros_like(v), v)[:, 1] - exact)[sl])
    both = fl.fair_skin(secs, params="station", start="not_a_knot", end="not_a_knot")
    free = fl.fair_skin(secs, params="station")
    start = fl.fair_skin(secs, params="station", start="not_a_knot")
    assert err(both) < 1e-9
    assert err(free) > 1e-3
    assert err(start, slice(0, 20)) < 0.1 * err(free, slice(0, 20))
    assert err(start, slice(180, None)) > 1e-3


def test_two_held_runs_that_meet_are_both_met():
    """Sections of one shape whose breadth steps by 33 um between two flat runs (stations 0-5
    and 6-10): every row is held on both runs, and the skin meets every station. With one knot
    between the runs, a control held by both kept one value and a station was 11 um off."""
    def line(x, y):
        return fl.NurbsCurve(1, [0, 0, 1, 1], np.array([[x, y, 1.0], [x, 0.5 * y, 0.0]]))

    xs = np.linspace(0.0, 40.0, 11)
    r = fl.fair_skin([line(x, 5.0 if i < 6 else 5.0 + 3.3e-5) for i, x in enumerate(xs)], params="station")
    assert r.held_columns > 0
    assert r.longitudinal_max < 1e-12


def _rows_touching_the_centre_plane(xs):
    """Sections (lines from y = 5 at z = 1 to the bottom row at z = 0) whose bottom row lies on
    the centre plane at x 20 and 22.5 m and leaves it quadratically either side."""
    out = []
    for x in xs:
        y = 0.05 * (x - 22.5) ** 2 if x > 22.5 else 0.05 * (x - 20.0) ** 2 if x < 20.0 else 0.0
        out.append(fl.NurbsCurve(1, [0, 0, 1, 1], np.array([[x, 5.0, 1.0], [x, y, 0.0]])))
    return out


def test_y_nonnegative_keeps_the_skin_off_the_centre_plane():
    """Through rows that touch the centre plane the least-E2 interpolant dips 2.9 cm across it
    (a fold of the half hull); with y_nonnegative every point of the skin has y >= 0 (convex
    hull property), the bottom row meets its points within the miss it reports (under
    kCentrePlaneMaxMiss of the sections' size, 4 cm here) and the top row is untouched."""
    xs = np.arange(0.0, 40.01, 2.5)
    secs = _rows_touching_the_centre_plane(xs)
    free = fl.fair_skin(secs, params="station", degree_u=1)
    kept = fl.fair_skin(secs, params="station", degree_u=1, y_nonnegative=True)
    u, v = (g.ravel() for g in np.meshgrid(np.linspace(0, 1, 51), np.linspace(0, 1, 801)))
    assert free.surface.evaluate(u, v)[:, 1].min() < -0.02
    assert kept.surface.evaluate(u, v)[:, 1].min() >= 0.0
    assert kept.centre_plane_columns == 1 and 0 < kept.centre_plane_miss <= 1e-3 * 40.0
    bottom = kept.surface.evaluate(np.ones_like(kept.section_params), kept.section_params)[:, 1]
    data = np.array([c.control_points[1, 1] for c in secs])
    assert np.max(np.abs(bottom - data)) == pytest.approx(kept.centre_plane_miss, rel=1e-6)
    assert np.array_equal(np.asarray(kept.surface.control_points)[0], np.asarray(free.surface.control_points)[0])


def test_y_nonnegative_keeps_a_straight_group_straight():
    """The same rows with a middle row on the straight segment between them (a straight group):
    the bottom row is kept off the plane, the middle row stays on the segment (half way) and
    the skin meets the top row exactly (before, the middle row's miss failed the interpolation check)."""
    secs = []
    for c in _rows_touching_the_centre_plane(np.arange(0.0, 40.01, 2.5)):
        top, bottom = c.control_points
        secs.append(fl.NurbsCurve(1, [0, 0, 0.5, 1, 1], np.array([top, (top + bottom) / 2, bottom])))
    kept = fl.fair_skin(secs, params="station", degree_u=1, y_nonnegative=True, straight_groups=[(0, 2)])
    P = np.asarray(kept.surface.control_points)
    assert kept.centre_plane_columns == 1 and P[..., 1].min() >= 0.0
    assert np.allclose(P[1], (P[0] + P[2]) / 2, atol=1e-12)
    assert kept.longitudinal_max < 1e-9


def test_y_nonnegative_leaves_a_skin_it_would_pull_far_off_its_rows():
    """Rows that drop from 1 m onto the centre plane within one station and leave it steeply
    one station later cannot be kept at y >= 0 without missing their points by more than
    kCentrePlaneMaxMiss of the sections' size (4 cm here): the skin is left as it was, bit for
    bit, and says what keeping it off would have cost."""
    def rows(x):
        y = 1.0 if x < 10.0 else 0.4 * max(0.0, x - 12.5)
        return fl.NurbsCurve(1, [0, 0, 1, 1], np.array([[x, 5.0, 1.0], [x, y, 0.0]]))

    secs = [rows(x) for x in np.arange(0.0, 40.01, 2.5)]
    free = fl.fair_skin(secs, params="station", degree_u=1)
    kept = fl.fair_skin(secs, params="station", degree_u=1, y_nonnegative=True)
    assert np.asarray(free.surface.control_points)[..., 1].min() < -0.1
    assert kept.centre_plane_columns == 0 and kept.centre_plane_refused_miss > 1e-3 * 40.0
    assert np.array_equal(np.asarray(kept.surface.control_points), np.asarray(free.surface.control_points))


def test_y_nonnegative_changes_nothing_where_no_row_dips(wigley):
    """A skin whose rows never go below y = 0 is the same, bit for bit."""
    xs = np.linspace(0.0, L, 21)
    secs = [wigley_section(x) for x in xs]
    kept = fl.fair_skin(secs, n_control=8, params="station", y_nonnegative=True)
    free = fl.fair_skin(secs, n_control=8, params="station")
    assert kept.centre_plane_columns == 0
    assert np.array_equal(np.asarray(kept.surface.control_points), np.asarray(free.surface.control_points))


def test_equal_arc_length_points_on_a_circle():
    c = fl.arc([0, 0, 0], 2.0, 0.0, np.pi)
    pts = c.evaluate(np.linspace(0, 1, 5))
    eq = fl.equal_arc_length_points(c, 9)
    ang = np.unwrap(np.arctan2(eq[:, 1], eq[:, 0]))
    assert np.allclose(np.linalg.norm(eq, axis=1), 2.0, atol=1e-12)
    assert np.max(np.abs(np.diff(ang) - np.pi / 8)) < 1e-4 * np.pi / 8
    assert fl.arc_length(c) == pytest.approx(2 * np.pi, rel=1e-10)
    assert pts.shape == (5, 3)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(mode="smooth"), "mode is 'smooth'"),
        (dict(start="clamped"), "end condition is 'clamped'"),
        (dict(params="uniform"), "params is 'uniform'"),
        (dict(n_control=2), "n_control is 2"),
        (dict(samples=3), "samples is 3"),
        (dict(c1_sections=[0]), "c1_sections contains 0"),
        (dict(c0_sections=[2]), "c0_sections contains 2"),
        (dict(start="not_a_knot", c0_sections=[1]), "end condition 'not_a_knot' at the first section"),
        (dict(end="natural"), "end condition is 'natural'"),
        (dict(degree_v=1), "degree_v is 1"),
        (dict(mode="approximate", smoothing=float("nan")), "smoothing is nan"),
    ],
)
def test_fair_skin_bad_options(kwargs, match):
    secs = [wigley_section(x) for x in (10.0, 20.0, 30.0)]
    with pytest.raises(ValueError, match=match):
        fl.fair_skin(secs, **kwargs)


def test_fair_skin_bad_curves():
    with pytest.raises(ValueError, match="at least 2"):
        fl.fair_skin([wigley_section(10.0)])
    flat = fl.NurbsCurve(1, [0, 0, 1, 1], [[0.0, 0.0], [1.0, 1.0]])
    with pytest.raises(ValueError, match=r"sections\[1\] is a 2-D curve"):
        fl.fair_skin([wigley_section(10.0), flat])
    point = fl.NurbsCurve(1, [0, 0, 1, 1], [[5.0, 1.0, 1.0], [5.0, 1.0, 1.0]])
    with pytest.raises(ValueError, match=r"sections\[1\].*zero length"):
        fl.fair_skin([wigley_section(10.0), point, wigley_section(30.0)])
    with pytest.raises(ValueError, match=r"curves\[0\] is"):
        fl.fair_skin(["not a curve", wigley_section(1.0)])
    with pytest.raises(ValueError, match="params is 'station' but the section x positions"):
        fl.fair_skin([wigley_section(20.0), wigley_section(10.0), wigley_section(30.0)], params="station")


@pytest.mark.parametrize("draft, match", [(0.0, "draft is 0"), (float("nan"), "draft is nan"), (-1.0, "draft is -1")])
def test_hydrostatics_bad_draft(wigley, draft, match):
    with pytest.raises(ValueError, match=match):
        fl.hydrostatics(wigley.surface, draft)


def test_hydrostatics_bad_options(wigley):
    with pytest.raises(ValueError, match="gauss is 1"):
        fl.hydrostatics(wigley.surface, T, gauss=1)
    with pytest.raises(ValueError, match="length is -3"):
        fl.hydrostatics(wigley.surface, T, length=-3.0)
    with pytest.raises(ValueError, match="sac_stations is 1"):
        fl.hydrostatics(wigley.surface, T, sac_stations=1)
    with pytest.raises(ValueError, match="midship_x is nan"):
        fl.hydrostatics(wigley.surface, T, midship_x=float("nan"))
    # Entirely above the water.
    P = np.array([[[0, 1, 5], [9, 1, 5]], [[0, 1, 2], [9, 1, 2]], [[0, 0, 2], [9, 0, 2]]], dtype=float)
    lifted = fl.NurbsSurface(1, 1, [0, 0, 0.5, 1, 1], [0, 0, 1, 1], P)
    with pytest.raises(ValueError, match="nothing below draft 1"):
        fl.hydrostatics(lifted, 1.0)


def test_curvature_weighted_spacing_crowds_where_the_curve_bends():
    # A polynomial hairpin: straight legs along x, a tight turn near x = 10.
    P = np.array([[0, 0, 0], [8, 0, 0], [10, 0, 0], [10, 1, 0], [8, 1, 0], [0, 1, 0]], dtype=float)
    c = fl.NurbsCurve(3, fl.clamped_uniform_knots(6, 3), P)
    plain = fl.equal_arc_length_points(c, 2001)
    d = np.linalg.norm(np.diff(plain, axis=0), axis=1)
    assert d.max() - d.min() < 2e-2 * d.mean()  # equal arc length (chords ~ arcs at this density)
    assert d.sum() == pytest.approx(fl.arc_length(c), rel=1e-4)
    w = fl.equal_arc_length_points(c, 201, curvature_weight=0.1)
    dw = np.linalg.norm(np.diff(w, axis=0), axis=1)
    turn = w[:-1, 0] > 9.0
    legs = w[:-1, 0] < 5.0
    assert dw[turn].mean() < 0.5 * dw[legs].mean()
    with pytest.raises(ValueError, match="curvature_weight is -1"):
        fl.equal_arc_length_points(c, 10, curvature_weight=-1.0)


def box_bilge_section(x, half_breadth, depth, radius):
    """Exact section: flat side y = half_breadth from the deck down to the bilge, a circular
    bilge of `radius` (rational quadratic arc), flat bottom z = 0 to the centre line."""
    b, r = half_breadth, radius
    w = np.sqrt(0.5)
    pts = [[x, b, depth], [x, b, 0.5 * (depth + r)], [x, b, r], [x, b, 0.0], [x, b - r, 0.0],
           [x, 0.5 * (b - r), 0.0], [x, 0.0, 0.0]]
    return fl.NurbsCurve(2, [0, 0, 0, 0.4, 0.4, 0.6, 0.6, 1, 1, 1], pts, weights=[1, 1, 1, w, 1, 1, 1])


def test_flats_keep_the_section_fits_exactly_on_the_planes():
    B2, D = 10.0, 12.0
    xs = np.linspace(0.0, 40.0, 9)
    radii = 2.0 + 0.05 * xs
    secs = [box_bilge_section(x, B2, D, r) for x, r in zip(xs, radii)]
    flats = [(1, B2), (2, 0.0)]
    held = fl.fair_skin(secs, n_control=24, flats=flats)
    plain = fl.fair_skin(secs, n_control=24)
    us = np.linspace(0.0, 1.0, 4001)
    margin = 5.0  # m: a control point's support (four knot spans of about 1 m) away from the bilge
    for res, exact in ((held, True), (plain, False)):
        side_dev, bottom_dev = 0.0, 0.0
        for v, r in zip(res.section_params, radii):
            p = res.surface.evaluate(us, np.full_like(us, v))
            side = p[:, 2] > r + margin
            bottom = p[:, 1] < B2 - r - margin
            side_dev = max(side_dev, np.abs(p[side, 1] - B2).max())
            bottom_dev = max(bottom_dev, np.abs(p[bottom, 2]).max())
        if exact:
            assert side_dev <= 1e-12 and bottom_dev <= 1e-12
        else:  # the plain least-squares fit ripples about the planes: the option matters
            assert max(side_dev, bottom_dev) > 1e-6
    # Rows flat in every section stay flat between the sections too.
    g = held.surface.evaluate_grid(us, np.linspace(0, 1, 201)).reshape(-1, 3)
    top = g[:, 2] > radii.max() + margin
    assert np.abs(g[top, 1] - B2).max() <= 1e-12
    # The fit still follows the exact sections closely.
    assert held.section_fit_max < 0.05


@pytest.mark.parametrize("flats, match", [([(3, 0.0)], "flats\\[0\\] has axis 3"),
                                          ([(1, float("nan"))], "flats\\[0\\] has value nan"),
                                          ([(1,)], "flats\\[0\\] is \\(1,\\); expected an \\(axis, value\\) pair")])
def test_fair_skin_bad_flats(flats, match):
    secs = [box_bilge_section(x, 10.0, 12.0, 2.0) for x in (0.0, 10.0, 20.0)]
    with pytest.raises(ValueError, match=match):
        fl.fair_skin(secs, flats=flats)


@pytest.mark.parametrize("option, value, says", [
    ("gaus", 4, "option 'gaus' is unknown; expected one of"),
    ("gauss", 8.5, "gauss is 8.5; expected an integer"),
    ("half_hull", "yes", "option half_hull is 'yes'; expected a bool"),
])
def test_hydrostatics_option_of_wrong_name_or_type_is_refused_by_name(wigley, option, value, says):
    with pytest.raises(fl.InvalidInput, match=says):
        fl.hydrostatics(wigley.surface, T, **{option: value})
