"""All-quad meshes and element quality at the hull's poles and the blend's ends.

Truths used: the surfaces' own closest points (chordal deviation), numpy edge censuses,
scaled Jacobians and volumes, NURBS quadrature of the blend surface (the volume the y >= 0 clamp removes) and of
the bare hull (fl.hydrostatics), the stem-top point evaluated on the NURBS surface.
"""

import numpy as np
import pytest

import fairlines as fl
from mesh_fixtures import (EXAMPLE_DRAFT, bilge_patch, closed_volume, composed_example_hull,
                           composed_wetted_hydrostatics, edge_census, example_hull_surface,
                           knupp_scaled_jacobians, quad_corner_angles)

SHIP_SIZE = 3.0          # m, element size on the whole ship (about 1.2 % of Lpp)
SHIP_TOL = 0.03          # m, chordal tolerance of the bench's whole-ship cases
MIN_SJ = 0.2             # scaled Jacobian below which an element is a sliver
CORNER_SHARE = 0.99      # share of quad corners within CORNER_LIMITS (the goal)
CORNER_LIMITS = (45.0, 135.0)  # deg, a quad corner's good range
QUAD_SHARE = 0.98        # share of quadrilaterals in the default (quad-dominant) mesh (the goal)
NEIGHBOUR_SIZE_RATIO = 3.0  # neighbouring elements' mean sides differ by at most this (2:1 steps, triangles)
WEDGE_RADIUS = 8.0       # m, the stem-top wedge: hull elements this close to the stem top
CLAMP_VOLUME_TOL = 1e-4  # volume the y >= 0 clamp may remove, relative to the half hull's
MESH_VOLUME_TOL = 2e-3   # closed mesh vs NURBS quadrature at this element size
CAPYTAINE_TOL = 3e-3     # capytaine's panel hydrostatics converge as O(h^2)
# m: 1 m reported with flat triangles at the stem top (mesh7), 0.9 m had them on this hull; at
# 0.9-0.7 m the blend's top end ran as a sheared strip up the stem (least 0.003-0.005)
FINE_SHIP_SIZES = (1.0, 0.9, 0.8, 0.7)


@pytest.fixture(scope="module")
def ship():
    return composed_example_hull()


@pytest.fixture(scope="module")
def bare():
    return example_hull_surface()


@pytest.fixture(scope="module")
def all_quad_ship(ship):
    return fl.mesh_hull(ship, size=SHIP_SIZE, all_quad=True)


def stem_top(surface):
    """The bare hull's stem-top pole (u = u1 collapses to one point), on the NURBS surface."""
    return np.asarray(surface.evaluate(surface.knots_u[-1], surface.knots_v[-1]))


def test_all_quad_whole_ship_has_only_quadrilaterals(all_quad_ship):
    assert len(all_quad_ship.faces) > 5000
    assert np.all(all_quad_ship.faces[:, 3] >= 0)


def test_all_quad_whole_ship_is_watertight_conforming_without_duplicate_nodes(all_quad_ship):
    m = all_quad_ship
    assert edge_census(m.faces) == (0, 0, 0)  # every seam's split midpoints shared
    assert len(np.unique(np.round(m.vertices, 9), axis=0)) == len(m.vertices)
    edges = {}
    for f, part in zip(m.faces, m.face_part):
        for i in range(4):
            edges.setdefault(tuple(sorted((f[i], f[(i + 1) % 4]))), set()).add(m.parts[part])
    pairs = {tuple(sorted(p)) for p in edges.values() if len(p) == 2}
    assert {("blend", "hull"), ("blend", "bulb"), ("aft", "hull"), ("centre_plane", "hull")} <= pairs


@pytest.mark.parametrize("size", [3.0, 1.5])
def test_all_quad_composed_ship_has_no_inverted_element(ship, size):
    """Both of the blend's folded ends (stem and keel) and the bulb's nose: every quad positive
    at all four corners about its diagonal normal, by numpy."""
    m = fl.mesh_hull(ship, size=size, all_quad=True)
    assert np.all(m.faces[:, 3] >= 0)
    assert knupp_scaled_jacobians(m.vertices, m.faces).min() > 0


