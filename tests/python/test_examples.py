"""Examples are runnable: each runs to completion and writes what it says."""

import pathlib
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


def test_build_hull(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", ["build_hull.py", "--out", str(tmp_path)])
    runpy.run_path(str(EXAMPLES / "build_hull.py"), run_name="__main__")
    text = capsys.readouterr().out
    assert "volume" in text and "m^3" in text and "LCB" in text and "Cb" in text
    import json

    net = json.loads((tmp_path / "bare_hull_surface.json").read_text())
    assert net["half_hull"] and len(net["control_points"]) == len(net["knots_u"]) - net["degree_u"] - 1
    report = json.loads((tmp_path / "fairness_report.json").read_text())
    assert set(report) == {"waterline", "buttock", "frame"}
