"""The designer's breadth with its options: fl.design_hull over Latin-hypercube particulars of
the issue's space (Cb 0.50-0.87, LCB -4..+4 % Lpp from midships, L/B 4-9, B/T 2-4.5) with a
depth of 1.3-2.2 T, each with options drawn at random (seeded): a cruiser stern (30 %), a bulb
(30 %), a skeg and single screw (25 %), a sonar dome (15 %), no parallel body (20 %), a stem
rake of 5-35 deg (20 %), a transom (not a cruiser stern) raked 5-25 deg (20 %, drawn apart so the
other draws are those of the bench before it). Prints how many build and meet volume, LCB and Cwp on the surface
(MATCH_REFUSE), how many are refused, grouped by what the refusal says to change, and whether
every refusal names a particular to change. bench_hull.py measures the plain space (depth
1.6 T, no options). Run by bench/run_all.py (FAIRLINES_OPTION_SAMPLES overrides the count).
"""

import os
import pathlib
import statistics
import sys
import time

import numpy as np

import fairlines as fl
from fairlines.designer import MATCH_REFUSE

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench_hull import SPACE  # noqa: E402  the same ranges

SAMPLES = int(os.environ.get("FAIRLINES_OPTION_SAMPLES", "500"))
DEPTH = (1.3, 2.2)  # D / T
#: What a refusal says to change, by a phrase of its message (the first that matches).
REMEDIES = {"bulb and dome": "sonar dome under the forefoot runs into the bulb",
            "blend onto the dome": "runs onto the sonar dome",
            "propeller over a short run": "too short to lift the hull over the propeller",
            "ends and LCB": "ends cannot hold this volume"}


#: (particular, share of the designs, value) of each option drawn; and the share with a stem rake of STEM_RAKES deg.
OPTIONS = (("stern", 0.3, "cruiser"), ("bulb", 0.3, True), ("skeg", 0.25, True), ("sonar_dome", 0.15, True),
           ("parallel_length", 0.2, 0.0))
STEM_RAKE_SHARE, STEM_RAKES = 0.2, (5.0, 35.0)
TRANSOM_RAKE_SHARE, TRANSOM_RAKES = 0.2, (5.0, 25.0)


def designs(n: int, seed: int = 11, lpp: float | None = None):
    """n particulars with options (Latin hypercube and option draws seeded by `seed`); Lpp
    60-300 m, or `lpp` for every design (tests/python/test_designer.py draws 150 m ships)."""
    from scipy.stats import qmc

    rng = np.random.default_rng(seed)
    rake_rng = np.random.default_rng(seed + 1000)  # its own stream: the other draws stay as they were
    for r in qmc.LatinHypercube(d=5, seed=seed).random(n):
        cb, lcb, lb, bt, dt = (lo + x * (hi - lo) for x, (lo, hi) in zip(r, [*SPACE.values(), DEPTH]))
        length = lpp if lpp is not None else 60.0 + 240.0 * ((r.sum() * 7.31) % 1.0)
        b = length / lb
        t = b / bt
        p = dict(lpp=length, breadth=b, draft=t, depth=dt * t, cb=cb, lcb=length / 2 + lcb / 100 * length)
        for key, share, value in OPTIONS:
            if rng.random() < share:
                p[key] = value
        if rng.random() < STEM_RAKE_SHARE:
            p["stem_rake"] = float(rng.uniform(*STEM_RAKES))
        draw, rake = rake_rng.random(), float(rake_rng.uniform(*TRANSOM_RAKES))
        if draw < TRANSOM_RAKE_SHARE and p.get("stern", "transom") == "transom":
            p["transom_rake"] = rake
        yield p


def main():
    built, missed, refused, times = 0, [], {}, []
    unnamed, raked = [], [0, 0]  # raked transoms: drawn, built
    for p in designs(SAMPLES):
        raked[0] += "transom_rake" in p
        t = time.perf_counter()
        try:
            hull = fl.design_hull(**p)
        except fl.InfeasibleFormParameters as e:
            msg = str(e)
            kind = next((k for k, phrase in REMEDIES.items() if phrase in msg), "other")
            refused[kind] = refused.get(kind, 0) + 1
            if not any(w in msg for w in ("give ", "move ", "lower ", "raise ", "change ")):
                unnamed.append(msg[:160])
            continue
        times.append(time.perf_counter() - t)
        h = hull.ship_hydrostatics()  # with a bulb the composed ship's
        lpp, asked = p["lpp"], p["cb"] * p["lpp"] * p["breadth"] * p["draft"]
        off = max(abs(h["volume"] / asked - 1), abs(h["lcb"] - p["lcb"]) / lpp)
        built += 1
        raked[1] += "transom_rake" in p
        if not off <= MATCH_REFUSE:
            missed.append((p, off))
    n = SAMPLES
    print(f"{n} designs with options (depth {DEPTH[0]}-{DEPTH[1]} T): {built} built ({100 * built / n:.1f} %), "
          f"median {1e3 * statistics.median(times):.0f} ms; {len(missed)} of them off volume or LCB by more than "
          f"{MATCH_REFUSE:g}")
    print(f"  with a raked transom ({TRANSOM_RAKES[0]:g}-{TRANSOM_RAKES[1]:g} deg): {raked[1]} of {raked[0]} built")
    said = ", ".join(f"{v} {k}" for k, v in sorted(refused.items(), key=lambda kv: -kv[1]))
    print(f"  refused {sum(refused.values())}: {said or 'none'}; "
          f"{'every refusal names what to change' if not unnamed else f'{len(unnamed)} name nothing to change'}")
    for m in unnamed[:5]:
        print("   ", m)


if __name__ == "__main__":
    main()
