"""Basic curves of a hull: each the fairest spline function of x meeting its form parameters
(fairlines.design_spline_function), and the sectional area curve designed through the sections'
fullness so that every section it asks for can be built.

The SAC is A(x) = 2 y_dwl(x) (T - z_keel(x)) s(x): the box the DWL and the centre profile leave
a section, times the section's fullness s. Every SAC form parameter -- volume, LCB, end values,
end slopes and curvatures, a flat part, points -- is linear in s for the given DWL and profile,
so designing s is one QP like any other basic curve; bounds on s keep every section inside the
fullness a fair section can have, and A vanishes by itself where the DWL or the immersed depth
does.
"""

from __future__ import annotations

import contextlib
import contextvars
import functools
import math
from collections import OrderedDict
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import _native
from .description import FORM_ALIASES, BasicCurveSpec

__all__ = ["BasicCurve", "solve_curve", "solve_sac", "solve_sac_area", "immersed_range", "terse_errors", "FULLNESS_BOUNDS"]

#: Section fullness A / (2 y_dwl (T - z_keel)) a designed SAC keeps within (a convex section
#: through the DWL point with a flat keel has at least half its box; at most the box).
FULLNESS_BOUNDS = (0.45, 0.995)
#: ... and with the bilge corner given (hollow sections hold less than half their box).
CORNER_FULLNESS_BOUNDS = (0.1, 0.995)
#: Weight of the fairness (int s''^2 dx, times the range cubed) against the fit when the SAC's
#: reference fullness is fitted to its fullness_fit points (and its flat part).
REFERENCE_FAIRNESS = 1e-6
#: ... and of the reference area of a SAC of given sections (fitted to their measured areas):
#: far smaller, so it follows a quick change of area (a bulb's neck ending within a metre) that
#: the fullness, a ratio, does not have.
AREA_REFERENCE_FAIRNESS = 1e-10
#: Knot spans of the factor that scales those areas onto the volume and LCB (linear unless a
#: flat part holds it).
AREA_FACTOR_SPANS = 4
#: Fullness of a section where the waterline ends on the centre plane (a straight wedge), and
#: the waterline breadth (fraction of its largest) below which an end counts as such.
WEDGE_FULLNESS = 0.5
WEDGE_BREADTH = 1e-9
#: Bisections of each range an infeasible curve's message names (to 2^-16 of the search span).
RANGE_STEPS = 16
#: A constant curve may lie this far past its bounds, relative to max(1, |value|): round-off in
#: a value read back from JSON, never a real excess.
CONSTANT_BOUND_TOL = 1e-12
#: The unit a constant curve's refusal names its range in (curves not listed: metres).
CURVE_UNITS = {"deadrise": " deg", "top_corner": " (a fraction of the freeboard)", "character": " (a fraction of the chord)",
               "corner_breadth": " (a fraction of the waterline's half-breadth)",
               "corner_height": " (a fraction of the immersed depth)",
               "flat_bottom": " (a fraction of the waterline's half-breadth)"}

_explain = contextvars.ContextVar("fairlines_explain_infeasible", default=True)


@contextlib.contextmanager
def terse_errors():
    """Within it, an infeasible basic curve's message names no feasible ranges: finding them
    takes some hundred solves, and callers that retry and explain at their own level (the
    designer, the importer) throw most of these errors away."""
    token = _explain.set(False)
    try:
        yield
    finally:
        _explain.reset(token)


def tersely(fn):
    """`fn` run within terse_errors()."""
    @functools.wraps(fn)
    def run(*args, **kwargs):
        with terse_errors():
            return fn(*args, **kwargs)
    return run


def _solved(r, integrals: list):
    """The request's spline with these integral conditions, or None when none meets it."""
    r.integrals = integrals
    try:
        return _native.design_spline_function(r)
    except _native.InfeasibleFormParameters:
        return None


def _interval(feasible, anchor: float, lo: float, hi: float) -> tuple[float, float]:
    """The feasible interval around `anchor` (feasible) within [lo, hi]: the feasible set of a
    curve's linear conditions is convex, so each side is one bisection."""
    ends = []
    for outside in (lo, hi):
        inside = anchor
        if feasible(outside):
            inside = outside
        else:
            for _ in range(RANGE_STEPS):
                mid = 0.5 * (inside + outside)
                inside, outside = (mid, outside) if feasible(mid) else (inside, mid)
        ends.append(inside)
    return ends[0], ends[1]


@dataclass
class BasicCurve:
    """A solved basic curve f(x) on [x_start, x_end]: a spline function (``curve``, a 1-D
    NurbsCurve whose parameter is x) or a constant ``value``."""

    name: str
    x_start: float
    x_end: float
    curve: Any = None
    value: float | None = None

    def __call__(self, x: Any, outside: float = math.nan) -> np.ndarray:
        """f at x (array); ``outside`` beyond the range."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        tol = 1e-9 * max(1.0, abs(self.x_end) + abs(self.x_start))
        inside = (x >= self.x_start - tol) & (x <= self.x_end + tol)
        out = np.full(x.shape, outside, dtype=float)
        if self.curve is None:
            out[inside] = self.value
        elif inside.any():
            out[inside] = np.asarray(self.curve.evaluate(clip(x[inside], self.x_start, self.x_end)))[:, 0]
        return out

    def derivative(self, x: float, order: int = 1) -> float:
        """d^order f / dx^order at x (0 for a constant)."""
        if self.curve is None or order > self.curve.degree:
            return 0.0
        return float(np.asarray(self.curve.derivatives(float(np.clip(x, self.x_start, self.x_end)), order))[order, 0])

    def integral(self, power: int = 0, lo: float | None = None, hi: float | None = None) -> float:
        """int x^power f dx over [lo, hi] (default the whole range), exact (the engine's
        fairlines.spline_product_integral). Raises InvalidInput for lo > hi or a range beyond
        the curve's."""
        lo = self.x_start if lo is None else lo
        hi = self.x_end if hi is None else hi
        return _native.spline_product_integral([self.factor()], lo, hi, power)

    def form_parameters(self) -> dict[str, float]:
        """Area (int f dx over the range) and its centroid xC, exact."""
        area = self.integral(0)
        return {"Area": area, "xC": self.integral(1) / area if area else math.nan}

    def factor(self, offset: float = 0.0, scale: float = 1.0):
        """offset + scale f as a 1-D spline (a weight factor for fairlines.SplineIntegral)."""
        if self.curve is None:
            k = np.array([self.x_start, self.x_start, self.x_end, self.x_end])
            return _native.NurbsCurve(1, k, np.full((2, 1), offset + scale * self.value))
        c = np.asarray(self.curve.control_points)
        return _native.NurbsCurve(self.curve.degree, np.asarray(self.curve.knots), offset + scale * c)


