"""The speed paths of the designer's chain give the geometry their definitions demand: a skin
built on a factorisation kept from an earlier skin still interpolates its own sections, and a
surface refined in one pass over all its lines is the same surface."""

import numpy as np

import fairlines as fl

from mesh_fixtures import example_hull

INTERPOLATION_TOL = 1e-8  # m: the skin passes through every section (longitudinal solve round-off)
REFINE_TOL = 1e-12        # relative: knot insertion does not move the surface


def _skin(sections, e2, e3):
    return fl.fair_skin(sections, params="station", e2=e2, e3=e3, hold_runs=True)


def _scaled(curve, factor):
    """The section with its half-breadths times `factor` (same x, same knots)."""
    p = np.asarray(curve.control_points, float).copy()
    p[:, 1] *= factor
    return fl.NurbsCurve(curve.degree, np.asarray(curve.knots), p)


def test_a_skin_on_a_kept_factorisation_interpolates_its_own_sections():
    hull = example_hull()
    d = hull.description
    _skin(hull.sections, d.skin_e2, d.skin_e3)  # keeps the factorisation of these stations
    wider = [_scaled(c, 1.05) for c in hull.sections]
    res = _skin(wider, d.skin_e2, d.skin_e3)  # same stations and held runs: the kept one is used
    for v, section in zip(np.asarray(res.section_params), wider):
        iso = res.surface.iso_curve("v", float(v))
        gap = np.abs(np.asarray(iso.control_points) - np.asarray(section.control_points)).max()
        assert gap <= INTERPOLATION_TOL, f"skin misses the section at v = {v} by {gap} m"


def test_a_surface_refined_along_both_directions_is_the_same_surface():
    rng = np.random.default_rng(11)
    ku = np.array([0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1], float)
    kv = np.array([0, 0, 0, 0.5, 1, 1, 1], float)
    s = fl.NurbsSurface(3, 2, ku, kv, rng.normal(size=(6, 4, 3)), rng.uniform(0.5, 2.0, size=(6, 4)))
    r = s.refine_knots("u", np.array([0.1, 0.3, 0.3, 0.75])).refine_knots("v", np.array([0.2, 0.5, 0.9]))
    assert np.asarray(r.control_points).shape == (10, 7, 3)
    uv = rng.random((200, 2))
    a = np.asarray(s.evaluate(uv[:, 0], uv[:, 1]))
    b = np.asarray(r.evaluate(uv[:, 0], uv[:, 1]))
    assert np.abs(a - b).max() <= REFINE_TOL * np.abs(a).max()


def test_a_copied_curve_spec_shares_nothing_an_edit_changes():
    """BasicCurveSpec.copy (what a Blender slider edits instead of a deep copy): every dict and
    list field is a new object with equal contents, so setting a form parameter, popping an
    alias or replacing a list on the copy leaves the original as it was."""
    import dataclasses

    spec = example_hull().description.curves["sac"]
    before = dataclasses.asdict(spec)
    twin = spec.copy()
    assert dataclasses.asdict(twin) == before
    for f in dataclasses.fields(spec):
        value = getattr(spec, f.name)
        if isinstance(value, (list, dict)):
            assert getattr(twin, f.name) is not value, f"{f.name} is shared with the original"
    twin.params["Area"] = 1.0
    twin.aliases.clear()
    twin.fullness_fit.append((0.0, 0.5))
    twin.flat_from = -1.0
    assert dataclasses.asdict(spec) == before
