"""A design-space study: the base design, the parameters varied and how they are sampled.

A study is a TOML file (or the same as a dict)::

    name = "Cb, LCB and bulb breadth"
    [base]                                   # particulars for fl.design_hull ...
    particulars = { lpp = 244.8, breadth = 32.25, draft = 11.0, depth = 19.0,
                    cb = 0.65, lcb = 118.73, bulb = true }
    # description = "container_ship.json"    # ... or a hull description (file or table)
    [sampling]
    method = "lhs"                           # "factorial", "lhs" or "sobol" (scipy.stats.qmc)
    samples = 64                             # lhs / sobol (sobol: a power of two)
    seed = 1
    levels = 3                               # factorial default levels per parameter
    [[parameters]]
    path = "cb"                              # a particular, or a description's dotted path
    low = 0.6                                #   ("basic_curves.sac.volume", "bulb.kracht.c_bb")
    high = 0.72
    [[parameters]]
    path = "stern"
    values = ["transom", "cruiser"]          # listed values (categorical in lhs / sobol)
    [measure]                                # what each variant measures (all on by default)
    fairness = true
    compose = true
    displacement = true
    [outputs]                                # paths relative to the study file
    table = "study.parquet"
    plot = "study.png"
    plot_columns = ["cb", "hydro.cp", "hydro.wetted_surface"]
    per_variant = ["stl"]                    # any of "stl", "step", "lines"
    directory = "study_variants"
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ._native import InvalidInput
from .sweep_variant import KRACHT_NAMES, OUTPUT_SUFFIX

METHODS = ("factorial", "lhs", "sobol")
MEASURE_KEYS = {"fairness": bool, "compose": bool, "displacement": bool, "fairness_options": dict}
OUTPUT_KEYS = ("table", "plot", "plot_columns", "per_variant", "directory")
#: Largest study the planner accepts (variants), so a typo in levels cannot ask for billions.
MAX_VARIANTS = 1_000_000


@dataclass
class Parameter:
    """One varied parameter: a range (low, high) or listed values."""

    path: str
    low: float | None = None
    high: float | None = None
    values: list | None = None
    levels: int | None = None

    def check(self, where: str) -> None:
        """Raises InvalidInput naming the field (at ``where``) of a malformed range or value list."""
        if self.values is not None:
            if not isinstance(self.values, list) or not self.values:
                raise InvalidInput(f"{where}.values is {self.values!r}; expected a non-empty list")
            if len({json.dumps(v) for v in self.values}) != len(self.values):
                raise InvalidInput(f"{where}.values is {self.values!r}; expected distinct values (a variant is "
                                   "identified by its values)")
            return
        for k in ("low", "high"):
            v = getattr(self, k)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InvalidInput(f"{where}.{k} is {v!r}; expected a finite number (or give 'values')")
        if not self.low <= self.high:
            raise InvalidInput(f"{where}.high is {self.high}; expected >= low = {self.low}")
        if self.levels is not None and (isinstance(self.levels, bool) or not isinstance(self.levels, int) or self.levels < 1):
            raise InvalidInput(f"{where}.levels is {self.levels!r}; expected an integer >= 1")

    def at(self, u: float):
        """The value at the unit coordinate u in [0, 1)."""
        if self.values is not None:
            return self.values[min(int(u * len(self.values)), len(self.values) - 1)]
        return float(self.low + u * (self.high - self.low))

    def grid(self, levels: int) -> list:
        if self.values is not None:
            return list(self.values)
        return [float(v) for v in np.linspace(self.low, self.high, self.levels or levels)]


@dataclass
class Study:
    """A parsed, checked study (see the module docstring). Paths are resolved against ``root``."""

    name: str
    base_kind: str
    base: dict
    parameters: list[Parameter]
    method: str = "lhs"
    samples: int = 16
    seed: int = 0
    levels: int = 3
    measure: dict = field(default_factory=dict)
    outputs: dict = field(default_factory=dict)
    root: Path = Path(".")

    # ---- reading --------------------------------------------------------------------
    @classmethod
    def from_toml(cls, path) -> Study:
        """Read a study file. Raises InvalidInput for a missing file, bad TOML or bad fields."""
        try:
            import tomllib
        except ModuleNotFoundError:  # Python 3.10
            import tomli as tomllib
        path = Path(path)
        try:
            data = tomllib.loads(path.read_text())
        except OSError as exc:
            raise InvalidInput(f"study is {str(path)!r}; expected a readable TOML file ({exc.strerror})") from exc
        except tomllib.TOMLDecodeError as exc:
            raise InvalidInput(f"study {str(path)!r} is not valid TOML: {exc}") from exc
        return cls.from_dict(data, root=path.parent)

    @classmethod
    def from_dict(cls, data: dict, root=".") -> Study:
        """From the parsed TOML (a dict). Raises InvalidInput naming the bad field."""
        root = Path(root)
        unknown = sorted(set(data) - {"name", "base", "sampling", "parameters", "measure", "outputs"})
        if unknown:
            raise InvalidInput(f"{unknown[0]} is not a study section; expected name, base, sampling, parameters, "
                               "measure, outputs")
        kind, base = _base(data.get("base"), root)
        s = dict(data.get("sampling", {}))
        params = [_parameter(p, i) for i, p in enumerate(data.get("parameters") or [])]
        study = cls(name=str(data.get("name", "study")), base_kind=kind, base=base, parameters=params,
                    method=s.pop("method", "lhs"), samples=s.pop("samples", 16), seed=s.pop("seed", 0),
                    levels=s.pop("levels", 3), measure=dict(data.get("measure", {})),
                    outputs=dict(data.get("outputs", {})), root=root)
        if s:
            raise InvalidInput(f"sampling.{sorted(s)[0]} is not a sampling field; expected method, samples, seed, levels")
        study.check()
        return study

    def check(self) -> None:
        """Raises InvalidInput naming the first bad field."""
        if not self.parameters:
            raise InvalidInput("parameters is empty; expected at least one [[parameters]] table")
        if self.method not in METHODS:
            raise InvalidInput(f"sampling.method is {self.method!r}; expected one of {list(METHODS)}")
        for k, lo in (("samples", 1), ("seed", 0), ("levels", 1)):
            v = getattr(self, k)
            if isinstance(v, bool) or not isinstance(v, int) or v < lo:
                raise InvalidInput(f"sampling.{k} is {v!r}; expected an integer >= {lo}")
        if self.method == "sobol" and self.samples & (self.samples - 1):
            raise InvalidInput(f"sampling.samples is {self.samples}; expected a power of two for sobol "
                               f"(e.g. {1 << self.samples.bit_length()})")
        paths = [p.path for p in self.parameters]
        if len(set(paths)) != len(paths):
            raise InvalidInput(f"parameters repeat a path ({sorted(p for p in paths if paths.count(p) > 1)[0]}); "
                               "expected each path once")
        for i, p in enumerate(self.parameters):
            p.check(f"parameters[{i}]")
            _check_path(self.base_kind, self.base, p.path, f"parameters[{i}].path")
        _check_measure(self.measure)
        _check_outputs(self.outputs)
        if self.method == "factorial" and self.size() > MAX_VARIANTS:
            raise InvalidInput(f"the factorial plan has {self.size()} variants; expected at most {MAX_VARIANTS}")

    # ---- the plan ---------------------------------------------------------------------
    def size(self) -> int:
        if self.method == "factorial":
            return math.prod(len(p.grid(self.levels)) for p in self.parameters)
        return self.samples

    def plan(self) -> list[dict]:
        """The parameter values of every variant, in variant order (deterministic for a seed)."""
        if self.method == "factorial":
            grids = [p.grid(self.levels) for p in self.parameters]
            return [dict(zip((p.path for p in self.parameters), combo)) for combo in itertools.product(*grids)]
        return [{p.path: p.at(float(x)) for p, x in zip(self.parameters, row)} for row in self._unit_samples()]

    def _unit_samples(self) -> np.ndarray:
        from scipy.stats import qmc

        d = len(self.parameters)
        engine = qmc.LatinHypercube if self.method == "lhs" else qmc.Sobol
        try:
            sampler = engine(d, rng=self.seed)
        except TypeError:  # SciPy before 1.15 names the seed `seed`
            sampler = engine(d, seed=self.seed)
        if self.method == "sobol":
            return sampler.random_base2(int(math.log2(self.samples)))
        return sampler.random(self.samples)

    def base_digest(self) -> str:
        """Hash of what makes a variant's row (base, measure options, per-variant outputs)."""
        what = {"kind": self.base_kind, "base": self.base, "measure": self.measure,
                "per_variant": sorted(self.outputs.get("per_variant", []))}
        return hashlib.sha256(json.dumps(what, sort_keys=True, default=str).encode()).hexdigest()

    def path(self, key: str, default: str | None = None) -> Path | None:
        """An output path (``outputs.<key>``) resolved against the study's folder."""
        v = self.outputs.get(key, default)
        return None if v is None else Path(os.path.normpath(self.root / v))


