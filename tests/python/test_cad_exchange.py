"""CAD exchange round trips through OpenCASCADE (STEP AP214 / AP242, IGES) and rhino3dm:
surfaces within 1e-7 m, the hull's solid closed and valid, its volume against our quadrature."""

import numpy as np
import pytest

import fairlines as fl
from cad_fixtures import (EXAMPLE_PARTICULARS as P, cruiser_stern_hull, example_composed_hull, example_hull,
                          example_hull_surface)

pytest.importorskip("OCP")
from fairlines import cad  # noqa: E402

#: Surface deviation after a round trip: STEP keeps full precision; OCCT's IGES writer prints
#: 9 significant digits, 1e-7 m at 245 m from the origin.
STEP_DEVIATION = 1e-7
IGES_DEVIATION = 2e-7
#: Solid volume against our hydrostatics (relative).
VOLUME_TOLERANCE = 5e-4
#: Transom cap area against the shoelace area of the hull's aft edge sampled at
#: TRANSOM_SAMPLES points (relative).
TRANSOM_AREA_TOLERANCE = 1e-5
TRANSOM_SAMPLES = 2001


def _surfaces(hull):
    return [s for s, _ in cad._patches(hull)]


@pytest.mark.parametrize("schema", ["AP214", "AP242"])
def test_step_surfaces_round_trip(tmp_path, schema):
    c = example_composed_hull()
    assert c.blend_note.startswith("blend:")  # bare hull, bulb and blend
    path = tmp_path / "s.step"
    cad.export_cad(c, path, what="surfaces", schema=schema)
    text = path.read_text(errors="replace")
    assert ("AUTOMOTIVE_DESIGN" in text) if schema == "AP214" else ("AP242" in text.upper() or "MANAGED_MODEL" in text.upper())
    v = cad.verify(cad.read_cad(path), _surfaces(c), samples=7)
    assert v["faces"] == 3 and v["valid"]
    assert v["max_deviation"] < STEP_DEVIATION


def test_iges_surfaces_are_trimmed_nurbs_entities(tmp_path):
    s = example_hull_surface()
    path = tmp_path / "s.igs"
    cad.export_cad(s, path, what="surfaces")
    types = {line[:8].split(",")[0] for line in path.read_text().splitlines() if line[72] == "P"}
    assert {"144", "128"} <= types
    v = cad.verify(cad.read_cad(path), [s], samples=7)
    assert v["max_deviation"] < IGES_DEVIATION


@pytest.mark.parametrize("full", [False, True])
def test_bare_hull_solid_step_closed_valid_volume(tmp_path, full):
    s = example_hull_surface()
    path = tmp_path / "h.step"
    cad.export_cad(s, path, what="solid", full=full)
    v = cad.verify(cad.read_cad(path))
    assert v["valid"] and v["closed"]
    expected = fl.hydrostatics(s, P["depth"]).volume * (1.0 if full else 0.5)
    assert v["volume"] == pytest.approx(expected, rel=VOLUME_TOLERANCE)


