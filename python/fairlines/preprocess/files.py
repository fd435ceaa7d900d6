"""The imported-hull document: import (input -> JSON), load, and build (surfaces, meshes, OBJ files)."""

from __future__ import annotations

import json
import pathlib

from .._native import InvalidInput
from ..io import save_json, tessellate, write_obj
from ..offsets import HullData, hull_data_from_dict, hull_data_to_dict
from .forebody import hull_description
from .jsonable import jsonable
from .meshes import input_hydrostatics, mesh_hydrostatics, surface_meshes
from .parameters import form_parameters
from .quadrature import surface_hydrostatics
from .rebuild import rebuild


HULL_JSON_TYPE = "fairlines_imported_hull"


def import_hull(data: HullData, progress=None) -> dict:
    """The hull description written by ``fairlines import``: principal dimensions, the form
    parameters found automatically (basic curves, per-section parameters, bow features), the
    hydrostatics of the input, the published particulars and the input data itself."""
    say = progress or (lambda msg: None)
    say("integrating the input (Simpson / trapezoid)")
    hyd = input_hydrostatics(data)
    for c in hyd.area_fraction_check:
        data.notes.append(f"station {c['station']!r}: tabulated area fraction {c['tabulated']:.3f} but the "
                          f"half-breadths integrate to {c['integrated']:.3f}; the half-breadths are used")
    say("skinning the sections into surfaces")
    rb = rebuild(data, progress=progress, deviation=False)
    say("reading the form parameters off the surfaces")
    fp = form_parameters(rb.surfaces, data, roles=rb.roles)
    try:
        description = hull_description(fp, data)
    except ValueError as exc:  # a hull whose forebody does not fit the description: say why
        description = None
        data.notes.append(f"no editable forebody description: {exc}")
    return jsonable({
        "type": HULL_JSON_TYPE,
        "hull_description": description,
        "name": data.name,
        "principal": {"lpp": data.lpp, "beam": data.beam, "draft": data.draft},
        "form_parameters": fp,
        "subdomains": [{"name": n, "role": r} for n, r in zip(rb.names, rb.roles)],
        "hydrostatics_input": hyd.as_dict(arrays=False),
        "published": data.published,
        "notes": data.notes,
        "input": hull_data_to_dict(data),
    })


def load_imported(doc) -> tuple:
    """(document, HullData) from a hull.json path or its dict; InvalidInput on anything else.
    Raises InvalidInput for an unreadable file, non-JSON text or a document of another type."""
    if not isinstance(doc, dict):
        path = pathlib.Path(doc)
        try:
            doc = json.loads(path.read_text())
        except OSError as exc:
            raise InvalidInput(f"cannot read {path}: {exc.strerror or exc}") from None
        except json.JSONDecodeError as exc:
            raise InvalidInput(f"{path}: not JSON ({exc.msg} at line {exc.lineno}); expected a hull.json "
                             "written by 'fairlines import --analysis'") from None
    if doc.get("type") != HULL_JSON_TYPE:
        designed = "principal" in doc  # the whole-ship design 'fairlines import' writes by default
        raise InvalidInput(f"hull description type is {doc.get('type')!r}; expected {HULL_JSON_TYPE!r} "
                           "(written by 'fairlines import --analysis')"
                           + ("; this is a whole-ship design: build it with fl.Hull.from_json or give it to "
                              "'fairlines lines', 'hydrostatics', 'export' or 'mesh'" if designed else ""))
    if "input" not in doc:
        raise InvalidInput("hull description has no 'input' entry; expected the data written by 'fairlines import'")
    return doc, hull_data_from_dict(doc["input"])


def build_hull(doc, out_dir=None, *, progress=None, mesh=(240, 160)) -> dict:
    """Rebuild the faired hull of an imported description: surfaces, deviation from every input
    point, hydrostatics of the input and of the surface (NURBS quadrature and, independently,
    a fine triangle mesh), next to the published particulars. Writes into ``out_dir`` (when
    given) one JSON and one OBJ per surface and ``report.json``."""
    say = progress or (lambda msg: None)
    doc, data = load_imported(doc)
    say("integrating the input (Simpson / trapezoid)")
    hin = input_hydrostatics(data)
    rb = rebuild(data, progress=progress)
    say("hydrostatics of the NURBS surface (Gauss quadrature)")
    hs = surface_hydrostatics(rb.surfaces, data.draft, data.lpp, data.beam, roles=rb.roles)
    say(f"hydrostatics of a {mesh[0]} x {mesh[1]} triangle mesh of the surface")
    hm = mesh_hydrostatics(surface_meshes(rb.surfaces, *mesh), data.draft, data.lpp, data.beam)
    report = jsonable({
        "name": data.name, "principal": {"lpp": data.lpp, "beam": data.beam, "draft": data.draft},
        "deviation": rb.deviation,
        "hydrostatics": {"input": hin.as_dict(arrays=False), "surface": hs.as_dict(arrays=False),
                         "surface_mesh": hm.as_dict(arrays=False)},
        "published": data.published, "subdomains": [{"name": n, "role": r} for n, r in zip(rb.names, rb.roles)],
        "notes": data.notes,
    })
    if out_dir is not None:
        out = pathlib.Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        for name, s in zip(rb.names, rb.surfaces):
            stem = "surface_" + "".join(c if c.isalnum() else "_" for c in name)
            save_json(s, out / f"{stem}.json")
            write_obj(out / f"{stem}.obj", *tessellate(s, 96, 48))
        (out / "report.json").write_text(json.dumps(report, indent=1))
    report["_surfaces"] = rb.surfaces
    return report