def _form_params(name: str, spec: BasicCurveSpec, path: str) -> dict[str, float]:
    """The spec's form parameters with aliases resolved and angles turned into slopes."""
    params = dict(spec.params)
    for alias, val in spec.aliases.items():
        key, factor = FORM_ALIASES[name][alias]
        if key in params:
            raise _native.InvalidInput(f"{path}.{alias} and {path}.{key} are both given; expected one of them")
        params[key] = factor * val
    for side in ("B", "E"):
        if f"alpha{side}" in params and f"slope{side}" in params:
            raise _native.InvalidInput(f"{path}.alpha{side} and {path}.slope{side} are both given; expected one of them")
        if f"alpha{side}" in params:
            a = params.pop(f"alpha{side}")
            if not -90 < a < 90:
                raise _native.InvalidInput(f"{path}.alpha{side} is {a}; expected an angle between -90 and 90 degrees")
            params[f"slope{side}"] = math.tan(math.radians(a))
    return params


@dataclass
class _Plan:
    """Where a curve lives and its flat part, checked against its range."""

    xs: float
    xe: float
    flat: tuple[float, float] | None
    value: float | None


def _plan(spec: BasicCurveSpec, x0: float, x1: float, path: str) -> _Plan:
    tol = 1e-9 * max(1.0, abs(x0) + abs(x1))
    xs = spec.x_start if spec.x_start is not None else x0
    xe = spec.x_end if spec.x_end is not None else x1
    if xs < x0 - tol or xe > x1 + tol or not xs < xe:
        raise _native.InvalidInput(f"{path}: x_start / x_end are {xs} / {xe}; expected {x0:.6g} <= x_start < x_end <= {x1:.6g} m")
    flat = None
    if spec.flat_to is not None or spec.flat_from is not None:
        ff = spec.flat_from if spec.flat_from is not None else xs
        ft = spec.flat_to if spec.flat_to is not None else xe
        if ff < xs - tol or ft > xe + tol:
            raise _native.InvalidInput(f"{path}: the flat part {ff} .. {ft} m is not inside the curve's range {xs:.6g} .. {xe:.6g} m")
        flat = (max(ff, xs), min(ft, xe))
    return _Plan(xs, xe, flat, spec.value)


def _conditions(params: dict, plan: _Plan, path: str, to_unknown) -> list:
    """End conditions as SplineConditions; `to_unknown(x, [c0, c1, c2], value)` maps a
    condition on f (sum c_k f^(k)(x) = value) to one on the designed spline."""
    out = []
    starts_flat = plan.flat is not None and plan.flat[0] <= plan.xs
    ends_flat = plan.flat is not None and plan.flat[1] >= plan.xe
    for side, x, flat in (("B", plan.xs, starts_flat), ("E", plan.xe, ends_flat)):
        y, s, k = params.get(f"y{side}"), params.get(f"slope{side}"), params.get(f"CA{side}")
        if flat:
            if y is not None and abs(y - plan.value) > 1e-9 * (1 + abs(plan.value)):
                raise _native.InvalidInput(f"{path}.y{side} is {y}; at the end of the flat part it is value = {plan.value}")
            if (s not in (None, 0.0)) or (k not in (None, 0.0)):
                raise _native.InvalidInput(f"{path}: an end angle or curvature is given at the flat part's end; "
                                           "the curve leaves a flat part with zero slope and curvature")
            continue
        alpha = "alphaB" if side == "B" else "alphaE"
        if y is not None:
            out += to_unknown(x, [1.0], y, f"y{side}")
        if s is not None:
            out += to_unknown(x, [0.0, 1.0], s, alpha)
        if k is not None:
            if s is None and k != 0:
                raise _native.InvalidInput(f"{path}.CA{side} is {k} without {alpha}; expected the end slope too (or CA{side} = 0)")
            out += to_unknown(x, [0.0, 0.0, 1.0], k * (1.0 + (s or 0.0) ** 2) ** 1.5, f"CA{side}")
    return out


def _monotone(plan: _Plan, params: dict, maximum: bool) -> list:
    """f' signs that make f move away from its flat part monotonically: down from a flat
    maximum, up from a flat minimum (an end value above the flat value says which; without
    one `maximum` decides)."""
    if plan.flat is None:
        return []
    out = []
    for side, (a, b), end in (("B", (plan.xs, plan.flat[0]), params.get("yB")), ("E", (plan.flat[1], plan.xe), params.get("yE"))):
        if not a < b:
            continue
        is_max = maximum if end is None or end == plan.value else end < plan.value
        sign = (1 if is_max else -1) * (1 if side == "B" else -1)
        out.append(_native.SplineShape(a, b, 1, sign, "monotone " + ("toward" if side == "B" else "away from") + " the flat part"))
    return out


def _curvature_signs(spec: BasicCurveSpec, plan: _Plan) -> list:
    """The spec's convex / concave ranges (clipped to the curve) as f'' sign conditions."""
    out = []
    for key, sign in (("convex", -1), ("concave", 1)):
        for a, b, k in getattr(spec, key):
            a, b = max(a, plan.xs), min(b, plan.xe)
            if a < b:
                out.append(_native.SplineShape(a, b, 2, sign, f"{key} {a:.5g} .. {b:.5g} m", k))
    return out


