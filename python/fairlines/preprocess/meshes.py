"""Hydrostatics of triangle meshes (an input grid triangulated, or a surface tessellated), by the
engine's divergence-theorem integrals clipped at the waterline."""

from __future__ import annotations

import numpy as np

from ..grid_faces import grid_triangles
from ..hydrostatics_mesh import hydrostatics_of_mesh
from ..offsets import HullData
from .integrate import ImportHydrostatics, coefficients, offsets_hydrostatics, sections_hydrostatics


def grid_mesh(points):
    """Triangles of a structured (rows, cols, 3) grid: vertices (n, 3), faces (m, 3); faces of
    zero area (a grid row collapsed to a point) are dropped."""
    ni, nj = points.shape[:2]
    faces = grid_triangles(ni, nj)
    tri = points.reshape(-1, 3)[faces]
    area = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    return points.reshape(-1, 3), faces[area > 0]


def mesh_hydrostatics(meshes, draft, lpp, beam) -> ImportHydrostatics:
    """Hydrostatics of one or more triangle meshes [(vertices, faces), ...] of the half hull,
    clipped at the draft (the engine's :func:`fairlines.hydrostatics_of_mesh`); both sides
    reported. Each mesh is oriented on its own. Raises InvalidInput for malformed meshes."""
    parts = [hydrostatics_of_mesh(v, f, draft, orient=True, midship_x=lpp / 2) for v, f in meshes]
    V = sum(h.volume for h in parts)
    awp = sum(h.waterplane_area for h in parts)
    return coefficients(V, sum(h.volume * h.lcb for h in parts) / V, sum(h.volume * h.vcb for h in parts) / V, awp,
                        sum(h.waterplane_area * h.lcf for h in parts) / awp, sum(h.midship_area for h in parts),
                        lpp, beam, draft, method="divergence theorem on a triangle mesh",
                        wetted_surface=sum(h.wetted_surface for h in parts))


def surface_meshes(surfaces, n_u=240, n_v=160):
    """Fine quad-split triangle meshes of the surfaces (the independent hydrostatics path)."""
    out = []
    for s in surfaces:
        us = np.linspace(*s.domain_u, n_u)
        vs = np.linspace(*s.domain_v, n_v)
        out.append(grid_mesh(s.evaluate_grid(us, vs)))
    return out


def input_hydrostatics(data: HullData) -> ImportHydrostatics:
    """Hydrostatics of the input itself: Simpson on an offsets table, or the exact integrals
    of the triangulated point grids (the trapezoid rule's surface counterpart)."""
    if data.offsets is not None:
        return offsets_hydrostatics(data)
    if data.sections:
        return sections_hydrostatics(data)
    return mesh_hydrostatics([grid_mesh(g.points) for g in data.grids], data.draft, data.lpp, data.beam)
