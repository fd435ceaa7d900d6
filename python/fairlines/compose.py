"""Boolean composition of hull subdomains (bare hull, bulbous bow, blending surface) into one
closed half hull, and its mesh. The geometry runs in the compiled engine
(``fairlines._native``); this module gives it a Pythonic face: :func:`compose` returning a
:class:`ComposedHull`, :func:`compose_with_blend`, :func:`intersect_surfaces`.
Conventions: metres, x forward from AP, y >= 0 the starboard half, z up.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from . import _native
from ._native import MeshHydrostatics, NurbsSurface
from ._options import fill_options, option_names
from .blend import BlendPlacement, BlendSurface, seam_blend_placement
from .bulb import BulbousBow
from .hydrostatics_mesh import displaced_volume_of_mesh
from .validation import integer

__all__ = ["ComposedHull", "FACE_PARTS", "Mesh", "compose", "compose_options", "compose_with_blend",
           "intersect_surfaces", "mesh_hydrostatics"]


@dataclass(frozen=True)
class Mesh:
    """Indexed triangle mesh: ``vertices`` (n, 3) metres, ``faces`` (m, 3) vertex indices,
    counter-clockwise seen from outside."""

    vertices: np.ndarray
    faces: np.ndarray

    @property
    def volume(self) -> float:
        """Enclosed volume (m^3) by the divergence theorem."""
        return float(_native.mesh_volume(self.vertices, self.faces))

    def write_obj(self, path) -> None:
        _native.write_obj(self.vertices, self.faces, str(path))

    def write_stl(self, path, binary: bool = True) -> None:
        _native.write_stl(self.vertices, self.faces, str(path), binary)


def intersect_surfaces(a: NurbsSurface, b: NurbsSurface, **options) -> list[dict]:
    """Every intersection branch of two clamped NURBS surfaces.

    Subdivision by control-net boxes of Bezier patches, Newton seeds, marching with Newton
    correction. ``options``: the fields of :class:`fl.IntersectOptions` by keyword (defaults in
    the engine): tolerance (m, <= 1e-6), subdivisions, step (m), max_turn_deg, max_points. Each
    branch is a dict with ``points`` (k, 3), ``uv_a`` (k, 2), ``uv_b`` (k, 2), ``closed`` and
    ``max_gap`` (m). Raises InvalidInput for unclamped surfaces or a bad option,
    ConvergenceError when a branch cannot be traced to the tolerance.
    """
    o = fill_options(_native.IntersectOptions, "intersect_surfaces", options)
    return list(_native._intersect_surfaces(a, b, o))


#: Face labels of :attr:`ComposedHull.face_part`.
FACE_PARTS = ("hull", "bulb", "centre_plane", "deck", "aft_cut", "blend")


class ComposedHull:
    """Result of :func:`compose`: one watertight, outward-oriented half hull (y >= 0) closed by
    the centre plane, the deck and the aft cut.

    ``mesh`` (:class:`Mesh`), ``face_part`` (per face, index into :data:`FACE_PARTS`),
    ``trimmed_surfaces`` (list of (surface, [loops (k, 2) in its (u, v) space, ccw, kept side
    inside])), ``intersection_curves`` (seams: dicts with ``points``, ``uv_a`` on the hull,
    ``uv_b`` on the bulb, ``max_gap``), ``seam_vertices`` (mesh indices of the seam points).
    """

    def __init__(self, native, surfaces: Sequence[NurbsSurface], continuity_samples: int = 0):
        self._c = native
        self.mesh = Mesh(np.asarray(native.vertices), np.asarray(native.faces))
        self.face_part = np.asarray(native.face_part)
        self.seam_vertices = np.asarray(native.seam_vertices)
        self.intersection_curves = list(native.intersection_curves)
        surf = [native.hull] + list(surfaces[1:])
        self.trimmed_surfaces = [(surf[i], [np.asarray(l) for l in loops])
                                 for i, loops in native.trimmed_surfaces]
        #: The blending surface actually meshed (or None).
        self.blend = native.blend
        self._bulb = surfaces[1] if len(surfaces) > 1 else None
        self._continuity_samples = continuity_samples
        self._continuity = None
        if self.blend is not None:
            self.trimmed_surfaces.append((self.blend, [np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])]))
        self.x_aft = float(native.x_aft)
        self.z_deck = float(native.z_deck)
        self._note = ""

    @property
    def blend_continuity(self) -> tuple[dict, dict] | None:
        """The blend's measured continuity ({max_angle_deg, max_gap} at the hull and at the bulb)
        at blend_check_samples points per boundary, or None without a blend. Measured when first
        read: the projections cost as much as a quarter of the composition, and the designer's
        compositions are read for volume only."""
        if self.blend is None:
            return None
        if self._continuity is None:
            n = self._continuity_samples
            self._continuity = (dict(_native.boundary_continuity(self.blend, False, self._c.hull, n)),
                                dict(_native.boundary_continuity(self.blend, True, self._bulb, n)))
        return self._continuity

    @property
    def blend_note(self) -> str:
        """What compose_with_blend did about the blend (empty from compose())."""
        if self._note is None:  # a blend by compose_with_blend: its continuity read when asked
            self._note = "blend: max normal angle %.3f deg at the hull, %.3f deg at the bulb" % tuple(
                d["max_angle_deg"] for d in self.blend_continuity)
        return self._note

    @blend_note.setter
    def blend_note(self, note: str) -> None:
        self._note = note

    @property
    def volume(self) -> float:
        """Half-hull volume (m^3)."""
        return self.mesh.volume

    @property
    def native(self) -> "_native._ComposedHull":
        """The engine's composed hull (the mesher meshes it; ``native.hull`` is the oriented bare hull)."""
        return self._c

    def full_mesh(self) -> Mesh:
        """The full hull: mirrored in y = 0 and welded along the centre plane."""
        v, f = self._c.full_mesh()
        return Mesh(np.asarray(v), np.asarray(f))

    def write_obj(self, path, full: bool = False) -> None:
        (self.full_mesh() if full else self.mesh).write_obj(path)

    def write_stl(self, path, full: bool = False, binary: bool = True) -> None:
        (self.full_mesh() if full else self.mesh).write_stl(path, binary)


