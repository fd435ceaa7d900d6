"""Form-parameter curve design (Kim, Shin & Kim 2002: the fairest B-spline meeting form parameters).

``design_curve`` finds the fairest clamped uniform B-spline (minimum e1 E1 + e2 E2 +
e3 E3 + s S, E_k = int |C^(k)|^2 dt over t in [0, 1]) that meets a chosen subset of form
parameters *exactly* (equality constraints, Lagrange-Newton / SQP with analytic
derivatives in the compiled engine), keeps a section a section (x monotone, y >= 0 on
the control polygon, by default) and reaches hard requests by continuation.
A request no such curve can meet raises :class:`fairlines.InfeasibleFormParameters`
(an ``InvalidInput``) naming the parameters in conflict and, where computable, the
achievable range; malformed input raises :class:`fairlines.InvalidInput` naming the value.

Units: offsets in metres (any consistent length unit), angles in degrees from +x,
curvature in 1/length, Area in length^2.
"""

from __future__ import annotations

import difflib
import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from . import _native
from ._native import InvalidInput, NurbsCurve

__all__ = ["FormCurveResult", "design_curve", "FORM_PARAMETERS", "form_parameters_of", "fairness_of"]

#: Names accepted in ``params``.
FORM_PARAMETERS = tuple(_native.form_parameter_names())

form_parameters_of = _native.form_parameters_of
fairness_of = _native.fairness_of

# Defaults come from the engine's request and option structs (fairlines/form_curve.hpp).
_REQUEST = _native.FormCurveRequest()
_OPTIONS = _REQUEST.options
_FAIRNESS_KEYS = ("e1", "e2", "e3", "length")
_BOUND_KEYS = ("monotone", "y_nonnegative", "min_end_speed")


@dataclass
class FormCurveResult:
    """Outcome of :func:`design_curve`.

    curve           NurbsCurve of the given degree, n_control x dim control points,
                    clamped uniform knots on [0, 1]
    residuals       achieved minus requested value, per requested parameter
                    (angles in degrees, wrapped to (-180, 180])
    achieved        achieved value per requested parameter
    fairness        {"E1", "E2", "E3", "length"} of the curve
    iterations      Newton iterations, all continuation and barrier stages and starts
    converged       True when the KKT conditions were met to tolerance (the
                    constraints are always met when a result is returned)
    point_parameters  curve parameter t of each entry of ``points``
    point_residuals   distance |C(t_j) - Q_j| for each entry of ``points``
    """

    curve: NurbsCurve
    residuals: dict
    achieved: dict
    fairness: dict
    iterations: int
    converged: bool
    objective: float
    continuation_steps: int
    point_parameters: np.ndarray = field(default_factory=lambda: np.zeros(0))
    point_residuals: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def control_points(self) -> np.ndarray:
        return np.asarray(self.curve.control_points)

    def max_residual(self) -> float:
        """Largest |residual| over the requested parameters and points (0 if none)."""
        vals = [abs(v) for v in self.residuals.values()] + [float(v) for v in self.point_residuals]
        return max(vals) if vals else 0.0


def _is_int(v) -> bool:
    return isinstance(v, numbers.Integral) and not isinstance(v, bool)


def _unknown(kind, key, expected):
    """InvalidInput for an unknown key, with the nearest valid one."""
    near = difflib.get_close_matches(str(key), expected, n=1, cutoff=0.5)
    hint = f" (did you mean {near[0]!r}?)" if near else ""
    return InvalidInput(f"unknown {kind} {key!r}{hint}; expected one of {', '.join(expected)}")


def _int(name, value, lo, hi=2**31 - 1):
    """value as an int in [lo, hi]; InvalidInput naming it otherwise."""
    if not _is_int(value) or not lo <= value <= hi:
        raise InvalidInput(f"{name} = {value!r}; expected an integer in [{lo}, {hi}]")
    return int(value)


def _number(name, value):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InvalidInput(f"{name} = {value!r}; expected a number")
    return float(value)


def _params(params):
    """The form-parameter mapping as {name: float}; names are checked by the engine."""
    if not isinstance(params, Mapping):
        raise InvalidInput(f"params must be a mapping of form parameter names to values, got {type(params).__name__}")
    out = {}
    for key, val in params.items():
        if not isinstance(key, str):
            raise InvalidInput(f"form parameter name {key!r} is not a string; expected one of {', '.join(FORM_PARAMETERS)}")
        if key not in FORM_PARAMETERS:
            raise _unknown("form parameter", key, FORM_PARAMETERS)
        out[key] = _number(f"form parameter {key}", val)
    return out


