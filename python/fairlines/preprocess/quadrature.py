"""Hydrostatics of NURBS half-hull surfaces by the engine's Gauss quadrature on the patches
(``fairlines._native.hydrostatics_of_patches``), with the form coefficients of the import report."""

from __future__ import annotations

from .. import _native
from .integrate import ImportHydrostatics, coefficients, polyline_area
from .sections import section_at


def surface_hydrostatics(surfaces, draft, lpp, beam, *, roles=None) -> ImportHydrostatics:
    """Hydrostatics of NURBS half-hull surfaces below the draft: the engine's Gauss quadrature
    over every patch clipped at the waterline, each patch turned outward about the station
    x = Lpp/2 (full ship). Midship area Am is the section of the surfaces at x = Lpp/2 (Green's
    theorem on the cut). Raises InvalidInput for a non-positive draft or when nothing of the
    surfaces lies below it."""
    h = _native.hydrostatics_of_patches(list(surfaces), float(draft), 0.5 * float(lpp))
    if h.volume <= 0.0:
        raise _native.InvalidInput(f"draft {draft} m leaves no volume below it; expected a draft above the keel")
    am = 2 * sum(polyline_area(p, draft) for p in section_at(surfaces, lpp / 2, roles=roles))
    return coefficients(h.volume, h.lcb, h.vcb, h.waterplane_area, h.lcf, am, lpp, beam, draft,
                        method="Gauss quadrature on the NURBS surface", wetted_surface=h.wetted_surface)
