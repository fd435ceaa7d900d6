"""Quad-dominant meshes of surfaces and composed hulls, and the files solvers read.

Truths used: numpy edge censuses and volumes of our own, the surfaces' own closest points,
NURBS quadrature (fl.hydrostatics), meshio and capytaine reading the files back.
"""

import re

import numpy as np
import pytest

import fairlines as fl
from mesh_fixtures import (EXAMPLE_DRAFT, WIGLEY, bilge_patch, closed_volume, composed_example_hull,
                           composed_wetted_hydrostatics, cruiser_stern_ship, edge_census, example_hull,
                           wigley_surface)

MESH_VOLUME_TOL = 2e-3     # closed hull mesh vs NURBS quadrature at about 1 % of L element size
CAPYTAINE_TOL = 3e-3       # capytaine's panel hydrostatics converge as O(h^2): ~2e-3 at 2 500 panels


@pytest.fixture(scope="module")
def bilge():
    return bilge_patch()


SHIP_SIZE = 3.0           # element size on the whole ship (m, about 1.2 % of Lpp)


@pytest.fixture(scope="module")
def blended():
    """The whole container ship composed: bare hull + bulb + blend, transom stern."""
    return composed_example_hull()


@pytest.fixture(scope="module")
def ship_meshes(blended):
    """Whole-ship meshes: closed whole hull, closed wetted part, open wetted part (BEM)."""
    return {"whole": fl.mesh_hull(blended, size=SHIP_SIZE),
            "wetted": fl.mesh_hull(blended, size=SHIP_SIZE, draft=EXAMPLE_DRAFT),
            "open": fl.mesh_hull(blended, size=SHIP_SIZE, draft=EXAMPLE_DRAFT, lids=False)}


@pytest.fixture(scope="module")
def wigley():
    return wigley_surface()


