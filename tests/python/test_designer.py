"""The whole-ship designer (fl.design_hull): particulars in, a hull whose surface holds them out.

Truths used: the particulars asked for (volume Cb Lpp B T, LCB, Cwp Lpp B), measured on the
surface by the engine's NURBS quadrature (fl.hydrostatics) and by the composed mesh
(fl.mesh_hydrostatics, a different integral of a different object); exact geometry of the
ends (deck, baseline, transom plane, centre plane); the curvature of the cut curves."""

import json
import math
import pathlib
import re

import numpy as np
import pytest

import fairlines as fl
from fairlines.designer import DRY_TRANSOM_DECK_LEAST
from fairlines.fairness import judge_cut
from conftest import edge_census, ship_tol

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "container_ship.json"
MATCH_TOL = 1e-5        # volume, Cwp (relative) and LCB (of Lpp) met on the surface
MESH_TOL = 5e-3         # composed mesh vs surface quadrature (chords inside convex sections)
GEOMETRY_TOL = 1e-6     # m: ends on their planes
OVERSHOOT_TOL = 1e-4    # of B: the skinned surface may pass the flat of side by this much

SHIPS = {
    "container": dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True),
    "tanker": dict(lpp=180.0, breadth=32.0, draft=11.5, depth=17.0, cb=0.82, lcb=95.4),
    "fine_ferry": dict(lpp=140.0, breadth=17.0, draft=5.5, depth=10.0, cb=0.50, lcb=67.2),
    "coaster_cruiser": dict(lpp=100.0, breadth=16.0, draft=6.0, depth=9.0, cb=0.75, lcb=51.0, stern="cruiser"),
}
# The design space: Cb, LCB % Lpp from midships, L/B, B/T
SPACE = dict(cb=(0.50, 0.87), lcb_pct=(-4.0, 4.0), l_over_b=(4.0, 9.0), b_over_t=(2.0, 4.5))


@pytest.fixture(scope="module", params=list(SHIPS))
def ship(request):
    p = SHIPS[request.param]
    return p, fl.design_hull(**p)


def _asked(p):
    return p["cb"] * p["lpp"] * p["breadth"] * p["draft"]


def _grid(surface, n=61):
    return np.asarray(surface.evaluate_grid(np.linspace(*surface.domain_u, n), np.linspace(*surface.domain_v, n)))


def test_particulars_are_met_on_the_surface(ship):
    """Without a bulb the bare hull is the ship; with one it holds less by the bulb's share
    (the next test), its waterplane the same."""
    p, hull = ship
    h = fl.hydrostatics(hull.bare_hull_surface(), p["draft"], length=p["lpp"], breadth=p["breadth"],
                        midship_x=p["lpp"] / 2)
    if p.get("bulb"):
        assert 0.003 < 1 - h.volume / _asked(p) < 0.015
    else:
        assert h.volume == pytest.approx(_asked(p), rel=MATCH_TOL)
        assert abs(h.lcb - p["lcb"]) <= MATCH_TOL * p["lpp"]
        assert h.cb == pytest.approx(p["cb"], rel=MATCH_TOL)
    assert 0 < h.cm <= 1 and h.cb < h.cwp <= 1 and fl.Particulars(**p).cwp is None


#: The composed mesh at a fine tessellation against the surface's figures (its chords: 1.6e-4
#: of the example's bare hull volume at 192 x 80).
FINE_MESH = dict(hull_u=192, hull_v=80)
FINE_MESH_TOL = 5e-4


def test_a_ship_with_a_bulb_holds_its_particulars_with_it():
    """The composed ship (bare hull, bulb and blend), not the bare hull, holds the asked volume
    and LCB: measured as the designer measures it (the surface plus the bulb's share of the
    composed mesh, designer.MATCH_TOL_BULB) and on a fine composed mesh alone. Before, the bare
    hull held them and the container ship's bulb added 0.89 % and moved the LCB 0.43 % Lpp
    forward."""
    from fairlines.designer import MATCH_TOL_BULB
    from fairlines.hydrostatics_composed import composed_hydrostatics

    p = SHIPS["container"]
    hull = fl.design_hull(**p)
    q = composed_hydrostatics(hull.composed_hull(), p["draft"], lpp=p["lpp"], beam=p["breadth"])
    assert q["volume"] == pytest.approx(_asked(p), rel=MATCH_TOL_BULB)
    assert abs(q["lcb"] - p["lcb"]) <= MATCH_TOL_BULB * p["lpp"]
    assert q["cwp"] == pytest.approx(hull.hydrostatics().cwp, rel=1e-5)
    fine = fl.mesh_hydrostatics(hull.composed_hull(**FINE_MESH).mesh, p["draft"])
    assert fine.volume == pytest.approx(_asked(p), rel=FINE_MESH_TOL)
    assert abs(fine.lcb - p["lcb"]) <= FINE_MESH_TOL * p["lpp"]



#: Full ships of bench_hull's sample (rounded) whose composed ship the designer had put 1.4e-4,
#: 1.1e-4 and 0.8e-4 of its volume off, and 6.3e-4 at most over the sample, when the bulb's share
#: was the two meshes' difference alone (its flat faces' chords over the hull cells the bulb removes).
SHARE_SHIPS = {
    "full 219 m": dict(lpp=218.852, breadth=25.663, draft=6.756, depth=10.81, cb=0.827, lcb=113.411, bulb=True),
    "full 131 m": dict(lpp=131.322, breadth=20.99, draft=4.837, depth=7.74, cb=0.859, lcb=70.56, bulb=True),
    "full 246 m": dict(lpp=246.242, breadth=28.144, draft=7.866, depth=12.586, cb=0.841, lcb=122.661, bulb=True),
}
#: Two fine tessellations (the second twice the first each way) and the convergence order of a
#: mesh's chords, for Richardson's extrapolation of the bulb's share.
SHARE_MESHES = (dict(hull_u=96, hull_v=40, bulb_u=48, bulb_v=64, blend_rows=16),
                dict(hull_u=192, hull_v=80, bulb_u=96, bulb_v=128, blend_rows=32))
#: The issue's mark for a design's volume and LCB (relative; LCB on Lpp).
DESIGN_TOL = 1e-4


def _converged_share(hull, draft: float, lpp: float) -> tuple:
    """(volume, moment about x = 0) the bulb and blend add below T: the composed and the bare
    hull's own meshes' difference (no correction) at the two SHARE_MESHES, extrapolated to a
    zero cell size (chords shrink as the cell squared)."""
    from fairlines.compose import compose, compose_with_blend
    from fairlines.hydrostatics_composed import mesh_below

    out = []
    for opts in SHARE_MESHES:
        surface = hull.bare_hull_surface()
        composed = compose_with_blend(surface, hull.bulbous_bow(), placement=hull.blend_placement(), **opts)
        c = mesh_below(composed, draft, lpp=lpp)
        b = mesh_below(compose([surface], hull_u=opts["hull_u"], hull_v=opts["hull_v"]), draft, lpp=lpp)
        out.append(np.array([c["volume"] - b["volume"], c["volume"] * c["lcb"] - b["volume"] * b["lcb"]]))
    return tuple(out[1] + (out[1] - out[0]) / 3.0)


@pytest.mark.parametrize("name", SHARE_SHIPS)
def test_a_ship_with_a_bulb_meets_its_volume_and_lcb_on_converged_meshes(name):
    """The composed ship holds the asked volume and LCB within the issue's 1e-4, measured apart
    from the designer: the bare hull's surface quadrature plus the bulb's share from meshes of
    4 and 16 times the default cells, extrapolated (SHARE_MESHES)."""
    p = SHARE_SHIPS[name]
    hull = fl.design_hull(**p)
    bare = hull.hydrostatics()
    dv, dm = _converged_share(hull, p["draft"], p["lpp"])
    volume = bare.volume + dv
    assert volume == pytest.approx(_asked(p), rel=DESIGN_TOL)
    assert abs((bare.volume * bare.lcb + dm) / volume - p["lcb"]) <= DESIGN_TOL * p["lpp"]


@pytest.mark.parametrize("trim", [0.0, 2.0])
def test_composed_hydrostatics_match_converged_meshes_upright_and_trimmed(trim):
    """The container ship's composed hydrostatics (surface quadrature plus the bulb's share with
    the chord difference) against the same surface quadrature plus the share of raw meshes at 4
    and 16 times the default cells, extrapolated: volume, LCB and VCB within 5e-5 (of the volume,
    Lpp and T), upright and trimmed 2 m by the stern."""
    from fairlines.compose import compose, compose_with_blend
    from fairlines.hydrostatics_composed import composed_hydrostatics, mesh_below

    p = SHIPS["container"]
    hull = fl.design_hull(**p)
    q = composed_hydrostatics(hull.composed_hull(), p["draft"], lpp=p["lpp"], beam=p["breadth"], trim=trim)
    bare = fl.hydrostatics(hull.bare_hull_surface(), p["draft"], length=p["lpp"], breadth=p["breadth"],
                           **({"trim": trim, "trim_length": p["lpp"]} if trim else {}))
    shares = []
    for opts in SHARE_MESHES:
        surface = hull.bare_hull_surface()
        c = mesh_below(compose_with_blend(surface, hull.bulbous_bow(), placement=hull.blend_placement(), **opts),
                       p["draft"], lpp=p["lpp"], trim=trim)
        b = mesh_below(compose([surface], hull_u=opts["hull_u"], hull_v=opts["hull_v"]), p["draft"], lpp=p["lpp"], trim=trim)
        shares.append(np.array([c["volume"] - b["volume"], c["volume"] * c["lcb"] - b["volume"] * b["lcb"],
                                c["volume"] * c["vcb"] - b["volume"] * b["vcb"]]))
    dv, dmx, dmz = shares[1] + (shares[1] - shares[0]) / 3.0
    volume = bare.volume + dv
    assert q["volume"] == pytest.approx(volume, rel=5e-5)
    assert abs(q["lcb"] - (bare.volume * bare.lcb + dmx) / volume) <= 5e-5 * p["lpp"]
    assert abs(q["vcb"] - (bare.volume * bare.vcb + dmz) / volume) <= 5e-5 * p["draft"]

# A section whose waterline point lies on B/2 meets it only as closely as its spline can pass
# through a point on its bound below a flat of side: 1.67 mm on the fine ferry's widest station
# (of 17 m) with the sections as designed, 1.84 mm with the station mean's basic curves; 2.22 mm
# before the bilge arc's fine weight fell from 0.7 to 0.5, 2.66 mm since: the arc's curvature at Q
# grows as 1 / w^2, and a spline clamped to B/2 follows it less closely.
BREADTH_REACH_TOL = 2e-4  # of B


