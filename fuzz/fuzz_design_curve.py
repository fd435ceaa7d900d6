"""Fuzz design_curve's parameter dicts. An input starting with '{' is a JSON object whose
entries are design_curve's arguments (params, n_control, degree, fairness, points, bounds,
dim, tangent_start, tangent_end, initial_control_points, tolerance, max_iterations,
continuation, multistart, seed), any JSON value in any of them; any other input is decoded
by atheris' FuzzedDataProvider into a request of valid and invalid names, extreme and
ordinary numbers, sizes and options, so the solver itself is exercised.

Sizes within the engine's limits are capped (n_control 30, max_iterations 400, multistart 2)
to keep each run short; sizes beyond the limits pass through and must be refused.
"""

import json
import math

import atheris
import common
from common import EXPECTED, fl

ARGUMENTS = ("params", "n_control", "degree", "fairness", "points", "bounds", "dim", "tangent_start",
             "tangent_end", "initial_control_points", "tolerance", "max_iterations", "continuation",
             "multistart", "seed")
CAPS = {"n_control": (30, fl._native.limits.MAX_FORM_CURVE_CONTROL_POINTS),
        "max_iterations": (400, fl._native.limits.MAX_FORM_CURVE_ITERATIONS),
        "multistart": (2, fl._native.limits.MAX_FORM_CURVE_MULTISTART)}


NAMES = list(fl.FORM_PARAMETERS) + ["e22", "Volume", "", "xb", "alpha"]
SPECIAL = [0.0, -0.0, 1.0, -1.0, 1e-300, 1e300, -1e300, math.inf, -math.inf, math.nan, 360.0, 1e9, 0.5]


def _number(fdp):
    """An ordinary number most of the time, an extreme or special one otherwise."""
    kind = fdp.ConsumeIntInRange(0, 3)
    if kind == 0:
        return fdp.PickValueInList(SPECIAL)
    if kind == 1:
        return fdp.ConsumeRegularFloat()
    return fdp.ConsumeFloatInRange(-2.0, 2.0)


def provided_arguments(data: bytes):
    """design_curve's keyword arguments decoded from raw bytes."""
    fdp = atheris.FuzzedDataProvider(data)
    params = {fdp.PickValueInList(NAMES): _number(fdp) for _ in range(fdp.ConsumeIntInRange(0, 8))}
    kwargs = {"params": params, "n_control": fdp.ConsumeIntInRange(-2, 40), "degree": fdp.ConsumeIntInRange(-1, 17)}
    if fdp.ConsumeBool():
        kwargs["fairness"] = {fdp.PickValueInList(["e1", "e2", "e3", "length", "e5"]): _number(fdp)
                              for _ in range(fdp.ConsumeIntInRange(0, 3))}
    if fdp.ConsumeBool():
        dim = fdp.ConsumeIntInRange(1, 4)
        kwargs["points"] = [([_number(fdp) for _ in range(dim)], fdp.PickValueInList([None, 1.0, 1e-3, -1.0, math.inf]))
                            for _ in range(fdp.ConsumeIntInRange(0, 4))]
    if fdp.ConsumeBool():
        kwargs["bounds"] = fdp.PickValueInList([False, None, {"monotone": None}, {"monotone": "y"},
                                                {"y_nonnegative": False}, {"min_end_speed": 0.9}, {"convex": 1}])
    if fdp.ConsumeBool():
        kwargs["tangent_start"] = [_number(fdp) for _ in range(3)]
    if fdp.ConsumeBool():
        kwargs["multistart"] = fdp.ConsumeIntInRange(0, 2)
    kwargs["max_iterations"] = fdp.ConsumeIntInRange(0, 400)
    return kwargs


def arguments(data: bytes):
    """design_curve's keyword arguments from the input, or None when it is not a JSON object."""
    if not data.lstrip().startswith(b"{"):
        return provided_arguments(data)
    try:
        request = json.loads(data.decode("utf-8", errors="replace"))
    except (ValueError, RecursionError):
        return None
    if not isinstance(request, dict):
        return None
    kwargs = {k: v for k, v in request.items() if k in ARGUMENTS}
    for key, (cap, limit) in CAPS.items():
        value = kwargs.get(key)
        if isinstance(value, int) and not isinstance(value, bool) and cap < value <= limit:
            kwargs[key] = cap
    kwargs.setdefault("params", {})
    return kwargs


def test_one_input(data: bytes) -> None:
    kwargs = arguments(data)
    if kwargs is None:
        return
    try:
        fl.design_curve(**kwargs)
    except EXPECTED + (fl.ConvergenceError,):
        pass


if __name__ == "__main__":
    common.main(test_one_input)
