"""Each station's section as the mean of the section family's on either side of the station.

The skin interpolates the sections at its stations, so it samples the family there. Between
the stations the family carries detail shorter than their spacing: the section spline's error
swings as the waterline point Q passes its knots (docs/sections.md), one period per knot span
of Q, about a station spacing near the ends. Sampled at the stations, that detail comes back as
wobbles a few stations long in the waterlines and buttocks. The mean of the family's sections
at x +- d, d a fraction of the station spacing, takes most of it out before the sampling, the
way a signal is filtered before it is sampled. The window is symmetric: an offset mean would
place the family a little off its station, and near the stem, where the keel point climbs the
stem, millimetres of x move the section by centimetres.

fl.Hull chooses d and the stations kept as designed (the hull's ends, given sections,
appendages, the SAC's flat part, where the waterline is at B/2). Here: a control-point
coordinate the three sections share (a flat of side or bottom) keeps its exact value, so the
skin still holds its runs; and the deck edge keeps its own, the mean's share rising over
DECK_ROWS control points below it (kept with no ramp, the deck made an S frame in 99 of 100
hulls). The keel and stem contour is averaged: it moves inside the profile's bends by up to
0.04 % Lpp (held like the deck edge, it costs what the mean gains; docs/sections.md), except
at the stem's top: where a forebody station's keel point lies on the stem near or above T
(keel_hold_share), its keel end is held like the deck edge, or the mean lifts it off the
profile (5.3 cm on the container ship) and the waterlines there end in a hollow, a lobe and a
hollow in their last metre.
"""

from __future__ import annotations

import numpy as np

from . import _native

__all__ = ["STATION_MEAN", "window", "mean_sections", "deck_ramp", "keel_hold_share"]

STATION_MEAN = 0.375  # default offset d of the two sections, fraction of the clustered station spacing
SHARED_TOL = 1e-9     # m: a coordinate the three sections hold within this keeps the station's value
KEEL_HOLD = (0.8, 1.0)  # keel point height / T over which a forebody station's keel end comes to be held
DECK_ROWS = 4         # the mean's share rises from 0 at the deck edge to 1 over this many control points


def deck_ramp(n: int) -> np.ndarray:
    """(n,) share of the mean by control point, deck edge first: a smoothstep from 0 to 1 over
    DECK_ROWS, so the deck edge stays as designed and the section leaves it without a kink."""
    t = np.clip(np.arange(n) / DECK_ROWS, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def keel_hold_share(keel_over_draft: np.ndarray, forebody: np.ndarray) -> np.ndarray:
    """(m,) how much of each station's keel end is held (0 .. 1): a smoothstep over KEEL_HOLD of
    its keel point's height over T, forebody stations only (the stem's top). Measured on
    bench_fairness_space's hulls 0-99 / 0-199: upper waterlines clean 213 -> 228 / 437 -> 457,
    lower 211 -> 207 / 430 -> 418 (a hollow of 0.1-0.6 deg in a 0.74 T waterline's last
    0.5 % Lpp); a ramp over 3 or 6 rows, or the hold from 0.7 or 0.85 T, did no better."""
    lo, hi = KEEL_HOLD
    t = np.clip((np.asarray(keel_over_draft, dtype=float) - lo) / (hi - lo), 0.0, 1.0)
    return np.where(forebody, t * t * (3.0 - 2.0 * t), 0.0)


def window(xs: np.ndarray, offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where the family is sampled for the station mean.

    xs: (q,) stations, increasing, metres; offsets: (q,) d of each station, metres, 0 for a
    station kept as designed, else less than its distance to either neighbour. Returns
    (x, averaged): (2 m,) positions, metres, x_i - d_i then x_i + d_i for each averaged
    station, and the (m,) indices i of those stations."""
    averaged = np.flatnonzero(np.asarray(offsets) > 0)
    d = offsets[averaged]
    return np.column_stack([xs[averaged] - d, xs[averaged] + d]).ravel(), averaged


def mean_sections(curves: list, samples: list, averaged: np.ndarray, keel_hold: np.ndarray | None = None) -> list:
    """The stations' sections with each averaged one replaced by the mean of its two samples.

    curves: the q section curves at the stations (one knot vector); samples: the section
    curves at window()'s positions, in its order; averaged: window()'s station indices;
    keel_hold: (m,) share of each averaged station's keel end held as designed
    (keel_hold_share; None: none). Returns q NurbsCurves on the same knots, each averaged one
    in its station's plane x."""
    out = list(curves)
    if not len(averaged):
        return out
    own = np.array([curves[i].control_points for i in averaged])        # (m, n, 3)
    pairs = np.array([c.control_points for c in samples]).reshape(len(averaged), 2, *own.shape[1:])
    mean = pairs.mean(axis=1)
    shared = np.abs(pairs - own[:, None]).max(axis=1) <= SHARED_TOL
    mean[shared] = own[shared]
    ramp = deck_ramp(own.shape[1])
    share = np.broadcast_to(ramp, own.shape[:2])
    if keel_hold is not None:  # the keel end held like the deck edge, by the station's share
        share = share * (1.0 - np.asarray(keel_hold, dtype=float)[:, None] * (1.0 - ramp[::-1][None, :]))
    mean = own + share[..., None] * (mean - own)
    mean[..., 0] = own[..., 0]
    degree, knots = curves[0].degree, list(curves[0].knots)
    for i, m in zip(averaged, mean):
        out[i] = _native.NurbsCurve(degree, knots, m)
    return out
