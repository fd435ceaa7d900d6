"""Real ships come back as whole-ship designs: offsets in mm, the four reference ships import,
and the rebuilt hulls are judged against the data's points and published particulars."""

from __future__ import annotations

import copy
import functools
import json

import numpy as np
import pytest

import fairlines as fl
from fairlines.offsets import read_offsets_csv

from import_fixtures import (ROOT, SHIPS, WIGLEY, data_volume, data_wetted_surface, imported, read, rebuilt, truth,
                             wigley_table_csv)

# Fidelity goals (fractions): distance to the data's points on B, volume, LCB on Lpp, wetted surface.
RMS_GOAL, MAX_GOAL, VOLUME_GOAL, LCB_GOAL, WETTED_GOAL = 0.005, 0.02, 0.005, 0.001, 0.01

# Measured shortfalls (the section family cannot hold these ships yet; docs/import.md says why).
SHORT = {
    ("volume", "dtmb5415"): "-0.60 %: the data's own grids at T hold 0.5504 m^3, -0.65 % from the published 0.554 m^3 "
                            "(flat facets cut the hull by chords, about 0.1 % on these 21 x 21 grids); the rebuilt hull is "
                            "+0.05 % over them (test_rebuilt_hull_volume_meets_the_datas_own), and -0.28 % from the "
                            "volume of its published Cb 0.507, which the published 0.554 m^3 exceeds by 0.3 % "
                            "(test_rebuilt_dtmb5415_volume_meets_its_published_block_coefficient). Its -0.49 % before had "
                            "been a quadrature that clipped the hull's rows at the waterline, not its sections",
    ("wetted", "kcs"): "+1.83 %: the data's own grids at T measure 9 546 m^2, +1.30 % over the published figure (its "
                       "source does not say what else it leaves out); the rebuilt hull is +0.52 % over them: the closed "
                       "propeller boss end (x 4-6 m) and, on the centre plane, webs (12 m^2 at the boss end, x 4.6-11.5 m, 7 m^2 "
                       "above the bulb). The skin's fold across the centre plane at the boss end is gone since the skin "
                       "keeps y >= 0 (SkinOptions.y_nonnegative: 9 601 -> 9 596 m^2)",
}


def _goal(kind: str, ship: str):
    reason = SHORT.get((kind, ship))
    return pytest.param(ship, marks=pytest.mark.xfail(strict=True, reason=reason)) if reason else ship


def test_offsets_in_mm_read_as_metres_with_blank_cells_noted():
    data = read_offsets_csv(ROOT / "tests" / "data" / "wigley_offsets_mm.csv", **WIGLEY)
    L, B, T = WIGLEY.values()
    mid = next(s for s in data.sections if s.x == 50.0)
    i = np.argmin(np.abs(mid.points[:, 1] - T))
    assert mid.points[i, 0] == pytest.approx(B / 2, abs=1e-3)  # exact Wigley value, rounded to 1 mm
    assert sum("blank cell" in n for n in data.notes) == 3


@pytest.mark.parametrize("ship", SHIPS)
def test_imported_description_rebuilds_from_json(ship):
    desc = imported(ship)
    hull = fl.Hull.from_json(json.dumps(desc))
    assert hull.bare_hull_surface() is not None
    assert desc["principal"]["Lpp"] == pytest.approx(truth(ship)["lpp"])


def test_kcs_bulb_is_held_by_the_given_sections_and_named_in_the_notes():
    desc = imported("kcs")
    assert "bulb" not in desc and desc["sections"].get("given")  # no composed bulb: the sections hold it
    assert "the bulb held by the sections (Kracht coefficients c_lpr 0.03" in desc["notes"]
    assert desc["ends"]["fore"] == pytest.approx(237.0, abs=0.01)  # the bulb's nose, 7 m forward of the FP


@pytest.mark.xfail(strict=True, reason="a web of zero half-breadth on the centre plane runs from the bulb's top to the "
                                       "deck out to the bulb's nose (x 237 m, the data's stem 230.0-232.0 m at these "
                                       "heights): each x = const section between the bulb's neck (229.5 m) and the stem "
                                       "head (232.6 m) meets hull twice and joins the two on the centre plane, so even "
                                       "sections ending at the bulb's top forward of the stem head leave it at 232.6 m")
