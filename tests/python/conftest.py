"""Shared fixtures: reproducible random NURBS data for the Python suite."""

import numpy as np
import pytest


def random_clamped_knots(rng, n, p):
    interior = np.sort(rng.uniform(0.05, 0.95, n - p - 1))
    return np.concatenate([np.zeros(p + 1), interior, np.ones(p + 1)])


@pytest.fixture
def rng():
    return np.random.default_rng(20261122)
