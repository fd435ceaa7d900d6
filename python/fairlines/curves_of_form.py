"""Curves of form: the hydrostatics of a hull surface over a range of drafts (and trims), as a
table (CSV) and plots, and the sectional area curve against the designed one.

Every row is :func:`fl.hydrostatics <fairlines.hydrostatics>` at one draft and trim, with the
coefficients on the ship's Lpp and B; the trim (by the stern, m) is an inclined waterplane
through the draft at Lpp / 2 (see ``hydrostatics.hpp``).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from ._native import HydrostaticsOptions, InvalidInput, NurbsSurface
from .hydrostatics_surface import hydrostatics, midship_x

__all__ = ["CurvesOfForm", "COLUMNS", "curves_of_form", "highest_draft"]

#: Table columns: (key of Hydrostatics.as_dict(), heading with unit).
COLUMNS = (
    ("trim", "trim_m"), ("draft", "draft_m"), ("volume", "volume_m3"), ("displacement", "displacement_t"),
    ("lcb", "LCB_m"), ("vcb", "VCB_m"), ("lcf", "LCF_m"), ("waterplane_area", "Awp_m2"),
    ("tpc", "TPC_t_per_cm"), ("mct1cm", "MCT1cm_tm_per_cm"), ("bmt", "BMt_m"), ("bml", "BMl_m"),
    ("kmt", "KMt_m"), ("kml", "KMl_m"), ("cb", "Cb"), ("cp", "Cp"), ("cm", "Cm"), ("cwp", "Cwp"),
    ("wetted_surface", "wetted_surface_m2"), ("inertia_t", "I_T_m4"), ("inertia_l", "I_L_m4"),
)
#: Points along each parameter at which the surface's length is found (its ends are the
#: clamped boundaries, so the grid's extreme points are exact).
EXTENT_SAMPLES = 65
#: Quantities drawn against the draft in :meth:`CurvesOfForm.plot`.
PLOTTED = ("displacement", "lcb", "vcb", "lcf", "waterplane_area", "tpc", "mct1cm", "kmt", "kml",
           "wetted_surface", "cb", "cp", "cm", "cwp")


@dataclass
class CurvesOfForm:
    """``rows``: one dict per (trim, draft) with the :data:`COLUMNS` keys; ``design``: the
    hydrostatics at the design draft (upright) when one was given; ``sac``: (x, area) at the
    design draft; ``particulars``: lpp, beam, depth."""

    rows: list
    particulars: dict
    design: dict | None = None
    sac: tuple | None = None

    def column(self, key: str, trim: float = 0.0) -> np.ndarray:
        """Values of one quantity over the drafts at one trim."""
        return np.array([r[key] for r in self.rows if r["trim"] == trim])

    def write_csv(self, path) -> None:
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow([h for _, h in COLUMNS])
            for r in self.rows:
                w.writerow([f"{r[k]:.10g}" for k, _ in COLUMNS])

    def plot(self, path, name: str = "") -> None:
        """Curves of form: each quantity against the draft (draft upward), one line per trim."""
        fig = _figure((16.5, 11.7))
        trims = sorted({r["trim"] for r in self.rows})
        axes = fig.subplots(3, 5).ravel()
        for ax, key in zip(axes, PLOTTED):
            for t in trims:
                ax.plot(self.column(key, t), self.column("draft", t), lw=1.2, label=f"trim {t:+g} m")
            ax.set_title(dict(COLUMNS)[key], fontsize=9)
            ax.grid(True, lw=0.3)
            ax.tick_params(labelsize=7)
        axes[0].set_ylabel("draft (m)")
        axes[len(PLOTTED) - 1].legend(fontsize=7)
        for ax in axes[len(PLOTTED):]:
            ax.set_axis_off()
        fig.suptitle(f"Curves of form {name}".strip() + f"  (Lpp {self.particulars['lpp']:g} m, "
                     f"B {self.particulars['beam']:g} m; MCT1cm with GML = BML)")
        fig.tight_layout()
        fig.savefig(str(path), dpi=120)

    def plot_sac(self, path, basic_curve: Callable[[np.ndarray], np.ndarray] | None = None,
                 name: str = "") -> None:
        """The sectional area curve at the design draft, with the designed SAC (``basic_curve``:
        x -> area, m^2) and their difference when it is given. Raises InvalidInput when the
        curves were computed without a design draft."""
        if self.sac is None:
            raise InvalidInput("no design draft was given; expected curves_of_form(..., design_draft=T)")
        fig = _figure((11.7, 6.0))
        ax = fig.add_subplot(111)
        x, a = self.sac
        ax.plot(x, a, "k-", lw=1.5, label="surface (quadrature)")
        if basic_curve is not None:
            b = np.asarray(basic_curve(x), float)
            ax.plot(x, b, "r--", lw=1.0, label="basic curve (design)")
            ax2 = ax.twinx()
            ax2.plot(x, a - b, "b:", lw=1.0, label="surface - design")
            ax2.set_ylabel("difference (m$^2$)", color="b")
        ax.set_xlabel("x from AP (m)")
        ax.set_ylabel("sectional area (m$^2$)")
        ax.grid(True, lw=0.3)
        ax.legend(loc="upper left")
        ax.set_title(f"Sectional area curve {name} at T = {self.design['draft']:g} m".replace("  ", " "))
        fig.tight_layout()
        fig.savefig(str(path), dpi=120)


def _figure(size):
    try:
        from matplotlib.figure import Figure
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("the curves-of-form plots need matplotlib: pip install fairlines[lines]") from exc
    return Figure(figsize=size)


def curves_of_form(hull, drafts: Sequence[float], *, lpp: float, beam: float,
                   depth: float | None = None, trims: Sequence[float] = (0.0,), design_draft: float | None = None,
                   density: float = HydrostaticsOptions().density,
                   half_hull: bool = HydrostaticsOptions().half_hull, gauss: int = HydrostaticsOptions().gauss,
                   sac_stations: int = 81) -> CurvesOfForm:
    """Hydrostatics of ``hull`` at every draft (m above base) and trim (m by the stern).

    hull         a NurbsSurface, or a composed hull (``hull.composed_hull()``: bare hull, bulb
                 and blend), measured by fairlines.hydrostatics_composed; it is a half hull
                 (half_hull stays True), and its SAC is the bare hull's.
    lpp, beam    the ship's Lpp (AP at x = 0) and B (m) for the coefficients and the trim.
    depth        D (m): a waterplane above the deck anywhere along the hull is refused
                 (upright: a draft above D; trimmed: above D at the end the trim sinks), as
                 is one above the surface's highest point (by fl.hydrostatics).
    design_draft T (m): its upright hydrostatics and SAC are kept for the SAC plot.
    sac_stations stations of that SAC (81, twice the engine's default, for a smooth plot).
    density, half_hull, gauss   as fl.hydrostatics (defaults: fl.HydrostaticsOptions).
    Raises InvalidInput for a draft <= 0, a waterplane above the deck or the surface's top, or
    bad options.
    """
    surface, row = _measure(hull, float(lpp), float(beam), density, half_hull, gauss)
    drafts = _checked_drafts(surface, drafts, depth, trims, lpp)
    rows = [{k: h[k] for k, _ in COLUMNS} for h in (row(float(T), float(t)) for t in trims for T in drafts)]
    design = sac = None
    if design_draft is not None:
        hd = hydrostatics(surface, float(design_draft), half_hull=half_hull, length=float(lpp),
                          breadth=float(beam), gauss=gauss, sac_stations=sac_stations, density=density,
                          midship_x=midship_x(surface, 0.5 * float(lpp)))
        design = hd.as_dict() if surface is hull else row(float(design_draft), 0.0)
        sac = (np.asarray(hd.sac_x), np.asarray(hd.sac_area))
    return CurvesOfForm(rows, dict(lpp=float(lpp), beam=float(beam), depth=depth), design, sac)


def _measure(hull, lpp: float, beam: float, density: float, half_hull: bool, gauss: int):
    """(the hull's NURBS surface, its bare hull's for a composed hull; a function (draft, trim)
    -> hydrostatics dict)."""
    if isinstance(hull, NurbsSurface):
        return hull, lambda T, t: _hydro(hull, T, lpp, beam, 0.5 * lpp, t, density, half_hull, gauss, 2)
    from .compose import compose
    from .hydrostatics_composed import composed_hydrostatics
    if not half_hull:
        raise InvalidInput("half_hull is False; expected True for a composed hull (it is the half y >= 0)")
    bare = hull.trimmed_surfaces[0][0]
    bare_mesh = compose([bare])  # made once: every row subtracts it
    return bare, lambda T, t: composed_hydrostatics(hull, T, lpp=lpp, beam=beam, trim=t, bare_mesh=bare_mesh,
                                                    density=density)


def _checked_drafts(surface, drafts, depth, trims, lpp) -> np.ndarray:
    """The drafts as an array. Raises InvalidInput for a draft <= 0 or a waterplane above the
    deck (depth) at any trim."""
    drafts = np.atleast_1d(np.asarray(drafts, float))
    if drafts.size == 0 or not np.all(np.isfinite(drafts)) or np.any(drafts <= 0):
        raise InvalidInput(f"drafts are {drafts.tolist()}; expected finite drafts > 0 (m)")
    if depth is not None and np.any(drafts > depth):
        raise InvalidInput(f"drafts {drafts[drafts > depth].tolist()} m are above the depth {depth} m (the deck); "
                           "expected drafts <= depth")
    if depth is not None:
        for t in trims:
            top = highest_draft(surface, depth, lpp, t)
            if np.any(drafts > top):
                raise InvalidInput(f"at trim {t:g} m the drafts {drafts[drafts > top].tolist()} m put the waterplane above "
                                   f"the deck (depth {depth} m) at the {'aft' if t > 0 else 'fore'} end; expected drafts "
                                   f"<= {top:.4g} m at that trim")
    return drafts


def highest_draft(surface: NurbsSurface, depth: float, lpp: float, trim: float = 0.0) -> float:
    """The largest draft (m, at Lpp / 2) whose waterplane, trimmed by ``trim`` (m by the stern,
    over ``lpp``), stays at or below the deck z = ``depth`` over the surface's whole length."""
    x = _x_extent(surface)
    sink = max(float(trim) * (0.5 * lpp - xe) / lpp for xe in x)  # rise of the waterline above T
    return float(depth) - max(sink, 0.0)


def _x_extent(surface):
    """(x_min, x_max) of the surface, from a grid of points on it."""
    g = np.asarray(surface.evaluate_grid(np.linspace(*surface.domain_u, EXTENT_SAMPLES),
                                         np.linspace(*surface.domain_v, EXTENT_SAMPLES)))[..., 0]
    return float(g.min()), float(g.max())


def _hydro(surface, T, lpp, beam, mid, trim, density, half_hull, gauss, sac_stations):
    return hydrostatics(surface, T, half_hull=half_hull, length=float(lpp), breadth=float(beam),
                                midship_x=midship_x(surface, mid), gauss=gauss, sac_stations=sac_stations,
                                density=density, trim=trim, trim_length=float(lpp)).as_dict()