def test_rebuilt_kcs_stem_above_the_bulb_is_the_datas():
    """Above the bulb the hull ends where the data's raked stem does (within 0.5 m), at the DWL,
    2 m above it and 1 m below the deck."""
    from fairlines.import_design import data_points

    data, desc = read("kcs"), imported("kcs")
    surface = fl.Hull.from_json(json.dumps(desc)).bare_hull_surface()
    pr = desc["principal"]
    pts = data_points(data, pr["D"])
    for z in (pr["T"], pr["T"] + 2.0, pr["D"] - 1.0):
        stem = pts[np.abs(pts[:, 2] - z) < 0.25, 0].max()
        hull_end = np.asarray(fl.plane_cut(surface, 2, z, 601).points)[:, 0].max()
        assert abs(hull_end - stem) <= 0.5, (z, hull_end, stem)


@functools.cache
def _rebuilt_points(ship: str) -> np.ndarray:
    """(n, 3) points of the rebuilt bare hull, a 300 x 600 grid over its parameters (shared by the
    tests below; callers must not edit it)."""
    s = fl.Hull.from_json(json.dumps(imported(ship))).bare_hull_surface()
    return np.asarray(s.evaluate_grid(np.linspace(*s.domain_u, 300), np.linspace(*s.domain_v, 600))).reshape(-1, 3)


@pytest.mark.parametrize("ship", SHIPS)
def test_rebuilt_hull_lies_nowhere_further_below_the_data_than_the_largest_distance_goal(ship):
    """No point of the rebuilt bare hull lies further below the data's lowest point than the
    largest distance the rebuilt hull may have from a data point (MAX_GOAL of B). Series 60's
    skin, through its last two stations alone, swung 0.51 m (3.1 % of B) under the base
    ahead of its forefoot, where the data's keel is flat (0.11 m with stations picked up there);
    0.23 m (1.4 % of B) ahead of its stern's deadwood."""
    from fairlines.import_design import data_points

    desc, g = imported(ship), _rebuilt_points(ship)
    low = data_points(read(ship), desc["principal"]["D"])[:, 2].min()
    assert low - g[:, 2].min() <= MAX_GOAL * desc["principal"]["B"]


FOLDS = {
    "dtmb5415": "the skin folds 4.6 mm across the centre plane in the recess between the dome's nose and the stem "
                "(x 5.69-5.73 m, z 0.01-0.23 m; docs/import.md): kept at y >= 0 its rows would miss the web on the "
                "centre plane there by up to 16 mm (2 % of B), so the skin is left as it was (skinning.hpp "
                "kCentrePlaneMaxMiss; the notes say so)",
}


@pytest.mark.parametrize("ship", [pytest.param(s, marks=pytest.mark.xfail(strict=True, reason=FOLDS[s])) if s in FOLDS
                                  else s for s in SHIPS])
def test_rebuilt_hull_stays_on_its_side_of_the_centre_plane(ship):
    """The bare hull is the half y >= 0: no point of it lies more than 1e-4 B across the centre
    plane (a fold there makes the mirrored hull cut itself). Stations picked up over Series 60's
    stern would have thinned its deadwood into a fin the skin folded 1.4 cm across."""
    assert _rebuilt_points(ship)[:, 1].min() >= -1e-4 * imported(ship)["principal"]["B"]


def test_kcs_propeller_boss_end_is_a_station_and_the_hull_follows_the_data_there():
    """KCS's centre-plane contour has a tail at x 4.75 m (the propeller boss's end under the
    counter, where the afterbody grid ends and only the counter goes on aft): a station is put
    there (import_design._contour_tails). The data's points aft of 8 m below 8 m lie within 1 % of
    B of the rebuilt hull (1.36 % with the cosine stations alone, at 4.18 and 5.16 m)."""
    from fairlines.import_design import data_points, point_deviation

    data, desc = read("kcs"), imported("kcs")
    assert any(abs(sec["x"] - 4.7495) < 1e-3 for sec in desc["sections"]["given"])
    pts = data_points(data, desc["principal"]["D"])
    near = pts[(pts[:, 0] < 8.0) & (pts[:, 2] < 8.0)]
    surface = fl.Hull.from_json(json.dumps(desc)).bare_hull_surface()
    assert point_deviation([surface], near).max() <= 0.01 * desc["principal"]["B"]


