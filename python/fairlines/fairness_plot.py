"""Curvature combs of a hull's cut curves, drawn the way a designer checks fairness in CAD.

Each waterline (half-breadth plan), buttock (profile) and frame (body plan) is cut from the
surface and judged on its own (:func:`fairlines.fairness.judge_cut`); along it a comb of
spines is drawn, one per sample, pointing away from the centre of curvature with a length
proportional to |curvature|. A fair line has a comb whose envelope is smooth and stays on one
side; a wobble shows as the comb crossing the line, and each sign change the judge counts is
marked with a red dot. One comb scale per view (stated in its title, metres of spine per 1/m of
curvature) so lines in a view compare directly.
"""

from __future__ import annotations

import pathlib

import numpy as np

from . import _native
from .fairness import MIN_TURN_DEG, judge_cut, surface_extent

__all__ = ["comb_spines", "fairness_figure", "sign_change_counts", "write_fairness_plot"]

#: The longest spine of a view, as a fraction of the view's larger extent.
COMB_LENGTH = 0.06
#: The view reaches this many comb lengths beyond the cuts: a spine longer than that (a
#: waterline's tight round end at the keel, 15 times the others') runs out of the frame instead of
#: shrinking every other comb to a line.
VIEW_COMBS = 1.25
#: Samples per cut and spines drawn per cut (every n-th sample).
SAMPLES = 801
SPINES = 160
#: Cut positions: waterlines at these fractions of the depth, buttocks and frames likewise.
WATERLINES = (0.05, 0.15, 0.3, 0.45, 0.58, 0.7, 0.85)
BUTTOCKS = (0.15, 0.3, 0.45, 0.6, 0.75, 0.9)
FRAMES = 21

# (axis cut, plot axes (horizontal, vertical) in x, y, z indices) of each view.
_VIEWS = {"waterline": (2, (0, 1)), "buttock": (1, (0, 2)), "frame": (0, (1, 2))}


def comb_spines(points: np.ndarray, curvature: np.ndarray, scale: float) -> tuple[np.ndarray, np.ndarray]:
    """Spines of a planar curve's comb: base points (n, 2) and tips (n, 2).

    points: #samples by 2 list of the curve's points in its plane (m), in order;
    curvature: #samples list of |curvature| or signed curvature (1/m), only its size is used;
    scale: spine length per unit curvature (m per 1/m).
    A spine points away from the centre of curvature (the side the curve bulges to); where
    the curve is straight it has length zero."""
    p = np.asarray(points, dtype=float)
    k = np.abs(np.asarray(curvature, dtype=float))
    if len(p) < 3:
        return p.copy(), p.copy()
    t = np.gradient(p, axis=0)
    t /= np.maximum(np.linalg.norm(t, axis=1, keepdims=True), 1e-300)
    turn = np.gradient(t, axis=0)  # points toward the centre of curvature
    left = np.column_stack([-t[:, 1], t[:, 0]])
    side = np.sign(np.sum(turn * left, axis=1))
    return p, p - (scale * k * side)[:, None] * left


def _cuts(surface, kind: str, values) -> list:
    axis = _VIEWS[kind][0]
    out = []
    for v in values:
        cut = _native.plane_cut(surface, axis, float(v), SAMPLES)
        if len(cut.points) >= 3:
            out.append(cut)
    return out


def _positions(surface) -> dict:
    lo, hi = surface_extent(surface)
    z0 = max(lo[2], 0.0)
    return {"waterline": [z0 + f * (hi[2] - z0) for f in WATERLINES],
            "buttock": [f * hi[1] for f in BUTTOCKS],
            "frame": list(np.linspace(lo[0], hi[0], FRAMES + 2)[1:-1])}


def sign_change_counts(surface) -> dict:
    """Curvature sign changes (fairlines.fairness.judge_cut) summed over the waterlines, buttocks
    and frames this module cuts from `surface`: {"waterline": n, "buttock": n, "frame": n}."""
    return {kind: sum(judge_cut(c)["sign_changes"] for c in _cuts(surface, kind, values))
            for kind, values in _positions(surface).items()}


