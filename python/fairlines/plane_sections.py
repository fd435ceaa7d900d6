"""Every branch of the section of a (trimmed) NURBS surface by a plane n . p = c.

:func:`fl.plane_cut <fairlines.plane_cut>` follows one branch of an axis-aligned cut on a hull
laid out girthwise in u and lengthwise in v, with analytic curvature, for the fairness check.
A lines plan needs more: every branch (a buttock through a bulb crosses it twice), any
parameter layout (the bulb runs lengthwise in u and ends in a pole), inclined planes
(diagonals) and trimmed surfaces (a composed hull). This module contours the signed distance
f(u, v) = n . S(u, v) - c over a sample grid of the parameter domain (marching squares, a
saddle cell resolved by its centre value), puts each crossing exactly on the surface and the
plane by bisection of f along its grid edge, chains the crossings into polylines and keeps the
parts inside the trimming loops.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._native import InvalidInput, NurbsSurface

__all__ = ["Cut", "plane_sections", "boundary_curves", "domain_samples", "chain_segments", "even_odd_inside"]

#: Bisection steps for a crossing on a grid edge: the bracket shrinks by 2^-52 of the edge.
_BISECTION_STEPS = 52
#: Newton steps that bring a trimming-loop crossing back onto the plane.
_NEWTON_STEPS = 4


@dataclass(frozen=True)
class Cut:
    """One branch of a plane section: ``points`` (k, 3) metres on the surface and the plane,
    ``uv`` (k, 2) their parameters, ``closed`` when the branch is a loop."""

    points: np.ndarray
    uv: np.ndarray
    closed: bool = False


def _breaks(knots: np.ndarray, degree: int) -> np.ndarray:
    k = np.asarray(knots, float)
    return np.unique(k[degree:len(k) - degree])


def domain_samples(knots: np.ndarray, degree: int, per_span: int, minimum: int) -> np.ndarray:
    """Parameters: ``per_span`` per knot span (breakpoints included), at least ``minimum`` in all."""
    b = _breaks(knots, degree)
    per = max(per_span, int(np.ceil(minimum / max(len(b) - 1, 1))))
    t = [np.linspace(b[i], b[i + 1], per, endpoint=False) for i in range(len(b) - 1)]
    return np.concatenate(t + [b[-1:]])


def even_odd_inside(uv: np.ndarray, loops: list[np.ndarray]) -> np.ndarray:
    """True where a (u, v) point is inside an odd number of the loops (closed polygons)."""
    crossings = np.zeros(len(uv), int)
    for loop in loops:
        a = np.asarray(loop, float)
        b = np.roll(a, -1, axis=0)
        u, v = uv[:, :1], uv[:, 1:]
        crosses = (a[None, :, 1] > v) != (b[None, :, 1] > v)
        with np.errstate(divide="ignore", invalid="ignore"):
            ux = a[None, :, 0] + (v - a[None, :, 1]) * (b[None, :, 0] - a[None, :, 0]) / (b[None, :, 1] - a[None, :, 1])
        crossings += np.count_nonzero(crosses & (u < ux), axis=1)
    return crossings % 2 == 1


def _bisect_edges(surface, normal, offset, lo, hi, f_lo):
    """Roots of f on the parameter segments lo -> hi (m, 2) where f changes sign."""
    lo, hi, f_lo = lo.copy(), hi.copy(), f_lo.copy()
    for _ in range(_BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        fm = surface.evaluate(mid[:, 0], mid[:, 1]) @ normal - offset
        same = (fm >= 0) == (f_lo >= 0)
        lo[same], f_lo[same] = mid[same], fm[same]
        hi[~same] = mid[~same]
    return 0.5 * (lo + hi)


def _cell_segments(sign, f_centre, nu, nv):
    """Marching squares: pairs of edge ids joined in each cell. Edge ids: horizontal
    (u-direction) edge (i, j) -> i nv + j; vertical edge (i, j) -> H + i (nv - 1) + j."""
    H = (nu - 1) * nv
    segs = []
    a = sign[:-1, :-1]
    b = sign[1:, :-1]
    c = sign[1:, 1:]
    d = sign[:-1, 1:]
    n_cross = (a != b).astype(int) + (b != c) + (c != d) + (d != a)
    for i, j in zip(*np.nonzero(n_cross)):
        bottom, top = i * nv + j, i * nv + j + 1
        left, right = H + i * (nv - 1) + j, H + (i + 1) * (nv - 1) + j
        crossing = [e for e, on in ((bottom, a[i, j] != b[i, j]), (right, b[i, j] != c[i, j]),
                                    (top, d[i, j] != c[i, j]), (left, a[i, j] != d[i, j])) if on]
        if len(crossing) == 2:
            segs.append(tuple(crossing))
        elif len(crossing) == 4:
            if (f_centre[i, j] >= 0) == a[i, j]:
                segs += [(bottom, right), (top, left)]
            else:
                segs += [(left, bottom), (right, top)]
    return segs


def chain_segments(segs):
    """Polylines (lists of node ids) from undirected segments; each node has degree <= 2."""
    adj: dict[int, list[int]] = {}
    for p, q in segs:
        adj.setdefault(p, []).append(q)
        adj.setdefault(q, []).append(p)
    seen: set[int] = set()
    chains = []
    starts = [n for n, nb in adj.items() if len(nb) == 1] + list(adj)
    for s in starts:
        if s in seen:
            continue
        chain, prev, cur = [s], None, s
        seen.add(s)
        while True:
            nxt = [n for n in adj[cur] if n != prev and n not in seen]
            if not nxt:
                closed = len(chain) > 2 and s in adj[cur] and prev is not None
                break
            prev, cur = cur, nxt[0]
            chain.append(cur)
            seen.add(cur)
        chains.append((chain, closed))
    return chains


def _onto_plane(surface, normal, offset, uv):
    """Newton steps along the parameter-space gradient of f, keeping the points on the surface."""
    uv = uv.copy()
    for _ in range(_NEWTON_STEPS):
        D = surface.derivatives(uv[:, 0], uv[:, 1], 1)
        f = D[:, 0, 0] @ normal - offset
        g = np.column_stack([D[:, 1, 0] @ normal, D[:, 0, 1] @ normal])
        gg = np.einsum("ij,ij->i", g, g)
        ok = gg > 0
        uv[ok] -= (f[ok] / gg[ok])[:, None] * g[ok]
    return uv


def _trim(surface, normal, offset, chain_uv, closed, loops):
    """The parts of one chain inside the loops, each ending exactly on the loop boundary."""
    inside = even_odd_inside(chain_uv, loops)
    if inside.all():
        return [(chain_uv, closed)]
    if not inside.any():
        return []
    if closed:  # start at an outside point so that every inside run is contiguous
        k = int(np.argmin(inside))
        chain_uv, inside = np.roll(chain_uv, -k, axis=0), np.roll(inside, -k)
        chain_uv, inside = np.vstack([chain_uv, chain_uv[:1]]), np.append(inside, inside[0])
    # every transition at once: bisection on the segment, inside end kept in lo
    ks = np.flatnonzero(inside[1:] != inside[:-1]) + 1
    lo = np.where(inside[ks - 1][:, None], chain_uv[ks - 1], chain_uv[ks])
    hi = np.where(inside[ks - 1][:, None], chain_uv[ks], chain_uv[ks - 1])
    for _ in range(_BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        m_in = even_odd_inside(mid, loops)
        lo[m_in], hi[~m_in] = mid[m_in], mid[~m_in]
    ends = _onto_plane(surface, normal, offset, lo)
    out, run, j = [], [], 0
    for k in range(len(chain_uv)):
        if j < len(ks) and k == ks[j]:
            run.append(ends[j])
            j += 1
            if not inside[k]:
                out.append((np.array(run), False))
                run = []
        if inside[k]:
            run.append(chain_uv[k])
    if len(run) > 1:
        out.append((np.array(run), False))
    return [(r, c) for r, c in out if len(r) > 1]


def _refine(surface, normal, offset, uv, closed, times):
    """Each segment split ``times`` times: midpoints in (u, v) brought back onto the plane."""
    for _ in range(times):
        nxt = np.vstack([uv[1:], uv[:1]]) if closed else uv[1:]
        mid = _onto_plane(surface, normal, offset, 0.5 * (uv[:len(nxt)] + nxt))
        out = np.empty((len(uv) + len(mid), 2))
        out[0::2][:len(uv)] = uv
        out[1::2][:len(mid)] = mid
        uv = out
    return uv


def plane_sections(surface: NurbsSurface, normal, offset: float, *, loops=None, per_span: int = 8,
                   min_samples: int = 96, refine: int = 0) -> list[Cut]:
    """Every branch of the section of ``surface`` by the plane ``normal . p = offset``.

    normal       (3,) plane normal (need not be unit; the plane is normal . p = offset).
    offset       float, in the units of normal . p (metres for a unit normal).
    loops        None (the whole parameter domain) or a list of (k, 2) (u, v) trimming loops:
                 a point is kept when it lies inside an odd number of them.
    per_span     grid samples per knot span in each direction (>= 2); ``min_samples`` at
                 least in each direction. Branches narrower than a grid cell can be missed.
    refine       times each polyline segment is halved (the new points on the plane too).

    Returns a list of :class:`Cut`, points exactly on the surface and the plane (bisection on
    the grid edges; trimming-loop ends by Newton steps). Raises InvalidInput for a zero or
    non-finite normal, a non-finite offset or per_span < 2.
    """
    n = np.asarray(normal, float).reshape(-1)
    if n.shape != (3,) or not np.all(np.isfinite(n)) or not np.any(n):
        raise InvalidInput(f"normal is {normal!r}; expected a finite non-zero 3-vector")
    if not np.isfinite(offset):
        raise InvalidInput(f"offset is {offset!r}; expected a finite value")
    if int(per_span) < 2:
        raise InvalidInput(f"per_span is {per_span!r}; expected at least 2")
    us = domain_samples(surface.knots_u, surface.degree_u, int(per_span), int(min_samples))
    vs = domain_samples(surface.knots_v, surface.degree_v, int(per_span), int(min_samples))
    nu, nv = len(us), len(vs)
    f = surface.evaluate_grid(us, vs) @ n - offset
    sign = f >= 0
    um, vm = 0.5 * (us[:-1] + us[1:]), 0.5 * (vs[:-1] + vs[1:])
    f_centre = surface.evaluate_grid(um, vm) @ n - offset
    segs = _cell_segments(sign, f_centre, nu, nv)
    if not segs:
        return []
    nodes = sorted({e for s in segs for e in s})
    H = (nu - 1) * nv
    ids = np.array(nodes)
    horiz = ids < H
    i = np.where(horiz, ids // nv, (ids - H) // (nv - 1))
    j = np.where(horiz, ids % nv, (ids - H) % (nv - 1))
    lo = np.column_stack([us[i], vs[j]])
    hi = np.column_stack([np.where(horiz, us[np.minimum(i + 1, nu - 1)], us[i]),
                          np.where(horiz, vs[j], vs[np.minimum(j + 1, nv - 1)])])
    uv_nodes = _bisect_edges(surface, n, offset, lo, hi, f[i, j])
    where = {e: k for k, e in enumerate(nodes)}
    cuts = []
    for chain, closed in chain_segments(segs):
        uv = uv_nodes[[where[e] for e in chain]]
        parts = [(uv, closed)] if loops is None else _trim(surface, n, offset, uv, closed, list(loops))
        for part_uv, part_closed in parts:
            part_uv = _refine(surface, n, offset, part_uv, part_closed, int(refine))
            pts = surface.evaluate(part_uv[:, 0], part_uv[:, 1])
            cuts.append(Cut(np.asarray(pts), part_uv, part_closed))
    return cuts


def boundary_curves(surface: NurbsSurface, loops=None, *, per_span: int = 8,
                    min_samples: int = 96) -> list[np.ndarray]:
    """The surface's edges as (k, 3) polylines: the four domain edges, or the trimming loops
    when ``loops`` is given (each loop edge subdivided so that no step exceeds 1 / min_samples
    of the parameter domain)."""
    if loops is None:
        us = domain_samples(surface.knots_u, surface.degree_u, per_span, min_samples)
        vs = domain_samples(surface.knots_v, surface.degree_v, per_span, min_samples)
        g = surface.evaluate_grid(us, vs)
        return [g[0], g[-1], g[:, 0], g[:, -1]]
    out = []
    for loop in loops:
        a = np.asarray(loop, float)
        a = np.vstack([a, a[:1]])
        size = np.array([np.ptp(surface.domain_u), np.ptp(surface.domain_v)]) / min_samples
        pieces = []
        for k in range(len(a) - 1):
            steps = max(1, int(np.ceil(np.max(np.abs(a[k + 1] - a[k]) / size))))
            t = np.linspace(0.0, 1.0, steps, endpoint=False)
            pieces.append(a[k] + t[:, None] * (a[k + 1] - a[k]))
        uv = np.concatenate(pieces + [a[-1:]])
        out.append(np.asarray(surface.evaluate(uv[:, 0], uv[:, 1])))
    return out
