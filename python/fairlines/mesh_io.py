"""Mesh and grid files a solver reads.

* unstructured meshes through meshio (``.msh`` gmsh, ``.vtu`` VTK, ``.stl``, ``.obj``, ``.med``,
  and every other format meshio writes): :func:`write_mesh`, :func:`read_mesh` (defined beside
  :class:`~fairlines.meshing.SurfaceMesh`, whose ``write`` they serve);
* panel files of the wetted part for BEM codes: WAMIT ``.gdf`` (:func:`write_gdf`) and Nemoh
  ``.mar`` (:func:`write_mar`), both with z measured up from the free surface and the y = 0
  symmetry of a half hull declared in the header;
* structured grids as multi-block Plot3D (:func:`write_plot3d`, :func:`read_plot3d`).

File formats only: the geometry comes from ``fairlines.meshing`` and ``fairlines.grids``.
"""

from __future__ import annotations

import pathlib

import numpy as np

from ._native import InvalidInput
from .meshing import SurfaceMesh, read_mesh, write_mesh

__all__ = ["write_mesh", "read_mesh", "write_gdf", "write_mar", "write_plot3d", "read_plot3d"]

def _panels(mesh: SurfaceMesh, draft: float | None):
    t = mesh.draft if draft is None else draft
    if t is None:
        raise InvalidInput("draft is None; a panel file measures z from the free surface, so give the draft (m)")
    v = np.asarray(mesh.vertices, float).copy()
    v[:, 2] -= float(t)
    f = mesh.faces.copy()
    tri = f[:, 3] < 0
    f[tri, 3] = f[tri, 2]  # a triangle is a panel with its last vertex repeated
    return v, f


def write_gdf(mesh: SurfaceMesh, path, *, draft: float | None = None, ulen: float = 1.0, gravity: float = 9.80665,
              symmetric: bool | None = None, title: str = "Fairlines wetted hull") -> None:
    """WAMIT geometric data file (low-order panels): ``ulen gravity``, ``ISX ISY`` (ISY = 1
    for a half hull, the other half its mirror about y = 0), the panel count, then four
    vertices per panel, counter-clockwise seen from the fluid (outward normals, as the mesh
    has them), z up from the free surface at ``draft`` (default: the mesh's own)."""
    v, f = _panels(mesh, draft)
    sym = mesh.symmetric if symmetric is None else symmetric
    lines = [title, f"{ulen:.6g} {gravity:.6g}", f"0 {1 if sym else 0}", str(len(f))]
    for panel in f:
        lines.append(" ".join(f"{c:.9g}" for c in v[panel].ravel()))
    pathlib.Path(path).write_text("\n".join(lines) + "\n")


def write_mar(mesh: SurfaceMesh, path, *, draft: float | None = None, symmetric: bool | None = None) -> None:
    """Nemoh mesh file (.mar): ``2 ISYM`` (ISYM = 1 for a half hull mirrored about y = 0), the
    nodes (1-based, z up from the free surface), ``0 0 0 0``, the panels as four node numbers
    (a triangle repeats its last node), ``0 0 0 0``."""
    v, f = _panels(mesh, draft)
    sym = mesh.symmetric if symmetric is None else symmetric
    lines = [f"2 {1 if sym else 0}"]
    lines += [f"{i + 1} {x:.9g} {y:.9g} {z:.9g}" for i, (x, y, z) in enumerate(v)]
    lines.append("0 0.00 0.00 0.00")
    lines += [" ".join(str(int(k) + 1) for k in panel) for panel in f]
    lines.append("0 0 0 0")
    pathlib.Path(path).write_text("\n".join(lines) + "\n")


def write_plot3d(grids, path) -> None:
    """Multi-block Plot3D (ASCII, whole, 3-D coordinates): the block count, each block's
    ``ni nj 1``, then per block all x, all y, all z with i running fastest. ``grids``: one
    (ni, nj, 3) array of points (metres) per block.
    Raises InvalidInput for a grid not shaped (ni, nj, 3)."""
    blocks = [np.asarray(g, float) for g in grids]
    for k, g in enumerate(blocks):
        if g.ndim != 3 or g.shape[2] != 3:
            raise InvalidInput(f"grids[{k}] has shape {g.shape}; expected (ni, nj, 3)")
    lines = [str(len(blocks))] + [f"{g.shape[0]} {g.shape[1]} 1" for g in blocks]
    for g in blocks:
        for c in range(3):
            vals = g[:, :, c].T.ravel()  # i fastest
            lines += [" ".join(f"{x:.12g}" for x in vals[k:k + 6]) for k in range(0, len(vals), 6)]
    pathlib.Path(path).write_text("\n".join(lines) + "\n")


def read_plot3d(path) -> list:
    """The blocks of a multi-block ASCII Plot3D file as (ni, nj, 3) arrays (nk must be 1).
    Raises InvalidInput for a malformed file or a block with nk != 1."""
    tok = pathlib.Path(path).read_text().split()
    nb = int(tok[0])
    dims = [tuple(int(x) for x in tok[1 + 3 * k: 4 + 3 * k]) for k in range(nb)]
    vals = np.array(tok[1 + 3 * nb:], float)
    out, pos = [], 0
    for ni, nj, nk in dims:
        if nk != 1:
            raise InvalidInput(f"{path}: a block has nk = {nk}; expected surface grids (nk = 1)")
        n = ni * nj
        g = np.stack([vals[pos + c * n: pos + (c + 1) * n].reshape(nj, ni).T for c in range(3)], axis=-1)
        out.append(g)
        pos += 3 * n
    return out
