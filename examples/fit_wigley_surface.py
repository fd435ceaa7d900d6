"""Fit a B-spline surface to points of a Wigley hull and report how close it is.

The Wigley hull y = B/2 (1 - (2x/L)^2)(1 - (z/T)^2) (x from midships, z depth below the
waterline) is sampled on a 61 x 21 grid of stations x waterlines, in the project's axes
(x forward from the aft end, z up from the baseline). The grid is interpolated and
approximated with fewer control points; deviations are measured at the data and,
independently, by closest points from a denser sampling of the exact hull.

    python examples/fit_wigley_surface.py --out out/
"""

import argparse
import pathlib

import numpy as np

import fairlines as fl
from fairlines.io import save_json, tessellate, write_obj

L, B, T = 100.0, 10.0, 6.25  # metres


def wigley_grid(n_x, n_z):
    x = np.linspace(-L / 2, L / 2, n_x)
    z = np.linspace(0.0, T, n_z)  # depth below the waterline
    X, Z = np.meshgrid(x, z, indexing="ij")
    Y = B / 2 * (1 - (2 * X / L) ** 2) * (1 - (Z / T) ** 2)
    return np.dstack([X + L / 2, Y, T - Z])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out", help="output folder (default: out)")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    grid = wigley_grid(61, 21)
    dense = wigley_grid(121, 41).reshape(-1, 3)
    print(f"Wigley hull L = {L} m, B = {B} m, T = {T} m: {grid.shape[0]} x {grid.shape[1]} offsets")
    print(f"  {'fit':<28s} {'control net':>12s} {'max dev at data':>16s} {'rms at data':>12s} {'max dev to hull':>16s}")
    results = {}
    for label, ncu, ncv in [("interpolation", None, None), ("least squares", 16, 8), ("least squares", 10, 6)]:
        fit = fl.fit_surface(grid, n_control_u=ncu, n_control_v=ncv)
        sample = dense[:: 7]
        hull_dev = max(np.linalg.norm(fit.surface.closest_point(p)[2] - p) for p in sample)
        nu, nv = fit.surface.shape
        print(f"  {label:<28s} {nu:>5d} x {nv:<5d} {fit.max_deviation * 1000:>13.4f} mm {fit.rms_deviation * 1000:>9.4f} mm"
              f" {hull_dev * 1000:>13.4f} mm")
        results[(nu, nv)] = fit
    best = results[(16, 8)].surface
    save_json(best, out / "wigley_surface.json")
    write_obj(out / "wigley_surface.obj", *tessellate(best, 121, 41))
    print(f"  wrote {out / 'wigley_surface.json'} and {out / 'wigley_surface.obj'}")


if __name__ == "__main__":
    main()