def test_all_quad_composed_ship_wetted_volume_matches_nurbs_hydrostatics(ship):
    m = fl.mesh_hull(ship, size=SHIP_SIZE, draft=EXAMPLE_DRAFT, all_quad=True)
    volume, _ = composed_wetted_hydrostatics(ship, EXAMPLE_DRAFT)
    assert 2 * closed_volume(m.vertices, m.faces) == pytest.approx(volume, rel=MESH_VOLUME_TOL)


def test_all_quad_split_keeps_the_chordal_tolerance():
    s, tol = bilge_patch(), 0.002
    m = fl.mesh_surface(s, size=1.0, chordal_tolerance=tol, all_quad=True)
    centroids = m.vertices[m.faces].mean(axis=1)  # every element, its nodes at twice the size first
    dev = [np.linalg.norm(s.closest_point(p)[2] - p) for p in centroids]
    assert len(centroids) > 1000 and max(dev) <= tol


def corner_share(mesh):
    """Share of the mesh's quad corners within CORNER_LIMITS, by numpy."""
    angles = quad_corner_angles(mesh.vertices, mesh.faces)
    return np.mean((angles >= CORNER_LIMITS[0]) & (angles <= CORNER_LIMITS[1]))


def test_all_quad_corners_lie_within_45_135_degrees(all_quad_ship):
    assert corner_share(all_quad_ship) >= CORNER_SHARE


def test_all_quad_open_wetted_corners_lie_within_45_135_degrees(ship):
    """The lowest share of the all-quad cases before the corner pass ran on the split (97.8 %)."""
    m = fl.mesh_hull(ship, size=SHIP_SIZE, draft=EXAMPLE_DRAFT, lids=False, all_quad=True)
    assert corner_share(m) >= CORNER_SHARE


@pytest.mark.parametrize("all_quad", [False, True])
def test_bare_hull_with_its_stem_top_pole_has_no_sliver(bare, all_quad):
    q = fl.mesh_surface(bare, size=SHIP_SIZE, chordal_tolerance=SHIP_TOL, all_quad=all_quad).quality()
    assert q["inverted"] == 0 and q["min_scaled_jacobian"] >= MIN_SJ


@pytest.mark.parametrize("size, all_quad", [(3.0, False), (3.0, True), (1.5, False), (1.5, True)])
def test_composed_ship_stem_top_wedge_has_no_sliver(ship, bare, size, all_quad):
    m = fl.mesh_hull(ship, size=size, all_quad=all_quad)
    sj = fl._native.scaled_jacobians(m.vertices, m.faces)
    centroids = np.array([m.vertices[f[f >= 0]].mean(axis=0) for f in m.faces])
    wedge = (m.face_part == m.parts.index("hull")) & (np.linalg.norm(centroids - stem_top(bare), axis=1) < WEDGE_RADIUS)
    assert wedge.sum() > 20  # about 30 quad-dominant elements at 3 m
    assert sj[wedge].min() >= MIN_SJ


@pytest.fixture(scope="module")
def default_meshes(ship):
    """The whole ship's default (quad-dominant) meshes at 3 and 1.5 m."""
    return {size: fl.mesh_hull(ship, size=size) for size in (SHIP_SIZE, SHIP_SIZE / 2)}


@pytest.mark.parametrize("size", [SHIP_SIZE, SHIP_SIZE / 2])
def test_default_mesh_of_the_composed_ship_is_nearly_all_quadrilaterals(default_meshes, size):
    """Triangle pairs across the 2:1 steps of the subdivision (a straight corner at the step's
    middle node) are merged once their node is moved off the line; counted by numpy."""
    faces = default_meshes[size].faces
    assert np.mean(faces[:, 3] >= 0) >= QUAD_SHARE


@pytest.mark.parametrize("size", [SHIP_SIZE, SHIP_SIZE / 2])
def test_default_mesh_of_the_composed_ship_has_no_sliver(default_meshes, size):
    m = default_meshes[size]
    assert knupp_scaled_jacobians(m.vertices, m.faces).min() >= MIN_SJ


