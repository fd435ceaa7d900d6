"""Fairness over the design space, judged on the cut curves: the first 100 Latin-hypercube
particulars of bench_hull.py (Cb 0.50-0.87, LCB -4..+4 % Lpp, L/B 4-9, B/T 2-4.5, D = 1.6 T),
each designed hull's waterlines (6, from T/4 to D - T/8), buttocks (5, 0.1-0.9 B/2) and frames
(19, 5-95 % Lpp) judged on their own (fairlines.fairness: curvature sign changes over 0.1 deg
of turn). The issue's marks: a waterline or buttock with more than two (one hollow each way),
a frame with any (an S); the frames aft of 5 % Lpp are read apart, for an S above T
(AFT_FRAMES). A waterline that closes on the centre plane in a rounded end counts
that round too, so its low waterlines read stricter than a naval architect's eye; so the
waterlines are also read as one would: a lobe under SMALL_LOBE_DEG of turn between two others
is a wobble (at a waterline's end it is how the line meets the stem or the transom, one turn), a
second hollow in one half of the waterline a step, and where the wobbles lie (within
FORE_TIP of Lpp of a waterline's fore end, within AFT_END of its aft end, or between).
The lowest waterlines (LOWEST, under T/4) are measured apart: the largest hollow in their aft
half, where one ending on the keel's rise and then only widening as the bilge fills reads as
shoulder, hollow, shoulder; and the keel's crease, the angle at which the frames meet the
centre plane where the keel lies on the base (a smooth hull meets it level). The hulls are
designed as the designer does by default (its flat of bottom), then again without a flat of
bottom and with one of FLAT_BOTTOM of the waterline's half-breadth over the parallel body.
Prints figures; run by bench/run_all.py (FAIRLINES_FAIRNESS_SAMPLES overrides the count).
"""

import os
import pathlib
import sys

import numpy as np

import fairlines as fl
from fairlines.fairness import SMALL_LOBE_DEG, cut_lobes, judge_cut, read_waterline

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench_hull import sample  # noqa: E402  the same design space and sampler

SAMPLES = int(os.environ.get("FAIRLINES_FAIRNESS_SAMPLES", "100"))
CUT_POINTS = 401
FORE_TIP, AFT_END = 0.015, 0.05  # the ends' stretches where wobbles are placed, fractions of Lpp
WATERLINES = 6  # T/4 .. D - T/8: the first three up to 0.74 T, the rest from 0.985 T (just under T)
# A frame's inflection this close under T (fraction of T) is the waterline's own: convex below,
# hollow above (a wine-glass section), counted apart from those above T so a shift of a few
# millimetres across T is seen for what it is.
WATERLINE_BAND = 0.99
#: ... and just below it, where an aft section's convex bilge turns into a hollow topside (fractions of T)
TOPSIDE_BAND = 0.75
#: The lowest waterlines, fractions of T, and the flat of bottom of the third reading.
LOWEST = (0.06, 0.12)
FLAT_BOTTOM = 0.3
#: A frame meets the centre plane at the keel at the angle of its chord to the point this share
#: of B/2 out (deg from the horizontal; 0: no crease), read where the keel lies on the base
#: (within KEEL_ON_BASE T), aft (0.15 .. 0.5 Lpp) and forward (0.55 .. 0.85 Lpp) apart.
KEEL_CHORD, KEEL_ON_BASE = 0.004, 1e-4
KEEL_FRAMES = (np.linspace(0.15, 0.5, 8), np.linspace(0.55, 0.85, 7))
#: The frames aft of the 19 (from AFT_FRAME_START of Lpp forward of the aft end to 5 % Lpp,
#: AFT_FRAMES of them), read apart: over a dry transom whose deck is wider than its sections lean
#: the topside turns hollow above T. An S there is measured by the smaller of the two lobes at an
#: inflection above T (deg; the largest over the frames), and counted also over AFT_FRAME_LOBE deg.
AFT_FRAMES, AFT_FRAME_START, AFT_FRAME_LOBE = 8, 0.002, 1.0


def sign_changes(surface, axis: int, value: float) -> int:
    cut = fl.plane_cut(surface, axis, float(value), CUT_POINTS)
    return judge_cut(cut)["sign_changes"] if len(cut.points) >= 3 else 0


