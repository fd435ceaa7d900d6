"""Hull's build cache (solved shape curves and fullness bands kept by value): a warm build is
bit for bit the cold one, and an edit the cache keys on is never served a stale result. The
truth is the same hull built with the cache emptied first."""

import copy

import numpy as np
import pytest

import fairlines as fl
from fairlines import hull as hull_module

PARTICULARS = dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True)


@pytest.fixture(scope="module")
def designed():
    return fl.design_hull(**PARTICULARS)


def _with(hull, curve, parameter, value):
    """A new Hull from a copy of `hull`'s description with one form parameter changed, the way
    the Blender add-on's Basic Curve node makes one (the other curve specs are shared)."""
    desc = copy.copy(hull.description)
    desc.curves = dict(desc.curves)
    desc.curves[curve] = desc.curves[curve].copy()
    out = fl.Hull(desc)
    out.set(curve, parameter, value)
    return out


def _surface_arrays(hull):
    s = hull.bare_hull_surface()
    return [np.asarray(a) for a in (s.control_points, s.weights, s.knots_u, s.knots_v)]


def _cold(make):
    hull_module._clear_build_caches()
    return _surface_arrays(make())


def _assert_identical(a, b):
    for x, y in zip(a, b):
        assert x.shape == y.shape and np.array_equal(x, y)


def test_warm_build_after_a_sac_change_is_bit_identical(designed):
    make = lambda: _with(designed, "sac", "volume", 56_600.0)  # noqa: E731
    cold = _cold(make)
    _surface_arrays(_with(designed, "sac", "volume", 56_500.0))  # fills the cache
    _assert_identical(_surface_arrays(make()), cold)


def test_warm_build_serves_the_shape_curves_unsolved(designed, monkeypatch):
    _surface_arrays(_with(designed, "sac", "volume", 56_500.0))
    calls = []
    monkeypatch.setattr(hull_module, "solve_curve", lambda *a, **k: calls.append(a[0]))
    _with(designed, "sac", "volume", 56_700.0).basic_curves
    assert calls == []


def test_a_deck_edit_is_not_served_from_the_cache(designed):
    edited = lambda: _with(designed, "deck", "yE", 1.0)  # noqa: E731
    cold = _cold(edited)
    hull_module._clear_build_caches()
    unedited = _surface_arrays(_with(designed, "sac", "volume", 56_448.8))  # the cache holds the old deck
    warm = _surface_arrays(edited())
    _assert_identical(warm, cold)
    assert not np.array_equal(warm[0], unedited[0])


def test_an_in_place_set_rebuilds_from_the_edited_spec(designed):
    hull = fl.Hull(copy.deepcopy(designed.description))
    hull.bare_hull_surface()
    hull.set("dwl", "yE", 0.5)
    warm = _surface_arrays(hull)
    cold = _cold(lambda: _with(designed, "dwl", "yE", 0.5))
    _assert_identical(warm, cold)
