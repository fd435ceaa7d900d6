"""A raked transom (ends.transom_rake; the designer's transom_rake): the aft end lies in the
transom's plane, the designed ship still meets its particulars, the waterplane reaches the raked
end, the composed hull is closed, and bad rakes are refused by name."""

import json
import math

import numpy as np
import pytest

import fairlines as fl
from conftest import ship_tol

# The fine ferry: a transom immersed 12 % of T (its lower edge 0.66 m under the waterline).
FERRY = dict(lpp=140.0, breadth=17.0, draft=5.5, depth=10.0, cb=0.5, lcb=67.2)
RAKE = 20.0
PLANE_TOL = 1e-9     # m: the aft end off the transom's plane (an affine map of its control points)
MATCH_TOL = 1e-4     # the designer's match of volume, LCB (of Lpp) and waterplane area
POLYGON_TOL = 2e-4   # a waterplane's area from 4001 points of its cut against the quadrature


@pytest.fixture(scope="module")
def raked():
    return fl.design_hull(**FERRY, transom_rake=RAKE)


def aft_edge(hull, n=81):
    s = hull.bare_hull_surface()
    return np.array([s.evaluate(u, s.domain_v[0]) for u in np.linspace(*s.domain_u, n)])


def test_the_aft_end_lies_in_the_transoms_plane_about_its_lower_edge(raked):
    d = raked.description
    z_edge = float(raked.basic_curves["profile"](d.x_aft)[0])
    p = aft_edge(raked)
    assert p[:, 2].min() == pytest.approx(z_edge, abs=1e-9)
    expected = d.x_aft - (p[:, 2] - z_edge) * math.tan(math.radians(RAKE))
    assert np.abs(p[:, 0] - expected).max() <= PLANE_TOL


CONTAINER = dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True)


@pytest.mark.parametrize("p, rake", [(FERRY, -15.0), (FERRY, 30.0), (CONTAINER, 15.0)],
                         ids=["ferry -15", "ferry 30", "container 15"])
def test_a_raked_ship_meets_its_particulars(p, rake):
    """Volume and LCB on the raked surface (the designer matches them there; the shear alone
    moves the ferry's by 0.5 % at 30 deg), and its aft end in the raked plane."""
    hull = fl.design_hull(**p, transom_rake=rake)
    h, tol = hull.ship_hydrostatics(), ship_tol(hull, MATCH_TOL)  # with a bulb the composed ship's
    assert h["volume"] == pytest.approx(p["cb"] * p["lpp"] * p["breadth"] * p["draft"], rel=tol)
    assert abs(h["lcb"] - p["lcb"]) <= tol * p["lpp"]
    d = hull.description
    z_edge = float(hull.basic_curves["profile"](d.x_aft)[0])
    e = aft_edge(hull)
    assert np.abs(e[:, 0] - (d.x_aft - (e[:, 2] - z_edge) * math.tan(math.radians(rake)))).max() <= PLANE_TOL


def test_the_waterplane_reaches_the_raked_end(raked):
    """The design waterline's area from its own cut (a polygon closed on the centre plane and
    across the transom) is the quadrature's, whose lid terms carry the raked end's share."""
    T = FERRY["draft"]
    cut = np.asarray(fl.plane_cut(raked.bare_hull_surface(), 2, T, 4001).points)
    cut = cut[np.argsort(cut[:, 0])]
    ring = np.vstack([[cut[0, 0], 0.0], cut[:, :2], [cut[-1, 0], 0.0]])
    x, y = ring[:, 0], ring[:, 1]
    area = 2 * 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    h = raked.hydrostatics()
    assert h.waterplane_area == pytest.approx(area, rel=POLYGON_TOL)
    d = raked.description
    z_edge = float(raked.basic_curves["profile"](d.x_aft)[0])
    assert cut[0, 0] == pytest.approx(d.x_aft - (T - z_edge) * math.tan(math.radians(RAKE)), abs=1e-3)


def test_the_composed_raked_hull_is_closed(raked):
    m = fl.mesh_hull(raked.composed_hull(), size=2.0, draft=FERRY["draft"])
    q = m.quality()
    assert q["open_edges"] == 0 and q["inverted"] == 0


def test_the_rake_survives_json(raked):
    again = fl.Hull.from_json(raked.to_json())
    assert again.description.transom_rake == RAKE
    assert np.array_equal(np.asarray(again.bare_hull_surface().control_points),
                          np.asarray(raked.bare_hull_surface().control_points))