@pytest.mark.parametrize("size", FINE_SHIP_SIZES)
def test_fine_default_mesh_has_no_flat_triangle_at_the_stem_top(ship, size):
    """At 0.9 m four stem nodes in a straight row at the stem-top pole made two flat triangles
    (scaled Jacobian 0.0000), one against the other, which the pole merge's single flip pass
    could not reach (the inner one can flip only after the outer one). At 0.9-0.7 m the blend's
    top end, an arc running up the stem along the hull's sections, fell to 0.003-0.005."""
    m = fl.mesh_hull(ship, size=size)
    assert knupp_scaled_jacobians(m.vertices, m.faces).min() >= MIN_SJ


@pytest.mark.parametrize("size", [SHIP_SIZE, SHIP_SIZE / 2])
def test_default_mesh_corners_lie_within_45_135_degrees(default_meshes, size):
    """The merged pairs across the 2:1 steps of the subdivision (a straight corner at the step's
    middle node) open their corners toward 90 deg; angles by numpy."""
    m = default_meshes[size]
    assert np.sum(m.faces[:, 3] >= 0) > 8000
    assert corner_share(m) >= CORNER_SHARE


def test_composed_ship_quad_dominant_mesh_has_no_inverted_element(ship):
    for size in (4.0, 3.0, 1.5):  # at 4 m smoothing folded a quad in the blend's creased keel end
        assert fl.mesh_hull(ship, size=size).quality()["inverted"] == 0


def test_half_hull_mesh_stays_on_its_side_of_the_centre_plane(ship):
    m = fl.mesh_hull(ship, size=SHIP_SIZE)
    assert m.vertices[:, 1].min() == 0.0


def test_clamping_the_blend_at_the_centre_plane_removes_a_negligible_volume(ship):
    """The volume the mesher's y >= 0 clamp removes (int max(-y, 0) over the blend's (x, z)
    projection, Gauss quadrature of the NURBS blend) is far below the half hull's. The blend
    dipped up to 6.6 cm across y = 0 near its ends; its tangent handles now turn to stay off
    the plane, and no Gauss point lies below it."""
    blend = ship.blend
    g, w = np.polynomial.legendre.leggauss(8)
    u_knots = np.linspace(0.0, 1.0, 201)
    removed, dipped = 0.0, False
    for a, b in zip(u_knots[:-1], u_knots[1:]):
        for c, d in zip(np.linspace(0, 1, 41)[:-1], np.linspace(0, 1, 41)[1:]):
            for gu, wu in zip(g, w):
                for gv, wv in zip(g, w):
                    u, v = a + (b - a) * (gu + 1) / 2, c + (d - c) * (gv + 1) / 2
                    D = np.asarray(blend.derivatives(u, v, 1))
                    y = D[0, 0][1]
                    if y < 0:
                        dipped = True
                        jac = abs(D[1, 0][0] * D[0, 1][2] - D[1, 0][2] * D[0, 1][0])
                        removed += -y * jac * wu * wv * (b - a) * (d - c) / 4
    assert not dipped
    assert removed < CLAMP_VOLUME_TOL * ship.volume


def test_all_quad_wetted_volume_matches_nurbs_hydrostatics(bare):
    m = fl.mesh_hull(bare, size=SHIP_SIZE, draft=EXAMPLE_DRAFT, all_quad=True)
    assert np.all(m.faces[:, 3] >= 0)
    ref = fl.hydrostatics(bare, EXAMPLE_DRAFT).volume
    assert 2 * closed_volume(m.vertices, m.faces) == pytest.approx(ref, rel=MESH_VOLUME_TOL)


def test_all_quad_open_wetted_mesh_ends_on_the_waterline_or_centre_plane(ship):
    m = fl.mesh_hull(ship, size=SHIP_SIZE, draft=EXAMPLE_DRAFT, lids=False, all_quad=True)
    assert np.all(m.faces[:, 3] >= 0)
    rows = np.array([(r[i], r[(i + 1) % 4]) for r in m.faces for i in range(4)])
    und, counts = np.unique(np.sort(rows, axis=1), axis=0, return_counts=True)
    rim = m.vertices[np.unique(und[counts == 1])]
    assert np.all((np.abs(rim[:, 2] - EXAMPLE_DRAFT) < 1e-9) | (np.abs(rim[:, 1]) < 1e-9))


