"""Diagonals in the fairness report: the cut of a lines plan's diagonal plane, judged on its own
like a waterline. Truth: a plane cuts a sphere in a circle of radius sqrt(R^2 - d^2), d the
plane's distance from the centre."""

import math
import pathlib

import numpy as np
import pytest

import fairlines as fl
from fairlines.fairness import DIAGONALS, diagonal_cut, fairness_report


@pytest.mark.parametrize("z_centre, angle", [(0.0, 45.0), (2.0, 45.0), (-1.5, 30.0), (3.0, 60.0)])
def test_a_diagonal_of_a_sphere_is_a_circle_in_its_plane(z_centre, angle):
    R = 5.0
    cut = diagonal_cut(fl.sphere(center=(0.0, 0.0, 0.0), radius=R), z_centre, angle, 801)
    a = math.radians(angle)
    p = cut.points
    # every point on the plane z = z_c - y tan(a) and on the sphere
    assert np.abs(p[:, 2] - (z_centre - p[:, 1] * math.tan(a))).max() < 1e-7
    assert np.abs(np.linalg.norm(p, axis=1) - R).max() < 1e-6
    r = math.sqrt(R**2 - (z_centre * math.cos(a)) ** 2)
    assert np.abs(np.abs(cut.curvature) - 1.0 / r).max() < 1e-6 / r


def test_the_report_judges_the_lines_plan_diagonals():
    s = fl.Hull.from_json(pathlib.Path(__file__).resolve().parents[2] / "examples" / "container_ship.json").bare_hull_surface()
    rep = fairness_report(s, 11.0)
    assert len(rep["diagonal"]) == len(DIAGONALS)
    assert rep["summary"]["diagonal"] == sum(c["sign_changes"] for c in rep["diagonal"])
    for c in rep["diagonal"]:  # a diagonal runs the length of the hull
        assert c["points"] > 100 and c["bending_energy"] > 0
