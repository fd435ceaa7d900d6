"""Geometry moved from Python into the engine, each call against the Python it replaced
(bench/python_peers.py) in the same process, medians: Kracht measurement of the composed
container ship's mesh, surface hydrostatics of the imported Series 60 (one rebuilt patch),
and the deviation report's projection of grid points (the KCS afterbody). The figures'
differences are printed beside the times."""

import os
import pathlib
import sys

import common  # noqa: F401  (one BLAS thread per process)
import numpy as np
from common import median_time, report

import python_peers as peers

DATA = pathlib.Path(os.environ.get("FAIRLINES_DATA", pathlib.Path(__file__).resolve().parents[2] / "shared" / "data"))


def difference(name: str, value: float) -> None:
    print(f"  {name:<58s} {value:>14.1e}")


def kracht(fl) -> None:
    hull = fl.Hull.from_json(os.path.join(os.path.dirname(__file__), "..", "examples", "container_ship.json"))
    bulb = hull.bulbous_bow()
    mesh = hull.composed_hull(bulb=bulb).mesh
    ship = bulb.ship
    engine, python = fl.measure_kracht(mesh, **ship), peers.python_measure_kracht(mesh, **ship)
    report("Kracht of the composed ship: engine", 1e3 * median_time(lambda: fl.measure_kracht(mesh, **ship)), "ms")
    report("Kracht: Python loop (peer)", 1e3 * median_time(lambda: peers.python_measure_kracht(mesh, **ship),
                                                           repeat=3), "ms")
    difference("Kracht: largest coefficient difference", max(abs(engine[k] - python[k]) for k in engine))


def series60_quadrature(fl) -> None:
    lpp = 121.92
    beam, draft = lpp / 6.5, lpp / 6.5 / 2.5
    data = fl.offsets.read_offsets_csv(DATA / "series60_cb080_offsets.csv", lpp, beam, draft)
    rb = fl.preprocess.rebuild(data, deviation=False)
    args = (rb.surfaces, draft, lpp, beam)
    engine = fl.preprocess.surface_hydrostatics(*args, roles=rb.roles)
    python = peers.python_surface_hydrostatics(*args, roles=rb.roles)
    t_e = median_time(lambda: fl.preprocess.surface_hydrostatics(*args, roles=rb.roles), repeat=5)
    t_p = median_time(lambda: peers.python_surface_hydrostatics(*args, roles=rb.roles), repeat=5)
    report("Series 60 surface hydrostatics: engine", 1e3 * t_e, "ms")
    report("Series 60 surface hydrostatics: Python quadrature (peer)", 1e3 * t_p, "ms")
    difference("Series 60 volume: engine / Python - 1", engine.volume / python.volume - 1)


def kcs_projection(fl) -> None:
    data = fl.offsets.read_kcs(DATA / "kcs")
    rb = fl.preprocess.rebuild(data, deviation=False)
    s, g = rb.surfaces[3], data.grids[3].points.reshape(-1, 3)
    uv = np.array([s.closest_point(p)[:2] for p in g[::7]])
    pts, u0, v0 = g[::7], uv[:, 0] + 1e-3, uv[:, 1] - 1e-3
    d_e = np.linalg.norm(fl.preprocess.project_points(s, pts, u0, v0) - pts, axis=1)
    d_p = np.linalg.norm(peers.python_project_points(s, pts, u0, v0) - pts, axis=1)
    report(f"KCS afterbody, {len(pts)} points projected: engine",
           1e3 * median_time(lambda: fl.preprocess.project_points(s, pts, u0, v0)), "ms")
    report("projection: Python Gauss-Newton (peer)",
           1e3 * median_time(lambda: peers.python_project_points(s, pts, u0, v0)), "ms")
    difference("projection: largest distance difference (m)", float(np.abs(d_e - d_p).max()))


def main() -> int:
    import fairlines as fl

    print(f"load average {os.getloadavg()[0]:.2f}")
    kracht(fl)
    series60_quadrature(fl)
    kcs_projection(fl)
    return 0


if __name__ == "__main__":
    sys.exit(main())
