"""The bare hull from basic curves: description, sections, skinned surface, hydrostatics.

Truths: the form parameters written in examples/panamax_forebody.json (volume, LCB, waterplane
area, end values and angles), the geometry of each section checked by an independent dense
polygon (shoelace area), analytic Wigley cuts for the fairness tool, and bad descriptions that
must be rejected with the field named.
"""

import copy
import json
import math
import pathlib

import numpy as np
import pytest

import fairlines as fl

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "panamax_forebody.json"


@pytest.fixture(scope="module")
def desc():
    return json.loads(EXAMPLE.read_text())


@pytest.fixture(scope="module")
def hull(desc):
    return fl.Hull.from_json(EXAMPLE)


def test_displacement_lcb_and_waterplane_match_the_basic_curves(hull, desc):
    sac = desc["basic_curves"]["sac"]
    dwl = desc["basic_curves"]["dwl"]
    lpp = desc["principal"]["Lpp"]
    h = hull.hydrostatics()
    assert h.volume == pytest.approx(sac["volume"], rel=2e-3)
    assert abs(h.lcb - sac["lcb"]) < 1e-3 * lpp
    assert h.waterplane_area == pytest.approx(dwl["waterplane_area"], rel=2e-3)
    assert h.midship_area == pytest.approx(sac["value"], rel=2e-3)
    assert h.cm == pytest.approx(sac["value"] / (desc["principal"]["B"] * desc["principal"]["T"]), rel=2e-3)


def test_every_station_area_matches_the_sac(hull, desc):
    surf = hull.bare_hull_surface()
    params = hull.section_parameters()
    am = desc["basic_curves"]["sac"]["value"]
    for x, half in zip(params["x"], params["half_area"]):
        area, _ = fl.section_area(surf, x, desc["principal"]["T"])
        assert abs(area - 2 * half) <= 2e-3 * max(2 * half, 1e-3 * am), x


def test_basic_curves_meet_their_form_parameters(hull, desc):
    bc = hull.basic_curves
    sac = bc["sac"].form_parameters()
    assert sac["Area"] == pytest.approx(desc["basic_curves"]["sac"]["volume"], rel=1e-6)
    assert sac["xC"] == pytest.approx(desc["basic_curves"]["sac"]["lcb"], rel=1e-6)
    dwl = bc["dwl"]
    assert 2 * dwl.form_parameters()["Area"] == pytest.approx(desc["basic_curves"]["dwl"]["waterplane_area"], rel=1e-6)
    # Entrance angle: dy/dx at the FP is -tan(iE); the curve's x is linear in t.
    d = dwl.curve.derivatives(1.0, 1)
    assert d[1][1] / d[1][0] == pytest.approx(-math.tan(math.radians(desc["basic_curves"]["dwl"]["entrance_angle"])), rel=1e-9)
    # Flat parts, and G2 departure from them: zero slope and zero curvature (y'' = 0).
    for name in ("sac", "dwl", "deck", "fos", "fob", "profile", "deck_angle", "bottom_angle"):
        spec = desc["basic_curves"][name]
        c = bc[name]
        assert c(spec["flat_to"] - 1.0)[0] == pytest.approx(spec["value"])
        d0 = c.curve.derivatives(0.0, 2)
        scale = max(1.0, abs(spec["value"]))
        assert abs(d0[1][1]) < 1e-9 * abs(d0[1][0]) * scale, name
        assert abs(d0[2][1]) < 1e-9 * abs(d0[1][0]) ** 2 * scale, name
    assert bc["profile"](244.8)[0] == pytest.approx(desc["basic_curves"]["profile"]["yE"])
    # End curvatures asked for (CAE): the flat of side meets the deck, the flat of bottom the
    # centre line, with zero slope and curvature; beyond their ends they are absent, and their
    # straight continuation stays at the deck / the centre line.
    for name, end in (("fos", desc["principal"]["D"]), ("fob", 0.0)):
        c = bc[name]
        d1 = c.curve.derivatives(1.0, 2)
        assert d1[0][1] == pytest.approx(end, abs=1e-9)
        assert abs(d1[1][1]) < 1e-9 * abs(d1[1][0]) * 20 and abs(d1[2][1]) < 1e-8 * abs(d1[1][0]) ** 2 * 20
        assert np.isnan(c(c.x_end + 5.0)[0])
        assert c.extended(c.x_end + 5.0)[0] == pytest.approx(end, abs=1e-8)


