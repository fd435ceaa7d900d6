"""Fine, flared sections forward of a dry transom (a narrow waterline under a wide deck), judged
on the frames cut from the hull and on one section: no S where the basic curves leave room for a
section that turns one way. The bilge corner's least breadth follows the asked area
(sections.cpp least_corner_breadth); held at 0.75 of the waterline's half-breadth, it kept the
side from leaning as the flare asks, and these frames turned convex by a little just above T
under their hollow flare."""

import numpy as np
import pytest

import fairlines as fl
from fairlines.fairness import judge_cut

#: Ships of bench_hull's design space (its sample's hulls 22 and 68, rounded) and the frame
#: (fraction of Lpp) that had an inflection above T before: a convex lobe of 0.92 / 0.31 deg
#: below a hollow flare, at 1.05 / 1.09 T. (Where the basic curves leave no room for a
#: convex section, a deck much wider than the waterline over an area well above the V's, the
#: inflection stays at the waterline: the same ships' frames at 5 % Lpp, convex by 7-10 deg below
#: T and hollow by as much above it, moved from 1.002 T to 0.996-1.000 T.)
#: The 259 m ship (hull 19 of that sample drawn 300 long) flared hollow above T at 20 % Lpp (1.4
#: deg from T to the deck, fullness 0.72) when the bilge arc's fine weight fell to 0.5 with the
#: corner's least breadth asking the conic for 0.45 of the polygon's excess (kCornerConicShare;
#: 0.6 now): its corner stayed out at 0.75 b, inboard of the flare's.
SHIPS = {
    "fine 193 m": (dict(lpp=193.277, breadth=33.334, draft=10.326, depth=16.522, cb=0.624, lcb=99.23), 0.10),
    "slender 125 m": (dict(lpp=124.511, breadth=14.343, draft=3.513, depth=5.621, cb=0.62, lcb=62.665), 0.10),
    "fine 259 m": (dict(lpp=258.829, breadth=39.981, draft=14.769, depth=23.63, cb=0.5605, lcb=133.079), 0.20),
}


@pytest.mark.parametrize("name", list(SHIPS))
def test_aft_frame_under_a_wide_deck_turns_one_way(name):
    p, fraction = SHIPS[name]
    surface = fl.design_hull(**p).bare_hull_surface()
    cut = fl.plane_cut(surface, 0, fraction * p["lpp"], 401)
    heights = [round(i["at"][2] / p["draft"], 3) for i in judge_cut(cut)["inflections"]]
    assert heights == []  # the inflections' heights, fractions of T


def _fine_flared_spec(fullness: float) -> fl.SectionSpec:
    """A section whose convex shape needs its side to lean at Q: waterline half-breadth 3 m at
    T = 10 m over a keel at 5 m, deck 5 m at 16 m (the line Q -> deck leans 0.33, the chord
    keel -> Q 0.6)."""
    s = fl.SectionSpec()
    s.x, s.y_max, s.y_deck, s.z_deck, s.z_keel, s.draft, s.y_dwl = 10.0, 10.0, 5.0, 16.0, 5.0, 10.0, 3.0
    s.half_area = fullness * 3.0 * 5.0
    return s


def _turns(curve, n: int = 2001) -> np.ndarray:
    """Signed turn (cross product of successive chords) along a section, deck -> keel, and the
    heights where it is read."""
    kn = np.asarray(curve.knots)
    p = np.asarray(curve.evaluate(np.linspace(kn[0], kn[-1], n)))[:, 1:]
    a, b = np.diff(p, axis=0)[:-1], np.diff(p, axis=0)[1:]
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], p[1:-1, 1]


def test_fine_flared_section_turns_one_way_and_meets_its_area():
    """The section alone: convex from the deck to the keel (every turn one sign, beyond round-off
    of 1e-9 of the largest), with the asked area below T (trapezoids on 20 001 points)."""
    spec = _fine_flared_spec(0.62)
    design = fl.design_section(spec)
    turn, z = _turns(design.curve)
    big = np.abs(turn).max()
    signs = np.sign(turn[np.abs(turn) > 1e-9 * big])
    assert signs.min() == signs.max(), z[np.abs(turn) > 1e-9 * big][np.flatnonzero(signs != signs[0])[:3]]
    assert design.area_met
    kn = np.asarray(design.curve.knots)
    y, z = np.asarray(design.curve.evaluate(np.linspace(kn[0], kn[-1], 20001)))[:, 1:].T
    below = z <= spec.draft  # the section runs down monotonically: one crossing of T
    zq = np.concatenate([[spec.draft], z[below]])
    yq = np.concatenate([[np.interp(spec.draft, z[::-1], y[::-1])], y[below]])
    area = -np.sum(0.5 * (yq[1:] + yq[:-1]) * np.diff(zq))  # int y dz, trapezoids
    assert area == pytest.approx(spec.half_area, rel=1e-5)
