"""Shared helpers of the import tests: the four reference ships, read, imported (once per
session) and built, with their independent truths (published particulars or exact geometry)."""

from __future__ import annotations

import functools
import pathlib

import numpy as np

import fairlines as fl
from fairlines.import_design import fidelity
from fairlines.offsets import read_hull_data

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT.parent / "shared" / "data"
WIGLEY = dict(lpp=100.0, beam=10.0, draft=6.25)
# Series 60 Cb 0.80 parent at 400 ft (Todd 1963: L/B 7.5, B/T 2.5).
SERIES60 = dict(lpp=121.92, beam=16.256, draft=6.5024)
DTMB_SCALE = 24.83

SHIPS = ("wigley_table", "series60", "kcs", "dtmb5415")


def wigley_wetted_surface(lpp: float, beam: float, draft: float, n: int = 400) -> float:
    """Both sides' area of y = (B/2)(1 - (2 xi/L)^2)(1 - (zeta/T)^2) below the waterline, by
    Gauss-Legendre quadrature of sqrt(1 + y_x^2 + y_z^2)."""
    g, w = np.polynomial.legendre.leggauss(n)
    xi, wx = g * lpp / 2, w * lpp / 2
    zeta, wz = (g + 1) * draft / 2, w * draft / 2
    X, Z = np.meshgrid(xi, zeta, indexing="ij")
    yx = beam / 2 * (-8 * X / lpp**2) * (1 - (Z / draft) ** 2)
    yz = beam / 2 * (1 - (2 * X / lpp) ** 2) * (-2 * Z / draft**2)
    return float(2 * np.einsum("i,j,ij->", wx, wz, np.sqrt(1 + yx**2 + yz**2)))


def _area_below(tri: np.ndarray, level: float) -> np.ndarray:
    """Area of the part of each triangle (n, 3, 3) at or below z = level, exactly: with its
    heights sorted a <= b <= c the plane cuts off a triangle similar along both edges from the
    lowest (or the highest) vertex, so the share below is (L - a)^2 / ((b - a)(c - a)) while
    L <= b, and 1 - (c - L)^2 / ((c - a)(c - b)) above b."""
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    a, b, c = np.sort(tri[:, :, 2], axis=1).T
    with np.errstate(divide="ignore", invalid="ignore"):
        low = (level - a) ** 2 / ((b - a) * (c - a))
        high = 1.0 - (c - level) ** 2 / ((c - a) * (c - b))
    share = np.where(level <= a, 0.0, np.where(level >= c, 1.0, np.where(level <= b, low, high)))
    return area * share


def data_wetted_surface(data) -> float:
    """The data's own wetted surface at T (both sides): every grid's quads split into two
    triangles (along the shorter diagonal) and clipped at z = T. Flat facets cut the hull's
    curvature by chords, so this is a little (about 0.1 % on 80 x 61 grids) below the surface's."""
    return 2.0 * float(sum(_area_below(_triangles(g.points), data.draft).sum() for g in data.grids))


def _triangles(P: np.ndarray) -> np.ndarray:
    """A grid's quads (m, n, 3) split into two triangles along the shorter diagonal, (k, 3, 3),
    each keeping the quad's orientation."""
    a, b, c, d = P[:-1, :-1], P[1:, :-1], P[1:, 1:], P[:-1, 1:]
    short = (np.linalg.norm(a - c, axis=-1) <= np.linalg.norm(b - d, axis=-1))[..., None, None]
    t1 = np.where(short, np.stack([a, b, c], -2), np.stack([a, b, d], -2)).reshape(-1, 3, 3)
    t2 = np.where(short, np.stack([a, c, d], -2), np.stack([b, c, d], -2)).reshape(-1, 3, 3)
    return np.concatenate([t1, t2])