def test_sections_follow_the_basic_curves(hull, desc):
    p = hull.section_parameters()
    T, D = desc["principal"]["T"], desc["principal"]["D"]
    for k, sec in enumerate(hull.sections):
        pts = sec.evaluate(np.linspace(0, 1, 6001))
        assert np.allclose(pts[:, 0], p["x"][k], atol=1e-9)
        assert pts[0, 1] == pytest.approx(p["y_deck"][k], abs=1e-9) and pts[0, 2] == pytest.approx(D, abs=1e-9)
        assert pts[-1, 1] == pytest.approx(0.0, abs=1e-9) and pts[-1, 2] == pytest.approx(p["z_keel"][k], abs=1e-9)
        assert pts[:, 1].min() >= -1e-9 and pts[:, 1].max() <= desc["principal"]["B"] / 2 + 1e-9
        # Half area below the DWL by the shoelace formula on a dense polygon closed along the
        # waterline and the centre line (independent of the engine's quadrature).
        y, z = pts[:, 1], pts[:, 2]
        below = z <= T
        if not below.any() or p["half_area"][k] == 0:
            assert p["half_area"][k] < 1e-9
            continue
        i = np.argmax(below)  # first point below the DWL; interpolate the crossing
        if i > 0:
            t = (T - z[i - 1]) / (z[i] - z[i - 1])
            y_wl = y[i - 1] + t * (y[i] - y[i - 1])
            assert y_wl == pytest.approx(p["y_dwl"][k], abs=2e-3)
            poly_y = np.concatenate([[0.0, y_wl], y[i:], [0.0]])
            poly_z = np.concatenate([[T, T], z[i:], [z[-1]]])
        else:
            poly_y, poly_z = np.concatenate([[0.0], y, [0.0]]), np.concatenate([[T], z, [z[-1]]])
        area = 0.5 * abs(np.dot(poly_y, np.roll(poly_z, -1)) - np.dot(poly_z, np.roll(poly_y, -1)))
        assert area == pytest.approx(p["half_area"][k], rel=1e-4, abs=1e-4)


def test_changing_one_form_parameter_rebuilds(desc):
    h = fl.Hull.from_json(EXAMPLE)
    before = h.bare_hull_surface()
    h.set("sac", "volume", 26000.0)
    after = h.bare_hull_surface()
    assert after is not before
    hy = h.hydrostatics()
    assert hy.volume == pytest.approx(26000.0, rel=2e-3)
    assert abs(hy.lcb - desc["basic_curves"]["sac"]["lcb"]) < 1e-3 * desc["principal"]["Lpp"]
    with pytest.raises(ValueError, match="basic_curves.sac.volume is nan"):
        h.set("sac", "volume", float("nan"))
    with pytest.raises(ValueError, match="curve is 'bulb'"):
        h.set("bulb", "volume", 1.0)


def test_json_round_trip_gives_the_same_surface(hull):
    again = fl.Hull.from_json(hull.to_json())
    a, b = hull.bare_hull_surface(), again.bare_hull_surface()
    assert np.allclose(a.control_points, b.control_points, atol=1e-9)
    assert isinstance(hull.description, fl.HullDescription)
    assert isinstance(hull.description.principal, fl.PrincipalDimensions)


def _bad(desc, path, value):
    d = copy.deepcopy(desc)
    node = d
    for key in path[:-1]:
        node = node[key]
    if value is KeyError:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return d


