"""Bounded work and strict input: every size and order a caller passes has a limit
(fl._native.limits) and is refused beyond it with InvalidInput naming the value and the limit,
before any allocation; absurd magnitudes and unknown names are refused with a hint.

Each call below used to run for minutes, end in MemoryError, or be accepted silently.
"""

import numpy as np
import pytest

import fairlines as fl

LIMITS = fl._native.limits
TABLE3 = {"xB": 0.0, "yB": 1.0, "xE": 1.0, "yE": 0.33, "alphaB": -5.0, "alphaE": -85.0, "Area": 0.80, "xC": 0.43}


def circle():
    return fl.circle((0.0, 0.0, 0.0), 1.0)


def patch():
    k = [0, 0, 1, 1]
    g = np.linspace(0, 1, 2)
    return fl.NurbsSurface(1, 1, k, k, np.dstack(list(np.meshgrid(g, g, indexing="ij")) + [np.zeros((2, 2))]))


@pytest.mark.parametrize(
    "call, fragments",
    [
        (lambda: circle().elevate_degree(10**6), ["times is 1000000", str(LIMITS.MAX_DEGREE)]),
        (lambda: circle().derivatives(0.3, 10**6), ["order is 1000000", str(LIMITS.MAX_DERIVATIVE_ORDER)]),
        (lambda: circle().derivatives(np.linspace(0, 1, 10), 31), ["order is 31"]),
        (lambda: patch().derivatives(0.5, 0.5, 10**6), ["order is 1000000"]),
        (lambda: fl.basis_functions([0, 0, 1, 1], 1, [0.5], 10**6), ["order is 1000000"]),
        (lambda: fl.NurbsCurve(40, np.r_[np.zeros(41), np.ones(41)], np.zeros((41, 2))), ["degree is 40"]),
        (lambda: fl.clamped_uniform_knots(10**9, 3), ["1000000000", str(LIMITS.MAX_CONTROL_POINTS)]),
        (lambda: patch().evaluate_grid(np.zeros(100000), np.zeros(100000)), ["evaluate_grid", str(LIMITS.MAX_RESULT_VALUES)]),
        (lambda: fl.fit_curve(np.random.default_rng(0).random((LIMITS.MAX_FIT_POINTS + 1, 2))),
         [str(LIMITS.MAX_FIT_POINTS + 1), "limit"]),
        (lambda: fl.fit_surface(np.random.default_rng(0).random((LIMITS.MAX_FIT_POINTS + 1, 4, 3))),
         [str(LIMITS.MAX_FIT_POINTS + 1), "limit"]),
    ],
    ids=["elevate_degree", "curve_derivatives", "curve_derivatives_array", "surface_derivatives", "basis_functions",
         "degree", "knot_count", "grid_size", "fit_curve_points", "fit_surface_rows"],
)
def test_sizes_and_orders_beyond_the_limit_are_refused(call, fragments):
    with pytest.raises(fl.InvalidInput) as exc:
        call()
    for fragment in fragments:
        assert fragment in str(exc.value)


@pytest.mark.parametrize("times", [10**12, 2**31 - 1, -(2**40)])
def test_integers_beyond_the_int_range_are_invalid_input(times):
    # 2**31 - 1 on a knot of multiplicity 2 would overflow a 32-bit multiplicity sum.
    c = circle()
    with pytest.raises(fl.InvalidInput, match=f"times|{times} time"):
        c.insert_knot(0.25, times)
    with pytest.raises(fl.InvalidInput, match="times"):
        c.elevate_degree(times)


def test_degree_elevation_of_a_long_curve_is_exact():
    # 20000 control points: a dense collocation solve needed 3.2 GB and O(n^3) work.
    rng = np.random.default_rng(3)
    n = 20000
    c = fl.NurbsCurve(3, fl.clamped_uniform_knots(n, 3), rng.normal(size=(n, 2)))
    e = c.elevate_degree(1)
    t = rng.uniform(0, 1, 2000)
    assert e.degree == 4
    assert np.max(np.abs(e.evaluate(t) - c.evaluate(t))) < 1e-9


@pytest.mark.parametrize(
    "kwargs, fragments",
    [
        (dict(params=TABLE3, n_control=10**6), ["n_control", str(LIMITS.MAX_FORM_CURVE_CONTROL_POINTS)]),
        (dict(params={}), ["empty"]),
        (dict(params=dict(TABLE3, alphaB=1e9)), ["alphaB", "360"]),
        (dict(params=dict(TABLE3, xE=1e300)), ["xE", "units"]),
        (dict(params=dict(TABLE3, Aera=1.0)), ["Aera", "did you mean 'Area'"]),
        (dict(params=TABLE3, fairness={"e22": 1.0}), ["e22", "did you mean 'e2'"]),
        (dict(params=TABLE3, bounds={"monotonic": "x"}), ["monotonic", "did you mean 'monotone'"]),
        (dict(params=TABLE3, multistart=10**6), ["multistart", str(LIMITS.MAX_FORM_CURVE_MULTISTART)]),
        (dict(params=TABLE3, max_iterations=10**9), ["max_iterations", str(LIMITS.MAX_FORM_CURVE_ITERATIONS)]),
        (dict(params=TABLE3, points=np.zeros((LIMITS.MAX_FORM_CURVE_POINTS + 1, 2))), ["points", "limit"]),
        (dict(params=TABLE3, points=[((0.5, 1e7), 1.0)]), ["points[0]", "units"]),
    ],
    ids=["n_control", "empty", "angle", "length", "unknown_param", "unknown_fairness", "unknown_bound", "multistart",
         "iterations", "point_count", "point_magnitude"],
)
def test_design_curve_refuses(kwargs, fragments):
    with pytest.raises(fl.InvalidInput) as exc:
        fl.design_curve(**kwargs)
    assert not isinstance(exc.value, fl.InfeasibleFormParameters)
    for fragment in fragments:
        assert fragment in str(exc.value)


def test_form_curve_measures_refuse_oversized_curves():
    cps = np.column_stack([np.linspace(0, 1, LIMITS.MAX_FORM_CURVE_CONTROL_POINTS + 1), np.ones(LIMITS.MAX_FORM_CURVE_CONTROL_POINTS + 1)])
    with pytest.raises(fl.InvalidInput, match="form_parameters_of"):
        fl.form_parameters_of(3, cps)
    with pytest.raises(fl.InvalidInput, match="fairness_of"):
        fl.fairness_of(3, cps)
