"""Appendages of the hull body: a single screw's skeg under the run with the propeller aperture
aft of it, and a sonar dome under the keel.

Truths: the particulars asked for (volume, LCB, Cwp measured on the surface), the propeller's
diameter and the clearances the designer promises (disc geometry, independent of the hull),
the dome's size from the particulars, and frames cut from the surface (fl.plane_cut)."""

import dataclasses

import numpy as np
import pytest

import fairlines as fl
from conftest import edge_census, ship_tol
from fairlines.designer import (DOME_DEPTH, DOME_HALF_BREADTH, DOME_LENGTH, HEEL_CLEARANCE,
                                PROPELLER_HALF_WIDTH, SKEG_HALF_THICKNESS, TIP_CLEARANCE, Propeller, propeller)
from fairlines.description import DOME_WIDEST, SKEG_FORE_TAPER
from fairlines.fairness import judge_cut

MATCH_TOL = 1e-5
BASELINE_TOL = 1e-3  # of T: the skinned skeg bottom on the baseline
SHIPS = {
    "tanker": dict(lpp=180.0, breadth=32.0, draft=11.5, depth=17.0, cb=0.82, lcb=95.4, skeg=True),
    "container": dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True, skeg=True),
    "coaster": dict(lpp=100.0, breadth=16.0, draft=6.0, depth=9.0, cb=0.75, lcb=51.0, stern="cruiser", skeg=True,
                    propeller_diameter=3.8),
}


@pytest.fixture(scope="module", params=list(SHIPS))
def ship(request):
    p = SHIPS[request.param]
    return p, fl.design_hull(**p)


def _frame(hull, x):
    return np.asarray(fl.plane_cut(hull.bare_hull_surface(), 0, float(x), 801).points)


def _used_diameter(hull):
    """The screw's diameter the designer used (m), read off its skeg (0.1 D half-thick)."""
    return hull.description.skeg.half_thickness / SKEG_HALF_THICKNESS


#: The screws the designer gives these ships (m): 0.55 T for the tanker (Cb 0.82), 0.7 T for the
#: container ship (Cb 0.65), the coaster's own 3.8 m.
USED_DIAMETER = {"tanker": 6.325, "container": 7.7, "coaster": 3.8}


def test_the_designer_uses_the_screw_its_rule_gives(ship, request):
    assert _used_diameter(ship[1]) == pytest.approx(USED_DIAMETER[request.node.callspec.params["ship"]], rel=1e-12)


@pytest.mark.parametrize("cb, share", [(0.6, 0.7), (0.7, 0.7), (0.75, 0.625), (0.82, 0.55), (0.85, 0.55)])
def test_the_default_screw_shrinks_from_0_7_to_0_55_draughts_as_cb_goes_from_0_7_to_0_8(cb, share):
    """Worked by hand: 0.7 T up to Cb 0.7, 0.55 T from 0.8, linear between (a dry transom: the
    room over the blades does not bind)."""
    from fairlines.designer import default_propeller_diameter

    p = fl.Particulars(lpp=150.0, breadth=24.0, draft=9.0, depth=14.0, cb=cb, lcb=75.0, skeg=True)
    assert default_propeller_diameter(p) == pytest.approx(share * 9.0, rel=1e-12)


def _assert_meets_particulars(p: dict, hull) -> None:
    """Volume Cb Lpp B T and the LCB of the ship (with a bulb the composed ship), within
    MATCH_TOL (with a bulb the designer's MATCH_TOL_BULB)."""
    h, tol = hull.ship_hydrostatics(), ship_tol(hull, MATCH_TOL)
    assert h["volume"] == pytest.approx(p["cb"] * p["lpp"] * p["breadth"] * p["draft"], rel=tol)
    assert abs(h["lcb"] - p["lcb"]) <= tol * p["lpp"]


def test_skeg_ship_meets_its_particulars(ship):
    _assert_meets_particulars(*ship)


def test_the_propeller_disc_clears_the_hull(ship):
    """Every point of the frames through the blades (the propeller's plane and its blades'
    axial extent either side) lies at least the tip clearance outside the disc (a circle of
    the given diameter about the shaft)."""
    p, hull = ship
    dp = _used_diameter(hull)
    x_p, shaft = propeller(fl.Particulars(**{**p, "propeller_diameter": dp})).x, (HEEL_CLEARANCE + 0.5) * dp
    assert shaft - dp / 2 == pytest.approx(HEEL_CLEARANCE * dp)  # the disc stays above the baseline
    for x in x_p + np.array([-1.0, 0.0, 1.0]) * PROPELLER_HALF_WIDTH * dp:
        f = _frame(hull, x)
        gap = np.hypot(f[:, 1], f[:, 2] - shaft).min() - dp / 2
        assert gap >= TIP_CLEARANCE * dp, (x, gap)