def _fairness(fairness):
    """FairnessWeights: the engine's default for None, else the given weights (others 0)."""
    w = _native.FairnessWeights()
    if fairness is None:
        return w
    if not isinstance(fairness, Mapping):
        raise InvalidInput(f"fairness = {fairness!r}; expected a mapping with keys {', '.join(_FAIRNESS_KEYS)}")
    for key in _FAIRNESS_KEYS:
        setattr(w, key, 0.0)
    for key, val in fairness.items():
        if key not in _FAIRNESS_KEYS:
            raise _unknown("fairness weight", key, _FAIRNESS_KEYS)
        setattr(w, key, _number(f"fairness weight {key}", val))
    return w


def _point_pairs(points):
    """Points as a list of (position, weight), weight inf for interpolation."""
    if points is None:
        return []
    if isinstance(points, Mapping):
        unknown = set(points) - {"positions", "weights"}
        if unknown or "positions" not in points:
            raise InvalidInput(
                f"points mapping has keys {sorted(map(str, points))}; expected 'positions' (m x dim) and optional 'weights' (m,)"
            )
        pos = np.asarray(points["positions"], dtype=float)
        w = points.get("weights")
        w = np.full(len(pos), math.inf) if w is None else np.asarray(w, dtype=float).reshape(-1)
        if pos.ndim != 2 or len(w) != len(pos):
            raise InvalidInput(
                f"points positions have shape {pos.shape} and weights {w.shape}; expected (m, dim) and (m,)"
            )
        return [(pos[i], float(w[i])) for i in range(len(pos))]
    try:
        arr = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        arr = None
    if arr is not None and arr.ndim == 2:
        return [(arr[i], math.inf) for i in range(len(arr))]
    out = []
    for j, item in enumerate(points):
        if not isinstance(item, (tuple, list)) or len(item) != 2:
            raise InvalidInput(
                f"points[{j}] = {item!r}; expected a position (x, y[, z]) or a pair (position, weight)"
            )
        pos, w = item
        w = math.inf if w is None else _number(f"points[{j}] weight", w)
        try:
            out.append((np.asarray(pos, dtype=float).reshape(-1), w))
        except (TypeError, ValueError):
            raise InvalidInput(f"points[{j}] position = {pos!r}; expected numbers (x, y[, z])") from None
    return out


def _points(points):
    """Checked point pairs; the engine's limit on their number is applied before any conversion."""
    if points is not None and hasattr(points, "__len__") and len(points) > _native.limits.MAX_FORM_CURVE_POINTS:
        raise InvalidInput(f"points has {len(points)} entries; the limit is {_native.limits.MAX_FORM_CURVE_POINTS}")
    try:
        return _point_pairs(points)
    except (TypeError, ValueError) as exc:
        if isinstance(exc, InvalidInput):
            raise
        raise InvalidInput(f"points could not be read: {exc}") from None


def _bounds(bounds):
    """FormBounds: the engine's defaults for None/True, none at all for False."""
    b = _native.FormBounds()
    if bounds is None or bounds is True:
        return b
    if bounds is False:
        b.monotone_axis, b.y_nonnegative = -1, False
        return b
    if not isinstance(bounds, Mapping):
        raise InvalidInput(
            f"bounds = {bounds!r}; expected None, False or a mapping with keys monotone ('x', 'y' or None), "
            "y_nonnegative (bool), min_end_speed (float)"
        )
    for key, val in bounds.items():
        if key == "monotone":
            axes = {"x": 0, "y": 1, None: -1, False: -1}
            if not isinstance(val, (str, type(None), bool)) or val not in axes:
                raise InvalidInput(f"bounds monotone = {val!r}; expected 'x', 'y' or None")
            b.monotone_axis = axes[val]
        elif key == "y_nonnegative":
            if not isinstance(val, (bool, np.bool_)):
                raise InvalidInput(f"bounds y_nonnegative = {val!r}; expected True or False")
            b.y_nonnegative = bool(val)
        elif key == "min_end_speed":
            b.min_end_speed = _number("bounds min_end_speed", val)
        else:
            raise _unknown("bound", key, _BOUND_KEYS)
    return b


def _solver_options(tolerance, max_iterations, continuation, multistart, seed):
    o = _native.FormSolverOptions()
    o.tolerance = _number("tolerance", tolerance)
    o.max_iterations = _int("max_iterations", max_iterations, 1, _native.limits.MAX_FORM_CURVE_ITERATIONS)
    o.continuation = bool(continuation)
    o.multistart = _int("multistart", multistart, 0, _native.limits.MAX_FORM_CURVE_MULTISTART)
    o.seed = _int("seed", seed, 0, 2**32 - 1)
    return o


