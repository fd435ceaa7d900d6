"""Bad input raises ValueError naming the problem; nothing aborts the interpreter."""

import subprocess
import sys
import textwrap

import numpy as np
import pytest

import fairlines as fl

GOOD_KNOTS = [0, 0, 0, 0, 1, 1, 1, 1]
GOOD_PTS = [[0, 0], [1, 1], [2, 0], [3, 1]]


@pytest.mark.parametrize(
    "args, match",
    [
        ((3, [0, 0, 0, 0.5, 0.2, 1, 1, 1], GOOD_PTS), "decrease at index"),
        ((3, [0, 0, 0, 1, 1, 1, 1], GOOD_PTS), "expected 8"),
        ((4, GOOD_KNOTS, GOOD_PTS), "degree-4 B-spline needs at least 5"),
        ((3, GOOD_KNOTS, [[0, 0], [1, 1], [2, 0]]), "at least 4"),
        ((3, GOOD_KNOTS, [[0, 0], [1, np.nan], [2, 0], [3, 1]]), r"control_points\[1, 1\] is nan"),
        ((3, GOOD_KNOTS, [[0, 0], [1, np.inf], [2, 0], [3, 1]]), "finite"),
        ((3, [0, 0, 0, 0, 1, 1, 1, np.nan], GOOD_PTS), "knots"),
        ((3, GOOD_KNOTS, np.zeros((0, 2))), "n >= 1"),
        ((3, GOOD_KNOTS, [0, 1, 2, 3]), r"expected \(n, dim\)"),
        ((0, GOOD_KNOTS, GOOD_PTS), "degree"),
        ((2.5, GOOD_KNOTS, GOOD_PTS), "integer"),
        ((3, "abc", GOOD_PTS), "knots could not be read"),
    ],
)
def test_curve_constructor_rejects(args, match):
    with pytest.raises(ValueError, match=match):
        fl.NurbsCurve(*args)


@pytest.mark.parametrize("weights, match", [([1, 1, 0, 1], r"weights\[2\] is 0"), ([1, -1, 1, 1], "weight > 0"),
                                            ([1, 1, 1], "expected 4"), ([1, np.nan, 1, 1], "weight")])
def test_bad_weights(weights, match):
    with pytest.raises(ValueError, match=match):
        fl.NurbsCurve(3, GOOD_KNOTS, GOOD_PTS, weights)


def test_surface_and_fit_errors():
    k = [0, 0, 1, 1]
    with pytest.raises(ValueError, match=r"expected \(nu, nv, 3\)"):
        fl.NurbsSurface(1, 1, k, k, np.zeros((2, 2, 2)))
    with pytest.raises(ValueError, match="weights has shape"):
        fl.NurbsSurface(1, 1, k, k, np.zeros((2, 2, 3)), np.ones((3, 2)))
    s = fl.NurbsSurface(1, 1, k, k, np.zeros((2, 2, 3)))
    with pytest.raises(ValueError, match="equal lengths"):
        s.evaluate([0.1, 0.2], [0.3])
    with pytest.raises(ValueError, match="not finite"):
        s.evaluate([np.nan], [0.3])
    # the batch screen works in blocks: the first bad pair is named wherever it lies
    for k in (0, 511, 512, 1000, 1999):
        for bad in (np.nan, np.inf, -np.inf):
            u, v = np.full(2000, 0.5), np.full(2000, 0.5)
            (u if k % 2 else v)[k] = bad
            u[1999 if k < 1999 else 0] = 0.0  # a finite extreme value is fine
            with pytest.raises(ValueError, match=f"parameter pair {k} is not finite"):
                s.evaluate(u, v)
            with pytest.raises(ValueError, match=f"parameter pair {k} is not finite"):
                s.derivatives(u, v, 1)
    s.evaluate(np.full(600, np.finfo(float).max), np.full(600, -np.finfo(float).tiny))  # finite: clamped
    with pytest.raises(ValueError, match="direction"):
        s.insert_knot("w", 0.5)
    with pytest.raises(ValueError, match="parameterization"):
        fl.fit_curve(np.random.default_rng(0).random((10, 2)), parameterization="arc")
    with pytest.raises(ValueError, match="n_control"):
        fl.fit_curve(np.random.default_rng(0).random((10, 2)), n_control=20)
    with pytest.raises(ValueError, match="radius"):
        fl.circle((0, 0, 0), -1.0)
    with pytest.raises(ValueError, match="multiplicity"):
        fl.NurbsCurve(3, GOOD_KNOTS, GOOD_PTS).insert_knot(0.5, times=4)


def test_bad_calls_never_abort_the_interpreter():
    code = textwrap.dedent(
        """
        import numpy as np, fairlines as fl
        bad = [
            lambda: fl.NurbsCurve(3, [1, 0], [[0, 0]]),
            lambda: fl.NurbsCurve(-1, [], []),
            lambda: fl.NurbsSurface(3, 3, [], [], np.zeros((0, 0, 3))),
            lambda: fl.fit_surface(np.zeros((1, 1, 3))),
            lambda: fl.fit_curve([[0, 0], [0, 0], [0, 0], [0, 0]]),
            lambda: fl.circle((0, 0, 0), 1.0, normal=(0, 0, 0)),
            lambda: fl.NurbsVolume((1, 1), ([0, 1],), np.zeros((1, 3))),
            lambda: fl.basis_functions([0, 0, 1, 1], 1, [0.5], order=-1),
            lambda: fl.sphere((0, 0), 1.0),
        ]
        n = 0
        for f in bad:
            try:
                f()
            except ValueError:
                n += 1
        print("caught", n, "of", len(bad))
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert "caught 9 of 9" in out.stdout


BULB_SHIP = dict(lpp=200.0, beam=32.0, draft_fp=11.0, midship_area=340.0, displacement_volume=50000.0)


@pytest.mark.parametrize("option, value, says", [
    ("c_lprr", 0.03, "BulbousBow option 'c_lprr' is unknown; expected one of c_lpr"),
    ("sections", 8.5, "BulbousBow option sections is 8.5; expected an integer"),
    ("sections", True, "BulbousBow option sections is True; expected an integer"),
    ("c_bb", "wide", "BulbousBow option c_bb is 'wide'; expected a float"),
])
def test_bulb_option_of_wrong_name_or_type_is_refused(option, value, says):
    with pytest.raises(ValueError, match=says):
        fl.BulbousBow(**BULB_SHIP, **{option: value})


def test_intersection_option_is_refused_by_name():
    plane = fl.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], np.array([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]]], float))
    with pytest.raises(fl.InvalidInput, match="intersect_surfaces option 'tol' is unknown"):
        fl.intersect_surfaces(plane, plane, tol=1e-7)


def test_a_placement_that_is_not_one_is_refused_by_name():
    from fairlines.compose import compose_with_blend

    plane = fl.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], np.array([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]]], float))
    with pytest.raises(fl.InvalidInput, match="placement is a dict; expected a BlendPlacement"):
        compose_with_blend(plane, plane, placement={"hull": plane})