def test_the_waterline_reaches_the_breadth(ship):
    """B is a particular: the surface's design waterline reaches B/2 (a fine ship without
    parallel body too, at midships), and never exceeds it."""
    p, hull = ship
    cut = np.asarray(fl.plane_cut(hull.bare_hull_surface(), 2, p["draft"], 2001).points)
    assert cut[:, 1].max() == pytest.approx(p["breadth"] / 2, abs=BREADTH_REACH_TOL * p["breadth"])


def test_the_waterline_widens_from_the_stern_to_its_widest(ship):
    """Cut from the surface, the design waterline's half-breadth never narrows going forward
    from the stern to where it is widest (no waist in the run, also behind a wide immersed
    transom on a fine ship)."""
    p, hull = ship
    cut = np.asarray(fl.plane_cut(hull.bare_hull_surface(), 2, p["draft"], 2001).points)
    cut = cut[np.argsort(cut[:, 0])]
    run = cut[: int(np.argmax(cut[:, 1])) + 1, 1]
    assert np.all(np.diff(run) >= -1e-4 * p["breadth"])


def test_sectional_area_has_no_hump(ship):
    """The surface's SAC (hydrostatics) rises to the midship area and falls away from it: no
    section holds more than the largest midship-body section, the SAC is one hill."""
    p, hull = ship
    h = hull.hydrostatics(sac_stations=241)
    a = np.asarray(h.sac_area)
    top = int(np.argmax(a))
    assert np.all(np.diff(a[:top + 1]) >= -1e-6 * a[top]) and np.all(np.diff(a[top:]) <= 1e-6 * a[top])


def test_whole_ship_geometry(ship):
    """Half hull y >= 0 within B/2, bottom on the baseline, deck edge at D, aft end on one plane
    (a transom) or on the centre plane (a cruiser stern), stem forward of the FP above T."""
    p, hull = ship
    g = _grid(hull.bare_hull_surface())
    assert g[..., 1].min() >= -GEOMETRY_TOL and g[..., 1].max() <= p["breadth"] * (0.5 + OVERSHOOT_TOL)
    assert -OVERSHOOT_TOL * p["breadth"] <= g[..., 2].min() <= GEOMETRY_TOL
    assert g[..., 2].max() == pytest.approx(p["depth"], abs=GEOMETRY_TOL)
    assert g[..., 0].min() < 0.0 and g[..., 0].max() > p["lpp"]
    along_u = np.ptp(g[:, 0, 0]) > np.ptp(g[0, :, 0])
    ends = (g[0], g[-1]) if along_u else (g[:, 0], g[:, -1])
    aft = min(ends, key=lambda e: e[:, 0].mean())
    if p.get("stern", "transom") == "transom":
        assert np.ptp(aft[:, 0]) < GEOMETRY_TOL
    else:
        assert np.abs(aft[:, 1]).max() < 1e-3 * p["breadth"]


def test_composed_whole_ship_is_watertight_and_holds_the_volume(ship):
    p, hull = ship
    c = hull.composed_hull() if p.get("bulb") else hull.composed_hull(hull_u=96, hull_v=40)  # without a bulb: closed
    assert c.blend_note.startswith("blend" if p.get("bulb") else "no bulb")
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    assert edge_census(c.full_mesh().faces) == (0, 0, 0)
    assert fl.mesh_hydrostatics(c.mesh, p["draft"]).volume == pytest.approx(_asked(p), rel=MESH_TOL)


def test_round_trip_through_json_rebuilds_the_same_hull():
    hull = fl.Hull.from_json(EXAMPLE.read_text())
    again = fl.Hull.from_json(json.loads(hull.to_json()))
    a, b = hull.bare_hull_surface(), again.bare_hull_surface()
    assert np.array_equal(np.asarray(a.control_points), np.asarray(b.control_points))
    assert np.array_equal(np.asarray(a.knots_u), np.asarray(b.knots_u))


def test_example_is_the_designed_container_ship():
    hull = fl.Hull.from_json(EXAMPLE.read_text())
    p = SHIPS["container"]
    assert hull.ship_hydrostatics()["volume"] == pytest.approx(_asked(p), rel=ship_tol(hull, MATCH_TOL))


@pytest.mark.parametrize("change", [dict(cb=0.65 * 1.06), dict(cb=0.65 * 0.94), dict(lcb=118.73 + 2.448),
                                    dict(lcb=118.73 - 2.448), dict(cwp=0.86), dict(bulb=False),
                                    dict(cb=0.65 * 1.10), dict(cb=0.65 * 0.90), dict(cwp=0.8162 * 1.10),
                                    dict(cwp=0.8162 * 0.90)])
def test_changed_particulars_of_the_container_ship_build(change):
    p = {**SHIPS["container"], **change}
    hull = fl.design_hull(**p)
    h, tol = hull.ship_hydrostatics(), ship_tol(hull, MATCH_TOL)
    assert h["volume"] == pytest.approx(_asked(p), rel=tol)
    assert abs(h["lcb"] - p["lcb"]) <= tol * p["lpp"]
    if "cwp" in change:  # with a bulb the designer stops within MATCH_TOL_BULB on all three (-2.7e-5 here)
        assert h["cwp"] == pytest.approx(change["cwp"], rel=tol)


def _space_sample(n, seed):
    from scipy.stats import qmc

    out = []
    for r in qmc.LatinHypercube(d=4, seed=seed).random(n):
        cb, lcb, lb, bt = (lo + x * (hi - lo) for x, (lo, hi) in zip(r, SPACE.values()))
        lpp = 150.0
        b = lpp / lb
        t = b / bt
        out.append(dict(lpp=lpp, breadth=b, draft=t, depth=1.6 * t, cb=cb, lcb=lpp / 2 + lcb / 100 * lpp))
    return out


def _failures(particulars) -> list:
    """The particulars whose designed ship does not build or misses its volume or LCB (1e-4)."""
    fails = []
    for p in particulars:
        try:
            h = fl.design_hull(**p).ship_hydrostatics()
            assert h["volume"] == pytest.approx(_asked(p), rel=1e-4)
            assert abs(h["lcb"] - p["lcb"]) <= 1e-4 * p["lpp"]
        except (fl.InfeasibleFormParameters, AssertionError) as e:
            fails.append((p, str(e)[:80]))
    return fails


def test_latin_hypercube_of_the_design_space_all_builds():
    assert _failures(_space_sample(40, 2026)) == []


def test_latin_hypercube_with_a_given_parallel_body_and_bulb_all_builds():
    """The same space with a parallel body of 2 .. 30 % Lpp given (as a designer gives it, also
    on fine ships) and every other ship with a bulb: each builds and meets its volume and LCB."""
    from scipy.stats import qmc

    ships = []
    for i, r in enumerate(qmc.LatinHypercube(d=5, seed=11).random(30)):
        cb, lcb, lb, bt, par = (lo + x * (hi - lo) for x, (lo, hi) in zip(r, (*SPACE.values(), (0.02, 0.3))))
        lpp = 150.0
        b = lpp / lb
        ships.append(dict(lpp=lpp, breadth=b, draft=b / bt, depth=1.6 * b / bt, cb=cb, lcb=lpp / 2 + lcb / 100 * lpp,
                          parallel_length=par * lpp, bulb=bool(i % 2)))
    assert _failures(ships) == []


def test_latin_hypercube_with_options_builds_or_names_what_to_change():
    """The space with a depth of 1.3-2.2 T and the designer's options drawn at random (seeded, by
    bench_design_options.designs: cruiser stern, bulb, skeg, sonar dome, no parallel body, stem
    rake, and 4 of the 24 with a transom raked 5-25 deg),
    150 m ships: each design builds and meets its volume and LCB, or is refused naming what to
    change; and most build (the bench: 488 of 500)."""
    import sys

    bench = str(EXAMPLE.parents[1] / "bench")
    if bench not in sys.path:
        sys.path.insert(0, bench)
    from bench_design_options import designs

    built, refusals = 0, []
    for p in designs(24, seed=5, lpp=150.0):
        try:
            h = fl.design_hull(**p).ship_hydrostatics()
        except fl.InfeasibleFormParameters as e:
            refusals.append((p, str(e)))
            continue
        assert h["volume"] == pytest.approx(_asked(p), rel=1e-4), p
        assert abs(h["lcb"] - p["lcb"]) <= 1e-4 * p["lpp"], p
        built += 1
    for p, msg in refusals:
        assert re.search(r"\b(give|move|lower|raise|change)\b", msg), (p, msg)
    assert built >= 21, (built, refusals)


@pytest.mark.parametrize("p", [
    dict(lpp=150.0, breadth=36.701, draft=11.138, depth=17.821, cb=0.641, lcb=77.56),  # L/B 4.1: beamy
    dict(lpp=150.0, breadth=16.714, draft=5.82, depth=9.312, cb=0.774, lcb=70.381),  # L/B 9.0: slender
])
def test_a_designed_bulb_fits_short_beamy_and_long_slender_ships(p):
    """The default Kracht coefficients ask a short, beamy ship's bulb for sections fuller than
    a superellipse can be (and a long, slender one's for sections too lean); the designer sizes
    the bulb's lateral area to the nearest it can have, and the ship composes watertight with
    its bulb and blend."""
    c = fl.design_hull(**p, bulb=True).composed_hull()
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    assert c.blend is not None


def test_latin_hypercube_with_bulbs_all_compose():
    """Every designed ship of the space with a bulb composes: bare hull, bulb and blend."""
    fails = []
    for p in _space_sample(40, 7):
        try:
            fl.design_hull(**p, bulb=True).composed_hull()
        except fl.InvalidInput as e:
            fails.append((p, str(e)[:80]))
    assert fails == []


def test_the_stem_is_not_a_knife():
    """A full ship with its LCB aft (Cb 0.79, LCB -3.1 % Lpp): its fairest waterline would run
    into the stem tangentially (0.8 deg), leaving the stem 2-5 cm thick a metre aft of its edge
    (a bulb's top then grazes it). Measured on the surface's own waterlines from half draught
    to the DWL: a metre aft of the stem each is at least as wide as a 5 deg half angle."""
    p = dict(lpp=150.0, breadth=27.6288, draft=9.4897, depth=15.1834, cb=0.7892, lcb=70.4057)
    s = fl.design_hull(**p).bare_hull_surface()
    for z in np.linspace(0.5, 1.0, 6) * p["draft"]:
        cut = np.asarray(fl.plane_cut(s, 2, float(z), 2001).points)
        cut = cut[np.argsort(cut[:, 0])]
        stem = cut[-1, 0]
        assert np.interp(stem - 1.0, cut[:, 0], cut[:, 1]) >= math.tan(math.radians(5.0)), z


