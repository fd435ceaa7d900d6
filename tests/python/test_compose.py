"""Bulbous bow, surface-surface intersection and the composed watertight hull.

Analytic stand-in (the real Panamax hull is in test_compose_panamax.py): a Wigley-type
forebody y = B/2 (1 - xi^4) (1 - (1 - z/D)^6) fitted as a bicubic surface, with Panamax particulars. Every check below
uses code of its own (numpy edge census, quadrature of the NURBS surfaces) rather than the
engine's own checks.
"""

import numpy as np
import pytest
from matplotlib.path import Path

import fairlines as fl
from conftest import edge_census
from mesh_fixtures import forebody_surface

L, B, T, D = 244.8, 32.25, 11.0, 19.0
SHIP = dict(lpp=L, beam=B, draft_fp=T, midship_area=0.97 * B * T, displacement_volume=0.65 * L * B * T)
KRACHT_TOL = 0.02      # bulb's Kracht coefficients measured on its mesh vs the requested ones: within 2 %
VOLUME_TOL = 0.002     # composing keeps volume: composed = bare + bulb's added volume within 0.2 %


@pytest.fixture(scope="module")
def hull():
    return forebody_surface()


@pytest.fixture(scope="module")
def bulb():
    return fl.BulbousBow(**SHIP)


@pytest.fixture(scope="module")
def composed(hull, bulb):
    return fl.compose([hull, bulb])


def test_composed_half_hull_is_closed_manifold_and_oriented(composed):
    m = composed.mesh
    assert m.vertices.shape[1] == 3 and m.faces.shape[1] == 3
    assert edge_census(m.faces) == (0, 0, 0)
    assert not np.any(m.faces[:, 0] == m.faces[:, 1]) and not np.any(m.faces[:, 1] == m.faces[:, 2])
    # outward: the signed volume (own divergence sum) is positive
    t = m.vertices[m.faces]
    vol = np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0
    assert vol > 0 and vol == pytest.approx(composed.volume, rel=1e-12)
    assert np.all(m.vertices[:, 1] >= 0.0)


def test_full_hull_is_closed_and_twice_the_half(composed):
    full = composed.full_mesh()
    assert edge_census(full.faces) == (0, 0, 0)
    assert full.volume == pytest.approx(2.0 * composed.volume, rel=1e-9)
    assert full.vertices[:, 1].min() == pytest.approx(-full.vertices[:, 1].max())


def test_seam_vertices_lie_on_both_surfaces_and_are_shared(composed, bulb):
    hull_s = composed.trimmed_surfaces[0][0]
    seam = composed.mesh.vertices[composed.seam_vertices]
    for p in seam[:: max(1, len(seam) // 8)]:
        assert np.linalg.norm(hull_s.closest_point(p)[2] - p) < 1e-6
        assert np.linalg.norm(bulb.surface.closest_point(p)[2] - p) < 1e-6
    (curve,) = composed.intersection_curves
    assert curve["max_gap"] <= 1e-6
    # each seam edge is used by one hull face and one bulb face
    f, part = composed.mesh.faces, composed.face_part
    for a, b in zip(composed.seam_vertices[:-1], composed.seam_vertices[1:]):
        users = [i for i in np.nonzero(np.any(f == a, axis=1) & np.any(f == b, axis=1))[0]]
        assert sorted(part[users].tolist()) == [0, 1]


def test_intersection_of_sphere_and_plane_is_the_circle():
    s = fl.sphere([0.0, 0.0, 0.0], 3.0)
    plane = fl.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1],
                            [[[-5, -5, 1], [-5, 5, 1]], [[5, -5, 1], [5, 5, 1]]])
    curves = fl.intersect_surfaces(s, plane)
    pts = np.concatenate([c["points"] for c in curves])
    assert len(pts) > 20
    assert np.abs(np.hypot(pts[:, 0], pts[:, 1]) - np.sqrt(8.0)).max() < 1e-6
    assert max(c["max_gap"] for c in curves) <= 1e-6


def test_kracht_coefficients_measured_back_within_two_percent(composed, bulb):
    got = fl.measure_kracht(composed.mesh, x_fp=L, **SHIP)
    for name in fl.KRACHT_NAMES:
        assert got[name] == pytest.approx(bulb.kracht[name], rel=KRACHT_TOL), name


