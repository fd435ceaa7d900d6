"""Blend boundaries around a seam (the engine's blend_boundaries_around_seam), judged by plain
geometry in parameter space: the boundary with the hull edges it meets closes a region that
holds every seam point, at least the clearance away from the boundary."""

import numpy as np
import pytest

import fairlines as fl
from fairlines.blend import _boundaries_around_seam

CLEAR_U, CLEAR_V = 0.05, 0.01


def _unit_square_surface() -> fl.NurbsSurface:
    """A bilinear patch over u, v in [0, 1]: the placement reads only the hull's domain and
    its keel-zone knots, so any surface serves."""
    pts = np.array([[[0, 0, 0], [0, 0, 1]], [[1, 0, 0], [1, 0, 1]]], float)
    k = [0.0, 0.0, 1.0, 1.0]
    return fl.NurbsSurface(1, 1, k, k, pts)


def _seam(u, v) -> dict:
    uv = np.column_stack([u, v])
    return {"uv_a": uv, "uv_b": np.column_stack([np.linspace(0.1, 0.3, len(u)), np.linspace(0, 1, len(u))])}


def _inside(poly: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Even-odd ray casting of points in a closed polygon."""
    x, y = pts[:, 0][:, None], pts[:, 1][:, None]
    a, b = poly, np.roll(poly, -1, axis=0)
    cross = (a[:, 1] > y) != (b[:, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xi = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return (cross & (x < xi)).sum(axis=1) % 2 == 1


def _distance_to_polyline(line: np.ndarray, pts: np.ndarray) -> np.ndarray:
    a, b = line[:-1], line[1:]
    d = b - a
    t = np.clip(((pts[:, None, :] - a) * d).sum(-1) / (d * d).sum(-1), 0, 1)
    return np.linalg.norm(pts[:, None, :] - (a + t[..., None] * d), axis=-1).min(axis=1)


def _check_holds_the_seam(boundary, seam_uv, closing):
    region = np.vstack([boundary, closing])
    assert _inside(region, seam_uv).all()
    assert _distance_to_polyline(boundary, seam_uv).min() >= min(CLEAR_U, CLEAR_V) * 0.999


def test_seam_on_the_stem_at_both_ends_is_held_by_a_half_ellipse():
    s = np.linspace(0, np.pi, 40)
    seam = _seam(1.0 - 0.2 * np.sin(s), 0.5 - 0.15 * np.cos(s))
    boundary, (_, bulb_u) = _boundaries_around_seam(_unit_square_surface(), seam)
    assert boundary[0, 0] == pytest.approx(1.0) and boundary[-1, 0] == pytest.approx(1.0)
    assert boundary[-1, 1] > seam["uv_a"][:, 1].max() > seam["uv_a"][:, 1].min() > boundary[0, 1]
    _check_holds_the_seam(boundary, seam["uv_a"][1:-1], np.empty((0, 2)))
    assert bulb_u == pytest.approx(0.3 + 0.01)


def test_seam_from_the_keel_to_the_stem_is_held_by_a_quarter_ellipse():
    s = np.linspace(0, 0.5 * np.pi, 40)
    seam = _seam(1.0 - 0.3 * np.cos(s) ** 0.7, 0.25 * np.sin(s))
    boundary, _ = _boundaries_around_seam(_unit_square_surface(), seam)
    assert boundary[0, 1] == pytest.approx(0.0) and boundary[-1, 0] == pytest.approx(1.0)
    _check_holds_the_seam(boundary, seam["uv_a"][1:-1], np.array([[1.0, 0.0]]))


def test_seam_from_keel_to_keel_is_held_by_an_arc_over_it():
    s = np.linspace(0, np.pi, 40)
    seam = _seam(0.7 - 0.1 * np.cos(s), 0.2 * np.sin(s) ** 0.8)
    boundary, _ = _boundaries_around_seam(_unit_square_surface(), seam)
    assert boundary[0, 1] == pytest.approx(0.0) and boundary[-1, 1] == pytest.approx(0.0)
    assert boundary[-1, 0] < 1.0
    _check_holds_the_seam(boundary, seam["uv_a"][1:-1], np.empty((0, 2)))


def test_arc_over_the_keel_leaves_a_raked_edge_square_to_it():
    """On a patch whose v lines meet its v = 0 edge at 79 deg (a raked stem's sections
    meet it at 20-30 deg), the arc's fore end leaves that edge at 90 deg in metres: angles of
    its last chord on the patch, by numpy."""
    pts = np.array([[[0, 0, 0], [0.2, 0, 1]], [[1, 0, 0], [1.2, 0, 1]]], float)
    k = [0.0, 0.0, 1.0, 1.0]
    raked = fl.NurbsSurface(1, 1, k, k, pts)
    s = np.linspace(0, np.pi, 40)
    seam = _seam(0.7 - 0.1 * np.cos(s), 0.2 * np.sin(s) ** 0.8)
    boundary, _ = _boundaries_around_seam(raked, seam, points=201)
    end = np.asarray(raked.evaluate(boundary[-2:, 0], boundary[-2:, 1]))
    chord = end[0] - end[1]
    assert np.degrees(np.arccos(chord[0] / np.linalg.norm(chord))) == pytest.approx(90.0, abs=1.0)
    _check_holds_the_seam(boundary, seam["uv_a"][1:-1], np.empty((0, 2)))


def test_a_seam_running_up_the_stem_past_the_arcs_reach_is_no_blend_fits():
    """A blunt seam that stays high until just aft of its fore end would cross the arc, whose
    fore end is held to a share of the stem: refused, not a boundary through the seam."""
    u = np.concatenate([np.linspace(0.6, 0.65, 20), np.linspace(0.65, 0.88, 20), np.linspace(0.885, 0.9, 20)])
    v = np.concatenate([0.2 * np.sin(np.linspace(0, np.pi / 2, 20)), np.linspace(0.2, 0.17, 20),
                        np.linspace(0.16, 0.0, 20)])
    with pytest.raises(fl.NoBlendFits, match="the seam runs too far up the stem"):
        _boundaries_around_seam(_unit_square_surface(), _seam(u, v))


def test_a_boundary_that_would_reach_the_deck_is_no_blend_fits():
    s = np.linspace(0, np.pi, 40)
    seam = _seam(1.0 - 0.2 * np.sin(s), 0.5 - 0.15 * np.cos(s))
    with pytest.raises(fl.NoBlendFits, match="no blend fits between hull and bulb: .*keel and deck"):
        _boundaries_around_seam(_unit_square_surface(), seam, clearance_v=0.5)
    assert issubclass(fl.NoBlendFits, fl.InvalidInput)


@pytest.mark.parametrize("option, value, says", [
    ("points", 2, "points is 2; expected an integer >= 3"),
    ("clearance_u", -0.1, "clearance_u is -0.1"),
    ("tension", 0.0, "tension is 0"),
    ("clearance", 0.1, "option 'clearance' is unknown"),
    ("points", "many", "option points is 'many'"),
])
def test_a_bad_placement_option_is_refused_by_name(option, value, says):
    s = np.linspace(0, np.pi, 10)
    seam = _seam(1.0 - 0.2 * np.sin(s), 0.5 - 0.15 * np.cos(s))
    with pytest.raises(fl.InvalidInput, match=says):
        _boundaries_around_seam(_unit_square_surface(), seam, **{option: value})

