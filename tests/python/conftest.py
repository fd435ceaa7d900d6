"""Shared fixtures: reproducible random NURBS data for the Python suite."""

import numpy as np
import pytest


def random_clamped_knots(rng, n, p):
    interior = np.sort(rng.uniform(0.05, 0.95, n - p - 1))
    return np.concatenate([np.zeros(p + 1), interior, np.ones(p + 1)])


@pytest.fixture
def rng():
    return np.random.default_rng(20261122)


def edge_census(faces):
    """(open, non-manifold, misoriented) edge counts of a triangle list, computed with numpy."""
    f = np.asarray(faces)
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    und = np.sort(directed, axis=1)
    _, counts = np.unique(und, axis=0, return_counts=True)
    _, dcounts = np.unique(directed, axis=0, return_counts=True)
    return int((counts == 1).sum()), int((counts > 2).sum()), int((dcounts > 1).sum())


def ship_tol(hull, tol: float) -> float:
    """`tol` for a bare hull; the designer's mark for a ship with a bulb (designer.MATCH_TOL_BULB)."""
    from fairlines.designer import MATCH_TOL_BULB

    return tol if hull.description.bulb is None else max(tol, MATCH_TOL_BULB)
