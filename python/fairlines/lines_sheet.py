"""The sheet a lines plan is drawn on and its drawing primitives, shared by
:mod:`fairlines.lines_plan` (which draws the lines) and :mod:`fairlines.lines_layout` (which
places the views and labels on the sheet)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Polyline", "Text", "STATIONS_PER_LPP", "SCALES", "SHEET_MM", "MARGIN_MM", "GAP_MM"]

#: Stations per Lpp.
STATIONS_PER_LPP = 20
#: Drawing scales 1:N tried, smallest first (N = {1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 7.5} x 10^k).
SCALES = [m * 10 ** k for k in range(0, 5) for m in (1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 7.5)]
#: A3 landscape sheet and its margin (mm).
SHEET_MM = (420.0, 297.0)
MARGIN_MM = 10.0
#: Space between views and around labels (mm on paper).
GAP_MM = 14.0


@dataclass
class Polyline:
    """A drawn line: ``points`` (k, 2) drawing metres; ``spline`` when it samples a smooth
    curve (written to DXF as a SPLINE through the points); ``name`` what it is (e.g. "WL 11")."""

    points: np.ndarray
    layer: str
    spline: bool = False
    name: str = ""


@dataclass
class Text:
    """A label at (x, y) drawing metres; ``size`` paper height (mm); ``alternatives``: other
    places ((x, y, ha, va) tuples) the layout may move it to when it would overlap a label."""

    x: float
    y: float
    text: str
    layer: str = "TEXT"
    size: float = 2.5
    ha: str = "center"
    va: str = "center"
    rotation: float = 0.0
    alternatives: tuple = ()