def _request(name: str, plan: _Plan, spec: BasicCurveSpec, path: str, stations=()) -> Any:
    """The request with its knots: `spans` spread over the pieces between the breakpoints, or a
    knot at every one of `stations` when given (then no piece needs more than one span)."""
    r = _native.SplineDesignRequest()
    r.name = path
    r.e3 = spec.e3
    breaks = [x for x in (*(plan.flat or ()), *spec.breaks, *(x for x, _ in spec.slopes), *stations) if plan.xs < x < plan.xe]
    r.knots = _native.spline_function_knots(plan.xs, plan.xe, breaks, spec.spans, 3, 1 if len(stations) else 4)
    return r


def clip(a: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """np.clip(a, lo, hi) for lo <= hi, the same values: on short rows np.clip's own overhead
    was most of its cost, and the stations' rows are read on every rebuild."""
    return np.minimum(np.maximum(a, lo), hi)


class BuildCache:
    """Results of pure build steps kept by the value of everything they read (the most recent
    `size`), shared by every Hull: a hull copied with only its SAC changed (a slider in the
    Blender add-on) re-solves the SAC alone. A hit returns the very objects a miss would have
    computed from the same inputs, so the geometry is bit for bit the same; callers never
    modify them."""

    def __init__(self, size: int):
        self.size = size
        self.entries: OrderedDict = OrderedDict()

    def get(self, key, compute):
        try:
            self.entries.move_to_end(key)
            return self.entries[key]
        except KeyError:  # not computed yet (or dropped by another thread meanwhile)
            pass
        value = self.entries[key] = compute()
        if len(self.entries) > self.size:
            self.entries.popitem(last=False)
        return value

    def clear(self) -> None:
        self.entries.clear()


# Recent solved curves kept by the value of everything solve_curve reads: the designer solves
# the profile and the waterline, then the hull it builds solves them again, and a match
# rebuild that changes only the SAC and the waterline's area solves the rest again. The SAC's
# reference fullness reads neither the volume nor the LCB, so a SAC slider re-solves the SAC alone.
CURVE_CACHE_SIZE = 32
_curve_cache = BuildCache(CURVE_CACHE_SIZE)
_reference_cache = BuildCache(CURVE_CACHE_SIZE)  # _reference_fullness


def clear_curve_cache() -> None:
    """Forget every cached basic curve (tests compare cold and warm builds)."""
    _curve_cache.clear()
    _reference_cache.clear()


def solve_curve(name: str, spec: BasicCurveSpec, x0: float, x1: float, *, lower: float | None = None,
                upper: float | None = None, maximum: bool = True, defaults: dict | None = None,
                at_least: list | None = None) -> BasicCurve:
    """Solve one basic curve on its range [x0, x1] (the spec may narrow it). `lower` / `upper`:
    physical bounds unless the spec gives its own; `maximum`: a flat part is its maximum
    (monotone away from it); `defaults`: form parameters used unless the spec gives them;
    `at_least`: [(x, y, what), ...] points where f(x) >= y (another curve it must clear).
    A repeated request returns the curve solved before (callers never modify it). Raises
    InvalidInput for a bad form parameter, InfeasibleFormParameters when none fits."""
    key = (name, repr(spec), float(x0), float(x1), lower, upper, maximum, repr(defaults), repr(at_least))
    return _curve_cache.get(key, lambda: _solve_curve(name, spec, x0, x1, lower, upper, maximum, defaults, at_least))


def _solve_curve(name, spec, x0, x1, lower, upper, maximum, defaults, at_least) -> BasicCurve:
    path = f"basic_curves.{name}"
    plan = _plan(spec, x0, x1, path)
    if spec.constant:
        _check_constant(path, spec, lower, upper, at_least, plan)
        return BasicCurve(name, plan.xs, plan.xe, None, spec.value)
    params = {**(defaults or {}), **_form_params(name, spec, path)}
    r = _request(name, plan, spec, path)

    def direct(x, combo, value, what):
        return [_native.SplineCondition(x, 0, value, what, combo)]

    r.conditions = _conditions(params, plan, path, direct)
    r.conditions += [_native.SplineCondition(x, 0, y, "points") for x, y in spec.points]
    r.conditions += [_native.SplineCondition(x, 1, v, "slopes") for x, v in spec.slopes]
    if "Area" in params:
        r.integrals = [_native.SplineIntegral(plan.xs, plan.xe, params["Area"], name="Area")]
    if "xC" in params:
        if "Area" not in params:
            raise _native.InvalidInput(f"{path}.xC is given without the area; expected both (the centroid of a given area)")
        r.integrals += [_native.SplineIntegral(plan.xs, plan.xe, centroid=params["xC"], name="xC")]
    if plan.flat is not None:
        r.flats = [_native.SplineFlat(plan.flat[0], plan.flat[1], plan.value, "flat part")]
    lo = spec.lower if spec.lower is not None else lower
    hi = spec.upper if spec.upper is not None else upper
    if lo is not None or hi is not None:
        r.bounds = [_native.SplineBound(plan.xs, plan.xe, math.nan if lo is None else lo, math.nan if hi is None else hi,
                                        f"{'' if lo is None else f'{lo:.6g} <= '}{name}{'' if hi is None else f' <= {hi:.6g}'}")]
    r.bounds += [_native.SplineBound(x, x, y, math.nan, what) for x, y, what in (at_least or []) if plan.xs <= x <= plan.xe]
    r.shapes = _monotone(plan, params, maximum) if spec.monotone else []
    r.shapes += _curvature_signs(spec, plan)
    r.fit = [_native.SplineFitPoint(x, y, spec.fit_weight) for x, y in spec.fit]
    try:
        return BasicCurve(name, plan.xs, plan.xe, _native.design_spline_function(r), None)
    except _native.InfeasibleFormParameters as e:
        if "Area" not in params or lo is None or hi is None or not _explain.get():
            raise
        said = _area_ranges(name, spec, r, plan, params, (lo, hi))
        raise _native.InfeasibleFormParameters(f"{e}{'; ' + said if said else ''}") from None


def _check_constant(path: str, spec: BasicCurveSpec, lower, upper, at_least, plan: _Plan) -> None:
    """A constant is not solved, so its bounds and the curves it must clear are checked here
    (it was taken as given: a top_corner of 5 or a deck outside B/2 built): the physical bounds
    and the spec's own both (the sections clip a shape curve to the physical ones). Raises
    InvalidInput naming the value and the range it must lie in."""
    lo = max((b for b in (lower, spec.lower) if b is not None), default=None)
    hi = min((b for b in (upper, spec.upper) if b is not None), default=None)
    v = spec.value
    tol = CONSTANT_BOUND_TOL * max(1.0, abs(v))
    if (lo is not None and v < lo - tol) or (hi is not None and v > hi + tol):
        span = (f"{lo:.6g} to {hi:.6g}" if lo is not None and hi is not None
                else f"at least {lo:.6g}" if lo is not None else f"at most {hi:.6g}")
        unit = CURVE_UNITS.get(path.rsplit(".", 1)[-1], " m")
        raise _native.InvalidInput(f"{path}.value is {v:g}; expected {span}{unit}")
    for x, y, what in at_least or []:
        if plan.xs <= x <= plan.xe and v < y - tol:
            raise _native.InvalidInput(f"{path}.value is {v:g}; expected at least {y:.6g} at x = {x:.6g} m ({what})")


def _area_ranges(name: str, spec: BasicCurveSpec, r, plan: _Plan, params: dict, bounds: tuple) -> str:
    """For an infeasible curve with an area (a waterline's): the areas a curve within its other
    conditions can have, and those with its centroid as asked, in the spec's own terms."""
    alias = next((a for a in spec.aliases if FORM_ALIASES.get(name, {}).get(a, ("",))[0] == "Area"), None)
    scale, key = (1.0 / FORM_ALIASES[name][alias][1], alias) if alias else (1.0, "Area")

    def solve(area=None, centroid=None):  # the curve's only integrals are its area and centroid
        return _solved(r, ([] if area is None else [_native.SplineIntegral(plan.xs, plan.xe, area, name="Area")]) +
                       ([] if centroid is None else [_native.SplineIntegral(plan.xs, plan.xe, centroid=centroid, name="xC")]))

    def area_of(c) -> float:
        return _native.spline_product_integral([c], plan.xs, plan.xe, 0)

    free = solve()
    if free is None:
        return ""
    lo, hi = (b * (plan.xe - plan.xs) for b in bounds)
    a, b = _interval(lambda v: solve(area=v) is not None, area_of(free), lo, hi)
    out = [f"a {name} within its other conditions has {key} {scale * a:.6g} to {scale * b:.6g} m^2"]
    at = solve(centroid=params["xC"]) if "xC" in params else None
    if at is not None:
        a, b = _interval(lambda v: solve(area=v, centroid=params["xC"]) is not None, area_of(at), lo, hi)
        out.append(f"with its centroid at {params['xC']:.6g} m, {scale * a:.6g} to {scale * b:.6g} m^2")
    return "; ".join(out) + f": give basic_curves.{name}.{key} within this"


CROSSING_TOL = 1e-13       # where the profile crosses T: to this fraction of its length
CROSSING_ITERATIONS = 60


def immersed_range(profile: BasicCurve, draft: float, samples: int = 2001) -> tuple[float, float]:
    """The x range where the centre profile is below the draft (the DWL's range): one interval,
    its ends found by bisection to round-off. Kept on the profile (a solved curve does not
    change): the designer and the hull's builds ask for it again and again. Raises
    InfeasibleFormParameters when the profile is nowhere below the draft, or rises above it
    between two immersed parts."""
    known = profile.__dict__.setdefault("_immersed", {})
    if (draft, samples) not in known:
        known[(draft, samples)] = _immersed_range(profile, draft, samples)
    return known[(draft, samples)]


def _immersed_range(profile: BasicCurve, draft: float, samples: int) -> tuple[float, float]:
    xs = np.linspace(profile.x_start, profile.x_end, samples)
    below = profile(xs) < draft
    if not below.any():
        raise _native.InfeasibleFormParameters(
            f"basic_curves.profile is above the draft T = {draft} m everywhere; expected a keel below the waterline")
    idx = np.flatnonzero(below)
    if np.any(np.diff(idx) != 1):
        raise _native.InfeasibleFormParameters("basic_curves.profile rises above the draft between two immersed parts; "
                                               "expected one immersed stretch (one design waterline)")

    tol = CROSSING_TOL * (profile.x_end - profile.x_start)

    def crossing(a: float, b: float) -> float:
        """Illinois regula falsi on the bracket [a, b] (superlinear, keeps the bracket)."""
        fa, fb = profile(a)[0] - draft, profile(b)[0] - draft
        side = 0
        for _ in range(CROSSING_ITERATIONS):
            m = (a * fb - b * fa) / (fb - fa) if fb != fa else 0.5 * (a + b)
            fm = profile(m)[0] - draft
            if fm == 0 or abs(b - a) < tol:
                return m
            if (fm < 0) == (fa < 0):
                a, fa = m, fm
                fb = 0.5 * fb if side == -1 else fb
                side = -1
            else:
                b, fb = m, fm
                fa = 0.5 * fa if side == 1 else fa
                side = 1
        return m

    i0, i1 = idx[0], idx[-1]
    x_a = xs[0] if i0 == 0 else crossing(xs[i0 - 1], xs[i0])
    x_f = xs[-1] if i1 == samples - 1 else crossing(xs[i1 + 1], xs[i1])
    return float(x_a), float(x_f)


#: Where the SAC's messages say a value was given.
_SAC_PATH = "basic_curves.sac"


@dataclass
class _Box:
    """w(x) = 2 y_dwl(x) (T - z_keel(x)): the box the DWL and the centre profile leave a section.
    The SAC is A = w s, s the section fullness the SAC is designed through."""

    dwl: BasicCurve
    profile: BasicCurve
    draft: float

    def derivatives(self, x: float) -> tuple[float, float, float]:
        """w and its first two derivatives at x."""
        yv = [float(self.dwl(x)[0])] + [self.dwl.derivative(x, k) for k in (1, 2)]
        dv = [self.draft - float(self.profile(x)[0])] + [-self.profile.derivative(x, k) for k in (1, 2)]
        return (2 * yv[0] * dv[0], 2 * (yv[1] * dv[0] + yv[0] * dv[1]), 2 * (yv[2] * dv[0] + 2 * yv[1] * dv[1] + yv[0] * dv[2]))

    def through_fullness(self, x, combo, value, what) -> list:
        """The condition sum c_k A^(k)(x) = value as one on s (nothing where the box vanishes
        with its slope and the value is zero; InfeasibleFormParameters where it is not)."""
        # A' = w s' + w' s, A'' = w s'' + 2 w' s' + w'' s.
        w, w1, w2 = self.derivatives(x)
        c = list(combo) + [0.0] * (3 - len(combo))
        coeffs = [c[0] * w + c[1] * w1 + c[2] * w2, c[1] * w + 2 * c[2] * w1, c[2] * w]
        if max(abs(v) for v in coeffs) <= 1e-12 * max(1.0, abs(w) + abs(w1)):
            if abs(value) > 1e-9 * max(1.0, abs(value)):
                raise _native.InfeasibleFormParameters(
                    f"{_SAC_PATH}.{what} is {value:.6g} at x = {x:.6g} m where the DWL and the immersed depth leave no section")
            return []
        while coeffs and coeffs[-1] == 0.0:
            coeffs.pop()
        return [_native.SplineCondition(x, 0, value, what, coeffs)]

    def factors(self) -> list:
        """y_dwl and T - z_keel as weight factors of the fullness's integrals (w / 2)."""
        return [self.dwl.factor(), self.profile.factor(offset=self.draft, scale=-1.0)]


def _wedge_ends(dwl: BasicCurve, plan: _Plan, wedge_flat: bool, free_ends: tuple) -> list:
    """Where the waterline ends on the centre plane the immersed part is a wedge between the
    waterline and the centre-line contour: its sections are straight, of fullness one half
    (not at `free_ends`: a post's sections shrink to a line keeping their shape; sections with a
    given bilge corner keep it to the waterline's end)."""
    widest = max(dwl.value or 0.0, float(np.max(dwl(np.linspace(dwl.x_start, dwl.x_end, 33)))))
    out = []
    for x_end in (plan.xs, plan.xe):
        if dwl(x_end)[0] <= WEDGE_BREADTH * widest and not any(abs(x_end - xp) <= 1e-9 * (plan.xe - plan.xs) for xp in free_ends):
            out.append(_native.SplineCondition(x_end, 0, WEDGE_FULLNESS, "fullness where the waterline ends (a wedge)"))
            # ... and stays near one half for a while (no slope), so the sections there stay near
            # the straight V that the dry sections beyond continue
            if wedge_flat:
                out.append(_native.SplineCondition(x_end, 1, 0.0, "fullness slope where the waterline ends"))
    return out


def _volume_and_lcb(plan: _Plan, params: dict, factors: list, share: float = 0.5) -> list:
    """The SAC's volume and LCB as weighted integrals of the designed curve: `share` of the
    volume (the fullness times the factors holds one side's: 1/2; the area itself all of it)."""
    integrals = []  # (pybind11 list fields are copies: build, then assign)
    if "Area" in params:
        integrals.append(_native.SplineIntegral(plan.xs, plan.xe, share * params["Area"], factors=factors, name="volume"))
    if "xC" in params:
        if "Area" not in params:
            raise _native.InvalidInput(f"{_SAC_PATH}.lcb is given without the volume; expected both")
        integrals.append(_native.SplineIntegral(plan.xs, plan.xe, centroid=params["xC"], factors=factors, name="lcb"))
    return integrals


def _flat_fullness(plan: _Plan, box: _Box) -> list:
    """The SAC's flat part as a flat fullness: the box must be constant over it."""
    a, b = plan.flat
    xs_ = np.linspace(a, b, 9)
    w = 2 * box.dwl(xs_) * (box.draft - box.profile(xs_))
    if np.ptp(w) > 1e-9 * np.max(np.abs(w)):
        raise _native.InfeasibleFormParameters(
            f"{_SAC_PATH}: the flat part {a:.6g} .. {b:.6g} m needs a constant box 2 y_dwl (T - z_keel) there; expected the DWL "
            "and the profile flat over it (dwl / profile flat parts cover the SAC's)")
    return [_native.SplineFlat(a, b, plan.value / w[0], "flat part (midship section area)")]


def _fullness_bounds(plan: _Plan, fullness: tuple[float, float], bands) -> list:
    """Fullness kept within `fullness` everywhere and within each station's band at its x."""
    lo, hi = fullness
    bounds = [_native.SplineBound(plan.xs, plan.xe, lo, hi, f"section fullness {lo:.3g} .. {hi:.3g}")]
    bounds += [_native.SplineBound(x, x, a, b, f"section fullness at x = {x:.5g} m: {a:.3g} .. {b:.3g}")
               for x, a, b in (bands or []) if plan.xs < x < plan.xe]
    return bounds


def _fullness_fit(spec: BasicCurveSpec, box: _Box) -> list:
    """The SAC's fit points as fullness points, weighted by w^2 (the same residual in A)."""
    fit = []
    for x, a in spec.fit:
        w = box.derivatives(x)[0]
        if w > 0:
            fit.append(_native.SplineFitPoint(x, a / w, spec.fit_weight * w * w))
    return fit


def _reference_fullness(spec: BasicCurveSpec, plan: _Plan, r) -> np.ndarray | None:
    """The fullness to stay near (fitted to fullness_fit, on the request's knots and with its
    flat part): the SAC is it changed as fairly as possible to meet the volume, the LCB and the
    rest. None without fullness_fit points in the range."""
    pts = [(x, f) for x, f in spec.fullness_fit if plan.xs <= x <= plan.xe]
    if not pts:
        return None
    key = (tuple(r.knots), tuple((f.from_, f.to, f.value) for f in r.flats), plan.xs, plan.xe, tuple(pts))

    def fit():
        ref = _native.SplineDesignRequest()
        ref.name, ref.knots = f"{_SAC_PATH}.fullness_fit", r.knots
        ref.flats = r.flats
        ref.e2 = REFERENCE_FAIRNESS * (plan.xe - plan.xs) ** 3 / len(pts)
        ref.fit = [_native.SplineFitPoint(x, f, 1.0) for x, f in pts]
        out = np.asarray(_native.design_spline_function(ref).control_points)[:, 0]
        out.flags.writeable = False  # shared by every request with this key
        return out

    return _reference_cache.get(key, fit)


def _sac_request(spec: BasicCurveSpec, dwl: BasicCurve, profile: BasicCurve, draft: float, fullness, bands, targets: bool,
                 wedge_flat: bool = True, free_ends: tuple = ()):
    """The fullness design request of the SAC (with or without its volume and LCB; with or
    without the level fullness where the waterline ends on the centre plane)."""
    path = _SAC_PATH
    plan = _plan(spec, dwl.x_start, dwl.x_end, path)
    params = _form_params("sac", spec, path)
    box = _Box(dwl, profile, draft)
    # A knot at every station with a band: the fullness can follow the sections' limits where
    # they change quickly (near the ends), E2 keeps it fair.
    r = _request("sac", plan, spec, path, [x for x, _, _ in (bands or [])])
    r.conditions = _conditions(params, plan, path, box.through_fullness) + _wedge_ends(dwl, plan, wedge_flat, free_ends)
    for x, a in spec.points:
        r.conditions += box.through_fullness(x, [1.0], a, "points")
    factors = box.factors()
    r.integrals = _volume_and_lcb(plan, params, factors) if targets else []
    if plan.flat is not None:
        r.flats = _flat_fullness(plan, box)
    if spec.lower is not None or spec.upper is not None:
        raise _native.InvalidInput(f"{path}.lower / upper are not used; the SAC is bounded through the section fullness")
    r.bounds = _fullness_bounds(plan, fullness, bands)
    if spec.monotone:
        r.shapes = _monotone(plan, params, True)
    r.shapes = list(r.shapes) + _curvature_signs(spec, plan)  # on the fullness, as the rest
    r.fit = _fullness_fit(spec, box)
    reference = _reference_fullness(spec, plan, r)
    if reference is not None:
        r.reference = reference
    return r, plan, params, factors


class _SacProbe:
    """Solves of the SAC's fullness request with a given volume and / or LCB (or neither)."""

    def __init__(self, r, plan: _Plan, factors: list):
        self.r, self.plan, self.factors = r, plan, factors

    def solve(self, volume: float | None = None, lcb: float | None = None):
        """The fullness spline, or None when no SAC meets the request."""
        p = self.plan
        return _solved(self.r, ([] if volume is None else [_native.SplineIntegral(p.xs, p.xe, volume / 2.0, factors=self.factors)]) +
                       ([] if lcb is None else [_native.SplineIntegral(p.xs, p.xe, centroid=lcb, factors=self.factors)]))

    def moment(self, s, power: int) -> float:  # int x^power s w dx, w the box's factors (one side)
        return _native.spline_product_integral([s, *self.factors], self.plan.xs, self.plan.xe, power)

    def volume(self, s) -> float:
        return 2.0 * self.moment(s, 0)

    def lcb(self, s) -> float:
        return self.moment(s, 1) / self.moment(s, 0)


def _sac_ranges(r, plan: _Plan, params: dict, factors: list) -> str:
    """What the SAC's sections can hold (for the error message): the volume range, that range
    with the asked LCB (or the LCB range when no volume has it), and the LCB range at the asked
    volume. Each by bisection between a SAC that is built and the range's end."""
    probe = _SacProbe(r, plan, factors)
    free = probe.solve()
    if free is None:
        return "no SAC meets its end conditions, flat part and section fullness with this DWL and profile"
    box = 2.0 * _native.spline_product_integral(list(factors), plan.xs, plan.xe, 0)
    vlo, vhi = _interval(lambda v: probe.solve(volume=v) is not None, probe.volume(free), 0.0, box)
    out = [f"the sections this DWL and profile allow hold {vlo:.6g} to {vhi:.6g} m^3"]
    if "xC" in params:
        at = probe.solve(lcb=params["xC"])
        if at is None:
            llo, lhi = _interval(lambda x: probe.solve(lcb=x) is not None, probe.lcb(free), plan.xs, plan.xe)
            out.append(f"their LCB can lie from {llo:.6g} to {lhi:.6g} m")
        else:
            a, b = _interval(lambda v: probe.solve(volume=v, lcb=params["xC"]) is not None, probe.volume(at), 0.0, box)
            out.append(f"with the LCB at {params['xC']:.6g} m, {a:.6g} to {b:.6g} m^3")
    vol = params.get("Area")
    s = probe.solve(volume=vol) if vol is not None and vlo <= vol <= vhi else None
    if s is not None and "xC" in params:
        a, b = _interval(lambda x: probe.solve(volume=vol, lcb=x) is not None, probe.lcb(s), plan.xs, plan.xe)
        out.append(f"at {vol:.6g} m^3 their LCB can lie from {a:.6g} to {b:.6g} m")
    return "; ".join(out)


def solve_sac(spec: BasicCurveSpec, dwl: BasicCurve, profile: BasicCurve, draft: float,
              fullness: tuple[float, float] = FULLNESS_BOUNDS, bands: list | None = None,
              free_ends: tuple = ()) -> tuple[BasicCurve, BasicCurve]:
    """The SAC (m^2, both sides) and the section fullness it is designed through, on the DWL's
    range. Every SAC form parameter is mapped onto the fullness (see the module docstring).
    `bands`: [(x, least, largest), ...] fullness the section at x can have (the sections'
    own limits, fairlines.section_fullness_bands), kept at those points. `free_ends`: x of
    waterline ends where the fullness is free (not the wedge's 1/2). Raises
    InfeasibleFormParameters for an infeasible request, naming the volume and LCB ranges the
    sections can hold."""
    params = None
    try:
        try:
            r, plan, params, factors = _sac_request(spec, dwl, profile, draft, fullness, bands, True, free_ends=free_ends)
            s = _native.design_spline_function(r)
        except _native.InfeasibleFormParameters:  # a short run: the fullness may rise at once
            r, plan, params, factors = _sac_request(spec, dwl, profile, draft, fullness, bands, True, wedge_flat=False,
                                                      free_ends=free_ends)
            s = _native.design_spline_function(r)
    except _native.InfeasibleFormParameters:
        if params is None:  # the request itself cannot be made (a flat part off the box's): its message says why
            raise
        said = (f"{_SAC_PATH}: volume {params.get('Area', float('nan')):.6g} m^3 with lcb {params.get('xC', float('nan')):.6g} m "
                "cannot be met by fair sections")
        if _explain.get():
            r2, plan2, params2, factors2 = _sac_request(spec, dwl, profile, draft, fullness, bands, False, free_ends=free_ends)
            said += (f": {_sac_ranges(r2, plan2, params2, factors2)}; give {_SAC_PATH}.volume and .lcb within these, "
                     "or change the DWL or the profile that bound the sections")
        raise _native.InfeasibleFormParameters(said) from None
    full = BasicCurve("fullness", plan.xs, plan.xe, s, None)
    return _ProductCurve("sac", plan.xs, plan.xe, full, dwl, profile, draft), full


def solve_sac_area(spec: BasicCurveSpec, dwl: BasicCurve, profile: BasicCurve, draft: float) -> BasicCurve:
    """The SAC (m^2, both sides) designed directly as area on the DWL's range, for hulls whose
    sections are given (``sections.given``): a given section holds the area it was measured
    with, which the fullness SAC / (2 y_dwl (T - z_keel)) cannot bound where the waterline is
    narrow and the section wide below it (a bulb's neck under a fine stem). A >= 0.

    With ``fit`` points (the measured areas) the SAC is their reference curve A_ref (the
    fairest through them, a knot at each, holding the end values, points and flat part) times
    1 + g, g the fairest factor (linear unless a flat part holds it) meeting the volume and
    LCB: the areas change in proportion, so a section with little area (at a waterline's end)
    changes little, and the correction lands at the stations, where the sections are built.
    Without fit points A itself is designed, 0 at a range end where the body leaves the water or
    the waterline closes (unless yB / yE are given). Raises InvalidInput for a fullness_fit,
    lower / upper or an LCB without the volume, InfeasibleFormParameters when the conditions
    contradict each other."""
    plan = _plan(spec, dwl.x_start, dwl.x_end, _SAC_PATH)
    params = _form_params("sac", spec, _SAC_PATH)
    pts = [(x, a) for x, a in spec.fit if plan.xs <= x <= plan.xe]
    r = _area_request(spec, plan, params, [x for x, _ in pts])
    try:
        if not pts:
            r.conditions = list(r.conditions) + _dry_area_ends(plan, params, dwl, profile, draft)
            r.integrals = _volume_and_lcb(plan, params, [], share=1.0)
            return BasicCurve("sac", plan.xs, plan.xe, _native.design_spline_function(r), None)
        r.e2 = AREA_REFERENCE_FAIRNESS * (plan.xe - plan.xs) ** 3 / len(pts)
        r.fit = [_native.SplineFitPoint(x, a, 1.0) for x, a in pts]
        ref = BasicCurve("sac", plan.xs, plan.xe, _native.design_spline_function(r), None)
        if "Area" not in params:
            return ref
        return _ScaledArea(ref, _area_factor(ref, plan, params))
    except _native.InfeasibleFormParameters as e:
        raise _native.InfeasibleFormParameters(
            f"{_SAC_PATH}: volume {params.get('Area', float('nan')):.6g} m^3 / lcb {params.get('xC', float('nan')):.6g} m "
            f"cannot be met by a SAC of given sections ({e})") from None


def _area_request(spec: BasicCurveSpec, plan: _Plan, params: dict, stations: list):
    """The area SAC's request without its fit or integrals: end conditions, points, flat part,
    A >= 0 and the monotone rise to the flat part; a knot at each of `stations`."""
    if spec.fullness_fit:
        raise _native.InvalidInput(f"{_SAC_PATH}.fullness_fit is given, but a SAC of given sections is designed as area; "
                                   "expected fit ([[x, area], ...]) instead")
    if spec.lower is not None or spec.upper is not None:
        raise _native.InvalidInput(f"{_SAC_PATH}.lower / upper are not used; the SAC of given sections is bounded below by 0")
    if "xC" in params and "Area" not in params:
        raise _native.InvalidInput(f"{_SAC_PATH}.lcb is given without the volume; expected both")
    r = _request("sac", plan, spec, _SAC_PATH, stations)

    def direct(x, combo, value, what):
        return [_native.SplineCondition(x, 0, value, what, combo)]

    r.conditions = _conditions(params, plan, _SAC_PATH, direct) + [_native.SplineCondition(x, 0, a, "points")
                                                                     for x, a in spec.points]
    if plan.flat is not None:
        r.flats = [_native.SplineFlat(plan.flat[0], plan.flat[1], plan.value, "flat part (midship section area)")]
    r.bounds = [_native.SplineBound(plan.xs, plan.xe, 0.0, math.nan, "0 <= sac")]
    r.shapes = _monotone(plan, params, True) if spec.monotone else []
    return r


def _dry_area_ends(plan: _Plan, params: dict, dwl: BasicCurve, profile: BasicCurve, draft: float) -> list:
    """A = 0 at a range end where the body leaves the water or the waterline closes (the
    sections hold no area there), unless yB / yE or the flat part says otherwise."""
    tol = 1e-9 * (plan.xe - plan.xs)
    ends = []
    for x, key in ((plan.xs, "yB"), (plan.xe, "yE")):
        flat = plan.flat is not None and plan.flat[0] - tol <= x <= plan.flat[1] + tol
        if key not in params and not flat and (float(profile(x)[0]) >= draft - tol or float(dwl(x)[0]) <= tol):
            ends.append(_native.SplineCondition(x, 0, 0.0, f"{key} (no immersed section)"))
    return ends


def _area_factor(ref: BasicCurve, plan: _Plan, params: dict):
    """g: the fairest spline (AREA_FACTOR_SPANS) with int A_ref g = V - V_ref and, with the LCB,
    int x A_ref g = V xC - M_ref; 0 on the flat part; g >= -1."""
    r = _native.SplineDesignRequest()
    r.name = f"{_SAC_PATH} (volume and LCB factor)"
    breaks = [x for x in (plan.flat or ()) if plan.xs < x < plan.xe]
    r.knots = _native.spline_function_knots(plan.xs, plan.xe, breaks, AREA_FACTOR_SPANS, 3, 1)
    factor = [ref.factor()]
    volume = params["Area"]
    integrals = [_native.SplineIntegral(plan.xs, plan.xe, volume - ref.integral(0), factors=factor, name="volume")]
    if "xC" in params:
        integrals.append(_native.SplineIntegral(plan.xs, plan.xe, volume * params["xC"] - ref.integral(1), power=1,
                                                factors=factor, name="lcb"))
    r.integrals = integrals
    if plan.flat is not None:
        r.flats = [_native.SplineFlat(plan.flat[0], plan.flat[1], 0.0, "flat part (kept as given)")]
    r.bounds = [_native.SplineBound(plan.xs, plan.xe, -1.0, math.nan, "0 <= sac")]
    return _native.design_spline_function(r)


class _ScaledArea(BasicCurve):
    """A(x) = A_ref(x) (1 + g(x)): a SAC of given sections, its reference areas scaled."""

    def __init__(self, ref: BasicCurve, g):
        super().__init__("sac", ref.x_start, ref.x_end, None, None)
        self.reference, self.g = ref, BasicCurve("g", ref.x_start, ref.x_end, g, None)

    def __call__(self, x: Any, outside: float = math.nan) -> np.ndarray:
        a = self.reference(x, outside=math.nan)
        out = a * (1.0 + self.g(x, outside=0.0))
        return np.where(np.isnan(a), outside, out)

    def derivative(self, x: float, order: int = 1) -> float:
        """d^order A / dx^order at x by Leibniz's rule on A_ref (1 + g)."""
        def factor(k):
            return 1.0 + self.g(x)[0] if k == 0 else self.g.derivative(x, k)

        def ref(k):
            return self.reference(x)[0] if k == 0 else self.reference.derivative(x, k)

        return float(sum(math.comb(order, k) * ref(order - k) * factor(k) for k in range(order + 1)))

    def integral(self, power: int = 0, lo: float | None = None, hi: float | None = None) -> float:
        """int x^power A dx over [lo, hi] (default the whole range), exact: the engine's
        integral of the product A_ref (1 + g). Raises InvalidInput for lo > hi or a range
        beyond the SAC's."""
        lo = self.x_start if lo is None else lo
        hi = self.x_end if hi is None else hi
        return _native.spline_product_integral([self.reference.factor(), self.g.factor(offset=1.0)], lo, hi, power)

    def factor(self, offset: float = 0.0, scale: float = 1.0):
        raise _native.InvalidInput("the SAC of given sections is a product of splines; use its reference and g as factors")


class _ProductCurve(BasicCurve):
    """A(x) = 2 y_dwl(x) (T - z_keel(x)) s(x): evaluated through its factors."""

    def __init__(self, name, xs, xe, fullness, dwl, profile, draft):
        super().__init__(name, xs, xe, None, None)
        self.fullness, self.dwl, self.profile, self.draft = fullness, dwl, profile, draft

    def __call__(self, x: Any, outside: float = math.nan) -> np.ndarray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        s = self.fullness(x, outside=math.nan)
        out = 2 * self.dwl(x) * (self.draft - self.profile(x)) * s
        return np.where(np.isnan(s), outside, out)

    def derivative(self, x: float, order: int = 1) -> float:
        h = 1e-4 * max(1.0, self.x_end - self.x_start)
        if order == 1:
            return float((self(x + h)[0] - self(x - h)[0]) / (2 * h))
        return float((self(x + h)[0] - 2 * self(x)[0] + self(x - h)[0]) / h**2)

    def integral(self, power: int = 0, lo: float | None = None, hi: float | None = None) -> float:
        """int x^power A dx over [lo, hi] (default the whole range), exact: twice the engine's
        integral of the product s y_dwl (T - z_keel). Raises InvalidInput for lo > hi or a
        range beyond the SAC's."""
        lo = self.x_start if lo is None else lo
        hi = self.x_end if hi is None else hi
        factors = [self.fullness.factor(), *_Box(self.dwl, self.profile, self.draft).factors()]
        return 2.0 * _native.spline_product_integral(factors, lo, hi, power)

    def factor(self, offset: float = 0.0, scale: float = 1.0):
        raise _native.InvalidInput("the SAC is a product of splines; use its fullness, DWL and profile as factors")
