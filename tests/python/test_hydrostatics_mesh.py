"""fl.hydrostatics_of_mesh against exact solids: a half box and a half wedge (a prism whose
section is a triangle, so the waterline cuts every side triangle), and the Python paths that
now call it against the geometry they measure."""

import numpy as np
import pytest

import fairlines as fl

EXACT = 1e-12  # relative: the divergence theorem is exact on a polyhedron


def half_box(length, half_breadth, depth):
    """Outward triangles of the box [0, L] x [0, b] x [0, D] without its centre-plane face."""
    x, b, d = length, half_breadth, depth
    v = np.array([[0, 0, 0], [x, 0, 0], [x, b, 0], [0, b, 0], [0, 0, d], [x, 0, d], [x, b, d], [0, b, d]], float)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5)]  # bottom, deck, side, aft, fore
    return v, np.array([t for a, b_, c, e in quads for t in ((a, b_, c), (a, c, e))])


def half_wedge(length, half_breadth, depth):
    """The prism 0 <= x <= L over the section triangle (0, 0), (0, D), (b, D) in (y, z): the
    side runs from the keel to (b, D), so the half-breadth at height z is b z / D."""
    v = np.array([[0, 0, 0], [0, 0, depth], [0, half_breadth, depth]], float)
    v = np.concatenate([v, v + [length, 0, 0]])
    faces = [(0, 5, 2), (0, 3, 5), (1, 2, 5), (1, 5, 4), (0, 2, 1), (3, 4, 5)]  # side, deck, aft, fore
    return v, np.array(faces)[:, ::-1]


def test_half_box_gives_the_box_below_the_waterline():
    L, b, D, T = 12.0, 2.5, 4.0, 1.5
    h = fl.hydrostatics_of_mesh(*half_box(L, b, D), T)
    assert h.volume == pytest.approx(L * 2 * b * T, rel=EXACT)
    assert (h.lcb, h.vcb) == pytest.approx((L / 2, T / 2), rel=EXACT)
    assert (h.waterplane_area, h.lcf) == pytest.approx((2 * L * b, L / 2), rel=EXACT)
    assert h.wetted_surface == pytest.approx(2 * (L * b + L * T + 2 * b * T), rel=EXACT)
    assert h.midship_area == pytest.approx(2 * b * T, rel=EXACT)


def test_half_wedge_clipped_through_its_sloped_side():
    L, b, D, T = 10.0, 3.0, 6.0, 2.0
    h = fl.hydrostatics_of_mesh(*half_wedge(L, b, D), T)
    half_section = 0.5 * (b * T / D) * T  # triangle with base b T / D at height T
    assert h.volume == pytest.approx(2 * L * half_section, rel=EXACT)
    assert h.vcb == pytest.approx(2 * T / 3, rel=EXACT)  # centroid of a triangle with its apex at the keel
    assert h.midship_area == pytest.approx(2 * half_section, rel=EXACT)


def test_orient_flips_an_inward_mesh_and_reports_it():
    v, f = half_box(12.0, 2.5, 4.0)
    out = fl.hydrostatics_of_mesh(v, f, 1.5)
    inward = fl.hydrostatics_of_mesh(v, f[:, ::-1], 1.5, orient=True)
    assert inward.flipped and not out.flipped
    assert inward.volume == pytest.approx(out.volume, rel=EXACT)


def test_nothing_below_the_draft_is_refused_where_a_body_must_float():
    v, f = half_box(12.0, 2.5, 4.0)
    assert fl.hydrostatics_of_mesh(v, f, -1.0).volume == 0.0
    with pytest.raises(fl.InvalidInput, match="no displaced volume"):
        fl.displaced_volume_of_mesh(v, f, -1.0)


@pytest.mark.parametrize("kwargs, match", [({"draft": float("nan")}, "not finite"),
                                           ({"faces": [[0, 1, 99]]}, "vertex indices"),
                                           ({"colour": 1}, "unknown")])
def test_bad_input_is_named(kwargs, match):
    v, f = half_box(12.0, 2.5, 4.0)
    args = dict(vertices=v, faces=f, draft=1.0) | kwargs
    with pytest.raises(fl.InvalidInput, match=match):
        fl.hydrostatics_of_mesh(**args)


def test_surface_mesh_hydrostatics_is_the_engine_result():
    v, f = half_box(12.0, 2.5, 4.0)
    mesh = fl.SurfaceMesh(v, np.column_stack([f, -np.ones(len(f), int)]), np.zeros(len(f), int), ("hull",), symmetric=True)
    assert mesh.hydrostatics(1.5).volume == pytest.approx(12.0 * 5.0 * 1.5, rel=EXACT)
