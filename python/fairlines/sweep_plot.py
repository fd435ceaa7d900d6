"""The summary plot of a sweep: a scatter matrix of chosen columns, failed variants marked."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pyarrow as pa

from ._native import InvalidInput

#: Point size and colours of the scatter matrix.
POINT_SIZE = 9
OK_COLOUR, FAILED_COLOUR = "#1f5fa8", "#d62728"


def _numeric(table: pa.Table, name: str) -> np.ndarray:
    col = table.column(name)
    if pa.types.is_string(col.type):
        values = col.to_pylist()
        levels = sorted({v for v in values if v is not None})
        return np.array([levels.index(v) if v is not None else np.nan for v in values], float)
    return np.array([np.nan if v is None else float(v) for v in col.to_pylist()], float)


def scatter_matrix(table: pa.Table, columns: list[str], path, title: str = "") -> Path:
    """Write a scatter matrix (histograms on the diagonal) of `columns` of a sweep table to
    the PNG `path`. Failed variants are red crosses where their values exist (the parameters).
    Raises InvalidInput naming a column the table does not have."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    missing = [c for c in columns if c not in table.column_names]
    if missing:
        raise InvalidInput(f"plot column {missing[0]!r} is not in the table; expected some of {table.column_names}")
    n = len(columns)
    data = {c: _numeric(table, c) for c in columns}
    failed = np.array([s != "ok" for s in table.column("status").to_pylist()], bool)
    fig, axes = plt.subplots(n, n, figsize=(2.1 * n + 0.6, 2.1 * n + 0.6), squeeze=False)
    for r, cy in enumerate(columns):
        for c, cx in enumerate(columns):
            ax = axes[r][c]
            x, y = data[cx], data[cy]
            if r == c:
                ok = x[~failed & np.isfinite(x)]
                ax.hist(ok, bins=min(20, max(5, len(ok) // 4)), color=OK_COLOUR, alpha=0.8)
            else:
                ax.scatter(x[~failed], y[~failed], s=POINT_SIZE, color=OK_COLOUR, linewidths=0)
                ax.scatter(x[failed], y[failed], s=2 * POINT_SIZE, color=FAILED_COLOUR, marker="x", linewidths=1)
            ax.tick_params(labelsize=6)
            if r == n - 1:
                ax.set_xlabel(cx, fontsize=7)
            if c == 0:
                ax.set_ylabel(cy, fontsize=7)
    ok_n = int((~failed).sum())
    fig.suptitle(f"{title}: {ok_n} variants built, {int(failed.sum())} failed (red x)", fontsize=9)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
