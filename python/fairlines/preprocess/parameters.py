"""Form parameters read off rebuilt surfaces: sectional area curve, DWL, deck, keel profile,
flats of side and bottom, bow features."""

from __future__ import annotations

import numpy as np

from ..offsets import HullData, knuckles
from .integrate import half_breadth_at, polyline_area
from .sections import dense_samples, section_at


# A section point counts as on the flat of side / flat of bottom when within this fraction of
# B/2 of the maximum half-breadth, or of T of the keel.
FLAT_TOL = 0.005


# A station has a flat of bottom when it runs along the keel line over at least this fraction of B.
FOB_MIN_HALF_WIDTH = 0.02


# A forefoot reaching further below the baseline than this fraction of T is a sonar dome (a
# skinned bare hull may dip a little below the baseline between stations; that is not one).
DOME_MIN_DEPTH = 0.05


def section_parameters(pieces, draft, beam):
    """Per-section form parameters of one station cut into (y, z) polylines."""
    if not pieces:
        return None
    allp = np.concatenate(pieces)
    area = 2 * sum(polyline_area(p, draft) for p in pieces)
    ymax = allp[:, 0].max()
    keel = allp[:, 1].min()
    top = pieces[int(np.argmax([p[:, 1].max() for p in pieces]))]
    deck = top[np.argmax(top[:, 1])]
    bottom = pieces[int(np.argmin([p[:, 1].min() for p in pieces]))]
    # Flat of side: the height range over which the half-breadth stays within FLAT_TOL of B/2.
    fos = allp[allp[:, 0] >= (1 - FLAT_TOL) * beam / 2]
    # Flat of bottom: the half-width over which the section stays on the keel line.
    fob = allp[allp[:, 1] <= keel + FLAT_TOL * draft]
    d = np.diff(bottom[:2], axis=0)[0] if len(bottom) >= 2 else np.array([1.0, 0.0])
    d_top = np.diff(top[-2:], axis=0)[0] if len(top) >= 2 else np.array([0.0, 1.0])
    kn = [float(p[k, 1]) for p in pieces for k in knuckles(p)]
    return {
        "area": area, "half_breadth_dwl": max(half_breadth_at(p, draft) for p in pieces),
        "max_half_breadth": float(ymax), "keel_z": float(keel),
        "deck": [float(deck[0]), float(deck[1])],
        "fos_z": [float(fos[:, 1].min()), float(fos[:, 1].max())] if len(fos) else None,
        "fob_half_width": float(fob[:, 0].max()) if len(fob) else 0.0,
        "bottom_angle_deg": float(np.degrees(np.arctan2(d[1], d[0]))),
        "deck_angle_deg": float(np.degrees(np.arctan2(d_top[1], d_top[0]))),
        "area_coefficient": area / max(2 * ymax * (draft - keel), 1e-300) if ymax > 0 else 0.0,
        "knuckles_z": kn,
        "bottom_segment": [float(d[0]), float(d[1])], "deck_segment": [float(d_top[0]), float(d_top[1])],
    }


def _stations(surfaces, samples, xs, draft, beam, roles) -> list:
    """section_parameters of the stations at ``xs`` (those the surfaces cut), each with its x."""
    stations = []
    for x0 in xs:
        sp = section_parameters(section_at(surfaces, x0, roles=roles, samples=samples), draft, beam)
        if sp is not None:
            sp["x"] = float(x0)
            stations.append(sp)
    return stations


