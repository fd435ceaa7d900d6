"""Shared helpers of the sweep tests: the base ship, small studies, a real Dask cluster."""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import fairlines as fl

#: The whole container ship's particulars (the designer's example).
BASE = dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True)
#: Cheap measurement options so a 20-variant study runs in seconds.
QUICK_MEASURE = {"fairness_options": {"n_waterlines": 3, "n_buttocks": 2, "n_frames": 4, "samples": 201},
                 "displacement": False}
CLUSTER_TIMEOUT = 90.0  # s to wait for a scheduler and its workers on a loaded machine


def base_description() -> dict:
    """The designed container ship's hull description (the one real hull the tests use)."""
    return json.loads(fl.design_hull(**BASE).to_json())


def study(table: Path, samples: int = 20, seed: int = 7, **extra) -> dict:
    """An LHS study of Cb (reaching past the designer's range, so some variants fail), the LCB
    and the bulb's length."""
    return {"name": "test study", "base": {"particulars": dict(BASE)},
            "sampling": {"method": "lhs", "samples": samples, "seed": seed},
            "parameters": [{"path": "cb", "low": 0.6, "high": 0.97},
                           {"path": "lcb", "low": 117.0, "high": 121.0},
                           {"path": "bulb.kracht.c_lpr", "low": 0.022, "high": 0.03}],
            "measure": dict(QUICK_MEASURE), "outputs": {"table": str(table)}, **extra}


def _spawn(args: list[str], log: Path) -> subprocess.Popen:
    with log.open("w") as out:  # the child keeps its own copy of the descriptor
        return subprocess.Popen([sys.executable, "-m", "dask", *args], stdout=out, stderr=subprocess.STDOUT,
                                start_new_session=True)


@contextlib.contextmanager
def dask_cluster(folder: Path, workers: int = 2):
    """A real `dask scheduler` and `workers` `dask worker` processes (no nanny, one thread) on
    loopback. Yields (address, [worker Popen]); stops them all at the end."""
    sched_file = folder / "scheduler.json"
    procs = [_spawn(["scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                     "--scheduler-file", str(sched_file)], folder / "scheduler.log")]
    try:
        deadline = time.monotonic() + CLUSTER_TIMEOUT
        while not sched_file.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        address = json.loads(sched_file.read_text())["address"]
        worker_procs = [_spawn(["worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard",
                                "--host", "127.0.0.1", "--name", f"w{i}"], folder / f"worker{i}.log")
                        for i in range(workers)]
        procs += worker_procs
        from distributed import Client
        with Client(address, timeout=CLUSTER_TIMEOUT) as c:
            c.wait_for_workers(workers, timeout=CLUSTER_TIMEOUT)
        yield address, worker_procs
    finally:
        for p in reversed(procs):  # workers first: a worker closing after its scheduler can hang
            _stop(p)


def _stop(p: subprocess.Popen) -> None:
    if p.poll() is None:
        os.killpg(p.pid, signal.SIGTERM)
    try:
        p.wait(timeout=15)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.wait()