def _flux_y(surface, loop=None, n=400):
    """int y n_y dA over the surface (or the part inside a parameter-space loop), by the
    midpoint rule on an n x n parameter grid with central-difference partials."""
    ku, kv = surface.knots_u, surface.knots_v
    u0, u1, v0, v1 = ku[0], ku[-1], kv[0], kv[-1]
    if loop is not None:
        u0, v0 = np.maximum(loop.min(axis=0), [u0, v0])
        u1, v1 = np.minimum(loop.max(axis=0), [u1, v1])
    du, dv = (u1 - u0) / n, (v1 - v0) / n
    uc = u0 + du * (np.arange(n) + 0.5)
    vc = v0 + dv * (np.arange(n) + 0.5)
    U, V = [a.ravel() for a in np.meshgrid(uc, vc, indexing="ij")]
    if loop is not None:
        keep = Path(loop).contains_points(np.column_stack([U, V]))
        U, V = U[keep], V[keep]
    h = 1e-6
    su = (surface.evaluate(np.minimum(U + h, u1), V) - surface.evaluate(np.maximum(U - h, u0), V)) / (
        np.minimum(U + h, u1) - np.maximum(U - h, u0))[:, None]
    sv = (surface.evaluate(U, np.minimum(V + h, v1)) - surface.evaluate(U, np.maximum(V - h, v0))) / (
        np.minimum(V + h, v1) - np.maximum(V - h, v0))[:, None]
    y = surface.evaluate(U, V)[:, 1]
    return float(np.sum(y * np.cross(su, sv)[:, 1]) * du * dv)


def test_composed_volume_is_bare_plus_bulb_two_independent_ways(hull, composed, bulb):
    """Way 1: divergence theorem on the meshes. Way 2: quadrature of y n_y over the NURBS
    surfaces (the caps add nothing: n_y = 0 on deck and aft cut, y = 0 on the centre plane):
    bare = whole hull surface; added = kept bulb - hull hole, over their trimming loops."""
    bare = fl.compose([hull])
    hull_s = composed.trimmed_surfaces[0][0]
    sign = -1.0 if _flux_y(hull_s, n=200) < 0 else 1.0  # u forward, v up: S_u x S_v points inward
    v_bare_q = sign * _flux_y(hull_s, n=200)
    (hole,) = [l for l in composed.trimmed_surfaces[0][1]]
    seam_uv = composed.intersection_curves[0]["uv_a"]
    hole_loop = np.vstack([seam_uv, [[hull_s.knots_u[-1], hull_s.knots_v[0]]]])
    (bulb_loop,) = composed.trimmed_surfaces[1][1]
    v_added_q = sign * (_flux_y(bulb.surface, bulb_loop) - _flux_y(hull_s, hole_loop))
    v_added_mesh = composed.volume - bare.volume
    assert bare.volume == pytest.approx(v_bare_q, rel=VOLUME_TOL)
    assert composed.volume == pytest.approx(v_bare_q + v_added_q, rel=VOLUME_TOL)
    assert v_added_mesh == pytest.approx(v_added_q, rel=0.05)
    assert v_added_q > 0.5 * bulb.shape["volume"]  # the half bulb forward of FP at least


@pytest.mark.parametrize("c_lpr", [0.018, 0.024, 0.031])
@pytest.mark.parametrize("c_bb", [0.15, 0.18, 0.21])
def test_sweep_of_bulb_length_and_breadth_composes(hull, c_lpr, c_bb):
    # length and breadth swept at constant shape: areas and volume scale with them
    sl, sb = c_lpr / 0.025, c_bb / 0.18
    b = fl.BulbousBow(**SHIP, c_lpr=c_lpr, c_bb=c_bb, c_abt=0.10 * sb, c_abl=0.10 * sl, c_vpr=0.0022 * sl * sb)
    c = fl.compose([hull, b])
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    got = fl.measure_kracht(c.mesh, x_fp=L, **SHIP)
    for name in fl.KRACHT_NAMES:
        assert got[name] == pytest.approx(b.kracht[name], rel=KRACHT_TOL), (name, c_lpr, c_bb)
    # and with a blending surface between hull and bulb
    on_bulb = ("u", float(c.intersection_curves[0]["uv_b"][:, 0].max()) + 0.04)
    bl = fl.blend_surface(hull, _hull_boundary_around(c), b.surface, on_bulb)
    cb = fl.compose([hull, b, bl])
    assert edge_census(cb.mesh.faces) == (0, 0, 0)
    assert max(d["max_angle_deg"] for d in cb.blend_continuity) <= MAX_BLEND_ANGLE_DEG


