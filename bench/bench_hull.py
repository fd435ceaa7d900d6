"""Hull designer speed and breadth: particulars -> whole hull (fl.design_hull, matched to the
volume, LCB and Cwp), description -> surface (the container ship of examples/container_ship.json),
one form-parameter change and rebuild (a Blender slider), particulars -> composed hull, and the
success rate over Latin-hypercube samples of the design space. Prints figures; run by
bench/run_all.py (FAIRLINES_BENCH_SAMPLES overrides the sample count, default 1000).

Goals: particulars -> composed whole hull <= 50 ms, description -> surface <= 20 ms, success 100 %.
"""

import json
import os
import pathlib
import re
import statistics
import time

import numpy as np

import fairlines as fl

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "container_ship.json"
CONTAINER = dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True)
SPACE = dict(cb=(0.50, 0.87), lcb_pct=(-4.0, 4.0), l_over_b=(4.0, 9.0), b_over_t=(2.0, 4.5))
SAMPLES = int(os.environ.get("FAIRLINES_BENCH_SAMPLES", "1000"))
FLAT_BOTTOM = 0.3  # the flat of bottom of the fourth pass, fraction of the waterline half-breadth


def timed(fn, repeat=9):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times) * 1e3, statistics.median(times) * 1e3


def sample(n, seed=7):
    from scipy.stats import qmc

    for r in qmc.LatinHypercube(d=4, seed=seed).random(n):
        cb, lcb, lb, bt = (lo + x * (hi - lo) for x, (lo, hi) in zip(r, SPACE.values()))
        lpp = 60.0 + 240.0 * ((r.sum() * 7.31) % 1.0)
        b = lpp / lb
        t = b / bt
        yield dict(lpp=lpp, breadth=b, draft=t, depth=1.6 * t, cb=cb, lcb=lpp / 2 + lcb / 100 * lpp)