def _bow(surfaces, samples, pts, data: HullData, am, roles) -> dict:
    """The bow feature: a sonar dome (reaching below the baseline forward), a bulb (protruding
    beyond the FP below the waterline; Kracht's ratios measured on the section at the FP) or none."""
    L, B, T = data.lpp, data.beam, data.draft
    sub = pts[pts[:, 2] <= T]
    below_base = pts[(pts[:, 2] < -DOME_MIN_DEPTH * T) & (pts[:, 0] > 0.5 * L)]
    protrusion = float(sub[:, 0].max() - L) if len(sub) else 0.0
    bow = {"kind": "none"}
    if len(below_base):
        bow = {"kind": "sonar dome", "depth_below_baseline": float(-below_base[:, 2].min()),
               "x_aft_end": float(below_base[:, 0].min()), "x_fwd_end": float(below_base[:, 0].max())}
    elif protrusion > 0.005 * L:
        at_fp = section_at(surfaces, L, roles=roles, samples=samples)
        abt = 2 * sum(polyline_area(p, T) for p in at_fp)
        bulb_pts = sub[sub[:, 0] >= L]
        tip = bulb_pts[np.argmax(bulb_pts[:, 0])]
        bb = 2 * max((p[p[:, 1] <= 0.8 * T, 0].max() if np.any(p[:, 1] <= 0.8 * T) else 0.0) for p in at_fp) \
            if at_fp else 0.0
        bow = {"kind": "bulb", "c_lpr": protrusion / L, "c_bb": bb / B, "c_zb": float(tip[2]) / T,
               "c_abt": abt / am, "length_beyond_fp": protrusion}
    if "bulb" in (roles or []) and bow["kind"] != "bulb":
        bow["kind"] = "bulb"
    return bow


def form_parameters(surfaces, data: HullData, n_stations=41, roles=None) -> dict:
    """Basic curves and per-section parameters read off the rebuilt surfaces.

    Returns the SAC (x, area), DWL, deck and keel-profile curves at ``n_stations`` stations,
    the flat-of-side and flat-of-bottom extents, the end angles of the DWL and SAC, and the
    bow features found (bulb with Kracht's ratios, sonar dome)."""
    L, B, T = data.lpp, data.beam, data.draft
    samples = [dense_samples(s) for s in surfaces]
    pts = np.concatenate([g.reshape(-1, 3) for g in samples])
    x_aft, x_fwd = float(pts[:, 0].min()), float(pts[:, 0].max())
    xs = np.linspace(x_aft, x_fwd, n_stations)
    xs[0] += 1e-6 * L
    xs[-1] -= 1e-6 * L
    stations = _stations(surfaces, samples, xs, T, B, roles)
    x = np.array([s["x"] for s in stations])
    sac = np.array([s["area"] for s in stations])
    dwl = np.array([s["half_breadth_dwl"] for s in stations])
    fos_x = x[[s["fos_z"] is not None and s["fos_z"][0] <= T for s in stations]]
    fob_x = x[[s["fob_half_width"] >= FOB_MIN_HALF_WIDTH * B and s["keel_z"] <= FLAT_TOL * T for s in stations]]
    wet = dwl > 0
    xe, ye = x[wet], dwl[wet]
    # End angles of the DWL: half-angle of entrance (forward end) and of run (aft end), degrees.
    entrance = float(np.degrees(np.arctan2(ye[-2] - ye[-1], xe[-1] - xe[-2]))) if len(xe) > 2 else 0.0
    run = float(np.degrees(np.arctan2(ye[1] - ye[0], xe[1] - xe[0]))) if len(xe) > 2 else 0.0
    return {
        "SAC": {"x": x.tolist(), "area": sac.tolist(),
                "entrance_slope": float((sac[-2] - sac[-1]) / (x[-1] - x[-2])),
                "run_slope": float((sac[1] - sac[0]) / (x[1] - x[0]))},
        "DWL": {"x": x.tolist(), "half_breadth": dwl.tolist(), "entrance_angle_deg": entrance,
                "run_angle_deg": run},
        "deck": {"x": x.tolist(), "y": [s["deck"][0] for s in stations], "z": [s["deck"][1] for s in stations]},
        "profile": {"x": x.tolist(), "keel_z": [s["keel_z"] for s in stations],
                    "x_aft_end": x_aft, "x_fwd_end": x_fwd},
        "FOS": {"x_aft": float(fos_x.min()) if fos_x.size else None,
                "x_fwd": float(fos_x.max()) if fos_x.size else None},
        "FOB": {"x_aft": float(fob_x.min()) if fob_x.size else None,
                "x_fwd": float(fob_x.max()) if fob_x.size else None},
        "bow": _bow(surfaces, samples, pts, data, float(sac.max()), roles),
        "sections": stations,
    }
