"""Fair skinning of section curves into one B-spline surface (Kim & Hwangbo 2008, eq. 6-9)."""

from __future__ import annotations

from collections.abc import Sequence

from . import _native
from ._native import SkinOptions
from ._options import fill_options

__all__ = ["fair_skin", "SkinOptions"]


def fair_skin(curves: Sequence[_native.NurbsCurve], n_control: int | None = None, mode: str | None = None,
              **options) -> _native.SkinResult:
    """Skin section curves (3-D NurbsCurves, ordered along the hull, metres) into one surface.

    Sections that already share one knot vector of degree ``degree_u`` (as fl.Hull's sections
    do) are used exactly: their control points are the rows and steps (b)-(d) are skipped
    (``n_control`` None or equal to their count). Otherwise:

    (b) ``samples`` equally spaced points along every section (default 4 x n_control);
    (c)-(d) one clamped uniform knot vector with ``n_control`` control points for all sections
    (default max(12, 2 x the largest section control count)), ends interpolated, the rest by
    least squares; (f) for each control-point row a longitudinal B-spline of ``degree_v`` with a
    knot at every section that, in ``mode="interpolate"``, passes through the row and has the
    least E2 = int |C''(v)|^2 dv (Kim & Hwangbo 2008, eq. 9), and in ``mode="approximate"`` minimises
    (1/q) sum |C(v_d) - P_d|^2 + smoothing h^4 E2 with h = 1/(q - 1).

    ``start`` / ``end``: "free" (natural: zero curvature at the end section), "parallel"
    (dy/dv = dz/dv = 0, so the surface meets a parallel middle body with C1 continuity) or
    "not_a_knot" (the two end spans one polynomial: the end keeps the curvature the rows' trend
    gives it, such as a transom's waterline). ``c1_sections``: interior section indices where
    the longitudinal curves are only C1 (the fore / aft body joint); ``c0_sections``: only C0
    (a knuckle the sections cross, e.g. a transom's edge: between two such sections the
    longitudinal curves are straight, and cannot ring). ``params``: "station"
    (v proportional to section x; then every section is the iso-curve v = v_d), "chord", or
    "auto" (station when the sections are planar at monotone x).

    ``curvature_weight`` w > 0 spaces the section points equally in ds (1 + w L |k|) (L the
    section length) instead of plain arc length, so the common knots crowd where the sections
    bend (tight bilges next to flat sides); 0 is Kim & Hwangbo's (2008) plain equal spacing.

    ``e2`` / ``e3``: fairness of the longitudinal curves, e2 E2 + e3 h^2 E3 (h = 1/(q-1)).
    The default (1, 0) is Kim & Hwangbo 2008 eq. 9, whose interpolant is the natural spline (zero
    curvature forced at the end sections); (0, 1) reproduces quadratic variation along the
    hull exactly and keeps the end curvature.

    ``flats``: planes ``(axis, value)`` (axis 0 / 1 / 2 for x / y / z, value in metres) the
    hull lies in over parts of its sections, e.g. ``[(1, B / 2), (2, 0.0)]`` for the flat of
    side and the flat of bottom. Where a section lies in one, the common-knot fit (c) holds
    every control point whose support lies there on the plane, so the fitted section is
    exactly flat there instead of rippling about the plane by the fit's residuals.

    ``hold_runs``: where a row of control points keeps one y or z over three or more
    consecutive sections (a parallel middle body, a flat that ends), its longitudinal curve
    keeps it exactly there and leaves it with full continuity (one extra knot next to the run
    keeps that fit well posed). ``straight_groups``: row ranges ``(first, last)`` whose
    interior rows lie at one fraction of the segment between the end rows in every section
    (fl.section_straight_groups: a hull's straight zones); their longitudinal curves are built
    from the end rows' so the segment stays straight between the sections.

    ``y_nonnegative``: keep the surface at y >= 0 (a half hull, which must not cross its centre
    plane): the surface is looked at on 9 points per knot span each way, and where it dips below
    y = 0 (rows running from a short section onto a web on the centre plane, as at KCS's
    propeller boss) each row with a control below the plane there is solved again near the dip
    with its controls bounded at 0, meeting its row points as closely as that lets it; where a
    row would then miss them by more than 0.1 % of the sections' size, or the dip stays, the
    whole skin is left as it was (``centre_plane_refused_miss`` says what keeping it off would
    have cost, infinite where nothing could).

    Returns a SkinResult: ``surface`` (u across the sections, v along the hull),
    ``section_params``, ``section_fit_max``, ``longitudinal_max``, ``row_e2`` and, with
    ``y_nonnegative``, ``centre_plane_columns``, ``centre_plane_miss`` and
    ``centre_plane_refused_miss`` (m).

    Options by keyword are the fields of :class:`fl.SkinOptions` (``degree_u``, ``degree_v``,
    ``samples``, ``smoothing``, ``start``, ``end``, ``params``, ``c1_sections``,
    ``c0_sections``, ``curvature_weight``, ``e2``, ``e3``, ``flats``, ``hold_runs``, ``straight_groups``,
    ``y_nonnegative``); their
    defaults live in the engine. ``n_control`` / ``samples`` None: automatic.

    Raises InvalidInput naming the bad curve or option (an unknown option name included).
    """
    values = {"n_control": n_control, "mode": mode, **options}
    o = fill_options(SkinOptions, "fair_skin", {k: v for k, v in values.items() if v is not None}, _CONVERT)
    return _native._fair_skin(list(curves), o)


def _flats(planes) -> list[tuple[int, float]]:
    return [_flat(k, f) for k, f in enumerate(planes)]


def _pairs(groups) -> list[tuple[int, int]]:
    return [(int(a), int(b)) for a, b in groups]


# Sequences the bound fields take as lists of plain ints / pairs (numpy values, tuples of arrays).
def _ints(seq) -> list[int]:
    return [int(i) for i in seq]


_CONVERT = {"c1_sections": _ints, "c0_sections": _ints, "flats": _flats, "straight_groups": _pairs}


def _flat(k: int, plane) -> tuple[int, float]:
    """One ``flats`` entry as (axis, value); the engine checks the axis range and finiteness."""
    try:
        axis, value = plane
        return int(axis), float(value)
    except (TypeError, ValueError):
        raise _native.InvalidInput(f"flats[{k}] is {plane!r}; expected an (axis, value) pair") from None
