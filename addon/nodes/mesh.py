"""Mesh and line nodes: tessellation, curvature analysis, iso-parametric lines."""

import functools

import bpy

from .. import engine, ids, props
from ..data import LazyAttributes, LinesData, MeshData
from .base import FairlinesNode, NodeError, register


@functools.lru_cache(maxsize=16)
def grid_quads(nu, nv):
    """Quad faces of an nu x nv point grid (fairlines.grid_quads: row-major, normals along
    S_u x S_v like the engine's surface normal) as int32. Cached (read-only) because a slider
    drag re-tessellates at the same resolution every time."""
    fl, np = engine.require()
    quads = fl.grid_quads(nu, nv).astype(np.int32)
    quads.flags.writeable = False
    return quads


_ORIENTATION = [("outward", "Outward", "Face normals point away from the surface's centroid (a hull's "
                 "outside); what Booleans, shading and volumes need"),
                ("native", "S_u x S_v", "Normals along the surface's own S_u x S_v"),
                ("reversed", "Reversed", "Normals opposite to S_u x S_v")]


@register
class FLNodeTessellate(FairlinesNode, bpy.types.Node):
    """Evaluate a surface on a parameter grid into a quad mesh (engine grid evaluation)"""
    bl_idname = ids.NODE_TESSELLATE
    bl_label = "Tessellate"
    category = "Mesh"
    inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {}),
                   (ids.SOCKET_INT, "Resolution U", {"default": 64}),
                   (ids.SOCKET_INT, "Resolution V", {"default": 32})]
    outputs_spec = [(ids.SOCKET_MESH, "Mesh")]
    params = ("orientation",)
    orientation: props.enum("Normals", _ORIENTATION, "outward")

    def compute(self, inputs):
        fl, np = engine.require()
        s = inputs["Surface"]
        if s is None:
            raise NodeError("Connect a surface")
        nu, nv = inputs["Resolution U"], inputs["Resolution V"]
        if nu < 2 or nv < 2 or nu * nv > 4_000_000:
            raise NodeError("Resolution %d x %d; each must be >= 2 and the total <= 4M points" % (nu, nv))
        us = np.linspace(*s.domain_u, nu)
        vs = np.linspace(*s.domain_v, nv)
        pts = s.evaluate_grid(us, vs).reshape(-1, 3)
        uu, vv = np.meshgrid(us, vs, indexing="ij")
        params = np.column_stack([uu.ravel(), vv.ravel()])
        faces = grid_quads(nu, nv)
        flip = self.orientation == "reversed"
        if self.orientation == "outward":
            # Outward = the faces see their own centroid from inside: the signed volume of the
            # cone from the centroid (fl.Mesh.volume) is positive. The hull's S_u x S_v
            # (u deck -> keel, v aft -> fore) points inboard, so a hull surface is flipped.
            tris = np.concatenate([faces[:, [0, 1, 2]], faces[:, [0, 2, 3]]])
            flip = fl.Mesh(pts - pts.mean(axis=0), tris).volume < 0.0
        if flip:
            faces = faces[:, ::-1].copy()
        mesh = MeshData(pts, faces, params=params, surface=s)
        return {"Mesh": mesh, "__info__": "%d vertices, %d faces%s" % (
            len(pts), len(mesh.faces), ", flipped" if flip else "")}


BOUNDARY_INSET = 1e-6  # fraction of a parameter domain: boundary vertices sampled this far inside


def _inset(domain):
    lo, hi = domain
    d = BOUNDARY_INSET * (hi - lo)
    return lo + d, hi - d


@register
class FLNodeCurvature(FairlinesNode, bpy.types.Node):
    """Gaussian and mean curvature of the surface at every vertex, as point attributes
    (gaussian_curvature 1/m^2, mean_curvature 1/m) for Geometry Nodes and shading"""
    bl_idname = ids.NODE_CURVATURE
    bl_label = "Curvature Analysis"
    category = "Mesh"
    inputs_spec = [(ids.SOCKET_MESH, "Mesh", {})]
    outputs_spec = [(ids.SOCKET_MESH, "Mesh")]

    def compute(self, inputs):
        _, np = engine.require()
        mesh = inputs["Mesh"]
        if mesh is None:
            raise NodeError("Connect a mesh from Tessellate")
        if mesh.surface is None or mesh.params is None:
            raise NodeError("Mesh has no surface parameters; connect Tessellate directly")
        s = mesh.surface
        params = mesh.params

        def curvature():
            # A whole-ship hull has degenerate corners (the deck line ends on the stem: no
            # tangent plane there). Vertices on the domain's boundary take the curvature a hair
            # inside it, the limit the shading sees; interior vertices are evaluated where they are.
            u = np.clip(params[:, 0], *_inset(s.domain_u))
            v = np.clip(params[:, 1], *_inset(s.domain_v))
            K, H = s.curvature(u, v)
            return {ids.ATTR_GAUSSIAN: np.asarray(K, dtype=np.float32), ids.ATTR_MEAN: np.asarray(H, dtype=np.float32)}
        # The attributes are computed when first read: by a node downstream, by a Mesh Output
        # whose material or modifier reads them, or else after the meshes are drawn (the mesh
        # itself does not wait for them; see data.LazyAttributes and evaluator.py).
        lazy = LazyAttributes((ids.ATTR_GAUSSIAN, ids.ATTR_MEAN), curvature)

        def info():
            values = lazy.values()
            K, H = values[ids.ATTR_GAUSSIAN], values[ids.ATTR_MEAN]
            return {"__info__": "K %.3g .. %.3g 1/m2\nH %.3g .. %.3g 1/m" % (K.min(), K.max(), H.min(), H.max())}
        return {"Mesh": mesh.with_attributes(lazy=lazy), "__later__": info}


@register
class FLNodeIsoLines(FairlinesNode, bpy.types.Node):
    """Iso-parametric lines of a surface (engine iso-curves), sampled as polylines"""
    bl_idname = ids.NODE_ISO_LINES
    bl_label = "Iso Lines"
    category = "Lines"
    inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {}),
                   (ids.SOCKET_INT, "Count U", {"default": 10}),
                   (ids.SOCKET_INT, "Count V", {"default": 5}),
                   (ids.SOCKET_INT, "Samples", {"default": 64})]
    outputs_spec = [(ids.SOCKET_LINES, "Lines")]

    def compute(self, inputs):
        _, np = engine.require()
        s = inputs["Surface"]
        if s is None:
            raise NodeError("Connect a surface")
        cu, cv, n = inputs["Count U"], inputs["Count V"], inputs["Samples"]
        if cu < 0 or cv < 0 or n < 2 or (cu + cv) * n > 2_000_000:
            raise NodeError("Counts must be >= 0, samples >= 2 and (counts) x samples <= 2M")
        lines = []
        params = {}  # iso-curves share their domain: one sample vector for all of them
        for direction, count, dom in (("u", cu, s.domain_u), ("v", cv, s.domain_v)):
            for t in np.linspace(dom[0], dom[1], count) if count > 1 else ([0.5 * (dom[0] + dom[1])] if count else []):
                c = s.iso_curve(direction, float(t))
                cdom = tuple(c.domain)
                ts = params.get(cdom)
                if ts is None:
                    ts = params[cdom] = np.linspace(cdom[0], cdom[1], n)
                lines.append(np.asarray(c.evaluate(ts), dtype=np.float64))
        return {"Lines": LinesData(lines), "__info__": "%d lines" % len(lines)}
