"""Given (auxiliary) sections, a sheer and a largest breadth in the hull description: a given
shape is held at its station, follows edits of the basic curves, holds the SAC's area, and bad
shapes are refused naming the value. Truths: exact section shapes and their areas."""

from __future__ import annotations

import copy
import json
import math

import numpy as np
import pytest

import fairlines as fl

B2, T, D = 5.0, 6.25, 9.0
# A given shape of 32 control points follows a smooth exact shape to this fraction of B/2.
SHAPE_TOL = 2e-3


def _parabola_points(b=B2, n=60, power=2):
    """Wigley section y = b (1 - (zeta / T)^power) below T, wall-sided above: deck edge to keel."""
    top = [(b, z) for z in np.linspace(D, T, 8)[:-1]]
    zeta = np.linspace(0.0, T, n)
    below = [(b * (1 - (q / T) ** power), T - q) for q in zeta]
    return np.array(top + below)


def _spec(points, half_area=math.nan, y_dwl=B2, z_keel=0.0):
    s = fl.SectionSpec()
    s.x, s.y_max, s.y_deck, s.z_deck, s.z_keel, s.draft, s.y_dwl = 50.0, B2, B2, D, z_keel, T, y_dwl
    s.n_control, s.half_area, s.given = 32, half_area, points
    return s


def _curve_points(curve, n=2000):
    kn = np.asarray(curve.knots)
    return np.asarray(curve.evaluate(np.linspace(kn[0], kn[-1], n)))


def _half_breadth_at(p, z):
    order = np.argsort(p[:, 2])
    return np.interp(z, p[order, 2], p[order, 1])


def _area_below(p, draft):
    """Area between the section and the centre plane below `draft` (shoelace of the samples,
    from the section's own crossing of the waterline)."""
    i = int(np.flatnonzero(p[:, 2] <= draft)[0])
    r = (p[i - 1, 2] - draft) / (p[i - 1, 2] - p[i, 2])
    crossing = p[i - 1, 1:] + r * (p[i, 1:] - p[i - 1, 1:])
    q = np.vstack([[0.0, draft], crossing, p[i:, 1:], [0.0, p[-1, 2]]])
    y, z = q[:, 0], q[:, 1]
    return 0.5 * abs(np.dot(y, np.roll(z, -1)) - np.dot(z, np.roll(y, -1)))


def test_a_given_wigley_section_is_held_at_its_station():
    p = _curve_points(fl.design_section(_spec(_parabola_points())).curve)
    z = np.linspace(0.2, T, 40)
    exact = B2 * (1 - ((T - z) / T) ** 2)
    assert np.abs(_half_breadth_at(p, z) - exact).max() <= SHAPE_TOL * B2


def test_a_given_section_holds_the_asked_area():
    exact = 2 / 3 * B2 * T  # the parabola's area
    for factor in (0.9, 1.0, 1.1):
        d = fl.design_section(_spec(_parabola_points(), half_area=factor * exact))
        assert _area_below(_curve_points(d.curve, 20000), T) == pytest.approx(factor * exact, rel=1e-4)
        assert d.fullness == pytest.approx(factor * 2 / 3, rel=1e-9)


def test_a_given_section_follows_a_narrower_waterline_and_a_higher_keel():
    """Mapped onto the station's own waterline point and keel: half-breadths below T scale by
    the waterline's ratio, heights stretch between the keel and T."""
    s = _spec(_parabola_points(), y_dwl=0.6 * B2, z_keel=1.0)
    p = _curve_points(fl.design_section(s).curve)
    z = np.linspace(1.2, T, 40)
    exact = 0.6 * B2 * (1 - ((T - z) / (T - 1.0)) ** 2)
    assert np.abs(_half_breadth_at(p, z) - exact).max() <= SHAPE_TOL * B2


