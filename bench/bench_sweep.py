"""Design-space sweep throughput: whole-ship variants per second per core, and the speed-up from
one to two Dask worker processes (goal >= 1.8x on a 2-core machine).

Each variant designs the container ship from particulars (fl.design_hull, with bulb), composes
it (bare hull + bulb + blend) and measures it fully (hydrostatics, fairness report, composed
displacement, Kracht measured back, mesh checks). The clusters are started and warmed before
the clock runs, so the figures are the sweep's, not Dask's start-up.
"""

import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import common  # noqa: F401  (one BLAS thread per process)
from common import report

VARIANTS = int(os.environ.get("SWEEP_BENCH_VARIANTS", "40"))
BASE = dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True)


def study(table: Path, samples: int, seed: int) -> dict:
    return {"name": "bench", "base": {"particulars": dict(BASE)},
            "sampling": {"method": "lhs", "samples": samples, "seed": seed},
            "parameters": [{"path": "cb", "low": 0.64, "high": 0.76}, {"path": "lcb", "low": 116.0, "high": 121.0}],
            "outputs": {"table": str(table)}}


def timed_sweep(table: Path, scheduler, seed: int) -> tuple[float, list]:
    """Seconds to run the study into a new table, and its rows."""
    from fairlines.sweep import sweep

    t0 = time.perf_counter()
    t = sweep(study(table, VARIANTS, seed), scheduler=scheduler)
    return time.perf_counter() - t0, t.to_pylist()


def on_cluster(folder: Path, workers: int, seed: int) -> tuple[float, list]:
    from distributed import Client, LocalCluster
    from fairlines.sweep import sweep

    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        sweep(study(folder / f"warm-{workers}.parquet", 2 * workers, 99), scheduler=client)  # imports, first build
        return timed_sweep(folder / f"workers-{workers}.parquet", client, seed)


def cores(rows: list, wall: float) -> float:
    """Cores a run obtained: the CPU seconds its variants used per second of wall clock."""
    return sum(r["time.cpu_s"] for r in rows) / wall


def busy(rows: list, wall: float, workers: int) -> float:
    """Fraction of the run's wall clock the workers spent inside variants (the rest is waiting
    on the scheduler, the driver or start-up)."""
    return sum(r["time.total_s"] for r in rows) / (wall * workers)


def main() -> int:
    print(f"{VARIANTS} whole-ship variants (design + compose + full measurement); {os.cpu_count()} cores; "
          f"load average before: {os.getloadavg()[0]:.2f}")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        timed_sweep(folder / "warm.parquet", "serial", 98)  # warm this process
        serial, rows = timed_sweep(folder / "serial.parquet", "serial", 1)
        one, rows1 = on_cluster(folder, 1, 1)
        two, rows2 = on_cluster(folder, 2, 1)
    ok = sum(r["status"] == "ok" for r in rows)
    report("variants per CPU-second (serial, per core)", VARIANTS / sum(r["time.cpu_s"] for r in rows), "1/s",
           f"{ok}/{VARIANTS} built")
    report("median CPU time of one built variant", statistics.median(r["time.cpu_s"] for r in rows
                                                                      if r["status"] == "ok"), "s")
    report("serial (this process): variants/s, wall clock", VARIANTS / serial, "1/s")
    report("local cluster, 1 worker: variants/s", VARIANTS / one, "1/s", f"on {cores(rows1, one):.2f} cores")
    report("local cluster, 2 workers: variants/s", VARIANTS / two, "1/s", f"on {cores(rows2, two):.2f} cores")
    report("speed-up 1 -> 2 workers, wall clock (goal >= 1.8)", one / two, "x")
    for n, wall, rs in ((1, one, rows1), (2, two, rows2)):
        report(f"worker occupancy, {n} worker(s): time in variants / wall", busy(rs, wall, n), "",
               "(1.0: never idle between variants)")
    eff = (VARIANTS / two / cores(rows2, two)) / (VARIANTS / one / cores(rows1, one))
    report("throughput per core obtained, 2 workers / 1 worker", eff, "",
           "(1.0: no sweep overhead; x 2 = speed-up on two idle cores)")
    print(f"load average after: {os.getloadavg()[0]:.2f} (other users of the machine share the cores)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