def fairness_figure(surface, *, title: str = "", min_turn_deg: float = MIN_TURN_DEG):
    """A matplotlib Figure: the half-breadth plan, profile and body plan of `surface` (a half
    hull, fl.NurbsSurface) with the curvature comb of every cut and its sign changes marked.
    Returns (figure, {kind: [judge_cut result, ...]}). Raises ImportError without matplotlib."""
    try:
        from matplotlib.figure import Figure
    except ImportError as exc:  # pragma: no cover - optional dependency
        raise ImportError("the fairness plot needs matplotlib: pip install fairlines[lines]") from exc
    fig = Figure(figsize=(16, 11), dpi=100)
    grid = fig.add_gridspec(2, 2, width_ratios=(3, 1))
    axes = {"waterline": fig.add_subplot(grid[0, 0]), "buttock": fig.add_subplot(grid[1, 0]),
            "frame": fig.add_subplot(grid[:, 1])}
    judged: dict = {}
    for kind, values in _positions(surface).items():
        judged[kind] = _draw_view(axes[kind], kind, _cuts(surface, kind, values), min_turn_deg)
    total = {k: sum(j["sign_changes"] for j in v) for k, v in judged.items()}
    fig.suptitle(f"{title}  curvature combs; sign changes (red, lobes over {min_turn_deg:g} deg): "
                 f"waterlines {total['waterline']}, buttocks {total['buttock']}, frames {total['frame']}", fontsize=11)
    fig.tight_layout()
    return fig, judged


def _draw_view(ax, kind: str, cuts: list, min_turn_deg: float) -> list:
    h, v = _VIEWS[kind][1]
    pts = [np.asarray(c.points)[:, [h, v]] for c in cuts]
    ks = [np.asarray(c.curvature) for c in cuts]
    allp = np.vstack(pts) if pts else np.zeros((1, 2))
    extent = float(np.max(np.ptp(allp, axis=0))) or 1.0
    kmax = max((float(np.percentile(np.abs(k), 99)) for k in ks), default=0.0)
    scale = COMB_LENGTH * extent / kmax if kmax > 0 else 0.0
    judged, tips = [], []
    for cut, p, k in zip(cuts, pts, ks):
        j = judge_cut(cut, min_turn_deg)
        judged.append(j)
        base, tip = comb_spines(p, k, scale)
        step = max(1, len(p) // SPINES)
        tips.append(tip[::step])
        for b, t in zip(base[::step], tip[::step]):
            ax.plot((b[0], t[0]), (b[1], t[1]), color="0.65", lw=0.4)
        ax.plot(tip[::step, 0], tip[::step, 1], color="tab:orange", lw=0.6)
        ax.plot(p[:, 0], p[:, 1], color="tab:blue", lw=1.0)
        for inf in j["inflections"]:
            q = np.asarray(inf["at"])[[h, v]]
            ax.plot(q[0], q[1], "o", color="red", ms=4)
    names = {"waterline": ("half-breadth plan: waterlines", "x (m)", "y (m)"),
             "buttock": ("profile: buttocks", "x (m)", "z (m)"), "frame": ("body plan: frames", "y (m)", "z (m)")}
    label, hx, vy = names[kind]
    ax.set_title(f"{label} (comb {scale:.3g} m per 1/m)", fontsize=10)
    _frame_view(ax, allp, tips, VIEW_COMBS * COMB_LENGTH * extent)
    ax.set_xlabel(hx)
    ax.set_ylabel(vy)
    ax.set_aspect("equal" if kind == "frame" else "auto")
    ax.grid(True, lw=0.3)
    return judged


def _frame_view(ax, points: np.ndarray, tips: list, margin: float) -> None:
    """Axis limits holding the cuts and their drawn spines' tips, each clipped at `margin` (m)
    beyond the cuts' box."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    shown = np.vstack([points] + [np.clip(t, lo - margin, hi + margin) for t in tips])
    pad = 0.02 * float(np.max(np.ptp(shown, axis=0)))
    ax.set_xlim(shown[:, 0].min() - pad, shown[:, 0].max() + pad)
    ax.set_ylim(shown[:, 1].min() - pad, shown[:, 1].max() + pad)


def write_fairness_plot(surface, path, *, title: str = "", dpi: int = 100) -> dict:
    """Write the fairness figure to `path` (.png, .svg or .pdf) and return the judged cuts
    ({kind: [judge_cut result, ...]}). Raises InvalidInput for another suffix, ImportError
    without matplotlib."""
    path = pathlib.Path(path)
    if path.suffix.lower() not in (".png", ".svg", ".pdf"):
        raise _native.InvalidInput(f"fairness plot path is {str(path)!r}; expected a .png, .svg or .pdf file")
    fig, judged = fairness_figure(surface, title=title)
    fig.savefig(path, dpi=dpi)
    return judged