def test_bulb_that_cannot_meet_the_hull_is_a_clear_error(hull):
    far = fl.BulbousBow(**SHIP, x_fp=L + 30.0)
    with pytest.raises(ValueError, match="bulb cannot meet the hull"):
        fl.compose([hull, far])
    short = fl.BulbousBow(**SHIP, aft_length=0.5)
    with pytest.raises(ValueError, match="bulb cannot meet the hull"):
        fl.compose([hull, short])


def test_bad_input_names_the_value(hull, bulb):
    with pytest.raises(ValueError, match="operation"):
        fl.compose([hull, bulb], operation="difference")
    with pytest.raises(ValueError, match="c_bb"):
        fl.BulbousBow(**{**SHIP, "c_bb": -0.1})
    with pytest.raises(fl.InfeasibleFormParameters, match="c_vpr"):
        fl.BulbousBow(**SHIP, c_vpr=0.02)
    with pytest.raises(fl.InfeasibleFormParameters, match="c_abt"):
        fl.BulbousBow(**SHIP, c_abt=0.05)  # a diamond section
    with pytest.raises(ValueError, match="hull_u"):
        fl.compose([hull, bulb], hull_u=1)
    with pytest.raises(ValueError, match="bulb_v is 12.5; expected an integer"):
        fl.compose([hull, bulb], bulb_v=12.5)
    with pytest.raises(ValueError, match="subdomains"):
        fl.compose([hull, bulb, bulb, bulb])
    with pytest.raises(ValueError, match="aft cut"):
        fl.compose([bulb.surface])  # a bulb is not a bare hull


def test_bulb_from_json_section():
    b = fl.BulbousBow.from_dict({"kracht": {"c_lpr": 0.027}, "shape": {"aft_length": 10.0}}, SHIP)
    assert b.shape["length"] == pytest.approx(0.027 * L)
    with pytest.raises(ValueError, match="unknown keys"):
        fl.BulbousBow.from_dict({"kracht": {"c_xx": 1.0}}, SHIP)


def test_obj_and_stl_round_trip(composed, tmp_path):
    m = composed.mesh
    composed.write_obj(tmp_path / "hull.obj")
    v, f = [], []
    for line in (tmp_path / "hull.obj").read_text().splitlines():
        if line.startswith("v "):
            v.append([float(x) for x in line.split()[1:]])
        elif line.startswith("f "):
            f.append([int(x) - 1 for x in line.split()[1:]])
    np.testing.assert_allclose(np.array(v), m.vertices, rtol=1e-9, atol=1e-7)
    np.testing.assert_array_equal(np.array(f), m.faces)
    composed.write_stl(tmp_path / "hull.stl", full=True)
    raw = (tmp_path / "hull.stl").read_bytes()
    n = int(np.frombuffer(raw[80:84], dtype="<u4")[0])
    full = composed.full_mesh()
    assert n == len(full.faces) and len(raw) == 84 + 50 * n
    rec = np.frombuffer(raw[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    np.testing.assert_allclose(rec["v"], full.vertices[full.faces], rtol=1e-6, atol=1e-4)


def test_mesh_hydrostatics_of_the_bare_forebody_match_the_analytic_integrals(hull):
    h = fl.mesh_hydrostatics(fl.compose([hull]).mesh, T)
    # y = B/2 g(xi) k(z): V = 2 int int y dz dx with int_0^1 (1 - xi^4) = 4/5 and
    # int_0^T (1 - (1 - z/D)^6) dz = T - D/7 (1 - (1 - T/D)^7)
    kz = T - D / 7 * (1 - (1 - T / D) ** 7)
    vol = 2 * 0.5 * B * 0.5 * L * 0.8 * kz
    # LCB: x = L/2 + (L/2) xi, int xi (1 - xi^4) / int (1 - xi^4) = (1/2 - 1/6) / (4/5)
    lcb = 0.5 * L + 0.5 * L * (1 / 2 - 1 / 6) / 0.8
    zs = np.linspace(0, T, 20001)
    w = 1 - (1 - zs / D) ** 6
    trap = lambda f: float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(zs)))  # noqa: E731
    kb = trap(zs * w) / trap(w)
    assert h.volume == pytest.approx(vol, rel=3e-3)
    assert h.lcb == pytest.approx(lcb, rel=1e-3)
    assert h.vcb == pytest.approx(kb, rel=3e-3)