def test_a_bulb_that_would_leave_a_fine_forefoot_again_runs_further_aft():
    """L/B 7.0, Cb 0.635: at the designer's usual aft length the bulb leaves the fine forefoot
    and meets the hull in two curves; the designer runs it further aft and the ship composes.
    (Found by a search of nearby particulars; the L/B 7.1, Cb 0.625 ship it was first shown on
    meets the hull in one curve at the usual length since flared sections' corner takes a share
    of their area.)"""
    hull = fl.design_hull(lpp=150.0, breadth=21.357, draft=7.33, depth=11.594, cb=0.635, lcb=67.624, bulb=True)
    k, shape = hull.description.bulb.kracht, hull.description.bulb.shape
    assert shape["aft_length"] > 2.6 * (k["c_lpr"] * 150.0 + k["c_bb"] * 21.357)
    assert edge_census(hull.composed_hull().mesh.faces) == (0, 0, 0)


def test_a_bulb_and_a_sonar_dome_under_its_forefoot_build_with_the_dome_aft_of_the_blend():
    """A cruiser-sterned coaster with a bulb and a sonar dome: with the dome's nose where the
    keel's flat ends, the bulb meets hull and dome in a seam that turns back at every aft length
    (design_hull refused it). With the nose aft of where the blend of the same ship without a
    dome starts (designer.DOME_BLEND_CLEARANCE) it builds, meets its particulars and composes
    closed, its mesh crossing itself nowhere."""
    from blend_fixtures import FOLD_DEG, largest_normal_turn_deg
    from mesh_fixtures import self_intersections

    p = dict(lpp=118.6, breadth=14.28, draft=5.9, depth=7.77, cb=0.59, lcb=55.44, stern="cruiser", bulb=True,
             skeg=True, sonar_dome=True)
    hull = fl.design_hull(**p)
    assert hull.ship_hydrostatics()["volume"] == pytest.approx(p["cb"] * p["lpp"] * p["breadth"] * p["draft"],
                                                         rel=ship_tol(hull, 1e-5))
    c = hull.composed_hull()
    assert c.blend is not None and largest_normal_turn_deg(c.blend) < FOLD_DEG
    blend = np.asarray(c.blend.evaluate_grid(np.linspace(0, 1, 81), np.linspace(0, 1, 21))).reshape(-1, 3)
    assert blend[:, 0].min() > hull.description.dome.x_fore
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    assert self_intersections(c.mesh) == []


#: Fine bulbed ships of bench_design_options (designs 11, 325, 174, 312; rounded) whose blend's
#: boundary on the hull heads straight for the centre plane over a stretch: the rows turned off
#: the plane to whichever side the sign of a near-zero product said, flipping between
#: neighbouring sections, and the blend pleated across its whole width (normal turns of 176-180
#: deg; design 11's composed mesh crossed itself in one pair of faces).
PLEATED = {
    "79 m, raked stem and transom": dict(lpp=78.716, breadth=10.254, draft=2.368, depth=4.536, cb=0.502, lcb=36.948,
                                         bulb=True, parallel_length=0.0, stem_rake=13.789, transom_rake=17.261),
    "250 m, no parallel body": dict(lpp=249.579, breadth=29.863, draft=6.781, depth=13.975, cb=0.525, lcb=122.231,
                                    bulb=True, parallel_length=0.0),
    "73 m with a skeg": dict(lpp=72.643, breadth=8.159, draft=2.4, depth=3.14, cb=0.588, lcb=34.197, bulb=True,
                             skeg=True, parallel_length=0.0),
    # design 312: with the turn fading out over |e . d| < 0.15 instead of 0.3 the rows turned faster
    # than the boundary's direction and it still folded (115 deg)
    "262 m, cruiser stern": dict(lpp=261.68, breadth=29.667, draft=6.967, depth=15.145, cb=0.52, lcb=122.358,
                                 stern="cruiser", bulb=True),
}


@pytest.mark.parametrize("name", list(PLEATED))
def test_a_blend_whose_boundary_heads_for_the_centre_plane_does_not_pleat(name):
    from blend_fixtures import FOLD_DEG, largest_normal_turn_deg
    from mesh_fixtures import self_intersections

    c = fl.design_hull(**PLEATED[name]).composed_hull()
    assert largest_normal_turn_deg(c.blend) < FOLD_DEG
    assert self_intersections(c.mesh) == []


def test_a_fine_ship_with_a_short_parallel_body_and_lcb_at_midships_builds():
    """Cb 0.50 with 6 m of parallel body and the LCB at midships: the default immersed transom
    (0.7 B/2) leaves the ends too full for the LCB; the designer narrows it."""
    hull = fl.design_hull(lpp=140, breadth=17, draft=5.5, depth=9, cb=0.50, lcb=70.0, parallel_length=6.0)
    h = hull.hydrostatics()
    assert h.volume == pytest.approx(0.50 * 140 * 17 * 5.5, rel=1e-4)
    assert hull.basic_curves["dwl"](hull.description.x_aft)[0] < 0.7 * 17 / 2


# Fine ships with a long given parallel body (bench_hull.sample_given_parallel(200), ships 27 and 9,
# rounded; the deep one's parallel body 42.07 -> 44 -> 45 m since the knob reads the natural leg and
# the transom is narrowed until the run is convex, with each of which the full-size bulb met the
# shorter one): the designer's full-size bulb meets their short
# entrance in two curves, or in a seam that turns back round it, at every aft length.
SHORT_ENTRANCE = {
    "slender": dict(lpp=150.0, breadth=16.944, draft=6.756, depth=10.809, cb=0.513, lcb=73.404, parallel_length=44.08),
    "deep": dict(lpp=150.0, breadth=32.651, draft=16.026, depth=25.642, cb=0.545, lcb=69.09, parallel_length=45.0),
}


@pytest.mark.parametrize("name", list(SHORT_ENTRANCE))
def test_a_bulb_too_large_for_a_short_entrance_is_made_smaller_and_the_ship_composes(name):
    """Such a ship was refused ("the bulb cannot meet the hull in one seam: give bulb=False or a
    smaller bulb") though a smaller bulb meets it: the designer now tries its bulb at
    BULB_SCALE_RETRIES of its size, names the size in the notes, and the composed ship is
    watertight and holds the asked volume and LCB."""
    from fairlines.designer import _kracht_defaults

    p = SHORT_ENTRANCE[name]
    hull = fl.design_hull(**p, bulb=True)
    scale = float(re.search(r"the bulb ([\d.]+) of the designer's size", hull.description.notes).group(1))
    assert scale < 1.0
    assert hull.description.bulb.kracht["c_bb"] == pytest.approx(scale * _kracht_defaults()["c_bb"])
    c = hull.composed_hull()
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    h = hull.ship_hydrostatics()
    assert h["volume"] == pytest.approx(_asked(p), rel=1e-4)
    assert abs(h["lcb"] - p["lcb"]) <= 1e-4 * p["lpp"]
    assert fl.Hull.from_json(hull.to_json()).description.bulb.kracht == hull.description.bulb.kracht


def test_a_given_bulb_too_large_for_a_short_entrance_keeps_its_size_and_is_refused():
    """Kracht coefficients the user gave are the user's: the designer does not shrink them, and
    the refusal names what to give."""
    from fairlines.designer import _kracht_defaults

    with pytest.raises(fl.InfeasibleFormParameters, match=r"cannot meet the hull in one seam .*give bulb=False, a smaller bulb"):
        fl.design_hull(**SHORT_ENTRANCE["slender"], bulb={"kracht": dict(_kracht_defaults())})


def test_too_long_a_parallel_body_on_a_fine_ship_asks_for_a_shorter_one():
    """Cb 0.51 with 30 % Lpp of parallel body: the ends would need a prismatic of 0.35, which
    no fair SAC within the sections' fullness holds; the message says which way to go and how
    far (the length that leaves the ends a prismatic of FINE_ENDS_CP), and that length builds."""
    from fairlines.designer import FINE_ENDS_CP

    p = dict(lpp=150, breadth=19.531, draft=6.807, depth=10.891, cb=0.51, lcb=71.837)
    with pytest.raises(fl.InfeasibleFormParameters, match=r"prismatic coefficient of 0\.347: give a shorter parallel_length") as e:
        fl.design_hull(**p, parallel_length=44.37)
    shorter = float(re.search(r"parallel_length \(at most ([\d.]+) m leaves them 0\.45\)", str(e.value)).group(1))
    cp = p["cb"] / float(re.search(r"cm ([\d.]+)", str(e.value)).group(1))  # the Cm the designer took
    assert shorter == pytest.approx((cp - FINE_ENDS_CP) / (1 - FINE_ENDS_CP) * p["lpp"], rel=1e-3)
    hull = fl.design_hull(**p, parallel_length=shorter)
    assert hull.ship_hydrostatics()["cb"] == pytest.approx(p["cb"], rel=1e-4)


def test_a_fine_waterplane_over_a_full_body_builds_with_the_keel_rising_over_less_of_the_run(monkeypatch):
    """Cwp 10 % below the designer's own (0.846 -> 0.762) under Cb 0.70, a vertical prismatic
    of 0.918 (hull 7 of bench_design_edits.py's 60, bench_hull.sample(60), rounded): the ends held the volume only once the
    keel's flat ran further aft (designer.KEEL_RISE_RETRIES; refused without them). Built, it
    meets volume, LCB and Cwp, and the keel leaves the base aft of where the default rise puts it."""
    from fairlines import designer

    p = dict(lpp=188.92, breadth=31.71, draft=10.91, depth=17.45, cb=0.70, lcb=95.34, cwp=0.762)
    hull = fl.design_hull(**p)
    h = hull.hydrostatics()
    assert h.volume == pytest.approx(_asked(p), rel=MATCH_TOL)
    assert h.cwp == pytest.approx(p["cwp"], rel=MATCH_TOL)
    assert abs(h.lcb - p["lcb"]) <= MATCH_TOL * p["lpp"]
    keel_flat = json.loads(hull.to_json())["basic_curves"]["profile"]["flat_from"]
    default_flat = designer.design_description(designer.Particulars(**p))["basic_curves"]["profile"]["flat_from"]
    assert keel_flat < default_flat - 0.01 * p["lpp"]
    monkeypatch.setattr(designer, "KEEL_RISE_RETRIES", ())
    with pytest.raises(fl.InfeasibleFormParameters, match=r"the ends cannot hold this volume"):
        fl.design_hull(**p)


