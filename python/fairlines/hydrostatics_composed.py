"""Hydrostatics of a composed hull (bare hull + bulbous bow + blend) at any draft and trim.

The bare hull is measured by NURBS quadrature (:func:`fl.hydrostatics <fairlines.hydrostatics>`);
what the bulb and blend change (volume, its centroid, wetted surface) is the difference between
the composed hull's mesh and the bare hull's own mesh at the same waterplane, so the meshes'
chordal error cancels wherever the two coincide, and where they do not (the hull cells the bulb
removes, the band round the seam) the hull surface's own figures replace the flat faces'
(bulb_share); the waterplane (area, LCF, I_T, I_L) comes
from the composed hull's exact plane section by the waterplane (Green's theorem). Conventions
are the engine's (``hydrostatics.hpp``): full-ship figures, a trim by the stern (m) over Lpp
inclines the waterplane through the draft at Lpp / 2, its area and transverse moment are the
true ones in that plane, I_L is about F along it, and LCF is the x of F.
"""

from __future__ import annotations

import math

import numpy as np

from . import _native
from ._native import HydrostaticsOptions
from .hydrostatics_mesh import hydrostatics_of_mesh
from .hydrostatics_surface import hydrostatics, midship_x
from .plane_sections import plane_sections

__all__ = ["composed_hydrostatics", "composed_waterplane", "bulb_share", "mesh_below", "waterplane_from_sections",
           "CAP_PARTS"]

#: Face labels of a composed hull's cap faces (centre plane, deck, aft cut): not wetted hull.
CAP_PARTS = (2, 3, 4)
#: The waterplane is cut this fraction of Lpp below its place: a draft at the deck would cut
#: along the hull's top edge (the deck cap), where a section has no branch of its own.
WATERPLANE_NUDGE = 1e-9


def waterplane_from_sections(cuts, density: float = HydrostaticsOptions().density) -> dict:
    """Full-ship waterplane area, LCF, I_T and I_L (about F) from the half waterline's branches
    (k, 3) by Green's theorem: the region between them, the centre line y = 0 and transverse
    lines x = const (which add nothing to the line integrals of y, x y, y^3 / 3, x^2 y along
    dx); open branches count positive, a closed branch (an island) by its enclosed area.
    Empty (no area) gives {}."""
    a = mx = it = ix2 = 0.0
    for c in cuts:
        x, y = c[:, 0], np.abs(c[:, 1])
        if np.linalg.norm(c[0] - c[-1]) < 1e-9 * max(1.0, np.ptp(x)) or len(c) < 2:
            x, y = np.r_[x, x[:1]], np.r_[y, y[:1]]
        dx = np.diff(x)
        ym, xm = 0.5 * (y[1:] + y[:-1]), 0.5 * (x[1:] + x[:-1])
        s = np.sign(np.sum(ym * dx)) or 1.0
        a += s * np.sum(ym * dx)
        mx += s * np.sum(xm * ym * dx)
        it += s * np.sum((y[1:] ** 3 + y[:-1] ** 3) / 6.0 * dx)
        ix2 += s * np.sum(xm * xm * ym * dx)
    if a <= 0:
        return {}
    lcf = mx / a
    return dict(waterplane_area=2 * a, lcf=lcf, inertia_t=2 * it, inertia_l=2 * (ix2 - a * lcf * lcf),
                tpc=density * 2 * a / 100)


class _Frame:
    """The waterplane's frame: the ship rotated about the y axis through (Lpp / 2, 0, T) by
    theta = atan(trim / Lpp), so the waterplane z = T + trim (Lpp / 2 - x) / Lpp becomes z' = T."""

    def __init__(self, draft: float, trim: float, lpp: float):
        self.x0, self.z0 = 0.5 * lpp, draft
        theta = math.atan2(trim, lpp)
        self.c, self.s = math.cos(theta), math.sin(theta)
        self.normal = (self.s, 0.0, self.c)  # the waterplane's unit normal in the ship's frame
        self.offset = self.s * self.x0 + self.c * self.z0

    def into(self, p: np.ndarray) -> np.ndarray:
        """(n, 3) ship points in the waterplane's frame."""
        dx, dz = p[:, 0] - self.x0, p[:, 2] - self.z0
        return np.column_stack([self.x0 + self.c * dx - self.s * dz, p[:, 1], self.z0 + self.s * dx + self.c * dz])

    def back(self, x: float, z: float) -> tuple[float, float]:
        """A point (x', z') of the waterplane's frame in the ship's frame."""
        dx, dz = x - self.x0, z - self.z0
        return self.x0 + self.c * dx + self.s * dz, self.z0 - self.s * dx + self.c * dz