@pytest.mark.parametrize(
    "path, value, match",
    [
        (("basic_curves", "fob"), KeyError, r"basic_curves\.fob is missing"),
        (("basic_curves", "sac"), KeyError, r"basic_curves\.sac is missing"),
        (("principal", "T"), KeyError, r"principal\.T is missing"),
        (("principal", "B"), float("nan"), r"principal\.B is nan"),
        (("principal", "Lpp"), -5.0, r"principal\.Lpp is -5.0"),
        (("basic_curves", "dwl", "waterplane_area"), float("nan"), r"basic_curves\.dwl\.waterplane_area is nan"),
        (("basic_curves", "sac", "lcb"), "aft", r"basic_curves\.sac\.lcb is 'aft'"),
        (("stations",), {"x": [122.4, 150.0, 200.0, 250.0]}, r"stations\[3\] is 250.0; expected a station inside the hull"),
        (("stations",), {"x": [122.4, 150.0, 140.0, 200.0]}, r"stations\[2\] is 140.0; expected stations in increasing x"),
        (("stations",), KeyError, r"stations is missing"),
        (("basic_curves", "sac", "value"), 400.0, r"basic_curves\.sac\.value is 400.0.*B x T"),
        (("basic_curves", "sac", "volume"), 43000.0, r"basic_curves\.sac\.volume is 43000.0.*Cp <= 1"),
        (("basic_curves", "sac", "volume"), 45000.0, r"basic_curves\.sac\.volume is 45000.0.*Cb <= 1"),
        (("basic_curves", "sac", "lcb"), 250.0, r"basic_curves\.sac\.lcb is 250.0.*inside the hull"),
        (("basic_curves", "sac", "lcb"), 140.0, r"basic_curves\.sac.*(negative sectional area|contradict)"),
        (("basic_curves", "dwl", "colour"), 3, r"basic_curves\.dwl\.colour is not a form parameter"),
        (("basic_curves", "bulb"), {"value": 1.0}, r"basic_curves\.bulb is not a basic curve"),
    ],
)
def test_bad_descriptions_name_the_field(desc, path, value, match):
    with pytest.raises(ValueError, match=match):
        h = fl.Hull.from_json(_bad(desc, path, value))
        h.bare_hull_surface()


def test_sac_impossible_for_the_centre_profile_is_infeasible(desc):
    # A forefoot rising almost to the DWL leaves no room for the SAC's area there.
    d = _bad(desc, ("basic_curves", "profile", "yE"), 10.9)
    d["basic_curves"]["profile"]["flat_to"] = 200.0
    with pytest.raises(fl.InfeasibleFormParameters, match=r"section at x = .* m"):
        fl.Hull.from_json(d).bare_hull_surface()


def test_invalid_json_text():
    with pytest.raises(ValueError, match="not valid JSON"):
        fl.Hull.from_json("{not json")


L, B, T = 100.0, 10.0, 6.25


def _wigley_surface(**kw):
    def sec(x):
        xm = x - L / 2

        def f(t):
            z = T * (1 - t)
            return np.array([x, B / 2 * (1 - (2 * xm / L) ** 2) * (1 - ((T - z) / T) ** 2), z])

        p0, p2 = f(0.0), f(1.0)
        return fl.NurbsCurve(2, [0, 0, 0, 1, 1, 1], np.array([p0, 2 * f(0.5) - (p0 + p2) / 2, p2]))

    return fl.fair_skin([sec(x) for x in np.linspace(0, L, 41)], n_control=8, **kw).surface


def test_plane_cuts_have_the_analytic_curvature_of_the_wigley_hull():
    # e3 fairness: the rows vary quadratically along x and are reproduced exactly.
    s = _wigley_surface(e2=0.0, e3=1.0)
    # Waterline z: y = c (1 - (2 xm / L)^2), c = B/2 (1 - ((T - z)/T)^2).
    z = 4.0
    c = B / 2 * (1 - ((T - z) / T) ** 2)
    cut = fl.plane_cut(s, "waterline", z, 201)
    x = cut.points[:, 0] - L / 2
    yp, ypp = -8 * c * x / L**2, -8 * c / L**2
    k = ypp / (1 + yp**2) ** 1.5
    # In (x, y) with x increasing the waterline bends toward -y: negative curvature.
    inner = np.abs(x) < 0.4 * L
    assert np.max(np.abs(cut.curvature[inner] - k[inner])) < 2e-2 * np.max(np.abs(k))
    assert cut.sign_changes == 0
    # Frame x: y = a (1 - ((T - z)/T)^2), one sign of curvature.
    fr = fl.plane_cut(s, "frame", 30.0, 201)
    assert fr.sign_changes == 0 and np.allclose(fr.points[:, 0], 30.0, atol=1e-9)
    bt = fl.plane_cut(s, "buttock", 2.0, 201)
    assert bt.sign_changes == 0 and np.allclose(bt.points[:, 1], 2.0, atol=1e-9)
    with pytest.raises(ValueError, match="axis is 'diagonal'"):
        fl.plane_cut(s, "diagonal", 1.0)


