"""NURBS core: scattered-point and grid evaluation of a bicubic 40 x 40 surface, points/s
on one core, against geomdl and a plain vectorised numpy implementation of the same
B-spline surface, all measured in this run on the same input."""

import common  # noqa: F401  (sets single-thread BLAS before numpy loads)
import numpy as np
from geomdl import BSpline

import fairlines as fl
from common import median_time, report

N = 40
P = 3


def make_surface(rng):
    knots = fl.clamped_uniform_knots(N, P)
    g = np.linspace(0, 1, N)
    U, V = np.meshgrid(g, g, indexing="ij")
    net = np.dstack([U * 200.0, V * 30.0, 10 * np.sin(3 * U) * np.cos(2 * V) + rng.normal(0, 0.1, U.shape)])
    return knots, net


def numpy_basis(knots, t):
    """All cubic basis values at t: (len(t), N) by vectorised Cox-de Boor."""
    spans = np.clip(np.searchsorted(knots, t, side="right") - 1, P, N - 1)
    B = np.zeros((len(t), P + 1))
    B[:, 0] = 1.0
    left = np.zeros((len(t), P + 1))
    right = np.zeros((len(t), P + 1))
    for j in range(1, P + 1):
        left[:, j] = t - knots[spans + 1 - j]
        right[:, j] = knots[spans + j] - t
        saved = np.zeros(len(t))
        for r in range(j):
            temp = B[:, r] / (right[:, r + 1] + left[:, j - r])
            B[:, r] = saved + right[:, r + 1] * temp
            saved = left[:, j - r] * temp
        B[:, j] = saved
    return spans, B


def numpy_scattered(knots, net, u, v):
    su, Bu = numpy_basis(knots, u)
    sv, Bv = numpy_basis(knots, v)
    iu = su[:, None] - P + np.arange(P + 1)
    iv = sv[:, None] - P + np.arange(P + 1)
    ctrl = net[iu[:, :, None], iv[:, None, :]]  # (m, 4, 4, 3)
    return np.einsum("ma,mb,mabc->mc", Bu, Bv, ctrl)


def numpy_grid(knots, net, us, vs):
    def dense(t):
        s, B = numpy_basis(knots, t)
        D = np.zeros((len(t), N))
        np.put_along_axis(D, s[:, None] - P + np.arange(P + 1), B, axis=1)
        return D

    Du, Dv = dense(us), dense(vs)
    return np.einsum("ai,ijc,bj->abc", Du, net, Dv, optimize=True)


def main():
    rng = np.random.default_rng(1)
    knots, net = make_surface(rng)
    surf = fl.NurbsSurface(P, P, knots, knots, net)
    m = 1_000_000
    u, v = rng.random(m), rng.random(m)
    side = 1000
    us, vs = np.linspace(0, 1, side), np.linspace(0, 1, side)

    # Agreement first: the peers compute the same surface.
    ref = numpy_scattered(knots, net, u[:1000], v[:1000])
    assert np.abs(surf.evaluate(u[:1000], v[:1000]) - ref).max() < 1e-9
    assert np.abs(surf.evaluate_grid(us[:50], vs[:60]) - numpy_grid(knots, net, us[:50], vs[:60])).max() < 1e-9

    gd = BSpline.Surface()
    gd.degree_u = gd.degree_v = P
    gd.ctrlpts_size_u = gd.ctrlpts_size_v = N
    gd.ctrlpts = net.reshape(-1, 3).tolist()
    gd.knotvector_u = knots.tolist()
    gd.knotvector_v = knots.tolist()
    mg = 2000
    pairs = list(zip(u[:mg].tolist(), v[:mg].tolist()))
    gd_pts = np.array([gd.evaluate_single(p) for p in pairs[:100]])
    assert np.abs(gd_pts - ref[:100]).max() < 1e-9

    t_ours_sc = median_time(lambda: surf.evaluate(u, v), repeat=5)
    t_ours_gr = median_time(lambda: surf.evaluate_grid(us, vs), repeat=5)
    t_np_sc = median_time(lambda: numpy_scattered(knots, net, u[:100_000], v[:100_000]), repeat=5) * 10
    t_np_gr = median_time(lambda: numpy_grid(knots, net, us, vs), repeat=5)
    t_gd = median_time(lambda: [gd.evaluate_single(p) for p in pairs], repeat=3, min_time=0.2) * (m / mg)

    rate = lambda t: m / t / 1e6  # noqa: E731  (M points/s)
    print("NURBS core: bicubic 40 x 40 surface, one core, 1,000,000 points")
    report("fairlines scattered evaluate", rate(t_ours_sc), "M pts/s", "(goal >= 20)")
    report("fairlines grid evaluate_grid (1000 x 1000)", rate(t_ours_gr), "M pts/s", "(goal >= 100)")
    report("numpy vectorised scattered", rate(t_np_sc), "M pts/s", f"fairlines/numpy = {t_np_sc / t_ours_sc:.1f}x")
    report("numpy dense-basis grid (einsum)", rate(t_np_gr), "M pts/s", f"fairlines/numpy = {t_np_gr / t_ours_gr:.1f}x")
    report("geomdl evaluate_single (scattered)", rate(t_gd), "M pts/s", f"fairlines/geomdl = {t_gd / t_ours_sc:,.0f}x")

    # Rational surface: same net with non-unit weights.
    w = rng.uniform(0.5, 2.0, (N, N))
    rs = fl.NurbsSurface(P, P, knots, knots, net, w)
    report("fairlines scattered evaluate, rational", rate(median_time(lambda: rs.evaluate(u, v), repeat=5)), "M pts/s")
    report("fairlines grid evaluate, rational", rate(median_time(lambda: rs.evaluate_grid(us, vs), repeat=5)), "M pts/s")


if __name__ == "__main__":
    main()
