"""Form-parameter curve design (seed 002; SPEC section 4).

``design_curve`` finds the fairest clamped uniform B-spline (minimum e1 E1 + e2 E2 +
e3 E3 + s S, E_k = int |C^(k)|^2 dt over t in [0, 1]) that meets a chosen subset of form
parameters *exactly* (equality constraints, Lagrange-Newton / SQP with analytic
derivatives in the compiled engine), keeps a section a section (x monotone, y >= 0 on
the control polygon, by default) and reaches hard requests by continuation.
A request no such curve can meet raises :class:`fairlines.InfeasibleFormParameters`
(a ``ValueError``) naming the parameters in conflict and, where computable, the
achievable range.

Units: offsets in metres (any consistent length unit), angles in degrees from +x,
curvature in 1/length, Area in length^2.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from . import _native
from ._native import NurbsCurve

__all__ = ["FormCurveResult", "design_curve", "FORM_PARAMETERS", "form_parameters_of", "fairness_of"]

#: Names accepted in ``params``.
FORM_PARAMETERS = tuple(_native.form_parameter_names())

form_parameters_of = _native.form_parameters_of
fairness_of = _native.fairness_of


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


def _points(points, dim_hint):
    """-> list of (position, weight) with weight inf for interpolation."""
    if points is None:
        return []
    if isinstance(points, Mapping):
        unknown = set(points) - {"positions", "weights"}
        if unknown or "positions" not in points:
            raise ValueError(
                f"points mapping has keys {sorted(points)}; expected 'positions' (m x dim) and optional 'weights' (m,)"
            )
        pos = np.asarray(points["positions"], dtype=float)
        w = points.get("weights")
        w = np.full(len(pos), math.inf) if w is None else np.asarray(w, dtype=float).reshape(-1)
        if pos.ndim != 2 or len(w) != len(pos):
            raise ValueError(
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
            raise ValueError(
                f"points[{j}] = {item!r}; expected a position (x, y[, z]) or a pair (position, weight)"
            )
        pos, w = item
        w = math.inf if w is None else w
        out.append((np.asarray(pos, dtype=float).reshape(-1), w))
    return out


def _bounds(bounds):
    if bounds is None or bounds is True:
        return {}
    if bounds is False:
        return {"monotone_axis": -1, "y_nonnegative": False}
    if not isinstance(bounds, Mapping):
        raise ValueError(
            f"bounds = {bounds!r}; expected None, False or a mapping with keys monotone ('x', 'y' or None), "
            "y_nonnegative (bool), min_end_speed (float)"
        )
    out = {}
    for key, val in bounds.items():
        if key == "monotone":
            axes = {"x": 0, "y": 1, None: -1, False: -1}
            if val not in axes:
                raise ValueError(f"bounds monotone = {val!r}; expected 'x', 'y' or None")
            out["monotone_axis"] = axes[val]
        elif key in ("y_nonnegative", "min_end_speed"):
            out[key] = val
        else:
            raise ValueError(
                f"unknown bound {key!r}; expected monotone, y_nonnegative or min_end_speed"
            )
    return out


def design_curve(
    params,
    n_control: int = 8,
    degree: int = 3,
    fairness=None,
    points=None,
    bounds=None,
    *,
    dim: int | None = None,
    tangent_start=None,
    tangent_end=None,
    initial_control_points=None,
    tolerance: float = 1e-12,
    max_iterations: int = 400,
    continuation: bool = True,
    multistart: int = 0,
    seed: int = 1,
) -> FormCurveResult:
    """Design the fairest B-spline curve meeting the requested form parameters exactly.

    params      mapping, any subset of xB, yB, xE, yE, alphaB, alphaE (deg from +x),
                CAB, CAE (signed curvature), Area (int y dx start to end), xC, yC
                (centroid of that area); zB, zE for 3-D curves
    n_control   number of control points (>= degree + 1, and more than the conditions
                need: the remaining freedom is used for fairness)
    degree      B-spline degree (>= 2)
    fairness    mapping of weights {e1, e2, e3, length}; default {"e2": 1}
    points      offsets to interpolate: (m, dim) array; or pairs (position, weight)
                where a finite weight approximates (adds weight * distance^2); or
                {"positions": (m, dim), "weights": (m,)} (inf = interpolate)
    bounds      None (default: x monotone from start to end, control y >= 0,
                end speed >= 0.2 * chord where an end angle is given), False (no
                bounds), or a mapping {monotone: 'x' | 'y' | None, y_nonnegative: bool,
                min_end_speed: float}
    dim         2 or 3 (default: 3 if zB/zE/tangents/3-D points are given, else 2)
    tangent_start, tangent_end   3-D tangent directions (dim 3)
    initial_control_points       (n_control, dim) start curve (must meet the bounds)
    tolerance, max_iterations, continuation, multistart, seed   solver options

    Returns FormCurveResult. Raises InfeasibleFormParameters (ValueError) when no
    curve can meet the request and ValueError on malformed input.
    """
    if not isinstance(params, Mapping):
        raise ValueError(f"params must be a mapping of form parameter names to values, got {type(params).__name__}")
    for name, val in (("n_control", n_control), ("degree", degree), ("max_iterations", max_iterations),
                      ("multistart", multistart), ("seed", seed)):
        if not _is_int(val):
            raise ValueError(f"{name} = {val!r}; expected an integer")
    for key in params:
        if not isinstance(key, str):
            raise ValueError(f"form parameter name {key!r} is not a string; expected one of {', '.join(FORM_PARAMETERS)}")
    if fairness is None:
        fairness = {"e2": 1.0}
    elif not isinstance(fairness, Mapping):
        raise ValueError(f"fairness = {fairness!r}; expected a mapping with keys e1, e2, e3, length")
    else:
        fairness = {"e1": 0.0, "e2": 0.0, "e3": 0.0, "length": 0.0, **fairness}
    pts = _points(points, dim)
    if dim is None:
        three = (
            "zB" in params
            or "zE" in params
            or tangent_start is not None
            or tangent_end is not None
            or any(len(p) == 3 for p, _ in pts)
            or (initial_control_points is not None and np.asarray(initial_control_points).shape[-1:] == (3,))
        )
        dim = 3 if three else 2
    if not _is_int(dim):
        raise ValueError(f"dim = {dim!r}; expected 2 or 3")
    options = {
        "tolerance": tolerance,
        "max_iterations": max_iterations,
        "continuation": bool(continuation),
        "multistart": multistart,
        "seed": seed,
    }
    raw = _native._design_form_curve(
        dict(params), int(n_control), int(degree), int(dim), dict(fairness), list(pts), _bounds(bounds), options,
        tangent_start, tangent_end, initial_control_points,
    )
    curve = NurbsCurve(raw["degree"], raw["knots"], raw["control_points"])
    return FormCurveResult(
        curve=curve,
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