def test_e2_skinning_has_natural_ends_that_e3_avoids():
    """Seed 000's E2 interpolant is the natural spline: zero curvature at the end sections,
    which on the Wigley waterline (constant sign of curvature) makes spurious inflections
    near the ends; the E3 objective keeps the end curvature."""
    z = 4.0
    e2 = fl.plane_cut(_wigley_surface(), "waterline", z, 201)
    e3 = fl.plane_cut(_wigley_surface(e2=0.0, e3=1.0), "waterline", z, 201)
    assert abs(e2.curvature[0]) < 0.1 * abs(e2.curvature[100])
    assert abs(e3.curvature[0]) > 0.8 * abs(e3.curvature[100])
    assert e2.sign_changes > 0 and e3.sign_changes == 0


def test_fairness_report_lists_every_cut(hull):
    rep = hull.fairness_report(n_waterlines=3, n_buttocks=2, n_frames=3, samples=101)
    assert [len(rep[k]) for k in ("waterline", "buttock", "frame")] == [3, 2, 3]
    for cuts in rep.values():
        for c in cuts:
            assert c["e2"] > 0 and c["bending_energy"] > 0
            assert len(c["inflections"]) == c["sign_changes"]


def test_sections_share_one_knot_vector_and_their_flats_are_exact(hull, desc):
    """Every section is designed on fl.section_knot_vector(n): no refit. The flat of side is
    the straight top zone at exactly B/2 down to the fos curve (plus the zone's soft maximum,
    under 1 cm), the flat of bottom the bottom zone at exactly z = 0 out to the fob curve."""
    n = desc["sections"]["n_control"]
    knots = np.asarray(fl.section_knot_vector(n))
    B2 = desc["principal"]["B"] / 2
    p = hull.section_parameters()
    for k, sec in enumerate(hull.sections):
        assert np.array_equal(np.asarray(sec.knots), knots)
        assert sec.control_points.shape == (n + 6, 3)
        cp = sec.control_points
        depth = desc["principal"]["D"] - p["z_keel"][k]
        if p["z_fos"][k] < desc["principal"]["D"] - 0.05:
            # the top zone and the curved part's first leg point (tangent) on y = B/2, exactly;
            # the second one too (zero curvature: G2) where the flat is longer than kG2Blend
            assert np.all(cp[:5, 1] == B2), p["x"][k]
            # the zone is a soft maximum of the flat's length L and the floor f: L + f^2/(L - f) at most
            L, f = desc["principal"]["D"] - p["z_fos"][k], 2.5e-3 * depth
            assert p["z_fos"][k] - f * f / (L - f) - 1e-9 <= cp[3, 2] <= p["z_fos"][k]
            if desc["principal"]["D"] - p["z_fos"][k] >= 0.05 * depth:
                assert cp[5, 1] == B2, p["x"][k]
        if p["y_fob"][k] > 0.05:
            assert np.all(cp[-5:, 2] == 0.0), p["x"][k]
            L, f = p["y_fob"][k], 2.5e-3 * depth
            assert p["y_fob"][k] <= cp[-4, 1] <= p["y_fob"][k] + f * f / (L - f) + 1e-9
            if p["y_fob"][k] >= 0.05 * depth:
                assert cp[-6, 2] == 0.0, p["x"][k]


def test_sections_change_smoothly_along_the_hull(hull):
    """The designed family is smooth in x: the control points' second differences on a fine x
    grid stay small compared with their first differences (no jumps where a flat ends, where
    the DWL leaves the flat of side, or at the stem)."""
    x = np.linspace(hull.description.x_start, hull.description.x_end - 1.0, 241)
    P = np.array([s.control_points for s in hull.sections_at(x)])
    h = x[1] - x[0]
    d1 = np.abs(np.diff(P[:, :, 1:], axis=0)) / h
    d2 = np.abs(np.diff(P[:, :, 1:], 2, axis=0)) / h**2
    # A jump of size J shows as d1 ~ J / h and d2 ~ J / h^2: with h = 0.5 m, a 5 cm jump in any
    # control point would give d2 ~ 0.2 1/m.
    assert d1.max() < 2.0
    assert d2.max() < 0.2


