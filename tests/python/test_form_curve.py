"""Form-parameter curve solver: definitions against independent computations,
exactness, infeasible requests, bad input, fairness against random multistarts."""

import itertools
import math

import numpy as np
import pytest

import fairlines as fl
from fairlines import _native

TABLE2 = dict(xB=0.0, yB=0.998204, xE=1.0, yE=0.33031, alphaB=-5.0, alphaE=-85.0, CAB=-0.5, CAE=-1.5,
              Area=0.8103, xC=0.4330, yC=0.42195)
TABLE3 = dict(xB=0.0, yB=0.569026, xE=1.0, yE=0.0, alphaB=-31.0, alphaE=-58.0, CAB=-1.5, CAE=-4.41,
              Area=0.1925, xC=0.28489, yC=0.16952)


def dense_parameters(curve, m=20001):
    """Every form parameter from the evaluated curve: composite Simpson in t of
    y x', x y x', y^2/2 x' from NurbsCurve derivatives (independent of the solver's
    Gauss quadrature and basis tables)."""
    t = np.linspace(0.0, 1.0, m)
    d = np.array([np.asarray(curve.derivatives(float(ti), 2)) for ti in t])  # (m, 3, dim)
    x, y, xp = d[:, 0, 0], d[:, 0, 1], d[:, 1, 0]
    w = np.ones(m)
    w[1:-1:2], w[2:-1:2] = 4.0, 2.0
    w *= (t[1] - t[0]) / 3.0
    A = w @ (y * xp)
    My = w @ (x * y * xp)
    Mx = w @ (0.5 * y * y * xp)
    out = dict(xB=x[0], yB=y[0], xE=x[-1], yE=y[-1], Area=A, xC=My / A, yC=Mx / A)
    for name, k in (("B", 0), ("E", -1)):
        x1, y1 = d[k, 1, 0], d[k, 1, 1]
        x2, y2 = d[k, 2, 0], d[k, 2, 1]
        out["alpha" + name] = math.degrees(math.atan2(y1, x1))
        out["CA" + name] = (x1 * y2 - y1 * x2) / (x1 * x1 + y1 * y1) ** 1.5
    out["min_dx"] = float(d[:, 1, 0].min())
    out["min_y"] = float(y.min())
    return out


def dense_e2(curve, m=4001):
    t = np.linspace(0.0, 1.0, m)
    d2 = np.array([np.asarray(curve.derivatives(float(ti), 2))[2] for ti in t])
    w = np.ones(m)
    w[1:-1:2], w[2:-1:2] = 4.0, 2.0
    w *= (t[1] - t[0]) / 3.0
    return float(w @ (d2 ** 2).sum(axis=1))


def assert_meets(res, req, tol=1e-9):
    for k, v in req.items():
        assert abs(res.residuals[k]) <= tol, (k, res.residuals[k])
    dense = dense_parameters(res.curve)
    for k, v in req.items():
        assert dense[k] == pytest.approx(v, abs=1e-8, rel=1e-8), k


# --- definitions -------------------------------------------------------------------

def test_parameter_definitions_match_dense_quadrature(rng):
    for _ in range(5):
        x = np.concatenate([[0.0], np.cumsum(rng.uniform(0.5, 1.5, 7))])
        cps = np.column_stack([x / x[-1], rng.uniform(0.2, 1.2, 8)])
        curve = fl.NurbsCurve(3, fl.clamped_uniform_knots(8, 3), cps)
        got = fl.form_parameters_of(3, cps)
        ref = dense_parameters(curve)
        for k in ("xB", "yB", "xE", "yE", "alphaB", "alphaE", "CAB", "CAE", "Area", "xC", "yC"):
            assert got[k] == pytest.approx(ref[k], rel=1e-9, abs=1e-11), k


