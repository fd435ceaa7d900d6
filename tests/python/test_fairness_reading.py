"""fairlines.fairness.read_waterline on analytic half-waterlines y(x), whose curvature is exact:
y'' / (1 + y'^2)^(3/2), marched toward +x (or reversed)."""

from types import SimpleNamespace

import numpy as np
import pytest

from fairlines.fairness import SMALL_LOBE_DEG, read_waterline

L, HALF_B = 100.0, 8.0
X = np.linspace(-L / 2, L / 2, 4001)


def _cut(y, dy, d2y, reverse=False):
    pts = np.column_stack([X, y, np.zeros_like(X)])
    k = d2y / (1.0 + dy**2) ** 1.5
    if reverse:  # marched toward -x: the points reversed, the signed curvature negated
        pts, k = pts[::-1], -k[::-1]
    return SimpleNamespace(points=pts, curvature=k, value=0.0, bending_energy=0.0)


def _parabola():  # Wigley's waterline: convex throughout
    xi = 2 * X / L
    return HALF_B * (1 - xi**2), HALF_B * (-2 * xi) * (2 / L), np.full_like(X, -2 * HALF_B * (2 / L) ** 2)


def _quartic():  # (1 - xi^2)^2: hollow toward each end (inflections at xi = +-1/sqrt 3)
    xi = 2 * X / L
    c = 2 / L
    return HALF_B * (1 - xi**2) ** 2, HALF_B * (-4 * xi * (1 - xi**2)) * c, HALF_B * (12 * xi**2 - 4) * c * c


def _bump(x0, height, width):  # a Gaussian bump of the half-breadth: its value and derivatives
    g = height * np.exp(-(((X - x0) / width) ** 2))
    u = (X - x0) / width**2
    return g, -2 * u * g, (4 * u**2 - 2 / width**2) * g


def _plus(*curves):
    return tuple(sum(parts) for parts in zip(*curves))


@pytest.mark.parametrize("reverse", [False, True])
def test_a_convex_waterline_is_fair_with_no_hollow(reverse):
    read = read_waterline(_cut(*_parabola(), reverse=reverse))
    assert read["fair"] and read["hollows"] == (0, 0) and read["judged"]["sign_changes"] == 0


@pytest.mark.parametrize("reverse", [False, True])
def test_a_hollow_run_and_entrance_are_one_hollow_each_half(reverse):
    read = read_waterline(_cut(*_quartic(), reverse=reverse))
    assert read["hollows"] == (1, 1) and read["fair"]


def test_a_small_bump_on_the_flank_is_a_wobble():
    """5 cm over 2 m on the parabola's flank: its sides turn the line hollow by a fraction of a
    degree each, between convex stretches."""
    read = read_waterline(_cut(*_plus(_parabola(), _bump(20.0, 0.05, 2.0))))
    assert not read["fair"] and read["wobbles"]
    assert all(lobe["turn_deg"] < SMALL_LOBE_DEG for lobe in read["wobbles"])
    assert all(abs(lobe["at"][0] - 20.0) < 6.0 for lobe in read["wobbles"])


def test_a_second_hollow_in_the_fore_half_is_a_step():
    """A dent of 15 cm over 3 m at x 12 m, where the quartic's fore half is convex: a second
    hollow there, turning degrees (a step, not a wobble)."""
    read = read_waterline(_cut(*_plus(_quartic(), _bump(12.0, -0.15, 3.0))))
    assert read["step"] and read["hollows"][1] == 2 and not read["fair"]
