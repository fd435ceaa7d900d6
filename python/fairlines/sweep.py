"""Design-space sweeps: many hull variants built, composed and measured, on Dask.

``fl.sweep(study)`` reads a study (fairlines.sweep_study: a base design, the parameters varied
and their sampling), runs every variant not yet in its table (fairlines.sweep_variant) and
returns the table (a ``pyarrow.Table``, one row per variant, failures included). Where the
variants run:

* ``scheduler=None``: a Dask ``LocalCluster`` of ``workers`` single-threaded processes
  (default: all cores), started and closed by the call;
* ``scheduler="tcp://host:8786"``: an existing Dask scheduler (workers on any machines that
  have fairlines installed); a ``distributed.Client`` is accepted too;
* ``scheduler="serial"``: in this process, one after another (no Dask).

The table is written as the variants finish (fairlines.sweep_store), so a stopped run loses at
most a few rows and a rerun only runs what is missing. Call it under
``if __name__ == "__main__":`` in a script: the local cluster's worker processes import the
main module.
"""

from __future__ import annotations

import logging
import os
import shutil
from collections.abc import Callable, Iterator
from pathlib import Path

from ._native import InvalidInput
from .sweep_study import Study, variant_key
from .sweep_variant import TIMING_COLUMNS, run_variant

__all__ = ["sweep", "load_study", "table_path", "SweepIncomplete", "deterministic_columns"]

#: Keys Dask gives the variant tasks (their study's key follows), so a shared scheduler's
#: dashboard shows what they are.
TASK_PREFIX = "fairlines-variant-"
#: Seconds to wait for a scheduler given by address before refusing it.
CONNECT_SECONDS = 20

Progress = Callable[[int, int, "dict | None"], None]


def deterministic_columns(schema) -> list[str]:
    """Columns a rerun reproduces exactly, on any scheduler (all but the timings and the worker)."""
    return [n for n in schema.names if n not in TIMING_COLUMNS]


class SweepIncomplete(RuntimeError):
    """Some variants were lost to the cluster (a worker or the scheduler died, a connection
    broke) and are not in the table; the table holds the rest. Rerun to complete it."""

    def __init__(self, message: str, missing: list[int]):
        super().__init__(message)
        self.missing = missing


def load_study(study) -> Study:
    """A Study from a Study, a dict (paths relative to the current folder) or a TOML path.
    Raises InvalidInput for a bad study."""
    if isinstance(study, Study):
        study.check()
        return study
    if isinstance(study, dict):
        return Study.from_dict(study)
    if isinstance(study, (str, os.PathLike)):
        return Study.from_toml(study)
    raise InvalidInput(f"study is {type(study).__name__}; expected a Study, a dict or a TOML file path")


def _serial(study: Study, pending: list[tuple[int, dict, str]]) -> Iterator[tuple[int, dict | None, str | None]]:
    outputs = _outputs(study)
    for i, params, _ in pending:
        yield i, run_variant(study.base_kind, study.base, params, study.measure, outputs, i), None


def _dask(client, study: Study, pending: list[tuple[int, dict, str]]) -> Iterator[tuple[int, dict | None, str | None]]:
    from distributed import as_completed

    futures = {}
    outputs = _outputs(study)
    for i, params, key in pending:
        f = client.submit(run_variant, study.base_kind, study.base, params, study.measure, outputs, i,
                          key=TASK_PREFIX + key, pure=False)
        futures[f] = i
    try:
        for f in as_completed(list(futures)):
            i = futures.pop(f)
            try:
                row = f.result()
            except Exception as exc:  # the cluster lost it (KilledWorker, CommClosedError, ...)
                yield i, None, f"{type(exc).__name__}: {exc}"
            else:
                yield i, row, None
            f.release()
    finally:
        client.cancel(list(futures))


def _outputs(study: Study) -> dict | None:
    if not study.outputs.get("per_variant"):
        return None
    folder = study.path("directory", f"{_slug(study.name)}_variants")
    return {"directory": str(folder.resolve()), "per_variant": list(study.outputs["per_variant"])}


def _slug(name: str) -> str:
    return "".join(c if c.isalnum() else "_" for c in name).strip("_") or "study"