def test_compose_ship_example_runs(tmp_path, monkeypatch, capsys):
    import runpy
    import sys
    from pathlib import Path

    script = Path(__file__).resolve().parents[2] / "examples" / "compose_ship.py"
    monkeypatch.setattr(sys, "argv", ["compose_ship.py", "--out", str(tmp_path)])
    runpy.run_path(str(script), run_name="__main__")
    assert "c_vpr" in capsys.readouterr().out
    assert (tmp_path / "container_ship_full.stl").stat().st_size > 84


MAX_BLEND_ANGLE_DEG = 0.5  # a tangent-continuous blend: normals across each blend boundary within 0.5 degrees


def _normal_angle_profile(blend, at_v1, surface, n=300):
    """Angles (deg) between blend and surface normals along a blend edge, computed here
    with the public evaluation API (closest_point + normal) independently of the engine's
    own measurement."""
    out = []
    for u in np.linspace(0.0, 1.0, n):
        d = blend.derivatives(u, 1.0 if at_v1 else 0.0, 1)
        nb = np.cross(d[1, 0], d[0, 1])
        nb /= np.linalg.norm(nb)
        su, sv, q = surface.closest_point(d[0, 0])
        out.append(np.degrees(np.arccos(min(1.0, abs(float(nb @ surface.normal(su, sv)))))))
        assert np.linalg.norm(q - d[0, 0]) < 1e-3
    return np.array(out)


def test_blend_between_hull_and_bulb_is_tangent_plane_continuous(composed, bulb):
    hull_s = composed.trimmed_surfaces[0][0]
    seam = composed.intersection_curves[0]
    on_hull = seam["uv_a"] - [0.03, 0.0]  # a curve on the hull aft of the seam
    on_bulb = ("u", float(seam["uv_b"][:, 0].max()) + 0.08)  # a bulb section ahead of it
    bl = fl.blend_surface(hull_s, on_hull, bulb.surface, on_bulb)
    assert bl.max_angle_deg <= MAX_BLEND_ANGLE_DEG
    assert _normal_angle_profile(bl.surface, False, hull_s).max() <= MAX_BLEND_ANGLE_DEG
    assert _normal_angle_profile(bl.surface, True, bulb.surface).max() <= MAX_BLEND_ANGLE_DEG
    assert bl.at_a["max_gap"] < 1e-3 and bl.at_b["max_gap"] < 1e-3


def test_blend_of_plane_and_cylinder_is_c1():
    """A fillet from the deck-like plane z = 0 (circle of radius 3) up to the bottom circle of
    a vertical cylinder of radius 1 at z = 2: normals must match the plane's (+-z) and the
    cylinder's (radial) along the two circles."""
    plane = fl.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1],
                            [[[-5, -5, 0], [-5, 5, 0]], [[5, -5, 0], [5, 5, 0]]])
    cyl = fl.cylinder([0.0, 0.0, 2.0], [0.0, 0.0, 1.0], 1.0, 3.0)
    a = np.linspace(0.0, 2.0 * np.pi, 129)
    circle_uv = np.column_stack([0.5 + 0.3 * np.cos(a), 0.5 + 0.3 * np.sin(a)])
    bl = fl.blend_surface(plane, circle_uv, cyl, ("v", 0.0))
    assert bl.max_angle_deg <= MAX_BLEND_ANGLE_DEG
    assert _normal_angle_profile(bl.surface, False, plane).max() <= MAX_BLEND_ANGLE_DEG
    assert _normal_angle_profile(bl.surface, True, cyl).max() <= MAX_BLEND_ANGLE_DEG
    mid = bl.surface.evaluate(np.linspace(0, 1, 50), np.full(50, 0.5))
    r = np.hypot(mid[:, 0], mid[:, 1])
    assert np.all((r > 1.0) & (r < 3.0)) and np.all((mid[:, 2] > 0.0) & (mid[:, 2] < 2.0))
    with pytest.raises(ValueError, match="boundary_a"):
        fl.blend_surface(plane, [[0.5, 0.5]], cyl, ("v", 0.0))
    with pytest.raises(ValueError, match="outside the surface domain"):
        fl.blend_surface(plane, [[0.5, 0.5], [2.0, 0.5]], cyl, ("v", 0.0))
    with pytest.raises(fl.InvalidInput, match=r"continuity is 3; expected 1 \(G1\) or 2 \(G2\)"):
        fl.blend_surface(plane, circle_uv, cyl, ("v", 0.0), continuity=3)
    with pytest.raises(fl.InvalidInput, match="continuity is 1.5; expected a int"):
        fl.blend_surface(plane, circle_uv, cyl, ("v", 0.0), continuity=1.5)