def test_a_waterplane_too_fine_for_the_volume_names_a_cwp_that_builds():
    """The coaster with Cwp 10 % below its own (0.876 -> 0.788, a vertical prismatic of 0.95)
    is refused; the message names a Cwp that builds, and it does."""
    p = {**SHIPS["coaster_cruiser"], "cwp": 0.788}
    with pytest.raises(fl.InfeasibleFormParameters, match=r"cwp (0\.\d+) builds \(asked 0\.788\)") as info:
        fl.design_hull(**p)
    cwp = float(re.search(r"cwp (0\.\d+) builds", str(info.value)).group(1))
    assert 0.788 < cwp < 0.876
    assert fl.design_hull(**{**p, "cwp": cwp}).hydrostatics().cwp == pytest.approx(cwp, rel=MATCH_TOL)


def test_a_design_whose_matching_stalls_is_refused_not_returned(monkeypatch):
    """A hull the matching leaves off its particulars by more than MATCH_REFUSE is refused
    naming the SAC and the miss (one rebuild leaves the container ship 4.3e-4 off its volume), not
    returned as designed: bench_hull's parallel-body sample 169 came back 1.2e-4 off. (The
    designer's last fallbacks, a shorter keel rise, do match within one rebuild: left out.)"""
    from fairlines import designer

    monkeypatch.setattr(designer, "MATCH_ITERATIONS", 1)
    monkeypatch.setattr(designer, "KEEL_RISE_RETRIES", ())
    with pytest.raises(fl.InfeasibleFormParameters, match=r"basic_curves\.sac: the surface stays off the asked volume"):
        fl.design_hull(**SHIPS["container"])


def test_a_deep_full_ship_is_refused_naming_a_depth_that_builds():
    """A full coaster (Cb 0.847, Cm 0.99) 2.6 draughts deep: its sections' knot spans below the
    waterline are too few to hold the near-box midship sections the SAC asks. The refusal
    names a depth that builds (the message named only lcb, cb, cm and cwp), and it does."""
    p = dict(lpp=88.15, breadth=14.02, draft=6.41, depth=16.67, cb=0.847, lcb=45.42)
    with pytest.raises(fl.InfeasibleFormParameters, match=r"depth (\d+\.\d+) m builds \(asked 16\.67 m\)") as info:
        fl.design_hull(**p)
    depth = float(re.search(r"depth (\d+\.\d+) m builds", str(info.value)).group(1))
    assert 1.6 * 6.41 < depth < 16.67
    assert fl.design_hull(**{**p, "depth": depth}).hydrostatics().volume == pytest.approx(_asked(p), rel=MATCH_TOL)


def test_an_impossible_request_names_the_particulars_to_change():
    """A full ship with its LCB 4 % Lpp forward, no parallel body and a waterplane barely
    fuller than its block: its ends cannot hold the volume. The message names the particulars
    and what to change, then the solver's own reason."""
    with pytest.raises(fl.InfeasibleFormParameters, match=r"cwp 0\.88.*ends cannot hold.*parallel_length.*basic_curves\.sac"):
        fl.design_hull(lpp=150, breadth=25, draft=9, depth=14, cb=0.87, lcb=81, cwp=0.88, parallel_length=0.0)


def _edited(ship: str, curve: str, key: str, factor: float):
    d = json.loads(fl.design_hull(**SHIPS[ship]).to_json())
    d["basic_curves"][curve][key] *= factor
    return d


def _hydrostatics_of(d):
    return fl.Hull.from_json(json.dumps(d)).hydrostatics()


@pytest.mark.parametrize("ship", ["container", "fine_ferry"])
@pytest.mark.parametrize("curve, key, factor", [("sac", "volume", 0.9), ("sac", "volume", 1.1),
                                                ("dwl", "waterplane_area", 0.9), ("dwl", "waterplane_area", 1.1)])
def test_a_ten_percent_edit_of_a_designed_description_builds(ship, curve, key, factor):
    """Volume or waterplane area changed 10 % in the description of a built design (the other
    curves as they were): the hull builds and its surface follows the change."""
    base = _hydrostatics_of(json.loads(fl.design_hull(**SHIPS[ship]).to_json()))
    h = _hydrostatics_of(_edited(ship, curve, key, factor))
    got = h.volume / base.volume if curve == "sac" else h.cwp / base.cwp
    assert got == pytest.approx(factor, rel=2e-3)


def test_a_waterline_widened_onto_the_half_breadth_keeps_its_deck():
    """A fine 71 m ship's waterplane area raised 10 % (Cwp 0.75 -> 0.82): its waterline then runs
    at B/2 forward of the deck's flat part, rounded past it by 1e-15 m, and the deck, which may
    not pass B/2, was asked to clear that (refused: 'deck ... contradict each other'). It builds,
    with the waterplane asked and the deck clear of the waterline (to 1e-6 B: 0.016 mm)."""

    p = dict(lpp=70.8, breadth=12.15, draft=5.13, depth=8.2, cb=0.537, lcb=36.89)
    d = json.loads(fl.design_hull(**p).to_json())
    area = 1.1 * d["basic_curves"]["dwl"]["waterplane_area"]
    d["basic_curves"]["dwl"]["waterplane_area"] = area
    hull = fl.Hull.from_json(json.dumps(d))
    assert hull.hydrostatics().waterplane_area == pytest.approx(area, rel=2e-3)
    assert _deck_clearance(hull) >= -1e-6 * p["breadth"]


def _deck_clearance(hull) -> float:
    """Least (deck line - design waterline) half-breadth, m, every 1 cm or so of the waterline."""
    curves = hull.basic_curves
    xs = np.linspace(*hull.immersed_range(), 20001)
    return float(np.min(np.ravel(curves["deck"](xs)) - np.ravel(curves["dwl"](xs))))


@pytest.mark.parametrize("p", [SHIPS["tanker"], dict(lpp=272.759, breadth=56.312, draft=14.094, depth=22.551, cb=0.812,
                                                    lcb=145.348)], ids=["tanker", "full_273m"])
def test_the_deck_line_clears_the_waterline_between_its_checks(p):
    """Designed to clear the waterline at DECK_CHECKS points, the deck line dipped inside it
    between them: 0.17 mm on the tanker, 5.3 mm on a full 273 m ship of 56 m beam. Where a close
    look finds it inside, checks are added there: within 1e-6 B."""
    assert _deck_clearance(fl.design_hull(**p)) >= -1e-6 * p["breadth"]


def test_a_volume_cut_the_bands_margin_refused_builds_near_the_v():
    """A 139 m ship of Cb 0.77 with its volume cut 10 % and its waterline, flat parts and profile
    kept: its ends must be nearly V-shaped. Within the fullness bands shrunk by BAND_MARGIN no SAC
    holds that (refused, naming 10 024 m^3 at its LCB the least); within RELAXED_BAND_MARGIN one does, so
    it builds, with the asked volume and LCB and the waterplane it had."""
    p = dict(lpp=139.38, breadth=16.33, draft=6.32, depth=10.1, cb=0.77, lcb=65.19)
    hull = fl.design_hull(**p)
    d = json.loads(hull.to_json())
    volume = 0.9 * d["basic_curves"]["sac"]["volume"]
    d["basic_curves"]["sac"]["volume"] = volume
    h = fl.Hull.from_json(json.dumps(d)).hydrostatics()
    assert h.volume == pytest.approx(volume, rel=2e-3)
    assert abs(h.lcb - d["basic_curves"]["sac"]["lcb"]) <= 1e-3 * p["lpp"]
    assert h.cwp == pytest.approx(hull.hydrostatics().cwp, rel=2e-3)


@pytest.mark.parametrize("ship", ["container", "tanker"])
@pytest.mark.parametrize("shift", [-0.01, 0.01])
def test_a_one_percent_lcb_edit_of_a_designed_description_builds(ship, shift):
    d = json.loads(fl.design_hull(**SHIPS[ship]).to_json())
    base = _hydrostatics_of(d).lcb
    d["basic_curves"]["sac"]["lcb"] += shift * SHIPS[ship]["lpp"]
    assert _hydrostatics_of(d).lcb - base == pytest.approx(shift * SHIPS[ship]["lpp"], abs=2e-3 * SHIPS[ship]["lpp"])


def test_an_edited_volume_too_large_names_the_volumes_that_build_and_they_do():
    """The tanker's SAC volume raised 10 % in its description (Cb 0.82 -> 0.90 with its flat part
    and waterline kept): refused, naming the volumes its sections hold at its LCB; the top of
    that range builds, a little above it does not."""
    d = _edited("tanker", "sac", "volume", 1.10)
    with pytest.raises(fl.InfeasibleFormParameters, match=r"basic_curves\.sac: volume .* cannot be met") as info:
        _hydrostatics_of(d)
    msg = str(info.value)
    assert "contradict" not in msg  # no list of solver conditions
    lo, hi = map(float, re.search(r"with the LCB at [\d.]+ m, ([\d.]+) to ([\d.]+) m\^3", msg).groups())
    assert lo < hi < d["basic_curves"]["sac"]["volume"]
    d["basic_curves"]["sac"]["volume"] = hi * (1 - 1e-3)
    assert _hydrostatics_of(d).volume == pytest.approx(hi * (1 - 1e-3), rel=2e-3)
    d["basic_curves"]["sac"]["volume"] = hi * (1 + 1e-3)
    with pytest.raises(fl.InfeasibleFormParameters):
        _hydrostatics_of(d)


def test_an_edited_waterplane_too_large_names_the_areas_that_build_and_they_do():
    """The tanker's waterplane area raised 10 % (Cwp 0.92 -> 1.01, more than its rectangle):
    refused, naming the areas a waterline with its LCF can have; the top of them builds."""
    d = _edited("tanker", "dwl", "waterplane_area", 1.10)
    with pytest.raises(fl.InfeasibleFormParameters, match=r"basic_curves\.dwl.*give basic_curves\.dwl\.waterplane_area") as info:
        _hydrostatics_of(d)
    lo, hi = map(float, re.search(r"with its centroid at [\d.]+ m, ([\d.]+) to ([\d.]+) m\^2", str(info.value)).groups())
    assert hi < 180.0 * 32.0  # inside the rectangle Lpp B
    d["basic_curves"]["dwl"]["waterplane_area"] = hi * (1 - 1e-3)
    assert fl.Hull.from_json(json.dumps(d)).basic_curves["dwl"].integral() == pytest.approx(0.5 * hi * (1 - 1e-3), rel=1e-6)


