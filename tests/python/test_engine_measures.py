"""Measures the engine now owns, against exact solids: Kracht's coefficients of a box bulb
mesh, hydrostatics of a box hull given as separate NURBS patches (some facing inward), and
batched foot points on a cylinder."""

import numpy as np
import pytest

import fairlines as fl
from fairlines import preprocess as pp

EXACT = 1e-12  # relative: flat faces, bilinear patches and distances to a circle are exact
FOOT_TOL = 1e-7  # relative: a foot point is found to about sqrt(machine eps) times the distance


def closed_half_box(x0, x1, b, z0, z1):
    """Outward triangles of the box [x0, x1] x [0, b] x [z0, z1], centre-plane face included."""
    v = np.array([[x0, 0, z0], [x1, 0, z0], [x1, b, z0], [x0, b, z0],
                  [x0, 0, z1], [x1, 0, z1], [x1, b, z1], [x0, b, z1]], float)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5), (0, 1, 5, 4)]
    return v, np.array([t for a, c, d, e in quads for t in ((a, c, d), (a, d, e))])


def test_kracht_of_a_box_bulb_is_exact():
    x_fp, p, b, z0, z1, draft = 100.0, 3.0, 1.5, 1.0, 4.0, 6.0
    v, f = closed_half_box(x_fp - 10.0, x_fp + p, b, z0, z1)
    ship = dict(x_fp=x_fp, lpp=100.0, beam=20.0, draft_fp=draft, midship_area=50.0, displacement_volume=2000.0)
    k = fl.measure_kracht(fl.Mesh(v, f), **ship)
    area = b * (z1 - z0)
    assert k["c_lpr"] == pytest.approx(p / 100.0, rel=EXACT)
    assert k["c_bb"] == pytest.approx(2 * b / 20.0, rel=EXACT)
    assert k["c_abt"] == pytest.approx(2 * area / 50.0, rel=EXACT)
    assert k["c_abl"] == pytest.approx(p * (z1 - z0) / 50.0, rel=EXACT)
    assert k["c_vpr"] == pytest.approx(2 * p * area / 2000.0, rel=EXACT)
    assert z0 <= k["c_zb"] * draft <= z1


@pytest.mark.parametrize("name, value", [("lpp", 0.0), ("draft_fp", float("nan")), ("x_fp", float("inf"))])
def test_kracht_refuses_a_bad_ship_dimension(name, value):
    v, f = closed_half_box(0.0, 10.0, 1.0, 0.0, 1.0)
    ship = dict(x_fp=5.0, lpp=10.0, beam=2.0, draft_fp=1.0, midship_area=1.0, displacement_volume=10.0)
    with pytest.raises(fl.InvalidInput, match=name):
        fl.measure_kracht(fl.Mesh(v, f), **{**ship, name: value})


def plane_patch(a, b, c):
    """The bilinear patch with corners a (u=0, v=0), b (u=1, v=0), c (u=0, v=1) of a parallelogram."""
    a, b, c = (np.asarray(p, float) for p in (a, b, c))
    pts = np.array([[a, c], [b, b + c - a]])
    return fl.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], pts)


def box_patches(L, b, D):
    """The half box [0, L] x [0, b] x [0, D] as four patches: side and aft end outward, bottom
    and fore end inward (their u, v swapped)."""
    side = plane_patch([0, b, 0], [L, b, 0], [0, b, D])          # normal +y: outward
    bottom = plane_patch([0, 0, 0], [0, b, 0], [L, 0, 0])        # normal +z: inward
    aft = plane_patch([0, 0, 0], [0, b, 0], [0, 0, D])           # normal +x at x = 0: inward
    fore = plane_patch([L, 0, 0], [L, b, 0], [L, 0, D])          # normal +x at x = L: outward
    return [side, bottom, aft, fore]


def test_box_patches_give_the_box_below_the_waterline():
    L, b, D, T = 12.0, 2.5, 4.0, 1.5
    h = fl.hydrostatics_of_patches(box_patches(L, b, D), T, L / 2)
    assert h.volume == pytest.approx(L * 2 * b * T, rel=EXACT)
    assert (h.lcb, h.vcb) == pytest.approx((L / 2, T / 2), rel=EXACT)
    assert (h.waterplane_area, h.lcf) == pytest.approx((2 * L * b, L / 2), rel=EXACT)
    assert h.wetted_surface == pytest.approx(2 * (L * b + L * T + 2 * b * T), rel=EXACT)


def test_a_patch_above_the_waterline_adds_nothing():
    L, b, D, T = 12.0, 2.5, 4.0, 1.5
    deck = plane_patch([0, 0, D], [L, 0, D], [0, b, D])
    with_deck = fl.hydrostatics_of_patches(box_patches(L, b, D) + [deck], T, L / 2)
    assert with_deck.volume == pytest.approx(L * 2 * b * T, rel=EXACT)
    with pytest.raises(fl.InvalidInput, match="draft"):
        fl.hydrostatics_of_patches([deck], -1.0, L / 2)


def test_patch_hydrostatics_refuse_an_empty_patch_list():
    with pytest.raises(fl.InvalidInput, match="patches is empty"):
        fl.hydrostatics_of_patches([], 1.0, 0.0)


def test_foot_points_on_a_cylinder_from_nearby_starts():
    r, length = 2.0, 5.0
    arc = fl.arc([0, 0, 0], r, 0.0, np.pi / 2)  # quarter circle in the (x, y) plane
    cyl = fl.NurbsSurface(arc.degree, 1, arc.knots, [0, 0, 1, 1],
                          np.stack([np.c_[arc.control_points[:, :2], np.zeros(3)],
                                    np.c_[arc.control_points[:, :2], np.full(3, length)]], axis=1),
                          weights=np.c_[arc.weights, arc.weights])
    rng = np.random.default_rng(1)
    ang, z, rho = rng.uniform(0.1, 1.4, 40), rng.uniform(0.5, 4.5, 40), rng.uniform(0.5, 3.5, 40)
    pts = np.c_[rho * np.cos(ang), rho * np.sin(ang), z]
    u0, v0 = ang / (np.pi / 2), z / length + 0.05  # near the foot points: a local search
    u, v, feet = cyl.closest_points(pts, u0, v0)
    exact = np.c_[r * np.cos(ang), r * np.sin(ang), z]
    # The distance is exact; the foot point only to sqrt(eps) of it (the distance is flat there).
    assert np.linalg.norm(feet - pts, axis=1) == pytest.approx(np.abs(rho - r), rel=EXACT, abs=EXACT * r)
    assert np.abs(feet - exact).max() < FOOT_TOL * r
    assert np.allclose(pp.project_points(cyl, pts, u0, v0), feet, rtol=0, atol=0)
    with pytest.raises(fl.InvalidInput, match="u0 / v0"):
        cyl.closest_points(pts, u0[:3], v0)
