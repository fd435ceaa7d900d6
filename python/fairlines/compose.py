"""Bulbous bow, Boolean composition of hull subdomains and mesh export.

The geometry runs in the compiled engine (``fairlines._native``); this module gives it a
Pythonic face: :class:`BulbousBow`, :func:`compose` returning a :class:`ComposedHull`, and
:func:`measure_kracht`, which reads the Kracht quantities back off a composed mesh.
Conventions: metres, x forward from AP, y >= 0 the starboard half, z up.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np

from . import _native
from ._native import NurbsSurface
from ._options import fill_options, option_names
from .hydrostatics_mesh import displaced_volume_of_mesh


def _whole(name: str):
    """Conversion of an integer option: an int, or a float with an integral value."""
    def convert(value):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
                or not float(value).is_integer():
            raise _native.InvalidInput(f"BulbousBow option {name} is {value!r}; expected an integer")
        return int(value)
    return convert


def _integer(path: str, value: Any, lo: int | None) -> int:
    """value as an int, or InvalidInput naming `path`."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or (lo is not None and int(value) < lo):
        raise _native.InvalidInput(f"{path} is {value!r}; expected {'an integer' if lo is None else f'an integer >= {lo}'}")
    return int(value)

__all__ = [
    "BlendPlacement",
    "BlendSurface",
    "BulbousBow",
    "blend_surface",
    "ComposedHull",
    "Mesh",
    "compose",
    "compose_options",
    "compose_with_blend",
    "intersect_surfaces",
    "measure_kracht",
    "mesh_hydrostatics",
    "placement_options",
    "seam_blend_placement",
    "KRACHT_NAMES",
]

#: The six Kracht (1978) coefficients.
KRACHT_NAMES = ("c_lpr", "c_bb", "c_zb", "c_abt", "c_abl", "c_vpr")
_SHIP_NAMES = ("lpp", "beam", "draft_fp", "midship_area", "displacement_volume")


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