def waterline_reading(surface, z: float, lpp: float) -> tuple[int, dict, bool]:
    """Sign changes, wobbles by where they lie ({"fore tip", "aft end", "between"}: count), and
    whether one half of the waterline has a second hollow (fairlines.fairness.read_waterline)."""
    cut = fl.plane_cut(surface, 2, float(z), CUT_POINTS)
    if len(cut.points) < 3:
        return 0, {}, False
    read = read_waterline(cut)
    x = np.asarray(cut.points)[:, 0]
    x_aft, x_fore = x.min(), x.max()
    wobbles: dict = {}
    for lobe in read["wobbles"]:
        at = lobe["at"][0]
        where = "fore tip" if x_fore - at < FORE_TIP * lpp else "aft end" if at - x_aft < AFT_END * lpp else "between"
        wobbles[where] = wobbles.get(where, 0) + 1
    return read["judged"]["sign_changes"], wobbles, read["step"]


def frame_inflection_heights(surface, x: float) -> list:
    """Heights z (m) of a frame's inflections (sign changes over 0.1 deg of turn)."""
    cut = fl.plane_cut(surface, 0, float(x), CUT_POINTS)
    return [i["at"][2] for i in judge_cut(cut)["inflections"]] if len(cut.points) >= 3 else []


def forced_by_basic_curves(hull, x: float, draft: float, depth: float) -> bool:
    """Whether no section turning one way can join the keel point (0, z_k) (the centre profile),
    the waterline point (b, T) and the deck point (y_d, D) of the basic curves at x with the asked
    fullness f = SAC / (2 b d), d = T - z_k. One way up from the keel, the side's dy/dz only falls, so it is
    at least s = (y_d - b) / (D - T) (the straight topside) everywhere below T: y(z) <= b - s (T - z).
    That needs b >= s d and bounds the area: f <= 1 - s d / (2 b) (a flat bottom, then the line of
    slope s). Within both, a one-way section exists (a blend of that and the V). A dry section
    (d <= 0) has no area to hold: never forced."""
    curves = hull.basic_curves
    b = float(curves["dwl"](x, outside=0.0)[0])
    y_d = float(curves["deck"](x, outside=np.nan)[0])
    z_k = float(curves["profile"](x, outside=np.nan)[0])  # the centre profile: the keel's height
    d = draft - z_k
    if not d > 0 or b <= 0 or np.isnan(y_d):
        return False
    s = (y_d - b) / (depth - draft)
    f = float(curves["sac"](x, outside=0.0)[0]) / (2 * b * d)
    return b < s * d or f > 1 - s * d / (2 * b)


def largest_aft_hollow(surface, z: float, lpp: float) -> float:
    """The largest hollow lobe (deg of turn) in the aft half of the waterline at z (0: none)."""
    cut = fl.plane_cut(surface, 2, float(z), CUT_POINTS)
    if len(cut.points) < 3:
        return 0.0
    points, curvature = np.asarray(cut.points), np.asarray(cut.curvature)
    aft = points[:, 0] < 0.5 * lpp
    return max([lobe["turn_deg"] for lobe in cut_lobes(points[aft], curvature[aft]) if lobe["sign"] > 0], default=0.0)


def keel_crease(surface, x: float, half_breadth: float, draft: float) -> float:
    """The angle (deg) at which the frame at x meets the centre plane at the keel; 0 when its
    keel is off the base (the rising keel, where a V is the deadwood's)."""
    points = np.asarray(fl.plane_cut(surface, 0, float(x), CUT_POINTS * 4).points)
    if len(points) < 3:
        return 0.0
    points = points[np.argsort(points[:, 1])]
    keel = points[0]
    if keel[2] > KEEL_ON_BASE * draft:
        return 0.0
    out = points[np.argmax(points[:, 1] > keel[1] + KEEL_CHORD * half_breadth)]
    return float(np.degrees(np.arctan2(out[2] - keel[2], out[1] - keel[1])))


def aft_frame_s(surface, x_aft: float, lpp: float, draft: float) -> float:
    """The largest S above T in the frames aft of 5 % Lpp (AFT_FRAMES): the smaller of the two
    lobes (deg) at an inflection above T, 0 with none."""
    worst = 0.0
    for x in np.linspace(x_aft + AFT_FRAME_START * lpp, 0.05 * lpp, AFT_FRAMES):
        cut = fl.plane_cut(surface, 0, float(x), CUT_POINTS)
        if len(cut.points) >= 3:
            worst = max([worst] + [min(i["turns_deg"]) for i in judge_cut(cut)["inflections"] if i["at"][2] > draft])
    return worst


