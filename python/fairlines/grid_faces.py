"""Faces of a structured point grid: the one grid triangulation of the package (surface
tessellation, offsets grids, the add-on's quad meshes).

A grid of n_u x n_v points is stored row-major (index = i n_v + j). A cell's corners run
(i, j) -> (i + 1, j) -> (i + 1, j + 1) -> (i, j + 1), so face normals follow S_u x S_v like
the engine's surface normal."""

from __future__ import annotations

import numpy as np

from ._native import InvalidInput

__all__ = ["grid_quads", "grid_triangles"]


def grid_quads(n_u: int, n_v: int) -> np.ndarray:
    """((n_u - 1)(n_v - 1), 4) vertex indices of the grid's cells, in row-major order.
    Raises InvalidInput for fewer than 2 x 2 points."""
    if n_u < 2 or n_v < 2:
        raise InvalidInput(f"grid is {n_u} x {n_v} points; expected at least 2 x 2")
    i, j = np.meshgrid(np.arange(n_u - 1), np.arange(n_v - 1), indexing="ij")
    a = (i * n_v + j).ravel()
    return np.column_stack([a, a + n_v, a + n_v + 1, a + 1])


def grid_triangles(n_u: int, n_v: int) -> np.ndarray:
    """(2 (n_u - 1)(n_v - 1), 3) vertex indices: every cell's first triangle (corners 0, 1, 2),
    then every cell's second (0, 2, 3). Raises InvalidInput for fewer than 2 x 2 points."""
    q = grid_quads(n_u, n_v)
    return np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
