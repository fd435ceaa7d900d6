"""Solver meshes and grids: the engine's quad-dominant hull mesh (fairlines.meshing) and
structured surface grids (fairlines.grids). The nodes map sockets to arguments; the geometry
is the package's."""

import bpy

from .. import engine, ids, props
from ..data import MeshData
from .base import FairlinesNode, NodeError, register

# Guards against a slip of the slider asking for millions of elements: the element size must
# leave at most this many elements of size^2 on the hull's bounding-box area.
MAX_ELEMENTS = 400_000


def mesh_data(solver, fl):
    """MeshData of a fairlines.SurfaceMesh, its elements' scaled Jacobian as a face attribute."""
    np = engine.np
    quality = np.asarray(fl._native.scaled_jacobians(solver.vertices, solver.faces), dtype=np.float32)
    return MeshData(np.asarray(solver.vertices, dtype=np.float64), np.asarray(solver.faces, dtype=np.int32),
                    face_attributes={ids.ATTR_QUALITY: quality}, solver=solver)


def _hull_of(value, fl):
    """The composed hull meshed for a Hull socket value (fl.Hull) or a surface."""
    if isinstance(value, fl.Hull):
        return value.composed_hull()
    if isinstance(value, fl.NurbsSurface):
        return value
    raise NodeError("Connect a hull (Particulars, Hull Description) or a bare-hull surface")


def _check_size(size, extent):
    if not size > 0.0:
        raise NodeError("Size is %s m; expected an element size > 0" % size)
    area = 2.0 * (extent[0] * extent[2] + extent[0] * extent[1] + extent[1] * extent[2])
    if area / (size * size) > MAX_ELEMENTS:
        raise NodeError("Size %.3g m gives about %d elements; expected at most %d (size >= %.3g m)" % (
            size, area / (size * size), MAX_ELEMENTS, (area / MAX_ELEMENTS) ** 0.5))


@register
class FLNodeHullMesh(FairlinesNode, bpy.types.Node):
    """Quad-dominant mesh of the composed hull (fairlines.mesh_hull): curvature-adaptive,
    conforming across the bulb and blend seams, watertight, normals out of the body. With Draft
    on, only the wetted part (closed by the waterplane unless Lids is off). Face attribute
    scaled_jacobian: each element's quality (1 square, <= 0 inverted)"""
    bl_idname = ids.NODE_HULL_MESH
    bl_label = "Hull Mesh"
    category = "Mesh"
    bl_width_default = 240
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {}),
                   (ids.SOCKET_LENGTH, "Size", {"default": 6.0}),
                   (ids.SOCKET_LENGTH, "Draft", {"default": 11.0, "optional": True, "use": False})]
    outputs_spec = [(ids.SOCKET_MESH, "Mesh")]
    params = ("all_quad", "lids", "full")
    all_quad: props.boolean("All Quads", False, "Split every element into quadrilaterals")
    lids: props.boolean("Lids", True, "Close the mesh with the waterplane / deck and centre plane (off: "
                        "the open wetted surface a BEM code reads)")
    full: props.boolean("Full Hull", False, "Mirror about y = 0 (turn Mirror off on Mesh Output)")

    def compute(self, inputs):
        fl, np = engine.require()
        hull = _hull_of(inputs["Hull"], fl)
        size, draft = float(inputs["Size"]), inputs["Draft"]
        box = hull.mesh.vertices if hasattr(hull, "mesh") else hull.evaluate_grid(
            np.linspace(*hull.domain_u, 9), np.linspace(*hull.domain_v, 9)).reshape(-1, 3)
        box = np.asarray(box)
        _check_size(size, box.max(axis=0) - box.min(axis=0))
        solver = fl.mesh_hull(hull, size=size, draft=None if draft is None else float(draft), lids=self.lids,
                              full=self.full, all_quad=self.all_quad)
        out = mesh_data(solver, fl)
        q = solver.quality()
        info = "%d quads, %d triangles (%.1f %% quads)\nscaled Jacobian min %.3f, mean %.3f\ninverted %d" % (
            q["quads"], q["triangles"], 100.0 * q["quad_fraction"], q["min_scaled_jacobian"],
            q["mean_scaled_jacobian"], q["inverted"])
        if draft is not None:
            info += "\nwetted, T %.3f m" % float(draft)
        return {"Mesh": out, "__info__": info}


_SPACINGS = [("uniform", "Uniform", "Equal spacing in arc length"),
             ("tanh_two_sided", "Two-sided tanh", "First and last spacing given (Vinokur 1983)"),
             ("tanh", "One-sided tanh", "First spacing given"),
             ("sinh", "One-sided sinh", "First spacing given"),
             ("geometric", "Geometric", "First spacing and a maximum growth ratio")]


def distribution(fl, kind, points, first, last, ratio):
    """A fairlines.grids distribution from a node's choice and values."""
    extra = {"tanh_two_sided": {"first": first, "last": last}, "tanh": {"first": first},
             "sinh": {"first": first}, "geometric": {"first": first, "max_ratio": ratio}}.get(kind, {})
    return fl.grids.distribution(kind, points, **extra)


@register
class FLNodeSurfaceGrid(FairlinesNode, bpy.types.Node):
    """Structured grid on a surface (fairlines.grids.surface_grid): the chosen point
    distribution along each direction, laid out in arc length; the grid's quality on the node"""
    bl_idname = ids.NODE_SURFACE_GRID
    bl_label = "Surface Grid"
    category = "Mesh"
    bl_width_default = 240
    inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {}),
                   (ids.SOCKET_INT, "Points U", {"default": 21}),
                   (ids.SOCKET_INT, "Points V", {"default": 41}),
                   (ids.SOCKET_LENGTH, "First", {"default": 0.2}),
                   (ids.SOCKET_LENGTH, "Last", {"default": 0.2}),
                   (ids.SOCKET_FLOAT, "Max Ratio", {"default": 1.2})]
    outputs_spec = [(ids.SOCKET_MESH, "Mesh")]
    params = ("spacing_u", "spacing_v")
    spacing_u: props.enum("U", _SPACINGS, "uniform")
    spacing_v: props.enum("V", _SPACINGS, "tanh_two_sided")

    def compute(self, inputs):
        fl, np = engine.require()
        s = inputs["Surface"]
        if s is None:
            raise NodeError("Connect a surface")
        nu, nv = inputs["Points U"], inputs["Points V"]
        if nu < 2 or nv < 2 or nu * nv > 1_000_000:
            raise NodeError("Points %d x %d; each must be >= 2 and the total <= 1M" % (nu, nv))
        args = (float(inputs["First"]), float(inputs["Last"]), float(inputs["Max Ratio"]))
        grid = fl.grids.surface_grid(s, u=distribution(fl, self.spacing_u, nu, *args),
                                     v=distribution(fl, self.spacing_v, nv, *args))
        from .mesh import grid_quads
        ni, nj = grid.shape
        q = grid.quality()
        mesh = MeshData(grid.points.reshape(-1, 3).astype(np.float64), grid_quads(ni, nj),
                        params=grid.params.reshape(-1, 2), surface=s)
        info = "%d x %d points\nmax stretching %.3g\northogonality max %.3g deg" % (
            ni, nj, q["max_stretching"], q["max_orthogonality_deg"])
        return {"Mesh": mesh, "__info__": info}