def test_any_parameter_orientation_of_the_bare_hull_is_accepted(hull, composed):
    """The bare-hull description's surface may run u/v the other way: transposed and reversed copies compose to
    the same closed half hull volume."""
    P = np.asarray(hull.control_points)
    ku, kv = np.asarray(hull.knots_u), np.asarray(hull.knots_v)
    swapped = fl.NurbsSurface(hull.degree_v, hull.degree_u, kv, ku, P.transpose(1, 0, 2))
    reversed_u = fl.NurbsSurface(hull.degree_u, hull.degree_v, ku[-1] + ku[0] - ku[::-1], kv, P[::-1])
    bulb = composed.trimmed_surfaces[1][0]
    for h in (swapped, reversed_u):
        c = fl.compose([h, bulb])
        assert edge_census(c.mesh.faces) == (0, 0, 0)
        assert c.volume == pytest.approx(composed.volume, rel=1e-9)


def _hull_boundary_around(composed, clearance_u=0.02, clearance_v=0.03, k=65):
    """A curve on the hull around the union seam: a half ellipse in (u, v) from the stem edge
    below the bulb to the stem edge above it."""
    uv = composed.intersection_curves[0]["uv_a"]
    tlo, thi = uv[:, 1].min(), uv[:, 1].max()
    tc, R, du = 0.5 * (tlo + thi), 0.5 * (thi - tlo) + clearance_v, 1.0 - uv[:, 0].min() + clearance_u
    phi = np.linspace(0.0, np.pi, k)
    return np.column_stack([1.0 - du * np.sin(phi), tc - R * np.cos(phi)])


def test_hull_bulb_and_blend_compose_into_one_watertight_c1_hull(composed, bulb):
    hull_s = composed.trimmed_surfaces[0][0]
    on_hull = _hull_boundary_around(composed)
    # a bulb section just ahead of the seam: the blend then stays short and the Kracht
    # quantities at FP stay the bulb's
    on_bulb = ("u", float(composed.intersection_curves[0]["uv_b"][:, 0].max()) + 0.04)
    blend = fl.blend_surface(hull_s, on_hull, bulb.surface, on_bulb)
    c = fl.compose([hull_s, bulb, blend])
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    assert edge_census(c.full_mesh().faces) == (0, 0, 0)
    assert set(np.unique(c.face_part)) == {0, 1, 2, 3, 4, 5}
    assert c.volume > composed.volume * 0.99
    # C1 across both blend boundaries, measured densely here and by the engine
    assert _normal_angle_profile(c.blend, False, hull_s).max() <= MAX_BLEND_ANGLE_DEG
    assert _normal_angle_profile(c.blend, True, bulb.surface).max() <= MAX_BLEND_ANGLE_DEG
    assert max(d["max_angle_deg"] for d in c.blend_continuity) <= MAX_BLEND_ANGLE_DEG
    got = fl.measure_kracht(c.mesh, x_fp=L, **SHIP)
    for name in fl.KRACHT_NAMES:
        assert got[name] == pytest.approx(bulb.kracht[name], rel=KRACHT_TOL), name
    with pytest.raises(ValueError, match="bulb section"):
        fl.compose([hull_s, bulb, fl.blend_surface(hull_s, on_hull, bulb.surface, ("v", 0.5))])


