"""Design-space sweeps: plans, failure rows, resume, and the same table on every scheduler."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys

import numpy as np
import pytest

import fairlines as fl

pytest.importorskip("distributed")
pytest.importorskip("pyarrow")

from fairlines.designer import MATCH_TOL_BULB, RANGES
import pyarrow.parquet as pq  # noqa: E402
from fairlines.sweep import SweepIncomplete, deterministic_columns, sweep
from fairlines.sweep_study import Study
from fairlines.sweep_variant import mesh_checks, named_parameter

from sweep_fixtures import base_description, dask_cluster, study


def same_table(a, b) -> None:
    cols = deterministic_columns(a.schema)
    assert a.schema.names == b.schema.names
    assert a.select(cols).to_pylist() == b.select(cols).to_pylist()


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    """The 20-variant study run in this process: the reference table."""
    return sweep(study(tmp_path_factory.mktemp("serial") / "t.parquet"), scheduler="serial")


# ---- plans ----------------------------------------------------------------------------
@pytest.mark.parametrize("method", ["lhs", "sobol"])
def test_samples_fall_one_in_each_stratum(method):
    """Latin hypercube by construction; scrambled Sobol because its 2^m first points form a
    (0, m, 1)-net in each coordinate."""
    s = Study.from_dict(study("t.parquet", samples=16))
    s.method = method
    for p in s.parameters:
        u = (np.array([v[p.path] for v in s.plan()]) - p.low) / (p.high - p.low)
        assert sorted(np.floor(u * 16).astype(int)) == list(range(16))


def test_factorial_plan_is_every_combination():
    d = study("t.parquet")
    d["sampling"] = {"method": "factorial", "levels": 3}
    d["parameters"][2] = {"path": "stern", "values": ["transom", "cruiser"]}
    plan = Study.from_dict(d).plan()
    assert len(plan) == 18
    assert len({tuple(p.values()) for p in plan}) == 18
    assert sorted({p["cb"] for p in plan}) == pytest.approx([0.6, 0.785, 0.97], abs=1e-15)


def test_sobol_wants_a_power_of_two():
    d = study("t.parquet", samples=20)
    d["sampling"]["method"] = "sobol"
    with pytest.raises(fl.InvalidInput, match="sampling.samples is 20; expected a power of two"):
        Study.from_dict(d)


def test_a_description_file_beside_the_study_is_the_base(tmp_path):
    desc = base_description()
    (tmp_path / "hull.json").write_text(json.dumps(desc))
    (tmp_path / "s.toml").write_text('[base]\ndescription = "hull.json"\n[[parameters]]\n'
                                     'path = "basic_curves.sac.lcb"\nlow = 118.0\nhigh = 119.0\n')
    s = Study.from_toml(tmp_path / "s.toml")
    assert s.base_kind == "description" and s.base == desc


def test_a_seed_fixes_the_plan():
    a, b, c = (Study.from_dict(study("t.parquet", seed=s)).plan() for s in (3, 3, 4))
    assert a == b and a != c


@pytest.mark.parametrize("path, match", [("cbb", "expected a particular"),
                                         ("bulb.kracht.c_xx", "expected bulb.kracht.NAME"),
                                         ("stem_rake.x", "expected a particular")])
def test_an_unknown_parameter_path_is_refused(path, match):
    d = study("t.parquet")
    d["parameters"][0]["path"] = path
    with pytest.raises(fl.InvalidInput, match=match):
        Study.from_dict(d)


def test_repeated_values_are_refused():
    d = study("t.parquet")
    d["parameters"][0] = {"path": "cb", "values": [0.65, 0.7, 0.65]}
    with pytest.raises(fl.InvalidInput, match="expected distinct values"):
        Study.from_dict(d)


def test_an_unknown_description_path_is_refused():
    d = study("t.parquet")
    d["base"] = {"description": base_description()}
    d["parameters"] = [{"path": "basic_curves.sac.volum", "low": 1.0, "high": 2.0}]
    with pytest.raises(fl.InvalidInput, match="the base has no 'basic_curves.sac.volum'"):
        Study.from_dict(d)


# ---- what a variant measures ------------------------------------------------------------
def test_mesh_checks_count_open_and_closed_edges():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    assert mesh_checks(v, f)["mesh.closed"] and mesh_checks(v, f)["mesh.boundary_edges"] == 0
    opened = mesh_checks(v, f[:3])
    assert opened["mesh.boundary_edges"] == 3 and not opened["mesh.closed"]


def test_a_description_path_reaches_the_hull(tmp_path):
    """Volume asked of the SAC by its dotted path = volume the built hull holds (without its bulb,
    whose share the ship's volume would add)."""
    desc = base_description()
    desc.pop("bulb")
    v0 = desc["basic_curves"]["sac"]["volume"]
    d = {"name": "sac", "base": {"description": desc}, "measure": {"fairness": False, "compose": False},
         "sampling": {"method": "factorial"}, "outputs": {"table": str(tmp_path / "t.parquet")},
         "parameters": [{"path": "basic_curves.sac.volume", "values": [0.97 * v0, 1.03 * v0]}]}
    t = fl.sweep(d, scheduler="serial").to_pylist()  # the package-level name is the function
    for r in t:
        assert r["status"] == "ok"
        assert r["hydro.volume"] == pytest.approx(r["basic_curves.sac.volume"], rel=2e-3)


def stl_volume(path) -> float:
    """Enclosed volume of a binary STL (divergence theorem over its triangles)."""
    data = path.read_bytes()
    n = int(np.frombuffer(data[80:84], "<u4")[0])
    rec = np.frombuffer(data[84:84 + 50 * n], np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    v = rec["v"].astype(float)
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)


def test_per_variant_outputs_are_written(tmp_path):
    d = study(tmp_path / "t.parquet", samples=1)
    d["parameters"] = [{"path": "cb", "values": [0.65]}]
    d["measure"].update(fairness=False)
    d["outputs"].update(per_variant=["stl", "lines"], directory=str(tmp_path / "v"))
    (r,) = sweep(d, scheduler="serial").to_pylist()
    assert r["status"] == "ok", r["error"]
    assert stl_volume(tmp_path / "v" / "variant-000000.stl") == pytest.approx(2 * r["compose.half_volume"], rel=1e-5)
    assert r["file.stl"] == str(tmp_path / "v" / "variant-000000.stl")
    assert (tmp_path / "v" / "variant-000000.png").read_bytes()[:4] == b"\x89PNG"


def test_failed_variants_are_rows_naming_the_parameter(serial):
    rows = serial.to_pylist()
    assert [r["variant"] for r in rows] == list(range(20))
    too_full = [r for r in rows if r["cb"] > RANGES["cb"][1]]
    assert too_full
    for r in too_full:
        assert r["status"] == "failed" and r["error_stage"] == "design" and r["error_type"] == "InvalidInput"
        assert r["error_parameter"] == "cb" and f"cb is {r['cb']:.4g};" in r["error"]
        assert r["hydro.volume"] is None
    built = [r for r in rows if r["status"] == "ok"]
    # the ship with its bulb, which the designer matches to MATCH_TOL_BULB
    assert built and all(r["hydro.cb"] == pytest.approx(r["cb"], rel=MATCH_TOL_BULB) for r in built)


def test_named_parameter_prefers_a_varied_path():
    params = {"cb": 0.7, "bulb.kracht.c_bb": 0.2}
    assert named_parameter("c_abt, c_bb and c_abl conflict", params) == "bulb.kracht.c_bb"
    assert named_parameter("lcb_pct is 5.1; expected -5.0 to 5.0", params) == "lcb_pct"
    assert named_parameter("the bulb's aft end is not inside the hull", params) is None


# ---- the same table everywhere --------------------------------------------------------
def test_local_cluster_gives_the_serial_table(serial, tmp_path):
    same_table(sweep(study(tmp_path / "t.parquet"), workers=2), serial)


def test_real_scheduler_and_two_workers_give_the_serial_table(serial, tmp_path):
    with dask_cluster(tmp_path) as (address, _):
        t = sweep(study(tmp_path / "t.parquet"), scheduler=address)
    same_table(t, serial)
    assert len(set(t.column("worker").to_pylist())) == 2


def test_killing_a_worker_loses_no_variant(serial, tmp_path):
    table = tmp_path / "t.parquet"
    with dask_cluster(tmp_path) as (address, workers):
        def kill_one(done, total, row):
            if done == 4 and workers[0].poll() is None:
                os.killpg(workers[0].pid, signal.SIGKILL)
        try:
            sweep(study(table), scheduler=address, progress=kill_one)
        except SweepIncomplete:
            pass
        assert workers[0].poll() is not None  # the worker did die mid-run
        rerun = sweep(study(table), scheduler=address)
    same_table(rerun, serial)


def test_a_stopped_run_resumes_with_what_is_missing(serial, tmp_path):
    class Stop(Exception):
        pass

    def stop_after_7(done, total, row):
        if done == 7:
            raise Stop
    with pytest.raises(Stop):
        sweep(study(tmp_path / "t.parquet"), scheduler="serial", progress=stop_after_7)
    seen = []
    t = sweep(study(tmp_path / "t.parquet"), scheduler="serial", progress=lambda d, n, r: seen.append(d))
    assert seen[0] == 7 and len(seen) == 1 + 13
    same_table(t, serial)


def test_a_table_of_another_study_is_refused(serial, tmp_path):
    pq.write_table(serial, tmp_path / "t.parquet")
    d = study(tmp_path / "t.parquet")
    d["measure"]["displacement"] = True
    with pytest.raises(fl.InvalidInput, match="rows of another study"):
        sweep(d, scheduler="serial")


def test_an_unreachable_scheduler_is_refused(tmp_path, monkeypatch):
    import importlib
    import socket

    monkeypatch.setattr(importlib.import_module("fairlines.sweep"), "CONNECT_SECONDS", 1)
    with socket.socket() as s:  # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with pytest.raises(fl.InvalidInput, match=f"scheduler is 'tcp://127.0.0.1:{port}'; could not connect"):
        sweep(study(tmp_path / "t.parquet"), scheduler=f"tcp://127.0.0.1:{port}")


def test_cli_writes_table_and_plot(tmp_path):
    toml = tmp_path / "s.toml"
    toml.write_text(f"""name = "cli"
[base]
particulars = {{ lpp = 244.8, breadth = 32.25, draft = 11.0, depth = 19.0, cb = 0.65, lcb = 118.73, bulb = true }}
[sampling]
method = "factorial"
[[parameters]]
path = "cb"
values = [0.65, 0.95]
[measure]
fairness = false
displacement = false
[outputs]
table = "s.parquet"
plot = "s.png"
""")
    r = subprocess.run([sys.executable, "-m", "fairlines.cli", "sweep", str(toml), "--scheduler", "serial"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "2/2 variants, 1 failed" in r.stderr and "2 variants: 1 built, 1 failed" in r.stdout
    assert pq.read_table(tmp_path / "s.parquet").num_rows == 2
    assert (tmp_path / "s.png").read_bytes()[:4] == b"\x89PNG"


def test_a_ship_without_a_bulb_is_composed_and_checked(tmp_path):
    """A bulb-less variant is composed too (its bare hull closed): a closed mesh whose
    displacement at T is the hull's volume, and no Kracht columns (it was not composed at all)."""
    d = study(tmp_path / "t.parquet", samples=1)
    d["base"]["particulars"].update(bulb=False)
    d["parameters"] = [{"path": "cb", "values": [0.65]}]
    d["measure"].update(fairness=False, displacement=True)
    d["outputs"].update(per_variant=["stl"], directory=str(tmp_path / "v"))
    (r,) = sweep(d, scheduler="serial").to_pylist()
    assert r["status"] == "ok", r["error"]
    assert r["mesh.closed"] and r["mesh.boundary_edges"] == 0
    assert r["compose.displacement"] == pytest.approx(r["hydro.volume"], rel=5e-3)
    assert r["kracht.c_lpr"] is None
    assert stl_volume(tmp_path / "v" / "variant-000000.stl") == pytest.approx(2 * r["compose.half_volume"], rel=1e-5)
