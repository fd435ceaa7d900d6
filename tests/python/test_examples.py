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