def test_seam_blend_is_c1_and_composes_with_the_original_hull(hull, bulb):
    """fl.seam_blend_placement(...).blend_surface() (the Blender Blend node's call) gives a
    blend that composes with the *unoriented* hull (orientation is idempotent) into a
    watertight, C1 hull."""
    bl = fl.seam_blend_placement(hull, bulb).blend_surface()
    a = fl.compose([hull, bulb, bl])
    assert edge_census(a.mesh.faces) == (0, 0, 0)
    assert max(d["max_angle_deg"] for d in a.blend_continuity) <= MAX_BLEND_ANGLE_DEG
    with pytest.raises(ValueError, match="cannot meet"):
        fl.seam_blend_placement(hull, fl.BulbousBow(**dict(SHIP, x_fp=L + 60.0)))


def test_seam_blend_equals_the_blend_around_the_union_seam(hull, bulb):
    """seam_blend_placement traces the seam without meshing the union (for the Blender
    latency); its blend must be the one built from compose([hull, bulb])'s seam, bit for bit."""
    from fairlines.blend import _boundaries_around_seam

    union = fl.compose([hull, bulb])
    on_hull, on_bulb = _boundaries_around_seam(union.trimmed_surfaces[0][0], union.intersection_curves[0],
                                               clearance_u=0.05, clearance_v=0.01, bulb_clearance=0.01, points=65)
    ref = fl.blend_surface(union.trimmed_surfaces[0][0], on_hull, bulb.surface, on_bulb, tension=0.6)
    got = fl.seam_blend_placement(hull, bulb, tension=0.6).blend_surface()
    assert np.array_equal(got.boundary_a, ref.boundary_a) and got.boundary_b == ref.boundary_b
    assert np.array_equal(got.surface.control_points, ref.surface.control_points)
    assert got.at_a == ref.at_a and got.at_b == ref.at_b


def test_compose_takes_the_blend_placement_for_the_surface(hull, bulb):
    """compose() only needs where the blend goes: with the placement it gives the mesh it gives
    with the skinned blend (the Blender Compose node relies on it)."""
    placement = fl.seam_blend_placement(hull, bulb)
    a = fl.compose([hull, bulb, placement])
    b = fl.compose([hull, bulb, placement.blend_surface()])
    assert np.array_equal(a.mesh.vertices, b.mesh.vertices) and np.array_equal(a.mesh.faces, b.mesh.faces)
    assert a.blend_continuity == b.blend_continuity
    blend = fl.blend_surface(placement.hull, placement.boundary_a, bulb.surface, placement.boundary_b, tension=0.6)
    assert np.array_equal(placement.blend_surface().surface.control_points, blend.surface.control_points)


def test_blend_continuity_can_be_measured_after_compose(hull, bulb):
    """compose(blend_check_samples=2) meshes the same hull, and boundary_continuity on its blend
    gives the figures compose() reports by default (the Blender Compose node defers them)."""
    placement = fl.seam_blend_placement(hull, bulb)
    full = fl.compose([hull, bulb, placement])
    quick = fl.compose([hull, bulb, placement], blend_check_samples=2)
    assert np.array_equal(full.mesh.vertices, quick.mesh.vertices) and np.array_equal(full.mesh.faces, quick.mesh.faces)
    later = (fl.boundary_continuity(quick.blend, False, quick.trimmed_surfaces[0][0], 200),
             fl.boundary_continuity(quick.blend, True, bulb.surface, 200))
    assert later == full.blend_continuity
    with pytest.raises(ValueError, match="blend_check_samples"):
        fl.compose([hull, bulb, placement], blend_check_samples=1)
    with pytest.raises(ValueError, match="blend_check_samples is nan; expected an integer"):
        fl.compose([hull, bulb, placement], blend_check_samples=float("nan"))


