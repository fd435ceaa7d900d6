"""Fairness of a hull judged the way a naval architect reads a lines plan: on each cut curve by
itself (waterlines, buttocks, frames, diagonals), never against the design that produced it.

A cut's signed curvature (fl.plane_cut: analytic, from the surface's derivatives) is split into
lobes -- maximal stretches of one curvature sign. A lobe whose turning angle (the integral of
|k| ds over it) is below ``min_turn`` is a ripple too small to see on any drawing and is merged
into its neighbours; the cut's sign changes are the alternations between the lobes that remain.
So a straight or gently curved line counts no inflection from round-off, while a wobble (a small
S in a waterline) or a step in a buttock shows up as a pair of sign changes, and an S-shaped
frame as one or two. Each cut also carries its fairness energy (the bending energy int k^2 ds)
and its largest curvature; the lobes are the curvature comb in numbers.
"""

from __future__ import annotations

import math

import numpy as np

from . import _native

__all__ = ["MIN_TURN_DEG", "SMALL_LOBE_DEG", "cut_lobes", "judge_cut", "read_waterline", "diagonal_cut", "fairness_report"]

#: Turning angle (degrees) below which a curvature lobe is a ripple, not a feature: 0.1 deg is
#: a 1.7 mm sag over a metre, far under what a lines plan or a reflection line shows.
MIN_TURN_DEG = 0.1
#: A waterline's lobe turning less than this (degrees) between two others is a wobble: its
#: features (a run, an entrance, a rounded end on the centre plane, a bulb's nose) turn more.
SMALL_LOBE_DEG = 1.0
# Curvature below this fraction of a cut's largest counts as zero (straight stretches).
ZERO_CURVATURE = 1e-6
#: The report's diagonals, as a lines plan draws them: (height on the centre line as a fraction
#: of the largest breadth, angle below the horizontal going outboard, deg).
DIAGONALS = ((0.25, 45.0), (0.375, 45.0), (0.5, 45.0))


def _arc(points: np.ndarray) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])


def cut_lobes(points: np.ndarray, curvature: np.ndarray, min_turn_deg: float = MIN_TURN_DEG) -> list[dict]:
    """Lobes of a cut: [{start, end (arc length, m), sign, turn (deg), at (point of largest |k|)}],
    ripples under `min_turn_deg` merged away."""
    pts = np.asarray(points, dtype=float)
    k = np.asarray(curvature, dtype=float)
    if len(k) < 3:
        return []
    s = _arc(pts)
    floor = ZERO_CURVATURE * max(np.max(np.abs(k)), 1e-12)
    sign = np.where(k > floor, 1, np.where(k < -floor, -1, 0))
    # Trapezoid weights of |k| ds per sample.
    ds = np.diff(s)
    w = np.zeros_like(s)
    w[:-1] += 0.5 * ds
    w[1:] += 0.5 * ds
    lobes: list[dict] = []
    for i, sg in enumerate(sign):
        if sg == 0:
            continue
        if lobes and lobes[-1]["sign"] == sg:
            lob = lobes[-1]
        else:
            lob = {"sign": int(sg), "first": i, "turn": 0.0, "peak": 0.0, "at": i}
            lobes.append(lob)
        lob["last"] = i
        lob["turn"] += abs(k[i]) * w[i]
        if abs(k[i]) > lob["peak"]:
            lob["peak"], lob["at"] = abs(k[i]), i
    min_turn = math.radians(min_turn_deg)
    kept = [lob for lob in lobes if lob["turn"] >= min_turn]
    merged: list[dict] = []
    for lob in kept:
        if merged and merged[-1]["sign"] == lob["sign"]:
            m = merged[-1]
            m["last"], m["turn"] = lob["last"], m["turn"] + lob["turn"]
            if lob["peak"] > m["peak"]:
                m["peak"], m["at"] = lob["peak"], lob["at"]
        else:
            merged.append(dict(lob))
    return [{"start": float(s[m["first"]]), "end": float(s[m["last"]]), "sign": m["sign"],
             "turn_deg": math.degrees(m["turn"]), "at": pts[m["at"]].tolist(), "peak_curvature": float(m["peak"]),
             "first": int(m["first"]), "last": int(m["last"])}
            for m in merged]


def judge_cut(cut, min_turn_deg: float = MIN_TURN_DEG) -> dict:
    """One cut judged on its own: lobes, significant sign changes (with where they are),
    bending energy int k^2 ds (1/m) and the largest |k| (1/m)."""
    pts = np.asarray(cut.points)
    k = np.asarray(cut.curvature)
    lobes = cut_lobes(pts, k, min_turn_deg)
    changes = []
    for a, b in zip(lobes[:-1], lobes[1:]):
        # the inflection lies between the two lobes: the sample of least |k| there
        i = a["last"] + int(np.argmin(np.abs(k[a["last"]:b["first"] + 1])))
        changes.append({"at": pts[i].tolist(), "turns_deg": [a["turn_deg"], b["turn_deg"]]})
    return {"value": float(cut.value), "points": int(len(pts)), "lobes": lobes, "sign_changes": len(changes),
            "inflections": changes, "bending_energy": float(cut.bending_energy),
            "max_curvature": float(np.max(np.abs(k))) if len(k) else 0.0}