def compose(subdomains: Sequence[Any], operation: str = "union", **options) -> ComposedHull:
    """Boolean composition of hull subdomains into one closed half hull.

    subdomains  [bare_hull], [bare_hull, bulb] or [bare_hull, bulb, blend]: NurbsSurface (or
                :class:`BulbousBow` for the bulb). The bare hull has one edge on an aft cut
                (a plane: x = const, or a raked transom's), one on the deck (z = const) and two
                on the centre plane (keel and
                stem); any parameter orientation is accepted without a blend. The blend is a
                :class:`BlendSurface` from ``blend_surface(hull, boundary_on_hull, bulb,
                ("u", u_b))`` (hull in the orient_bare_hull convention; the boundary on the
                hull runs from centre-plane edge to centre-plane edge): the hull is trimmed
                along its boundary, the bulb ahead of ``u_b``, and the blend (re-skinned at
                the mesh resolution, G2 along both) joins them with shared vertices.
    operation   "union" (the only Boolean a hull needs: the bulb's part inside the hull is
                removed, and the hull's part inside the bulb).
    options     fields of :class:`fl.ComposeOptions` by keyword (defaults in the engine):
    hull_u, hull_v, bulb_u, bulb_v   tessellation cells; tolerance: intersection (m, <= 1e-6);
    margin      clearance between the seam and whole hull cells (fraction of a cell).
    blend_rows  blend cells from the hull boundary to the bulb boundary.
    blend_check_samples   points per boundary at which the blend's continuity
                ``blend_continuity`` is measured (>= 2; each is a projection onto hull or
                bulb). The same figures come from ``boundary_continuity(c.blend, False,
                c.trimmed_surfaces[0][0], n)`` and ``(c.blend, True, bulb, n)``, so a caller
                can pass 2 and measure them later.

    Raises InvalidInput ("bulb cannot meet the hull ...") when the bulb does not cross the hull
    in one seam from the keel/stem line around to the stem, and for an unknown or bad option.
    """
    o = compose_options(**options)
    if operation != "union":
        raise _native.InvalidInput(f"operation is {operation!r}; expected 'union'")
    subs = list(subdomains)
    if not 1 <= len(subs) <= 3:
        raise _native.InvalidInput(f"subdomains has {len(subs)} entries; expected [bare_hull], [bare_hull, bulb] "
                         "or [bare_hull, bulb, blend]")
    blend = None
    if len(subs) == 3:
        bl = subs.pop()
        if not isinstance(bl, (BlendSurface, BlendPlacement)):
            raise _native.InvalidInput(f"subdomains[2] is {type(bl).__name__}; expected a BlendSurface from blend_surface() "
                             "or a BlendPlacement from seam_blend_placement()")
        bb = bl.boundary_b
        if not (isinstance(bb, tuple) and len(bb) == 2 and bb[0] == "u"):
            raise _native.InvalidInput(f"the blend's bulb boundary is {bb!r}; expected a bulb section ('u', value)")
        blend = fill_options(_native.BlendSpec, "blend", dict(hull_uv=np.asarray(bl.boundary_a, float),
                                                              bulb_u=float(bb[1]), tension=float(bl.tension)))
    surfaces = [s.surface if isinstance(s, BulbousBow) else s for s in subs]
    for i, s in enumerate(surfaces):
        if not isinstance(s, NurbsSurface):
            raise _native.InvalidInput(f"subdomains[{i}] is {type(s).__name__}; expected a NurbsSurface or BulbousBow")
    samples = o.blend_check_samples
    if samples < 2:
        raise _native.InvalidInput(f"blend_check_samples is {samples}; expected >= 2")
    o.blend_check_samples = 2  # the least the engine takes; ComposedHull.blend_continuity measures at `samples`
    native = _native._compose_hull(surfaces[0], surfaces[1] if len(surfaces) > 1 else None, o, blend)
    return ComposedHull(native, surfaces, samples)


