"""Hydrostatics of a hull surface (the engine's Gauss-Legendre quadrature on the surface)."""

from __future__ import annotations

import numpy as np

from . import _native
from ._native import NurbsSurface
from ._options import fill_options


def hydrostatics_options(**options) -> _native.HydrostaticsOptions:
    """A :class:`fl.HydrostaticsOptions` with the given fields set (defaults in the engine).
    Raises InvalidInput naming an unknown field or a value of the wrong type."""
    return fill_options(_native.HydrostaticsOptions, "hydrostatics", options)


def hydrostatics(surface: NurbsSurface, draft: float, **options) -> _native.Hydrostatics:
    """Hydrostatics of a hull surface at ``draft`` (m above base) by Gauss-Legendre quadrature
    on the surface. ``options``: the fields of :class:`fl.HydrostaticsOptions` by keyword --
    half_hull (the surface is the y >= 0 half of the hull: volume, areas and SAC doubled to
    full-ship values; openings other than the centre plane must lie in planes with no y in
    their normal: x = const or a raked transom's, at the surface's ends along the hull),
    length / breadth for the coefficients (0: submerged extent), midship_x (the
    station of Am; None: middle), gauss, sac_stations, density (t/m^3), trim by the stern (m)
    over trim_length (AP at x = 0 to FP; draft is then the draft at trim_length / 2).

    Raises InvalidInput for a bad draft or option, or a waterplane above the surface's highest
    point."""
    return _native._hydrostatics(surface, draft, hydrostatics_options(**options))


def midship_x(surface: NurbsSurface, mid: float) -> float | None:
    """``mid`` (m, Lpp / 2) as the station of Am when the surface reaches it, else None (the
    middle of its extent): a forebody model has no midship section."""
    x = np.asarray(surface.control_points)[..., 0]
    return mid if x.min() <= mid <= x.max() else None