class BulbousBow:
    """Bulbous bow from the six Kracht (1978) coefficients and the ship's particulars.

    The bulb forward of FP has superelliptic sections (exponent ``section_fullness``) whose
    breadth and height follow a superelliptic outline (exponent ``nose_shape``) to the nose at
    height Z_B; the section height H, fullness and nose shape are solved so that A_BT, A_BL
    and V_PR hold. Behind FP the section runs on unchanged for ``aft_length`` metres (default
    2 (L_PR + B_B)) into the hull. Shape controls: ``nose_height_shift`` (m) lifts the
    section centres behind a lower nose. ``surface`` is the fair-skinned NurbsSurface (u aft
    -> nose pole, v bottom -> top centre line, y >= 0).
    """

    def __init__(self, *, lpp: float, beam: float, draft_fp: float, midship_area: float,
                 displacement_volume: float, x_fp: float | None = None, **options):
        """``options`` by keyword (defaults in the engine): the Kracht coefficients (fields of
        :class:`fl.KrachtCoefficients`: c_lpr, c_bb, c_zb, c_abt, c_abl, c_vpr) and the shape
        (fields of :class:`fl.BulbOptions`: aft_length, nose_height_shift, sections,
        section_points, control_u, control_v). Raises InvalidInput naming an unknown option, a
        value of the wrong type or out of range."""
        kracht = {n: v for n, v in options.items() if n in KRACHT_NAMES}
        shape = {n: v for n, v in options.items() if n not in KRACHT_NAMES}
        unknown = set(shape) - set(option_names(_native.BulbOptions))
        if unknown:
            raise _native.InvalidInput(f"BulbousBow option {sorted(unknown)[0]!r} is unknown; expected one of "
                                       + ", ".join(KRACHT_NAMES + option_names(_native.BulbOptions)))
        ship = dict(lpp=lpp, beam=beam, draft_fp=draft_fp, midship_area=midship_area,
                    displacement_volume=displacement_volume, x_fp=-1.0 if x_fp is None else x_fp)
        as_float = {n: float for n in (*KRACHT_NAMES, *ship, "aft_length", "nose_height_shift")}
        whole = {n: _whole(n) for n in ("sections", "section_points", "control_u", "control_v")}
        k = fill_options(_native.KrachtCoefficients, "BulbousBow", kracht, as_float)
        o = fill_options(_native.BulbOptions, "BulbousBow", shape, {**as_float, **whole})
        sh = fill_options(_native.BulbShip, "BulbousBow", ship, as_float)
        self.ship = {**ship, "x_fp": lpp if x_fp is None else x_fp}
        self.kracht = {n: getattr(k, n) for n in KRACHT_NAMES}
        self._bow = _native._BulbousBow(k, sh, o)
        self.surface: NurbsSurface = self._bow.surface
        #: Derived dimensions and shape exponents (metres, m^2, m^3).
        self.shape: dict = dict(self._bow.shape)
        #: Max distance of the skinned surface from its analytic sample points (m).
        self.max_fit_deviation: float = float(self._bow.max_fit_deviation)

    @classmethod
    def from_dict(cls, section: Mapping[str, Any], ship: Mapping[str, float]) -> "BulbousBow":
        """From the ``"bulb"`` section of a hull JSON::

            {"kracht": {"c_lpr": 0.025, "c_bb": 0.18, ...},
             "shape": {"aft_length": 12.0, "nose_height_shift": 0.0}}

        and the ship particulars ``lpp, beam, draft_fp, midship_area, displacement_volume``
        (optionally ``x_fp``). Unknown keys raise InvalidInput naming them.
        """
        section = dict(section)
        unknown = set(section) - {"kracht", "shape"}
        if unknown:
            raise _native.InvalidInput(f"bulb section has unknown keys {sorted(unknown)}; expected 'kracht', 'shape'")
        kr = dict(section.get("kracht", {}))
        bad = set(kr) - set(KRACHT_NAMES)
        if bad:
            raise _native.InvalidInput(f"bulb 'kracht' has unknown keys {sorted(bad)}; expected some of {list(KRACHT_NAMES)}")
        shape = dict(section.get("shape", {}))
        allowed = set(option_names(_native.BulbOptions))
        bad = set(shape) - allowed
        if bad:
            raise _native.InvalidInput(f"bulb 'shape' has unknown keys {sorted(bad)}; expected some of {sorted(allowed)}")
        sh = dict(ship)
        missing = [n for n in _SHIP_NAMES if n not in sh]
        if missing:
            raise _native.InvalidInput(f"ship particulars miss {missing}; expected {list(_SHIP_NAMES)}")
        kw = {n: sh[n] for n in _SHIP_NAMES}
        if "x_fp" in sh:
            kw["x_fp"] = sh["x_fp"]
        return cls(**kw, **kr, **shape)

    def __repr__(self) -> str:
        s = self.shape
        return (f"BulbousBow(L_PR={s['length']:.3f} m, B_B={s['breadth']:.3f} m, "
                f"Z_B={s['nose_height']:.3f} m, H={s['height']:.3f} m, n={s['section_fullness']:.3f}, "
                f"m={s['nose_shape']:.3f})")


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

    def __init__(self, native, surfaces: Sequence[NurbsSurface]):
        self._c = native
        self.mesh = Mesh(np.asarray(native.vertices), np.asarray(native.faces))
        self.face_part = np.asarray(native.face_part)
        self.seam_vertices = np.asarray(native.seam_vertices)
        self.intersection_curves = list(native.intersection_curves)
        surf = [native.hull] + list(surfaces[1:])
        self.trimmed_surfaces = [(surf[i], [np.asarray(l) for l in loops])
                                 for i, loops in native.trimmed_surfaces]
        #: The blending surface actually meshed (or None) and its measured continuity
        #: ({max_angle_deg, max_gap} at the hull and at the bulb).
        self.blend = native.blend
        self.blend_continuity = tuple(dict(d) for d in native.blend_continuity) if native.blend is not None else None
        if self.blend is not None:
            self.trimmed_surfaces.append((self.blend, [np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])]))
        self.x_aft = float(native.x_aft)
        self.z_deck = float(native.z_deck)
        #: What compose_with_blend did about the blend (empty from compose()).
        self.blend_note = ""

    @property
    def volume(self) -> float:
        """Half-hull volume (m^3)."""
        return self.mesh.volume

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
                (x = const), one on the deck (z = const) and two on the centre plane (keel and
                stem); any parameter orientation is accepted without a blend. The blend is a
                :class:`BlendSurface` from ``blend_surface(hull, boundary_on_hull, bulb,
                ("u", u_b))`` (hull in the orient_bare_hull convention; the boundary on the
                hull runs from centre-plane edge to centre-plane edge): the hull is trimmed
                along its boundary, the bulb ahead of ``u_b``, and the blend (re-skinned at
                the mesh resolution, C1 along both) joins them with shared vertices.
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
    native = _native._compose_hull(surfaces[0], surfaces[1] if len(surfaces) > 1 else None, o, blend)
    return ComposedHull(native, surfaces)