_COUNTS = ("hull_u", "hull_v", "bulb_u", "bulb_v", "blend_rows", "blend_check_samples")


def compose_options(**options) -> _native.ComposeOptions:
    """A :class:`fl.ComposeOptions` with the given fields set (counts must be integers; the
    defaults live in the engine). Raises InvalidInput for an unknown name or a non-integer count."""
    checks = {name: (lambda v, n=name: integer(n, v)) for name in _COUNTS}
    return fill_options(_native.ComposeOptions, "compose", options,
                        {**checks, "tolerance": float, "margin": float, "plane_tolerance": float})


def mesh_hydrostatics(mesh: Mesh, draft: float, *, half: bool = True) -> MeshHydrostatics:
    """Hydrostatics (volume m^3, lcb and vcb m, waterplane, wetted surface ...) of a closed,
    outward-oriented mesh floating at z = draft, by the engine (:func:`fl.hydrostatics_of_mesh`).
    ``half``: the mesh is the starboard half (volume doubled, centroid unchanged). Raises
    InvalidInput when the draft leaves no displaced volume or the mesh is malformed."""
    return displaced_volume_of_mesh(mesh.vertices, mesh.faces, draft, half_hull=half)


def compose_with_blend(bare_hull: NurbsSurface, bulb: "BulbousBow | NurbsSurface", *, blend: bool = True,
                       placement: BlendPlacement | None = None, **options) -> ComposedHull:
    """Bare hull + bulb composed into one closed half hull, with a G2 blending surface between
    them when ``blend`` (placed by :func:`seam_blend_placement`). ``options`` by keyword: the
    fields of :class:`fl.BlendPlacementOptions` (clearance_u, clearance_v, bulb_clearance,
    tension, points) place the blend, the rest go to :func:`compose`; ``placement``: the
    BlendPlacement seam_blend_placement already found for this hull, bulb and options (None:
    found here). The result carries
    ``blend_note``: what was done, or why no blend could be placed (then it is the plain union).

    Raises InvalidInput when the bulb cannot meet the hull (see :func:`compose`), an option
    is out of range or ``placement`` is not a BlendPlacement."""
    if placement is not None and not isinstance(placement, BlendPlacement):
        raise _native.InvalidInput(f"placement is a {type(placement).__name__}; expected a BlendPlacement from "
                                   "seam_blend_placement() or None")
    names = set(option_names(_native.BlendPlacementOptions))
    placing = {k: v for k, v in options.items() if k in names}
    meshing = {k: v for k, v in options.items() if k not in names}
    if not blend:
        union = compose([bare_hull, bulb], **meshing)
        union.blend_note = "no blend requested: plain union"
        return union
    seam = compose_options(**{k: meshing[k] for k in ("bulb_v", "tolerance") if k in meshing})
    try:
        if placement is None:
            placement = seam_blend_placement(bare_hull, bulb, seam_options=seam, **placing)
    except _native.NoBlendFits as e:
        union = compose([bare_hull, bulb], **meshing)
        union.blend_note = "no blend: " + str(e).split(": ", 1)[1] + "; plain union"
        return union
    # compose() skins the blend at the mesh resolution; its continuity is measured when read
    out = compose([placement.hull, bulb, placement], **meshing)
    out._note = None  # blend_note formats the continuity when read
    return out
