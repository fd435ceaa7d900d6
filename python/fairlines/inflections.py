"""Which curvature sign changes of a hull's plane cuts does the shape call for? (issue 4, SPEC §5)

A waterline, buttock or frame cut from the skinned surface may change the sign of its curvature
only where the designed shape itself does. The designed shape is the set of section curves
(each the fairest curve meeting the basic curves at its station), so the judge works on them,
never on the surface:

* waterline z = c / buttock y = c: the sections cross the plane at one point each, (x_d, y_d) /
  (x_d, z_d). If two second divided differences of these station data have opposite signs,
  every C2 curve through the data must change the sign of its second derivative between them
  (f[x0, x1, x2] = f''(xi) / 2 for some xi in [x0, x2]): the inflection is called for. It is
  real when such a pair lies within ``window`` station spacings of it; otherwise the data keep
  one convexity (or are straight) there and the inflection is false (ringing or end effects).
* frame x = c: the two designed sections bracketing c. The inflection is called for when one of
  them changes its own curvature sign at a height within ``dz`` of the frame's (the flare's
  transition from concave above water to convex below), otherwise it is false.
"""

from __future__ import annotations

import numpy as np

__all__ = ["section_inflection_heights", "classify_cut"]

# Station data second divided differences smaller than this fraction of the largest on the
# same cut count as straight (the flats are exact: y = B/2, z = 0 up to root-finding round-off).
DATA_FLAT_REL = 1e-6
# A station-data convexity change within this many station spacings of a cut's inflection
# calls for it (a C2 curve through the data must inflect within the span of the triples).
WINDOW_STATIONS = 2.0
# Samples of a section when locating its plane crossings and its own inflections.
SECTION_SAMPLES = 4001
# Curvature below this fraction of the section's largest counts as straight (as plane_cut).
SECTION_FLAT_REL = 1e-6


def _crossing(section, axis: int, value: float) -> np.ndarray | None:
    """First point (from the deck) where the section crosses coordinate `axis` = value."""
    t = np.linspace(0.0, 1.0, SECTION_SAMPLES)
    lo_dom, hi_dom = section.domain
    t = lo_dom + (hi_dom - lo_dom) * t
    p = section.evaluate(t)
    f = p[:, axis] - value
    idx = np.nonzero((f[:-1] > 0) != (f[1:] > 0))[0]
    exact = np.nonzero(f == 0)[0]
    if len(exact) and (not len(idx) or exact[0] <= idx[0]):
        return p[exact[0]]
    if not len(idx):
        return None
    a, b = t[idx[0]], t[idx[0] + 1]
    fa = f[idx[0]]
    for _ in range(60):
        m = 0.5 * (a + b)
        fm = section.evaluate(np.array([m]))[0, axis] - value
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
    return section.evaluate(np.array([0.5 * (a + b)]))[0]


def section_inflection_heights(section) -> list[float]:
    """Heights z where a section's curvature in its (y, z) plane changes sign."""
    from . import _native

    c2 = _native.NurbsCurve(section.degree, section.knots, np.asarray(section.control_points)[:, 1:])
    lo_dom, hi_dom = c2.domain
    t = np.linspace(lo_dom, hi_dom, SECTION_SAMPLES)
    pts = c2.evaluate(t)
    if np.max(np.abs(pts[:, 0])) < 1e-9:
        return []  # the stem: a straight centre-line segment
    k = c2.curvature(t)
    kmax = np.max(np.abs(k))
    out, last_sign, last_i = [], 0, -1
    for i, ki in enumerate(k):
        if abs(ki) <= SECTION_FLAT_REL * kmax + 1e-12:
            continue
        sg = 1 if ki > 0 else -1
        if last_sign and sg != last_sign:
            out.append(float(0.5 * (pts[i, 1] + pts[last_i, 1])))
        last_sign, last_i = sg, i
    return out


def _station_data(sections, axis: int, value: float):
    """(x_d, f_d) of the sections' crossings with the plane: f = y for waterlines, z for buttocks."""
    other = 1 if axis == 2 else 2
    xs, fs = [], []
    for s in sections:
        p = _crossing(s, axis, value)
        if p is not None:
            xs.append(p[0])
            fs.append(p[other])
    return np.asarray(xs), np.asarray(fs)