def judged(p: dict) -> tuple[list, list, list, list, list, list, list, list, list, list, float]:
    hull = fl.design_hull(**p)
    s = hull.bare_hull_surface()
    T, D, B, L = p["draft"], p["depth"], p["breadth"], p["lpp"]
    waterlines = [waterline_reading(s, z, L) for z in np.linspace(0.25 * T, D - 0.125 * T, WATERLINES)]
    xs = np.linspace(0.05, 0.95, 19) * L
    frames = [frame_inflection_heights(s, x) for x in xs]
    at_or_above = [any(z > WATERLINE_BAND * T for z in f) for f in frames]
    just_below = [any(TOPSIDE_BAND * T <= z <= WATERLINE_BAND * T for z in f) for f in frames]
    return ([w[0] for w in waterlines],
            [sign_changes(s, 1, y) for y in np.linspace(0.1, 0.9, 5) * B / 2],
            [len(f) for f in frames],
            [w[1:] for w in waterlines],
            [sum(z > T for z in f) for f in frames],
            [sum(WATERLINE_BAND * T < z <= T for z in f) for f in frames],
            [a and forced_by_basic_curves(hull, x, T, D) for a, x in zip(at_or_above, xs)],
            [(b, b and forced_by_basic_curves(hull, x, T, D)) for b, x in zip(just_below, xs)],
            [largest_aft_hollow(s, f * T, L) for f in LOWEST],
            [max(keel_crease(s, f * L, B / 2, T) for f in fs) for fs in KEEL_FRAMES],
            aft_frame_s(s, hull.description.x_aft, L, T))