def variant_key(digest: str, params: dict) -> str:
    """Identity of a variant's row: the study digest and its parameter values."""
    return hashlib.sha256((digest + json.dumps(params, sort_keys=True)).encode()).hexdigest()[:20]


def _base(base: Any, root: Path) -> tuple[str, dict]:
    if not isinstance(base, dict) or len(set(base) & {"particulars", "description"}) != 1 or len(base) != 1:
        raise InvalidInput(f"base is {base!r}; expected a table with exactly one of 'particulars' or 'description'")
    if "particulars" in base:
        p = base["particulars"]
        if not isinstance(p, dict):
            raise InvalidInput(f"base.particulars is {p!r}; expected a table of particulars")
        return "particulars", dict(p)
    d = base["description"]
    if isinstance(d, dict):
        return "description", dict(d)
    if not isinstance(d, str):
        raise InvalidInput(f"base.description is {d!r}; expected a JSON file path or a table")
    path = root / d
    try:
        return "description", json.loads(path.read_text())
    except OSError as exc:
        raise InvalidInput(f"base.description is {d!r}; expected a readable JSON file ({exc.strerror})") from exc
    except json.JSONDecodeError as exc:
        raise InvalidInput(f"base.description {d!r} is not valid JSON: {exc}") from exc


def _parameter(p: Any, i: int) -> Parameter:
    if not isinstance(p, dict) or not isinstance(p.get("path"), str):
        raise InvalidInput(f"parameters[{i}] is {p!r}; expected a table with a 'path' string")
    names = {f.name for f in dataclasses.fields(Parameter)}
    unknown = sorted(set(p) - names)
    if unknown:
        raise InvalidInput(f"parameters[{i}].{unknown[0]} is not a parameter field; expected some of {sorted(names)}")
    return Parameter(**p)


