"""Quad-dominant surface meshes of NURBS surfaces and of composed hulls.

The engine (``fairlines._native``) does the work: curvature-adaptive nodes, constrained
Delaunay triangulation, 3-D edge swaps, quadrilaterals by matching triangle pairs, an optional
all-quad split, and smoothing that keeps nodes on the surface and never lowers an element's
quality (docs/meshing.md). A composed hull is meshed face by face with every seam's nodes
shared, optionally cut at a draft along the exact waterline. Conventions: metres, x
forward from AP, y >= 0 the starboard half, z up; normals point out of the body.
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from . import _native
from ._native import InvalidInput, NurbsSurface
from ._options import fill_options

__all__ = ["SurfaceMesh", "mesh_options", "mesh_surface", "mesh_hull", "mesh_quality", "write_mesh", "read_mesh"]


#: Most elements a mesh may be asked for, estimated as the surface's area over size^2 (the
#: curvature refinement adds about as many again): about 0.5 kB and 10 us each, so 2 million
#: is a minute and a few GB; a millimetre on a ship's hull would exhaust the memory instead.
MAX_MESH_ELEMENTS = 2_000_000


def _check_budget(size: float, max_elements: int, area_of: Callable[[], float]) -> None:
    """InvalidInput when area_of() / size^2 (m^2, m) exceeds max_elements, naming the least
    size. A size that is not a length > 0 is left to the engine's own refusal."""
    if isinstance(max_elements, bool) or not isinstance(max_elements, int) or max_elements < 1:
        raise InvalidInput(f"max_elements is {max_elements!r}; expected a whole number >= 1")
    if not (size > 0 and math.isfinite(size)):
        return
    area = area_of()
    estimate = area / (size * size)
    if estimate > max_elements:
        least = math.sqrt(area / max_elements)
        step = 10.0 ** (math.floor(math.log10(least)) - 2)  # three significant figures, rounded up: it meshes
        raise InvalidInput(f"size is {size:g} m, about {estimate:.3g} elements over {area:.4g} m^2; expected at most "
                           f"{max_elements} (size >= {math.ceil(least / step) * step:.3g} m), or a larger max_elements")