def test_the_skin_kept_off_the_centre_plane_or_not_is_said_in_the_notes():
    """Where the skin leaves the given sections to stay at y >= 0 (KCS's boss end) the notes say
    so and by how much; where that would move them too far (DTMB 5415's recess: 16 mm) they say
    the skin crosses the plane; a ship whose skin never needed it (Series 60) says neither."""
    import re

    said = re.search(r"the skin kept at y >= 0 in (\d+) rows of its control net, off the given sections by up to "
                     r"([0-9.]+) mm", imported("kcs")["notes"])
    assert said and int(said[1]) > 0 and 0 < float(said[2]) <= 10.0
    left = re.search(r"the skin crosses the centre plane: keeping it at y >= 0 would move the given sections by "
                     r"up to ([0-9.]+) mm", imported("dtmb5415")["notes"])
    assert left and float(left[1]) > 0
    assert "centre plane" not in imported("series60")["notes"]


def test_the_stations_picked_up_at_series60s_forefoot_are_named_in_the_notes():
    """Stations the data does not have are said, with where they are (not silently invented)."""
    assert "3 stations (x 119.6, 120.4, 121.2 m) picked up along the waterlines" in imported("series60")["notes"]


def test_rebuilt_series60_waterlines_run_into_the_stem_without_a_hook():
    """Below T each waterline of the rebuilt Series 60 ends on its forefoot without a hollow
    turn of more than 5 deg in its last metre. The table has no station between 19.5 and the FP
    (where the hull starts at T); skinned through those two alone the waterlines curled into the
    centre plane (hollow turns of 18-209 deg there); stations picked up along the waterlines
    between them (import_design._end_span_sections) leave 0.2-3.7 deg."""
    from fairlines.fairness import judge_cut

    desc = imported("series60")
    s = fl.Hull.from_json(json.dumps(desc)).bare_hull_surface()
    T = desc["principal"]["T"]
    for z in np.linspace(0.1, 0.95, 9) * T:
        cut = fl.plane_cut(s, 2, float(z), 801)
        end = np.asarray(cut.points)[:, 0].max()
        hooks = [lb["turn_deg"] for lb in judge_cut(cut)["lobes"] if lb["sign"] > 0 and end - lb["at"][0] < 1.0]
        assert max(hooks, default=0.0) <= 5.0, (z, hooks)


@pytest.mark.parametrize("ship", [_goal("rms", s) for s in SHIPS])
def test_rebuilt_hull_rms_distance_to_the_data(ship):
    assert rebuilt(ship)["rms_of_B"] <= RMS_GOAL


@pytest.mark.parametrize("ship", [_goal("max", s) for s in SHIPS])
def test_rebuilt_hull_largest_distance_to_the_data(ship):
    assert rebuilt(ship)["max_of_B"] <= MAX_GOAL


@pytest.mark.parametrize("ship", [_goal("volume", s) for s in SHIPS])
def test_rebuilt_hull_volume_meets_the_published_one(ship):
    t = truth(ship)
    assert abs(rebuilt(ship)["volume"] / t["volume"] - 1) <= VOLUME_GOAL


def test_rebuilt_dtmb5415_volume_meets_its_published_block_coefficient():
    """DTMB 5415's published particulars disagree with each other by 0.3 %: Cb 0.507 at its
    Lpp 5.719, B 0.768 and T 0.248 m is 0.5523 m^3, its published volume 0.554 m^3 (Cb 0.5086).
    Against the first the rebuilt hull meets the volume goal (-0.28 %), against the second not
    (-0.60 %, the strict xfail above); its own grids hold 0.5504 m^3 (Cb 0.5052)."""
    t = truth("dtmb5415")
    published = 0.507 * t["lpp"] * t["beam"] * 0.248
    assert abs(rebuilt("dtmb5415")["volume"] / published - 1) <= VOLUME_GOAL


@pytest.mark.parametrize("ship", [_goal("lcb", s) for s in SHIPS])
def test_rebuilt_hull_lcb_meets_the_published_one(ship):
    t = truth(ship)
    assert abs(rebuilt(ship)["lcb"] - t["lcb"]) / t["lpp"] <= LCB_GOAL


@pytest.mark.parametrize("ship", [_goal("wetted", s) for s in SHIPS if truth(s)["wetted_surface"]])
def test_rebuilt_hull_wetted_surface_meets_the_published_one(ship):
    t = truth(ship)
    assert abs(rebuilt(ship)["wetted_surface"] / t["wetted_surface"] - 1) <= WETTED_GOAL


