"""The real hull: the whole Panamax container ship of examples/container_ship.json with the
bulbous bow of its "bulb" section, blended and composed into one watertight half hull. Every check uses code of its own (numpy edge census, a brute-force triangle-triangle
test, quadrature of the NURBS surfaces, closest-point normals) rather than the engine's own
checks. Resolutions are reduced where that keeps the test time down."""

import json
import pathlib

import numpy as np
import pytest
from matplotlib.path import Path

import fairlines as fl
from conftest import edge_census
from mesh_fixtures import self_intersections

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "container_ship.json"
KRACHT_TOL = 0.02           # measured coefficients within 2 % ...
KRACHT_TOL_BLENDED = 0.025  # ... 2.5 % with the blend, whose fillet adds about 2 % of A_BT at the FP
VOLUME_TOL = 0.002          # composing keeps volume: composed = bare + bulb's added volume within 0.2 %
MAX_BLEND_ANGLE_DEG = 0.5   # a tangent-continuous blend: normals across each blend boundary within 0.5 degrees
QUAD_N = 240                # quadrature cells per parameter direction
MIDSHIP_TOL = 1e-5          # skinning the sections moves the midship area by a few 1e-6
# Kracht ranges of container ships swept over: length and breadth ratios
C_LPR_SWEEP = (0.018, 0.031)
C_BB_SWEEP = (0.15, 0.21)


@pytest.fixture(scope="module")
def description():
    return json.loads(EXAMPLE.read_text())


@pytest.fixture(scope="module")
def hull(description):
    return fl.Hull.from_json(description)


@pytest.fixture(scope="module")
def ship(hull):
    return hull.ship_particulars()


@pytest.fixture(scope="module")
def bulb(hull):
    return hull.bulbous_bow()


@pytest.fixture(scope="module")
def union(hull, bulb):
    return hull.composed_hull(blend=False, bulb=bulb)


@pytest.fixture(scope="module")
def blended(hull, bulb):
    return hull.composed_hull(blend=True, bulb=bulb)


def _y_flux(surface, loops=None, n=QUAD_N):
    """int y n_y dA over a surface (or over the part inside its trimming loops), with the
    normal's sign chosen outward (y n_y >= 0 on most of a half hull's side), by the midpoint
    rule on an n x n parameter grid with central-difference partials."""
    ku, kv = surface.knots_u, surface.knots_v
    u0, u1, v0, v1 = ku[0], ku[-1], kv[0], kv[-1]
    du, dv = (u1 - u0) / n, (v1 - v0) / n
    U, V = [a.ravel() for a in np.meshgrid(u0 + du * (np.arange(n) + 0.5), v0 + dv * (np.arange(n) + 0.5), indexing="ij")]
    h = 1e-6
    su = (surface.evaluate(np.minimum(U + h, u1), V) - surface.evaluate(np.maximum(U - h, u0), V)) / (
        np.minimum(U + h, u1) - np.maximum(U - h, u0))[:, None]
    sv = (surface.evaluate(U, np.minimum(V + h, v1)) - surface.evaluate(U, np.maximum(V - h, v0))) / (
        np.minimum(V + h, v1) - np.maximum(V - h, v0))[:, None]
    f = surface.evaluate(U, V)[:, 1] * np.cross(su, sv)[:, 1] * du * dv
    sign = 1.0 if f.sum() > 0 else -1.0  # the whole surface faces outward on the whole
    if loops is not None:
        keep = np.zeros(len(U), bool)
        for lp in loops:
            keep ^= Path(lp).contains_points(np.column_stack([U, V]))
        f = f[keep]
    return sign * float(f.sum())


