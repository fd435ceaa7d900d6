"""Plain-data (JSON-ready) forms of curves and surfaces, and a small OBJ writer for
tessellated surfaces. Units are metres throughout."""

from __future__ import annotations

import json
import pathlib

import numpy as np

from ._native import InvalidInput, NurbsCurve, NurbsSurface
from .grid_faces import grid_triangles


def curve_to_dict(curve: NurbsCurve) -> dict:
    """{'type', 'degree', 'knots', 'control_points' (n x dim), 'weights'} as lists."""
    return {
        "type": "nurbs_curve",
        "degree": curve.degree,
        "knots": curve.knots.tolist(),
        "control_points": curve.control_points.tolist(),
        "weights": curve.weights.tolist(),
    }


def surface_to_dict(surface: NurbsSurface) -> dict:
    """{'type', 'degree_u', 'degree_v', 'knots_u', 'knots_v', 'control_points' (nu x nv x 3),
    'weights' (nu x nv)} as lists."""
    return {
        "type": "nurbs_surface",
        "degree_u": surface.degree_u,
        "degree_v": surface.degree_v,
        "knots_u": surface.knots_u.tolist(),
        "knots_v": surface.knots_v.tolist(),
        "control_points": surface.control_points.tolist(),
        "weights": surface.weights.tolist(),
    }


def from_dict(data: dict):
    """Inverse of curve_to_dict / surface_to_dict. Raises InvalidInput naming a missing key or an
    unknown type, and the engine's InvalidInput for degrees, knots or points that make no curve."""
    kind = data.get("type")
    try:
        if kind == "nurbs_curve":
            return NurbsCurve(data["degree"], data["knots"], data["control_points"], data.get("weights"))
        if kind == "nurbs_surface":
            return NurbsSurface(data["degree_u"], data["degree_v"], data["knots_u"], data["knots_v"],
                                data["control_points"], data.get("weights"))
    except KeyError as exc:
        raise InvalidInput(f"{kind} data has no {exc.args[0]!r} entry") from None
    raise InvalidInput(f"type is {kind!r}; expected 'nurbs_curve' or 'nurbs_surface'")


def save_json(obj, path) -> None:
    """Write a curve or surface as JSON."""
    data = curve_to_dict(obj) if isinstance(obj, NurbsCurve) else surface_to_dict(obj)
    pathlib.Path(path).write_text(json.dumps(data, indent=1))


def tessellate(surface: NurbsSurface, n_u: int = 64, n_v: int = 32):
    """Quad-split triangle mesh of a surface on an n_u x n_v parameter grid:
    vertices (n_u * n_v, 3) in metres, faces (2 (n_u - 1)(n_v - 1), 3) vertex indices.
    Raises InvalidInput for a grid smaller than 2 x 2."""
    if n_u < 2 or n_v < 2:
        raise InvalidInput(f"tessellation is {n_u} x {n_v}; expected at least 2 x 2")
    us = np.linspace(*surface.domain_u, n_u)
    vs = np.linspace(*surface.domain_v, n_v)
    return surface.evaluate_grid(us, vs).reshape(-1, 3), grid_triangles(n_u, n_v)


def write_obj(path, vertices, faces) -> None:
    """Wavefront OBJ with 1-based indices (metres)."""
    lines = [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in np.asarray(vertices)]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in np.asarray(faces)]
    pathlib.Path(path).write_text("\n".join(lines) + "\n")
