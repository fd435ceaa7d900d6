"""Bulbous bow from Kracht's (1978) coefficients, and those coefficients measured back off a
composed mesh. The geometry runs in the compiled engine (``fairlines._native``).
Conventions: metres, x forward from AP, y >= 0 the starboard half, z up.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from . import _native
from ._native import NurbsSurface
from ._options import fill_options, option_names
from .validation import integral

__all__ = ["BulbousBow", "KRACHT_NAMES", "measure_kracht"]

#: The six Kracht (1978) coefficients.
KRACHT_NAMES = ("c_lpr", "c_bb", "c_zb", "c_abt", "c_abl", "c_vpr")
_SHIP_NAMES = ("lpp", "beam", "draft_fp", "midship_area", "displacement_volume")


class BulbousBow:
    """Bulbous bow from the six Kracht (1978) coefficients and the ship's particulars.

    The bulb forward of FP has superelliptic sections (exponent ``section_fullness``) whose
    breadth and height follow a superelliptic outline (exponent ``nose_shape``) to the nose at
    height Z_B; the section height H, fullness and nose shape are solved so that A_BT, A_BL
    and V_PR hold. Behind FP the section runs on unchanged for ``aft_length`` metres (default
    2 (L_PR + B_B)) into the hull. Shape controls: ``nose_height_shift`` (m) lifts the
    section centres behind a lower nose. ``surface`` is the fair-skinned NurbsSurface (u aft
    -> nose pole, v bottom -> top centre line, y >= 0).
    """

    def __init__(self, *, lpp: float, beam: float, draft_fp: float, midship_area: float,
                 displacement_volume: float, x_fp: float | None = None, **options):
        """``options`` by keyword (defaults in the engine): the Kracht coefficients (fields of
        :class:`fl.KrachtCoefficients`: c_lpr, c_bb, c_zb, c_abt, c_abl, c_vpr) and the shape
        (fields of :class:`fl.BulbOptions`: aft_length, nose_height_shift, sections,
        section_points, control_u, control_v). Raises InvalidInput naming an unknown option, a
        value of the wrong type or out of range."""
        kracht = {n: v for n, v in options.items() if n in KRACHT_NAMES}
        shape = {n: v for n, v in options.items() if n not in KRACHT_NAMES}
        unknown = set(shape) - set(option_names(_native.BulbOptions))
        if unknown:
            raise _native.InvalidInput(f"BulbousBow option {sorted(unknown)[0]!r} is unknown; expected one of "
                                       + ", ".join(KRACHT_NAMES + option_names(_native.BulbOptions)))
        ship = dict(lpp=lpp, beam=beam, draft_fp=draft_fp, midship_area=midship_area,
                    displacement_volume=displacement_volume, x_fp=-1.0 if x_fp is None else x_fp)
        as_float = {n: float for n in (*KRACHT_NAMES, *ship, "aft_length", "nose_height_shift")}
        whole = {n: integral(f"BulbousBow option {n}") for n in ("sections", "section_points", "control_u", "control_v")}
        k = fill_options(_native.KrachtCoefficients, "BulbousBow", kracht, as_float)
        o = fill_options(_native.BulbOptions, "BulbousBow", shape, {**as_float, **whole})
        sh = fill_options(_native.BulbShip, "BulbousBow", ship, as_float)
        self.ship = {**ship, "x_fp": lpp if x_fp is None else x_fp}
        self.kracht = {n: getattr(k, n) for n in KRACHT_NAMES}
        self._bow = _native._BulbousBow(k, sh, o)
        self.surface: NurbsSurface = self._bow.surface
        #: Derived dimensions and shape exponents (metres, m^2, m^3).
        self.shape: dict = dict(self._bow.shape)
        #: Max distance of the skinned surface from its analytic sample points (m).
        self.max_fit_deviation: float = float(self._bow.max_fit_deviation)

    @classmethod
    def from_dict(cls, section: Mapping[str, Any], ship: Mapping[str, float]) -> "BulbousBow":
        """From the ``"bulb"`` section of a hull JSON::

            {"kracht": {"c_lpr": 0.025, "c_bb": 0.18, ...},
             "shape": {"aft_length": 12.0, "nose_height_shift": 0.0}}

        and the ship particulars ``lpp, beam, draft_fp, midship_area, displacement_volume``
        (optionally ``x_fp``). Unknown keys raise InvalidInput naming them.
        """
        section = dict(section)
        unknown = set(section) - {"kracht", "shape"}
        if unknown:
            raise _native.InvalidInput(f"bulb section has unknown keys {sorted(unknown)}; expected 'kracht', 'shape'")
        kr = dict(section.get("kracht", {}))
        bad = set(kr) - set(KRACHT_NAMES)
        if bad:
            raise _native.InvalidInput(f"bulb 'kracht' has unknown keys {sorted(bad)}; expected some of {list(KRACHT_NAMES)}")
        shape = dict(section.get("shape", {}))
        allowed = set(option_names(_native.BulbOptions))
        bad = set(shape) - allowed
        if bad:
            raise _native.InvalidInput(f"bulb 'shape' has unknown keys {sorted(bad)}; expected some of {sorted(allowed)}")
        sh = dict(ship)
        missing = [n for n in _SHIP_NAMES if n not in sh]
        if missing:
            raise _native.InvalidInput(f"ship particulars miss {missing}; expected {list(_SHIP_NAMES)}")
        kw = {n: sh[n] for n in _SHIP_NAMES}
        if "x_fp" in sh:
            kw["x_fp"] = sh["x_fp"]
        return cls(**kw, **kr, **shape)

    def __repr__(self) -> str:
        s = self.shape
        return (f"BulbousBow(L_PR={s['length']:.3f} m, B_B={s['breadth']:.3f} m, "
                f"Z_B={s['nose_height']:.3f} m, H={s['height']:.3f} m, n={s['section_fullness']:.3f}, "
                f"m={s['nose_shape']:.3f})")


def measure_kracht(mesh, *, x_fp: float, lpp: float, beam: float, draft_fp: float,
                   midship_area: float, displacement_volume: float) -> dict:
    """Kracht coefficients (:data:`KRACHT_NAMES`) measured by the engine on a closed,
    outward-oriented half-hull mesh (y >= 0), on its part below the waterline z = draft_fp (a
    raked stem reaches forward of the FP above it, and is not bulb): protrusion of the foremost
    point, breadth of the section x = x_fp, nose height, section area at the FP, centre-plane
    area and volume forward of the FP, each made dimensionless by the ship's figures. The ship
    is a :class:`fl.BulbShip` as for :class:`BulbousBow` (x_fp < 0 puts the FP at lpp).
    Raises InvalidInput for a bad mesh or a non-finite / non-positive ship dimension."""
    ship = _native.BulbShip()
    for name, value in dict(x_fp=x_fp, lpp=lpp, beam=beam, draft_fp=draft_fp, midship_area=midship_area,
                            displacement_volume=displacement_volume).items():
        setattr(ship, name, float(value))
    k = _native._measure_kracht(np.asarray(mesh.vertices, float), np.asarray(mesh.faces), ship)
    return {name: getattr(k, name) for name in KRACHT_NAMES}
