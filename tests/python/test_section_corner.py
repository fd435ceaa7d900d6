"""Sections with their bilge corner given (corner_y / corner_z; the description's corner_breadth
and corner_height curves) and hull ends that are vertical posts (ends.aft_post / fore_post)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import fairlines as fl

B2, T, D = 5.0, 6.25, 9.0
# The section spline (20 control points) follows its conic arc to this fraction of y_dwl.
ARC_TOL = 0.005


def _spec(corner=(1.0, 0.5), fullness=2 / 3):
    s = fl.SectionSpec()
    s.x, s.y_max, s.y_deck, s.z_deck, s.z_keel, s.draft, s.y_dwl = 50.0, B2, B2, D, 0.0, T, B2
    s.half_area = fullness * B2 * T
    s.corner_y, s.corner_z = corner
    return s


def _points(curve, n=400):
    kn = np.asarray(curve.knots)
    return np.asarray(curve.evaluate(np.linspace(kn[0], kn[-1], n)))


def test_corner_at_half_depth_with_a_parabolas_area_is_the_wigley_parabola():
    p = _points(fl.design_section(_spec()).curve)
    below = p[:, 2] < T
    exact = B2 * (1 - ((T - p[below, 2]) / T) ** 2)  # Wigley: y = (B/2)(1 - (zeta/T)^2)
    assert np.abs(p[below, 1] - exact).max() <= ARC_TOL * B2


def test_corner_inside_the_chord_makes_a_hollow_section_of_the_asked_area():
    s = _spec(corner=(0.3, 0.6), fullness=0.4)
    s.y_dwl = 0.6 * B2  # room above the waterline for the top to lean out
    s.half_area = 0.4 * s.y_dwl * T
    d = fl.design_section(s)
    assert d.area_met and d.fullness == pytest.approx(0.4, abs=1e-9)
    p = _points(d.curve)
    mid = np.argmin(np.abs(p[:, 2] - T / 2))
    assert p[mid, 1] < s.y_dwl * p[mid, 2] / T  # inside the chord K-Q: hollow


@pytest.mark.parametrize("field, value, message", [
    ("corner_y", 0.0, "corner_y is 0"), ("corner_y", 1.5, "corner_y is 1.5"), ("corner_z", 1.0, "corner_z is 1"),
    ("corner_z", math.nan, "expected both given or both NaN")])
def test_section_refuses_a_corner_out_of_range(field, value, message):
    s = _spec()
    setattr(s, field, value)
    with pytest.raises(fl.InvalidInput, match=message):
        fl.design_section(s)


def _wigley_description(**ends) -> dict:
    """A Wigley-like whole hull typed in: parabolic waterline, flat keel, wall-sided above T."""
    xs = np.linspace(0, 100, 21)
    half = [[float(x), float(B2 * (1 - (2 * (x - 50) / 100) ** 2))] for x in xs]
    return {
        "principal": {"Lpp": 100.0, "B": 2 * B2, "T": T, "D": D},
        "ends": {"aft": 0.0, "fore": 100.0, **ends},
        "basic_curves": {
            "profile": {"value": 0.0},
            "dwl": {"fit": half, "fit_weight": 1e3, "yB": 0.0, "yE": 0.0},
            "deck": {"fit": half, "fit_weight": 1e3, "yB": 0.0, "yE": 0.0},
            "sac": {"volume": 4 / 9 * 100 * 2 * B2 * T},
            "corner_breadth": {"value": 1.0},
            "corner_height": {"value": 0.5},
        },
    }


def test_post_ends_are_lines_on_the_centre_plane():
    hull = fl.Hull.from_json(_wigley_description(aft_post=True, fore_post=True))
    for end in (hull.sections[0], hull.sections[-1]):
        assert np.abs(_points(end)[:, 1]).max() <= 1e-9


def test_wigley_typed_as_curves_holds_the_exact_volume_and_sections():
    hull = fl.Hull.from_json(_wigley_description(aft_post=True, fore_post=True))
    assert hull.hydrostatics().volume == pytest.approx(4 / 9 * 100 * 2 * B2 * T, rel=5e-3)
    p = _points(hull.sections_at([50.0])[0])
    below = p[:, 2] < T
    assert np.abs(p[below, 1] - B2 * (1 - ((T - p[below, 2]) / T) ** 2)).max() <= 2 * ARC_TOL * B2


def test_corner_breadth_without_corner_height_is_refused_by_name():
    desc = _wigley_description()
    del desc["basic_curves"]["corner_height"]
    with pytest.raises(fl.InvalidInput, match="basic_curves.corner_height is missing"):
        fl.Hull.from_json(desc)


def test_a_post_flag_must_be_true_or_false():
    with pytest.raises(fl.InvalidInput, match="ends.aft_post is 'yes'; expected true or false"):
        fl.Hull.from_json(_wigley_description(aft_post="yes"))


def test_a_post_where_the_deck_is_wide_is_refused_when_built():
    desc = _wigley_description(fore_post=True)
    desc["basic_curves"]["deck"]["yE"] = 2.0
    with pytest.raises(fl.InvalidInput, match="ends.fore_post is true"):
        fl.Hull.from_json(desc).section_specs()
