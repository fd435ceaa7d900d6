"""fl.spline_product_integral (the engine's exact integral of a product of spline functions times
x^k, the rule of the SplineIntegral conditions) against numpy's exact polynomial integration, and
the basic curves' integrals that use it."""

import numpy as np
import pytest

import fairlines as fl
from fairlines.basic_curves import BasicCurve

#: Relative agreement with the numpy truth: both exact, so only round-off of sums of a few
#: hundred terms and of the per-piece power-basis fits (conditioned by the pieces' lengths) is left.
ROUND_OFF = 1e-11


def random_function(rng, degree, n, x0, x1):
    """A non-rational spline function of x on [x0, x1] with random interior knots."""
    interior = np.sort(rng.uniform(x0, x1, n - degree - 1))
    knots = np.concatenate([[x0] * (degree + 1), interior, [x1] * (degree + 1)])
    return fl.NurbsCurve(degree, knots, rng.uniform(-2.0, 3.0, (n, 1)))


def numpy_integral(factors, a, b, power):
    """int_a^b x^power prod f dx: on each piece between the factors' knots every factor is one
    polynomial, read off by an interpolating fit of its own degree in the piece's own variable
    s = (x - middle) / half in [-1, 1] (well conditioned); numpy multiplies the polynomials and
    integrates the product exactly."""
    knots = np.unique(np.concatenate([np.asarray(f.knots) for f in factors] + [[a, b]]))
    pieces = knots[(knots >= a) & (knots <= b)]
    P = np.polynomial.Polynomial
    total = 0.0
    for lo, hi in zip(pieces[:-1], pieces[1:]):
        middle, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
        product = P([middle, half]) ** power  # x in terms of s
        for f in factors:
            s = np.cos(np.pi * (np.arange(f.degree + 1) + 0.5) / (f.degree + 1))  # Chebyshev nodes
            y = np.asarray(f.evaluate(middle + half * s))[:, 0]
            product = product * P(np.polynomial.polynomial.polyfit(s, y, f.degree))
        primitive = product.integ()
        total += half * (primitive(1.0) - primitive(-1.0))
    return total


@pytest.mark.parametrize("seed", range(6))
def test_products_of_random_splines_match_numpy(seed):
    rng = np.random.default_rng(seed)
    x0, x1 = -3.0, 12.0
    factors = [random_function(rng, d, n, x0, x1) for d, n in ((3, 9), (2, 6), (1 + seed % 4, 8))]
    for power in (0, 1, 2):
        a, b = sorted(rng.uniform(x0, x1, 2)) if power == 2 else (x0, x1)
        truth = numpy_integral(factors, a, b, power)
        assert fl.spline_product_integral(factors, a, b, power) == pytest.approx(truth, rel=ROUND_OFF)


def test_no_factor_is_the_moment_of_the_range():
    assert fl.spline_product_integral([], 1.0, 4.0, 2) == pytest.approx((4.0**3 - 1.0) / 3.0, rel=1e-15)


@pytest.mark.parametrize("bad", [
    dict(from_=2.0, to=1.0),                       # reversed range
    dict(from_=-1.0, to=1.0),                      # beyond the factor's domain
    dict(power=-1),
])
def test_refusals(bad):
    f = fl.NurbsCurve(1, [0.0, 0.0, 3.0, 3.0], [[1.0], [2.0]])
    kw = {"from_": 0.0, "to": 3.0, "power": 0, **bad}
    with pytest.raises(fl.InvalidInput):
        fl.spline_product_integral([f], **kw)


def test_basic_curve_integrals_are_exact():
    rng = np.random.default_rng(11)
    f = random_function(rng, 3, 10, 5.0, 45.0)
    curve = BasicCurve("f", 5.0, 45.0, f)
    for power in (0, 1):
        assert curve.integral(power) == pytest.approx(numpy_integral([f], 5.0, 45.0, power), rel=ROUND_OFF)
    assert curve.integral(0, 10.0, 30.0) == pytest.approx(numpy_integral([f], 10.0, 30.0, 0), rel=ROUND_OFF)
    params = curve.form_parameters()
    assert params["xC"] == pytest.approx(numpy_integral([f], 5.0, 45.0, 1) / numpy_integral([f], 5.0, 45.0, 0), rel=ROUND_OFF)
    constant = BasicCurve("c", 2.0, 6.0, None, 1.5)
    assert constant.integral(1) == pytest.approx(1.5 * (36.0 - 4.0) / 2.0, rel=1e-15)


def test_designed_sac_meets_its_volume_and_lcb():
    """The SAC's own integral (a product of the fullness, the waterline and the immersed depth)
    reads back the volume and LCB its description asks for (the designer's targets, corrected
    so that the surface meets cb and lcb)."""
    hull = fl.design_hull(lpp=120, breadth=20, draft=5, depth=9, cb=0.6, lcb=58.8)
    sac, asked = hull.basic_curves["sac"], hull.description.curves["sac"].aliases
    assert sac.integral(0) == pytest.approx(asked["volume"], rel=1e-10)  # the QP's equality rows: round-off
    assert sac.integral(1) / sac.integral(0) == pytest.approx(asked["lcb"], rel=1e-10)
    parts = [sac.fullness.curve, sac.dwl.factor(), sac.profile.factor(offset=sac.draft, scale=-1.0)]
    assert sac.integral(0) == pytest.approx(2 * numpy_integral(parts, sac.x_start, sac.x_end, 0), rel=ROUND_OFF)