def main():
    desc = json.loads(EXAMPLE.read_text())
    best, med = timed(lambda: fl.Hull.from_json(desc).bare_hull_surface())
    h = fl.Hull.from_json(desc)
    print(f"description -> surface (container ship, {len(h.stations())} stations): best {best:.1f} ms, median {med:.1f} ms "
          "(goal <= 20 ms)")
    vols = iter(np.linspace(0.99, 1.01, 100) * desc["basic_curves"]["sac"]["volume"])

    def slider():
        h.set("sac", "volume", float(next(vols)))
        h.bare_hull_surface()

    best, med = timed(slider)
    print(f"one form-parameter change (sac.volume) and rebuild: best {best:.1f} ms, median {med:.1f} ms")
    no_bulb = {**CONTAINER, "bulb": False}
    best, med = timed(lambda: fl.design_hull(**no_bulb))
    print(f"particulars -> matched whole hull (design_hull): best {best:.1f} ms, median {med:.1f} ms")
    best, med = timed(lambda: fl.design_hull(**CONTAINER).composed_hull())
    print(f"particulars -> composed whole hull with bulb and blend: best {best:.1f} ms, median {med:.1f} ms "
          f"(goal <= 50 ms)")
    ok, times, fails, plain = space_pass(sample(SAMPLES))
    print(f"design space (Cb 0.50-0.87, LCB -4..+4 % Lpp, L/B 4-9, B/T 2-4.5), {SAMPLES} Latin-hypercube samples: "
          f"{ok} built and matched ({100 * ok / SAMPLES:.1f} %, goal 100 %), median {1e3 * statistics.median(times):.0f} ms; "
          f"failures by curve: {fails}; drawn without the designer's default flat of bottom: {plain}")
    n = max(SAMPLES // 5, 1)
    ok, times, fails, plain = space_pass(sample_given_parallel(n))
    print(f"the same space with a given parallel body of 2-30 % Lpp and a bulb on every other ship, {n} samples: "
          f"{ok} built and matched ({100 * ok / n:.1f} %), median {1e3 * statistics.median(times):.0f} ms; "
          f"failures by curve: {fails}; drawn without the designer's default flat of bottom: {plain}")
    ok, times, fails, _ = space_pass({**p, "flat_bottom": FLAT_BOTTOM} for p in sample(n, seed=13))
    print(f"the space with a flat of bottom of {FLAT_BOTTOM:g} of B/2 over the parallel body (flat_bottom), {n} samples: "
          f"{ok} built and matched ({100 * ok / n:.1f} %), median {1e3 * statistics.median(times):.0f} ms; "
          f"failures by curve: {fails}")
    ok, times, fails, worst = compose_pass(sample(n, seed=11))
    print(f"the space with a bulb, {n} samples, particulars -> composed hull (bare hull + bulb + blend): "
          f"{ok} composed ({100 * ok / n:.1f} %), median {1e3 * statistics.median(times):.0f} ms; failures: {fails}; "
          f"the composed ships' volume and LCB within {worst[0]:.1e} and {worst[1]:.1e} Lpp of the asked (largest)")


def compose_pass(particulars):
    """(composed with bulb and blend, times of those, failures by the first words of the error,
    the composed ships' largest relative volume and LCB (on Lpp) errors against the asked)."""
    ok, times, fails, worst = 0, [], {}, [0.0, 0.0]
    for p in particulars:
        t = time.perf_counter()
        try:
            hull = fl.design_hull(**p, bulb=True)
            hull.composed_hull()
            ok += 1
            times.append(time.perf_counter() - t)
        except (fl.InfeasibleFormParameters, fl.InvalidInput) as e:
            key = str(e).split(":")[0][:60]
            fails[key] = fails.get(key, 0) + 1
            continue
        h = hull.ship_hydrostatics()  # the composition made above, measured (not timed)
        worst[0] = max(worst[0], abs(h["volume"] / (p["cb"] * p["lpp"] * p["breadth"] * p["draft"]) - 1))
        worst[1] = max(worst[1], abs(h["lcb"] - p["lcb"]) / p["lpp"])
    return ok, times, fails, worst


def sample_given_parallel(n, seed=5):
    from scipy.stats import qmc

    for i, r in enumerate(qmc.LatinHypercube(d=5, seed=seed).random(n)):
        cb, lcb, lb, bt, par = (lo + x * (hi - lo) for x, (lo, hi) in zip(r, (*SPACE.values(), (0.02, 0.3))))
        b = 150.0 / lb
        yield dict(lpp=150.0, breadth=b, draft=b / bt, depth=1.6 * b / bt, cb=cb, lcb=75.0 + lcb / 100 * 150.0,
                   parallel_length=par * 150.0, bulb=bool(i % 2))


def space_pass(particulars):
    """(built and matched, times of those, failures by the curve named, hulls drawn without the
    designer's default flat of bottom) over the particulars."""
    ok, times, fails, plain = 0, [], {}, 0
    for p in particulars:
        t = time.perf_counter()
        try:
            hull = fl.design_hull(**p)
            times.append(time.perf_counter() - t)
            v = hull.ship_hydrostatics()["volume"]  # with a bulb the composed ship's
            ok += abs(v / (p["cb"] * p["lpp"] * p["breadth"] * p["draft"]) - 1) <= 1e-4
            plain += "flat_bottom" not in p and "flat_bottom" not in hull.description.curves
        except (fl.InfeasibleFormParameters, fl.InvalidInput) as e:
            cause = re.search(r"\((basic_curves\.\w+|section at x = -?)", str(e))  # design_hull: ... (the solver's message)
            key = cause.group(1) if cause else str(e).split(":")[0]
            key = "design_hull: a bulb no size meets in one seam" if "bulb cannot meet the hull" in str(e) else key
            key = "sections" + (" (transom, x < 0)" if " -" in key else "") if key.startswith("section at") else key
            fails[key] = fails.get(key, 0) + 1
    return ok, times, fails, plain


if __name__ == "__main__":
    main()