_COUNTS = ("hull_u", "hull_v", "bulb_u", "bulb_v", "blend_rows", "blend_check_samples")


def compose_options(**options) -> _native.ComposeOptions:
    """A :class:`fl.ComposeOptions` with the given fields set (counts must be integers; the
    defaults live in the engine). Raises InvalidInput for an unknown name or a non-integer count."""
    checks = {name: (lambda v, n=name: _integer(n, v, None)) for name in _COUNTS}
    return fill_options(_native.ComposeOptions, "compose", options,
                        {**checks, "tolerance": float, "margin": float, "plane_tolerance": float})


def measure_kracht(mesh: Mesh, *, x_fp: float, lpp: float, beam: float, draft_fp: float,
                   midship_area: float, displacement_volume: float) -> dict:
    """Kracht coefficients (:data:`KRACHT_NAMES`) measured by the engine on a closed,
    outward-oriented half-hull mesh (y >= 0), on its part below the waterline z = draft_fp (a
    raked stem reaches forward of the FP above it, and is not bulb): protrusion of the foremost
    point, breadth of the section x = x_fp, nose height, section area at the FP, centre-plane
    area and volume forward of the FP, each made dimensionless by the ship's figures.
    Raises InvalidInput for a bad mesh or a non-finite / non-positive ship dimension."""
    ship = _native.KrachtShip()
    for name, value in dict(x_fp=x_fp, lpp=lpp, beam=beam, draft_fp=draft_fp, midship_area=midship_area,
                            displacement_volume=displacement_volume).items():
        setattr(ship, name, float(value))
    k = _native._measure_kracht(np.asarray(mesh.vertices, float), np.asarray(mesh.faces), ship)
    return {name: getattr(k, name) for name in KRACHT_NAMES}


def mesh_hydrostatics(mesh: Mesh, draft: float, *, half: bool = True) -> dict:
    """Displaced volume (m^3), LCB and KB (m) of a closed, outward-oriented mesh floating at
    z = draft, by the engine's mesh hydrostatics (:func:`fl.hydrostatics_of_mesh`). ``half``:
    the mesh is the starboard half (volume doubled, centroid unchanged). Raises InvalidInput
    when the draft leaves no displaced volume or the mesh is malformed."""
    h = displaced_volume_of_mesh(mesh.vertices, mesh.faces, draft, half_hull=half)
    return dict(volume=h.volume, lcb=h.lcb, kb=h.vcb)