def mesh_below(composed, draft: float, *, lpp: float, trim: float = 0.0) -> dict:
    """What of a closed half-hull mesh (a ComposedHull, ``fl.compose``'s) lies below the
    waterplane of ``draft`` (m at Lpp / 2) and ``trim`` (m by the stern over ``lpp``):
    full-ship ``volume`` (m^3), its centroid ``lcb``, ``vcb`` (m, the ship's frame) and
    ``wetted`` area (m^2) of its hull faces (not the caps: centre plane, deck, aft cut)."""
    return _below(composed, _Frame(draft, trim, lpp))


def _below(m, frame: _Frame) -> dict:
    v, f = frame.into(np.asarray(m.mesh.vertices)), np.asarray(m.mesh.faces)
    h = hydrostatics_of_mesh(v, f, frame.z0)
    x, z = frame.back(h.lcb, h.vcb) if h.volume > 0 else (0.0, 0.0)
    hull_faces = f[~np.isin(np.asarray(m.face_part), CAP_PARTS)]
    return dict(volume=h.volume, lcb=x, vcb=z, wetted=hydrostatics_of_mesh(v, hull_faces, frame.z0).wetted_surface)


def bulb_share(composed, bare_mesh, draft: float, *, lpp: float, trim: float = 0.0) -> dict:
    """What the bulb and blend add below the waterplane: the composed hull's mesh minus the bare
    hull's own mesh (``fl.compose([bare])``), with the hull surface's own figures over the hull
    faces the two meshes do not share (the cells the bulb removes, the band round the seam:
    _hull_chord_difference) in place of their flat faces': ``volume`` (m^3), its moments ``mx``,
    ``mz`` (m^4, the ship's frame) and ``wetted`` area (m^2). The flat faces alone put the
    share of the sampled designs 3.5e-4 of the ship's volume off, 6.3e-4 at most (their chords
    over the removed cells' curvature); with the surface there, within 1e-5 of a fine mesh."""
    frame = _Frame(draft, trim, lpp)
    c, b = _below(composed, frame), _below(bare_mesh, frame)
    d = _native._hull_chord_difference(composed._c, bare_mesh._c, draft, trim, lpp)
    dv, mx, mz = (2.0 * d[k] for k in ("volume", "mx", "mz"))  # the half hull's, in the waterplane's frame
    ex, ez = mx - frame.x0 * dv, mz - frame.z0 * dv  # moments about (x0, z0), turned back to the ship's frame
    return dict(volume=c["volume"] - b["volume"] + dv,
                mx=c["volume"] * c["lcb"] - b["volume"] * b["lcb"] + frame.x0 * dv + frame.c * ex + frame.s * ez,
                mz=c["volume"] * c["vcb"] - b["volume"] * b["vcb"] + frame.z0 * dv - frame.s * ex + frame.c * ez,
                wetted=c["wetted"] - b["wetted"] + 2.0 * d["wetted"])


