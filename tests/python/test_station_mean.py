"""The station mean (fairlines.station_mean): each section the skin interpolates is the mean of
the designed family's at x +- d. Judged on the cut curves (the ringing it takes out of the
design waterlines), on what it must keep exact (the hull's ends, the deck edge, the SAC's flat
part, given sections) and on how far it may move the keel and stem contour."""

from __future__ import annotations

import json

import numpy as np
import pytest

import fairlines as fl
from fairlines.fairness import cut_lobes
from fairlines.station_mean import STATION_MEAN

from test_designer import SHIPS
from test_given_sections import _wigley_hull

# The mean of a curved keel/stem contour lies inside it, most at the forefoot: measured
# 0.018-0.039 % Lpp on the designed ships and the first 16 of bench_hull's sample.
KEEL_CONTOUR_TOL = 5e-4  # of Lpp


@pytest.fixture(scope="module")
def tanker():
    return fl.design_hull(**SHIPS["tanker"])


def _waterline_lobes(hull, z, x_lo=-np.inf, x_hi=np.inf):
    cut = fl.plane_cut(hull.bare_hull_surface(), 2, float(z), 801)
    p, k = np.asarray(cut.points), np.asarray(cut.curvature)
    keep = (p[:, 0] >= x_lo) & (p[:, 0] <= x_hi)
    return cut_lobes(p[keep], k[keep])


def _shown(lobes):
    return [(round(lb["turn_deg"], 2), lb["sign"], round(lb["at"][0], 1)) for lb in lobes]


def test_the_tanker_design_waterline_does_not_ring_over_its_transom(tanker):
    """Over the tanker's last 6 % Lpp aft, its design waterline turns convex at the transom,
    hollow into the run and convex into the body, no more (2 sign changes). With the sections as
    designed (station_mean 0) it rang there: 12 lobes of 0.19-0.55 deg at x -2.4..7.6 m, the
    family's swing as Q passes the section's knots, sampled at the stations."""
    x_aft = tanker.immersed_range()[0]
    lobes = _waterline_lobes(tanker, SHIPS["tanker"]["draft"], x_hi=x_aft + 0.06 * SHIPS["tanker"]["lpp"])
    assert len(lobes) - 1 <= 2, _shown(lobes)


def test_the_cruiser_sterned_coaster_design_waterline_has_one_hollow_each_way():
    """The coaster's design waterline: a convex end at the counter, the run, the body, the
    entrance and the stem, at most one hollow each way (2 sign changes). With the sections as
    designed it had 4 (a convex lobe of 0.2 deg at the counter, a hollow of 0.14 deg at the stem)."""
    p = SHIPS["coaster_cruiser"]
    lobes = _waterline_lobes(fl.design_hull(**p), p["draft"])
    assert len(lobes) - 1 <= 2, _shown(lobes)


def test_the_deck_edge_ends_and_flat_part_are_kept_as_designed(tanker):
    designed = [np.asarray(c.control_points) for c in tanker.section_curves]
    used = [np.asarray(c.control_points) for c in tanker.sections]
    sac = tanker.description.curves["sac"]
    xs = tanker.stations()
    for i, (a, b) in enumerate(zip(designed, used)):
        assert np.array_equal(a[0], b[0]), xs[i]  # the deck edge: deck line and sheer exact
        if i in (0, len(xs) - 1) or sac.flat_from <= xs[i] <= sac.flat_to:
            assert np.array_equal(a, b), xs[i]
    moved = sum(not np.array_equal(a, b) for a, b in zip(designed, used))
    assert moved >= len(xs) // 2  # the mean is at work elsewhere


@pytest.mark.parametrize("name", list(SHIPS))
def test_the_keel_and_stem_contour_stays_on_the_profile(name):
    """The keel points of the sections the skin interpolates lie within KEEL_CONTOUR_TOL of the
    designed family's keel and stem contour (a polyline of 4000 of its keel points)."""
    p = SHIPS[name]
    hull = fl.design_hull(**p)
    xs = hull.stations()
    family = np.array([np.asarray(c.control_points)[-1, [0, 2]] for c in hull.sections_at(np.linspace(xs[0], xs[-1], 4000))])
    a, ab = family[:-1], np.diff(family, axis=0)
    for c in hull.sections:
        k = np.asarray(c.control_points)[-1, [0, 2]]
        t = np.clip(np.einsum("ij,ij->i", k - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0.0, 1.0)
        assert np.linalg.norm(a + t[:, None] * ab - k, axis=1).min() <= KEEL_CONTOUR_TOL * p["lpp"], k


def test_given_sections_are_met_as_given():
    h = fl.Hull.from_json(_wigley_hull())
    for s, c in zip(h.section_designs, h.sections):
        assert np.array_equal(np.asarray(s.curve.control_points), np.asarray(c.control_points))


def test_station_mean_zero_skins_the_sections_as_designed(tanker):
    d = json.loads(tanker.to_json())
    assert d["skinning"]["station_mean"] == STATION_MEAN
    d["skinning"]["station_mean"] = 0.0
    h = fl.Hull.from_json(d)
    for s, c in zip(h.section_curves, h.sections):
        assert np.array_equal(np.asarray(s.control_points), np.asarray(c.control_points))


@pytest.mark.parametrize("value", [1.0, -0.1, "wide"])
def test_a_bad_station_mean_is_refused_naming_it(tanker, value):
    d = json.loads(tanker.to_json())
    d["skinning"]["station_mean"] = value
    with pytest.raises(fl.InvalidInput, match=r"skinning\.station_mean"):
        fl.Hull.from_json(d)