def test_a_sac_flat_part_past_the_waterlines_is_refused_naming_it():
    """The SAC's flat part moved past the DWL's (found by fuzzing descriptions: it raised an
    UnboundLocalError). A flat SAC needs a constant box there; the message says so."""
    d = _edited("coaster_cruiser", "sac", "flat_to", 1.44)
    with pytest.raises(fl.InfeasibleFormParameters, match=r"basic_curves\.sac: the flat part .* needs a constant box"):
        _hydrostatics_of(d)


@pytest.mark.parametrize("bad, field", [(dict(cb=1.2), "cb"), (dict(lpp=244800.0), "millimetres"),
                                        (dict(draft=25.0), "draft"), (dict(stern="pram"), "stern"),
                                        (dict(lcb=0.0), "lcb_pct"), (dict(breadth=float("nan")), "breadth"),
                                        (dict(lcf=300.0), "lcf"), (dict(parallel_length=-5.0), "parallel_length"),
                                        (dict(transom_immersion=float("nan")), "transom_immersion"),
                                        (dict(transom_breadth=20.0), "transom_breadth is 20.0; expected a waterline"),
                                        (dict(bredth=32.0), "did you mean 'breadth'"), (dict(bulb="yes"), "bulb is 'yes'"),
                                        (dict(stem_rake="20"), "stem_rake is '20'")])
def test_bad_particulars_name_the_value(bad, field):
    with pytest.raises(fl.InvalidInput, match=field):
        fl.design_hull(**{**SHIPS["container"], **bad})


def test_missing_particulars_are_named():
    p = {k: v for k, v in SHIPS["container"].items() if k not in ("lcb", "depth")}
    with pytest.raises(fl.InvalidInput, match=r"depth, lcb are missing; expected lpp, breadth, draft, depth \(m\), cb and lcb"):
        fl.design_hull(**p)


def test_sections_asked_off_the_hull_are_named_not_listed():
    """Asking sections at 401 stations of which 3 lie beyond the stem names those three and the
    hull's range (the message once listed all 401)."""
    hull = fl.design_hull(**SHIPS["coaster_cruiser"])
    d = hull.description
    xs = np.append(np.linspace(d.x_aft, d.x_fore, 398), d.x_fore + np.array([1.0, 2.0, 3.0]))
    with pytest.raises(fl.InvalidInput) as info:
        hull.sections_at(xs)
    msg = str(info.value)
    assert f"x is {d.x_fore + 1:g}, {d.x_fore + 2:g}, {d.x_fore + 3:g} m (3 of 401 stations off the hull)" in msg
    assert f"{d.x_aft:g} to {d.x_fore:g} m" in msg and len(msg) < 300


def _sign_changes(surface, axis, value):
    return judge_cut(fl.plane_cut(surface, axis, float(value), 601))["sign_changes"]


@pytest.fixture(scope="module")
def example_surface():
    return fl.Hull.from_json(EXAMPLE.read_text()).bare_hull_surface()


@pytest.fixture(scope="module")
def tanker_surface():
    return fl.design_hull(**SHIPS["tanker"]).bare_hull_surface()


def _cuts(values, short: dict):
    """One test case per cut; the cuts the designer does not yet draw fair are strict xfails
    with what was measured on them."""
    return [pytest.param(v, marks=pytest.mark.xfail(strict=True, reason=short[v])) if v in short else v
            for v in map(float, values)]


def test_frames_from_the_midbody_to_the_stem_are_convex(example_surface):
    for x in np.linspace(70.0, 240.0, 18):
        assert _sign_changes(example_surface, 0, x) == 0, x


def test_no_s_shaped_frames(example_surface):
    for x in np.linspace(10.0, 230.0, 23):
        assert _sign_changes(example_surface, 0, x) == 0, x


def test_the_fine_ferrys_aft_sections_are_convex():
    """The fine ferry's frames from its immersed transom to midships turn one way (no sign
    change over 0.1 deg). With its deck at 0.92 B/2 over a waterline of 0.51 B/2 at the transom
    (a flare of 37 deg over the freeboard) those at 6-28 % Lpp were S-shaped: a convex bilge
    under a hollow topside (inflections at 0.89-1.06 T)."""
    p = SHIPS["fine_ferry"]
    surface = fl.design_hull(**p).bare_hull_surface()
    for x in np.linspace(0.0, 0.5 * p["lpp"], 15):
        assert _sign_changes(surface, 0, x) == 0, x


def _first_frame_inflected_above_t(surface, xs, draft: float) -> list:
    """(x, [z of its inflections above T]) of the first frame at xs (m) that has one; [] when none
    has (m)."""
    for x in xs:
        cut = fl.plane_cut(surface, 0, float(x), 801)
        above = [round(i["at"][2], 2) for i in judge_cut(cut)["inflections"] if i["at"][2] > draft]
        if above:
            return [round(float(x), 2), above]
    return []


def test_a_fine_ships_aft_frames_turn_one_way_above_the_waterline():
    """A fine 234 m ship (Cb 0.51; hull 136 of bench_hull's sample(300), rounded): its frames at
    5-30 % Lpp have no inflection above T. While the design waterline's fairness was its
    curvature's square alone (designer.DWL_E3 = 0), four of them turned hollow above T
    (inflections at 1.06-1.11 T)."""
    p = dict(lpp=233.892, breadth=35.461, draft=8.518, depth=13.629, cb=0.508, lcb=113.868)
    surface = fl.design_hull(**p).bare_hull_surface()
    assert _first_frame_inflected_above_t(surface, np.linspace(0.05, 0.3, 26) * p["lpp"], p["draft"]) == []


#: Measured shortfalls of the aft frames (test_frames_aft_of_five_percent_turn_one_way_above_the_waterline):
#: none since the deck at a dry transom leans no more than the sections there (designer.DRY_TRANSOM_LEAN_MARGIN;
#: before, the tanker's frames at x -1..8 m had a hollow topside of 0.1-4.1 deg above an inflection at T).
AFT_FRAMES_SHORT: dict = {}
#: Ships of bench_hull's sample (hulls 1, 22, 29 and 71 of sample(100), rounded) whose frames aft of
#: 5 % Lpp had an S above T of 1.7-2.4 deg (the smaller lobe) under a deck of 0.92 B/2 at their dry transom.
DRY_TRANSOM_SAMPLE = {
    "hull_1": dict(lpp=74.06, breadth=11.664, draft=3.281, depth=5.25, cb=0.639, lcb=37.571),
    "hull_22": dict(lpp=193.277, breadth=33.334, draft=10.326, depth=16.522, cb=0.624, lcb=99.23),
    "hull_29": dict(lpp=240.705, breadth=33.068, draft=13.203, depth=21.125, cb=0.649, lcb=125.333),
    "hull_71": dict(lpp=188.623, breadth=21.84, draft=7.632, depth=12.211, cb=0.727, lcb=98.658),
}


def _aft_frame_inflections_above_t(hull) -> list:
    """_first_frame_inflected_above_t over the frames from 0.2 % Lpp forward of the aft end to
    5 % Lpp (12 frames)."""
    pr = hull.description.principal
    xs = np.linspace(hull.description.x_aft + 0.002 * pr.lpp, 0.05 * pr.lpp, 12)
    return _first_frame_inflected_above_t(hull.bare_hull_surface(), xs, pr.draft)


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.xfail(strict=True, reason=AFT_FRAMES_SHORT[n]))
                                  if n in AFT_FRAMES_SHORT else n for n in SHIPS])
def test_frames_aft_of_five_percent_turn_one_way_above_the_waterline(name):
    """The frames from 0.2 % Lpp forward of the aft end to 5 % Lpp (the ones bench_fairness_space's
    19 frames leave out) have no inflection above T: a topside there turns one way."""
    assert _aft_frame_inflections_above_t(fl.design_hull(**SHIPS[name])) == []


@pytest.mark.parametrize("name", list(DRY_TRANSOM_SAMPLE))
def test_frames_over_a_dry_transom_turn_one_way_above_the_waterline(name):
    """Sampled ships with a dry transom: their frames aft of 5 % Lpp have no inflection above T
    (the deck there no wider than the sections lean, designer.DRY_TRANSOM_LEAN_MARGIN), and the
    deck at the transom is still at least DRY_TRANSOM_DECK_LEAST of B/2."""
    p = DRY_TRANSOM_SAMPLE[name]
    hull = fl.design_hull(**p)
    assert _aft_frame_inflections_above_t(hull) == []
    deck = hull.description.curves["deck"].to_dict()
    assert deck["yB"] >= DRY_TRANSOM_DECK_LEAST * p["breadth"] / 2 - 1e-9


def test_a_fine_ships_lower_waterlines_do_not_wobble_where_its_waterline_is_widest():
    """A fine ship without a parallel body (Cb 0.50, the waterline at B/2 only at midships):
    its T/4, T/2 and 0.74 T waterlines read as a lines plan have no wobble. While the SAC was
    fitted to the natural fullness up to the waterline's peak, it bent upward there and the T/4
    and T/2 waterlines took a wobble at 0.52 Lpp (0.42 and 0.12 deg, hull 18 of bench_hull's
    sample(40))."""
    from fairlines.fairness import read_waterline

    p = dict(lpp=250.86, breadth=33.52, draft=10.09, depth=16.14, cb=0.50, lcb=128.61)
    surface = fl.design_hull(**p).bare_hull_surface()
    for f in (0.25, 0.5, 0.74):
        read = read_waterline(fl.plane_cut(surface, 2, f * p["draft"], 601))
        assert not read["wobbles"], (f, [(w["at"][0], w["turn_deg"]) for w in read["wobbles"]])


