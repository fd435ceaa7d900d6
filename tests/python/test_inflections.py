"""Which curvature sign changes of a hull's cuts the designed shape calls for (issue 4).

Truths: analytic hull families whose waterlines / frames have known convexity -- the Wigley
hull (every waterline strictly concave: no inflection is called for), a hull whose half-breadth
along x follows a tanh step (exactly one waterline inflection, at midships) and a hull whose
sections are one S-shaped cubic (one frame inflection, at the height where the cubic's
y'z'' - z'y'' vanishes, solved here in closed form).
"""

import json
import pathlib

import numpy as np
import pytest

import fairlines as fl
from fairlines.inflections import classify_cut, section_inflection_heights

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "panamax_forebody.json"
L, B, T = 100.0, 10.0, 6.25
STATIONS = np.linspace(0.0, L, 41)
SPACING = STATIONS[1] - STATIONS[0]


def _quadratic_sections(half_breadth):
    """Sections y = b(x) (1 - ((T - z)/T)^2), deck (z = T) to keel, as exact quadratics."""

    def sec(x):
        def f(t):
            z = T * (1 - t)
            return np.array([x, half_breadth(x) * (1 - ((T - z) / T) ** 2), z])

        p0, p2 = f(0.0), f(1.0)
        return fl.NurbsCurve(2, [0, 0, 0, 1, 1, 1], np.array([p0, 2 * f(0.5) - (p0 + p2) / 2, p2]))

    return [sec(x) for x in STATIONS]


def test_wigley_natural_end_inflections_are_false():
    # b(x) = B/2 (1 - (2 xm / L)^2) is strictly concave: any inflection is the skinning's.
    secs = _quadratic_sections(lambda x: B / 2 * (1 - (2 * (x - L / 2) / L) ** 2))
    surf = fl.fair_skin(secs, n_control=8).surface  # E2: natural ends, zero end curvature
    cut = fl.plane_cut(surf, "waterline", 4.0, 201)
    assert cut.sign_changes > 0
    judged = classify_cut("waterline", 4.0, cut.inflections, secs, STATIONS, dz=T / 10)
    assert len(judged) == cut.sign_changes
    assert not any(j["real"] for j in judged)
    assert all("concave" in j["reason"] for j in judged)


def test_tanh_waterline_inflection_is_real_and_at_midships():
    # b(x) = B/2 (0.6 + 0.3 tanh((x - L/2) / (L/8))): b'' = 0 only at x = L/2.
    secs = _quadratic_sections(lambda x: B / 2 * (0.6 + 0.3 * np.tanh((x - L / 2) / (L / 8))))
    surf = fl.fair_skin(secs, n_control=8, e2=0.0, e3=1.0).surface
    cut = fl.plane_cut(surf, "waterline", 4.0, 401)
    judged = classify_cut("waterline", 4.0, cut.inflections, secs, STATIONS, dz=T / 10)
    real = [j for j in judged if j["real"]]
    assert len(real) == 1
    assert abs(real[0]["point"][0] - L / 2) < SPACING
    assert "change convexity" in real[0]["reason"]


def _s_section_hull():
    """Every section the same S-shaped cubic Bezier in (y, z), scaled in y by a concave b(x)."""
    ctrl_yz = np.array([[4.0, T], [2.0, 0.7 * T], [5.0, 0.3 * T], [0.0, 0.0]])

    def sec(x):
        s = 1 - 0.5 * (2 * (x - L / 2) / L) ** 2
        P = np.column_stack([np.full(4, x), s * ctrl_yz[:, 0], ctrl_yz[:, 1]])
        return fl.NurbsCurve(3, [0, 0, 0, 0, 1, 1, 1, 1], P)

    # y'z'' - z'y'' of a cubic Bezier is quadratic in t; its root in (0, 1) is the inflection.
    d1 = 3 * np.diff(ctrl_yz, axis=0)
    d2 = 2 * np.diff(d1, axis=0)

    def cross(t):
        b1 = np.array([(1 - t) ** 2, 2 * t * (1 - t), t**2]) @ d1
        b2 = np.array([1 - t, t]) @ d2
        return b1[0] * b2[1] - b1[1] * b2[0]

    c0, c_half, c1 = cross(0.0), cross(0.5), cross(1.0)
    # Quadratic through (0, c0), (0.5, c_half), (1, c1).
    a = 2 * c0 - 4 * c_half + 2 * c1
    b = -3 * c0 + 4 * c_half - c1
    roots = [r.real for r in np.roots([a, b, c0]) if abs(r.imag) < 1e-12 and 0 < r.real < 1]
    assert len(roots) == 1
    t0 = roots[0]
    z0 = float(np.array([(1 - t0) ** 3, 3 * t0 * (1 - t0) ** 2, 3 * t0**2 * (1 - t0), t0**3]) @ ctrl_yz[:, 1])
    return [sec(x) for x in STATIONS], z0


def test_frame_inflection_of_s_sections_is_real_at_the_analytic_height():
    secs, z0 = _s_section_hull()
    heights = section_inflection_heights(secs[10])
    assert len(heights) == 1 and abs(heights[0] - z0) < 1e-2
    surf = fl.fair_skin(secs, n_control=12, e2=0.0, e3=1.0).surface
    x = 0.5 * (STATIONS[12] + STATIONS[13])
    cut = fl.plane_cut(surf, "frame", x, 401)
    judged = classify_cut("frame", x, cut.inflections, secs, STATIONS, dz=T / 10)
    assert cut.sign_changes >= 1
    real = [j for j in judged if j["real"]]
    assert len(real) == 1 and abs(real[0]["point"][2] - z0) < T / 10
    # No more real ones than the sections have: extra sign changes are the skin's.
    assert all(not j["real"] for j in judged if j is not real[0])


@pytest.fixture(scope="module")
def panamax_report():
    hull = fl.Hull.from_json(EXAMPLE)
    return hull.fairness_report(n_waterlines=3, n_buttocks=2, n_frames=4, samples=201)


def test_panamax_report_judges_every_inflection(panamax_report):
    for kind, cuts in panamax_report.items():
        for c in cuts:
            assert len(c["classified"]) == c["sign_changes"]
            assert c["real_inflections"] + c["false_inflections"] == c["sign_changes"]
            for j in c["classified"]:
                assert j["reason"] and (j["real"] != j["reason"].startswith("false"))
    json.dumps(panamax_report)  # the report is what build_hull.py writes


def test_wigley_e3_skin_has_no_inflection_in_any_cut_family():
    # Every Wigley waterline, buttock and frame keeps one sign of curvature.
    secs = _quadratic_sections(lambda x: B / 2 * (1 - (2 * (x - L / 2) / L) ** 2))
    surf = fl.fair_skin(secs, n_control=8, e2=0.0, e3=1.0).surface
    plan = {"waterline": np.linspace(0.7, 5.6, 8), "buttock": np.linspace(0.7, 4.3, 6), "frame": np.linspace(5, 95, 12)}
    for kind, values in plan.items():
        for v in values:
            cut = fl.plane_cut(surf, kind, float(v), 401)
            assert len(cut.points) > 0
            assert cut.sign_changes == 0, (kind, v)
