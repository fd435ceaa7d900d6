"""Examples are runnable: each runs to completion and writes what it says."""

import pathlib
import re
import runpy
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def test_fit_wigley_surface(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", ["fit_wigley_surface.py", "--out", str(tmp_path)])
    runpy.run_path(str(EXAMPLES / "fit_wigley_surface.py"), run_name="__main__")
    text = capsys.readouterr().out
    assert "least squares" in text
    assert (tmp_path / "wigley_surface.obj").stat().st_size > 1000
    assert (tmp_path / "wigley_surface.json").exists()


def test_import_reference_hulls(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", ["import_reference_hulls.py", "--out", str(tmp_path)])
    runpy.run_path(str(EXAMPLES / "import_reference_hulls.py"), run_name="__main__")
    text = capsys.readouterr().out
    assert text.count("deviation of the surface from") == 3 and "bow feature: bulb" in text and "sonar dome" in text
    for key in ("series60", "dtmb5415", "kcs"):
        assert (tmp_path / f"{key}_hull.json").exists()
        assert (tmp_path / f"{key}_rebuilt" / "report.json").exists()


def test_design_ship(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", ["design_ship.py", "--out", str(tmp_path), "--docs", str(tmp_path)])
    runpy.run_path(str(EXAMPLES / "design_ship.py"), run_name="__main__")
    text = capsys.readouterr().out
    assert text.count("designed in") == 4
    misses = [float(v) for v in re.findall(r"\(asked [\d.]+, ([+-]\d+\.\d+) %\)", text)]
    # the container ship with its bulb to designer.MATCH_TOL_BULB, the others to 1e-6 relative
    assert len(misses) == 4 and abs(misses[0]) <= 5e-3 and max(abs(v) for v in misses[1:]) <= 1e-4
    assert (tmp_path / "designed_ships.png").stat().st_size > 10_000
    import json

    import fairlines as fl
    d = json.loads((tmp_path / "designed" / "product_tanker.json").read_text())
    h = fl.Hull.from_json(d).hydrostatics()
    assert h.volume == __import__("pytest").approx(0.82 * 180.0 * 32.0 * 11.5, rel=1e-5)
