"""Plain containers passed between nodes besides the engine's own objects.

They hold numpy arrays produced by the engine; nodes never modify a value they received
(cached outputs are shared by every downstream node), they build new ones.
"""


class LazyAttributes:
    """Point attributes computed on first use, once, for every mesh that shares them (curvature:
    nothing on the way to the drawn meshes reads it, so it is worked out after they are drawn,
    or at once when something asks). `names` are known up front; `compute() -> {name: (n,)
    float32}`."""

    __slots__ = ("names", "_compute", "_values")

    def __init__(self, names, compute):
        self.names = tuple(names)
        self._compute = compute
        self._values = None

    @property
    def ready(self):
        return self._values is not None

    def values(self):
        if self._values is None:
            self._values = self._compute()
        return self._values


class MeshData:
    """A polygon mesh: vertices (n, 3) float64 metres, faces (m, k) int32 vertex indices with k
    corners each, params (n, 2) surface parameters (u, v) of each vertex or None, attributes
    {name: (n,) float32} on the point domain (reading it computes the lazy ones). A mixed quad /
    triangle mesh has k = 4 and -1 in the last column of its triangles. face_attributes {name:
    (m,) float32} on the face domain; solver the fairlines.SurfaceMesh it came from (parts,
    draft), or None; lazy a LazyAttributes or None."""

    __slots__ = ("vertices", "faces", "params", "_attributes", "surface", "face_attributes", "solver", "lazy")

    def __init__(self, vertices, faces, params=None, attributes=None, surface=None, face_attributes=None,
                 solver=None, lazy=None):
        self.vertices = vertices
        self.faces = faces
        self.params = params
        self._attributes = dict(attributes or {})
        self.surface = surface
        self.face_attributes = dict(face_attributes or {})
        self.solver = solver
        self.lazy = lazy

    @property
    def attributes(self):
        """Every point attribute, the lazy ones computed now if they were not yet."""
        if self.lazy is None:
            return self._attributes
        return {**self._attributes, **self.lazy.values()}

    def ready_attributes(self):
        """The point attributes that need no more work (lazy ones only once computed)."""
        if self.lazy is None or not self.lazy.ready:
            return self._attributes
        return self.attributes

    def pending_names(self):
        """Names of the point attributes still to be computed."""
        return () if self.lazy is None or self.lazy.ready else self.lazy.names

    def with_attributes(self, extra=None, lazy=None):
        attrs = dict(self._attributes)
        attrs.update(extra or {})
        if self.lazy is not None and lazy is not None:
            attrs.update(self.lazy.values())  # one lazy set per mesh: settle the older one
        return MeshData(self.vertices, self.faces, self.params, attrs, self.surface, self.face_attributes,
                        self.solver, lazy if lazy is not None else self.lazy)

    def __repr__(self):
        return "MeshData(%d vertices, %d faces)" % (len(self.vertices), len(self.faces))


class LinesData:
    """Polylines sampled from curves: a list of (k, 3) float64 arrays, metres."""

    __slots__ = ("polylines",)

    def __init__(self, polylines):
        self.polylines = list(polylines)

    def __repr__(self):
        return "LinesData(%d polylines)" % len(self.polylines)