def test_hull_json_has_a_bulb_section_and_the_ship_comes_from_the_hull(description, hull, ship, bulb):
    d = hull.description
    assert d.bulb is not None and set(d.bulb.kracht) == set(fl.KRACHT_NAMES)
    h = hull.hydrostatics()
    assert ship["midship_area"] == pytest.approx(h.midship_area)
    # A_MS of the bare hull is the SAC's flat value (both sides), Cm B T
    assert ship["midship_area"] == pytest.approx(description["basic_curves"]["sac"]["value"], rel=MIDSHIP_TOL)
    # a whole ship: the displacement is the hull's own
    assert d.bulb.displacement_volume is None and ship["displacement_volume"] == pytest.approx(h.volume)
    assert bulb.kracht == {**bulb.kracht, **d.bulb.kracht}
    assert ship["x_fp"] == d.principal.lpp
    # round trip through to_dict keeps the bulb section
    again = fl.Hull.from_json(json.loads(hull.to_json()))
    assert again.description.bulb == d.bulb


@pytest.mark.parametrize("edit, field", [
    (lambda b: b["kracht"].__setitem__("c_bb", -0.1), "bulb.kracht.c_bb"),
    (lambda b: b["kracht"].__setitem__("c_xx", 0.1), "bulb.kracht.c_xx"),
    (lambda b: b["shape"].__setitem__("aft_length", "long"), "bulb.shape.aft_length"),
    (lambda b: b["shape"].__setitem__("sections", 2), "bulb.shape.sections"),
    (lambda b: b.__setitem__("colour", "red"), "bulb.colour"),
    (lambda b: b.__setitem__("displacement_volume", 0.0), "bulb.displacement_volume"),
])
def test_bad_bulb_section_names_the_field(description, edit, field):
    d = json.loads(json.dumps(description))
    edit(d["bulb"])
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        fl.Hull.from_json(d)


def test_hull_without_bulb_section_says_so(description):
    d = {k: v for k, v in description.items() if k != "bulb"}
    h = fl.Hull.from_json(d)
    assert h.description.bulb is None
    with pytest.raises(ValueError, match="bulb is missing"):
        h.bulbous_bow()


def test_union_on_the_real_hull_is_closed_manifold_oriented(union):
    assert edge_census(union.mesh.faces) == (0, 0, 0)
    assert edge_census(union.full_mesh().faces) == (0, 0, 0)
    assert union.volume > 0
    assert max(c["max_gap"] for c in union.intersection_curves) < 1e-6


def test_blended_real_hull_is_watertight_and_c1(blended, bulb):
    assert blended.blend is not None, blended.blend_note
    m = blended.mesh
    assert edge_census(m.faces) == (0, 0, 0)
    full = blended.full_mesh()
    assert edge_census(full.faces) == (0, 0, 0)
    assert full.volume == pytest.approx(2 * m.volume, rel=1e-9)
    assert set(np.unique(blended.face_part)) == {0, 1, 2, 3, 4, 5}
    # open edges only where intended: none on the half (the centre plane closes it)
    assert self_intersections(m) == []
    assert self_intersections(full) == []
    hull_s = blended.trimmed_surfaces[0][0]
    for at_v1, surf in ((False, hull_s), (True, bulb.surface)):
        angles = []
        for u in np.linspace(0.0, 1.0, 150):
            d = blended.blend.derivatives(u, 1.0 if at_v1 else 0.0, 1)
            nb = np.cross(d[1, 0], d[0, 1])
            nb /= np.linalg.norm(nb)
            su, sv, q = surf.closest_point(d[0, 0])
            assert np.linalg.norm(q - d[0, 0]) < 1e-3
            angles.append(np.degrees(np.arccos(min(1.0, abs(float(nb @ surf.normal(su, sv)))))))
        assert max(angles) <= MAX_BLEND_ANGLE_DEG
    assert max(d["max_angle_deg"] for d in blended.blend_continuity) <= MAX_BLEND_ANGLE_DEG