def _planar_faces_normal_to_x(shape):
    """(x, area) of the solid's planar faces whose normal is along x."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepGProp import BRepGProp
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.GProp import GProp_GProps
    out = []
    for f in cad._faces_of(shape):
        a = BRepAdaptor_Surface(f)
        if a.GetType() != GeomAbs_Plane:
            continue
        pln = a.Plane()
        if abs(pln.Axis().Direction().X()) > 1 - 1e-12:
            props = GProp_GProps()
            BRepGProp.SurfaceProperties_s(f, props)
            out.append((pln.Location().X(), props.Mass()))
    return out


def test_transom_closed_by_one_planar_cap_of_the_transom_area(tmp_path):
    s = example_hull_surface()
    x_aft = float(np.asarray(s.control_points)[0, 0, 0])
    path = tmp_path / "h.step"
    cad.export_cad(s, path, what="solid")
    caps = _planar_faces_normal_to_x(cad.read_cad(path))
    # the transom: the hull's aft edge (v = 0) from the deck down to the centre plane, closed
    # along the centre line to the deck; its area by the shoelace formula
    u = np.linspace(*s.domain_u, TRANSOM_SAMPLES)
    edge = np.asarray(s.evaluate(u, np.full_like(u, s.domain_v[0])))
    assert np.ptp(edge[:, 0]) < 1e-9
    yz = np.vstack([edge[:, 1:], [0.0, P["depth"]]])
    area = 0.5 * abs(np.dot(yz[:, 0], np.roll(yz[:, 1], -1)) - np.dot(yz[:, 1], np.roll(yz[:, 0], -1)))
    assert len(caps) == 1 and caps[0][0] == pytest.approx(x_aft, abs=1e-9)
    assert caps[0][1] == pytest.approx(area, rel=TRANSOM_AREA_TOLERANCE)


def test_cruiser_stern_solid_closes_without_a_transom_cap(tmp_path):
    s = cruiser_stern_hull().bare_hull_surface()
    path = tmp_path / "c.step"
    cad.export_cad(s, path, what="solid")
    shape = cad.read_cad(path)
    v = cad.verify(shape)
    assert v["valid"] and v["closed"] and not _planar_faces_normal_to_x(shape)
    assert v["volume"] == pytest.approx(fl.hydrostatics(s, P["depth"]).volume / 2, rel=VOLUME_TOLERANCE)


def test_composed_hull_solid_step_closed_valid_volume(tmp_path):
    # reference: the bare hull by quadrature plus what the bulb and blend add on the meshes
    c = example_composed_hull()
    s = example_hull_surface()
    expected = 2 * (fl.hydrostatics(s, P["depth"]).volume / 2 + c.volume - fl.compose([s]).volume)
    path = tmp_path / "c.step"
    cad.export_cad(c, path, what="solid", full=True, schema="AP242")
    v = cad.verify(cad.read_cad(path))
    assert v["valid"] and v["closed"] and v["faces"] == 10
    assert v["volume"] == pytest.approx(expected, rel=VOLUME_TOLERANCE)


@pytest.mark.parametrize("c_bb", [0.15, 0.21])
def test_composed_solid_of_a_swept_bulb_closes(tmp_path, c_bb):
    """Bulbs of the C_BB range whose blend boundary turns sharply in (u, v) near its top: the
    hull's trimming loop runs along the blend's edge there and must take that edge once,
    not once per run between corners of the polygon."""
    h = example_hull()
    k = h.description.bulb.kracht
    b = h.bulbous_bow(c_bb=c_bb, c_abt=k["c_abt"] * c_bb / k["c_bb"], c_vpr=k["c_vpr"] * c_bb / k["c_bb"])
    c = h.composed_hull(bulb=b)
    s = h.bare_hull_surface()
    expected = 2 * (fl.hydrostatics(s, P["depth"]).volume / 2 + c.volume - fl.compose([s]).volume)
    path = tmp_path / "c.step"
    cad.export_cad(c, path, what="solid", full=True)
    v = cad.verify(cad.read_cad(path))
    assert v["valid"] and v["closed"] and v["faces"] == 10
    assert v["volume"] == pytest.approx(expected, rel=VOLUME_TOLERANCE)


def test_iges_solid_sews_back_closed(tmp_path):
    s = example_hull_surface()
    path = tmp_path / "h.iges"
    cad.export_cad(s, path, what="solid")
    v = cad.verify(cad.read_cad(path))
    assert v["valid"] and v["closed"]
    assert v["volume"] == pytest.approx(fl.hydrostatics(s, P["depth"]).volume / 2, rel=VOLUME_TOLERANCE)


def test_rhino_3dm_round_trip_through_occt(tmp_path):
    pytest.importorskip("rhino3dm")
    from OCP.gp import gp_Pnt  # noqa: F401
    c = example_composed_hull()
    path = tmp_path / "h.3dm"
    cad.export_cad(c, path)
    back = cad.read_3dm(path)
    ours = _surfaces(c)
    assert len(back) == len(ours)
    t = np.linspace(0.0, 1.0, 9)
    for a, b in zip(ours, back):
        g = cad.occ_surface(b)
        us = a.domain_u[0] + t * np.ptp(a.domain_u)
        vs = a.domain_v[0] + t * np.ptp(a.domain_v)
        pa = np.asarray(a.evaluate_grid(us, vs))
        pb = np.array([[[g.Value(u, v).X(), g.Value(u, v).Y(), g.Value(u, v).Z()] for v in vs] for u in us])
        assert np.abs(pa - pb).max() < STEP_DEVIATION


def test_unknown_format_and_options_are_named(tmp_path):
    s = example_hull_surface()
    with pytest.raises(fl.InvalidInput, match="suffix"):
        cad.export_cad(s, tmp_path / "h.obj")
    with pytest.raises(fl.InvalidInput, match="schema"):
        cad.export_cad(s, tmp_path / "h.step", schema="AP203")