def test_the_propeller_is_a_frozen_record_and_none_without_a_skeg():
    coaster = SHIPS["coaster"]
    pr = propeller(fl.Particulars(**coaster))
    assert isinstance(pr, Propeller) and pr.diameter == coaster["propeller_diameter"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        pr.diameter = 1.0
    plain = {k: v for k, v in coaster.items() if k not in ("skeg", "propeller_diameter")}
    assert propeller(fl.Particulars(**plain)) is None


def test_the_skeg_runs_on_the_baseline_at_its_thickness(ship):
    """Where the skeg is whole (between its raked aft end and its taper into the keel), each
    frame reaches the baseline on it, and its sides stand the designer's half-thickness off the
    centre plane (at 10-20 % of its depth: clear of the bottom's rounded corner and the fillet)."""
    p, hull = ship
    sk = hull.description.skeg
    dp = _used_diameter(hull)
    body = hull.basic_curves["profile"]
    a, b = sk.x_aft + sk.end_length, sk.x_fore - SKEG_FORE_TAPER * (sk.x_fore - sk.x_aft)
    deepest = float(body(a)[0])
    for x in np.linspace(a, b, 5):
        f = _frame(hull, x)
        assert f[:, 2].min() == pytest.approx(0.0, abs=BASELINE_TOL * p["draft"]), x
        depth = float(body(x)[0])
        if depth < 0.5 * deepest:  # shallow: the rounded bottom corner reaches up the side
            continue
        side = f[(f[:, 2] > 0.1 * depth) & (f[:, 2] < 0.2 * depth) & (f[:, 1] < 2 * SKEG_HALF_THICKNESS * dp)]
        assert len(side) and np.all(np.abs(side[:, 1] - SKEG_HALF_THICKNESS * dp) <= 0.1 * SKEG_HALF_THICKNESS * dp), x


def _turns_above(hull, x, draft):
    cut = judge_cut(fl.plane_cut(hull.bare_hull_surface(), 0, float(x), 601))
    return sum(i["at"][2] > draft for i in cut["inflections"])


def test_the_skeg_adds_no_hollow_above_the_waterline(ship):
    """The skeg's hollow is below the water: a frame over it turns hollow above T no more often
    than the same ship's frame without a skeg."""
    p, hull = ship
    plain = fl.design_hull(**{**p, "skeg": False, "propeller_diameter": None})
    sk = hull.description.skeg
    for x in np.linspace(sk.x_aft, sk.x_fore, 8):
        assert _turns_above(hull, x, p["draft"]) <= _turns_above(plain, x, p["draft"]), x


def test_the_skegged_tankers_outer_buttocks_rise_aft_in_one_s():
    """The skegged tanker's buttocks outside the skeg's fillet (y 6-14 m) rise from the flat of
    bottom to the counter in one S aft of midships (one sign change over 0.1 deg). With its
    screw at 0.7 T (8.05 m) the keel rose 10.4 m over the 14 m aft of its flat and these
    buttocks turned 3-9 times, a cliff at x 10-20 m; at 0.55 T (the default for Cb 0.8 and up)
    it rises 8.2 m."""
    from fairlines.fairness import cut_lobes

    p = SHIPS["tanker"]
    surface = fl.design_hull(**p).bare_hull_surface()
    for y in (6.0, 8.0, 10.0, 12.0, 14.0):
        cut = fl.plane_cut(surface, 1, y, 2001)
        pts, k = np.asarray(cut.points), np.asarray(cut.curvature)
        aft = pts[:, 0] < p["lpp"] / 2
        lobes = cut_lobes(pts[aft], k[aft])
        assert len(lobes) <= 2, (y, [(round(lobe["turn_deg"], 2), round(lobe["at"][0], 1)) for lobe in lobes])


#: Where a skeg starts, the half-breadths of the sections either side (2 mm apart) of its aft
#: edge differ by at most this (m): they change about 0.3 m per metre there.
SKEG_START_STEP = 1e-3


@pytest.mark.parametrize("height", [13.3, 16.15])
def test_the_skegged_container_ships_topside_has_no_step_where_its_skeg_starts(height):
    """The container ship's skeg starts (x 9.7 m) inside its dry transom's run (to 11 m), where
    the topsides are faired onto lines (fairlines.transom_run): its sections' half-breadths above
    T (13.3 m, 16.15 m) run on across the skeg's aft edge. The skeg's sections were left off the
    run's fairing and stepped 20 / 11 mm; now their topside is the body's own, faired alike."""
    hull = fl.design_hull(**SHIPS["container"])
    x = hull.description.skeg.x_aft
    sections = hull.sections_at([x - 1e-3, x + 1e-3])
    pts = [np.asarray(c.evaluate(np.linspace(*c.domain, 20001)))[::-1] for c in sections]  # keel -> deck
    assert all(np.all(np.diff(p[:, 2]) > 0) for p in pts)
    ys = [float(np.interp(height, p[:, 2], p[:, 1])) for p in pts]
    assert abs(ys[1] - ys[0]) <= SKEG_START_STEP, ys


def test_skeg_ship_composes_watertight(ship):
    p, hull = ship
    c = hull.composed_hull() if p.get("bulb") else fl.compose([hull.bare_hull_surface()], hull_u=96, hull_v=40)
    assert edge_census(c.full_mesh().faces) == (0, 0, 0)


def test_skeg_ships_cfd_mesh_is_manifold(ship):
    """A fine surface mesh of a skeg ship (fl.mesh_hull at 0.8 % Lpp, lids on) is closed and
    manifold. Where the skeg's bottom rises over its raked aft edge the hull is a strip a few
    centimetres wide turning through 90 deg, and the mesher's edge swaps, judged in space, made
    edges that were there already: the container ship's 2 m mesh had 54 edges on four triangles."""
    p, hull = ship
    c = fl.compose([hull.bare_hull_surface()])
    q = fl.mesh_hull(c, size=0.008 * p["lpp"]).quality()
    assert (q["open_edges"], q["non_manifold_edges"], q["misoriented_edges"]) == (0, 0, 0)


@pytest.mark.parametrize("bad, message", [
    (dict(propeller_diameter=7.0), "expected it only with skeg=True"),
    (dict(skeg=True, propeller_diameter=20.0), "propeller_diameter is 20.0; expected a propeller diameter"),
    (dict(skeg="yes"), "skeg is 'yes'; expected true or false")])
def test_bad_propeller_particulars_name_the_value(bad, message):
    with pytest.raises(fl.InvalidInput, match=message):
        fl.design_hull(**{**SHIPS["tanker"], "skeg": False, **bad})


def test_a_skeg_in_the_description_is_refused_off_the_hull():
    d = fl.design_hull(**SHIPS["tanker"]).to_dict()
    d["skeg"]["x_fore"] = 500.0
    with pytest.raises(fl.InvalidInput, match="skeg.x_aft / x_fore"):
        fl.Hull.from_json(d)


FRIGATE = dict(lpp=140.0, breadth=17.0, draft=5.5, depth=10.0, cb=0.50, lcb=67.2, sonar_dome=True)


@pytest.fixture(scope="module")
def frigate():
    return fl.design_hull(**FRIGATE)


def test_dome_ship_meets_its_particulars(frigate):
    _assert_meets_particulars(FRIGATE, frigate)


def test_the_dome_hangs_its_depth_below_the_keel_at_its_breadth(frigate):
    """At its widest station the frame reaches DOME_DEPTH T below the baseline, is DOME_HALF_BREADTH
    B wide there, and comes in to a neck above it (narrower at the baseline than the dome)."""
    p, dm = FRIGATE, frigate.description.dome
    assert dm.x_fore - dm.x_aft == pytest.approx(DOME_LENGTH * p["lpp"])
    f = _frame(frigate, dm.x_aft + DOME_WIDEST * (dm.x_fore - dm.x_aft))
    assert f[:, 2].min() == pytest.approx(-DOME_DEPTH * p["draft"], abs=1e-3 * p["draft"])
    below = f[f[:, 2] < -0.05 * p["draft"]]
    assert below[:, 1].max() == pytest.approx(DOME_HALF_BREADTH * p["breadth"], rel=0.03)
    neck = f[np.abs(f[:, 2]) < 0.01 * p["draft"]]
    assert neck[:, 1].min() < 0.8 * below[:, 1].max()


def test_nothing_hangs_below_the_keel_outside_the_dome(frigate):
    dm = frigate.description.dome
    for x in (dm.x_aft - 3.0, dm.x_fore + 3.0, 0.5 * FRIGATE["lpp"]):
        assert _frame(frigate, x)[:, 2].min() >= -1e-3 * FRIGATE["draft"], x


def test_dome_ship_composes_watertight(frigate):
    c = fl.compose([frigate.bare_hull_surface()], hull_u=96, hull_v=60)
    assert edge_census(c.full_mesh().faces) == (0, 0, 0)


#: Ships of bench_design_options with a bulb and a sonar dome (rounded). With the dome's nose
#: where the keel's flat ends, design 120's blend ran down the dome's side to its keel (2.2 m
#: below the base) and folded, its normal turning by 178 deg between neighbouring points and 6
#: pairs of its composed mesh's faces crossing; with the nose 0.01 Lpp aft of the blend (not
#: enough: the dome draws the keel in forward of its nose) design 491's blend folded by 165 deg,
#: 41 pairs crossing.
BULB_AND_DOME = {
    "208 m, Cb 0.82": dict(lpp=208.29, breadth=23.3, draft=5.5, depth=9.24, cb=0.82, lcb=108.2, bulb=True,
                           sonar_dome=True, stem_rake=7.0),
    "232 m, cruiser stern": dict(lpp=232.306, breadth=35.192, draft=12.92, depth=27.076, cb=0.616, lcb=106.995,
                                 stern="cruiser", bulb=True, sonar_dome=True),
    # its blend starts on the flat keel, 5 m forward of the dome, which draws the keel 2 mm under
    # the base there: refused as a blend on the dome while that counted 1e-4 T
    "166 m, blend on the flat keel": dict(lpp=165.726, breadth=32.56, draft=15.956, depth=26.411, cb=0.6112, lcb=84.66,
                                          stern="cruiser", bulb=True, sonar_dome=True),
}


@pytest.fixture(scope="module", params=list(BULB_AND_DOME))
def bulb_and_dome(request):
    p = BULB_AND_DOME[request.param]
    return p, fl.design_hull(**p)


def _blend_clears_the_dome(hull, p):
    """The blend lies forward of the dome and above the base, does not fold; the composed hull
    is closed and crosses itself nowhere."""
    from blend_fixtures import FOLD_DEG, largest_normal_turn_deg
    from mesh_fixtures import self_intersections

    c = hull.composed_hull()
    blend = np.asarray(c.blend.evaluate_grid(np.linspace(0, 1, 121), np.linspace(0, 1, 31))).reshape(-1, 3)
    assert blend[:, 0].min() > hull.description.dome.x_fore
    assert blend[:, 2].min() >= -BASELINE_TOL * p["draft"]
    assert largest_normal_turn_deg(c.blend) < FOLD_DEG
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    assert self_intersections(c.mesh) == []


def test_a_bulbs_blend_stays_clear_of_the_sonar_dome(bulb_and_dome):
    """... and the dome still hangs its depth below the keel."""
    p, hull = bulb_and_dome
    dm = hull.description.dome
    assert _frame(hull, dm.x_aft + DOME_WIDEST * (dm.x_fore - dm.x_aft))[:, 2].min() == pytest.approx(
        -DOME_DEPTH * p["draft"], abs=1e-3 * p["draft"])
    _blend_clears_the_dome(hull, p)


def test_the_bulb_and_dome_ship_meets_its_particulars(bulb_and_dome):
    _assert_meets_particulars(*bulb_and_dome)


def test_the_dome_nose_the_designer_chose_is_a_particular_that_rebuilds_the_ship(bulb_and_dome):
    """The description's record of the particulars holds the nose the designer chose; designed
    again from that record the ship has the same dome and hull."""
    p, hull = bulb_and_dome
    record = hull.to_dict()["design"]
    assert record["sonar_dome_nose"] == pytest.approx(hull.description.dome.x_fore)
    again = fl.design_hull(**{k: v for k, v in record.items() if v is not None})
    assert again.description.dome.x_fore == hull.description.dome.x_fore
    assert again.hydrostatics().volume == pytest.approx(hull.hydrostatics().volume, rel=1e-12)


def test_a_dome_nose_given_where_the_blend_would_run_onto_it_is_refused_naming_what_to_give(bulb_and_dome):
    """The dome's nose given at the keel's flat end (the designer's place without a bulb): the
    refusal names a nose, and with that nose the blend clears the dome."""
    import re

    p, hull = bulb_and_dome
    flat_to = hull.description.curves["profile"].flat_to
    with pytest.raises(fl.InfeasibleFormParameters, match="runs onto the sonar dome") as err:
        fl.design_hull(**p, sonar_dome_nose=flat_to)
    nose = float(re.search(r"give sonar_dome_nose at most ([-0-9.e+]+) m", str(err.value)).group(1))
    _blend_clears_the_dome(fl.design_hull(**p, sonar_dome_nose=nose), p)


@pytest.mark.parametrize("ship, change, says", [
    ("frigate", {"sonar_dome": False, "sonar_dome_nose": 100.0}, "sonar_dome_nose is 100.0; expected it only with sonar_dome=True"),
    ("frigate", {"sonar_dome_nose": 1e4}, "sonar_dome_nose is 10000.0; expected a dome nose 0.11 Lpp or more forward of the AP"),
    ("frigate", {"sonar_dome_nose": 139.9}, r"sonar_dome_nose is 139.9; expected [0-9.]+ to [0-9.]+ m from the AP \(the dome "
                                            "hangs under the flat keel"),
    ("frigate", {"sonar_dome_nose": 16.0}, r"sonar_dome_nose is 16.0; expected [0-9.]+ to [0-9.]+ m from the AP"),
    ("coaster", {"sonar_dome": True, "sonar_dome_nose": 23.72}, r"sonar_dome_nose is 23.72; expected [0-9.]+ to"),
    ("frigate", {"sonar_dome_nose": "fore"}, "sonar_dome_nose is 'fore'"),
])
def test_a_bad_dome_nose_is_refused_naming_the_value(ship, change, says):
    """Outside the flat keel (under the rising run, over a skeg, forward of where the keel
    leaves the base) the dome would not hang as built: refused, naming the range."""
    with pytest.raises(fl.InvalidInput, match=says):
        fl.design_hull(**{**(FRIGATE if ship == "frigate" else SHIPS[ship]), **change})


def test_a_bad_dome_is_refused_naming_the_value(frigate):
    with pytest.raises(fl.InvalidInput, match="sonar_dome is 'yes'"):
        fl.design_hull(**{**FRIGATE, "sonar_dome": "yes"})
    d = frigate.to_dict()
    d["dome"]["depth"] = -1.0
    with pytest.raises(fl.InvalidInput, match="dome.depth is -1.0 m; expected > 0"):
        fl.Hull.from_json(d)


def test_command_line_design_with_skeg_and_dome(tmp_path):
    from fairlines.cli import main

    out = tmp_path / "ship.json"
    assert main(["design", "--lpp", "140", "--breadth", "17", "--draft", "5.5", "--depth", "10", "--cb", "0.5",
                 "--lcb", "67.2", "--skeg", "--propeller-diameter", "3.5", "--sonar-dome", "-o", str(out)]) == 0
    d = fl.Hull.from_json(out.read_text()).description
    assert d.skeg is not None and d.dome is not None
    assert d.skeg.half_thickness == pytest.approx(SKEG_HALF_THICKNESS * 3.5)


def test_a_propeller_the_run_cannot_clear_is_refused_naming_what_to_change():
    """A full ship (Cb 0.86) with its LCB far aft: its keel's flat starts where the screw would
    turn. Refused naming the propeller, what to change and an LCB that builds."""
    with pytest.raises(fl.InfeasibleFormParameters, match=r"over the propeller: give a smaller propeller_diameter.*lcb [\d.]+ m builds"):
        fl.design_hull(lpp=150.0, breadth=22.37, draft=5.0, depth=8.0, cb=0.86, lcb=69.54, skeg=True)


def test_skeg_ships_build_over_the_design_space():
    """A seeded Latin-hypercube sample of 20 particulars over Cb 0.50-0.87, LCB -4..+4 % Lpp,
    L/B 4-9, B/T 2-4.5, each with a skeg (every other with a sonar dome): all but the full
    ships whose run is too short for a propeller build and meet volume and LCB (1e-4)."""
    from scipy.stats import qmc

    space = dict(cb=(0.50, 0.87), lcb_pct=(-4.0, 4.0), l_over_b=(4.0, 9.0), b_over_t=(2.0, 4.5))
    refused = []
    for i, r in enumerate(qmc.LatinHypercube(d=4, seed=11).random(20)):
        cb, lcb, lb, bt = (lo + x * (hi - lo) for x, (lo, hi) in zip(r, space.values()))
        lpp = 150.0
        b = lpp / lb
        t = b / bt
        p = dict(lpp=lpp, breadth=b, draft=t, depth=1.6 * t, cb=cb, lcb=lpp / 2 + lcb / 100 * lpp, skeg=True,
                 sonar_dome=i % 2 == 0)
        try:
            h = fl.design_hull(**p).hydrostatics()
        except fl.InfeasibleFormParameters as e:
            refused.append((cb, str(e)))
            continue
        assert h.volume == pytest.approx(cb * lpp * b * t, rel=1e-4)
        assert abs(h.lcb - p["lcb"]) <= 1e-4 * lpp
    assert all(cb > 0.8 and "over the propeller" in msg for cb, msg in refused), refused