@pytest.mark.parametrize("cells", [(32, 16), (48, 16), (160, 48)])
def test_hull_band_around_the_blend_follows_the_surface(hull, bulb, cells):
    """The hull's triangles between its kept cells and the blend (ear-clipped in parameter
    space) lie along the NURBS hull: each face's normal within 30 deg of the surface's at the
    closest point of its centroid. Ear clipping alone left slivers from a grid node to a short
    seam edge metres away, folded up to 124 deg off at the render's 160 x 48 cells."""
    c = hull.composed_hull(bulb=bulb, hull_u=cells[0], hull_v=cells[1], bulb_u=48, bulb_v=64)
    V, F = np.asarray(c.mesh.vertices), np.asarray(c.mesh.faces)[:, :3]
    H = c.trimmed_surfaces[0][0]
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    area = 0.5 * np.linalg.norm(n, axis=1)
    cen = V[F].mean(axis=1)
    band = (c.face_part == 0) & (cen[:, 0] > 200.0) & (area > 1e-9)  # the hull near the bulb
    su, sv, _ = H.closest_points(cen[band])
    cos = np.abs(np.einsum("ij,ij->i", n[band], np.asarray(H.normal(su, sv)))) / (2 * area[band])
    worst = np.argmin(cos)
    assert cos[worst] >= np.cos(np.radians(30.0)), (cells, cen[band][worst].round(2), np.degrees(np.arccos(min(cos[worst], 1.0))))


@pytest.mark.parametrize("cells", [None, (160, 48)])
def test_composed_mesh_has_no_face_of_zero_area(hull, bulb, cells):
    """The hull's u edge collapses to the stem top: its nodes are one vertex, so the cells there
    give one triangle each (a triangle and a zero-area one before, 2 K of them with the centre
    plane's cap); the caps' collinear runs (the deck's parallel edge) are flipped out."""
    c = hull.composed_hull(bulb=bulb, **(dict(hull_u=cells[0], hull_v=cells[1]) if cells else {}))
    for m in (c.mesh, c.full_mesh()):
        V, F = np.asarray(m.vertices), np.asarray(m.faces)
        area = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)
        assert area.min() > 1e-6, V[F[np.argmin(area)]]
        assert edge_census(F) == (0, 0, 0)


@pytest.mark.parametrize("which", ["union", "blended"])
def test_kracht_measured_back_on_the_real_hull_within_two_percent(which, union, blended, bulb, ship):
    c = union if which == "union" else blended
    got = fl.measure_kracht(c.mesh, **ship)
    tol = KRACHT_TOL if which == "union" else KRACHT_TOL_BLENDED
    for name in fl.KRACHT_NAMES:
        assert got[name] == pytest.approx(bulb.kracht[name], rel=tol), name


def test_volume_identity_two_ways_on_the_real_hull(hull, union, blended, bulb):
    """Way 1: divergence theorem on the meshes. Way 2: quadrature of y n_y over the trimmed
    NURBS surfaces (the caps add nothing: n_y = 0 on deck and aft cut, y = 0 on the centre
    plane). Composed = bare + added both ways, within 0.2 %."""
    bare = fl.compose([hull.bare_hull_surface()])
    hull_s = union.trimmed_surfaces[0][0]
    v_bare_q = _y_flux(hull_s)
    assert bare.volume == pytest.approx(v_bare_q, rel=VOLUME_TOL)
    # and below the waterline a finer mesh agrees with the bare hull's own NURBS hydrostatics
    # (the default 48 x 20 cells give -0.25 %: chords inside the convex sections)
    T = hull.description.principal.draft
    fine = fl.compose([hull.bare_hull_surface()], hull_u=96, hull_v=40)
    assert fl.mesh_hydrostatics(fine.mesh, T).volume == pytest.approx(hull.hydrostatics().volume, rel=VOLUME_TOL)
    for c in (union, blended):
        v_q = sum(_y_flux(s, loops) for s, loops in c.trimmed_surfaces)
        added_q = v_q - v_bare_q
        added_mesh = c.volume - bare.volume
        assert c.volume == pytest.approx(v_q, rel=VOLUME_TOL)
        assert c.volume == pytest.approx(bare.volume + added_q, rel=VOLUME_TOL)
        assert added_mesh == pytest.approx(added_q, rel=0.05)
        assert added_q > 0.5 * bulb.shape["volume"]  # at least the half bulb forward of FP