def test_surface_mesh_is_quad_dominant_valid_and_on_the_surface(bilge):
    m = fl.mesh_surface(bilge, size=0.5)
    q = m.quality()
    assert q["quad_fraction"] >= 0.98 and q["inverted"] == 0 and q["duplicate_nodes"] == 0
    assert q["min_scaled_jacobian"] > 0.45 and q["corners_in_45_135"] >= 0.97
    sample = m.vertices[:: max(1, len(m.vertices) // 200)]
    gap = [np.linalg.norm(bilge.closest_point(p)[2] - p) for p in sample]
    assert max(gap) < 1e-8


def test_chordal_deviation_within_the_tolerance(bilge):
    tol = 0.002
    m = fl.mesh_surface(bilge, size=1.0, chordal_tolerance=tol)
    cent = np.array([m.vertices[f[f >= 0]].mean(axis=0) for f in m.faces[:: max(1, len(m.faces) // 300)]])
    dev = [np.linalg.norm(bilge.closest_point(c)[2] - c) for c in cent]
    assert max(dev) <= tol
    assert m.quality()["max_edge"] <= 1.0 * 1.05


def test_all_quad_mode_has_no_triangles(bilge):
    q = fl.mesh_surface(bilge, size=0.8, all_quad=True).quality()
    assert q["triangles"] == 0 and q["inverted"] == 0 and q["min_scaled_jacobian"] > 0.4


@pytest.mark.parametrize("which", ["whole", "wetted"])
def test_whole_ship_mesh_is_watertight_conforming_and_has_no_duplicates(ship_meshes, which):
    m = ship_meshes[which]
    assert {"hull", "bulb", "blend", "centre_plane"} <= set(m.parts)
    assert ("waterplane" in m.parts) == (which == "wetted") and ("deck" in m.parts) == (which == "whole")
    assert ("aft" in m.parts) == (which == "whole")  # the transom's lower edge is 0.55 m above T
    assert edge_census(m.faces) == (0, 0, 0)  # closed: every seam's nodes are shared
    assert len(np.unique(np.round(m.vertices, 9), axis=0)) == len(m.vertices)
    assert np.all(fl._native.scaled_jacobians(m.vertices, m.faces) > 0)
    assert closed_volume(m.vertices, m.faces) > 0  # outward
    if which == "wetted":
        assert m.vertices[:, 2].max() <= EXAMPLE_DRAFT + 1e-9


def test_whole_ship_seams_are_shared_by_the_parts_on_both_sides(ship_meshes):
    m = ship_meshes["whole"]
    edges = {}
    for f, part in zip(m.faces, m.face_part):
        k = 3 if f[3] < 0 else 4
        for i in range(k):
            edges.setdefault(tuple(sorted((f[i], f[(i + 1) % k]))), []).append(m.parts[part])
    pairs = {tuple(sorted(set(p))) for p in edges.values() if len(set(p)) == 2}
    assert {("blend", "hull"), ("blend", "bulb"), ("aft", "hull")} <= pairs


def test_whole_ship_transom_is_dry_and_the_open_wetted_part_ends_on_the_waterline(blended, ship_meshes):
    m = ship_meshes["open"]
    assert "aft" not in m.parts  # the transom lies above the design draft
    open_, nonman, misor = edge_census(m.faces)
    assert nonman == 0 and misor == 0 and open_ > 0
    f = m.faces
    rows = [(r[i], r[(i + 1) % (3 if r[3] < 0 else 4)]) for r in f for i in range(3 if r[3] < 0 else 4)]
    und, counts = np.unique(np.sort(np.array(rows), axis=1), axis=0, return_counts=True)
    rim = m.vertices[np.unique(und[counts == 1])]
    on_wl = np.abs(rim[:, 2] - EXAMPLE_DRAFT) < 1e-9
    on_cp = np.abs(rim[:, 1]) < 1e-9
    assert np.all(on_wl | on_cp)  # open only along the waterline (and the centre plane of the half)


def test_whole_ship_mesh_volume_matches_the_composed_hull(blended, ship_meshes):
    whole = 2 * closed_volume(ship_meshes["whole"].vertices, ship_meshes["whole"].faces)
    assert whole == pytest.approx(2 * blended.volume, rel=MESH_VOLUME_TOL)


def test_bare_hull_mesh_volume_matches_nurbs_hydrostatics():
    s = example_hull().bare_hull_surface()
    m = fl.mesh_hull(s, size=SHIP_SIZE, draft=EXAMPLE_DRAFT)
    ref = fl.hydrostatics(s, EXAMPLE_DRAFT).volume
    assert 2 * closed_volume(m.vertices, m.faces) == pytest.approx(ref, rel=MESH_VOLUME_TOL)


def test_coarse_wetted_mesh_follows_the_waterline_round_its_tight_turn(blended):
    """At 8 m the waterline trace's step is longer than the level curve's turn near the DWL's
    end on the centre plane: the corrector must not jump across the face (it looped there)."""
    m = fl.mesh_hull(blended, size=8.0, draft=EXAMPLE_DRAFT)
    assert edge_census(m.faces) == (0, 0, 0)
    assert m.vertices[:, 2].max() <= EXAMPLE_DRAFT + 1e-9


CUT_DRAFTS = (2.0, 8.0, 11.0, 14.0, 17.0)  # m: keel to deck, through the bulb and the transom's edge (11.55 m)
# m: the chords of the bilge and of the flat of bottom's rounded corner (0.15 of B/2 there, rounded
# over 1.2 m) cut 0.21 % of the volume at 2 m at 1.5 m, 0.14 % at 1 m (without the flat 0.15 % at 1.5 m)
CUT_SIZE = 1.0


@pytest.fixture(scope="module")
def cut_meshes(blended):
    """Closed wetted meshes of the whole ship at drafts from the keel to the deck."""
    return {t: fl.mesh_hull(blended, size=CUT_SIZE, draft=t) for t in CUT_DRAFTS}


@pytest.mark.parametrize("draft", CUT_DRAFTS)
def test_wetted_mesh_at_any_draft_is_watertight(cut_meshes, draft):
    """Above the transom's lower edge (11.55 m) the waterline trace on the hull runs into the
    aft edge of the parameter domain; it used to slide along it and never leave."""
    assert edge_census(cut_meshes[draft].faces) == (0, 0, 0)


@pytest.mark.parametrize("draft", CUT_DRAFTS)
def test_wetted_mesh_volume_at_any_draft_matches_nurbs_quadrature(blended, cut_meshes, draft):
    m = cut_meshes[draft]
    volume, _ = composed_wetted_hydrostatics(blended, draft)
    assert 2 * closed_volume(m.vertices, m.faces) == pytest.approx(volume, rel=MESH_VOLUME_TOL)


@pytest.mark.parametrize("draft", (14.0, 17.0))
def test_cut_near_a_trim_curve_end_and_at_the_stem_top_leaves_no_sliver(blended, draft):
    """At 14 m the waterline passes 9 cm above the stem's vertex where the bulb's trim curve
    ends (a 9 cm stem edge: it used to be fanned to a 3 m side, scaled Jacobian 0.036); at 17 m
    the waterline's trace from the stem used to leap 18 m along the stem's nearly degenerate
    end, and its nodes bunched there in a fan (0.016)."""
    assert fl.mesh_hull(blended, size=3.0, draft=draft).quality()["min_scaled_jacobian"] >= 0.2


def test_cruiser_stern_ship_meshes_watertight_with_its_volume():
    s = cruiser_stern_ship().bare_hull_surface()  # no bulb: composed alone
    for draft in (None, 5.0):
        m = fl.mesh_hull(s, size=1.5, draft=draft)
        assert "aft" not in m.parts and edge_census(m.faces) == (0, 0, 0)
        assert np.all(fl._native.scaled_jacobians(m.vertices, m.faces) > 0)
    assert 2 * closed_volume(m.vertices, m.faces) == pytest.approx(fl.hydrostatics(s, 5.0).volume,
                                                                   rel=MESH_VOLUME_TOL)


@pytest.mark.parametrize("aft, rake", [("cruiser", 0.0), ("transom", 0.0), ("transom", 20.0)])
def test_every_aft_closure_composes_and_meshes_watertight(aft, rake):
    s = wigley_surface(aft=aft, rake_deg=rake)
    T = WIGLEY["T"]
    c = fl.compose([s])
    from conftest import edge_census as tri_census
    assert tri_census(c.mesh.faces) == (0, 0, 0)
    assert tri_census(c.full_mesh().faces) == (0, 0, 0)
    m = fl.mesh_hull(c, size=1.0, draft=T)
    assert edge_census(m.faces) == (0, 0, 0)
    assert ("aft" in m.parts) == (aft == "transom")
    assert 2 * closed_volume(m.vertices, m.faces) == pytest.approx(fl.hydrostatics(s, T).volume, rel=MESH_VOLUME_TOL)


def test_files_reread_by_meshio_give_the_same_mesh(ship_meshes, tmp_path):
    m = ship_meshes["wetted"]
    for name in ("hull.msh", "hull.vtu", "hull.obj"):
        fl.write_mesh(m, tmp_path / name)
        r = fl.read_mesh(tmp_path / name)
        assert np.allclose(r.vertices, m.vertices)
        key = lambda f: sorted(tuple(row) for row in f)  # noqa: E731
        assert key(r.faces) == key(m.faces)
    fl.write_mesh(m, tmp_path / "hull.stl", binary=False)
    assert (tmp_path / "hull.stl").read_text().count("facet normal") == len(m.triangulated())


def test_panel_files_read_by_capytaine_give_the_same_panels_and_hydrostatics(wigley, tmp_path):
    cpt = pytest.importorskip("capytaine")
    T = WIGLEY["T"]
    m = fl.mesh_hull(wigley, size=2.0, draft=T, lids=False)  # half hull, open at the waterline
    n = len(m.faces)
    assert 1000 < 2 * n < 4000
    ref = fl.hydrostatics(wigley, T)
    for name, fmt, writer in (("w.gdf", "gdf", fl.write_gdf), ("w.mar", "mar", fl.write_mar)):
        writer(m, tmp_path / name)
        cm = cpt.load_mesh(tmp_path / name, file_format=fmt)
        assert cm.nb_faces == 2 * n  # the mirrored half comes from the symmetry flag
        assert cm.volume == pytest.approx(ref.volume, rel=CAPYTAINE_TOL)
        assert cm.waterplane_area == pytest.approx(ref.waterplane_area, rel=CAPYTAINE_TOL)
        assert cm.wet_surface_area == pytest.approx(ref.wetted_surface, rel=CAPYTAINE_TOL)
        cob = cm.center_of_buoyancy
        assert cob[0] == pytest.approx(ref.lcb, abs=CAPYTAINE_TOL * WIGLEY["L"])
        assert cob[2] + T == pytest.approx(ref.vcb, abs=CAPYTAINE_TOL * T)


def test_whole_ship_wetted_panels_give_capytaine_the_nurbs_hydrostatics(blended, ship_meshes, tmp_path):
    cpt = pytest.importorskip("capytaine")
    m, T = ship_meshes["open"], EXAMPLE_DRAFT
    bare = fl.hydrostatics(example_hull().bare_hull_surface(), T)  # NURBS quadrature, both sides
    volume, lcb = composed_wetted_hydrostatics(blended, T)
    fl.write_gdf(m, tmp_path / "ship.gdf")
    cm = cpt.load_mesh(tmp_path / "ship.gdf", file_format="gdf")
    assert cm.nb_faces == 2 * len(m.faces)
    assert cm.volume == pytest.approx(volume, rel=CAPYTAINE_TOL)
    assert cm.waterplane_area == pytest.approx(bare.waterplane_area, rel=CAPYTAINE_TOL)
    assert cm.center_of_buoyancy[0] == pytest.approx(lcb, abs=CAPYTAINE_TOL * 244.8)


def test_plot3d_round_trip(tmp_path):
    a = np.random.default_rng(1).normal(size=(5, 4, 3))
    b = np.random.default_rng(2).normal(size=(3, 7, 3))
    fl.write_plot3d([a, b], tmp_path / "g.xyz")
    r = fl.read_plot3d(tmp_path / "g.xyz")
    assert np.allclose(r[0], a) and np.allclose(r[1], b)
    head = (tmp_path / "g.xyz").read_text().split("\n")[:3]
    assert head == ["2", "5 4 1", "3 7 1"]


def test_a_mesh_option_of_the_wrong_type_is_refused_by_name(bilge):
    with pytest.raises(fl.InvalidInput, match="mesh option all_quad is 'yes'; expected a bool"):
        fl.mesh_surface(bilge, size=1.0, all_quad="yes")


def test_bad_mesh_input_is_refused(bilge, blended):
    with pytest.raises(fl.InvalidInput, match="size is -1"):
        fl.mesh_surface(bilge, size=-1.0)
    with pytest.raises(fl.InvalidInput, match="unknown"):
        fl.mesh_surface(bilge, size=1.0, smoothness=3)
    with pytest.raises(fl.InvalidInput, match="draft is 40"):
        fl.mesh_hull(blended, size=2.0, draft=40.0)
    with pytest.raises(fl.InvalidInput, match="draft"):
        fl.write_gdf(fl.mesh_surface(bilge, size=2.0), "/tmp/never.gdf")


def test_a_size_too_small_for_the_hull_is_refused_naming_one_that_meshes(blended):
    """A 1 mm size on the container ship asked billions of elements: the engine ran out of
    memory after a minute and a half. Refused at once, naming the least size within the budget;
    that size meshes."""
    with pytest.raises(fl.InvalidInput, match=r"size is 0.001 m, about .* elements .*; expected at most 2000000"):
        fl.mesh_hull(blended, size=0.001)
    with pytest.raises(fl.InvalidInput, match=r"expected at most 3000 \(size >= ") as info:
        fl.mesh_hull(blended, size=1.0, max_elements=3000)
    least = float(re.search(r"size >= ([\d.]+) m", str(info.value)).group(1))
    assert len(fl.mesh_hull(blended, size=least, max_elements=3000).faces) > 1000


def test_cli_meshes_a_ship_without_a_bulb_into_panels(tmp_path):
    from fairlines.cli import main
    src = tmp_path / "cruiser.json"
    src.write_text(cruiser_stern_ship().to_json())
    assert main(["mesh", str(src), "--size", "2", "--draft", "5", "--open", "-o", str(tmp_path / "c.gdf")]) == 0
    rows = (tmp_path / "c.gdf").read_text().split("\n")
    assert int(rows[3].split()[0]) > 100  # panel count after ULEN/g, symmetry flags


def test_cli_refuses_a_size_too_small_for_the_hull(tmp_path, capsys):
    from fairlines.cli import main
    src = tmp_path / "cruiser.json"
    src.write_text(cruiser_stern_ship().to_json())
    assert main(["mesh", str(src), "--size", "0.01", "-o", str(tmp_path / "c.vtu")]) == 2
    assert "expected at most 2000000" in capsys.readouterr().err
    assert main(["mesh", str(src), "--size", "3", "--max-elements", "10", "-o", str(tmp_path / "c.vtu")]) == 2
    assert "expected at most 10 (size >= " in capsys.readouterr().err
