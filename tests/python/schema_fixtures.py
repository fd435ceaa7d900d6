"""Shared helpers of the hull-description schema tests: the schema and its validator, the
descriptions to check (the examples, designed hulls, a ship written by `fairlines import`) and
edits that make a description malformed."""

from __future__ import annotations

import copy
import functools
import json
import pathlib
import re

from jsonschema import Draft202012Validator

import fairlines as fl
from fairlines.cli import main as cli_main
from import_fixtures import DATA, SERIES60

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCHEMA_PATH = ROOT / "docs" / "hull_description.schema.json"
DOC_PATH = ROOT / "docs" / "hull_description.md"
EXAMPLES = ("container_ship.json",)

#: Particulars of designed hulls whose to_json() must validate: a cargo ship with a bulb, a fine
#: ferry without a bulb with and without a parallel body, a cruiser stern, given Kracht coefficients.
DESIGNS = {
    "container_bulb": dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True),
    "ferry_no_parallel_body": dict(lpp=140.0, breadth=17.0, draft=5.5, depth=10.0, cb=0.50, lcb=67.2),
    "ferry_parallel_body": dict(lpp=140.0, breadth=17.0, draft=5.5, depth=10.0, cb=0.55, lcb=68.6,
                                parallel_length=10.0),
    "coaster_cruiser_stern": dict(lpp=100.0, breadth=16.0, draft=6.0, depth=9.0, cb=0.75, lcb=51.0, stern="cruiser"),
    "tanker_given_kracht": dict(lpp=180.0, breadth=32.0, draft=11.5, depth=17.0, cb=0.82, lcb=95.4,
                                bulb={"c_lpr": 0.03, "c_bb": 0.16}, parallel_length=50.0, parallel_centre=100.0),
}


@functools.cache
def schema() -> dict:
    return json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))


@functools.cache
def validator() -> Draft202012Validator:
    return Draft202012Validator(schema())


def schema_errors(doc) -> list[str]:
    """The schema's complaints about doc, each as 'json.path: message' (empty: valid)."""
    return [f"{e.json_path}: {e.message}" for e in validator().iter_errors(doc)]


def schema_error_paths(doc) -> list[tuple]:
    """Where in doc (a tuple of keys / indices) each of the schema's complaints points."""
    return [tuple(e.absolute_path) for e in validator().iter_errors(doc)]


def example_description() -> dict:
    """The whole container ship example as a dict (a fresh copy each call)."""
    return example("container_ship.json")


def example(name: str) -> dict:
    return json.loads((ROOT / "examples" / name).read_text(encoding="utf-8"))


@functools.cache
def _designed_json(name: str) -> str:
    return fl.design_hull(**DESIGNS[name]).to_json()


def designed_description(name: str) -> dict:
    """hull.to_json() of the designed hull `name` of DESIGNS, parsed (a fresh copy each call)."""
    return json.loads(_designed_json(name))


def imported_description(out_dir: pathlib.Path) -> dict:
    """What `fairlines import` writes for the Series 60 Cb 0.80 offsets table (the quickest real ship)."""
    out = out_dir / "series60.json"
    args = ["import", str(DATA / "series60_cb080_offsets.csv"), "--lpp", str(SERIES60["lpp"]),
            "--beam", str(SERIES60["beam"]), "--draft", str(SERIES60["draft"]), "-o", str(out)]
    assert cli_main(args) == 0
    return json.loads(out.read_text(encoding="utf-8"))


def documented_example() -> dict:
    """The minimal example of docs/hull_description.md (its first ```json block)."""
    block = re.search(r"```json\n(.*?)\n```", DOC_PATH.read_text(encoding="utf-8"), re.DOTALL)
    assert block, f"{DOC_PATH} has no ```json block"
    return json.loads(block.group(1))


# ---- edits of a description (each returns the edited copy) -------------------------------
def put(path: tuple, value):
    """An edit that sets the key at `path` (a tuple of keys / indices) to value."""
    def edit(doc: dict) -> dict:
        doc = copy.deepcopy(doc)
        node = doc
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
        return doc
    edit.path = path
    return edit


def drop(path: tuple):
    """An edit that removes the key at `path`."""
    def edit(doc: dict) -> dict:
        doc = copy.deepcopy(doc)
        node = doc
        for key in path[:-1]:
            node = node[key]
        del node[path[-1]]
        return doc
    edit.path = path
    return edit


def both(*edits):
    """The edits applied in turn."""
    def edit(doc: dict) -> dict:
        for e in edits:
            doc = e(doc)
        return doc
    return edit