def test_e3_skin_passes_through_the_panamax_sections(hull):
    """The E3 KKT system mixes fairness entries ~ q^3 with O(1) interpolation rows; unscaled, its
    solve missed the sections by 0.15 m. The sections share one knot vector, so the surface's
    iso-curve at each station must reproduce the section's control points themselves."""
    sk = hull.skin()
    assert sk.section_fit_max == 0.0
    s = sk.surface
    for d, sec in enumerate(hull.sections):
        iso = s.iso_curve("v", float(sk.section_params[d]))
        assert np.array_equal(np.asarray(iso.knots), np.asarray(sec.knots))
        assert np.max(np.abs(iso.control_points - sec.control_points)) < 1e-9 * 250, d
    assert sk.longitudinal_max < 1e-9


def test_parallel_body_and_flats_are_exact_on_the_surface(hull, desc):
    """Held runs (fair_skin hold_runs): forward of midships to the end of the SAC's flat part
    the surface is exactly the midship section; the flat of side stays at B/2 and the flat of
    bottom at z = 0 between the stations too, wherever the designed sections have them."""
    s = hull.bare_hull_surface()
    x0, x1 = desc["range"]["x_start"], desc["range"]["x_end"]
    v_of = lambda x: (x - x0) / (x1 - x0)  # noqa: E731
    u = np.linspace(0, 1, 301)
    mid = s.evaluate_grid(u, np.array([0.0]))[:, 0, 1:]
    for x in np.linspace(x0, desc["basic_curves"]["sac"]["flat_to"], 7):
        assert np.max(np.abs(s.evaluate_grid(u, np.array([v_of(x)]))[:, 0, 1:] - mid)) < 1e-12
    B2 = desc["principal"]["B"] / 2
    bc = hull.basic_curves
    xs = np.linspace(x0, x1 - 1.0, 97)
    grid = s.evaluate_grid(u, v_of(xs))  # (u, x, 3)
    for j, x in enumerate(xs):
        z_fos, y_fob = bc["fos"].extended(x)[0], bc["fob"].extended(x)[0]
        side = grid[:, j, 2] >= z_fos + 0.05
        bottom = grid[:, j, 1] <= y_fob - 0.05
        assert np.all(grid[side, j, 1] == pytest.approx(B2, abs=1e-12)), x
        assert np.all(np.abs(grid[bottom, j, 2]) < 1e-12), x
        # The keel line holds z = 0 up to the keel's rise even where the flat bottom has ended
        # (the zones are built from their end rows), so it never dips below the base.
        assert grid[:, j, 1].max() <= B2 + 1e-9 and grid[:, j, 2].min() >= -1e-12


def test_surface_follows_the_designed_family_between_the_stations(hull):
    """Between the stations the skin approximates the sections the basic curves define there
    (the designed family): midway between each pair of stations the iso-curve lies within
    1.5 cm of the designed section (3 cm in the last interval at the stem, where the sections'
    end angles fade to vertical), and the area below the DWL within 0.2 % of the midship area."""
    s = hull.bare_hull_surface()
    d = hull.description
    xs = hull.stations()
    mid = 0.5 * (xs[:-1] + xs[1:])
    fam = hull.sections_at(mid)
    u = np.linspace(0, 1, 401)
    worst = []
    for x, sec in zip(mid, fam):
        iso = s.evaluate_grid(u, np.array([(x - xs[0]) / (xs[-1] - xs[0])]))[:, 0, :]
        dense = sec.evaluate(np.linspace(0, 1, 4001))
        gap = np.min(np.linalg.norm(iso[:, None, 1:] - dense[None, :, 1:], axis=2), axis=1)
        worst.append(gap.max())
        area, _ = fl.section_area(s, float(x), d.principal.draft)
        sac = hull.basic_curves["sac"](x)[0]
        assert abs(area - sac) <= 2e-3 * d.curves["sac"].value, x
    assert max(worst[:-1]) < 0.015 and worst[-1] < 0.03


def test_panamax_has_no_false_inflection(hull):
    """Issue 4: no waterline, buttock or frame of the Panamax forebody changes the sign of its
    curvature where the designed shape does not call for it (fairlines.inflections judges each
    against the designed family); every real one says why."""
    rep = hull.fairness_report()
    assert [len(rep[k]) for k in ("waterline", "buttock", "frame")] == [8, 6, 12]
    for kind, cuts in rep.items():
        for c in cuts:
            assert c["false_inflections"] == 0, (kind, c["value"], [j["reason"] for j in c["classified"] if not j["real"]])
            assert c["real_inflections"] == c["sign_changes"]
            for j in c["classified"]:
                assert j["real"] and j["reason"] and not j["reason"].startswith("false")


