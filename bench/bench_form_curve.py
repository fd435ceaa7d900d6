"""Benchmark of the form-parameter curve solver.

Random parameter sets that are feasible by construction: a random fair section curve
(x monotone, y >= 0, cubic, 8 control points) is made first and all 11 of its form
parameters are requested. For every set we run

  * fl.design_curve (compiled Lagrange-Newton / SQP with continuation), and
  * SciPy SLSQP on the same problem (min E2, the same 11 equalities, the same linear
    section conditions on the control polygon, started from the same straight-line
    start curve), analytic gradient of E2, finite-difference constraint Jacobians.

A solve succeeds when every |achieved - requested| <= 1e-9 (angles in degrees) and the
control polygon is x-monotone with y >= 0. Prints success rates, median time per
solve and the time ratio, and the E2 of both where both succeed.

usage: python bench/bench_form_curve.py [--n 1000] [--seed 0] [--slsqp-n 100]
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

import fairlines as fl

NAMES = ("xB", "yB", "xE", "yE", "alphaB", "alphaE", "CAB", "CAE", "Area", "xC", "yC")
N_CONTROL, DEGREE = 8, 3


def random_section(rng: np.random.Generator) -> np.ndarray:
    """A random fair-looking section: x increasing, y > 0, smooth y profile."""
    while True:
        x = np.cumsum(rng.uniform(0.5, 1.5, N_CONTROL - 1))
        x = np.concatenate([[0.0], x / x[-1]])
        base = rng.uniform(0.3, 1.0)
        t = np.linspace(0, 1, N_CONTROL)
        y = base + rng.uniform(-0.4, 0.4) * t + rng.uniform(-0.3, 0.3) * np.sin(np.pi * t * rng.uniform(0.5, 2.0))
        y = y + rng.normal(0, 0.03, N_CONTROL)
        if y.min() <= 0.02:
            continue
        cps = np.column_stack([x, y])
        chord = np.linalg.norm(cps[-1] - cps[0])
        # end speeds |C'(0)|, |C'(1)| of a clamped uniform cubic: (p / dt) |P1 - P0|
        speed = DEGREE * (N_CONTROL - DEGREE) * np.array(
            [np.linalg.norm(cps[1] - cps[0]), np.linalg.norm(cps[-1] - cps[-2])]
        )
        if speed.min() < 0.3 * chord:
            continue
        return cps


def requested_params(cps: np.ndarray) -> dict:
    allp = fl.form_parameters_of(DEGREE, cps)
    return {k: allp[k] for k in NAMES}


class SlsqpProblem:
    """The same problem written for scipy.optimize.minimize(method='SLSQP')."""

    def __init__(self, n: int, p: int):
        from numpy.polynomial.legendre import leggauss
        from scipy.interpolate import BSpline

        self.n = n
        knots = np.asarray(fl.clamped_uniform_knots(n, p))
        g, w = leggauss(8)
        br = np.unique(knots)
        T = np.concatenate([(a + b) / 2 + (b - a) / 2 * g for a, b in zip(br[:-1], br[1:])])
        self.W = np.concatenate([(b - a) / 2 * w for a, b in zip(br[:-1], br[1:])])
        eye = np.eye(n)
        basis = [BSpline(knots, eye[i], p) for i in range(n)]
        self.N0 = np.array([b(T) for b in basis]).T
        self.N1 = np.array([b(T, nu=1) for b in basis]).T
        N2 = np.array([b(T, nu=2) for b in basis]).T
        self.K = (N2.T * self.W) @ N2
        self.D0 = np.array([[b(0.0, nu=d) for b in basis] for d in (1, 2)])
        self.D1 = np.array([[b(1.0, nu=d) for b in basis] for d in (1, 2)])

    def e2(self, z):
        x, y = z[: self.n], z[self.n :]
        return x @ self.K @ x + y @ self.K @ y

    def e2_grad(self, z):
        x, y = z[: self.n], z[self.n :]
        return np.concatenate([2 * self.K @ x, 2 * self.K @ y])

    def values(self, z, req):
        n = self.n
        x, y = z[:n], z[n:]
        X, Y, Xp = self.N0 @ x, self.N0 @ y, self.N1 @ x
        A = self.W @ (Y * Xp)
        My = self.W @ (X * Y * Xp)
        Mx = self.W @ (0.5 * Y * Y * Xp)
        out = [x[0] - req["xB"], y[0] - req["yB"], x[-1] - req["xE"], y[-1] - req["yE"]]
        for D, a, k in ((self.D0, req["alphaB"], req["CAB"]), (self.D1, req["alphaE"], req["CAE"])):
            x1, y1 = D[0] @ x, D[0] @ y
            x2, y2 = D[1] @ x, D[1] @ y
            ar = np.radians(a)
            out.append(-np.sin(ar) * x1 + np.cos(ar) * y1)
            out.append((x1 * y2 - y1 * x2) / (x1 * x1 + y1 * y1) ** 1.5 - k)
        out += [A - req["Area"], My - req["xC"] * A, Mx - req["yC"] * A]
        return np.array(out)

    def solve(self, req, z0):
        from scipy.optimize import minimize

        n = self.n
        G = np.zeros((2 * n - 1, 2 * n))
        for i in range(n - 1):
            G[i, i + 1], G[i, i] = 1.0, -1.0
        for i in range(n):
            G[n - 1 + i, n + i] = 1.0
        cons = [
            {"type": "eq", "fun": lambda z: self.values(z, req)},
            {"type": "ineq", "fun": lambda z: G @ z, "jac": lambda z: G},
        ]
        return minimize(self.e2, z0, jac=self.e2_grad, method="SLSQP", constraints=cons,
                        options={"maxiter": 500, "ftol": 1e-16})


def check(cps, req):
    got = fl.form_parameters_of(DEGREE, cps)
    err = 0.0
    for k in NAMES:
        d = got[k] - req[k]
        if k.startswith("alpha"):
            d = (d + 180) % 360 - 180
        err = max(err, abs(d))
    mono = bool(np.all(np.diff(cps[:, 0]) >= -1e-12) and np.all(cps[:, 1] >= -1e-12))
    return err, mono


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=1000, help="number of random parameter sets")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--slsqp-n", type=int, default=100,
                    help="run SLSQP on the first N sets (default 100: SLSQP takes ~1 s per set)")
    args = ap.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    sets = [requested_params(random_section(rng)) for _ in range(args.n)]

    fl.design_curve(sets[0])  # warm-up (first call loads tables)
    ok, times, e2_fl, fails = 0, [], {}, []
    for i, req in enumerate(sets):
        t0 = time.perf_counter()
        try:
            res = fl.design_curve(req)
            dt = time.perf_counter() - t0
            err, mono = check(res.control_points, req)
            if err <= 1e-9 and mono:
                ok += 1
                e2_fl[i] = res.fairness["E2"]
            else:
                fails.append((i, f"residual {err:.2e}, monotone {mono}"))
        except (ValueError, RuntimeError) as exc:
            dt = time.perf_counter() - t0
            fails.append((i, str(exc)[:120]))
        times.append(dt)
    med = float(np.median(times))
    print(f"fairlines.design_curve: {ok}/{args.n} solved ({100.0 * ok / args.n:.1f}%), "
          f"median {med * 1e3:.3f} ms, p90 {np.percentile(times, 90) * 1e3:.3f} ms, max {max(times) * 1e3:.1f} ms")
    for i, why in fails[:10]:
        print(f"  failed set {i}: {why}")

    n_s = args.n if args.slsqp_n is None else min(args.n, args.slsqp_n)
    if n_s <= 0:
        return 0 if ok == args.n else 1
    prob = SlsqpProblem(N_CONTROL, DEGREE)
    ok_s, times_s, better, worse, both = 0, [], 0, 0, 0
    for i, req in enumerate(sets[:n_s]):
        x0 = np.linspace(req["xB"], req["xE"], N_CONTROL)
        y0 = np.maximum(np.linspace(req["yB"], req["yE"], N_CONTROL), 0.05)
        t0 = time.perf_counter()
        r = prob.solve(req, np.concatenate([x0, y0]))
        times_s.append(time.perf_counter() - t0)
        cps = np.column_stack([r.x[:N_CONTROL], r.x[N_CONTROL:]])
        err, mono = check(cps, req)
        if err <= 1e-9 and mono:
            ok_s += 1
            if i in e2_fl:
                both += 1
                e2s = prob.e2(r.x)
                better += e2_fl[i] < e2s - 1e-9 * e2s
                worse += e2_fl[i] > e2s + 1e-6 * e2s
    med_s = float(np.median(times_s))
    print(f"scipy SLSQP:            {ok_s}/{n_s} solved ({100.0 * ok_s / n_s:.1f}%), median {med_s * 1e3:.3f} ms")
    med_same = float(np.median(times[:n_s]))
    print(f"fairlines on the same {n_s} sets: median {med_same * 1e3:.3f} ms")
    print(f"median time ratio SLSQP / fairlines (same sets, same run): {med_s / med_same:.1f}x")
    print(f"where both succeed ({both}): fairlines fairer (lower E2) in {better}, "
          f"SLSQP fairer by > 1e-6 relative in {worse}")
    return 0 if ok == args.n else 1


if __name__ == "__main__":
    sys.exit(main())
