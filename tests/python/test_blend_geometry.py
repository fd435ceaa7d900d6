"""The blend of the composed container ship measured from outside the engine: sampled points
for the side of the centre plane it lies on, finite-difference normals against those of the
hull and bulb (at closest points) for the angle across each seam."""

import numpy as np
import pytest

from blend_fixtures import container_ship_composed, fd_normal

#: Largest admissible normal angle across a C1 seam (degrees), as the README's C1 claim states.
C1_ANGLE_DEG = 0.5
#: How far below the centre plane a half-hull surface may reach (m): round-off only.
CENTRE_PLANE_TOL = 1e-9
SEAM_SAMPLES = 121


def _cos_across(edge_v: float, neighbour) -> np.ndarray:
    """Signed cosines between the blend's normal and the neighbour's (at closest points) along
    the blend's edge v = edge_v, at SEAM_SAMPLES points."""
    blend = container_ship_composed().blend
    cos = []
    for s in np.linspace(0.0, 1.0, SEAM_SAMPLES):
        u, v, _ = neighbour.closest_point(np.asarray(blend.evaluate(s, edge_v)))
        cos.append(float(fd_normal(blend, s, edge_v) @ fd_normal(neighbour, u, v)))
    return np.array(cos)


def _max_angle_across(edge_v: float, neighbour) -> float:
    return float(np.degrees(np.arccos(min(1.0, np.abs(_cos_across(edge_v, neighbour)).min()))))


def test_blend_is_tangent_to_the_hull_along_its_hull_boundary():
    hull = container_ship_composed().trimmed_surfaces[0][0]
    assert _max_angle_across(0.0, hull) <= C1_ANGLE_DEG


@pytest.mark.parametrize("end", [0.0, 1.0])
def test_blend_is_tangent_to_the_bulb_where_it_meets_the_centre_plane(end):
    """At both centre-plane ends (the bulb's bottom and top centre lines) the blend arrives
    across the plane, tangent to the bulb: its mirror image continues it smoothly."""
    c = container_ship_composed()
    blend, bulb = c.blend, c.trimmed_surfaces[1][0]
    p = np.asarray(blend.evaluate(end, 1.0))
    assert abs(p[1]) <= CENTRE_PLANE_TOL
    u, v, _ = bulb.closest_point(p)
    cos = abs(float(fd_normal(blend, end, 1.0) @ fd_normal(bulb, u, v)))
    assert np.degrees(np.arccos(min(1.0, cos))) <= C1_ANGLE_DEG


def test_blend_is_tangent_to_the_bulb_along_its_bulb_boundary():
    bulb = container_ship_composed().trimmed_surfaces[1][0]
    assert _max_angle_across(1.0, bulb) <= C1_ANGLE_DEG


@pytest.mark.parametrize("edge_v", [0.0, 1.0])
def test_blend_does_not_fold_back_over_its_neighbour(edge_v):
    """Along each boundary the blend's normal keeps one orientation against the neighbour's:
    a section whose tangent handle points the wrong way (toward the part of the bulb that is
    kept) folds the blend back over the bulb, which a check of |cos| alone reads as tangent.
    The handles flipped near the bulb's top, where the hull lies straight above (s 0.94)."""
    neighbour = container_ship_composed().trimmed_surfaces[0 if edge_v == 0.0 else 1][0]
    cos = _cos_across(edge_v, neighbour)
    assert np.all(cos > 0) or np.all(cos < 0)
    assert np.abs(cos).min() >= np.cos(np.radians(C1_ANGLE_DEG))


def test_composed_mesh_stays_on_the_starboard_side():
    assert container_ship_composed().mesh.vertices[:, 1].min() >= 0.0


def test_blend_surface_stays_on_the_starboard_side():
    """Near both centre-plane ends the stem's and the bulb top's tangent planes run across
    y = 0 within a tangent handle's length; the handles turn within them to stay off the plane
    (the surface dipped to y = -0.072 m before)."""
    blend = container_ship_composed().blend
    pts = np.asarray(blend.evaluate_grid(np.linspace(0.0, 1.0, 801), np.linspace(0.0, 1.0, 101)))
    assert pts[..., 1].min() >= -CENTRE_PLANE_TOL