@pytest.mark.parametrize("ship", ["kcs", "dtmb5415"])
def test_rebuilt_hull_wetted_surface_meets_the_datas_own(ship):
    """Like with like: the rebuilt hull's wetted surface at T against the data's own grids'
    (triangulated, clipped at T). KCS's grids measure 9 546 m^2, 1.3 % over the published
    9 424 m^2, so a rebuild true to them cannot meet the published figure within 1 %."""
    assert abs(rebuilt(ship)["wetted_surface"] / data_wetted_surface(read(ship)) - 1) <= WETTED_GOAL


@pytest.mark.parametrize("ship", ["kcs", "dtmb5415"])
def test_rebuilt_hull_volume_meets_the_datas_own(ship):
    """Like with like: the rebuilt hull's volume at T against the data's own grids' (the flux of
    y through their triangles clipped at T). DTMB 5415's grids hold 0.5504 m^3, 0.65 % under the
    published 0.554 m^3, so a rebuild true to them cannot meet it within 0.5 %."""
    assert abs(rebuilt(ship)["volume"] / data_volume(read(ship)) - 1) <= VOLUME_GOAL


def test_measured_volume_of_the_typed_wigley_table_is_the_exact_one():
    m = fl.measure_hull_data(read("wigley_table"))
    assert m.volume == pytest.approx(truth("wigley_table")["volume"], rel=1e-3)
    assert m.lcb == pytest.approx(WIGLEY["lpp"] / 2, abs=1e-4 * WIGLEY["lpp"])