def test_a_bulb_under_a_narrow_stem_head_keeps_its_breadth():
    """A bow station with no waterline: a stem head 0.2 m wide over a web on the centre plane and
    a bulb of radius 2 m. A deck 10 % narrower than the head changes the bulb by the head's
    difference as a share of its widest (1 %), not by the deck's ratio (it was 0.9)."""
    t = np.linspace(0.0, np.pi, 60)
    head = [(0.2 * (1 - q), D - q * (D - 7.0)) for q in np.linspace(0.0, 1.0, 10)]
    web = [(0.0, z) for z in np.linspace(7.0, 5.0, 10)[1:]]
    bulb = [(2.0 * np.sin(a), 3.0 + 2.0 * np.cos(a)) for a in t[1:]]
    s = _spec(np.array(head + web + bulb), y_dwl=0.0, z_keel=1.0)
    s.y_deck = 0.18
    p = _curve_points(fl.design_section(s).curve)
    assert p[p[:, 2] < 5.0, 1].max() == pytest.approx(2.0 * (1 - 0.02 / 2.0), abs=0.02)


def test_a_station_between_two_given_sections_blends_them():
    """Mix 0 and 1 are the two shapes; between, the section lies between them (fairness
    skinning's blend of control points, exact for equal shapes)."""
    z = np.linspace(0.3, T - 0.3, 30)

    def at(mix, fore_power=3):
        s = _spec(_parabola_points())
        s.given_fore, s.given_mix = _parabola_points(power=fore_power), mix
        return _half_breadth_at(_curve_points(fl.design_section(s).curve), z)

    alone = {p: _half_breadth_at(_curve_points(fl.design_section(_spec(_parabola_points(power=p))).curve), z) for p in (2, 3)}
    assert np.array_equal(at(0.0), alone[2])
    assert np.abs(at(1.0) - alone[3]).max() <= 1e-12 * B2
    assert np.abs(at(0.5, fore_power=2) - alone[2]).max() <= 1e-12 * B2
    mid = at(0.5)
    assert np.all(mid >= alone[2] - 1e-9) and np.all(mid <= alone[3] + 1e-9)
    assert np.abs(mid - 0.5 * (alone[2] + alone[3])).max() <= 0.05 * B2


@pytest.mark.parametrize("points, message", [
    ([[1.0, 0.0], [2.0, 5.0], [0.0, 9.0]], "expected the deck edge first"),
    ([[1.0, 9.0], [-2.0, 5.0], [0.0, 0.0]], "expected y >= 0"),
    ([[1.0, 9.0], [math.nan, 5.0], [0.0, 0.0]], "not finite"),
    ([[1.0, 9.0], [0.0, 0.0]], "m >= 3")])
def test_a_bad_given_shape_is_refused_naming_it(points, message):
    with pytest.raises(fl.InvalidInput, match=message):
        fl.design_section(_spec(np.array(points)))


def _wigley_hull(**extra) -> dict:
    """A Wigley-like whole hull typed in with every station's section given."""
    L = 100.0
    xs = np.linspace(0.0, L, 21)
    d = {"name": "given wigley", "principal": {"Lpp": L, "B": 2 * B2, "T": T, "D": D},
         "ends": {"aft_post": True, "fore_post": True},
         "stations": {"x": xs.tolist()},
         "sections": {"n_control": 24, "given": [{"x": float(x), "points": _parabola_points().tolist()} for x in xs[1:-1]]},
         "basic_curves": {"profile": {"value": 0.0},
                          "dwl": {"yB": 0.0, "yE": 0.0, "points": [[L / 2, B2]], "spans": 16},
                          "deck": {"yB": 0.0, "yE": 0.0, "points": [[L / 2, B2]], "spans": 16},
                          "sac": {"volume": 4 / 9 * L * 2 * B2 * T, "spans": 16}}}
    d.update(extra)
    return d


def test_a_hull_of_given_sections_round_trips_through_json():
    h = fl.Hull.from_json(_wigley_hull())
    again = fl.Hull.from_json(h.to_json())
    a, b = (np.asarray(x.bare_hull_surface().control_points) for x in (h, again))
    assert np.array_equal(a, b)
    assert json.loads(h.to_json())["sections"]["given"][0]["points"][0] == [B2, D]


def test_a_hull_of_given_sections_holds_the_sac_volume():
    h = fl.Hull.from_json(_wigley_hull())
    assert h.hydrostatics().volume == pytest.approx(4 / 9 * 100.0 * 2 * B2 * T, rel=2e-3)


