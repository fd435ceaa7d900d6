"""The real hulls the CAD-exchange, lines-plan and curves-of-form tests use, each got through
one function here so that they can be repointed at another example in one place."""

from __future__ import annotations

import functools
import pathlib

import numpy as np

import fairlines as fl

ROOT = pathlib.Path(__file__).resolve().parents[2]

#: Principal particulars of the example ship (m).
EXAMPLE_PARTICULARS = dict(lpp=244.8, beam=32.25, draft=11.0, depth=19.0)


@functools.lru_cache(maxsize=None)
def example_hull():
    return fl.Hull.from_json(str(ROOT / "examples" / "container_ship.json"))


def example_hull_surface() -> fl.NurbsSurface:
    """The example bare hull (half hull, y >= 0)."""
    return example_hull().bare_hull_surface()


@functools.lru_cache(maxsize=None)
def example_composed_hull():
    """The example bare hull + bulb + blend composed into one closed half hull."""
    return example_hull().composed_hull()


def box_barge_surface(length: float, breadth: float, depth: float) -> fl.NurbsSurface:
    """Half box barge (y >= 0) laid out as the hull designer's surfaces: u girthwise from the
    deck edge down the side to the bilge corner (a knot, degree 1) and in to the centre
    plane, v along x from the AP (x = 0)."""
    b = 0.5 * breadth
    section = np.array([[b, depth], [b, 0.0], [0.0, 0.0]])
    cp = np.array([[[x, y, z] for x in (0.0, length)] for y, z in section])
    return fl.NurbsSurface(1, 1, [0, 0, 0.5, 1, 1], [0, 0, 1, 1], cp)


def wigley_surface(length: float = 100.0, breadth: float = 10.0, draft: float = 6.25,
                   depth: float = 10.0, n: int = 41) -> fl.NurbsSurface:
    """Wigley hull y = (B/2)(1 - (2x/L)^2)(1 - (z/T)^2) (x from -L/2 .. L/2, shifted to start
    at 0), fitted as a bicubic surface to depth: u from the deck down to the keel, v along x."""
    xs = np.linspace(0.0, length, n)
    zs = np.linspace(0.0, depth, 21)
    xi = 2.0 * xs / length - 1.0
    zeta = (zs - draft) / draft
    y = 0.5 * breadth * (1 - xi[:, None] ** 2) * (1 - zeta[None, :] ** 2)
    grid = np.stack([np.broadcast_to(xs[:, None], y.shape), y, np.broadcast_to(zs[None, :], y.shape)], axis=-1)
    grid = np.ascontiguousarray(grid.transpose(1, 0, 2)[::-1])
    return fl.fit_surface(grid, degree_u=3, degree_v=3).surface


@functools.lru_cache(maxsize=None)
def cruiser_stern_hull():
    """The example ship's particulars designed with a cruiser stern (aft edge on y = 0)."""
    d = example_hull().to_dict()["design"]
    return fl.design_hull(**{k: v for k, v in d.items() if v is not None and k not in ("name", "stern")}, stern="cruiser")