def _infer_dim(params, pts, tangent_start, tangent_end, initial_control_points):
    three = (
        "zB" in params
        or "zE" in params
        or tangent_start is not None
        or tangent_end is not None
        or any(len(p) == 3 for p, _ in pts)
        or (initial_control_points is not None and np.asarray(initial_control_points).shape[-1:] == (3,))
    )
    return 3 if three else 2


def design_curve(
    params,
    n_control: int = _REQUEST.n_control,
    degree: int = _REQUEST.degree,
    fairness=None,
    points=None,
    bounds=None,
    *,
    dim: int | None = None,
    tangent_start=None,
    tangent_end=None,
    initial_control_points=None,
    tolerance: float = _OPTIONS.tolerance,
    max_iterations: int = _OPTIONS.max_iterations,
    continuation: bool = _OPTIONS.continuation,
    multistart: int = _OPTIONS.multistart,
    seed: int = _OPTIONS.seed,
) -> FormCurveResult:
    """Design the fairest B-spline curve meeting the requested form parameters exactly.

    params      mapping, any subset of xB, yB, xE, yE, alphaB, alphaE (deg from +x),
                CAB, CAE (signed curvature), Area (int y dx start to end), xC, yC
                (centroid of that area); zB, zE for 3-D curves. At least one form
                parameter, point or tangent. Lengths within fairlines.limits.MAX_FORM_CURVE_LENGTH,
                angles within [-360, 360] degrees.
    n_control   number of control points (>= degree + 1, and more than the conditions
                need: the remaining freedom is used for fairness; at most
                fairlines.limits.MAX_FORM_CURVE_CONTROL_POINTS)
    degree      B-spline degree (2 .. 15)
    fairness    mapping of weights {e1, e2, e3, length} (unlisted weights 0); default
                the engine's FairnessWeights (E2 alone)
    points      offsets to interpolate: (m, dim) array; or pairs (position, weight)
                where a finite weight approximates (adds weight * distance^2); or
                {"positions": (m, dim), "weights": (m,)} (inf = interpolate)
    bounds      None (the engine's FormBounds: x monotone from start to end, control
                y >= 0, end speed >= 0.2 * chord where an end angle is given), False (no
                bounds), or a mapping {monotone: 'x' | 'y' | None, y_nonnegative: bool,
                min_end_speed: float}
    dim         2 or 3 (default: 3 if zB/zE/tangents/3-D points are given, else 2)
    tangent_start, tangent_end   3-D tangent directions (dim 3)
    initial_control_points       (n_control, dim) start curve (must meet the bounds)
    tolerance, max_iterations, continuation, multistart, seed   solver options
                (FormSolverOptions)

    Returns FormCurveResult.
    Raises InvalidInput (a ValueError) on malformed input, naming the value: an unknown
    name (with the nearest valid one), a non-number, a size or magnitude beyond its limit,
    an empty request; InfeasibleFormParameters (an InvalidInput) when no curve can meet
    the request; ConvergenceError when the values were reached but not to tolerance.
    """
    req = _native.FormCurveRequest()
    req.params = _params(params)
    req.n_control = _int("n_control", n_control, 1, _native.limits.MAX_FORM_CURVE_CONTROL_POINTS)
    req.degree = _int("degree", degree, 1, 2**31 - 1)
    req.fairness = _fairness(fairness)
    pts = _points(points)
    if dim is None:
        dim = _infer_dim(req.params, pts, tangent_start, tangent_end, initial_control_points)
    req.dim = _int("dim", dim, 2, 3)
    req.bounds = _bounds(bounds)
    req.options = _solver_options(tolerance, max_iterations, continuation, multistart, seed)
    raw = _native._design_form_curve(
        req, points=pts, tangent_start=tangent_start, tangent_end=tangent_end,
        initial_control_points=initial_control_points,
    )
    return FormCurveResult(
        curve=NurbsCurve(raw["degree"], raw["knots"], raw["control_points"]),
        residuals=dict(raw["residuals"]),
        achieved=dict(raw["achieved"]),
        fairness=dict(raw["fairness"]),
        iterations=int(raw["iterations"]),
        converged=bool(raw["converged"]),
        objective=float(raw["objective"]),
        continuation_steps=int(raw["continuation_steps"]),
        point_parameters=np.asarray(raw["point_parameters"]),
        point_residuals=np.asarray(raw["point_residuals"]),
    )
