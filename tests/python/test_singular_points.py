"""Curvature at degenerate points of a parametrisation: the limit from the interior where the
geometry is smooth (a sphere's poles), a named error where there is none (a cone's apex)."""

import numpy as np
import pytest

import fairlines as fl

R = 2.0
# The limit is extrapolated from interior samples; it matches the exact value to this.
LIMIT_RTOL = 1e-7


@pytest.mark.parametrize("u, v", [(0.0, 0.0), (0.5, 0.0), (0.3, 1.0), (0.77, 1.0), (0.5, 1e-12)])
def test_sphere_pole_curvature_is_the_sphere_curvature(u, v):
    s = fl.sphere((1.0, 2.0, 3.0), R)
    K, H = s.curvature(u, v)
    assert K == pytest.approx(1 / R**2, rel=LIMIT_RTOL)
    assert abs(H) == pytest.approx(1 / R, rel=LIMIT_RTOL)


def test_pole_mean_curvature_keeps_the_sign_of_its_neighbours():
    s = fl.sphere((0.0, 0.0, 0.0), R)
    _, H_pole = s.curvature(0.4, 0.0)
    _, H_near = s.curvature(0.4, 0.01)
    assert np.sign(H_pole) == np.sign(H_near)


def test_cone_apex_is_a_named_error():
    line = fl.NurbsCurve(1, [0, 0, 1, 1], [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0]])
    cone = fl.revolve(line, (0, 0, 0), (0, 0, 1))
    assert cone.curvature(0.3, 0.5)[0] == pytest.approx(0.0, abs=1e-12)  # a cone is developable
    with pytest.raises(fl.InvalidInput, match="singular"):
        cone.curvature(0.3, 0.0)