def print_reading(hulls: list) -> None:
    """The waterlines read as a naval architect would, below T and above it."""
    print(f"  waterlines read as a lines plan (a wobble: a lobe under {SMALL_LOBE_DEG:g} deg between two others; a "
          "step: a second hollow in one half):")
    for name, rows in (("T/4 .. 0.74 T", slice(0, WATERLINES // 2)),
                       ("0.985 T .. D - T/8", slice(WATERLINES // 2, WATERLINES))):
        read = [r for h in hulls for r in h[3][rows]]
        clean = sum(not w and not step for w, step in read)
        wobbly = sum(bool(w) for w, _ in read)
        where = {k: sum(w.get(k, 0) for w, _ in read) for k in ("fore tip", "aft end", "between")}
        print(f"    {name}: {clean} of {len(read)} clean; {wobbly} with a wobble, {sum(s for _, s in read)} with a "
              f"step; wobbles within {100 * FORE_TIP:g} % Lpp of the fore end {where['fore tip']}, within "
              f"{100 * AFT_END:g} % of the aft end {where['aft end']}, between {where['between']}")


def main():
    hulls = [judged(p) for p in sample(SAMPLES)]
    n = len(hulls)
    wavy = sum(any(v > 2 for v in h[0]) for h in hulls)
    stepped = sum(any(v > 2 for v in h[1]) for h in hulls)
    s_frames = sum(any(v > 0 for v in h[2]) for h in hulls)
    s_above = sum(any(v > 0 for v in h[4]) for h in hulls)
    clean = sum(all(v <= 2 for v in h[0] + h[1]) and not any(h[2]) for h in hulls)
    print(f"{n} designed hulls, each cut and judged on its own (sign changes over 0.1 deg of turn):")
    print(f"  a waterline with more than 2: {wavy} hulls ({100 * wavy / n:.0f} %); per waterline, mean "
          f"{np.mean([v for h in hulls for v in h[0]]):.2f}")
    print(f"  a buttock with more than 2:   {stepped} hulls ({100 * stepped / n:.0f} %); per buttock, mean "
          f"{np.mean([v for h in hulls for v in h[1]]):.2f}")
    print(f"  an S-shaped frame (anywhere): {s_frames} hulls ({100 * s_frames / n:.0f} %); S frames per hull, mean "
          f"{np.mean([sum(v > 0 for v in h[2]) for h in hulls]):.2f} of 19")
    print(f"    ... with its inflection above T (the issue's mark: an S above the waterline): {s_above} hulls; "
          f"{sum(v for h in hulls for v in h[4])} of {sum(v for h in hulls for v in h[2])} frame inflections")
    at_t = sum(any(v > 0 for v in h[5]) for h in hulls)
    print(f"    ... with it at the waterline ({WATERLINE_BAND:g} T .. T: convex below, hollow above): {at_t} hulls; "
          f"{sum(v for h in hulls for v in h[5])} frame inflections")
    frames_up = sum(a + b > 0 for h in hulls for a, b in zip(h[4], h[5]))
    forced = sum(v for h in hulls for v in h[6])
    print(f"    ... of the {frames_up} frames with an inflection at or above {WATERLINE_BAND:g} T, {forced} forced by the "
          f"basic curves (no one-way section joins their keel, waterline and deck points with the asked area), "
          f"{frames_up - forced} not")
    below = [v for h in hulls for v in h[7]]
    print(f"    ... with it just below the waterline ({TOPSIDE_BAND:g} .. {WATERLINE_BAND:g} T: a convex bilge under a "
          f"hollow topside): {sum(any(b for b, _ in h[7]) for h in hulls)} hulls; {sum(b for b, _ in below)} frames, "
          f"{sum(f for _, f in below)} of them forced by the basic curves")
    print(f"  none of these (the issue's marks): {clean} hulls ({100 * clean / n:.0f} %)")
    aft = np.array([h[10] for h in hulls])
    clean_aft = sum(all(v <= 2 for v in h[0] + h[1]) and not any(h[2]) and not h[10] for h in hulls)
    print(f"  the {AFT_FRAMES} frames aft of 5 % Lpp (from {100 * AFT_FRAME_START:g} % Lpp forward of the aft end), an "
          f"S above T: {(aft > 0).sum()} hulls, {(aft > AFT_FRAME_LOBE).sum()} with both its lobes over "
          f"{AFT_FRAME_LOBE:g} deg (largest {aft.max():.1f} deg); none of the issue's marks with these frames too: "
          f"{clean_aft} hulls")
    wl, bt, fr = (np.array([h[k] for h in hulls]) for k in range(3))
    print("  mean sign changes by waterline, T/4 .. D - T/8:", " ".join(f"{v:.1f}" for v in wl.mean(axis=0)))
    print("  mean sign changes by buttock, 0.1 .. 0.9 B/2:   ", " ".join(f"{v:.1f}" for v in bt.mean(axis=0)))
    print("  share of hulls with an S frame, 5 .. 95 % Lpp:  ", " ".join(f"{v:.2f}" for v in (fr > 0).mean(axis=0)))
    print_reading(hulls)
    print_lowest(hulls)
    for flat, what in ((0.0, "without a flat of bottom (flat_bottom=0)"),
                       (FLAT_BOTTOM, f"with a flat of bottom of {FLAT_BOTTOM:g} of B/2 over the parallel body")):
        print_pass(f"the same {n} hulls {what}:", [judged({**p, "flat_bottom": flat}) for p in sample(SAMPLES)])


def print_pass(title: str, hulls: list) -> None:
    """The headline counts, the waterlines' reading and the bottom's figures of another pass."""
    print(title)
    print(f"  a waterline with more than 2: {sum(any(v > 2 for v in h[0]) for h in hulls)} hulls; a buttock with more "
          f"than 2: {sum(any(v > 2 for v in h[1]) for h in hulls)} hulls, per buttock, mean "
          f"{np.mean([v for h in hulls for v in h[1]]):.2f}; an S-shaped frame: "
          f"{sum(any(v > 0 for v in h[2]) for h in hulls)} hulls, above T {sum(any(v > 0 for v in h[4]) for h in hulls)}")
    print_reading(hulls)
    print_lowest(hulls)


def print_lowest(hulls: list) -> None:
    largest = np.array([h[8] for h in hulls])
    print(f"  the lowest waterlines ({', '.join(f'{f:g}' for f in LOWEST)} T), largest hollow in the aft half, mean: "
          + ", ".join(f"{v:.1f}" for v in largest.mean(axis=0)) + " deg; median: "
          + ", ".join(f"{v:.1f}" for v in np.median(largest, axis=0)) + " deg")
    crease = np.array([h[9] for h in hulls])
    print(f"  the keel's crease (the largest angle a frame meets the centre plane at, where the keel is on the base), "
          f"aft / forward of midships, median: " + " / ".join(f"{v:.1f}" for v in np.median(crease, axis=0))
          + " deg; mean: " + " / ".join(f"{v:.1f}" for v in crease.mean(axis=0)) + " deg; over 5 deg: "
          + " / ".join(f"{v}" for v in (crease > 5).sum(axis=0)) + " hulls")


if __name__ == "__main__":
    main()