# Sampled ships (bench_hull's sample(100) hulls 19, 52, 87, 100 and sample(150) hulls 106, 128,
# rounded) and the height (fraction of T) of a lower waterline whose entrance over the forefoot
# had a wobble, convex lobes of 0.18-0.63 deg at 0.89-0.96 Lpp between hollows, while the shape
# knob met the area on the top corner drawn inside the deck edge (sections.cpp knob_template).
FOREFOOT_SAMPLE = {
    "hull_19": (dict(lpp=150.5, breadth=17.98, draft=4.93, depth=7.89, cb=0.715, lcb=78.99), 0.25),
    "hull_52": (dict(lpp=104.22, breadth=17.28, draft=4.25, depth=6.8, cb=0.741, lcb=54.11), 0.25),
    "hull_87": (dict(lpp=102.27, breadth=12.8, draft=3.46, depth=5.54, cb=0.654, lcb=54.13), 0.25),
    "hull_128": (dict(lpp=189.02, breadth=24.74, draft=7.02, depth=11.23, cb=0.811, lcb=98.57), 0.25),
    "hull_106": (dict(lpp=86.57, breadth=11.27, draft=3.02, depth=4.84, cb=0.702, lcb=44.26), 0.495),
    "hull_100": (dict(lpp=186.16, breadth=39.65, draft=11.41, depth=18.26, cb=0.625, lcb=99.34), 0.495),
}


@pytest.mark.parametrize("name", list(FOREFOOT_SAMPLE))
def test_a_lower_waterline_runs_over_the_forefoot_without_a_wobble(name):
    """A lower waterline of a sampled ship, cut from the bare hull, has at most two curvature
    sign changes over 0.1 deg (the bench's mark: one hollow each way) and reads fair as a lines
    plan; before, each had four."""
    from fairlines.fairness import read_waterline

    p, f = FOREFOOT_SAMPLE[name]
    cut = fl.plane_cut(fl.design_hull(**p).bare_hull_surface(), 2, f * p["draft"], 401)
    judged = judge_cut(cut)
    assert judged["sign_changes"] <= 2, [(lobe["at"][0] / p["lpp"], lobe["turn_deg"]) for lobe in judged["lobes"]]
    assert read_waterline(cut)["fair"]


# Fine ships of bench_fairness_space's sample (hulls 13, 18, 47, 56, 85, 96 of bench_hull.sample(100),
# rounded) with an immersed transom. While the design waterline took the widest transom that
# still widened to its peak, its run was hollow; the hollow carried down into the waterlines
# below T: at 0.495 T a hollow of 0.3-1.6 deg in the run between convex lobes (4-6 sign
# changes), at 0.985 T a convex lobe at the transom's end (3).
FINE_RUN_SAMPLE = {
    "hull_13": dict(lpp=157.57, breadth=22.72, draft=5.05, depth=8.09, cb=0.518, lcb=76.72),
    "hull_18": dict(lpp=253.13, breadth=49.7, draft=11.22, depth=17.95, cb=0.545, lcb=122.58),
    "hull_47": dict(lpp=169.92, breadth=25.4, draft=11.62, depth=18.59, cb=0.595, lcb=87.64),
    "hull_56": dict(lpp=227.06, breadth=25.61, draft=7.86, depth=12.57, cb=0.535, lcb=104.98),
    "hull_85": dict(lpp=189.13, breadth=27.76, draft=6.22, depth=9.95, cb=0.565, lcb=88.92),
    "hull_96": dict(lpp=250.49, breadth=34.05, draft=10.88, depth=17.4, cb=0.551, lcb=119.54),
}


@pytest.mark.parametrize("name", list(FINE_RUN_SAMPLE))
def test_a_fine_ship_s_waterlines_under_t_run_to_the_transom_without_a_hollow_wobble(name):
    """The waterlines at 0.495 T and 0.985 T of a fine sampled ship, cut from the bare hull, each
    have at most two curvature sign changes over 0.1 deg (the bench's mark) and read fair as a
    lines plan; before, each ship failed one of them."""
    from fairlines.fairness import read_waterline

    p = FINE_RUN_SAMPLE[name]
    surface = fl.design_hull(**p).bare_hull_surface()
    for f in (0.495, 0.985):
        cut = fl.plane_cut(surface, 2, f * p["draft"], 401)
        judged = judge_cut(cut)
        assert judged["sign_changes"] <= 2, (f, [(lobe["at"][0] / p["lpp"], lobe["turn_deg"]) for lobe in judged["lobes"]])
        assert read_waterline(cut)["fair"], f


WOBBLY_WATERLINES: dict = {}


# The design waterline weighs its change of curvature (designer.DWL_E3): it still bends where it
# ends at the FP (the tanker's curvature there -0.11 1/m, about 0 with the curvature's square alone),
# and a waterline just above T takes a sub-degree wobble in its last metre. Kept for what DWL_E3 gives
# over bench_fairness_space's 300 hulls: S frames above T on 19 -> 6 hulls, frame inflections 210 -> 151.
STEM_TIP_SHORT = {
    ("container", 0.25): "a hollow of 0.56 deg at x 245.17 m then a convex lobe of 0.21 deg at 245.49 m (z 13 m, 2 m above T), "
                         "the waterline's last 0.6 m over the stem (a hollow of 0.40 and a convex lobe of 0.25 deg before the "
                         "forward deck followed the waterline as smoothstep^0.4, designer.DECK_FOLLOW_POWER)",
    ("fine_ferry", 0.25): "a hollow of 0.20 deg at x 140.19 m then a convex lobe of 0.18 deg at 140.37 m (z 6.6 m; 0.28 and 0.16 deg before 0180c0f narrowed the transom), the "
                          "waterline's last 0.4 m over the stem, since the forward deck follows the waterline's narrowing "
                          "as smoothstep^0.4 (designer.DECK_FOLLOW_POWER; one hollow of 0.25 deg with the smoothstep)",
}
# The tanker's waterlines just above T: one at the stem (11.9 m, as above; 13 m's stem tip is clean since
# kTopFilletFar), all three over the transom.
TANKER_SHORT = {
    12.5: "over the transom: a convex lobe of 0.52 deg at x -0.8 m between hollows of 1.50 and 1.00 deg (x -2.3 and 2.0 m; "
          "0.60 between 0.83 and 1.02 with the top corner at 0.5 of the freeboard and the top fillet's kFilletFar, "
          "designer.TOP_CORNER, sections.cpp kTopFilletFar); "
          "since the keel rises over 0.9 of the run (designer.KEEL_RISE) this waterline runs nearly straight into the "
          "transom (one hollow of 7.1 deg before), and its ripple reads as a wobble (0.45 between 0.73 and 0.94 deg "
          "with the bilge's fine weight 0.7, 0.48 between 0.69 and 1.13 with 0.5 and the transom's run of 3 % Lpp)",
    11.9: "a hollow lobe of 0.26 deg at x 179.8 m, 0.3 m aft of the stem (0.33 with the deck edge's blend over e^0.25, "
          "sections.cpp kDeckEdgeBlend; 0.30 before an immersed section's top corner was kept "
          "inside its deck edge, sections.cpp inside_deck_edge; 0.36 with the top corner at 0.5 and the top "
          "fillet's kFilletFar; 0.17 deg at x 179.2 m before the last two station spans aft of the FP were halved, "
          "hull.CLOSED_END_HALVED_SPANS); and since the bilge's fine weight is 0.5 (0.7 before), over the transom a "
          "convex lobe of 0.37 deg at x -0.1 m between hollows of 0.35 and 0.17 deg (x -2.0 and 2.3 m; 0.39 between 0.10 and "
          "0.27 before)",
    13.0: "over the transom a convex lobe of 0.41 deg at x -0.8 m between hollows of 2.16 and 1.33 deg (x -4.2 and 2.0 m), since the bilge's "
          "fine weight is 0.5 (0.7 before; 0.11 with the transom's run of 3 % Lpp, transom_run.RUN_LENGTH); its stem "
          "tip is clean since the top fillet's middle points lie at 0.68 of its legs (sections.cpp kTopFilletFar: a "
          "hollow of 0.11 deg and a convex lobe of 0.18 deg in the last 0.7 m with 0.611)",
}


@pytest.mark.parametrize("height", [0.25, 0.5, 0.75, 0.9])
def test_upper_waterlines_run_into_the_stem_without_an_inflection(ship, height, request):
    """Forward of the design waterline's fore end (over the stem's overhang) a waterline between
    T and D ends on the stem in one lobe, straight, hollow or convex, never an S. Measured before
    the dry sections there were read off the waterlines (fairlines.dry_ends): at 0.9 of the way
    to D the container ship's turned hollow then convex (0.28, 0.9 deg), the tanker's three times
    (4.8, 1.5, 4.4 deg), the ferry's twice (0.41, 1.23 deg)."""
    from fairlines.fairness import cut_lobes

    p, hull = ship
    name = request.node.callspec.params["ship"]
    if (name, height) in STEM_TIP_SHORT:
        request.applymarker(pytest.mark.xfail(strict=True, reason=STEM_TIP_SHORT[name, height]))
    x_end = hull.immersed_range()[1]
    z = p["draft"] + height * (p["depth"] - p["draft"])
    cut = fl.plane_cut(hull.bare_hull_surface(), 2, z, 801)
    over = np.asarray(cut.points)[:, 0] >= x_end
    lobes = cut_lobes(np.asarray(cut.points)[over], np.asarray(cut.curvature)[over])
    assert len(lobes) <= 1, [(round(lobe["turn_deg"], 2), lobe["sign"], round(lobe["at"][0], 2)) for lobe in lobes]


@pytest.mark.parametrize("height", [0.25, 0.5, 0.75])
def test_upper_waterlines_run_into_a_cruiser_stern_without_an_inflection(height):
    """Aft of the design waterline's aft end, over the coaster's cruiser-stern counter, a
    waterline between T and D ends on the centre plane in one lobe. Measured before the dry
    sections there were read off the waterlines too (fairlines.dry_ends): at 0.5 and 0.75 of
    the way to D it turned hollow, then convex (0.37 / 0.18 deg, 0.62 / 0.12 deg); at 0.9 a pair
    of 0.11 and 0.12 deg is left, at the threshold of the count."""
    from fairlines.fairness import cut_lobes

    p = SHIPS["coaster_cruiser"]
    hull = fl.design_hull(**p)
    z = p["draft"] + height * (p["depth"] - p["draft"])
    cut = fl.plane_cut(hull.bare_hull_surface(), 2, z, 801)
    over = np.asarray(cut.points)[:, 0] <= hull.immersed_range()[0]
    lobes = cut_lobes(np.asarray(cut.points)[over], np.asarray(cut.curvature)[over])
    assert len(lobes) <= 1, [(round(lobe["turn_deg"], 2), lobe["sign"], round(lobe["at"][0], 2)) for lobe in lobes]


def _assert_waterline_is_fair(surface, z):
    """Read as a lines plan (fairlines.fairness.read_waterline): no lobe under SMALL_LOBE_DEG
    between two others (a wobble) and at most one hollow in each half (a run, an entrance)."""
    from fairlines.fairness import read_waterline

    read = read_waterline(fl.plane_cut(surface, 2, float(z), 601))
    assert read["fair"], ([(round(lobe["turn_deg"], 2), lobe["sign"], round(lobe["at"][0], 1)) for lobe in read["wobbles"]],
                          read["hollows"])