def test_blend_ending_on_the_centre_plane_is_c1_there():
    """Both boundaries end on y = 0 (a stem and a bulb top centre line): the blend's end
    section must stay in the centre plane and still be tangent to both surfaces there, also
    where the boundary on the first surface climbs (its tangent is not horizontal). Plane a
    holds the vertical stem line x = y = 0 and leaves it at a half entrance angle of 20 deg;
    plane b is the horizontal z = 2 ahead of the stem."""
    alpha = np.radians(20.0)
    back = np.array([-10.0 * np.cos(alpha), 10.0 * np.sin(alpha), 0.0])
    a = fl.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1],
                        [[back + [0, 0, 4], back + [0, 0, 12]], [[0, 0, 4], [0, 0, 12]]])
    b = fl.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1],
                        [[[3, 0, 2], [3, 6, 2]], [[9, 0, 2], [9, 6, 2]]])
    on_a = np.array([[0.3, 0.1], [1.0, 0.6]])  # climbs to the stem at z = 8.8
    on_b = np.array([[0.5, 0.8], [0.5, 0.0]])  # the line x = 6 to the centre line
    bl = fl.blend_surface(a, on_a, b, on_b)
    end = bl.surface.evaluate(np.ones(20), np.linspace(0.0, 1.0, 20))
    assert np.abs(end[:, 1]).max() < 1e-9
    d = bl.surface.derivatives(1.0, 0.0, 1)
    nb = np.cross(d[1, 0], d[0, 1])
    na = np.array([np.sin(alpha), np.cos(alpha), 0.0])  # plane a's normal
    angle = np.degrees(np.arccos(min(1.0, abs(nb @ na) / np.linalg.norm(nb))))
    assert angle <= MAX_BLEND_ANGLE_DEG
    d = bl.surface.derivatives(1.0, 1.0, 1)
    nb = np.cross(d[1, 0], d[0, 1])
    assert np.degrees(np.arccos(min(1.0, abs(nb[2]) / np.linalg.norm(nb)))) <= MAX_BLEND_ANGLE_DEG
    assert bl.max_angle_deg <= MAX_BLEND_ANGLE_DEG


def test_chord_difference_brings_two_tessellations_of_one_hull_to_one_volume(hull):
    """The hull closed alone at 48 x 20 and at 96 x 40 cells share no face: their meshes' volumes
    below T differ by their chords (2e-3 of it), and the chord difference (the surface over each
    face's parameter triangle less the flat face, and the faces a pole collapses) accounts for
    that within 2e-5, the moment about x = 0 and the wetted area too."""
    from fairlines.hydrostatics_composed import mesh_below

    a, b = fl.compose([hull]), fl.compose([hull], hull_u=96, hull_v=40)
    ma, mb = mesh_below(a, T, lpp=L), mesh_below(b, T, lpp=L)
    d = fl._native._hull_chord_difference(a._c, b._c, T, 0.0, L)
    assert abs(ma["volume"] - mb["volume"]) > 1e-3 * mb["volume"]  # what there is to account for
    assert ma["volume"] + 2 * d["volume"] == pytest.approx(mb["volume"], rel=2e-5)
    assert ma["volume"] * ma["lcb"] + 2 * d["mx"] == pytest.approx(mb["volume"] * mb["lcb"], rel=2e-5)
    assert ma["wetted"] + 2 * d["wetted"] == pytest.approx(mb["wetted"], rel=2e-5)


@pytest.mark.parametrize("trim", [0.0, 3.0])
def test_bulb_share_of_two_tessellations_of_one_hull_is_nothing_trimmed_or_not(hull, trim):
    """bulb_share (meshes' difference plus the chord difference, turned back from the trimmed
    waterplane's frame) of the hull against itself at another tessellation: no volume, no
    moments, where the meshes alone differ by 2e-3 of the volume and 1e-3 of its moment."""
    from fairlines.hydrostatics_composed import bulb_share, mesh_below

    a, b = fl.compose([hull]), fl.compose([hull], hull_u=96, hull_v=40)
    v = mesh_below(b, T, lpp=L, trim=trim)["volume"]
    s = bulb_share(a, b, T, lpp=L, trim=trim)
    assert abs(s["volume"]) <= 2e-5 * v and abs(s["mx"]) <= 2e-5 * v * L and abs(s["mz"]) <= 2e-5 * v * T


def test_chord_difference_of_one_mesh_with_itself_is_nothing_and_a_bad_lpp_is_named(composed):
    d = fl._native._hull_chord_difference(composed._c, composed._c, T, 0.0, L)
    assert d == {"volume": 0.0, "mx": 0.0, "mz": 0.0, "wetted": 0.0}
    with pytest.raises(fl.InvalidInput, match="lpp is 0.*expected a length > 0"):
        fl._native._hull_chord_difference(composed._c, composed._c, T, 0.0, 0.0)
