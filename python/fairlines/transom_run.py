"""The topsides' run into a transom: the sections above T aft of RUN_LENGTH Lpp forward of the
design waterline's aft end, read off faired waterlines rather than off the section template.

Notation: x_a the transom (the hull's aft end), x_e the waterline's aft end (where the keel
leaves the water, x_e > x_a for a dry transom, x_e = x_a for a wet one), x_r = x_e + RUN_LENGTH
Lpp the run's forward end, eta = (z - T) / (z_deck - T) the height above T as a fraction of the
topside at x, y_t(x, eta) the template section's half-breadth there, h = x_r - x.

Each topside line eta = const of a dry transom's run is the quadratic with the template's value a
and slope b at x_r (the slope read over END_SLOPE_BASE Lpp forward of x_r) that fits the templates
at RUN_SAMPLES sections from x_a to x_r by least squares (a wet transom's: below):

    q(h) = a - b h + c h^2,   c = sum h^2 (y_t - a + b h) / sum h^4,

so it has no inflection within the run and meets the rest of the line with its value and
slope. A section in the run keeps its designed curve and has each control point's half-breadth
shifted by w (q - y_t) read at its Greville abscissa (Schoenberg's variation-diminishing
approximation of the shift), less the deck row's shift shared linearly in eta (the deck edge
stays on the deck line); w rises from 0 where the control point's support reaches down to the
keel or T (whichever is higher) to 1 over BLEND_DEPTH of the topside (smoothstep), so below T
(the design waterline and the immersed area) the section is exactly as designed.

Why: as the immersed part of a section vanishes toward x_e, the template's topside changes
character (the flare from a waterline point near the centre plane to the deck edge); the
topside lines rounded in to the transom and overshot ahead of it, a wobble of 0.1-1 deg in the
upper waterlines 0.5-3 % Lpp forward of x_e: 72 of the 219 upper waterlines of the 73
dry-transom hulls among bench_hull's first 100, 33 with the run. Over those 100 hulls
(bench_fairness_space) the upper waterlines clean as a lines plan went 176 -> 208 of 300 (aft-end
wobbles 101 -> 52, steps 23 -> 6), on hulls 100-199 189 -> 215; refitting the sections as
given shapes instead moved them by up to 14 mm (the fit's bending penalty and the shifts
through Q), which made wobbles of its own.

A wet transom (its bottom under water, x_e = x_a) has the same round-in: the immersed depth
shrinks toward the transom, so the sections' flare at T (about b / d) grows fast and the topside
lines turn in over the last 2-4 % Lpp, a convex lobe of 0.1-1.6 deg aft of a hollow run. There
the least-squares fit found that lobe and put the inflection at x_r; so a wet transom's lines
keep the template's bend at x_r instead (c from the second difference over two END_SLOPE_BASE
steps, b one-sided to second order): the hollow of the run carries through to the transom.
bench_fairness_space, hulls 0-99: the upper waterlines (1.23 T, 1.475 T) with more than two sign
changes 52 -> 22 (the least-squares fit 41); every mark 38 -> 38 on hulls 0-99, 40 -> 41 on
100-199; S frames and buttocks unchanged. The bend's continuation for dry transoms too made
every mark 36 / 34: their fit stays.
"""

from __future__ import annotations

import numpy as np

from . import _native
from .basic_curves import clip

#: The run's length forward of the waterline's aft end, fraction of Lpp. 0.04, not 0.03: since
#: the bilge arc's fine weight is 0.5 the upper waterlines took wobbles of 0.1-0.2 deg where the
#: run ended (about 4.7 % Lpp from the transom; 300 hulls: upper waterlines clean 778 -> 791 of
#: 900, hulls meeting all the marks 65 -> 71; 0.035 / 0.045 / 0.05: 791 / 779 / 771).
RUN_LENGTH = 0.04
#: Template sections the run's lines are fitted to, from the transom to x_r.
RUN_SAMPLES = 8
#: Topside lines (eta from 0 to 1) fitted; a section's points in between are interpolated.
RUN_LEVELS = 41
_LEVELS = np.linspace(0.0, 1.0, RUN_LEVELS)
_LEVELS.flags.writeable = False
#: Points of a section read as a function of height for its topside lines.
OFFSET_SAMPLES = 161
#: The lines' slopes at x_r are read over this fraction of Lpp forward of it.
END_SLOPE_BASE = 0.01
#: Length over which the shift onto the faired lines fades out toward x_r, fraction of Lpp: the
#: lines' slope at x_r is read over END_SLOPE_BASE, so without the fade the sections kinked along
#: x there (the tanker's 23 times the median second difference of its control points along x).
FADE_LENGTH = 0.01
#: Height over which the faired topside takes over from the template, fraction of the topside.
BLEND_DEPTH = 0.25


def sample_params(curve) -> tuple:
    """(knots, degree, n, t) of a section curve: t its n Greville abscissae, the last knot of
    each control point's support (n) and OFFSET_SAMPLES parameters over the curve, so one
    evaluation gives all that the run reads of a section."""
    knots, p = np.asarray(curve.knots), curve.degree
    n = len(knots) - p - 1
    greville = np.convolve(knots[1:n + p], np.full(p, 1.0 / p), mode="valid")
    return knots, p, n, np.concatenate([greville, knots[p + 1:n + p + 1], np.linspace(knots[0], knots[-1], OFFSET_SAMPLES)])