def _second_differences(x: np.ndarray, f: np.ndarray):
    """Centres x_{d+1} and second divided differences f[x_d, x_{d+1}, x_{d+2}]."""
    if len(x) < 3:
        return np.zeros(0), np.zeros(0)
    d1 = np.diff(f) / np.diff(x)
    d2 = np.diff(d1) / (x[2:] - x[:-2])
    return x[1:-1], d2


def classify_cut(kind: str, value: float, inflections: np.ndarray, sections, station_x: np.ndarray,
                 dz: float) -> list[dict]:
    """For each inflection (x, y, z) of a cut: {"point", "real", "reason"}.

    `sections` the designed section curves in x order, `station_x` their stations, `dz` the
    height tolerance for frames (a section control spacing)."""
    out = []
    inflections = np.asarray(inflections, dtype=float).reshape(-1, 3)
    if not len(inflections):
        return out
    spacing = float(np.max(np.diff(station_x))) if len(station_x) > 1 else 0.0
    if kind in ("waterline", "buttock"):
        axis = 2 if kind == "waterline" else 1
        xd, fd = _station_data(sections, axis, value)
        centres, d2 = _second_differences(xd, fd)
        tol = DATA_FLAT_REL * (np.max(np.abs(d2)) if len(d2) else 0.0) + 1e-15
        name = "half-breadth" if kind == "waterline" else "height"
        keep = np.abs(d2) > tol
        cs, ds = centres[keep], d2[keep]
        # Each change of sign between consecutive non-straight second differences forces one
        # inflection of any C2 curve through the data, within the span of the two triples.
        changes = [(cs[i] - spacing, cs[i + 1] + spacing, i) for i in range(len(ds) - 1) if ds[i] * ds[i + 1] < 0]
        used = set()
        for p in inflections:
            match = next((c for c in changes if c[2] not in used and c[0] - (WINDOW_STATIONS - 1) * spacing <= p[0]
                          <= c[1] + (WINDOW_STATIONS - 1) * spacing), None)
            if match is not None:
                used.add(match[2])
                i = match[2]
                reason = (f"the designed sections' {name}s on this {kind} change convexity: second divided "
                          f"difference {ds[i]:+.3g} at x = {cs[i]:.2f} m, {ds[i + 1]:+.3g} at x = {cs[i + 1]:.2f} m, "
                          f"so every C2 curve through them inflects there")
                out.append({"point": p.tolist(), "real": True, "reason": reason})
                continue
            near = np.abs(cs - p[0]) <= WINDOW_STATIONS * spacing
            signs = {1 if d > 0 else -1 for d in ds[near]}
            sgn = ("straight" if not signs else "convex (f'' > 0)" if signs == {1} else "concave (f'' < 0)"
                   if signs == {-1} else "of both signs, but their sign change is already taken by another inflection")
            reason = (f"false: the designed sections' {name}s within {WINDOW_STATIONS:g} station spacings are "
                      f"{sgn}; the sign change is not in the data (ringing or an end effect of the skinning)")
            out.append({"point": p.tolist(), "real": False, "reason": reason})
        return out
    # frames: each inflection of a bracketing section may account for one of the frame's.
    k = int(np.searchsorted(station_x, value))
    bracket = [i for i in (k - 1, k) if 0 <= i < len(sections)]
    heights = {i: section_inflection_heights(sections[i]) for i in bracket}
    allowed = max((len(h) for h in heights.values()), default=0)
    used: set = set()
    for p in inflections:
        cands = [(abs(h - p[2]), i, j, h) for i in bracket for j, h in enumerate(heights[i])
                 if abs(h - p[2]) <= dz and (i, j) not in used]
        if cands and len(used) < allowed:
            _, i, j, h = min(cands)
            used.add((i, j))
            reason = (f"the designed section at x = {station_x[i]:.2f} m changes its curvature sign at z = {h:.2f} m "
                      f"(within {dz:.2f} m of this one): the frame between the stations follows it")
            out.append({"point": p.tolist(), "real": True, "reason": reason})
        else:
            found = "; ".join(f"x = {station_x[i]:.2f} m: {', '.join('%.2f' % h for h in heights[i]) or 'none'}" for i in bracket)
            reason = (f"false: the bracketing designed sections inflect at z = [{found}], none left within {dz:.2f} m "
                      f"(ringing of the common-knot refit or of the longitudinal curves)")
            out.append({"point": p.tolist(), "real": False, "reason": reason})
    return out