def test_a_sheer_lifts_the_deck_edge():
    d = _wigley_hull()
    d["basic_curves"]["sheer"] = {"yB": D + 1.0, "yE": D + 2.0, "points": [[50.0, D]], "spans": 12}
    h = fl.Hull.from_json(d)
    sheer = h.basic_curves["sheer"]
    for x in (10.0, 50.0, 90.0):
        top = _curve_points(h.sections_at(x)[0])[0]
        assert top[2] == pytest.approx(float(sheer(x)[0]), abs=1e-9)
    assert float(sheer(100.0)[0]) == pytest.approx(D + 2.0)


def test_a_largest_breadth_lets_the_deck_flare_beyond_b():
    d = _wigley_hull()
    d["principal"]["B_max"] = 2 * B2 + 1.0
    d["basic_curves"]["deck"] = {"yB": 0.0, "yE": 0.0, "points": [[50.0, B2 + 0.5]], "spans": 16}
    d["sections"]["given"] = [{"x": g["x"], "points": [[B2 + 0.5, D]] + g["points"][1:]} for g in d["sections"]["given"]]
    s = fl.Hull.from_json(d).bare_hull_surface()
    y = np.asarray(s.evaluate_grid(np.linspace(0, 1, 41), np.linspace(0, 1, 101)))[..., 1]
    assert y.max() == pytest.approx(B2 + 0.5, abs=1e-3 * B2)  # the deck edge at midships, beyond B/2


@pytest.mark.parametrize("edit, message", [
    (("principal", "B_max", 9.0), "B_max is 9.0; expected the largest breadth"),
    (("sections", "given", [{"x": 10.0, "points": [[1.0, 0.0], [2.0, 5.0], [0.0, 9.0]]}]), "expected the deck edge first"),
    (("sections", "given", [{"x": 60.0, "points": [[1.0, 9.0], [2.0, 5.0], [0.0, 0.0]]},
                            {"x": 50.0, "points": [[1.0, 9.0], [2.0, 5.0], [0.0, 0.0]]}]), "expected increasing x"),
    (("sections", "given", [{"x": 150.0, "points": [[1.0, 9.0], [2.0, 5.0], [0.0, 0.0]]}]), "expected a station on the hull")])
def test_the_loader_refuses_what_the_schema_cannot_state(edit, message):
    d = _wigley_hull()
    d[edit[0]][edit[1]] = edit[2]
    with pytest.raises(fl.InvalidInput, match=message):
        fl.Hull.from_json(d)


def _wigley_with_measured_areas(volume_factor=1.0) -> dict:
    """The given Wigley hull with the SAC fitted to its sections' exact areas (a parabola in x:
    2 * 2/3 * b(x) * T with b the waterline's parabola) and its volume scaled by volume_factor."""
    d = _wigley_hull()
    L = d["principal"]["Lpp"]
    xs = np.linspace(0.0, L, 41)
    area = 2 * (2 / 3) * B2 * (1 - (2 * xs / L - 1) ** 2) * T
    d["basic_curves"]["sac"] = {"volume": volume_factor * 4 / 9 * L * 2 * B2 * T, "lcb": L / 2, "spans": 16,
                                "fit": [[float(x), float(a)] for x, a in zip(xs, area)]}
    return d


def test_the_sac_of_given_sections_is_designed_as_area_through_their_measured_areas():
    h = fl.Hull.from_json(_wigley_with_measured_areas())
    sac = h.basic_curves["sac"]
    L = h.description.principal.lpp
    xs = np.linspace(5.0, 95.0, 19)
    exact = 2 * (2 / 3) * B2 * (1 - (2 * xs / L - 1) ** 2) * T
    assert np.abs(sac(xs) - exact).max() <= 1e-3 * exact.max()
    assert h.basic_curves["fullness"] is None  # no fullness: a given section holds its own shape


def test_a_volume_change_scales_the_given_sections_areas_in_proportion():
    """+2 % volume at the same LCB: every area +2 % (the factor's fairest form: a constant), the
    sections at the waterline's ends, with next to no area, next to unchanged."""
    base = fl.Hull.from_json(_wigley_with_measured_areas())
    more = fl.Hull.from_json(_wigley_with_measured_areas(1.02))
    xs = np.linspace(2.0, 98.0, 25)
    ratio = more.basic_curves["sac"](xs) / base.basic_curves["sac"](xs)
    assert np.allclose(ratio, 1.02, atol=1e-6)
    assert more.hydrostatics().volume == pytest.approx(1.02 * base.hydrostatics().volume, rel=2e-3)