def _aft_hollows(surface, z: float, lpp: float) -> list:
    """Turns (deg) of the hollow lobes of the waterline at z in the hull's aft half."""
    from fairlines.fairness import cut_lobes

    cut = fl.plane_cut(surface, 2, float(z), 801)
    points, curvature = np.asarray(cut.points), np.asarray(cut.curvature)
    aft = points[:, 0] < 0.5 * lpp
    return [round(lobe["turn_deg"], 2) for lobe in cut_lobes(points[aft], curvature[aft]) if lobe["sign"] > 0]


def test_the_lowest_waterlines_widen_through_the_run_in_one_sweep(example_surface):
    """Where the keel reaches the base before the sections' bilges fill, a low waterline grows,
    slows and grows again: a shoulder, a hollow and a shoulder a naval architect would fair. With
    the keel rising over 0.9 of the run the example's 2, 3 and 4 m waterlines are convex from
    their start to the midbody (the 2 m one held a hollow of 7.9 deg over 0.65 of it) and the 1 m
    one holds a hollow of 5.5 deg (15.7 before)."""
    lpp = 244.8
    for z in (2.0, 3.0, 4.0):
        assert _aft_hollows(example_surface, z, lpp) == [], z
    assert max(_aft_hollows(example_surface, 1.0, lpp)) < 8.0


@pytest.mark.parametrize("z", _cuts(np.linspace(1.0, 17.0, 9), WOBBLY_WATERLINES))
def test_waterline_has_no_wobble(example_surface, z):
    """No wobble and one hollow each way at most. A low waterline's rounded end where the keel
    lands on its flat and the bulb's nose are shape features like the body (1 m: lobes of 4-45
    deg, 4 sign changes); it was once read as at most 2 sign changes, which failed them."""
    _assert_waterline_is_fair(example_surface, z)


@pytest.mark.parametrize("name, side", [("tanker", "fore"), ("coaster_cruiser", "fore"), ("coaster_cruiser", "aft")])
def test_station_spans_inside_a_closed_end_are_halved(name, side):
    """Where the waterline closes on the stem (or a cruiser stern's counter) the last
    hull.CLOSED_END_HALVED_SPANS station spans toward it are halved (two equal halves each, the
    next span in whole): at the clustered spacing the skin rang there (the tanker's 12.5 m
    waterline turned hollow, convex, hollow in its last 0.9 m)."""
    from fairlines.hull import CLOSED_END_HALVED_SPANS as n

    hull = fl.design_hull(**SHIPS[name])
    x_end = hull.immersed_range()[1 if side == "fore" else 0]
    st = hull.stations()
    inward = np.sort(np.abs(st[(st - x_end) * (1 if side == "fore" else -1) <= 1e-6] - x_end))[:2 * n + 2]
    spans = np.diff(inward)  # from x_end inward: n spans halved, then the next one whole
    assert inward[0] < 1e-6, inward
    assert all(abs(spans[2 * k] - spans[2 * k + 1]) < 1e-9 for k in range(n)), spans
    assert spans[2 * n] > 1.5 * spans[2 * n - 1], spans


def test_halving_the_spans_inside_an_end_at_either_end_and_when_the_end_is_no_station():
    """hull._halved_inside on a row of stations: the fore and the aft end, an end between
    stations (halved up to the first station beyond it), an end within the tolerance of a
    station, a span already shorter than the least kept."""
    from fairlines.hull import _halved_inside

    st = np.array([0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 11.0])
    fore = _halved_inside(st, 8.0, 11.0, 2, 1e-9, 0.5)
    assert fore.tolist() == [0, 2, 4, 5, 6, 7, 8, 10, 11]
    assert _halved_inside(st, 2.0, 0.0, 2, 1e-9, 0.5).tolist() == [0, 2, 3, 4, 5, 6, 8, 10, 11]
    assert _halved_inside(st, 7.0, 11.0, 2, 1e-9, 0.5).tolist() == [0, 2, 4, 5, 6, 7, 8, 10, 11]
    assert _halved_inside(st, 8.0 + 1e-12, 11.0, 2, 1e-9, 0.5).tolist() == fore.tolist()
    assert _halved_inside(st, 12.0, 13.0, 2, 1e-9, 0.5).tolist() == st.tolist()  # no station beyond: unchanged
    assert _halved_inside(np.array([0.0, 2.0, 7.8, 8.0]), 8.0, 11.0, 2, 1e-9, 0.5).tolist() == [0, 2, 4.9, 7.8, 8]


@pytest.mark.parametrize("z", _cuts([11.9, 12.5, 13.0], TANKER_SHORT))
def test_tanker_waterline_over_its_transom_has_no_wobble(tanker_surface, z):
    """No wobble and one hollow each way at most in a waterline just above the tanker's DWL (at
    13 m its transom's convex edge, its run's hollow, the body and the stem's hollow tip)."""
    _assert_waterline_is_fair(tanker_surface, z)


def test_sections_change_smoothly_along_the_run():
    """The designed sections at any x (sections_at) change smoothly along the tanker's run: every
    2 cm over x -2..15 m, no control point's second difference along x exceeds 20 times its
    median there (a flicker of the construction, not a change of shape). The correction's flat
    guard read an inflection of the control polygon as straight for the moment it passed a
    control point: 6.2 mm, 450 times the median, every knot span at x 4-7 m."""
    hull = fl.design_hull(**SHIPS["tanker"])
    xs = np.arange(-2.0, 15.0, 0.02)
    P = np.array([np.asarray(c.control_points)[:, 1:] for c in hull.sections_at(xs)])
    d2 = np.linalg.norm(np.diff(P, 2, axis=0), axis=2)
    assert np.all(d2 <= 20.0 * np.median(d2, axis=0))


@pytest.mark.parametrize("y", np.linspace(2.0, 14.0, 7))
def test_buttock_has_no_steps(example_surface, y):
    """At most two sign changes. The outermost (y 14 m) turned back by 0.94 deg where it leaves
    the bilge aft (x 53-66 m) until the design waterline weighed its change of curvature
    (designer.DWL_E3), and by 0.49 deg at x 59 m with the designer's default flat of bottom until
    the keel rose over 0.9 of the run (designer.KEEL_RISE). Since then y 2-12 m took a hollow just
    above T between the transom's convex turn and the run's, where they cross T at a shallower
    angle: y 10 and 12 m lost it when the bilge's fine weight fell from 0.7 to 0.5, y 6 and 8 m
    (0.31 and 0.67 deg) when the sections' top corner rose to 0.55 of the freeboard
    (designer.TOP_CORNER), y 2 and 4 m (0.23 and 0.12 deg then) when the top fillet's middle
    points moved to 0.68 of its legs (sections.cpp kTopFilletFar): the top turns less just above T."""
    assert _sign_changes(example_surface, 1, y) <= 2


#: A full ship whose LCB lies far aft (bench_hull's sample 41 of 100: Cb 0.80, LCB -3.56 % Lpp).
FULL_AFT_LCB = dict(lpp=273.7608, breadth=37.397659, draft=16.743835, depth=26.790136, cb=0.80116602, lcb=127.13907)


@pytest.fixture(scope="module")
def full_aft_lcb_hull():
    return fl.design_hull(**FULL_AFT_LCB)


@pytest.mark.parametrize("share", [0.3, 0.5, 0.7])
def test_full_ships_buttocks_do_not_step_down_in_the_run(full_aft_lcb_hull, share):
    """Cut at share B/2, the buttock turns one way (hollow) from where it lands in the run to
    the parallel body (x 0.03-0.28 Lpp): no convex lobe there. Its SAC stood level over
    0.06-0.14 Lpp (the fullness's monotone bound met) and rose again, and these buttocks landed
    with the keel (a hollow of 44 deg at x 0.053 Lpp) and then stepped down: convex lobes of
    1.95 / 4.94 / 9.53 deg at x 0.17 Lpp, until the designer held the run's fullness convex
    (sac.convex_where_met; read on its description without it)."""
    L, B = FULL_AFT_LCB["lpp"], FULL_AFT_LCB["breadth"]
    cut = fl.plane_cut(full_aft_lcb_hull.bare_hull_surface(), 1, share * B / 2, 401)
    lobes = judge_cut(cut)["lobes"]
    hollow = max(lobes, key=lambda l: l["turn_deg"] if l["at"][0] < 0.3 * L else 0.0)["sign"]
    steps = [l for l in lobes if 0.03 * L < l["at"][0] < 0.28 * L and l["sign"] != hollow]
    assert not steps, [(round(l["turn_deg"], 2), round(l["at"][0] / L, 3)) for l in steps]


def test_full_ships_volume_cut_builds_without_the_runs_convex_fullness(full_aft_lcb_hull):
    """The description's volume 10 % less: the run's fullness cannot stay convex at that volume
    (an SAC whose fullness rises at least linearly from the keel's landing to the parallel body
    holds more), so it is dropped (convex_where_met) and the hull builds with the volume asked."""
    d = json.loads(full_aft_lcb_hull.to_json())
    assert d["basic_curves"]["sac"]["convex_where_met"]
    d["basic_curves"]["sac"]["volume"] *= 0.9
    assert fl.Hull.from_json(d).hydrostatics().volume == pytest.approx(d["basic_curves"]["sac"]["volume"], rel=2e-3)


def test_designed_hull_is_editable():
    hull = fl.design_hull(**SHIPS["tanker"])
    v0 = hull.hydrostatics().volume
    d = json.loads(hull.to_json())
    d["basic_curves"]["sac"]["volume"] *= 1.02
    edited = fl.Hull.from_json(d)
    assert edited.hydrostatics().volume == pytest.approx(1.02 * v0, rel=2e-3)
    assert math.isfinite(edited.hydrostatics().lcb)


def test_command_line_design_writes_a_description_that_rebuilds(tmp_path, capsys):
    from fairlines.cli import main

    out = tmp_path / "coaster.json"
    args = ["design", "--lpp", "100", "--breadth", "16", "--draft", "6", "--depth", "9", "--cb", "0.75", "--lcb", "51",
            "--stern", "cruiser", "-o", str(out)]
    assert main(args) == 0
    h = fl.Hull.from_json(out.read_text()).hydrostatics()
    assert h.volume == pytest.approx(0.75 * 100 * 16 * 6, rel=MATCH_TOL)
    assert main(args[:-2] + ["--cb", "1.5", "-o", str(out)]) == 2
    assert "cb is 1.5" in capsys.readouterr().err


