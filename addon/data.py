"""Plain containers passed between nodes besides the engine's own objects.

They hold numpy arrays produced by the engine; nodes never modify a value they received
(cached outputs are shared by every downstream node), they build new ones.
"""


class MeshData:
    """A polygon mesh: vertices (n, 3) float64 metres, faces (m, k) int32 vertex indices with k
    corners each, params (n, 2) surface parameters (u, v) of each vertex or None, attributes
    {name: (n,) float32} on the point domain. A mixed quad / triangle mesh has k = 4 and -1 in
    the last column of its triangles. face_attributes {name: (m,) float32} on the face domain;
    solver the fairlines.SurfaceMesh it came from (parts, draft), or None."""

    __slots__ = ("vertices", "faces", "params", "attributes", "surface", "face_attributes", "solver")

    def __init__(self, vertices, faces, params=None, attributes=None, surface=None, face_attributes=None,
                 solver=None):
        self.vertices = vertices
        self.faces = faces
        self.params = params
        self.attributes = dict(attributes or {})
        self.surface = surface
        self.face_attributes = dict(face_attributes or {})
        self.solver = solver

    def with_attributes(self, extra):
        attrs = dict(self.attributes)
        attrs.update(extra)
        return MeshData(self.vertices, self.faces, self.params, attrs, self.surface, self.face_attributes,
                        self.solver)

    def __repr__(self):
        return "MeshData(%d vertices, %d faces)" % (len(self.vertices), len(self.faces))


class LinesData:
    """Polylines sampled from curves: a list of (k, 3) float64 arrays, metres."""

    __slots__ = ("polylines",)

    def __init__(self, polylines):
        self.polylines = list(polylines)

    def __repr__(self):
        return "LinesData(%d polylines)" % len(self.polylines)
