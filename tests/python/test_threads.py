"""Engine calls from several Python threads at once give the same results as serial calls.

The bindings release the GIL inside surface evaluation, fitting and the form-curve solver,
so these calls really run concurrently; the engine keeps no mutable shared state."""

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import fairlines as fl

THREADS = 4
TABLE3 = {"xB": 0.0, "yB": 1.0, "xE": 1.0, "yE": 0.33, "alphaB": -5.0, "alphaE": -85.0, "Area": 0.80, "xC": 0.43}


@pytest.fixture(scope="module")
def surface():
    rng = np.random.default_rng(11)
    n = 20
    g = np.linspace(0, 1, n)
    U, V = np.meshgrid(g, g, indexing="ij")
    net = np.dstack([U * 100, V * 10, np.sin(3 * U) * np.cos(2 * V) + rng.normal(0, 0.01, U.shape)])
    k = fl.clamped_uniform_knots(n, 3)
    return fl.NurbsSurface(3, 3, k, k, net, rng.uniform(0.5, 2.0, (n, n)))


def jobs(surface):
    """Independent calls, each returning arrays, keyed by a name."""
    rng = np.random.default_rng(5)
    u, v = rng.uniform(0, 1, 200_000), rng.uniform(0, 1, 200_000)
    grid = surface.evaluate_grid(np.linspace(0, 1, 30), np.linspace(0, 1, 25))
    return {
        "evaluate": lambda: surface.evaluate(u, v),
        "evaluate_grid": lambda: surface.evaluate_grid(np.linspace(0, 1, 400), np.linspace(0, 1, 300)),
        "derivatives": lambda: surface.derivatives(u[:20000], v[:20000], 1),
        "fit_surface": lambda: fl.fit_surface(grid, n_control_u=12, n_control_v=10).surface.control_points,
        "design_curve": lambda: fl.design_curve(TABLE3).control_points,
        "design_curve_points": lambda: fl.design_curve(TABLE3, n_control=10, points=[(0.5, 0.75)]).control_points,
    }


def test_concurrent_calls_equal_serial_calls(surface):
    work = jobs(surface)
    serial = {name: call() for name, call in work.items()}
    names = [name for name in work for _ in range(THREADS)]
    with ThreadPoolExecutor(max_workers=THREADS) as pool:
        results = list(pool.map(lambda name: (name, work[name]()), names))
    for name, value in results:
        np.testing.assert_array_equal(value, serial[name], err_msg=name)
