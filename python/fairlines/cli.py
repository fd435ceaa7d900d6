"""The `fairlines` command line.

    fairlines version
    fairlines fit POINTS.csv [--degree 3] [--n-control N] [--parameterization chord] -o curve.json
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from . import __version__, fit_curve
from .io import save_json


def _fit(args) -> int:
    try:
        pts = np.loadtxt(args.points, delimiter=",", ndmin=2)
    except (OSError, ValueError) as exc:
        print(f"fairlines fit: cannot read {args.points}: {exc}", file=sys.stderr)
        return 2
    fit = fit_curve(pts, degree=args.degree, n_control=args.n_control, parameterization=args.parameterization,
                    knots=args.knots)
    print(f"{len(pts)} points, {fit.curve.n_control} control points, degree {fit.curve.degree}: "
          f"max deviation {fit.max_deviation:.6g}, rms {fit.rms_deviation:.6g} (units of the input)")
    if args.output:
        save_json(fit.curve, args.output)
        print(f"wrote {args.output}")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="fairlines", description="Fair parametric hull design.")
    sub = ap.add_subparsers(dest="command", required=True)
    sub.add_parser("version", help="print the version")
    f = sub.add_parser("fit", help="fit a B-spline curve to points (CSV, one point per row)")
    f.add_argument("points")
    f.add_argument("--degree", type=int, default=3)
    f.add_argument("--n-control", type=int, default=None, help="control points (default: interpolate)")
    f.add_argument("--parameterization", default="chord", choices=["chord", "centripetal", "uniform"])
    f.add_argument("--knots", default="average", choices=["average", "hartley_judd"])
    f.add_argument("-o", "--output", help="write the curve as JSON")
    args = ap.parse_args(argv)
    try:
        if args.command == "version":
            print(__version__)
            return 0
        return _fit(args)
    except ValueError as exc:  # bad input: a one-line message, no traceback
        print(f"fairlines {args.command}: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