def test_all_quad_cut_through_the_bulb_is_watertight(ship):
    """A waterline below the bulb's top cuts the bulb face; its nose pole edge (one vertex at
    both ends) must stay in the bulb's loop, not become a face of its own."""
    m = fl.mesh_hull(ship, size=2.0, draft=8.0, all_quad=True)
    assert edge_census(m.faces) == (0, 0, 0)


def test_all_quad_cut_through_the_bulb_is_quads_only(ship):
    m = fl.mesh_hull(ship, size=2.0, draft=8.0, all_quad=True)
    assert np.all(m.faces[:, 3] >= 0)


def test_all_quad_open_wetted_panels_give_capytaine_the_nurbs_volume(bare, tmp_path):
    cpt = pytest.importorskip("capytaine")
    m = fl.mesh_hull(bare, size=SHIP_SIZE, draft=EXAMPLE_DRAFT, lids=False, all_quad=True)
    fl.write_gdf(m, tmp_path / "quads.gdf")
    cm = cpt.load_mesh(tmp_path / "quads.gdf", file_format="gdf")
    ref = fl.hydrostatics(bare, EXAMPLE_DRAFT)
    assert cm.nb_faces == 2 * len(m.faces)
    assert cm.volume == pytest.approx(ref.volume, rel=CAPYTAINE_TOL)
    assert cm.waterplane_area == pytest.approx(ref.waterplane_area, rel=CAPYTAINE_TOL)


def test_bem_panels_of_the_wetted_ship_have_no_sliver_where_a_waterline_runs_close_to_a_trim_curve(ship):
    """Where the waterline runs a few centimetres from a trim curve (or two trim curves run
    close), the strip between them is meshed by elements as wide as the gap, not by slivers
    fanned across it from nodes a size apart (least scaled Jacobian 0.211 before)."""
    m = fl.mesh_hull(ship, size=SHIP_SIZE, draft=EXAMPLE_DRAFT, lids=False)
    assert knupp_scaled_jacobians(m.vertices, m.faces).min() >= 0.3


def _peer_case(case, bare):
    return (bilge_patch(), 0.5, 0.005) if case == "bilge patch" else (bare, SHIP_SIZE, SHIP_TOL)


def _census(V, F):
    return fl.mesh_quality(fl.SurfaceMesh(V, F, np.zeros(len(F), int), ("s",)))


@pytest.mark.parametrize("case", ["bilge patch", "bare hull"])
def test_default_mesh_scores_at_least_gmsh_held_to_the_same_chordal_tolerance(bare, case):
    """Least and mean scaled Jacobian (one census for both) at least those of gmsh's Blossom quads
    on the same B-spline surface and element size in the same run, gmsh's curvature sizing
    raised until its mesh keeps the same chordal tolerance (like with like). Before the mean pass
    and the valence-3 split the bilge patch's minimum was 0.680 against gmsh's 0.721; before the
    curvature size was graded inside the face the bare hull's mean was 0.9189 against gmsh's
    0.9186 (curvature 96, 15 294 elements), 0.934 after (gmsh 4.15.2, 2026-12-04)."""
    pytest.importorskip("gmsh")
    from mesh_fixtures import gmsh_meeting

    surface, size, tol = _peer_case(case, bare)
    q = fl.mesh_surface(surface, size=size, chordal_tolerance=tol).quality()
    _, (V, F, _) = gmsh_meeting(surface, size, tol)
    g = _census(V, F)
    assert q["min_scaled_jacobian"] >= g["min_scaled_jacobian"]
    assert q["mean_scaled_jacobian"] >= g["mean_scaled_jacobian"]


@pytest.mark.parametrize("case", ["bilge patch", "bare hull"])
def test_default_mesh_least_score_is_at_least_gmsh_at_its_common_setting(bare, case):
    """gmsh at its common curvature sizing (12 per 2 pi: 4-5 times our tolerance, 5 times fewer
    elements): our least scaled Jacobian is at least its (bilge patch 0.680 against 0.720 before)."""
    pytest.importorskip("gmsh")
    from mesh_fixtures import gmsh_mesh

    surface, size, tol = _peer_case(case, bare)
    q = fl.mesh_surface(surface, size=size, chordal_tolerance=tol).quality()
    V, F, _ = gmsh_mesh(surface, size)
    assert q["min_scaled_jacobian"] >= _census(V, F)["min_scaled_jacobian"]


