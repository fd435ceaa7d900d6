"""Writers of a :class:`~fairlines.lines_plan.LinesPlan`: SVG, PDF and PNG through matplotlib,
DXF through ezdxf (one layer per line family, SPLINE entities through the exact section points,
TEXT labels; model space in metres at 1:1). Both are optional dependencies
(``pip install fairlines[lines]``); a missing one raises ImportError naming the package.
"""

from __future__ import annotations

import pathlib

import numpy as np

from ._native import InvalidInput

__all__ = ["LAYERS", "save", "write_dxf", "figure"]

#: Layer -> (matplotlib colour, line width on paper (mm), DXF colour index (ACI)).
LAYERS = {
    "STATIONS": ("#000000", 0.25, 7),
    "WATERLINES": ("#1f4fbf", 0.25, 5),
    "DWL": ("#0000ff", 0.45, 5),
    "BUTTOCKS": ("#c8102e", 0.25, 1),
    "DIAGONALS": ("#138a36", 0.25, 3),
    "KNUCKLES": ("#b000b0", 0.35, 6),
    "OUTLINE": ("#000000", 0.5, 7),
    "GRID": ("#9a9a9a", 0.1, 8),
    "PERPENDICULARS": ("#404040", 0.25, 8),
    "BASELINE": ("#404040", 0.35, 8),
    "CENTRELINE": ("#404040", 0.2, 8),
    "TEXT": ("#000000", 0.0, 7),
    "TITLE": ("#000000", 0.3, 7),
}
_MM_PER_PT = 25.4 / 72.0


def figure(plan):
    """A matplotlib Figure of the A3 sheet at the plan's scale. Raises ImportError without matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        from matplotlib.figure import Figure
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("the lines plan drawing needs matplotlib: pip install fairlines[lines]") from exc
    W, H = plan.sheet_mm
    fig = Figure(figsize=(W / 25.4, H / 25.4))
    ax = fig.add_axes((0, 0, 1, 1))
    left, bottom, right, top = plan.sheet
    ax.set_xlim(left, right)
    ax.set_ylim(bottom, top)
    ax.set_axis_off()
    for prim in plan.primitives:
        if hasattr(prim, "points"):
            color, lw, _ = LAYERS[prim.layer]
            ls = (0, (6, 2, 1, 2)) if prim.layer == "CENTRELINE" else "-"
            ax.plot(prim.points[:, 0], prim.points[:, 1], color=color, lw=lw / _MM_PER_PT, ls=ls,
                    solid_capstyle="round", solid_joinstyle="round")
        else:
            color = LAYERS[prim.layer][0]
            ax.text(prim.x, prim.y, prim.text, fontsize=prim.size / _MM_PER_PT / 0.72, color=color,
                    ha=prim.ha, va=prim.va, rotation=prim.rotation, family="DejaVu Sans")
    ax.plot([left, right, right, left, left], [bottom, bottom, top, top, bottom], color="k", lw=0.6)
    return fig


def write_dxf(plan, path) -> None:
    """DXF R2010, model space in metres: one layer per family, SPLINE through the section points
    (ezdxf's CAD-style control frame), LINE / LWPOLYLINE for the grid, TEXT for labels.
    Raises ImportError without ezdxf."""
    try:
        import ezdxf
        from ezdxf import units
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("the DXF lines plan needs ezdxf: pip install fairlines[lines]") from exc
    doc = ezdxf.new("R2010", setup=True)
    doc.units = units.M
    for name, (_, lw, aci) in LAYERS.items():
        layer = doc.layers.add(name, color=aci)
        layer.dxf.lineweight = int(round(lw * 100)) if lw > 0 else -3
    msp = doc.modelspace()
    m = plan.scale / 1000.0
    for prim in plan.primitives:
        if hasattr(prim, "points"):
            pts = _dedupe([(float(x), float(y)) for x, y in prim.points])
            if len(pts) < 2:
                continue
            if prim.spline and len(pts) >= 3:
                e = msp.add_cad_spline_control_frame([(x, y, 0.0) for x, y in pts],
                                                     dxfattribs={"layer": prim.layer})
            else:
                e = msp.add_lwpolyline(pts, dxfattribs={"layer": prim.layer})
            if prim.name:
                e.set_xdata("FAIRLINES", [(1000, prim.name)])
        else:
            t = msp.add_text(prim.text, height=prim.size * m, dxfattribs={"layer": prim.layer, "rotation": prim.rotation})
            t.set_placement((prim.x, prim.y), align=_align(prim.ha, prim.va))
    if "FAIRLINES" not in doc.appids:
        doc.appids.new("FAIRLINES")
    doc.saveas(str(path))


def _dedupe(pts):
    out = [pts[0]]
    for p in pts[1:]:
        if np.hypot(p[0] - out[-1][0], p[1] - out[-1][1]) > 1e-9:
            out.append(p)
    return out


def _align(ha, va):
    from ezdxf.enums import TextEntityAlignment as A
    v = {"top": "TOP", "bottom": "BOTTOM", "center": "MIDDLE", "baseline": "BOTTOM"}[va]
    h = {"left": "LEFT", "right": "RIGHT", "center": "CENTER"}[ha]
    return getattr(A, f"{v}_{h}")


def save(plan, path, dpi: int = 200) -> None:
    """Write ``plan`` to ``path``: .svg, .pdf, .png (matplotlib) or .dxf (ezdxf). Raises
    InvalidInput for another suffix."""
    path = pathlib.Path(path)
    suffix = path.suffix.lower()
    if suffix == ".dxf":
        write_dxf(plan, path)
    elif suffix in (".svg", ".pdf", ".png"):
        fig = figure(plan)
        fig.savefig(str(path), dpi=dpi)
    else:
        raise InvalidInput(f"path suffix is {suffix!r}; expected .svg, .pdf, .png or .dxf")