def test_area_is_signed_integral_y_dx_against_polygon_area():
    # a curve reproducing a straight line y = 1 - 0.5 x (control points on the line)
    x = np.linspace(0, 2, 6)
    cps = np.column_stack([x, 1 - 0.5 * x])
    p = fl.form_parameters_of(3, cps)
    assert p["Area"] == pytest.approx(1.0, rel=1e-13)  # trapezoid 2 * (1 + 0) / 2
    assert p["xC"] == pytest.approx(2 / 3, rel=1e-12)  # triangle centroid
    assert p["yC"] == pytest.approx(1 / 3, rel=1e-12)
    assert p["CAB"] == pytest.approx(0.0, abs=1e-12)
    assert p["alphaB"] == pytest.approx(math.degrees(math.atan2(-0.5, 1)), abs=1e-12)
    # reversed direction flips the sign of the area but not the centroid
    q = fl.form_parameters_of(3, cps[::-1].copy())
    assert q["Area"] == pytest.approx(-1.0, rel=1e-13)
    assert q["xC"] == pytest.approx(2 / 3, rel=1e-12)


def test_fairness_measures_against_dense_quadrature(rng):
    cps = rng.uniform(0, 1, (9, 2))
    curve = fl.NurbsCurve(3, fl.clamped_uniform_knots(9, 3), cps)
    f = fl.fairness_of(3, cps)
    assert f["E2"] == pytest.approx(dense_e2(curve), rel=1e-6)