@pytest.mark.parametrize("case", ["bilge patch", "bare hull"])
def test_default_mesh_mean_score_and_corners_are_at_least_gmsh_at_its_common_setting(bare, case):
    """Mean scaled Jacobian and share of quad corners within 45-135 deg at least gmsh's at its common
    curvature sizing. Before the curvature size was graded inside the face the bare hull missed both:
    mean 0.919 against 0.921, corners 99.58 against 99.63 %; after, 0.934 and 99.98 % (gmsh 4.15.2;
    on this main's hull 0.934 and 99.87 % against 0.918 and 99.13 %)."""
    pytest.importorskip("gmsh")
    from mesh_fixtures import gmsh_mesh

    surface, size, tol = _peer_case(case, bare)
    q = fl.mesh_surface(surface, size=size, chordal_tolerance=tol).quality()
    V, F, _ = gmsh_mesh(surface, size)
    g = _census(V, F)
    assert q["mean_scaled_jacobian"] >= g["mean_scaled_jacobian"]
    assert q["corners_in_45_135"] >= g["corners_in_45_135"]


def test_bare_hull_element_size_changes_gradually_between_neighbours(bare):
    """The curvature size is graded inside the face, not only from its boundary, and a quad
    much smaller than a neighbour is collapsed: neighbouring elements' mean sides differ by at
    most NEIGHBOUR_SIZE_RATIO. Before the collapse the example had one quad of 0.59 m beside one
    of 1.95 m at x 212.6 m, z 4.0 m (ratio 3.30; the corner pass had made it), after it 2.49 at
    most. The ungraded mesher's largest, 4.02 on an earlier hull, was one small quad (0.32 m
    among 1.2 m ones at the forefoot)."""
    assert worst_neighbour_size_ratio(fl.mesh_surface(bare, size=SHIP_SIZE, chordal_tolerance=SHIP_TOL)) <= NEIGHBOUR_SIZE_RATIO


def worst_neighbour_size_ratio(m) -> float:
    """The largest ratio of the mean sides of two elements sharing a side."""
    V, F = np.asarray(m.vertices), np.asarray(m.faces)
    rings = [row[row >= 0] for row in F]
    mean_side = np.array([np.linalg.norm(V[np.roll(r, -1)] - V[r], axis=1).mean() for r in rings])
    sides = {}
    for e, r in enumerate(rings):
        for a, b in zip(r, np.roll(r, -1)):
            sides.setdefault((min(a, b), max(a, b)), []).append(e)
    pairs = np.array([s for s in sides.values() if len(s) == 2])
    h0, h1 = mean_side[pairs[:, 0]], mean_side[pairs[:, 1]]
    return float((np.maximum(h0, h1) / np.minimum(h0, h1)).max())


def test_small_quad_is_collapsed_where_a_node_would_be_left_in_two_quads():
    """A designed coaster (bench_hull's sample 39 of 100) at Lpp / 80: the collapse of its
    smallest quad (mean side 0.17 m among 0.6-0.7 m ones at the forefoot, x 112.5 m, z 1.4 m) left
    a free node in two quads and was refused (ratio 4.15); the two quads now become one and the
    collapse stands (2.35 at most, least scaled Jacobian 0.565 both ways). Since the SAC holds the
    stations where its keel leaves the water inside the family (hull.BAND_FREE_DRY_DEPTH) its mesh
    had a triangle of 0.17 m beside a 0.68 m quad there (x -1.4 m, z 6.2 m; ratio 3.97): small
    triangles are collapsed along a side too (2.41 at most)."""
    hull = fl.design_hull(lpp=115.73465, breadth=20.704413, draft=6.5236795, depth=10.437887, cb=0.83916908,
                          lcb=54.219531)
    m = fl.mesh_surface(hull.bare_hull_surface(), size=115.73465 / 80, chordal_tolerance=SHIP_TOL * 115.73465 / 244.8)
    assert worst_neighbour_size_ratio(m) <= NEIGHBOUR_SIZE_RATIO