def test_stations_move_onto_the_basic_curve_junctions(desc):
    """With skinning.junctions the station nearest each junction (end of a flat part, end of a
    basic curve) moves onto it, so every flat and the parallel body ends exactly there on the
    surface (the held runs end at a station)."""
    h = fl.Hull.from_json(desc)
    bc = desc["basic_curves"]
    junctions = h.junctions()
    expected = sorted({bc[n]["flat_to"] for n in bc} | {bc[n]["x_end"] for n in bc if "x_end" in bc[n]})
    assert junctions == [x for x in expected if desc["range"]["x_start"] < x < desc["range"]["x_end"]]
    xs = h.stations()
    assert all(np.min(np.abs(xs - j)) < 1e-9 for j in junctions)
    assert len(xs) == desc["stations"]["count"]
    plain = copy.deepcopy(desc)
    plain["skinning"]["junctions"] = False
    assert not np.any([np.min(np.abs(fl.Hull.from_json(plain).stations() - j)) < 1e-9 for j in junctions[1:]])


@pytest.mark.parametrize(
    "path, value, match",
    [
        (("basic_curves", "profile", "CAE"), 0.01, r"basic_curves\.profile: CAE is 0\.01 without alphaE"),
        (("basic_curves", "sac", "CAB"), 0.01, r"basic_curves\.sac\.CAB is given after a flat part"),
        (("basic_curves", "fos", "CAE"), float("nan"), r"basic_curves\.fos\.CAE is nan"),
        (("sections", "n_control"), 7, r"sections\.n_control is 7; expected an integer >= 8"),
        (("basic_curves", "dwl", "flat_to"), 150.0, r"section at x = .* DWL half-breadth"),
    ],
)
def test_contradicting_section_data_names_the_curves(desc, path, value, match):
    with pytest.raises(ValueError, match=match):
        fl.Hull.from_json(_bad(desc, path, value)).bare_hull_surface()


def test_designed_sections_anywhere_and_bad_stations(hull, desc):
    x = [130.0, 150.5, 200.25]
    got = hull.sections_at(x)
    assert [float(s.control_points[0, 0]) for s in got] == x
    at_station = hull.sections_at(hull.stations()[5:6])[0]
    assert np.array_equal(at_station.control_points, hull.sections[5].control_points)
    with pytest.raises(ValueError, match=r"x\[1\] is 300.0; expected a station inside the hull"):
        hull.sections_at([150.0, 300.0])
    with pytest.raises(ValueError, match="per_interval is 0"):
        hull.design_family(0)


def test_auxiliary_section_on_the_shared_knots(desc):
    d = copy.deepcopy(desc)
    x = 214.0
    ref = fl.Hull.from_json(desc).sections_at([x])[0]
    pts = ref.evaluate(np.linspace(0, 1, 80))
    d["auxiliary_sections"] = [{"x": x, "offsets": pts[:, 1:].tolist()}]
    h = fl.Hull.from_json(d)
    aux = [s for s in h.sections if abs(s.control_points[0, 0] - x) < 1e-9]
    assert len(aux) == 1 and np.array_equal(np.asarray(aux[0].knots), np.asarray(fl.section_knot_vector(16)))
    dense = aux[0].evaluate(np.linspace(0, 1, 2001))
    gap = np.min(np.linalg.norm(dense[:, None, 1:] - pts[None, :, 1:], axis=2), axis=0)
    assert gap.max() < 0.05  # a least-squares fit of the offsets on the sections' knots
    assert h.skin().section_fit_max == 0.0  # still one knot vector: no refit
    d["auxiliary_sections"] = [{"x": x, "offsets": pts[:10, 1:].tolist()}]
    with pytest.raises(ValueError, match=r"auxiliary_sections\[0\]\.offsets has 10 points; expected at least 22"):
        fl.Hull.from_json(d).sections


def test_fair_skin_straight_groups_are_checked(hull):
    secs = hull.sections
    with pytest.raises(ValueError, match=r"straight_groups\[0\] is \(3, 40\)"):
        fl.fair_skin(secs, straight_groups=[(3, 40)])
    with pytest.raises(ValueError, match=r"straight_groups\[0\]: row 6 is not at one fraction"):
        fl.fair_skin(secs, straight_groups=[(5, 9)])
