"""Fairness over the design space, judged on the cut curves: the first 100 Latin-hypercube
particulars of bench_hull.py (Cb 0.50-0.87, LCB -4..+4 % Lpp, L/B 4-9, B/T 2-4.5, D = 1.6 T),
each designed hull's waterlines (6, from T/4 to D - T/8), buttocks (5, 0.1-0.9 B/2) and frames
(19, 5-95 % Lpp) judged on their own (fairlines.fairness: curvature sign changes over 0.1 deg
of turn). The issue's marks: a waterline or buttock with more than two (one hollow each way),
a frame with any (an S). A waterline that closes on the centre plane in a rounded end counts
that round too, so its low waterlines read stricter than a naval architect's eye.
Prints figures; run by bench/run_all.py (FAIRLINES_FAIRNESS_SAMPLES overrides the count).
"""

import os
import pathlib
import sys

import numpy as np

import fairlines as fl
from fairlines.fairness import judge_cut

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench_hull import sample  # noqa: E402  the same design space and sampler

SAMPLES = int(os.environ.get("FAIRLINES_FAIRNESS_SAMPLES", "100"))
CUT_POINTS = 401


def sign_changes(surface, axis: int, value: float) -> int:
    cut = fl.plane_cut(surface, axis, float(value), CUT_POINTS)
    return judge_cut(cut)["sign_changes"] if len(cut.points) >= 3 else 0


def judged(p: dict) -> tuple[list, list, list]:
    s = fl.design_hull(**p).bare_hull_surface()
    T, D, B, L = p["draft"], p["depth"], p["breadth"], p["lpp"]
    return ([sign_changes(s, 2, z) for z in np.linspace(0.25 * T, D - 0.125 * T, 6)],
            [sign_changes(s, 1, y) for y in np.linspace(0.1, 0.9, 5) * B / 2],
            [sign_changes(s, 0, x) for x in np.linspace(0.05, 0.95, 19) * L])


def main():
    hulls = [judged(p) for p in sample(SAMPLES)]
    n = len(hulls)
    wavy = sum(any(v > 2 for v in wl) for wl, _, _ in hulls)
    stepped = sum(any(v > 2 for v in bt) for _, bt, _ in hulls)
    s_frames = sum(any(v > 0 for v in fr) for _, _, fr in hulls)
    clean = sum(all(v <= 2 for v in wl + bt) and not any(fr) for wl, bt, fr in hulls)
    print(f"{n} designed hulls, each cut and judged on its own (sign changes over 0.1 deg of turn):")
    print(f"  a waterline with more than 2: {wavy} hulls ({100 * wavy / n:.0f} %); per waterline, mean "
          f"{np.mean([v for wl, _, _ in hulls for v in wl]):.2f}")
    print(f"  a buttock with more than 2:   {stepped} hulls ({100 * stepped / n:.0f} %); per buttock, mean "
          f"{np.mean([v for _, bt, _ in hulls for v in bt]):.2f}")
    print(f"  an S-shaped frame (anywhere): {s_frames} hulls ({100 * s_frames / n:.0f} %); S frames per hull, mean "
          f"{np.mean([sum(v > 0 for v in fr) for _, _, fr in hulls]):.2f} of 19")
    print(f"  none of these (the issue's marks): {clean} hulls ({100 * clean / n:.0f} %)")
    wl, bt, fr = (np.array([h[k] for h in hulls]) for k in range(3))
    print("  mean sign changes by waterline, T/4 .. D - T/8:", " ".join(f"{v:.1f}" for v in wl.mean(axis=0)))
    print("  mean sign changes by buttock, 0.1 .. 0.9 B/2:   ", " ".join(f"{v:.1f}" for v in bt.mean(axis=0)))
    print("  share of hulls with an S frame, 5 .. 95 % Lpp:  ", " ".join(f"{v:.2f}" for v in (fr > 0).mean(axis=0)))


if __name__ == "__main__":
    main()