def _triangles_area(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> float:
    """Summed area (m^2) of the triangles (a, b, c), each (..., 3) corner points."""
    return 0.5 * float(np.linalg.norm(np.cross(b - a, c - a), axis=-1).sum())


def _surface_area(surface: NurbsSurface, samples: int = 65) -> float:
    """Area of a surface (m^2) from its samples x samples grid of points (a lower bound)."""
    P = np.asarray(surface.evaluate_grid(np.linspace(*surface.domain_u, samples), np.linspace(*surface.domain_v, samples)))
    a, b, c, d = P[:-1, :-1], P[1:, :-1], P[1:, 1:], P[:-1, 1:]
    return _triangles_area(a, b, c) + _triangles_area(a, c, d)


def _hull_area(hull, draft: float | None) -> float:
    """Area (m^2) of a composed half hull's triangles, those whose middle lies below the draft
    when one is given (the part a wetted mesh covers)."""
    v, f = np.asarray(hull.mesh.vertices, float), np.asarray(hull.mesh.faces)
    if draft is not None:
        f = f[v[f].mean(axis=1)[:, 2] <= draft]
    return _triangles_area(v[f[:, 0]], v[f[:, 1]], v[f[:, 2]])


def mesh_options(**options) -> "_native.MeshOptions":
    """A :class:`fairlines._native.MeshOptions` with the given fields set (``size``,
    ``chordal_tolerance``, ``min_size``, ``all_quad``, ``smoothing_passes``,
    ``min_quad_quality``; the defaults live in the engine). Raises InvalidInput for an unknown
    name or a value of the wrong type."""
    return fill_options(_native.MeshOptions, "mesh", options)


@dataclass(frozen=True)
class SurfaceMesh:
    """A mixed quadrilateral / triangle surface mesh.

    ``vertices`` (n, 3) metres, each node once; ``faces`` (m, 4) node indices counter-clockwise
    seen from outside, -1 in column 3 for a triangle; ``face_part`` (m) index into ``parts``
    (names such as ``"hull"``, ``"bulb"``, ``"blend"``, ``"waterplane"``); ``draft`` the cut
    height of a wetted-part mesh (None for a whole hull or a surface)."""

    vertices: np.ndarray
    faces: np.ndarray
    face_part: np.ndarray
    parts: tuple = ()
    draft: Optional[float] = None
    symmetric: bool = False  #: a half hull (y >= 0) whose other half is its mirror image

    @property
    def quads(self) -> np.ndarray:
        """(q, 4) node indices of the quadrilaterals."""
        return self.faces[self.faces[:, 3] >= 0]

    @property
    def triangles(self) -> np.ndarray:
        """(t, 3) node indices of the triangles."""
        return self.faces[self.faces[:, 3] < 0, :3]

    def part(self, *names: str) -> "SurfaceMesh":
        """The elements of the named parts only (nodes kept as they are). Raises InvalidInput
        for a part the mesh does not have."""
        bad = [n for n in names if n not in self.parts]
        if bad:
            raise InvalidInput(f"parts {bad} are not in this mesh; it has {list(self.parts)}")
        keep = np.isin(self.face_part, [self.parts.index(n) for n in names])
        return SurfaceMesh(self.vertices, self.faces[keep], self.face_part[keep], self.parts, self.draft,
                           self.symmetric)

    def triangulated(self) -> np.ndarray:
        """(k, 3) triangles: each quad split along its shorter diagonal."""
        q = self.quads
        v = self.vertices
        d02 = np.linalg.norm(v[q[:, 2]] - v[q[:, 0]], axis=1)
        d13 = np.linalg.norm(v[q[:, 3]] - v[q[:, 1]], axis=1)
        a = np.where((d02 <= d13)[:, None], q[:, [0, 1, 2]], q[:, [0, 1, 3]])
        b = np.where((d02 <= d13)[:, None], q[:, [0, 2, 3]], q[:, [1, 2, 3]])
        return np.concatenate([self.triangles, a, b])

    def quality(self) -> dict:
        """Element quality census (:func:`mesh_quality`)."""
        return mesh_quality(self)

    def hydrostatics(self, draft: float | None = None) -> "_native.MeshHydrostatics":
        """Hydrostatics (``volume`` m^3, both sides of a half hull; ``lcb``, ``vcb`` m; ...) of
        the body this mesh bounds floating at ``draft`` (default: its own cut), by the
        divergence theorem (:func:`fairlines.hydrostatics_of_mesh`; a wetted mesh open along
        the waterline or the centre plane is fine: the fields vanish there). Raises
        InvalidInput without a draft or when the draft leaves no displaced volume."""
        from .hydrostatics_mesh import displaced_volume_of_mesh
        t = self.draft if draft is None else draft
        if t is None:
            raise InvalidInput("draft is None; this mesh was not cut at a draft, so give one (m)")
        return displaced_volume_of_mesh(self.vertices, self.triangulated(), t, half_hull=self.symmetric)

    def write(self, path, file_format: str | None = None, **kw) -> None:
        """Writes the mesh (see :func:`write_mesh`). Raises InvalidInput for an unknown format."""
        write_mesh(self, path, file_format, **kw)


def _wrap(result, draft=None, symmetric=False) -> SurfaceMesh:
    v, f, p, parts = result
    return SurfaceMesh(np.asarray(v), np.asarray(f), np.asarray(p), tuple(parts), draft, symmetric)


def mesh_surface(surface: NurbsSurface, *, size: float, max_elements: int = MAX_MESH_ELEMENTS,
                 **options) -> SurfaceMesh:
    """Quad-dominant mesh of a whole NURBS surface.

    size       maximum element edge length (m).
    max_elements  most elements asked for (area / size^2; MAX_MESH_ELEMENTS).
    options    chordal_tolerance (m, default size / 100), min_size (m, default size / 20),
               all_quad (bool), smoothing_passes, min_quad_quality (see :func:`mesh_options`).
    Elements are counter-clockwise about S_u x S_v. A closed (periodic) surface is meshed as
    if its seam were two edges. Raises InvalidInput for bad options or a size that would make
    more than max_elements elements.
    """
    if not isinstance(surface, NurbsSurface):
        raise InvalidInput(f"surface is {type(surface).__name__}; expected a NurbsSurface")
    o = mesh_options(size=size, **options)
    _check_budget(o.size, max_elements, lambda: _surface_area(surface))
    return _wrap(_native._mesh_surface(surface, o))


def mesh_hull(hull, *, size: float, draft: float | None = None, lids: bool = True, full: bool = False,
              progress: Callable[[int, int, str], None] | None = None, max_elements: int = MAX_MESH_ELEMENTS,
              **options) -> SurfaceMesh:
    """Mesh of a composed hull, conforming across the bare-hull / bulb / blend seams.

    hull       a :class:`fairlines.ComposedHull` (``fl.compose(...)``, ``hull.composed_hull()``)
               or a bare-hull NurbsSurface (composed alone).
    size, options   as :func:`mesh_surface`.
    draft      cut at z = draft (m): only the wetted part is meshed, its edge on the exact
               waterline; None: the whole hull.
    lids       close the mesh with planar faces: the waterplane (with a draft) or the deck (without),
               and the centre plane of a half hull. ``lids=False`` with a draft gives the open
               wetted surface a BEM code wants (WAMIT, Nemoh, capytaine).
    full       mirror about y = 0 into the full hull (no centre-plane face).
    progress   called as progress(faces_done, faces_total, face_name).
    max_elements  most elements asked for (the composed hull's area, below the draft when
               one is given, both sides when ``full``, over size^2; MAX_MESH_ELEMENTS).
    Normals point out of the body. Raises InvalidInput for bad options, a draft outside
    keel..deck or a size that would make more than max_elements elements.
    """
    from .compose import ComposedHull, compose
    if isinstance(hull, NurbsSurface):
        hull = compose([hull])
    if not isinstance(hull, ComposedHull):
        raise InvalidInput(f"hull is {type(hull).__name__}; expected a ComposedHull or a bare-hull NurbsSurface")
    t = float("nan") if draft is None else float(draft)
    o = mesh_options(size=size, **options)
    _check_budget(o.size, max_elements, lambda: (2.0 if full else 1.0) * _hull_area(hull, None if draft is None else t))
    res = _native._mesh_hull(hull.native, o, t, bool(lids), bool(full), progress)
    return _wrap(res, None if draft is None else float(draft), not full)


def mesh_quality(mesh: SurfaceMesh) -> dict:
    """Quality census: quads, triangles, inverted elements, min / mean scaled Jacobian
    (Knupp 2000; 1 for a square or an equilateral triangle, <= 0 inverted), the fraction of quad
    corners within 45..135 deg, extreme corner angles (deg) and edge lengths (m), duplicate
    nodes and the open / non-manifold / misoriented edge counts."""
    q = dict(_native.mesh_quality(mesh.vertices, mesh.faces))
    n = q["quads"] + q["triangles"]
    q["quad_fraction"] = q["quads"] / n if n else 0.0
    return q


# Files through meshio, beside the mesh class they read and write (fairlines.mesh_io re-exports them).

#: Formats that hold triangles only: quads are split along their shorter diagonal.
_TRIANGLE_ONLY = {"stl"}
#: Suffixes whose meshio format is ambiguous or worth naming (".msh": gmsh 2.2, which needs no entity tags).
_SUFFIX_FORMAT = {".msh": "gmsh22", ".vtu": "vtu", ".vtk": "vtk", ".stl": "stl", ".obj": "obj", ".med": "med",
                  ".ply": "ply", ".off": "off", ".xdmf": "xdmf", ".inp": "abaqus", ".mesh": "medit"}


def _cells(mesh: SurfaceMesh, triangles_only: bool):
    if triangles_only:
        return [("triangle", mesh.triangulated())], None
    tri, quad = mesh.faces[:, 3] < 0, mesh.faces[:, 3] >= 0
    cells, part = [], []
    if tri.any():
        cells.append(("triangle", mesh.faces[tri, :3]))
        part.append(mesh.face_part[tri])
    if quad.any():
        cells.append(("quad", mesh.faces[quad]))
        part.append(mesh.face_part[quad])
    return cells, part


def write_mesh(mesh: SurfaceMesh, path, file_format: str | None = None, **kw) -> None:
    """Writes a mesh with meshio; the format follows the suffix unless ``file_format`` names
    one (a meshio format name such as ``"gmsh"``, ``"vtu"``, ``"stl"``, ``"obj"``, ``"med"``).
    Formats that hold triangles only get each quad as two triangles. Element parts go out as
    the cell data ``part`` (and gmsh physical groups) where the format keeps cell data.
    Raises InvalidInput for an unknown format."""
    import meshio
    path = pathlib.Path(path)
    fmt = file_format or _SUFFIX_FORMAT.get(path.suffix.lower())
    if fmt is None:
        raise InvalidInput(f"cannot tell the mesh format of {path}; give file_format (a meshio format name)")
    cells, part = _cells(mesh, fmt in _TRIANGLE_ONLY)
    cell_data = {}
    if part is not None and fmt not in ("obj", "off", "ply"):
        if fmt.startswith("gmsh"):  # parts as physical groups (numbered from 1)
            cell_data = {"gmsh:physical": [p.astype(np.int32) + 1 for p in part],
                         "gmsh:geometrical": [p.astype(np.int32) + 1 for p in part]}
        else:
            cell_data = {"part": [p.astype(np.int32) for p in part]}
    m = meshio.Mesh(np.asarray(mesh.vertices, float), cells, cell_data=cell_data)
    if fmt.startswith("gmsh"):
        m.field_data = {name: np.array([i + 1, 2]) for i, name in enumerate(mesh.parts)}
    try:
        meshio.write(path, m, file_format=fmt, **kw)
    except (KeyError, ValueError, meshio.WriteError) as exc:
        raise InvalidInput(f"cannot write {path} as {fmt!r}: {exc}") from None


def read_mesh(path) -> SurfaceMesh:
    """Reads a surface mesh of triangles and quads with meshio (the ``part`` cell data, when
    present, becomes ``face_part``).
    Raises InvalidInput for a file meshio cannot read or one with no triangles or quadrilaterals."""
    import meshio
    m = meshio.read(path)
    faces, part = [], []
    for k, block in enumerate(m.cells):
        if block.type not in ("triangle", "quad"):
            continue
        d = np.asarray(block.data)
        f = np.full((len(d), 4), -1, dtype=int)
        f[:, : d.shape[1]] = d
        faces.append(f)
        p = m.cell_data.get("part")
        g = m.cell_data.get("gmsh:physical")
        part.append(np.asarray(p[k], int) if p is not None else
                    np.asarray(g[k], int) - 1 if g is not None else np.zeros(len(d), int))
    if not faces:
        raise InvalidInput(f"{path} holds no triangles or quadrilaterals")
    return SurfaceMesh(np.asarray(m.points, float)[:, :3], np.concatenate(faces), np.concatenate(part))
