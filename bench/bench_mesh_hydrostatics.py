"""Mesh hydrostatics of the composed container ship (bare hull + bulb + blend) at its draft:
the engine's fl.hydrostatics_of_mesh against the per-triangle Python loop that the sweep and
the lines plan used before (bench/python_peers.py), in one process."""

import os
import sys

import common  # noqa: F401  (one BLAS thread per process)
from common import median_time, report

from python_peers import python_mesh_hydrostatics


def main() -> int:
    import fairlines as fl

    hull = fl.Hull.from_json(os.path.join(os.path.dirname(__file__), "..", "examples", "container_ship.json"))
    mesh = hull.composed_hull(bulb=hull.bulbous_bow()).mesh
    draft = hull.description.principal.draft
    print(f"composed container ship: {len(mesh.faces)} triangles; load average {os.getloadavg()[0]:.2f}")
    engine = fl.hydrostatics_of_mesh(mesh.vertices, mesh.faces, draft)
    loop = python_mesh_hydrostatics(mesh, draft)
    t_engine = median_time(lambda: fl.hydrostatics_of_mesh(mesh.vertices, mesh.faces, draft))
    t_loop = median_time(lambda: python_mesh_hydrostatics(mesh, draft), repeat=3)
    report("engine mesh_hydrostatics (C++)", 1e3 * t_engine, "ms")
    report("per-triangle Python loop (peer, same process)", 1e3 * t_loop, "ms")
    report("speed-up", t_loop / t_engine, "x")
    report("volume difference engine - loop (relative)", abs(engine.volume - loop["volume"]) / loop["volume"], "")
    return 0


if __name__ == "__main__":
    sys.exit(main())
