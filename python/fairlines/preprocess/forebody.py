"""An editable forebody description (basic curves with form parameters) from measured form
parameters."""

from __future__ import annotations

import numpy as np

from .._native import InvalidInput
from ..offsets import HullData
from .integrate import simpson
from .jsonable import jsonable


# A basic curve stays on its midship value (the parallel middle body) while within this
# fraction of its scale (B/2, T, Am, or 1 degree for angles).
PARALLEL_TOL = 0.002


# The description's range ends at the last station whose keel lies below this fraction of T.
STEM_KEEL_FRACTION = 0.5


# Interior points handed to each basic curve beyond its parallel part.
DESCRIPTION_POINTS = 5


def _downward_angle(dy, dz):
    """Section tangent angle in degrees from the downward vertical toward +y, for a section
    running down from deck to keel whose upward segment is (dy, dz): 0 vertical, < 0 flare,
    -90 horizontal at the keel."""
    return float(np.degrees(np.arctan2(-dy, dz)))


def hull_description(fp: dict, data: HullData, *, n_stations=25) -> dict:
    """The forebody (midships to the FP) as a bare-hull description of basic curves with form
    parameters (the hull JSON of ``fl.Hull.from_json``): each curve's midship value and
    the end of its parallel part, points read off the imported hull beyond it, its end value,
    and the integral parameters (forebody volume and LCB, waterplane area, entrance angle).
    Raises InvalidInput when fewer than 4 stations lie between midships and the FP."""
    L, B, T = data.lpp, data.beam, data.draft
    st, x, x1 = _forebody_stations(fp, data)
    x0 = L / 2
    top = float(np.median([s["deck"][1] for s in st[: max(2, len(st) // 4)]]))
    fos_low = np.array([s["fos_z"][0] if s["fos_z"] else np.nan for s in st])  # flat side's lower end
    curves = _measured_curves(fp, st, fos_low, B, T)
    out = {name: _curve_spec(x, f if scale is None else np.maximum(f, 0.0), scale, x0, x1, L)
           for name, (f, scale) in curves.items()}
    out["fos"] = _flat_of_side_spec(x, fos_low, T, top, x0, L)
    fob_end = fp["FOB"]["x_fwd"] if fp["FOB"]["x_fwd"] else x0 + 2e-3 * L
    fob = np.minimum([s["fob_half_width"] for s in st], B / 2)
    out["fob"] = _curve_spec(x, fob, B / 2, x0, fob_end, L) | {"x_end": float(fob_end), "yE": 0.0}
    fore = x >= x0
    sac, xf = curves["sac"][0][fore], x[fore]
    out["sac"]["volume"] = float(simpson(sac, xf))
    out["sac"]["lcb"] = float(simpson(sac * xf, xf) / out["sac"]["volume"])
    out["dwl"]["waterplane_area"] = float(2 * simpson(curves["dwl"][0][fore], xf))
    return jsonable({
        "name": f"{data.name}, forebody read off the imported hull",
        "notes": "Written by fairlines import: basic curves and form parameters found automatically "
                 "(Kim & Hwangbo 2008, pipeline step 1); edit any value and rebuild with fl.Hull.from_json.",
        "principal": {"Lpp": L, "B": B, "T": T, "D": top},
        "range": {"x_start": x0, "x_end": x1},
        "stations": {"count": int(n_stations)},
        "basic_curves": out,
        "sections": {"n_control": 16},
        "skinning": {"start": "parallel", "end": "free"},
    })


def _forebody_stations(fp, data):
    """(stations, their x, the range's end) from midships forward. The description's stem is
    vertical at the end of its range: the range ends at the last station whose keel is still
    below STEM_KEEL_FRACTION of the draft (a raked forefoot forward of it is left to auxiliary
    sections or the bulb)."""
    L, T = data.lpp, data.draft
    st = [s for s in fp["sections"] if s["x"] >= L / 2 - 1e-9 * L and s["x"] <= L]
    if len(st) < 4:
        raise InvalidInput(f"{data.name}: {len(st)} stations between midships and the FP; expected at least 4")
    x = np.array([s["x"] for s in st])
    deep = np.flatnonzero(np.array([s["keel_z"] for s in st]) <= STEM_KEEL_FRACTION * T)
    x1 = min(L, float(x[deep[-1]]))
    st = [s for s in st if s["x"] <= x1]
    return st, x[: len(st)], x1


def _measured_curves(fp, st, fos_low, B, T) -> dict:
    """name: (value at each station, scale of its parallel tolerance or None for an angle).
    Where the flat side reaches below the DWL, the DWL and deck lie on it (within FLAT_TOL):
    they say so exactly, as the section design requires."""
    on_fos = ~np.isnan(fos_low) & (fos_low < T)
    return {
        "sac": (np.array([s["area"] for s in st]), max(fp["SAC"]["area"])),
        "dwl": (np.where(on_fos, B / 2, np.minimum([s["half_breadth_dwl"] for s in st], B / 2)), B / 2),
        "deck": (np.where(on_fos, B / 2, np.minimum([s["deck"][0] for s in st], B / 2)), B / 2),
        "profile": (np.array([s["keel_z"] for s in st]), T),
        "deck_angle": (np.array([_downward_angle(*s["deck_segment"]) for s in st]), None),
        "bottom_angle": (np.array([_downward_angle(*s["bottom_segment"]) for s in st]), None),
    }


def _curve_spec(x, f, scale, x0, x_end, L) -> dict:
    """One basic curve's description: its midship value, where its parallel part ends (f within
    PARALLEL_TOL of its scale, or 1 degree when scale is None), up to DESCRIPTION_POINTS interior
    points and its value at x_end; room for every condition and some freedom left for fairness."""
    tol = PARALLEL_TOL * scale if scale else 1.0
    n_flat = int(np.argmax(np.abs(f - f[0]) > tol)) if np.any(np.abs(f - f[0]) > tol) else len(f)
    flat_to = float(x[max(n_flat - 1, 0)])
    flat_to = min(max(flat_to, x0 + 1e-3 * L), x_end - 1e-2 * L)
    k = np.flatnonzero((x > flat_to + 1e-3 * L) & (x < x_end - 1e-3 * L))
    if len(k) > DESCRIPTION_POINTS:
        k = k[np.round(np.linspace(0, len(k) - 1, DESCRIPTION_POINTS)).astype(int)]
    return {"flat_to": flat_to, "value": float(f[0]), "yE": float(np.interp(x_end, x, f)),
            "points": [[float(x[i]), float(f[i])] for i in k], "n_control": len(k) + 9}


def _flat_of_side_spec(x, fos_low, T, top, x0, L) -> dict:
    """The flat side as a basic curve: its lower end at every station from midships on where the
    side is flat, rising to the deck where the flat side ends (fairlines.sections continues a
    curve that ends on the deck smoothly; one that ended lower would stop abruptly)."""
    ok = np.flatnonzero(~np.isnan(fos_low))
    ok = ok[: int(np.argmax(np.diff(np.append(ok, -9)) != 1)) + 1] if len(ok) else ok
    if len(ok) < 2 or ok[-1] + 1 >= len(x):
        return {"value": T, "flat_to": x0 + 1e-3 * L, "x_end": x0 + 2e-3 * L, "yE": T}
    end = float(x[ok[-1] + 1])
    f = np.where(np.arange(len(x)) <= ok[-1], np.nan_to_num(fos_low, nan=top), top)
    return _curve_spec(x, f, T, x0, end, L) | {"x_end": end, "yE": top}