def test_import_refuses_data_without_hull_below_the_draft(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("x,1.0,2.0\n0,0,0\n5,0,1\n10,0,0\n")
    with pytest.raises(fl.InvalidInput, match="below T"):
        fl.import_design(read_offsets_csv(p, 10.0, 2.0, 0.5))


def test_import_refuses_fewer_stations_than_a_description_needs(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("x,0.0,1.0,2.0\n0,0,0.5,0.5\n5,0,1,1\n10,0,0.5,0.5\n")
    with pytest.raises(fl.InvalidInput, match=r"3 station\(s\) with hull below the deck; expected at least 4"):
        fl.import_design(read_offsets_csv(p, 10.0, 2.0, 0.5))


def test_cli_import_writes_a_description_hull_from_json_builds(tmp_path, capsys):
    from fairlines.cli import main

    out = tmp_path / "design.json"
    table = ROOT / "tests" / "data" / "wigley_offsets_mm.csv"
    assert main(["import", str(table), "--lpp", "100", "--beam", "10", "--draft", "6.25", "-o", str(out)]) == 0
    hull = fl.Hull.from_json(str(out))
    assert hull.hydrostatics().volume == pytest.approx(truth("wigley_table")["volume"], rel=VOLUME_GOAL)
    assert "whole-ship description" in capsys.readouterr().out


@pytest.mark.parametrize("kwargs, message", [({"depth": 1.0}, "depth is 1.0"), ({"depth": float("nan")}, "depth is nan")])
def test_import_refuses_a_depth_not_above_the_draft(kwargs, message):
    with pytest.raises(fl.InvalidInput, match=message):
        fl.import_design(read("wigley_table"), **kwargs)


def test_import_refuses_what_is_not_hull_data():
    with pytest.raises(fl.InvalidInput, match="expected fairlines.offsets.HullData"):
        fl.import_design({"name": "x"})


@pytest.mark.parametrize("ship, posts", [("wigley_table", {"aft_post": True, "fore_post": True}), ("series60", {})])
def test_end_posts_of_zero_width_are_read_only_where_the_data_has_them(ship, posts):
    ends = imported(ship)["ends"]
    assert {k: v for k, v in ends.items() if k.endswith("_post")} == posts


def test_imported_wigley_sections_have_the_parabolas_bilge_corner():
    curves = imported("wigley_table")["basic_curves"]
    # y = b (1 - (zeta / T)^2): the tangents at the waterline and the keel meet at (b, T / 2)
    assert np.allclose([v for _, v in curves["corner_breadth"]["fit"]], 1.0, atol=0.02)
    assert np.allclose([v for _, v in curves["corner_height"]["fit"]], 0.5, atol=0.02)


class _Part:
    """The part of a plane cut inside [x_lo, x_hi] (what judge_cut reads)."""

    def __init__(self, cut, lo, hi):
        p = np.asarray(cut.points)
        keep = (p[:, 0] >= lo) & (p[:, 0] <= hi)
        self.points, self.curvature = p[keep], np.asarray(cut.curvature)[keep]
        self.value, self.bending_energy = cut.value, 0.0


def _sign_changes(surface, axis, value, lo, hi):
    from fairlines.fairness import judge_cut

    part = _Part(fl.plane_cut(surface, axis, float(value), 801), lo, hi)
    return judge_cut(part)["sign_changes"] if len(part.points) >= 3 else 0


#: Measured shortfalls of the fairness comparison below (rebuilt vs a refit of the data's grid).
REFIT_SHORT = {
    ("dtmb5415", "main"): "the waterlines at z 0.07 and 0.14 m turn 7 and 3 times against 2 and 0 for the refit (3-7 "
                "on the waterlines at 0.07-0.21 m and the buttocks at 0.28-0.35 m before the measured shapes were "
                "smoothed, import_design.MEASURED_SHAPE_SMOOTHING), most of it toward the bow grid's joint (x 3.9-4.8 m; lobes of 0.2-2.2 deg: the lower "
                "waterlines hollow toward the dome's forefoot, where the refit's do not); round the transom (x < 1 m) every cut is "
                "within the refit's + 2 (test_rebuilt_dtmb5415_cuts_round_its_transom_are_as_fair_as_a_refit). Before "
                "the skin was ruled aft of the grid's first square row, 3-8 there on the waterlines and 8-9 on the "
                "buttocks; before the stations were the grid's own sections, 9-37 on the waterlines and 23-36 on the "
                "buttocks (stations cut from the chords between the sections, which kink at each)",
    ("kcs", "afterbody"): "the given sections round the propeller boss and the skeg (x 5-14 m): sign changes against "
                          "the refit's, over its + 2 on the waterlines at z 5.63 m (13 against 10), 9.38 m (7 against 4) "
                          "and 13.13 m (4 against 0) and the buttocks at y 2.68 m (4 against 1; 7 before a station lay at "
                          "the boss end's tip) and 8.05 m (9 against 4); the 3.75 m waterline 11 against 9 (12 before the "
                          "measured shapes were smoothed)",
}


@pytest.mark.parametrize("ship, grid", [
    pytest.param(s, g, marks=pytest.mark.xfail(strict=True, reason=REFIT_SHORT[s, g]) if (s, g) in REFIT_SHORT else ())
    for s, g in (("dtmb5415", "main"), ("kcs", "forebody"), ("kcs", "afterbody"))])
def test_rebuilt_hull_is_as_fair_as_a_refit_of_its_data(ship, grid):
    """Over a data grid's extent, each waterline and buttock of the rebuilt hull has no more
    curvature sign changes (lobes over 0.1 deg) than the same cut of the bicubic interpolant
    of the grid's own points (fl.fit_surface), two allowed for the rebuilt hull's ends."""
    data = read(ship)
    g = next(gr for gr in data.grids if gr.name.startswith(grid)).points
    refit = fl.fit_surface(g, degree_u=3, degree_v=3).surface
    hull = fl.Hull.from_json(json.dumps(imported(ship))).bare_hull_surface()
    lo, hi = g[..., 0].min(), g[..., 0].max()
    cuts = [(2, z) for z in np.linspace(max(g[..., 2].min(), 0.0), g[..., 2].max(), 9)[1:-1]]
    cuts += [(1, y) for y in np.linspace(0.0, g[..., 1].max(), 7)[1:-1]]
    for axis, v in cuts:
        assert _sign_changes(hull, axis, v, lo, hi) <= _sign_changes(refit, axis, v, lo, hi) + 2, (axis, v)


def test_rebuilt_dtmb5415_waterlines_forward_of_its_transom_are_as_fair_as_a_refit():
    """DTMB 5415's main grid is 21 sections; the given stations over it are those sections
    (import_design._section_rows), not stations cut between them from the grid's chords, which
    kink at every section: the skin through those rang, 9-21 sign changes on these waterlines
    against 0-1 for the refit. Forward of x = 1 m (past the transom, the xfail above) each
    waterline from z 0.21 m up has no more than the refit's + 2."""
    data = read("dtmb5415")
    g = next(gr for gr in data.grids if gr.name.startswith("main")).points
    refit = fl.fit_surface(g, degree_u=3, degree_v=3).surface
    hull = fl.Hull.from_json(json.dumps(imported("dtmb5415"))).bare_hull_surface()
    hi = g[..., 0].max()
    for z in np.linspace(max(g[..., 2].min(), 0.0), g[..., 2].max(), 9)[3:-1]:
        assert _sign_changes(hull, 2, z, 1.0, hi) <= _sign_changes(refit, 2, z, 1.0, hi) + 2, z


def test_rebuilt_dtmb5415_cuts_round_its_transom_are_as_fair_as_a_refit():
    """Round DTMB 5415's transom (aft of x = 1 m) each waterline and buttock of the rebuilt hull
    has no more curvature sign changes than the refit's + 2. The stations there are cut from
    the transom face and the grid's chords from its raked edge to its first square row; a C2
    skin through them rang round the knuckle (waterlines 3-8 and buttocks 8-9 against 0-2,
    lobes of 94, 21, 7, 2.2, 1.3, 0.4 deg); ruled there (skinning.ruled_aft_of), it cannot."""
    data = read("dtmb5415")
    g = next(gr for gr in data.grids if gr.name.startswith("main")).points
    refit = fl.fit_surface(g, degree_u=3, degree_v=3).surface
    desc = imported("dtmb5415")
    assert desc["skinning"]["ruled_aft_of"] == pytest.approx(0.228, abs=1e-3)  # the main grid's second row
    hull = fl.Hull.from_json(json.dumps(desc)).bare_hull_surface()
    lo = g[..., 0].min()
    cuts = [(2, z) for z in np.linspace(max(g[..., 2].min(), 0.0), g[..., 2].max(), 9)[1:-1]]
    cuts += [(1, y) for y in np.linspace(0.0, g[..., 1].max(), 7)[1:-1]]
    for axis, v in cuts:
        assert _sign_changes(hull, axis, v, lo, 1.0) <= _sign_changes(refit, axis, v, lo, 1.0) + 2, (axis, v)


def test_kcs_forebody_waterlines_through_the_bulb_are_as_fair_as_a_refit():
    """The forebody's waterlines up to the bulb's top (z 1.9-7.5 m), each no more sign changes
    than the refit's + 2: the given sections keep their measured deck edge, waterline and keel
    points (sections.given[i].offsets), where mapped onto the fair basic curves, which pass
    up to 5 cm off them alternately near the stem, they rang (8-10 sign changes against 1-2)."""
    data = read("kcs")
    g = next(gr for gr in data.grids if gr.name.startswith("forebody")).points
    refit = fl.fit_surface(g, degree_u=3, degree_v=3).surface
    hull = fl.Hull.from_json(json.dumps(imported("kcs"))).bare_hull_surface()
    lo, hi = g[..., 0].min(), g[..., 0].max()
    for z in np.linspace(0.0, g[..., 2].max(), 9)[1:5]:
        assert _sign_changes(hull, 2, z, lo, hi) <= _sign_changes(refit, 2, z, lo, hi) + 2, z


@pytest.mark.parametrize("ship", ["kcs", "dtmb5415"])
def test_rebuilt_stations_keep_the_measured_deck_edge_and_keel(ship):
    """At every given station the designed section starts at the measured shape's deck edge and
    ends at its keel point (but at the profile's breaks, where the keel is the profile's)."""
    desc = imported(ship)
    hull = fl.Hull.from_json(json.dumps(desc))
    breaks = desc["basic_curves"]["profile"].get("breaks", [])
    designed = dict(zip(np.round(hull.stations(), 9), hull.section_designs))
    for g in desc["sections"]["given"]:
        p = np.asarray(designed[round(g["x"], 9)].curve.control_points)
        shape = np.asarray(g["points"])
        assert p[0, 1:] == pytest.approx(shape[0], abs=1e-9), g["x"]
        if not any(abs(b - g["x"]) < 1e-9 for b in breaks):
            assert p[-1, 2] == pytest.approx(shape[-1, 1], abs=1e-9), g["x"]


def test_an_edit_of_the_imported_kcs_waterline_moves_its_given_sections():
    """The offsets are kept from the curves: the design waterline's measured half-breadths
    lowered by 5 cm move the given sections' waterline points in the entrance by that much (aft
    of x 162 m less: there the measured points lie up to 1 cm beyond B/2, where Q is held)."""
    desc = copy.deepcopy(imported("kcs"))
    before = fl.Hull.from_json(json.dumps(desc))
    desc["basic_curves"]["dwl"]["fit"] = [[x, max(y - 0.05, 0.0) if y > 0.1 else y] for x, y in desc["basic_curves"]["dwl"]["fit"]]
    after = fl.Hull.from_json(json.dumps(desc))
    xs = [g["x"] for g in desc["sections"]["given"] if 165.0 <= g["x"] <= 215.0]
    T = desc["principal"]["T"]
    for a, b in zip(before.sections_at(xs), after.sections_at(xs)):
        moved = _waterline_half_breadth(b, T) - _waterline_half_breadth(a, T)
        assert moved == pytest.approx(-0.05, abs=1e-3)


def _waterline_half_breadth(curve, z0: float) -> float:
    kn = np.asarray(curve.knots)
    p = np.asarray(curve.evaluate(np.linspace(kn[0], kn[-1], 4001)))
    i = int(np.flatnonzero((p[:-1, 2] >= z0) & (p[1:, 2] < z0))[0])
    return float(p[i, 1] + (p[i, 2] - z0) / (p[i, 2] - p[i + 1, 2]) * (p[i + 1, 1] - p[i, 1]))


def test_a_table_whose_midship_cells_above_t_are_blank_imports_with_its_depth(tmp_path):
    """The midship station's 7.5 and 9 m cells blank: the depth is still the deck's 9 m (it fell
    to T, and the import was refused: 'draught below the depth D = 6.25 m'), and the rebuilt
    hull holds the Wigley volume 4/9 L B T."""
    desc = fl.import_design(read_offsets_csv(wigley_table_csv(tmp_path, {"50000": ["7500", "9000"]}), **WIGLEY))
    assert desc["principal"]["D"] == pytest.approx(9.0)
    L, B, T = WIGLEY.values()
    assert fl.Hull.from_json(json.dumps(desc)).hydrostatics().volume == pytest.approx(4 / 9 * L * B * T, rel=VOLUME_GOAL)


def test_a_table_that_stops_at_the_draught_asks_for_the_depth(tmp_path):
    data = read_offsets_csv(wigley_table_csv(tmp_path, {}, drop=("7500", "9000")), **WIGLEY)
    with pytest.raises(fl.InvalidInput, match=r"the data's top near midships is z = 6.25 m, not above T = 6.25 m .* give the depth"):
        fl.import_design(data)


def test_stations_picked_up_toward_a_steep_end_lie_on_its_waterlines():
    """A wedge bow, y = 0.2 (x_c(z) - x) with the forefoot x_c(z) = 90 + 2.5 z (m): the table's
    stations 50-90 m have their keel on the base, the end station (100 m) its own 4 m up. The
    stations picked up between 90 and 100 m, one per quarter T of that rise, start on the
    profile and lie on the wedge at every height (the waterlines are straight, and the
    shape-preserving cubic along each, through the stations and the place it closes on the
    profile, is exact for them)."""
    from fairlines.import_design import _end_span_sections
    from fairlines.offsets import HullData, Section

    def wedge(x, z):
        return 0.2 * (90.0 + 2.5 * z - x)

    sections = []
    for x in (50.0, 60.0, 70.0, 80.0, 90.0, 100.0):
        zs = np.arange(max(0.0, (x - 90.0) / 2.5), 9.01, 1.0)
        sections.append(Section(x, np.array([(0.0, zs[0])] + [(wedge(x, z), z) for z in zs]), str(x)))
    data = HullData("wedge", 100.0, 30.0, 6.0, sections=sections)
    picked = _end_span_sections(data, lambda x: np.clip((np.asarray(x) - 90.0) / 2.5, 0.0, None))
    assert [p.x for p in picked] == pytest.approx([90 + 10 / 3, 90 + 20 / 3])  # a rise of 4 m: 2 stations per 1.5 m
    for p in picked:
        (y0, z0), rest = p.points[0], p.points[1:]
        assert (y0, z0) == pytest.approx((0.0, (p.x - 90.0) / 2.5), abs=1e-12)
        assert np.abs(rest[:, 0] - wedge(p.x, rest[:, 1])).max() <= 1e-9
