"""Bare-hull speed (issue 4 goals): description -> surface for the Panamax forebody (33
sections), one form-parameter change and rebuild (what a Blender slider does), fair skinning
alone, and hydrostatics. Prints figures; run by bench/run_all.py.

Goal: the whole bare hull (>= 30 sections) from description to surface in <= 20 ms.
"""

import json
import pathlib
import statistics
import time

import numpy as np

import fairlines as fl

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "panamax_forebody.json"
GOAL_MS = 20.0


def best_of(fn, repeat=15):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times) * 1e3, statistics.median(times) * 1e3


def main():
    desc = json.loads(EXAMPLE.read_text())

    def full_build():
        h = fl.Hull.from_json(desc)
        h.bare_hull_surface()
        return h

    h = full_build()
    n_sections = len(h.sections)
    best, med = best_of(full_build)
    print(f"bare hull, description -> surface ({n_sections} sections): best {best:.2f} ms, median {med:.2f} ms "
          f"(goal <= {GOAL_MS:.0f} ms: {'met' if best <= GOAL_MS else 'NOT met'})")

    vols = iter(np.linspace(26000.0, 27000.0, 1000))

    def slider():
        h.set("sac", "volume", float(next(vols)))
        h.bare_hull_surface()

    best, med = best_of(slider)
    print(f"one form-parameter change (sac.volume) and rebuild: best {best:.2f} ms, median {med:.2f} ms")

    secs = h.sections
    n = h.description.section_n_control
    groups = fl.section_straight_groups(n)
    skin = h.skin()
    net = skin.surface.control_points.shape
    best, med = best_of(lambda: fl.fair_skin(secs, start="parallel", e2=0.0, e3=1.0, straight_groups=groups))
    print(f"fair_skin alone ({n_sections} sections on one knot vector, held runs, {net[0]} x {net[1]} control net): "
          f"best {best:.2f} ms, median {med:.2f} ms")
    best, med = best_of(lambda: fl.fair_skin(secs, n_control=32, start="parallel"))
    print(f"fair_skin with seed 000's refit to 32 common knots (for comparison): best {best:.2f} ms, median {med:.2f} ms")

    fields = h.section_parameters()
    best, med = best_of(lambda: fl._native._design_sections(fields, n, 3, desc["principal"]["B"] / 2))
    print(f"{n_sections} sections from basic curves (one C++ call): best {best:.3f} ms, median {med:.3f} ms")

    t = time.perf_counter()
    rep = h.fairness_report()
    t_rep = (time.perf_counter() - t) * 1e3
    counts = {k: (sum(c["sign_changes"] for c in v), sum(c["false_inflections"] for c in v)) for k, v in rep.items()}
    print(f"fairness report (8 waterlines, 6 buttocks, 12 frames judged against the designed family): {t_rep:.0f} ms; "
          + ", ".join(f"{k}s {n_all} sign changes, {n_false} false" for k, (n_all, n_false) in counts.items()))

    surf = h.bare_hull_surface()
    best, med = best_of(lambda: fl.hydrostatics(surf, desc["principal"]["T"]), repeat=5)
    print(f"hydrostatics at T (quadrature on the surface, SAC at 41 stations): best {best:.1f} ms, median {med:.1f} ms")


if __name__ == "__main__":
    main()
