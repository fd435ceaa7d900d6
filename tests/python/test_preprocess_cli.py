"""`fairlines import` and `fairlines build`: outputs, progress, and one-line errors."""

import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from fairlines.cli import main
from fairlines.io import from_dict

# The reference hulls live next to the repository (../shared/data; see its README.md).
DATA = pathlib.Path(os.environ.get(
    "FAIRLINES_DATA", pathlib.Path(__file__).resolve().parents[3] / "shared" / "data"))


def _wigley_table(path, L=60.0, B=6.0, T=3.75):
    x = np.linspace(0, L, 13)
    z = np.linspace(0, T * 1.2, 7)
    hb = np.clip(B / 2 * (1 - (2 * (x - L / 2) / L) ** 2)[:, None] * (1 - ((T - z) / T) ** 2)[None, :], 0, None)
    hb[:, z > T] = hb[:, [np.flatnonzero(z <= T)[-1]]]  # wall-sided above the waterline
    path.write_text("x," + ",".join(f"{v:g}" for v in z) + "\n"
                    + "\n".join(f"{a:g}," + ",".join(f"{v:.9f}" for v in r) for a, r in zip(x, hb)) + "\n")
    return L, B, T


def test_import_then_build(tmp_path, capsys):
    table = tmp_path / "wigley.csv"
    L, B, T = _wigley_table(table)
    hull = tmp_path / "hull.json"
    assert main(["import", str(table), "--lpp", str(L), "--beam", str(B), "--draft", str(T), "--analysis",
                 "-o", str(hull)]) == 0
    out = capsys.readouterr()
    assert "form parameters" in out.out and "wrote" in out.out
    assert ".. skinning" in out.err  # progress on stderr
    doc = json.loads(hull.read_text())
    assert doc["type"] == "fairlines_imported_hull"
    assert doc["principal"] == {"lpp": L, "beam": B, "draft": T}
    fp = doc["form_parameters"]
    assert {"SAC", "DWL", "deck", "profile", "FOS", "FOB", "bow", "sections"} <= set(fp)
    assert max(fp["DWL"]["half_breadth"]) == pytest.approx(B / 2, rel=1e-3)
    assert doc["hydrostatics_input"]["cb"] == pytest.approx(4 / 9, rel=1e-9)  # Simpson, exact
    outdir = tmp_path / "out" / "wigley"  # as the README: build makes its folder, parents too
    assert main(["build", str(hull), "-o", str(outdir)]) == 0
    text = capsys.readouterr().out
    assert "deviation of the surface from" in text and "published" in text
    report = json.loads((outdir / "report.json").read_text())
    assert report["hydrostatics"]["surface"]["cb"] == pytest.approx(4 / 9, rel=2e-3)
    assert report["deviation"]["rms"] < 1e-3 * B
    surf = from_dict(json.loads((outdir / "surface_hull.json").read_text()))
    assert surf.evaluate(0.5, 0.5)[0] == pytest.approx(L / 2, rel=0.05)
    assert (outdir / "surface_hull.obj").stat().st_size > 1000


def test_import_reference_grid_folder(tmp_path, capsys):
    hull = tmp_path / "kcs.json"
    assert main(["import", str(DATA / "kcs"), "--analysis", "-o", str(hull)]) == 0
    doc = json.loads(hull.read_text())
    assert doc["form_parameters"]["bow"]["kind"] == "bulb"
    assert [s["role"] for s in doc["subdomains"]].count("bulb") == 1
    assert doc["hydrostatics_input"]["volume"] == pytest.approx(52030, rel=0.005)


@pytest.mark.parametrize("argv, message", [
    (["import", "nowhere.csv", "--lpp", "1", "--beam", "1", "--draft", "1", "-o", "h.json"], "does not exist"),
    (["import", "{table}", "--beam", "1", "--draft", "1", "-o", "h.json"], "--lpp not given"),
    (["import", "{table}", "--lpp", "1", "--beam", "-1", "--draft", "1", "-o", "h.json"], "beam is -1.0"),
    (["build", "{notjson}", "-o", "out"], "not JSON"),
    (["build", "{table}", "-o", "out"], "not JSON"),
])
def test_bad_input_one_line_no_traceback(tmp_path, capsys, argv, message):
    table = tmp_path / "t.csv"
    _wigley_table(table)
    notjson = tmp_path / "x.json"
    notjson.write_text("{oops")
    argv = [a.format(table=table, notjson=notjson) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0] and "Traceback" not in err[0]


def test_build_refuses_other_json(tmp_path, capsys):
    p = tmp_path / "c.json"
    p.write_text(json.dumps({"type": "nurbs_curve"}))
    assert main(["build", str(p), "-o", str(tmp_path / "o")]) == 2
    assert "expected 'fairlines_imported_hull'" in capsys.readouterr().err


def test_console_script_exit_code(tmp_path):
    r = subprocess.run([sys.executable, "-m", "fairlines.cli", "import", str(tmp_path / "missing.csv"),
                        "-o", str(tmp_path / "h.json")], capture_output=True, text=True)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "Traceback" not in r.stderr


def test_import_generic_tecplot_grid(tmp_path, capsys):
    """A Wigley hull as one Tecplot zone in the project's axes (metres), imported and built from the command line."""
    L, B, T = 40.0, 4.0, 2.5
    x, z = np.linspace(0, L, 17), np.linspace(0, T * 1.2, 9)
    X, Z = np.meshgrid(x, z, indexing="ij")
    Y = B / 2 * (1 - (2 * (X - L / 2) / L) ** 2) * np.clip(1 - ((T - Z) / T) ** 2, 0, None)
    Y[:, z > T] = Y[:, [np.flatnonzero(z <= T)[-1]]]
    rows = [f"{X[i, j]} {-Y[i, j]} {Z[i, j]}" for j in range(len(z)) for i in range(len(x))]  # port side
    p = tmp_path / "wigley.dat"
    p.write_text(f"Zone i= {len(x)} j= {len(z)} f=point\n" + "\n".join(rows) + "\n")
    hull = tmp_path / "h.json"
    assert main(["import", str(p), "--lpp", str(L), "--beam", str(B), "--draft", str(T), "--analysis",
                 "-o", str(hull)]) == 0
    doc = json.loads(hull.read_text())
    # The triangulated grid is a trapezoid-rule hull: 4/9 to the grid's resolution (17 x 9).
    assert doc["hydrostatics_input"]["cb"] == pytest.approx(4 / 9, rel=0.02)
    assert main(["build", str(hull), "-o", str(tmp_path / "o")]) == 0
    report = json.loads((tmp_path / "o" / "report.json").read_text())
    assert report["hydrostatics"]["surface"]["cb"] == pytest.approx(4 / 9, rel=0.005)


def test_build_given_the_whole_ship_design_says_where_it_goes(tmp_path, capsys):
    """'fairlines import' writes a whole-ship design by default; 'build' reads the --analysis file
    and, given the design, says what builds it instead."""
    p = tmp_path / "design.json"
    p.write_text(json.dumps({"principal": {"Lpp": 100.0, "B": 10.0, "T": 6.0, "D": 9.0}}))
    assert main(["build", str(p), "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "(written by 'fairlines import --analysis'); this is a whole-ship design: build it with fl.Hull.from_json" in err