def test_a_fullness_fit_with_given_sections_is_refused_naming_it():
    d = _wigley_hull()
    d["basic_curves"]["sac"]["fullness_fit"] = [[50.0, 0.6]]
    with pytest.raises(fl.InvalidInput, match="fullness_fit is given, but a SAC of given sections is designed as area"):
        fl.Hull.from_json(d).basic_curves


def _with_offsets(offsets: dict, at: float = 50.0) -> dict:
    d = _wigley_hull()
    next(g for g in d["sections"]["given"] if g["x"] == at)["offsets"] = offsets
    return d


def test_given_offsets_put_the_deck_edge_waterline_and_keel_points_off_the_curves():
    """Offsets move the points a given shape is mapped onto: at their station by their whole
    value (the curves give (B/2, D), B/2 at T and z 0 there), at the next given station (5 m
    away, no offsets) not at all, and half way between by half."""
    off = {"deck": [-0.3, -0.5], "waterline": -0.2, "keel": 0.4}
    h, plain = fl.Hull.from_json(_with_offsets(off)), fl.Hull.from_json(_wigley_hull())
    p = _curve_points(h.sections_at(50.0)[0])
    assert p[0, 1:] == pytest.approx([B2 - 0.3, D - 0.5], abs=1e-9)
    assert p[-1, 1:] == pytest.approx([0.0, 0.4], abs=1e-9)
    assert _half_breadth_at(p, T) == pytest.approx(B2 - 0.2, abs=1e-6)

    def deck_edge(hull, x):
        return _curve_points(hull.sections_at(x)[0])[0, 1:]

    assert np.array_equal(deck_edge(h, 55.0), deck_edge(plain, 55.0))
    assert deck_edge(h, 52.5) == pytest.approx(deck_edge(plain, 52.5) + [-0.15, -0.25], abs=1e-9)


def test_given_offsets_round_trip_through_json():
    h = fl.Hull.from_json(_with_offsets({"waterline": -0.2}))
    again = json.loads(h.to_json())
    assert next(g for g in again["sections"]["given"] if g["x"] == 50.0)["offsets"] == {
        "deck": [0.0, 0.0], "waterline": -0.2, "keel": 0.0}
    a, b = (np.asarray(x.bare_hull_surface().control_points) for x in (h, fl.Hull.from_json(again)))
    assert np.array_equal(a, b)


@pytest.mark.parametrize("offsets, message", [
    ({"deck": [0.1]}, r"sections\.given\[9\]\.offsets\.deck is .*; expected a pair \[dy, dz\]"),
    ({"waterline": "0.1"}, r"sections\.given\[9\]\.offsets\.waterline"),
    ({"keal": 0.1}, "did you mean 'keel'"),
    ({"keel": math.inf}, r"sections\.given\[9\]\.offsets\.keel")])
def test_bad_given_offsets_are_refused_naming_them(offsets, message):
    with pytest.raises(fl.InvalidInput, match=message):
        fl.Hull.from_json(_with_offsets(offsets))


def test_a_given_flat_of_bottom_stays_exactly_flat():
    """A box section with a flat of bottom 2 m wide and a round bilge of radius 3 m: the fitted
    spline lies exactly on the flat where every control point it rests on lies on it (those whose
    support is on the flat held at the keel's height). Fitted freely it sat off the flat by the
    fit's residuals, and a skin, which holds a row only where its height repeats exactly along the
    hull, rippled the flat."""
    a = np.linspace(0.0, np.pi / 2, 40)
    wall = [(B2, z) for z in np.linspace(D, 3.0, 12)[:-1]]
    bilge = [(2.0 + 3.0 * np.cos(t), 3.0 - 3.0 * np.sin(t)) for t in a]
    flat = [(y, 0.0) for y in np.linspace(2.0, 0.0, 12)[1:]]
    p = _curve_points(fl.design_section(_spec(np.array(wall + bilge + flat))).curve, 4000)
    on_flat = p[:, 1] < 0.4  # the last knot span: every control point it rests on lies on the flat
    assert on_flat.sum() > 50
    assert np.abs(p[on_flat, 2]).max() <= 1e-12
    assert p[:, 2].min() >= -1e-3 * T  # nor under it beside the flat