@pytest.mark.parametrize("c_lpr", np.linspace(*C_LPR_SWEEP, 3))
@pytest.mark.parametrize("c_bb", np.linspace(*C_BB_SWEEP, 3))
def test_sweep_of_bulb_length_and_breadth_composes_on_the_real_hull(hull, ship, c_lpr, c_bb):
    """Length and breadth swept at constant shape (areas and volume scale with them), with a
    blend every time, at a reduced resolution."""
    k = hull.description.bulb.kracht
    sl, sb = c_lpr / k["c_lpr"], c_bb / k["c_bb"]
    b = hull.bulbous_bow(c_lpr=c_lpr, c_bb=c_bb, c_abt=k["c_abt"] * sb, c_abl=k["c_abl"] * sl,
                         c_vpr=k["c_vpr"] * sl * sb, sections=41, section_points=25)
    c = hull.composed_hull(blend=True, bulb=b, hull_u=32, hull_v=16)
    assert c.blend is not None, c.blend_note
    assert edge_census(c.mesh.faces) == (0, 0, 0)
    assert self_intersections(c.full_mesh()) == []
    assert max(d["max_angle_deg"] for d in c.blend_continuity) <= MAX_BLEND_ANGLE_DEG
    got = fl.measure_kracht(c.mesh, **ship)
    for name in fl.KRACHT_NAMES:
        assert got[name] == pytest.approx(b.kracht[name], rel=KRACHT_TOL), (name, c_lpr, c_bb)


def test_bulb_that_cannot_meet_the_hull_is_a_clear_error(hull, ship):
    far = fl.BulbousBow(**{**ship, "x_fp": ship["x_fp"] + 30.0})
    with pytest.raises(ValueError, match="bulb cannot meet the hull"):
        hull.composed_hull(bulb=far)
    short = hull.bulbous_bow(aft_length=0.3)
    with pytest.raises(ValueError, match="bulb cannot meet the hull"):
        hull.composed_hull(bulb=short)


def test_blend_continuity_read_later_is_the_engines_at_the_asked_samples(hull, bulb):
    """compose() leaves the blend's continuity to be measured when read: the figures are the
    engine's own check at the asked blend_check_samples (projected onto the oriented hull and
    the bulb), and fewer than two samples are refused as the engine refuses them."""
    from fairlines._options import fill_options

    p = hull.blend_placement()
    got = fl.compose([p.hull, bulb, p], blend_check_samples=37)
    spec = fill_options(fl._native.BlendSpec, "blend", dict(hull_uv=np.asarray(p.boundary_a, float),
                                                            bulb_u=float(p.boundary_b[1]), tension=float(p.tension)))
    eager = fl._native._compose_hull(p.hull, bulb.surface, fl.compose_options(blend_check_samples=37), spec)
    assert got.blend_continuity == tuple(dict(d) for d in eager.blend_continuity)
    assert fl.compose([hull.bare_hull_surface()]).blend_continuity is None
    with pytest.raises(ValueError, match="blend_check_samples is 1; expected >= 2"):
        fl.compose([p.hull, bulb, p], blend_check_samples=1)


def test_ship_meshes_are_the_composed_and_the_closed_bare_hull(description):
    """Hull.ship_meshes closes the bare hull on a second thread: the pair is the hull's kept
    composed_hull() and bare_hull_closed(), the closed one the same mesh as fl.compose of the
    bare surface alone; no thread outlives the call, also when the bulb cannot meet the hull."""
    import threading

    before = threading.active_count()
    h = fl.Hull.from_json(description)
    composed, closed = h.ship_meshes()
    assert composed is h.composed_hull() and closed is h.bare_hull_closed()
    alone = fl.compose([h.bare_hull_surface()])
    assert np.array_equal(closed.mesh.vertices, alone.mesh.vertices)
    assert np.array_equal(closed.mesh.faces, alone.mesh.faces)
    short = json.loads(json.dumps(description))
    short["bulb"].setdefault("shape", {})["aft_length"] = 0.3
    h = fl.Hull.from_json(short)
    with pytest.raises(ValueError, match="bulb cannot meet the hull"):
        h.ship_meshes()
    assert threading.active_count() == before
    assert h.bare_hull_closed().volume == pytest.approx(alone.volume, rel=1e-12)
