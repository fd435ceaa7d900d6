"""Hydrostatics of triangle meshes: one engine function (``fairlines._native.mesh_hydrostatics``,
the divergence theorem over the triangles clipped at the waterplane) and one vocabulary of
results (``volume``, ``lcb``, ``vcb``, ``waterplane_area``, ``lcf``, ``wetted_surface``,
``midship_area``). Every Python path that measures a mesh calls it."""

from __future__ import annotations

import numpy as np

from . import _native
from ._native import InvalidInput, MeshHydrostatics, MeshHydrostaticsOptions
from ._options import fill_options

__all__ = ["MeshHydrostatics", "MeshHydrostaticsOptions", "hydrostatics_of_mesh", "mesh_hydrostatics_options",
           "displaced_volume_of_mesh"]


def mesh_hydrostatics_options(**options) -> MeshHydrostaticsOptions:
    """A :class:`MeshHydrostaticsOptions` with the given fields set (``half_hull``, ``orient``,
    ``midship_x``; the defaults live in the engine). Raises InvalidInput for an unknown name."""
    return fill_options(MeshHydrostaticsOptions, "mesh hydrostatics", options)


def hydrostatics_of_mesh(vertices, faces, draft: float, **options) -> MeshHydrostatics:
    """Hydrostatics of a half-hull triangle mesh (``vertices`` (n, 3) m, ``faces`` (m, 3)
    outward unless ``orient=True``) floating at ``draft`` (m); options by keyword (see
    :func:`mesh_hydrostatics_options`). A mesh with nothing below the draft has volume 0.
    Raises InvalidInput for bad shapes, face indices, a non-finite draft or an unknown option."""
    return _native.mesh_hydrostatics(np.asarray(vertices, float), np.asarray(faces), float(draft),
                                     mesh_hydrostatics_options(**options))


def displaced_volume_of_mesh(vertices, faces, draft: float, **options) -> MeshHydrostatics:
    """:func:`hydrostatics_of_mesh` for a body that must float: raises InvalidInput when the
    draft leaves no displaced volume (a draft at or below the keel)."""
    h = hydrostatics_of_mesh(vertices, faces, draft, **options)
    if h.volume <= 0.0:
        raise InvalidInput(f"draft {draft} m gives no displaced volume; expected a draft above the keel")
    return h