def _y_flux_below(tri: np.ndarray, level: float) -> np.ndarray:
    """int y n_y dA over the part of each triangle (n, 3, 3) at or below z = level, n the
    (unit) normal of the triangle's own orientation: y's mean over that part times its area
    vector's y. With the heights sorted a <= b <= c the part is the triangle cut off at the
    lowest vertex (sides s = (L - a)/(b - a), t = (L - a)/(c - a) of its edges) while L <= b, and
    the whole less the one cut off at the highest above."""
    area_y = 0.5 * np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])[:, 1]
    order = np.argsort(tri[:, :, 2], axis=1)
    A, B, C = (np.take_along_axis(tri, order[:, k, None, None], axis=1)[:, 0] for k in range(3))
    a, b, c = A[:, 2], B[:, 2], C[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        s, t = (level - a) / (b - a), (level - a) / (c - a)
        low = s * t * (A[:, 1] + (A[:, 1] + s * (B[:, 1] - A[:, 1])) + (A[:, 1] + t * (C[:, 1] - A[:, 1]))) / 3
        u, v = (c - level) / (c - a), (c - level) / (c - b)
        top = u * v * (C[:, 1] + (C[:, 1] + u * (A[:, 1] - C[:, 1])) + (C[:, 1] + v * (B[:, 1] - C[:, 1]))) / 3
    whole = tri[:, :, 1].mean(axis=1)
    mean_times_share = np.where(level <= a, 0.0, np.where(level >= c, whole, np.where(level <= b, low, whole - top)))
    return area_y * mean_times_share


def data_volume(data) -> float:
    """The data's own displaced volume at T (both sides): the flux of (0, y, 0) through every
    grid's triangles (as data_wetted_surface's) clipped at z = T. The centre plane, the
    waterplane and a transom plane x = const carry no flux of it. Flat facets cut a convex hull
    by chords, so this is a little below the surface's."""
    return 2.0 * abs(sum(float(_y_flux_below(_triangles(g.points), data.draft).sum()) for g in data.grids))


def wigley_table_csv(folder: pathlib.Path, blank: dict, drop: tuple = ()) -> pathlib.Path:
    """The typed Wigley table (tests/data/wigley_offsets_mm.csv) with the cells {station label:
    [column headers]} blanked and the columns `drop` left out, written into `folder`."""
    src = (ROOT / "tests" / "data" / "wigley_offsets_mm.csv").read_text().splitlines()
    cols = next(line for line in src if not line.startswith("#")).split(",")
    keep = [k for k, c in enumerate(cols) if c not in drop]
    out = []
    for line in src:
        if not line.startswith("#"):
            cells = line.split(",")
            line = ",".join("" if cols[k] in blank.get(cells[0], ()) else cells[k] for k in keep)
        out.append(line)
    path = folder / "wigley_blanks.csv"
    path.write_text("\n".join(out) + "\n")
    return path


def truth(ship: str) -> dict:
    """Independent truth: volume (m^3), LCB (m from the AP), wetted surface (m^2, None when
    no published figure), Lpp, B."""
    if ship == "wigley_table":
        L, B, T = WIGLEY.values()
        return {"volume": 4 / 9 * L * B * T, "lcb": L / 2, "wetted_surface": wigley_wetted_surface(L, B, T), "lpp": L, "beam": B}
    if ship == "series60":
        L, B, T = SERIES60.values()
        return {"volume": 0.80 * L * B * T, "lcb": L / 2 + 0.025 * L, "wetted_surface": None, "lpp": L, "beam": B}
    if ship == "kcs":
        return {"volume": 52030.0, "lcb": 115.0 - 0.0148 * 230.0, "wetted_surface": 9424.0, "lpp": 230.0, "beam": 32.2}
    L = 5.719
    return {"volume": 0.554, "lcb": L / 2 - 0.00683 * L, "wetted_surface": 2972.6 / DTMB_SCALE**2, "lpp": L, "beam": 0.768}


def read(ship: str):
    """The ship's HullData."""
    if ship == "wigley_table":
        return read_hull_data(ROOT / "tests" / "data" / "wigley_offsets_mm.csv", **WIGLEY)
    if ship == "series60":
        return read_hull_data(DATA / "series60_cb080_offsets.csv", **SERIES60)
    return read_hull_data(DATA / ("kcs" if ship == "kcs" else "dtmb5415"))


@functools.cache
def imported(ship: str) -> dict:
    """fl.import_design of the ship (computed once per session; callers must not edit it)."""
    return fl.import_design(read(ship))


@functools.cache
def rebuilt(ship: str) -> dict:
    """fidelity of the hull fl.Hull.from_json builds from the imported description's JSON."""
    import json

    return fidelity(fl.Hull.from_json(json.dumps(imported(ship))), read(ship))