@pytest.mark.parametrize("rake", [50.0, -40.0])
def test_a_rake_out_of_range_is_refused_naming_it(raked, rake):
    d = json.loads(raked.to_json())
    d["ends"]["transom_rake"] = rake
    with pytest.raises(fl.InvalidInput, match=rf"ends\.transom_rake is {rake:g} deg; expected -30 to 45 deg"):
        fl.Hull.from_json(json.dumps(d))
    with pytest.raises(fl.InvalidInput, match=rf"transom_rake is {rake!r}; expected -30 to 45 deg"):
        fl.design_hull(**FERRY, transom_rake=rake)


def test_a_cruiser_stern_has_no_transom_to_rake():
    with pytest.raises(fl.InvalidInput, match=r"transom_rake is 10 deg with stern='cruiser'; expected 0"):
        fl.design_hull(**FERRY, stern="cruiser", transom_rake=10.0)


def test_the_raked_hull_exports_as_one_closed_solid_of_its_volume(raked):
    """OpenCASCADE's own volume of the exported half-hull solid (caps on the deck, the centre
    plane and the raked transom) against the quadrature's up to the deck."""
    pytest.importorskip("OCP")
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    from fairlines.cad import hull_solid

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(hull_solid(raked.composed_hull()), props)
    below_deck = fl.hydrostatics(raked.bare_hull_surface(), FERRY["depth"] * (1 - 1e-12), half_hull=True).volume / 2
    assert props.Mass() == pytest.approx(below_deck, rel=1e-5)


def test_a_rake_on_a_stern_without_a_transom_is_refused_naming_it():
    """A cruiser stern's profile meets the deck at the aft end: nothing to rake (the rake was
    kept in the description and did nothing)."""
    d = json.loads(fl.design_hull(**FERRY, stern="cruiser").to_json())
    d["ends"]["transom_rake"] = 15.0
    with pytest.raises(fl.InvalidInput, match=r"ends\.transom_rake is 15 deg; expected 0: the hull has no transom"):
        fl.Hull.from_json(json.dumps(d)).bare_hull_surface()


def test_a_stern_standing_round_off_above_its_edge_has_no_transom():
    """The aft end's control points at the deck may stand round-off above the profile there (a
    cruiser stern's stood 4e-15 m above it with the keel rising over 0.7 of the run): still no
    transom to rake, refused by name."""
    from fairlines.transom_rake import raked

    s = fl.design_hull(**FERRY, stern="cruiser").bare_hull_surface()
    top = float(np.array(s.control_points)[:, 0, 2].max())
    with pytest.raises(fl.InvalidInput, match=r"ends\.transom_rake is 15 deg; expected 0: the hull has no transom"):
        raked(s, -3.5, top - 4e-15, 15.0, FERRY["lpp"])


def test_a_rake_with_an_aft_post_is_refused(raked):
    d = json.loads(raked.to_json())
    d["ends"]["aft_post"] = True
    with pytest.raises(fl.InvalidInput, match=r"ends\.transom_rake is 20 deg with ends\.aft_post; expected 0"):
        fl.Hull.from_json(json.dumps(d))


def test_a_rake_too_steep_to_fade_out_on_a_short_deep_hull_is_refused_naming_the_steepest():
    """A half box 10 m long and 10 m deep raked 45 deg about its bottom: the top would move 10 m,
    whose fade (3 moves at least) would run past half the hull; 9.5 deg is the steepest."""
    from fairlines.transom_rake import raked

    P = np.zeros((3, 2, 3))
    for i, (y, z) in enumerate([(2.0, 10.0), (2.0, 0.0), (0.0, 0.0)]):
        P[i, 0], P[i, 1] = (0.0, y, z), (10.0, y, z)
    box = fl.NurbsSurface(1, 1, [0, 0, 0.5, 1, 1], [0, 0, 1, 1], P)
    with pytest.raises(fl.InvalidInput, match=r"ends\.transom_rake is 45 deg; expected at most 9\.5 deg on this hull"):
        raked(box, 0.0, 0.0, 45.0, 10.0)
    assert np.asarray(raked(box, 0.0, 0.0, 9.0, 10.0).control_points)[0, 0, 0] == pytest.approx(-10 * math.tan(math.radians(9)))
