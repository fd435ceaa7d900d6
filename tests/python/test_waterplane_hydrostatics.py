"""Waterplane inertias, metacentres, TPC / MCT1cm, trim and the refusal of drafts above the
deck in fl.hydrostatics, against closed-form results for a box barge and a Wigley hull."""

import numpy as np
import pytest

import fairlines as fl
from cad_fixtures import box_barge_surface, wigley_surface

L, B, D = 100.0, 20.0, 10.0


@pytest.mark.parametrize("T", [1.0, 4.0, 7.5, 10.0])
def test_box_barge_kmt_is_b2_over_12t_plus_t_over_2(T):
    h = fl.hydrostatics(box_barge_surface(L, B, D), T)
    assert h.kmt == pytest.approx(B * B / (12 * T) + T / 2, rel=1e-13)


def test_box_barge_waterplane_moments_tpc_and_mct():
    h = fl.hydrostatics(box_barge_surface(L, B, D), 5.0, density=1.025)
    assert h.inertia_t == pytest.approx(L * B**3 / 12, rel=1e-13)
    assert h.inertia_l == pytest.approx(B * L**3 / 12, rel=1e-13)
    assert h.kml == pytest.approx(5.0 / 2 + L * L / (12 * 5.0), rel=1e-13)
    assert h.tpc == pytest.approx(1.025 * L * B / 100, rel=1e-13)
    assert h.mct1cm == pytest.approx(h.displacement * h.bml / (100 * L), rel=1e-13)


def test_wigley_transverse_inertia_against_its_waterline():
    # waterline y = (B/2)(1 - xi^2), x = (L/2) xi: I_T = (2/3) int y^3 dx = (2/3)(B/2)^3 (L/2)(32/35)
    Lw, Bw, Tw = 100.0, 10.0, 6.25
    h = fl.hydrostatics(wigley_surface(Lw, Bw, Tw), Tw)
    assert h.inertia_t == pytest.approx((2 / 3) * (Bw / 2) ** 3 * (Lw / 2) * (32 / 35), rel=2e-4)
    assert h.lcf == pytest.approx(Lw / 2, abs=1e-6)


def test_trim_by_the_stern_moves_lcb_aft_as_a_linear_draft():
    # box barge, draft T + t (L/2 - x)/L: V unchanged, LCB = L/2 - t L / (12 T)
    T, t = 5.0, 1.0
    h = fl.hydrostatics(box_barge_surface(L, B, D), T, trim=t, trim_length=L)
    assert h.volume == pytest.approx(L * B * T, rel=1e-12)
    assert h.lcb == pytest.approx(L / 2 - t * L / (12 * T), rel=1e-12)
    assert h.waterplane_area == pytest.approx(L * B * np.hypot(1, t / L), rel=1e-12)
    assert h.trim == t


def test_draft_above_the_deck_is_refused_naming_both():
    with pytest.raises(fl.InvalidInput, match=r"10\.5 m.*highest point z = 10 m"):
        fl.hydrostatics(box_barge_surface(L, B, D), 10.5)
    assert fl.hydrostatics(box_barge_surface(L, B, D), D).volume == pytest.approx(L * B * D, rel=1e-13)


def test_trim_without_its_length_is_refused():
    with pytest.raises(fl.InvalidInput, match="trim_length"):
        fl.hydrostatics(box_barge_surface(L, B, D), 5.0, trim=1.0)


def raked_box_half(b, depth, length, rake_deg):
    """Half a box barge (half-breadth b) whose aft end is a plane raked rake_deg from the
    vertical, its top aft: the end at x = -z tan(rake), the fore end upright at x = length."""
    t = np.tan(np.radians(rake_deg))
    P = np.zeros((3, 2, 3))
    for i, (y, z) in enumerate([(b, depth), (b, 0.0), (0.0, 0.0)]):
        P[i, 0], P[i, 1] = (-z * t, y, z), (length, y, z)
    return fl.NurbsSurface(1, 1, [0, 0, 0.5, 1, 1], [0, 0, 1, 1], P)


@pytest.mark.parametrize("rake", [20.0, -15.0])
def test_a_raked_transoms_lid_adds_its_share_of_the_waterplane(rake):
    """An immersed raked transom's lid is not upright (n_z != 0): the waterplane runs to where
    the raked end meets it, T tan(rake) past the keel's end. Without the lid's fluxes the
    waterplane stopped at the keel's end (Awp 400 m^2 for 414.56 at 20 deg)."""
    b, T = B / 4, 4.0
    h = fl.hydrostatics(raked_box_half(b, D, 40.0, rake), T, half_hull=True)
    lw = 40.0 + T * np.tan(np.radians(rake))
    assert h.volume == pytest.approx(2 * b * (40.0 * T + 0.5 * T * T * np.tan(np.radians(rake))), rel=1e-13)
    assert h.waterplane_area == pytest.approx(2 * b * lw, rel=1e-13)
    assert h.lcf == pytest.approx(40.0 - lw / 2, rel=1e-13)
    assert h.inertia_l == pytest.approx(2 * b * lw**3 / 12, rel=1e-12)
    assert h.inertia_t == pytest.approx((2 * b) ** 3 * lw / 12, rel=1e-13)


def test_highest_point_is_the_deck_or_a_point_above_it():
    """fl.hydrostatics(...).z_max: a deck at constant height is the highest point (read at the
    breakpoints, where the net's top is reached); a control point raised above the deck makes
    the surface rise above it there, and z_max is the top a dense grid of the surface finds."""
    assert fl.hydrostatics(box_barge_surface(L, B, D), 5.0).z_max == pytest.approx(D, rel=1e-14)
    s = wigley_surface(100.0, 10.0, 6.25, 10.0)
    assert fl.hydrostatics(s, 6.25).z_max == pytest.approx(10.0, rel=1e-14)
    P = np.asarray(s.control_points)
    i, j = 2, P.shape[1] // 2  # a row below the deck's, amidships
    s.set_control_point(i, j, P[i, j] + np.array([0.0, 0.0, 3.0]))
    u = np.linspace(*s.domain_u, 801)
    v = np.linspace(*s.domain_v, 801)
    dense = float(np.asarray(s.evaluate_grid(u, v))[..., 2].max())
    assert dense > 10.05
    assert fl.hydrostatics(s, 6.25).z_max == pytest.approx(dense, abs=2e-3)
