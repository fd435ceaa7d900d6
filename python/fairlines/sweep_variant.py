"""One variant of a design-space sweep: built, composed and measured, on whatever process runs it.

:func:`run_variant` is the unit of work a Dask worker (or a serial loop) executes. It never
raises for a bad variant: every failure becomes a row with ``status = "failed"``, the stage
that failed, the error's type and message, and the parameter the message names. Only a lost
process (a killed worker) loses a variant, and the sweep driver reruns it.

Row columns (``None`` where a stage did not run):

* ``hydro.*``   the ship's hydrostatics at the design draft (``Hull.ship_hydrostatics``: the bare
  hull's, with a bulb the composed ship's; volume m^3, LCB/LCF m from the AP, Cb Cp Cm Cwp on
  Lpp and B, wetted surface and waterplane area m^2, KMt KMl m);
* ``fair.*``    fairlines.fairness_report of the bare hull: significant curvature sign changes
  and bending energy (1/m) summed per family of cuts, and the largest |curvature| (1/m);
* ``compose.*`` the composed hull (bare hull + bulbous bow + blend; without a bulb the bare hull
  closed by deck, transom and centre plane, no Kracht columns): its closed half-hull
  volume, displacement and LCB at the design draft with the bulb (mesh, both sides), and the
  blend's largest normal angle (deg) and gap (m) at the hull and at the bulb;
* ``kracht.*``  the six Kracht coefficients measured back on the composed mesh, and the ones
  asked for (``kracht.<name>_target``);
* ``mesh.*``    checks of the composed half-hull mesh: triangles, boundary and non-manifold
  edges, degenerate triangles, closed (no boundary or non-manifold edge);
* ``time.*``    wall-clock seconds per stage and in all, and the CPU seconds of the process
  (less than the wall clock when other processes share the cores); ``worker`` host:pid;
* ``file.*``    paths of the optional per-variant outputs: STL of the full composed hull, STEP
  of its trimmed surfaces, lines-plan PNG.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import os
import re
import socket
import time
from pathlib import Path

import numpy as np

from .bulb import KRACHT_NAMES

#: A triangle with less area than this fraction of the mesh's mean triangle area is degenerate.
DEGENERATE_AREA_FRACTION = 1e-10
HYDRO_FIELDS = ("volume", "lcb", "lcf", "cb", "cp", "cm", "cwp", "wetted_surface", "waterplane_area", "kmt", "kml")
FAIR_KINDS = ("waterline", "buttock", "frame")
STAGES = ("design", "build", "hydrostatics", "fairness", "compose", "kracht", "mesh", "outputs")
#: Optional per-variant outputs and their file suffixes.
OUTPUT_SUFFIX = {"stl": ".stl", "step": ".step", "lines": ".png"}

# Every measured column and its kind ("float", "int", "bool", "str"): the table's fixed schema.
MEASURE_COLUMNS: dict[str, str] = {
    **{f"hydro.{k}": "float" for k in HYDRO_FIELDS},
    **{f"fair.{k}_sign_changes": "int" for k in FAIR_KINDS},
    **{f"fair.{k}_energy": "float" for k in FAIR_KINDS},
    "fair.max_curvature": "float",
    "compose.half_volume": "float", "compose.displacement": "float", "compose.lcb": "float",
    "compose.blend_angle_hull_deg": "float", "compose.blend_angle_bulb_deg": "float", "compose.blend_gap": "float",
    **{f"kracht.{k}": "float" for k in KRACHT_NAMES},
    **{f"kracht.{k}_target": "float" for k in KRACHT_NAMES},
    "mesh.triangles": "int", "mesh.boundary_edges": "int", "mesh.nonmanifold_edges": "int",
    "mesh.degenerate_triangles": "int", "mesh.closed": "bool",
    **{f"file.{k}": "str" for k in OUTPUT_SUFFIX},
}
STATUS_COLUMNS: dict[str, str] = {"status": "str", "error_stage": "str", "error_type": "str",
                                  "error_parameter": "str", "error": "str"}
TIMING_COLUMNS: dict[str, str] = {**{f"time.{s}_s": "float" for s in STAGES}, "time.total_s": "float",
                                  "time.cpu_s": "float", "worker": "str"}

_NAMED = re.compile(r"([A-Za-z_][\w.\[\]]*) is (?=[-+.\d'\"\[({]|nan|inf|None|True|False)")


class _StageError(Exception):
    def __init__(self, stage: str, error: BaseException):
        super().__init__(str(error))
        self.stage, self.error = stage, error


def set_path(doc: dict, path: str, value) -> None:
    """Set ``doc[a][b][c] = value`` for the dotted path ``a.b.c`` (a particulars ``bulb: true``
    becomes a dict on the way)."""
    keys = path.split(".")
    node = doc
    for k in keys[:-1]:
        nxt = node.get(k)
        if not isinstance(nxt, dict):
            nxt = {}
            node[k] = nxt
        node = nxt
    node[keys[-1]] = value


def apply_parameters(base: dict, params: dict) -> dict:
    """A deep copy of ``base`` with each dotted path of ``params`` set."""
    doc = copy.deepcopy(base)
    for path, value in params.items():
        set_path(doc, path, value)
    return doc


def named_parameter(message: str, params: dict) -> str | None:
    """The parameter an error message names: a varied path the message mentions (whole, or its
    last part as a word: "c_bb" for bulb.kracht.c_bb), else the subject of the message's first
    "NAME is VALUE" ("lower_angle is 84.6 deg; expected ..."), else None."""
    for path in sorted(params, key=len, reverse=True):
        for name in (path, path.rsplit(".", 1)[-1]):
            if re.search(rf"(?<![\w.]){re.escape(name)}(?![\w])", message):
                return path
    m = _NAMED.search(message)
    return m.group(1) if m else None


def _timed(row: dict, stage: str, fn):
    t = time.perf_counter()
    try:
        return fn()
    except Exception as exc:  # a variant's failure becomes its row, with the stage named
        raise _StageError(stage, exc) from exc
    finally:
        row[f"time.{stage}_s"] = time.perf_counter() - t


def _design(kind: str, doc: dict):
    from .designer import Particulars, design_hull
    from .hull import Hull

    if kind == "particulars":
        names = {f.name for f in dataclasses.fields(Particulars)}
        unknown = sorted(set(doc) - names)
        if unknown:
            from ._native import InvalidInput
            raise InvalidInput(f"{unknown[0]} is not a particular; expected one of {sorted(names)}")
        return design_hull(Particulars(**doc))
    return Hull.from_json(doc)


def _hydrostatics(row: dict, hull) -> None:
    h = hull.ship_hydrostatics()  # with a bulb the composed ship's, which the designer matched
    for k in HYDRO_FIELDS:
        row[f"hydro.{k}"] = float(h[k])


def _fairness(row: dict, hull, options: dict) -> None:
    rep = hull.fairness_report(**options)
    for kind in FAIR_KINDS:
        row[f"fair.{kind}_sign_changes"] = int(rep["summary"][kind])
        row[f"fair.{kind}_energy"] = float(sum(c["bending_energy"] for c in rep[kind]))
    row["fair.max_curvature"] = float(max((c["max_curvature"] for k in FAIR_KINDS for c in rep[k]), default=0.0))


def mesh_checks(vertices: np.ndarray, faces: np.ndarray) -> dict:
    """Triangles, boundary edges (used once), non-manifold edges (used more than twice),
    degenerate triangles (area under DEGENERATE_AREA_FRACTION of the mean) and closed."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    area = 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1)
    boundary, nonmanifold = int(np.sum(counts == 1)), int(np.sum(counts > 2))
    return {"mesh.triangles": int(len(f)), "mesh.boundary_edges": boundary, "mesh.nonmanifold_edges": nonmanifold,
            "mesh.degenerate_triangles": int(np.sum(area < DEGENERATE_AREA_FRACTION * max(area.mean(), 1e-300))),
            "mesh.closed": boundary == 0 and nonmanifold == 0}


