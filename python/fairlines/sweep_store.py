"""The sweep's results on disk: one Parquet table, one row per variant, written as it grows.

While a sweep runs, finished rows go to ``TABLE.parts/part-*.parquet`` every few rows or
seconds (each part written to a temporary name and renamed, so a part is whole or absent).
At the end the table and the parts are merged, sorted by variant, written to TABLE the same
way and the parts removed. A rerun reads TABLE and any parts left by a run that was stopped,
and only the variants not there are run again: a stopped driver loses at most the rows not
yet flushed, a killed worker none (its variants are still pending, and Dask reruns them).
"""

from __future__ import annotations

import os
import time
import uuid
from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq

from ._native import InvalidInput
from .sweep_variant import MEASURE_COLUMNS, STATUS_COLUMNS, TIMING_COLUMNS

#: Flush finished rows to a part file after this many rows or this many seconds.
CHECKPOINT_ROWS = 32
CHECKPOINT_SECONDS = 10.0
_ARROW = {"float": pa.float64(), "int": pa.int64(), "bool": pa.bool_(), "str": pa.string()}


def parameter_kind(values: list) -> str:
    """Column kind of a parameter's values across the plan."""
    if all(isinstance(v, bool) for v in values):
        return "bool"
    if all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return "int"
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return "float"
    return "str"


def table_schema(parameters: dict[str, str], study_name: str, digest: str) -> pa.Schema:
    """variant, key, the parameters (path -> kind), status, measurements, timings."""
    cols = {"variant": "int", "key": "str", **parameters, **STATUS_COLUMNS, **MEASURE_COLUMNS, **TIMING_COLUMNS}
    meta = {"fairlines.study": study_name, "fairlines.digest": digest}
    return pa.schema([pa.field(k, _ARROW[v]) for k, v in cols.items()], metadata=meta)


def _cast(value, kind: str):
    if value is None or kind != "str":
        return value
    return str(value)


def rows_to_table(rows: list[dict], schema: pa.Schema) -> pa.Table:
    kinds = {f.name: ("str" if f.type == pa.string() else "") for f in schema}
    cols = {n: [_cast(r.get(n), kinds[n]) for r in rows] for n in schema.names}
    return pa.Table.from_pydict(cols, schema=schema)


def _write_atomic(table: pa.Table, path: Path) -> None:
    tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex}.tmp")
    pq.write_table(table, tmp)
    os.replace(tmp, path)


class ResultStore:
    """The table at ``path`` and its parts folder, for one study (``schema``)."""

    def __init__(self, path, schema: pa.Schema, rows: int = CHECKPOINT_ROWS, seconds: float = CHECKPOINT_SECONDS):
        self.path = Path(path)
        self.parts = self.path.with_name(self.path.name + ".parts")
        self.schema = schema
        self.every_rows, self.every_s = rows, seconds
        self._pending: list[dict] = []
        self._last = time.monotonic()

    def _files(self) -> list[Path]:
        files = [self.path] if self.path.exists() else []
        return files + (sorted(self.parts.glob("part-*.parquet")) if self.parts.is_dir() else [])

    def done(self, plan_keys: set[str]) -> pa.Table:
        """Rows already computed for this plan. Raises InvalidInput when the table holds rows
        of another study (a different base, measure options or plan)."""
        tables = []
        for f in self._files():
            t = pq.read_table(f)
            if t.schema.names != self.schema.names:
                raise InvalidInput(f"table {str(f)!r} has other columns than this study; expected a new table path "
                                   "(or remove the old table)")
            tables.append(t.cast(self.schema))
        if not tables:
            return self.schema.empty_table()
        t = pa.concat_tables(tables)
        keys = t.column("key").to_pylist()
        foreign = [k for k in keys if k not in plan_keys]
        if foreign:
            raise InvalidInput(f"table {str(self.path)!r} holds {len(foreign)} rows of another study (other base, "
                               "measure options or parameter values); expected a new table path (or remove the old table)")
        first = {k: i for i, k in reversed(list(enumerate(keys)))}
        return t.take(sorted(first.values()))

    def add(self, row: dict) -> None:
        """Keep a finished row; flush when enough rows or time have gathered."""
        self._pending.append(row)
        if len(self._pending) >= self.every_rows or time.monotonic() - self._last >= self.every_s:
            self.flush()

    def flush(self) -> None:
        if self._pending:
            self.parts.mkdir(parents=True, exist_ok=True)
            name = f"part-{time.time_ns():020d}-{uuid.uuid4().hex[:8]}.parquet"
            _write_atomic(rows_to_table(self._pending, self.schema), self.parts / name)
            self._pending = []
        self._last = time.monotonic()

    def finish(self, plan_keys: set[str]) -> pa.Table:
        """Merge the table and the parts into TABLE (sorted by variant); remove the parts."""
        self.flush()
        t = self.done(plan_keys)
        t = t.sort_by("variant")
        self.path.parent.mkdir(parents=True, exist_ok=True)
        _write_atomic(t, self.path)
        for f in self._files()[1:]:
            f.unlink()
        if self.parts.is_dir() and not any(self.parts.iterdir()):
            self.parts.rmdir()
        return t
