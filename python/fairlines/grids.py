"""Structured surface grids of NURBS surfaces and of a composed hull's surfaces.

The engine (``fairlines._native``) does the work (docs/meshing.md):

* point distributions along a line, laid out in arc length (metres), not in the parameter:
  uniform, one-sided sinh and tanh, two-sided tanh (Vinokur 1983) with the first and last
  spacing in metres, geometric growth within a maximum ratio (:func:`distribution`,
  :func:`distribute`);
* algebraic grids: the distributions on the four boundaries joined by transfinite
  interpolation in the parameter plane (:func:`surface_grid`), or a grid at given parameters
  (:func:`parameter_grid`);
* grid control that leaves the surface where it is (Yoon 2007's knot insertion and weights):
  knots inserted where a knot-line grid should cluster (:func:`cluster_by_knots`,
  :func:`knot_grid`), and a rational reparameterisation by weights that clusters a uniform
  parameter grid (:func:`cluster_by_weights`);
* a quality report: end spacings, stretching, orthogonality, skewness, aspect ratio.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _native
from ._native import InvalidInput, NurbsSurface

__all__ = ["StructuredGrid", "distribution", "distribute", "surface_grid", "parameter_grid", "knot_grid",
           "cluster_by_knots", "cluster_by_weights", "grid_quality", "hull_grids"]

_KINDS = {k: getattr(_native.Spacing, k) for k in ("uniform", "sinh", "tanh", "tanh_two_sided", "geometric")}


def distribution(kind: str = "uniform", points: int = _native.Distribution().points, **options) -> "_native.Distribution":
    """A :class:`fairlines._native.Distribution`.

    kind      "uniform", "sinh", "tanh" (one-sided: give ``first`` to cluster at the start or
              ``last`` at the end), "tanh_two_sided" (both ``first`` and ``last``),
              "geometric" (``first`` and ``max_ratio``; ``points=0`` picks the fewest points).
    options   first, last (m), max_ratio; the defaults live in the engine.
    Raises InvalidInput for an unknown kind or option.
    """
    if kind not in _KINDS:
        raise InvalidInput(f"kind is {kind!r}; expected one of {', '.join(_KINDS)}")
    d = _native.Distribution()
    d.kind, d.points = _KINDS[kind], int(points)
    for name, value in options.items():
        if name.startswith("_") or name == "kind" or not hasattr(d, name):
            raise InvalidInput(f"distribution option {name!r} is unknown; expected first, last or max_ratio")
        setattr(d, name, value)
    return d


def _dist(d) -> "_native.Distribution":
    if isinstance(d, _native.Distribution):
        return d
    if isinstance(d, dict):
        return distribution(**d)
    if isinstance(d, (int, np.integer)):
        return distribution("uniform", int(d))
    raise InvalidInput(f"distribution is {type(d).__name__}; expected fl.grids.distribution(...), a dict or a point count")


def distribute(length: float, kind: str = "uniform", points: int = _native.Distribution().points,
               **options) -> np.ndarray:
    """Positions (m, from 0 to ``length``) of a distribution's points on a line of ``length`` m
    (arguments as :func:`distribution`). End spacings are met to round-off.
    Raises InvalidInput for bad options, fl.InfeasibleFormParameters when the spacings cannot be
    met (e.g. a one-sided spacing not below the uniform one, a geometric ratio above max_ratio)."""
    return np.asarray(_native.distribute(distribution(kind, points, **options), float(length)))


@dataclass(frozen=True)
class StructuredGrid:
    """A structured grid on a surface: ``points`` (ni, nj, 3) metres, ``params`` (ni, nj, 2) the
    (u, v) of every point; i runs along u, j along v."""

    points: np.ndarray
    params: np.ndarray

    @property
    def shape(self) -> tuple:
        return self.points.shape[:2]

    def quality(self) -> dict:
        """:func:`grid_quality` of this grid."""
        return grid_quality(self.points)

    def write_plot3d(self, path) -> None:
        """Writes this grid as a one-block Plot3D file (``fairlines.mesh_io.write_plot3d``)."""
        from .mesh_io import write_plot3d
        write_plot3d([self.points], path)


def _wrap(res) -> StructuredGrid:
    ni, nj, pts, par = res
    return StructuredGrid(np.asarray(pts).reshape(ni, nj, 3), np.asarray(par).reshape(ni, nj, 2))


def _surface(s):
    if not isinstance(s, NurbsSurface):
        raise InvalidInput(f"surface is {type(s).__name__}; expected a NurbsSurface")
    return s


def surface_grid(surface: NurbsSurface, u=21, v=21) -> StructuredGrid:
    """Grid on the whole surface: distribution ``u`` in arc length along the boundaries v = v0 and
    v = v1, ``v`` along u = u0 and u = u1, interior by transfinite interpolation in the
    parameter plane. ``u``, ``v``: :func:`distribution` objects, dicts of its arguments, or point
    counts (uniform). A zero-length boundary (a pole) takes the opposite one's distribution.
    Raises InvalidInput / fl.InfeasibleFormParameters as :func:`distribute`."""
    return _wrap(_native._surface_grid(_surface(surface), _dist(u), _dist(v)))


def parameter_grid(surface: NurbsSurface, us, vs) -> StructuredGrid:
    """Grid at the parameters ``us`` x ``vs`` (increasing, within the domain). Raises InvalidInput."""
    return _wrap(_native._parameter_grid(_surface(surface), us, vs))


def knot_grid(surface: NurbsSurface, per_span_u: int = 1, per_span_v: int = 1) -> StructuredGrid:
    """Grid on the knot lines, every knot span cut into ``per_span`` equal parameter parts: knots
    inserted by :func:`cluster_by_knots` add grid lines where they go. Raises InvalidInput."""
    s = _surface(surface)
    return parameter_grid(s, _native.knot_line_parameters(s, "u", per_span_u),
                          _native.knot_line_parameters(s, "v", per_span_v))


def cluster_by_knots(surface: NurbsSurface, direction: str, at: float, spacing: float, count: int,
                     growth: float = 1.5) -> NurbsSurface:
    """The same surface with ``count`` knots inserted about parameter ``at`` in ``direction``
    ("u" or "v"): at at, at +- spacing, at +- spacing (1 + growth), ... (Boehm insertion: no point
    of the surface moves). Raises InvalidInput for bad values."""
    return _native._cluster_by_knots(_surface(surface), direction, float(at), float(spacing), int(count),
                                     float(growth))


def cluster_by_weights(surface: NurbsSurface, direction: str, ratio: float) -> NurbsSurface:
    """The same surface reparameterised in ``direction`` by a Moebius map of its parameter (knots
    moved, weights scaled, control points and every surface point unchanged; Lee & Lucian 1991),
    so that a uniform parameter grid has last / first spacing ``ratio`` on a surface of uniform
    speed (> 1 clusters at the start). Raises InvalidInput unless 1e-3 <= ratio <= 1e3."""
    return _native._cluster_by_weights(_surface(surface), direction, float(ratio))


def grid_quality(points) -> dict:
    """Quality of a structured grid ``points`` (ni, nj, 3): first / last spacing along i-lines
    (``first_min``, ``first_max``, ``last_min``, ``last_max``) and j-lines (the same with ``_j``),
    ``max_stretching`` (ratio of neighbouring spacings), ``max_orthogonality_deg`` and
    ``mean_orthogonality_deg`` (|corner angle - 90|), ``max_skewness`` (equiangle),
    ``max_aspect_ratio``, ``degenerate_cells`` (at poles; skipped). Raises InvalidInput."""
    p = np.asarray(points, dtype=float)
    if p.ndim != 3 or p.shape[2] != 3:
        raise InvalidInput(f"points has shape {p.shape}; expected (ni, nj, 3)")
    return dict(_native._grid_quality(p.reshape(-1, 3), p.shape[0], p.shape[1]))


def hull_grids(hull, u=41, v=21) -> dict:
    """Grids on every NURBS surface of a composed hull (``"hull"``, ``"bulb"``, ``"blend"``), each on
    its whole parameter domain: the bare hull's grid is not trimmed where the blend replaces it.
    ``u``, ``v`` as :func:`surface_grid`. Raises InvalidInput."""
    from .compose import ComposedHull
    if not isinstance(hull, ComposedHull):
        raise InvalidInput(f"hull is {type(hull).__name__}; expected a ComposedHull")
    surfaces = {"hull": hull.native.hull}
    if len(hull.trimmed_surfaces) > 1 and hull.trimmed_surfaces[1][0] is not hull.blend:
        surfaces["bulb"] = hull.trimmed_surfaces[1][0]
    if hull.blend is not None:
        surfaces["blend"] = hull.blend
    return {name: surface_grid(s, u, v) for name, s in surfaces.items()}
