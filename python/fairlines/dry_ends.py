"""Sections above the water beyond an end of the design waterline that closes in a point at
the deck (a raked stem's overhang; a cruiser stern's counter), read off the waterlines rather
than off a section template.

Notation: x_e the waterline's end (the stem, or the counter, at T), y_e(z) and s_e(z) the
half-breadth and its slope dy/dh of the waterline at height z at x_e (from the immersed sections
there), x_s(z) the end contour (the profile turned round: where the waterline at z ends on the
centre plane), h = |x - x_e| the distance beyond the end, Delta(z) = |x_s(z) - x_e|.

Each waterline above T is continued from x_e to the stem by the quadratic with its value and
slope at x_e that reaches 0 at x_s(z):

    q(x, z) = y_e + s_e h + c h^2,   c = -(y_e + s_e Delta) / Delta^2,

so it has no inflection past x_e: straight where its tangent at x_e meets the stem, hollow where
it would meet the centre plane short of it, convex beyond. A section at x is q at the heights
from its keel point (on the stem) to its deck edge, plus the deck line's difference from q at
the deck, shared linearly in height (nothing at the keel), so the section ends on the deck line
and the sheer. The section template's dry continuation (a fillet cut at the keel point, whose
lean follows the profile's slope) put a hollow bump into every waterline above T just past x_e
and, with the skin's one span from x_e to the stem head (a section of one point), a hollow-convex
pair of lobes at the stem. Measured on the first 100 hulls of bench_hull's sample, with two
stations added in the overhang (Hull.stations): waterlines above T clean as a lines plan 105 ->
127 of 300, their wobbles within 1.5 % Lpp of the stem 149 -> 111; on 60 of them with a cruiser
stern, read off at both ends: upper waterlines clean 61 -> 91 of 180, their wobbles at the aft end
126 -> 74 (docs/sections.md).
"""

from __future__ import annotations

import numpy as np

from . import _native

#: The waterlines' slopes at x_e are read from the sections at x_e and this fraction of Lpp
#: inside it: the immersed sections' ripple within a knot span is not the waterline's run.
END_SLOPE_BASE = 0.01
#: Heights per dry section (deck edge to keel point) handed to the section's fit.
SECTION_HEIGHTS = 60
#: Samples of a section and of the end contour when read as functions of height.
SAMPLES = 401


def section_half_breadth(curve, z: np.ndarray, samples: int = SAMPLES, outside: float | None = None) -> np.ndarray:
    """Half-breadth (m) of a section curve (3-D, deck -> keel) at heights z (m), read as a
    function of height from `samples` points over its knots; beyond its heights the nearest
    end's, or `outside`."""
    kn = np.asarray(curve.knots)
    p = np.asarray(curve.evaluate(np.linspace(kn[0], kn[-1], samples)))
    order = np.argsort(p[:, 2], kind="stable")
    return np.interp(z, p[order, 2], p[order, 1], left=outside, right=outside)


def end_waterlines(end_specs: list, lpp: float, draft: float) -> tuple:
    """(z, y_e(z), s_e(z)) at a waterline's end from the specs of the sections 2 and 1 times
    END_SLOPE_BASE Lpp inside x_e and at x_e (m, m, dy/dh), z from T to the lower deck edge. The
    slope is the one-sided difference of second order: the first-order one read the slope half
    the base inside x_e, off by y'' END_SLOPE_BASE Lpp / 2 where the waterline still bends at its end."""
    curves = [d.curve for d in _native.design_sections(end_specs)]
    top = min(float(np.asarray(c.evaluate([0.0]))[0, 2]) for c in curves)
    z = np.linspace(draft, top, SAMPLES)
    y2, y1, y_end = (section_half_breadth(c, z) for c in curves)
    return z, y_end, (3.0 * y_end - 4.0 * y1 + y2) / (2.0 * END_SLOPE_BASE * lpp)


def end_contour(profile, x_end: float, x_tip: float):
    """x_s(z) (m): where the profile from x_end out to the hull's end x_tip (either side) reaches
    height z (its running maximum, so a profile flat to round-off stays a function)."""
    x = np.linspace(x_end, x_tip, SAMPLES)
    z = np.maximum.accumulate(np.asarray(profile(x), dtype=float))
    return lambda zq: np.interp(zq, z, x)


def dry_section(spec, x_end: float, ends: tuple, x_contour) -> np.ndarray | None:
    """(SECTION_HEIGHTS, 2) points (y, z), m, deck edge to keel point, of the dry section at
    spec.x (beyond x_end) from the end waterlines `ends` (end_waterlines) and the end contour
    `x_contour` (end_contour); None for a section of one point (the stem head, the stern's end)."""
    if spec.z_deck - spec.z_keel <= 1e-9 * max(spec.z_deck, 1.0):
        return None
    z_e, y_e, s_e = ends
    z = np.linspace(spec.z_deck, spec.z_keel, SECTION_HEIGHTS)
    zc = np.clip(z, z_e[0], z_e[-1])
    y0, s0 = np.interp(zc, z_e, y_e), np.interp(zc, z_e, s_e)
    h = abs(spec.x - x_end)
    span = np.maximum(np.abs(x_contour(z) - x_end), h)  # the keel point's own waterline ends at spec.x
    s0 = np.maximum(s0, -2.0 * y0 / span)  # steeper, q would cross the centre plane short of the end
    q = y0 + s0 * h - (y0 + s0 * span) * (h / span) ** 2
    share = (z - spec.z_keel) / (spec.z_deck - spec.z_keel)
    y = np.clip(q + share * (spec.y_deck - q[0]), 0.0, spec.y_max)
    y[-1] = 0.0
    return np.column_stack([y, z])