def composed_hydrostatics(composed, draft: float, *, lpp: float, beam: float, trim: float = 0.0,
                          bare_mesh=None, waterline_cuts=None,
                          density: float = HydrostaticsOptions().density) -> dict:
    """Hydrostatics of a composed hull (``hull.composed_hull()``) floating at ``draft`` (m above
    base at Lpp / 2), trimmed ``trim`` m by the stern over ``lpp``: a dict with the keys of
    ``fl.Hydrostatics.as_dict()`` that a hydrostatic table shows (volume, displacement, lcb,
    vcb, lcf, waterplane_area, tpc, mct1cm, bmt, bml, kmt, kml, cb, cp, cm, cwp,
    wetted_surface, inertia_t, inertia_l, draft, trim) and ``source``. Am (so Cm) is the bare
    hull's at Lpp / 2, which a bulb does not reach. The waterplane is the bare hull's where the
    bulb and blend lie wholly under it, else the composed hull's section (composed_waterplane).
    ``bare_mesh``: ``fl.compose([bare])`` if already made (a table reuses it);
    ``waterline_cuts``: the upright waterplane's section branches if already cut (the lines
    plan's DWL). Raises InvalidInput as fl.hydrostatics does (a draft <= 0, a waterplane above
    the hull)."""
    from .compose import compose

    bare = composed.trimmed_surfaces[0][0]
    q = hydrostatics(bare, draft, length=lpp, breadth=beam, midship_x=midship_x(bare, 0.5 * lpp), density=density,
                     **({"trim": trim, "trim_length": lpp} if trim else {})).as_dict()
    d = bulb_share(composed, compose([bare]) if bare_mesh is None else bare_mesh, draft, lpp=lpp, trim=trim)
    vol = q["volume"] + d["volume"]
    h = dict(q, volume=vol, displacement=density * vol,
             lcb=(q["volume"] * q["lcb"] + d["mx"]) / vol, vcb=(q["volume"] * q["vcb"] + d["mz"]) / vol,
             wetted_surface=q["wetted_surface"] + d["wetted"], cb=q["cb"] * vol / q["volume"],
             cp=q["cp"] * vol / q["volume"],
             source="bare hull by NURBS quadrature, bulb and blend added from the composed mesh")
    if waterline_cuts is not None and not trim:
        w, where = _waterplane(waterline_cuts, _Frame(draft, 0.0, lpp), density), "from the composed hull's section"
    elif _under(composed.trimmed_surfaces[1:], _Frame(draft, trim, lpp)):
        w, where = {k: q[k] for k in ("waterplane_area", "lcf", "inertia_t", "inertia_l", "tpc")}, "the bare hull's"
    else:
        w = composed_waterplane(composed, draft, lpp=lpp, trim=trim, density=density)
        where = "from the composed hull's section"
    h["source"] += "; waterplane " + where
    if w:
        h.update(w, cwp=w["waterplane_area"] / (lpp * beam), bmt=w["inertia_t"] / vol, bml=w["inertia_l"] / vol)
        h.update(kmt=h["vcb"] + h["bmt"], kml=h["vcb"] + h["bml"],
                 mct1cm=h["displacement"] * h["bml"] / (100 * lpp))
    return h


def composed_waterplane(composed, draft: float, *, lpp: float, trim: float = 0.0,
                        density: float = HydrostaticsOptions().density) -> dict:
    """Full-ship waterplane area (true, in the plane), LCF (the x of F), I_T, I_L (about F along
    the plane) and TPC of a composed hull at ``draft`` and ``trim`` (as composed_hydrostatics),
    from its section by the waterplane ({} when it cuts nothing)."""
    frame = _Frame(draft, trim, lpp)
    at = frame.offset - WATERPLANE_NUDGE * lpp
    cuts = [c.points for s, loops in composed.trimmed_surfaces
            for c in plane_sections(s, frame.normal, at, loops=loops) if len(c.points) > 1]
    return _waterplane(cuts, frame, density)


def _waterplane(cuts, frame: _Frame, density: float) -> dict:
    w = waterplane_from_sections([frame.into(c) for c in cuts], density)
    if w:
        w["lcf"] = frame.back(w["lcf"], frame.z0)[0]
    return w


def _under(patches, frame: _Frame) -> bool:
    """Whether every patch lies below the waterplane: its control net does (a NURBS surface lies
    in the convex hull of its control points)."""
    n = np.asarray(frame.normal)
    return all(float((np.asarray(s.control_points).reshape(-1, 3) @ n).max()) < frame.offset for s, _ in patches)