class _Cluster:
    """A Dask client for `scheduler` (see the module docstring); closes what it started."""

    def __init__(self, scheduler, workers: int | None):
        self.client = self.cluster = None
        self.owned = False
        if scheduler == "serial":
            return
        from distributed import Client, LocalCluster

        if scheduler is None:
            if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
                raise InvalidInput(f"workers is {workers!r}; expected an integer >= 1 (or None: all cores)")
            n = workers or os.cpu_count() or 1
            # Worker logs are silenced: a variant's error is its row, and a heartbeat racing the
            # shutdown would otherwise print a traceback after a finished sweep.
            self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                                        silence_logs=logging.CRITICAL)
            self.client, self.owned = Client(self.cluster), True
        elif isinstance(scheduler, str):
            if not scheduler.startswith(("tcp://", "tls://", "inproc://", "ucx://")):
                raise InvalidInput(f"scheduler is {scheduler!r}; expected 'serial', None or an address like "
                                   "'tcp://host:8786'")
            try:
                self.client, self.owned = Client(scheduler, timeout=CONNECT_SECONDS), True
            except OSError as exc:
                raise InvalidInput(f"scheduler is {scheduler!r}; could not connect within {CONNECT_SECONDS} s "
                                   f"({exc}); expected a running Dask scheduler there") from exc
        else:
            self.client = scheduler

    def close(self) -> None:
        if self.owned:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _plan(study: Study):
    from .sweep_store import parameter_kind, table_schema

    plan = study.plan()
    digest = study.base_digest()
    keys = [variant_key(digest, p) for p in plan]
    kinds = {p.path: parameter_kind([row[p.path] for row in plan]) for p in study.parameters}
    return plan, keys, table_schema(kinds, study.name, digest)


def table_path(study, table=None) -> Path:
    """Where sweep() writes the study's table: `table`, else outputs.table, else NAME.parquet."""
    if table is not None:
        return Path(table)
    study = load_study(study)
    return study.path("table", f"{_slug(study.name)}.parquet")


def sweep(study, *, scheduler=None, workers: int | None = None, table=None, resume: bool = True,
          progress: Progress | None = None, plot=None):
    """Run a study (a Study, a dict, or a TOML path; see fairlines.sweep_study) and return its
    table: one row per variant, sorted by variant, failed variants included (``status``,
    ``error*`` columns; fairlines.sweep_variant lists the columns).

    scheduler  None (a local cluster of `workers` processes, default all cores), "serial", a
               scheduler address "tcp://host:port", or a distributed.Client.
    table      the Parquet file (default the study's ``outputs.table``, else NAME.parquet beside
               the study). Rows already there are kept and not run again (``resume=False``:
               start afresh, removing the old table).
    progress   called as progress(done, total, row) after each variant (row None at the start);
               an exception it raises stops the sweep, keeping the finished rows.
    plot       a PNG path for the scatter matrix (default the study's ``outputs.plot``, if any).

    Raises InvalidInput for a bad study or a table of another study, SweepIncomplete when the
    cluster lost variants (the table holds the others: rerun to complete it).
    """
    from .sweep_store import ResultStore

    study = load_study(study)
    plan, keys, schema = _plan(study)
    store = ResultStore(table_path(study, table), schema)
    if not resume:
        store.path.unlink(missing_ok=True)
        shutil.rmtree(store.parts, ignore_errors=True)
    plan_keys = set(keys)
    done = set(store.done(plan_keys).column("key").to_pylist())
    pending = [(i, p, k) for i, (p, k) in enumerate(zip(plan, keys)) if k not in done]
    count, total, lost = len(plan) - len(pending), len(plan), []
    if progress:
        progress(count, total, None)
    cluster = _Cluster(scheduler, workers) if pending else _Cluster("serial", None)
    runner = _serial(study, pending) if cluster.client is None else _dask(cluster.client, study, pending)
    try:
        for i, row, error in runner:
            if row is None:
                lost.append((i, error))
                continue
            row.update(plan[i], key=keys[i])
            store.add(row)
            count += 1
            if progress:
                progress(count, total, row)
    finally:
        runner.close()  # cancels what is still queued (a stopped sweep on a shared scheduler)
        store.flush()
        cluster.close()
    result = store.finish(plan_keys)
    _maybe_plot(study, result, plot)
    if lost:
        raise SweepIncomplete(f"{len(lost)} of {total} variants were lost to the cluster (first: variant {lost[0][0]}, "
                              f"{lost[0][1]}); the table {str(store.path)!r} holds the rest: rerun to complete it",
                              [i for i, _ in lost])
    return result


def _maybe_plot(study: Study, table, plot) -> None:
    path = Path(plot) if plot is not None else study.path("plot")
    if path is None:
        return
    from .sweep_plot import scatter_matrix

    columns = study.outputs.get("plot_columns") or [p.path for p in study.parameters] + ["hydro.cp", "hydro.wetted_surface"]
    scatter_matrix(table, columns, path, title=study.name)