def _check_path(kind: str, base: dict, path: str, where: str) -> None:
    """A particular's name (or bulb.kracht.* / bulb.shape.*), or a dotted path to a value the
    base description holds (the bulb's Kracht and shape keys may be absent: they default)."""
    from .designer import Particulars

    keys = path.split(".")
    if kind == "particulars":
        names = {f.name for f in dataclasses.fields(Particulars)} - {"notes"}
        if keys[0] not in names or (len(keys) > 1 and keys[0] != "bulb"):
            raise InvalidInput(f"{where} is {path!r}; expected a particular ({sorted(names)}) or bulb.kracht.NAME")
    if keys[0] == "bulb" and len(keys) > 1 and (len(keys) != 3 or keys[1] not in ("kracht", "shape")
                                                or (keys[1] == "kracht" and keys[2] not in KRACHT_NAMES)):
        raise InvalidInput(f"{where} is {path!r}; expected bulb.kracht.NAME (NAME one of {list(KRACHT_NAMES)}) "
                           "or bulb.shape.NAME")
    node: Any = base
    for depth, k in enumerate(keys):
        if isinstance(node, dict) and k in node:
            node = node[k]
            continue
        if keys[0] == "bulb" and depth >= 1:
            return
        if kind == "particulars" and depth == 0:
            return
        have = sorted(node) if isinstance(node, dict) else []
        raise InvalidInput(f"{where} is {path!r}; the base has no {'.'.join(keys[:depth + 1])!r} (expected one of {have})")


def _check_measure(measure: dict) -> None:
    for k, v in measure.items():
        if k not in MEASURE_KEYS:
            raise InvalidInput(f"measure.{k} is not a measure option; expected some of {sorted(MEASURE_KEYS)}")
        if not isinstance(v, MEASURE_KEYS[k]):
            raise InvalidInput(f"measure.{k} is {v!r}; expected a {MEASURE_KEYS[k].__name__}")


def _check_outputs(outputs: dict) -> None:
    for k, v in outputs.items():
        if k not in OUTPUT_KEYS:
            raise InvalidInput(f"outputs.{k} is not an output option; expected some of {list(OUTPUT_KEYS)}")
    bad = [w for w in outputs.get("per_variant", []) if w not in OUTPUT_SUFFIX]
    if bad:
        raise InvalidInput(f"outputs.per_variant has {bad[0]!r}; expected some of {sorted(OUTPUT_SUFFIX)}")
    if not isinstance(outputs.get("plot_columns", []), list):
        raise InvalidInput(f"outputs.plot_columns is {outputs['plot_columns']!r}; expected a list of column names")
