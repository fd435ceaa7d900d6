"""Shared benchmark helpers: medians of repeated timings on a noisy shared machine."""

import os
import statistics
import time

# Per-core figures: keep numpy's BLAS to one thread in every benchmark process.
for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(var, "1")


def median_time(fn, repeat=7, min_time=0.05):
    """Median wall time of fn() in seconds; each sample loops until min_time has passed."""
    samples = []
    for _ in range(repeat):
        n = 0
        t0 = time.perf_counter()
        while True:
            fn()
            n += 1
            dt = time.perf_counter() - t0
            if dt >= min_time:
                break
        samples.append(dt / n)
    return statistics.median(samples)


def report(name, value, unit, extra=""):
    print(f"  {name:<58s} {value:>14,.3f} {unit:<10s} {extra}")
