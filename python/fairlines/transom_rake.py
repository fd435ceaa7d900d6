"""A raked transom: the skinned hull sheared so that its aft end lies in the transom's plane.

The sections are designed and skinned upright (x = const); the skin's control points above the
transom's lower edge z_e are then moved aft by (z - z_e) tan(rake), fully at the aft end and
fading to none RAKE_FADE times the largest such move forward of it. The aft end's control points
all move fully, and an affine map of a curve's control points maps the curve itself, so the aft
end lies exactly in the plane x = x_aft - (z - z_e) tan(rake); the keel and counter below z_e do
not move. The fade is a smoothstep whose steepest slope, 1.5 / (the fade's length / the move),
keeps every row of control points running forward while the fade is longer than MIN_FADE moves.
"""

from __future__ import annotations

import math

import numpy as np

from ._native import InvalidInput, NurbsSurface

__all__ = ["raked", "RAKE_FADE", "MIN_FADE", "MAX_FADE_SHARE", "NO_TRANSOM_TOL"]

#: The rake fades out over this many times the transom's largest move (its top's), forward of it.
#: At 3 the container ship raked 15 deg had 20 / 11 waterline / buttock sign changes against 17 / 8
#: upright (the fade bends the cuts it crosses, as 1 / fade length squared); from 10 on, 17 / 8.
RAKE_FADE = 10.0
#: ... but over at most this share of the hull's length (a short, deep hull raked steeply would
#: fade past its stem), and never over fewer than MIN_FADE moves (rows would then run aft).
MAX_FADE_SHARE = 0.5
MIN_FADE = 3.0
#: A transom lower than this share of the hull's length above its lower edge is none: a cruiser
#: stern's control points at the deck stand round-off above the profile there (4e-15 m).
NO_TRANSOM_TOL = 1e-9


def raked(surface: NurbsSurface, x_aft: float, z_edge: float, rake_deg: float, length: float) -> NurbsSurface:
    """The half hull `surface` (v from aft to fore, its aft end at x = x_aft, m, `length` m long)
    with its transom raked rake_deg from the vertical about its lower edge at height z_edge (m):
    positive, the top aft. rake_deg 0 returns the surface itself. Raises InvalidInput (naming
    ends.transom_rake) where no transom stands above z_edge, or where the rake is too steep for
    its fade to fit the hull."""
    if rake_deg == 0.0:
        return surface
    t = math.tan(math.radians(rake_deg))
    P = np.array(surface.control_points, dtype=float)  # (nu, nv, 3)
    h = np.maximum(P[..., 2] - z_edge, 0.0)
    height = float(h[:, 0].max())  # the transom's, above its lower edge
    if height <= NO_TRANSOM_TOL * length:
        raise InvalidInput(f"ends.transom_rake is {rake_deg:g} deg; expected 0: the hull has no transom at its aft end "
                           f"(the profile meets the deck there, z {z_edge:.6g} m: a cruiser stern or a post)")
    move = float(h.max()) * abs(t)
    reach = min(RAKE_FADE * move, MAX_FADE_SHARE * length)
    if reach < MIN_FADE * move:
        steepest = math.degrees(math.atan(MAX_FADE_SHARE * length / (MIN_FADE * float(h.max()))))
        raise InvalidInput(f"ends.transom_rake is {rake_deg:g} deg; expected at most {steepest:.1f} deg on this hull "
                           f"(its top would move {move:.3g} m, too far to fade out over half its length)")
    s = np.clip((P[..., 0] - x_aft) / reach, 0.0, 1.0)
    P[..., 0] -= (1.0 - s * s * (3.0 - 2.0 * s)) * h * t
    weights = np.array(surface.weights) if surface.is_rational else None
    return NurbsSurface(surface.degree_u, surface.degree_v, surface.knots_u, surface.knots_v, P, weights)
