"""Curve and surface fitting: options, reported deviations, convergence order."""

import numpy as np
import pytest

import fairlines as fl


def analytic(m):
    s = np.linspace(0, np.pi / 2, m)
    return np.c_[3 * np.cos(s) + 0.2 * np.sin(3 * s), 1.5 * np.sin(s)]


def dense_error(curve):
    pts = analytic(600)
    return max(np.linalg.norm(curve.closest_point(p)[1] - p) for p in pts)


@pytest.mark.parametrize("parameterization", ["chord", "centripetal", "uniform"])
@pytest.mark.parametrize("knots", ["average", "hartley_judd"])
def test_interpolation_hits_every_point(parameterization, knots):
    fit = fl.fit_curve(analytic(30), degree=3, parameterization=parameterization, knots=knots)
    assert fit.max_deviation <= 1e-12
    assert fit.rms_deviation <= fit.max_deviation
    assert np.abs(fit.curve.evaluate(fit.params) - analytic(30)).max() <= 1e-12


def test_interpolation_converges_at_order_four():
    errors = [dense_error(fl.fit_curve(analytic(m)).curve) for m in (9, 17, 33, 65)]
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert (rates > 3.3).all(), (errors, rates)


def test_least_squares_converges_and_reports_deviation():
    pts = analytic(500)
    prev = None
    for n in (6, 12, 24):
        fit = fl.fit_curve(pts, degree=3, n_control=n)
        dev = np.linalg.norm(fit.curve.evaluate(fit.params) - pts, axis=1)
        assert fit.max_deviation == pytest.approx(dev.max(), rel=1e-12)
        assert fit.rms_deviation == pytest.approx(np.sqrt(np.mean(dev**2)), rel=1e-12)
        if prev is not None:
            assert prev / fit.max_deviation > 8
        prev = fit.max_deviation


def test_surface_fit_interpolates_and_approximates():
    x = np.linspace(0, 2, 25) ** 1.2
    y = np.linspace(0, 1.5, 19)
    X, Y = np.meshgrid(x, y, indexing="ij")
    grid = np.dstack([X, Y, np.sin(X) * np.cos(Y)])
    fit = fl.fit_surface(grid)
    assert fit.max_deviation <= 1e-12
    assert fit.surface.shape == (25, 19)
    coarse = fl.fit_surface(grid, n_control_u=9, n_control_v=7)
    assert 0 < coarse.max_deviation < 1e-3
    assert coarse.surface.shape == (9, 7)
    finer = fl.fit_surface(grid, n_control_u=17, n_control_v=13)
    assert finer.max_deviation < coarse.max_deviation / 8