def _boundary_uv(surface: NurbsSurface, boundary, what: str) -> np.ndarray:
    if isinstance(boundary, tuple) and len(boundary) == 2 and isinstance(boundary[0], str):
        which, value = boundary
        t = np.linspace(0.0, 1.0, 129)
        if which == "u":
            kv = surface.knots_v
            return np.column_stack([np.full_like(t, float(value)), kv[0] + (kv[-1] - kv[0]) * t])
        if which == "v":
            ku = surface.knots_u
            return np.column_stack([ku[0] + (ku[-1] - ku[0]) * t, np.full_like(t, float(value))])
        raise _native.InvalidInput(f"{what} iso-line direction is {which!r}; expected 'u' or 'v'")
    arr = np.asarray(boundary, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise _native.InvalidInput(f"{what} has shape {arr.shape}; expected (k, 2) (u, v) points or ('u'|'v', value)")
    return arr


@dataclass(frozen=True)
class BlendSurface:
    """A blending surface: ``surface`` (u along the boundaries, v = 0 on surface a, v = 1 on
    b) and its measured continuity at each boundary (``at_a``, ``at_b``: max normal angle in
    degrees and max gap in metres, by closest-point projection)."""

    surface: NurbsSurface
    at_a: dict
    at_b: dict
    boundary_a: Any = None  #: the boundary on surface a as given ((k, 2) (u, v) array)
    boundary_b: Any = None  #: the boundary on surface b as given
    tension: float = 1.0

    @property
    def max_angle_deg(self) -> float:
        return max(self.at_a["max_angle_deg"], self.at_b["max_angle_deg"])


@dataclass(frozen=True)
class BlendPlacement:
    """Where the blend around a hull/bulb seam goes (:func:`seam_blend_placement`): the hull
    in the orient_bare_hull convention, the bulb surface, the blend's boundary on each
    (``boundary_a`` (k, 2) (u, v) on the hull, ``boundary_b`` ``("u", u_b)`` on the bulb) and
    its tension. That is all compose() takes from a blend (it skins the blend at the mesh
    resolution itself), so ``compose([hull, bulb, placement])`` equals ``compose([hull, bulb,
    placement.blend_surface()])`` without skinning a surface it does not use."""

    hull: NurbsSurface
    bulb: NurbsSurface
    boundary_a: np.ndarray
    boundary_b: tuple
    tension: float

    def blend_surface(self, **options) -> BlendSurface:
        """The blending surface itself, at this placement's tension; ``options`` as for
        :func:`blend_surface`. Raises InvalidInput for a bad option."""
        return blend_surface(self.hull, self.boundary_a, self.bulb, self.boundary_b,
                             **{"tension": self.tension, **options})


def blend_surface(surface_a: NurbsSurface, boundary_a, surface_b: NurbsSurface, boundary_b,
                  **options) -> BlendSurface:
    """Blending surface between two surfaces with C1 (tangent-plane) continuity along both
    boundary curves (Kim and Hwangbo 2008), by fair skinning of cubic Hermite sections.

    boundary_a, boundary_b   curves on each surface: a (k, 2) polyline of (u, v) parameters, or
                             an iso-line ``("u", value)`` / ``("v", value)``; both run the
                             same way (first point to first point).
    options                  fields of :class:`fl.BlendOptions` by keyword (defaults in the
                             engine): samples, sections along the boundaries; tension,
                             cross-boundary tangent length relative to a third of the gap;
                             check_samples, points per boundary at which the normal angle and
                             gap are measured; centre_plane_ends.

    Raises InvalidInput for a bad boundary or option.
    """
    ba = _boundary_uv(surface_a, boundary_a, "boundary_a")
    bb = _boundary_uv(surface_b, boundary_b, "boundary_b")
    checks = {"samples": int, "check_samples": int, "tension": float, "centre_plane_ends": bool}
    o = fill_options(_native.BlendOptions, "blend_surface", options, checks)
    s, at_a, at_b = _native._blend_surface(surface_a, ba, surface_b, bb, o)
    return BlendSurface(s, dict(at_a), dict(at_b), ba, boundary_b, o.tension)


def placement_options(**options) -> "_native.BlendPlacementOptions":
    """A :class:`fl.BlendPlacementOptions` with the given fields set (defaults in the engine):
    clearance_u, clearance_v (hull parameter units between the seam and the blend's boundary),
    bulb_clearance (bulb u ahead of the seam), tension, points. Raises InvalidInput naming an
    unknown field or a value of the wrong type."""
    return fill_options(_native.BlendPlacementOptions, "seam_blend_placement", options)


def _boundaries_around_seam(hull: NurbsSurface, seam: dict, **options):
    """The blend's boundaries around a hull/bulb seam (``hull`` oriented, ``seam`` a dict with
    ``uv_a`` on the hull and ``uv_b`` on the bulb): (on_hull (k, 2), ("u", u_b)), placed by the
    engine (see :func:`seam_blend_placement`). Raises NoBlendFits when none fits."""
    on_hull, bulb_u = _native._blend_boundaries_around_seam(hull, seam["uv_a"], seam["uv_b"],
                                                            placement_options(**options))
    return on_hull, ("u", float(bulb_u))


def compose_with_blend(bare_hull: NurbsSurface, bulb: "BulbousBow | NurbsSurface", *, blend: bool = True,
                       **options) -> ComposedHull:
    """Bare hull + bulb composed into one closed half hull, with a C1 blending surface between
    them when ``blend`` (placed by :func:`seam_blend_placement`). ``options`` by keyword: the
    fields of :class:`fl.BlendPlacementOptions` (clearance_u, clearance_v, bulb_clearance,
    tension, points) place the blend, the rest go to :func:`compose`. The result carries
    ``blend_note``: what was done, or why no blend could be placed (then it is the plain union).

    Raises InvalidInput when the bulb cannot meet the hull (see :func:`compose`) or an option
    is out of range."""
    names = set(option_names(_native.BlendPlacementOptions))
    placing = {k: v for k, v in options.items() if k in names}
    compose_options = {k: v for k, v in options.items() if k not in names}
    if not blend:
        union = compose([bare_hull, bulb], **compose_options)
        union.blend_note = "no blend requested: plain union"
        return union
    seam_options = {k: compose_options[k] for k in ("bulb_v", "tolerance") if k in compose_options}
    try:
        placement = _place_blend(bare_hull, bulb, placement_options(**placing), seam_options)
    except _native.NoBlendFits as e:
        union = compose([bare_hull, bulb], **compose_options)
        union.blend_note = "no blend: " + str(e).split(": ", 1)[1] + "; plain union"
        return union
    # compose() skins the blend at the mesh resolution and measures its continuity itself
    out = compose([placement.hull, bulb, placement], **compose_options)
    out.blend_note = "blend: max normal angle %.3f deg at the hull, %.3f deg at the bulb" % tuple(
        d["max_angle_deg"] for d in out.blend_continuity)
    return out


def seam_blend_placement(hull: NurbsSurface, bulb: "BulbousBow | NurbsSurface", **options) -> BlendPlacement:
    """Where the blend around the seam a bulb makes on a bare hull goes, as a
    :class:`BlendPlacement`: ``compose([hull, bulb, placement])`` composes with it (skinning
    the blend at the mesh resolution), ``placement.blend_surface()`` skins the surface itself.

    On the hull (``placement.hull``: the hull in the orient_bare_hull convention, u aft cut ->
    stem, v keel -> deck) the boundary is an ellipse arc in (u, v) around the seam,
    ``clearance_u`` / ``clearance_v`` (parameter units) clear of it; on the bulb the section
    ``bulb_clearance`` ahead of the seam's foremost point; ``tension``: cross-boundary tangent
    length relative to a third of the gap. ``options``: the fields of
    :class:`fl.BlendPlacementOptions` by keyword (defaults in the engine).

    Raises InvalidInput when the bulb cannot meet the hull or an option is bad, NoBlendFits (an
    InvalidInput) when no boundary fits (the message says why)."""
    return _place_blend(hull, bulb, placement_options(**options), {})


def _place_blend(hull, bulb, options, seam_options) -> BlendPlacement:
    surface_b = bulb.surface if isinstance(bulb, BulbousBow) else bulb
    if not isinstance(hull, NurbsSurface) or not isinstance(surface_b, NurbsSurface):
        raise _native.InvalidInput(f"hull and bulb are {type(hull).__name__}, {type(bulb).__name__}; expected a "
                                   "NurbsSurface hull and a BulbousBow or NurbsSurface bulb")
    # the seam compose([hull, bulb]) traces (same checks), without meshing the union
    oriented, on_hull, bulb_u, tension = _native._seam_blend_placement(
        hull, surface_b, compose_options(**seam_options), options)
    return BlendPlacement(oriented, surface_b, on_hull, ("u", float(bulb_u)), float(tension))