def _compose(row: dict, hull, displacement: bool):
    from .hydrostatics_mesh import displaced_volume_of_mesh

    bulb = hull.bulbous_bow() if hull.description.bulb is not None else None
    composed = hull.composed_hull()  # the one ship_hydrostatics measured; without a bulb the bare hull closed
    row["compose.half_volume"] = float(composed.volume)
    if displacement:
        d = displaced_volume_of_mesh(composed.mesh.vertices, composed.mesh.faces, hull.description.principal.draft)
        row["compose.displacement"], row["compose.lcb"] = d.volume, d.lcb
    if composed.blend_continuity:
        at_hull, at_bulb = composed.blend_continuity
        row["compose.blend_angle_hull_deg"] = float(at_hull["max_angle_deg"])
        row["compose.blend_angle_bulb_deg"] = float(at_bulb["max_angle_deg"])
        row["compose.blend_gap"] = float(max(at_hull["max_gap"], at_bulb["max_gap"]))
    return bulb, composed


def _kracht(row: dict, bulb, composed) -> None:
    from .bulb import measure_kracht

    got = measure_kracht(composed.mesh, **bulb.ship)
    for k in KRACHT_NAMES:
        row[f"kracht.{k}"] = float(got[k])
        row[f"kracht.{k}_target"] = float(bulb.kracht[k])


