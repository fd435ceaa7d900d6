"""``fairlines sweep STUDY.toml``: run a design-space study with a progress bar on the terminal."""

from __future__ import annotations

import shutil
import sys
import time

#: Redraw the bar at most this often (s), so thousands of variants do not flood a slow terminal.
REDRAW_SECONDS = 0.2


class ProgressBar:
    """A one-line text progress bar (stderr): done/total, failures, rate and time left."""

    def __init__(self, stream=sys.stderr):
        self.stream = stream
        self.tty = stream.isatty()
        self._step = -1
        self.failed = 0
        self.start = time.monotonic()
        self.first = None
        self._drawn = 0.0

    def __call__(self, done: int, total: int, row: dict | None) -> None:
        if row is None:
            self.first = done
        elif row.get("status") != "ok":
            self.failed += 1
        now = time.monotonic()
        if done < total and now - self._drawn < REDRAW_SECONDS:
            return
        step = 10 * done // max(total, 1)
        if not self.tty and step == self._step:  # a log file: a line every tenth of the study
            return
        self._step = step
        self._drawn = now
        ran = done - (self.first or 0)
        rate = ran / max(now - self.start, 1e-9)
        left = f"{(total - done) / rate:.0f} s left" if rate > 0 and done < total else ""
        width = max(10, min(40, shutil.get_terminal_size((80, 20)).columns - 60))
        fill = int(width * done / max(total, 1))
        line = (f"\r[{'#' * fill}{'.' * (width - fill)}] {done}/{total} variants, {self.failed} failed, "
                f"{rate:.2f}/s {left}")
        self.stream.write(line.ljust(len(line) + 4) if self.tty else line[1:].rstrip() + "\n")
        if done >= total and self.tty:
            self.stream.write("\n")
        self.stream.flush()


def add_parser(sub) -> None:
    s = sub.add_parser("sweep", help="run a design-space study (TOML) on Dask: one Parquet row per variant")
    s.add_argument("study", help="study TOML (see docs/sweeps.md)")
    s.add_argument("--scheduler", default=None,
                   help="Dask scheduler address (tcp://host:8786), or 'serial'; default a local cluster")
    s.add_argument("--workers", type=int, default=None, help="local cluster worker processes (default all cores)")
    s.add_argument("-o", "--table", default=None, help="Parquet table (default the study's outputs.table)")
    s.add_argument("--plot", default=None, help="scatter-matrix PNG (default the study's outputs.plot)")
    s.add_argument("--fresh", action="store_true", help="remove the old table and run every variant")


def run(args) -> int:
    from .sweep import SweepIncomplete, sweep, table_path

    bar = ProgressBar()
    t0 = time.monotonic()
    try:
        table = sweep(args.study, scheduler=args.scheduler, workers=args.workers, table=args.table,
                      resume=not args.fresh, progress=bar, plot=args.plot)
    except SweepIncomplete as exc:
        print(f"fairlines sweep: {exc}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        where = table_path(args.study, args.table)
        print(f"\nfairlines sweep: stopped; the finished variants are kept ({where} and {where.name}.parts): "
              "rerun to go on", file=sys.stderr)
        return 130
    status = table.column("status").to_pylist()
    failed = sum(s != "ok" for s in status)
    ran = len(status) - (bar.first or 0)
    print(f"{len(status)} variants: {len(status) - failed} built, {failed} failed ({ran} run now, "
          f"{time.monotonic() - t0:.1f} s)")
    print(f"wrote {table_path(args.study, args.table)}")
    return 0