def test_the_parallel_body_lies_where_asked():
    """The tanker's parallel body of 50 m centred 100 m from the AP: the surface's sectional
    area (hydrostatics, not the design's SAC) is the midship area along it, less 25 m beyond
    its ends (by 0.25 % aft, where the keel rising over 0.9 of the run leaves the run's sections a
    shallower box and the SAC stays full longer; 1.7 % forward), and nowhere more (no hump in
    the SAC)."""
    p = {**SHIPS["tanker"], "parallel_length": 50.0, "parallel_centre": 100.0}
    h = fl.design_hull(**p).hydrostatics(sac_stations=361)
    area = lambda x: float(np.interp(x, h.sac_x, h.sac_area))  # noqa: E731
    mid = area(100.0)
    assert all(area(x) == pytest.approx(mid, rel=1e-4) for x in np.linspace(76.0, 124.0, 13))
    assert area(50.0) < (1 - 1e-3) * mid and area(150.0) < 0.99 * mid
    assert np.max(h.sac_area) <= mid * (1 + 1e-4)


def test_hydrostatics_are_cached_until_the_hull_changes():
    hull = fl.Hull.from_json(EXAMPLE.read_text())
    a = hull.hydrostatics()
    assert hull.hydrostatics() is a
    assert hull.hydrostatics(midship_x=100.0) is not a
    hull.set("sac", "volume", 1.01 * a.volume)
    b = hull.hydrostatics()
    assert b.volume == pytest.approx(1.01 * a.volume, rel=2e-3)


def test_composed_hull_uses_the_blend_placement_the_designer_found():
    """design_hull checks that its bulb meets the hull in one seam (a blend placement); the
    composed hull uses that placement rather than finding it again, and is the hull composed
    with a placement found afresh."""
    from fairlines.compose import compose_with_blend

    hull = fl.design_hull(**SHIPS["container"])
    found = hull._placement[2] if hull._placement else None
    assert found is not None and hull.blend_placement() is found
    composed = hull.composed_hull()
    afresh = compose_with_blend(hull.bare_hull_surface(), fl.BulbousBow(**hull.ship_particulars(),
                                **hull.description.bulb.kracht, **hull.description.bulb.shape))
    assert np.array_equal(np.asarray(composed.mesh.vertices), np.asarray(afresh.mesh.vertices))
    assert composed.blend_note == afresh.blend_note


#: Ships of bench_hull's sample (hulls 37 and 127) whose waterline just under T took wobbles at the
#: stem's tip from the correction through the waterline point (sections.cpp, kCorrectionSmoothing 1:
#: a hollow and a convex lobe within 1.5 % Lpp of the fore end, 0.13 / 0.92 and 0.12 / 0.66 deg; none with 2).
TIP_SHIPS = {"217 m, Cb 0.64": dict(lpp=216.9472, breadth=24.9964, draft=10.3722, depth=16.5954, cb=0.6375, lcb=113.7989),
             "137 m, Cb 0.80": dict(lpp=137.0296, breadth=15.3594, draft=3.8063, depth=6.0901, cb=0.7995, lcb=66.4204)}


@pytest.mark.parametrize("name", TIP_SHIPS)
def test_waterline_under_t_runs_into_the_stem_without_a_wobble(name):
    """The waterline at 0.985 T, read as a lines plan (fairlines.fairness.read_waterline), has no
    wobble within 1.5 % Lpp of its fore end."""
    from fairlines.fairness import read_waterline

    p = TIP_SHIPS[name]
    cut = fl.plane_cut(fl.design_hull(**p).bare_hull_surface(), 2, 0.985 * p["draft"], 401)
    x_fore = np.asarray(cut.points)[:, 0].max()
    tip = [w for w in read_waterline(cut)["wobbles"] if x_fore - w["at"][0] < 0.015 * p["lpp"]]
    assert not tip, [(round(w["turn_deg"], 2), w["sign"], round(w["at"][0], 2)) for w in tip]


def test_a_steeply_raked_stem_head_stays_on_its_side_of_the_centre_plane():
    """A broad, deep ship with its stem raked 34 deg (design 215 of bench_design_options): where
    the rows meet at the stem head its skin folded 2.1 mm across the centre plane (x 280.5 m,
    z 43.3 m); kept at y >= 0 there (SkinOptions.y_nonnegative) no point of the bare hull lies
    across it."""
    p = dict(lpp=271.3987, breadth=58.0992, draft=27.8698, depth=55.3839, cb=0.7202, lcb=129.9507, skeg=True,
             stem_rake=34.3928)
    s = fl.design_hull(**p).bare_hull_surface()
    g = np.asarray(s.evaluate_grid(np.linspace(*s.domain_u, 400), np.linspace(*s.domain_v, 4000))).reshape(-1, 3)
    assert g[:, 1].min() >= 0.0


#: Full, beamy ships of bench_hull's sample(300) (rounded) whose dry transom's section rose over
#: the deck: the topside fillet's corner lay above it (hull 284: 1.23 m at x -2.5 m; 153: 0.90 m).
ABOVE_DECK = {
    "hull 284": dict(lpp=173.0, breadth=41.993, draft=10.666, depth=17.066, cb=0.83, lcb=93.034),
    "hull 153": dict(lpp=213.213, breadth=41.003, draft=11.936, depth=19.098, cb=0.843, lcb=114.202),
}


@pytest.mark.parametrize("name", list(ABOVE_DECK))
def test_no_section_rises_over_the_deck(name):
    """No point of the bare hull lies above the deck (D): the topside fillet's corner is kept
    below it (sections.cpp below_deck), so the section leaves the deck edge downward."""
    p = ABOVE_DECK[name]
    s = fl.design_hull(**p).bare_hull_surface()
    g = np.asarray(s.evaluate_grid(np.linspace(*s.domain_u, 400), np.linspace(*s.domain_v, 800))).reshape(-1, 3)
    assert g[:, 2].max() <= p["depth"] * (1.0 + 1e-9), (g[:, 2].max() - p["depth"], g[np.argmax(g[:, 2])])


def test_a_composed_hull_with_a_wide_transom_does_not_cut_itself():
    """A bulbed ship of bench_hull's compose sample (sample(200, seed=11), hull 120, rounded):
    its transom's section rose 1 cm over the deck near the deck edge, so the deck's cap crossed
    the hull's faces there (28 pairs of faces crossing; 7 of the 200 composed meshes cut
    themselves so). Triangle pairs tested by numpy (mesh_fixtures.self_intersections)."""
    from mesh_fixtures import self_intersections

    p = dict(lpp=88.897, breadth=15.024, draft=3.48, depth=5.567, cb=0.855, lcb=47.247, bulb=True)
    c = fl.design_hull(**p).composed_hull()
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    assert self_intersections(c.mesh) == []


def test_the_example_description_is_what_the_designer_writes_for_its_particulars():
    """examples/container_ship.json is design_hull's description of the Panamax particulars (the
    Blender example graph designs the ship from them and checks it against the file): every
    number of the designer's output within 1e-9 of the file's, names aside."""
    example = json.loads((pathlib.Path(__file__).resolve().parents[2] / "examples" / "container_ship.json").read_text())
    designed = json.loads(fl.design_hull(**SHIPS["container"]).to_json())

    def numbers(d, path=""):
        if isinstance(d, dict):
            return {k: v for key, item in d.items() if key != "name" for k, v in numbers(item, f"{path}/{key}").items()}
        if isinstance(d, list):
            return {k: v for i, item in enumerate(d) for k, v in numbers(item, f"{path}[{i}]").items()}
        return {path: d}

    got, want = numbers(designed), numbers(example)
    assert got.keys() == want.keys()
    off = {k: (got[k], want[k]) for k in got if isinstance(got[k], float) and got[k] != pytest.approx(want[k], rel=1e-9, abs=1e-12)}
    assert not off, off


#: A forward frame may stand out past its deck edge above T by this much (fraction of B/2) at most.
TUMBLEHOME_TOL = 1e-3
#: Measured shortfalls: none since an immersed section's top corner lies no further out than its
#: deck point (sections.cpp inside_deck_edge; before, 1.80 % of B/2 on the container ship, 0.88 % on
#: the ferry and the coaster, with designer.DECK_FOLLOW_POWER 0.4).
TUMBLEHOME: dict = {}


def _tumblehome(hull) -> float:
    """The most any frame cut forward of 0.55 Lpp (40 of them) stands out above T past the
    half-breadth at its top (the deck edge), fraction of B/2."""
    pr = hull.description.principal
    worst = 0.0
    for x in np.linspace(0.55 * pr.lpp, hull.immersed_range()[1], 40):
        P = np.asarray(fl.plane_cut(hull.bare_hull_surface(), 0, float(x), 401).points)
        above = P[P[:, 2] >= pr.draft]
        if len(above):
            worst = max(worst, (above[:, 1].max() - P[np.argmax(P[:, 2]), 1]) / (pr.breadth / 2))
    return worst


@pytest.mark.parametrize("name", ["container", "fine_ferry", "coaster_cruiser"])
def test_forward_frames_do_not_tumble_home_above_t(request, name):
    """Forward of 0.55 Lpp no frame cut above T stands out past its deck edge (no tumblehome at
    the bow, where a naval architect wants flare): its widest half-breadth above T is within
    TUMBLEHOME_TOL of B/2 of the half-breadth at its top."""
    if name in TUMBLEHOME:
        request.applymarker(pytest.mark.xfail(strict=True, reason=TUMBLEHOME[name]))
    assert _tumblehome(fl.design_hull(**SHIPS[name])) <= TUMBLEHOME_TOL


#: ... and over a sample of the design space by at most this (fraction of B/2).
SAMPLED_TUMBLEHOME_TOL = 5e-3


def test_sampled_designs_forward_frames_do_not_tumble_home_above_t():
    """The same over 20 designs of the Latin-hypercube sample: each stands out past its deck edge
    by under SAMPLED_TUMBLEHOME_TOL of B/2 (0.33 % at most measured; before an immersed section's
    top corner was kept inside its deck edge 13 of the 20 stood out by more, 0.90 % median, 2.49 %
    at most)."""
    worst = {i: _tumblehome(fl.design_hull(**p)) for i, p in enumerate(_space_sample(20, 2026))}
    assert {i: w for i, w in worst.items() if w > SAMPLED_TUMBLEHOME_TOL} == {}