def _outputs(row: dict, hull, composed, outputs: dict, variant: int) -> None:
    folder = Path(outputs["directory"])
    folder.mkdir(parents=True, exist_ok=True)
    pr = hull.description.principal
    for what in outputs.get("per_variant", ()):
        path = folder / f"variant-{variant:06d}{OUTPUT_SUFFIX[what]}"
        shape = composed if composed is not None else hull.bare_hull_surface()
        if what == "stl":
            if composed is None:
                continue
            composed.write_stl(path, full=True)
        elif what == "step":
            from .cad import export_cad
            export_cad(shape, path, what="surfaces")  # trimmed surfaces: the whole ship does not sew into a solid yet
        else:
            from .lines_plan import lines_plan
            lines_plan(shape, lpp=pr.lpp, beam=pr.breadth, draft=pr.draft, depth=pr.depth,
                       name=f"variant {variant}").save(path)
        row[f"file.{what}"] = str(path)


def _measure(row: dict, kind: str, doc: dict, measure: dict, outputs: dict | None, variant: int) -> None:
    hull = _timed(row, "design", lambda: _design(kind, doc))
    _timed(row, "build", hull.bare_hull_surface)
    _timed(row, "hydrostatics", lambda: _hydrostatics(row, hull))
    if measure.get("fairness", True):
        _timed(row, "fairness", lambda: _fairness(row, hull, dict(measure.get("fairness_options", {}))))
    bulb = composed = None
    if measure.get("compose", True):
        bulb, composed = _timed(row, "compose", lambda: _compose(row, hull, measure.get("displacement", True)))
        if bulb is not None:
            _timed(row, "kracht", lambda: _kracht(row, bulb, composed))
        _timed(row, "mesh", lambda: row.update(mesh_checks(composed.mesh.vertices, composed.mesh.faces)))
    if outputs and outputs.get("per_variant"):
        _timed(row, "outputs", lambda: _outputs(row, hull, composed, outputs, variant))


def run_variant(kind: str, base: dict, params: dict, measure: dict | None = None, outputs: dict | None = None,
                variant: int = 0) -> dict:
    """Build, compose and measure one variant: ``base`` (a particulars dict when ``kind`` is
    "particulars", a hull description dict when "description") with each dotted path of
    ``params`` set. ``measure``: {"fairness": bool, "fairness_options": {...}, "compose": bool,
    "displacement": bool}; ``outputs``: {"directory": path, "per_variant": ["stl", "step",
    "lines"]}. Returns the row (see the module docstring); raises nothing for a failed variant."""
    row: dict = {"variant": int(variant), "status": "ok"}
    t0, c0 = time.perf_counter(), time.process_time()
    try:
        _measure(row, kind, apply_parameters(base, params), measure or {}, outputs, variant)
    except _StageError as exc:
        msg = str(exc.error) or repr(exc.error)
        row.update(status="failed", error_stage=exc.stage, error_type=type(exc.error).__name__, error=msg,
                   error_parameter=named_parameter(msg, params))
    row["time.total_s"] = time.perf_counter() - t0
    row["time.cpu_s"] = time.process_time() - c0  # below total_s when other processes hold the cores
    row["worker"] = f"{socket.gethostname()}:{os.getpid()}"
    for k, v in list(row.items()):
        if isinstance(v, float) and not math.isfinite(v) and row["status"] == "ok":
            row.update(status="failed", error_stage="measure", error_type="NonFinite",
                       error=f"{k} is {v}; expected a finite number", error_parameter=None)
    return row