def topside_offsets(samples: np.ndarray, z_deck: float, draft: float, z_keel: float) -> np.ndarray:
    """Half-breadths (m) on the RUN_LEVELS topside lines (eta 0 .. 1) of a section sampled at
    `samples` (k, 3) points (read as a function of height); NaN below its keel point."""
    z = draft + _LEVELS * (z_deck - draft)
    order = np.argsort(samples[:, 2], kind="stable")
    return np.where(z >= z_keel, np.interp(z, samples[order, 2], samples[order, 1]), np.nan)


def fit_run(x: np.ndarray, y: np.ndarray, x_r: float, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """c (1 / m) of each topside line: x (n,) sample stations, y (n, RUN_LEVELS) their template
    offsets (NaN where a section has none), a and b (RUN_LEVELS,) the value (m) and slope dy/dx
    at x_r. A line with no sample aft of x_r keeps c = 0."""
    h = (x_r - x)[:, None]
    g = h * h
    r = y - a[None, :] + b[None, :] * h
    have = np.isfinite(r)
    num = (g * np.where(have, r, 0.0)).sum(axis=0)
    den = np.where(have, g * g, 0.0).sum(axis=0)
    return np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)


class TransomRun:
    """The faired topside lines of a transom's run (see the module docstring)."""

    def __init__(self, x_aft: float, x_end: float, lpp: float, draft: float, template_specs, wet: bool = False):
        """template_specs(xs) -> SectionSpecs of the template at xs (m), without the run; `wet`:
        the transom's bottom is under water (x_end = x_aft), so the lines keep the template's bend
        at x_r (see the module docstring)."""
        self.x_a, self.draft = x_aft, draft
        self.x_r = x_end + RUN_LENGTH * lpp
        xs = np.linspace(x_aft, self.x_r, RUN_SAMPLES)
        e = END_SLOPE_BASE * lpp
        ahead = self.x_r + e * np.arange(1, 3 if wet else 2)  # the bend needs a second step
        specs = template_specs(np.append(xs, ahead))
        curves = [d.curve for d in _native.design_sections(specs)]
        self._params = sample_params(curves[0])  # the sections share one knot vector
        n = self._params[2]
        y = np.array([topside_offsets(np.asarray(c.evaluate(self._params[3]))[2 * n:], s.z_deck, draft, s.z_keel)
                      for c, s in zip(curves, specs)])
        y_run, self.a, y_ahead = y[:RUN_SAMPLES - 1], y[RUN_SAMPLES - 1], y[RUN_SAMPLES:]
        if wet:  # one-sided second-order slope and the bend at x_r
            self.b = (-3.0 * self.a + 4.0 * y_ahead[0] - y_ahead[1]) / (2.0 * e)
            self.c = (self.a - 2.0 * y_ahead[0] + y_ahead[1]) / (2.0 * e * e)
        else:
            self.b = (y_ahead[0] - self.a) / e
            self.c = fit_run(xs[:-1], y_run, self.x_r, self.a, self.b)
        self.levels = _LEVELS
        self.fade_length = FADE_LENGTH * lpp

    def covers(self, x: float) -> bool:
        return self.x_a <= x < self.x_r

    def lines(self, x: float) -> np.ndarray:
        """The faired topside lines' half-breadths (m) at x, RUN_LEVELS of them (eta 0 .. 1)."""
        h = self.x_r - x
        return self.a - self.b * h + self.c * h * h

    def fade(self, x: float) -> float:
        """The share of the shift kept at x: 1 aft of the last FADE_LENGTH Lpp of the run, 0 at
        x_r, a quintic smoothstep between (the section changes C2 along x at x_r)."""
        s = min(max((self.x_r - x) / self.fade_length, 0.0), 1.0)
        return s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)

    def corrected(self, curve, spec):
        """The section `curve` (3-D, deck -> keel, designed from `spec`) with its topside moved onto
        the faired lines: each control point's half-breadth shifted by w (q - y_t) (y_t read on
        the same RUN_LEVELS lines, so the shift is nothing at x_r) at its Greville abscissa
        (Schoenberg's variation-diminishing approximation of the shift: local, no ringing), w
        rising from 0 where the control point's support reaches down to max(T, keel point), so
        the section below T (the design waterline too) stays exactly as designed, and the deck
        edge, where q is the deck line, stays exact."""
        T, zd, zk = self.draft, spec.z_deck, spec.z_keel
        z_lo = max(T, zk)
        if zd - z_lo <= 1e-9 * max(zd, 1.0):
            return curve
        knots, p, n, t = self._params
        pts = np.asarray(curve.evaluate(t))
        P, z_low = pts[:n], pts[n:2 * n, 2]  # z_low: the lowest point of each control point's support
        shift = self.lines(spec.x) - topside_offsets(pts[2 * n:], zd, T, zk)
        shift[np.isnan(shift)] = 0.0
        shift *= self.fade(spec.x)
        shift -= self.levels * shift[-1]  # the deck edge stays on the deck line
        eta = clip((P[:, 2] - T) / (zd - T), 0.0, 1.0)
        s = clip((z_low - z_lo) / (BLEND_DEPTH * (zd - T)), 0.0, 1.0)
        w = s * s * (3 - 2 * s)
        w[[0, -1]] = 0.0
        ctrl = np.array(curve.control_points, dtype=float)
        ctrl[:, 1] = clip(ctrl[:, 1] + w * np.interp(eta, self.levels, shift), 0.0, spec.y_max)
        return _native.NurbsCurve(p, knots, ctrl)