def read_waterline(cut, min_turn_deg: float = MIN_TURN_DEG, small_lobe_deg: float = SMALL_LOBE_DEG) -> dict:
    """A waterline (a z cut, fl.plane_cut) read as a naval architect reads it off a lines plan.
    Its lobes (judge_cut) that turn under `small_lobe_deg` between two others are wobbles; the
    others that curve toward the centre plane are hollows, counted in the aft and the fore half
    of its x extent. Fair: no wobble and at most one hollow in each half (a run and an
    entrance; a second is a step). A rounded end on the centre plane or a bulb's nose is a lobe
    like any other, so a low waterline's ends cost it nothing. Returns {"judged", "wobbles"
    (lobes), "hollows" (aft, fore), "step", "fair"}."""
    judged = judge_cut(cut, min_turn_deg)
    pts = np.asarray(cut.points)
    lobes = judged["lobes"]
    wobbles, hollows = [], [0, 0]
    if len(pts) >= 2:
        # marching toward +x, a half-breadth's hollow has positive curvature
        toward = 1 if pts[-1, 0] >= pts[0, 0] else -1
        middle = 0.5 * (pts[:, 0].min() + pts[:, 0].max())
        for k, lobe in enumerate(lobes):
            if lobe["turn_deg"] < small_lobe_deg and 0 < k < len(lobes) - 1:
                wobbles.append(lobe)
            elif lobe["sign"] * toward > 0:
                hollows[int(lobe["at"][0] >= middle)] += 1
    step = max(hollows) > 1
    return {"judged": judged, "wobbles": wobbles, "hollows": tuple(hollows), "step": step,
            "fair": not wobbles and not step}


def surface_extent(surface) -> tuple[np.ndarray, np.ndarray]:
    """Least and largest (x, y, z) of a surface, m, from a 41 x 81 sample of it."""
    g = np.asarray(surface.evaluate_grid(np.linspace(*surface.domain_u, 41), np.linspace(*surface.domain_v, 81))).reshape(-1, 3)
    return g.min(axis=0), g.max(axis=0)


class DiagonalCut:
    """A diagonal of a lines plan cut from a surface: the plane through the line z = z_c - y
    tan(angle) of the body plan, along the hull. ``points`` (n, 3) in the hull's frame,
    ``curvature`` (1/m, signed in the plane), ``bending_energy`` (int k^2 ds, 1/m), ``value``
    (z_c, m), ``angle`` (deg)."""

    def __init__(self, surface, z_centre: float, angle_deg: float, samples: int = 601):
        a = math.radians(angle_deg)
        c, s = math.cos(a), math.sin(a)
        # A rotation about x takes the diagonal's plane to z' = z_c cos(a): the engine's plane
        # cut of the rotated surface (rotation is exact on the control points) gives the curve
        # and its analytic curvature, which a rotation leaves unchanged.
        rot = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
        cp = np.asarray(surface.control_points) @ rot.T
        turned = _native.NurbsSurface(surface.degree_u, surface.degree_v, np.asarray(surface.knots_u),
                                      np.asarray(surface.knots_v), cp, np.asarray(surface.weights))
        cut = _native.plane_cut(turned, 2, float(z_centre * c), samples)
        pts = np.asarray(cut.points, dtype=float)
        self.points = pts @ rot if len(pts) else pts.reshape(0, 3)
        self.curvature = np.asarray(cut.curvature)
        self.bending_energy = float(cut.bending_energy)
        self.value, self.angle = float(z_centre), float(angle_deg)


def diagonal_cut(surface, z_centre: float, angle_deg: float = 45.0, samples: int = 601) -> DiagonalCut:
    """The diagonal through (y = 0, z = z_centre) of the body plan, falling outboard at
    `angle_deg` below the horizontal, cut from `surface` (see DiagonalCut)."""
    return DiagonalCut(surface, z_centre, angle_deg, samples)


def fairness_report(surface, draft: float, n_waterlines: int = 8, n_buttocks: int = 6, n_frames: int = 20,
                    samples: int = 601, min_turn_deg: float = MIN_TURN_DEG, z_max: float | None = None) -> dict:
    """Waterlines, buttocks, frames and diagonals cut from `surface` and judged on their own
    (judge_cut).

    Waterlines at equal spacing strictly between the lowest point and `z_max` (default the top
    of the surface), buttocks at fractions of the largest half-breadth, frames at equal x strictly
    inside the surface, the diagonals of DIAGONALS (a lines plan's). Returns {"waterline": [...],
    "buttock": [...], "frame": [...], "diagonal": [...], "summary"}.
    """
    lo, hi = surface_extent(surface)
    z_top = hi[2] if z_max is None else min(z_max, hi[2])
    plan = {
        "waterline": (2, np.linspace(max(lo[2], 0.0), z_top, n_waterlines + 2)[1:-1]),
        "buttock": (1, np.linspace(0.0, hi[1], n_buttocks + 2)[1:-1]),
        "frame": (0, np.linspace(lo[0], hi[0], n_frames + 2)[1:-1]),
    }
    report: dict = {"draft": draft, "min_turn_deg": min_turn_deg}
    for kind, (axis, values) in plan.items():
        report[kind] = []
        for v in values:
            cut = _native.plane_cut(surface, axis, float(v), samples)
            if len(cut.points) >= 3:
                report[kind].append(judge_cut(cut, min_turn_deg))
    report["diagonal"] = []
    for frac, angle in DIAGONALS:
        cut = diagonal_cut(surface, frac * 2.0 * hi[1], angle, samples)
        if len(cut.points) >= 3:
            judged = judge_cut(cut, min_turn_deg)
            judged["angle_deg"] = angle
            report["diagonal"].append(judged)
    report["summary"] = {kind: sum(c["sign_changes"] for c in report[kind])
                         for kind in ("waterline", "buttock", "frame", "diagonal")}
    return report