def test_analytic_derivatives_against_finite_differences(rng):
    params = dict(TABLE3)
    n = 8
    pts = [((0.5, 0.2), math.inf), ((0.3, 0.4), 50.0)]
    fair = {"e1": 0.1, "e2": 1.0, "e3": 0.01, "length": 0.5}
    x = np.concatenate([[0.0], np.cumsum(rng.uniform(0.5, 1.5, n - 1))])
    z = np.concatenate([x / x[-1], rng.uniform(0.2, 0.8, n), [0.45, 0.35]])
    lam = rng.normal(size=len(params) + 2)
    d = _native._form_curve_derivatives(params, n, 3, 2, fair, pts, z, lam)
    h = 1e-6
    J_fd = np.zeros_like(d["J"])
    HL_fd = np.zeros_like(d["HL"])
    g_fd = np.zeros_like(d["g"])
    H_fd = np.zeros_like(d["H"])
    for i in range(len(z)):
        e = np.zeros_like(z)
        e[i] = h
        dp = _native._form_curve_derivatives(params, n, 3, 2, fair, pts, z + e, lam)
        dm = _native._form_curve_derivatives(params, n, 3, 2, fair, pts, z - e, lam)
        J_fd[:, i] = (dp["c"] - dm["c"]) / (2 * h)
        HL_fd[:, i] = (lam @ dp["J"] - lam @ dm["J"]) / (2 * h)
        g_fd[i] = (dp["f"] - dm["f"]) / (2 * h)
        H_fd[:, i] = (dp["g"] - dm["g"]) / (2 * h)
    np.testing.assert_allclose(d["J"], J_fd, rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(d["HL"], HL_fd, rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(d["g"], g_fd, rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(d["H"], H_fd, rtol=1e-5, atol=1e-4)


# --- exact solutions -----------------------------------------------------------------

def test_table3_all_eleven_parameters_exact():
    res = fl.design_curve(TABLE3)
    assert res.converged
    assert_meets(res, TABLE3)
    dense = dense_parameters(res.curve)
    assert dense["min_dx"] >= -1e-12 and dense["min_y"] >= -1e-12
    assert isinstance(res.curve, fl.NurbsCurve)
    assert set(res.fairness) == {"E1", "E2", "E3", "length"}
    assert res.fairness["E2"] == pytest.approx(dense_e2(res.curve), rel=1e-6)
    assert res.iterations > 0


def test_table2_is_infeasible_without_folding_and_says_why():
    with pytest.raises(fl.InfeasibleFormParameters) as exc:
        fl.design_curve(TABLE2)
    msg = str(exc.value)
    assert isinstance(exc.value, ValueError)
    for name in ("Area", "xC", "yC"):
        assert name in msg
    assert "0.42697" in msg  # the achievable lower bound of yC


def test_table2_yc_lower_bound_is_a_real_bound():
    # the bound is attained only by a straight line: a straight line over [0, 1] with
    # the requested area and centroid x has exactly the bound as yC
    A, xC = TABLE2["Area"], TABLE2["xC"]
    b = 12 * A * (xC - 0.5)
    a = A - b / 2
    x = np.linspace(0, 1, 8)
    p = fl.form_parameters_of(3, np.column_stack([x, a + b * x]))
    assert p["xC"] == pytest.approx(xC, rel=1e-12)
    assert p["yC"] == pytest.approx(A / 2 * (1 + 12 * (xC - 0.5) ** 2), rel=1e-12)


@pytest.mark.parametrize(
    "dropped",
    [("yC",), ("yC", "CAB", "CAE"), ("yC", "xC"), ("yC", "Area", "xC"), ("yC", "alphaB", "alphaE"),
     ("yC", "CAE"), ("xC", "yC", "CAB")],
)
def test_table2_subsets_give_fair_exact_non_folding_curves(dropped):
    req = {k: v for k, v in TABLE2.items() if k not in dropped}
    res = fl.design_curve(req)
    assert_meets(res, req)
    dense = dense_parameters(res.curve)
    assert dense["min_dx"] >= -1e-12
    assert np.all(np.diff(res.control_points[:, 0]) >= 0)


def test_subsets_of_table3_all_solve():
    keys = ["CAB", "CAE", "Area", "xC", "yC"]
    for r in range(len(keys) + 1):
        for drop in itertools.combinations(keys, r):
            req = {k: v for k, v in TABLE3.items() if k not in drop}
            if "Area" not in req and ("xC" in req or "yC" in req):
                continue  # a centroid without the area is a different request
            res = fl.design_curve(req)
            assert res.max_residual() <= 1e-9, drop


def test_sweeps_converge_at_every_step():
    base = {k: v for k, v in TABLE3.items() if k not in ("xC", "yC")}
    for A in np.linspace(0.12, 0.32, 6):
        res = fl.design_curve(dict(base, Area=float(A)))
        assert abs(res.residuals["Area"]) <= 1e-9
    prev = None
    for yc in np.linspace(0.158, 0.182, 7):
        res = fl.design_curve(dict(TABLE3, yC=float(yc)), initial_control_points=prev)
        assert res.max_residual() <= 1e-9
        prev = res.control_points


def test_at_least_as_fair_as_twenty_random_multistarts(rng):
    req = {k: v for k, v in TABLE2.items() if k != "yC"}
    best = fl.design_curve(req)
    e2s = []
    for _ in range(20):
        x = np.sort(rng.uniform(0.05, 0.95, 8))
        x[0], x[-1] = 0.0, 1.0
        y = rng.uniform(0.3, 1.2, 8)
        try:
            r = fl.design_curve(req, initial_control_points=np.column_stack([x, y]))
        except ValueError:
            continue
        assert r.max_residual() <= 1e-9
        e2s.append(r.fairness["E2"])
    assert len(e2s) >= 5
    assert best.fairness["E2"] <= min(e2s) * (1 + 1e-7)


def test_fairness_weights_change_the_curve():
    req = {k: v for k, v in TABLE3.items() if k not in ("yC",)}
    a = fl.design_curve(req)
    b = fl.design_curve(req, fairness={"e2": 1.0, "length": 5.0})
    c = fl.design_curve(req, fairness={"e3": 1.0})
    assert b.fairness["length"] < a.fairness["length"]
    assert c.fairness["E3"] <= a.fairness["E3"] * (1 + 1e-9)
    for r in (a, b, c):
        assert r.max_residual() <= 1e-9


def test_points_interpolated_and_approximated():
    req = dict(xB=0.0, yB=1.0, xE=1.0, yE=0.2, alphaB=0.0, alphaE=-60.0)
    res = fl.design_curve(req, points=[(0.5, 0.9)])
    assert res.point_residuals[0] <= 1e-9
    pt = np.asarray(res.curve.evaluate(float(res.point_parameters[0])))
    np.testing.assert_allclose(pt.reshape(-1), [0.5, 0.9], atol=1e-9)
    loose = fl.design_curve(req, points=[((0.5, 0.9), 1e-3)])
    tight = fl.design_curve(req, points=[((0.5, 0.9), 1e3)])
    assert tight.point_residuals[0] < loose.point_residuals[0]
    assert loose.fairness["E2"] < res.fairness["E2"]


def test_space_curve_with_tangent_directions():
    req = dict(xB=0.0, yB=0.0, zB=0.0, xE=1.0, yE=1.0, zE=0.5)
    res = fl.design_curve(req, n_control=10, tangent_start=(1.0, 0.0, 0.0), tangent_end=(0.0, 1.0, 1.0),
                          bounds=False)
    assert res.control_points.shape == (10, 3)
    d0 = np.asarray(res.curve.derivatives(0.0, 1))[1]
    d1 = np.asarray(res.curve.derivatives(1.0, 1))[1]
    assert np.linalg.norm(np.cross(d0, [1, 0, 0])) <= 1e-9 * np.linalg.norm(d0) and d0[0] > 0
    assert np.linalg.norm(np.cross(d1, [0, 1, 1])) <= 1e-9 * np.linalg.norm(d1) and d1[1] > 0
    assert res.max_residual() <= 1e-12


def test_more_control_points():
    res = fl.design_curve(TABLE3, n_control=14)
    assert_meets(res, TABLE3)
    assert res.control_points.shape == (14, 2)


# --- infeasible requests ---------------------------------------------------------------

@pytest.mark.parametrize(
    "change, names",
    [
        (dict(xC=1.2), ["xC"]),                      # centroid outside the end points' x range
        (dict(xC=-0.1), ["xC"]),
        (dict(Area=-0.3), ["Area"]),                 # negative area above y = 0
        (dict(alphaB=120.0), ["alphaB"]),            # x would run backwards
        (dict(yB=-0.2), ["yB"]),                     # below y >= 0
        (dict(yC=0.1), ["yC"]),                      # below the Cauchy-Schwarz bound
        (dict(xE=0.0), ["xB", "xE"]),                # x-monotone needs xE != xB
        (dict(alphaE=30.0), ["alphaE"]),             # ends on y = 0 coming from below
    ],
)
def test_infeasible_requests_name_the_parameters(change, names):
    req = dict(TABLE3, **change)
    with pytest.raises(fl.InfeasibleFormParameters) as exc:
        fl.design_curve(req)
    for name in names:
        assert name in str(exc.value)
    assert "achievable" in str(exc.value).lower() or "needs" in str(exc.value)


def test_infeasible_is_a_value_error():
    assert issubclass(fl.InfeasibleFormParameters, ValueError)


# --- bad input -------------------------------------------------------------------------

@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        (dict(params=dict(TABLE3, Area=float("nan"))), "Area"),
        (dict(params=dict(TABLE3, Volume=1.0)), "Volume"),
        (dict(params=TABLE3, n_control=4), "n_control"),
        (dict(params=TABLE3, n_control=3), "n_control"),
        (dict(params=TABLE3, degree=1), "degree"),
        (dict(params=TABLE3, n_control=8.5), "n_control"),
        (dict(params=TABLE3, n_control=True), "n_control"),
        (dict(params=[1, 2, 3]), "mapping"),
        (dict(params=TABLE3, fairness={"e5": 1.0}), "e5"),
        (dict(params=TABLE3, fairness={"e2": -1.0}), "e2"),
        (dict(params=TABLE3, bounds={"convex": True}), "convex"),
        (dict(params=TABLE3, bounds={"monotone": "z"}), "monotone"),
        (dict(params=dict(TABLE3, zB=0.0), dim=2), "zB"),
        (dict(params=TABLE3, points=[((0.5, float("inf")), None)]), "points[0]"),
        (dict(params=TABLE3, points=[((0.5, 0.2), -1.0)]), "weight"),
        (dict(params=dict(TABLE3, CAB="big")), "CAB"),
    ],
)
def test_bad_input_raises_value_error_naming_it(kwargs, fragment):
    with pytest.raises(ValueError) as exc:
        fl.design_curve(**kwargs)
    assert fragment in str(exc.value)
    assert not isinstance(exc.value, fl.InfeasibleFormParameters)


def test_families_example_writes_png(tmp_path, monkeypatch, capsys):
    import pathlib
    import runpy
    import sys

    script = pathlib.Path(__file__).resolve().parents[2] / "examples" / "form_curve_families.py"
    monkeypatch.setattr(sys, "argv", ["form_curve_families.py", str(tmp_path)])
    with pytest.raises(SystemExit) as exc:
        runpy.run_path(str(script), run_name="__main__")
    assert exc.value.code == 0
    out = capsys.readouterr().out
    assert "Area family: 9 curves" in out and "yC family: 8 curves" in out
    assert (tmp_path / "form_curve_families.png").stat().st_size > 10000
