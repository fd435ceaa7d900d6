"""The blending surface between a bare hull and a bulb (Kim and Hwangbo 2008): where it goes
around their seam (:func:`seam_blend_placement`, placed by the engine) and the surface itself
(:func:`blend_surface`), curvature-continuous (G2) with both. Conventions: metres, x forward from AP, y >= 0.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from . import _native
from ._native import NurbsSurface
from ._options import fill_options
from .bulb import BulbousBow

__all__ = ["BlendPlacement", "BlendSurface", "blend_surface", "placement_options", "seam_blend_placement"]


def _boundary_uv(surface: NurbsSurface, boundary, what: str) -> np.ndarray:
    if isinstance(boundary, tuple) and len(boundary) == 2 and isinstance(boundary[0], str):
        which, value = boundary
        t = np.linspace(0.0, 1.0, 129)
        if which == "u":
            kv = surface.knots_v
            return np.column_stack([np.full_like(t, float(value)), kv[0] + (kv[-1] - kv[0]) * t])
        if which == "v":
            ku = surface.knots_u
            return np.column_stack([ku[0] + (ku[-1] - ku[0]) * t, np.full_like(t, float(value))])
        raise _native.InvalidInput(f"{what} iso-line direction is {which!r}; expected 'u' or 'v'")
    arr = np.asarray(boundary, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise _native.InvalidInput(f"{what} has shape {arr.shape}; expected (k, 2) (u, v) points or ('u'|'v', value)")
    return arr


@dataclass(frozen=True)
class BlendSurface:
    """A blending surface: ``surface`` (u along the boundaries, v = 0 on surface a, v = 1 on
    b) and its measured continuity at each boundary (``at_a``, ``at_b``: max normal angle in
    degrees and max gap in metres, by closest-point projection)."""

    surface: NurbsSurface
    at_a: dict
    at_b: dict
    boundary_a: Any = None  #: the boundary on surface a as given ((k, 2) (u, v) array)
    boundary_b: Any = None  #: the boundary on surface b as given
    tension: float = 1.0

    @property
    def max_angle_deg(self) -> float:
        return max(self.at_a["max_angle_deg"], self.at_b["max_angle_deg"])


@dataclass(frozen=True)
class BlendPlacement:
    """Where the blend around a hull/bulb seam goes (:func:`seam_blend_placement`): the hull
    in the orient_bare_hull convention, the bulb surface, the blend's boundary on each
    (``boundary_a`` (k, 2) (u, v) on the hull, ``boundary_b`` ``("u", u_b)`` on the bulb) and
    its tension. That is all compose() takes from a blend (it skins the blend at the mesh
    resolution itself), so ``compose([hull, bulb, placement])`` equals ``compose([hull, bulb,
    placement.blend_surface()])`` without skinning a surface it does not use."""

    hull: NurbsSurface
    bulb: NurbsSurface
    boundary_a: np.ndarray
    boundary_b: tuple
    tension: float

    def blend_surface(self, **options) -> BlendSurface:
        """The blending surface itself, at this placement's tension; ``options`` as for
        :func:`blend_surface`. Raises InvalidInput for a bad option."""
        return blend_surface(self.hull, self.boundary_a, self.bulb, self.boundary_b,
                             **{"tension": self.tension, **options})


def blend_surface(surface_a: NurbsSurface, boundary_a, surface_b: NurbsSurface, boundary_b,
                  **options) -> BlendSurface:
    """Blending surface between two surfaces, curvature-continuous (G2) along both boundary
    curves by default (Kim and Hwangbo 2008's fair skinning of Hermite sections, quintic here).
    The surface is cubic along the boundaries and quintic across (cubic with continuity=1).

    boundary_a, boundary_b   curves on each surface: a (k, 2) polyline of (u, v) parameters, or
                             an iso-line ``("u", value)`` / ``("v", value)``; both run the
                             same way (first point to first point).
    options                  fields of :class:`fl.BlendOptions` by keyword (defaults in the
                             engine): samples, sections along the boundaries; tension,
                             the sections' speed across the boundaries over the gap (0.8
                             of it for quintic sections);
                             check_samples, points per boundary at which the normal angle and
                             gap are measured; continuity, 2 (the surfaces' normal
                             curvature across each boundary: G2) or 1 (tangent planes
                             only: G1, cubic sections); centre_plane_ends.

    Raises InvalidInput for a bad boundary or option.
    """
    ba = _boundary_uv(surface_a, boundary_a, "boundary_a")
    bb = _boundary_uv(surface_b, boundary_b, "boundary_b")
    checks = {"samples": int, "check_samples": int, "tension": float, "centre_plane_ends": bool}
    o = fill_options(_native.BlendOptions, "blend_surface", options, checks)
    s, at_a, at_b = _native._blend_surface(surface_a, ba, surface_b, bb, o)
    return BlendSurface(s, dict(at_a), dict(at_b), ba, boundary_b, o.tension)


def placement_options(**options) -> "_native.BlendPlacementOptions":
    """A :class:`fl.BlendPlacementOptions` with the given fields set (defaults in the engine):
    clearance_u, clearance_v (hull parameter units between the seam and the blend's boundary),
    bulb_clearance (bulb u ahead of the seam), tension, points. Raises InvalidInput naming an
    unknown field or a value of the wrong type."""
    return fill_options(_native.BlendPlacementOptions, "seam_blend_placement", options)


def _boundaries_around_seam(hull: NurbsSurface, seam: dict, **options):
    """The blend's boundaries around a hull/bulb seam (``hull`` oriented, ``seam`` a dict with
    ``uv_a`` on the hull and ``uv_b`` on the bulb): (on_hull (k, 2), ("u", u_b)), placed by the
    engine (see :func:`seam_blend_placement`). Raises NoBlendFits when none fits."""
    on_hull, bulb_u = _native._blend_boundaries_around_seam(hull, seam["uv_a"], seam["uv_b"],
                                                            placement_options(**options))
    return on_hull, ("u", float(bulb_u))


def seam_blend_placement(hull: NurbsSurface, bulb: "BulbousBow | NurbsSurface", *,
                         seam_options: "_native.ComposeOptions | None" = None, **options) -> BlendPlacement:
    """Where the blend around the seam a bulb makes on a bare hull goes, as a
    :class:`BlendPlacement`: ``compose([hull, bulb, placement])`` composes with it (skinning
    the blend at the mesh resolution), ``placement.blend_surface()`` skins the surface itself.

    On the hull (``placement.hull``: the hull in the orient_bare_hull convention, u aft cut ->
    stem, v keel -> deck) the boundary is an ellipse arc in (u, v) around the seam,
    ``clearance_u`` / ``clearance_v`` (parameter units) clear of it; on the bulb the section
    ``bulb_clearance`` ahead of the seam's foremost point; ``tension``: cross-boundary tangent
    length relative to a third of the gap. ``options``: the fields of
    :class:`fl.BlendPlacementOptions` by keyword (defaults in the engine).

    ``seam_options``: the :class:`fl.ComposeOptions` the seam is traced with (bulb_v,
    tolerance; default the engine's), so that the seam is the one ``compose`` traces.

    Raises InvalidInput when the bulb cannot meet the hull or an option is bad, NoBlendFits (an
    InvalidInput) when no boundary fits (the message says why)."""
    surface_b = bulb.surface if isinstance(bulb, BulbousBow) else bulb
    if not isinstance(hull, NurbsSurface) or not isinstance(surface_b, NurbsSurface):
        raise _native.InvalidInput(f"hull and bulb are {type(hull).__name__}, {type(bulb).__name__}; expected a "
                                   "NurbsSurface hull and a BulbousBow or NurbsSurface bulb")
    # the seam compose([hull, bulb]) traces (same checks), without meshing the union
    oriented, on_hull, bulb_u, tension = _native._seam_blend_placement(
        hull, surface_b, seam_options if seam_options is not None else _native.ComposeOptions(),
        placement_options(**options))
    return BlendPlacement(oriented, surface_b, on_hull, ("u", float(bulb_u)), float(tension))
