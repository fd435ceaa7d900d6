"""fairlines export / lines / hydrostatics on the example description."""

import pytest

from fairlines.cli import main
from cad_fixtures import ROOT

DESCRIPTION = str(ROOT / "examples" / "container_ship.json")


def test_lines_writes_the_drawing(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    assert main(["lines", DESCRIPTION, "-o", str(tmp_path / "l.svg")]) == 0
    assert "scale 1:" in capsys.readouterr().out
    assert (tmp_path / "l.svg").stat().st_size > 10000


def test_hydrostatics_table_and_refusal(tmp_path, capsys):
    assert main(["hydrostatics", DESCRIPTION, "-o", str(tmp_path / "c.csv"), "--drafts", "2:18:4"]) == 0
    assert len((tmp_path / "c.csv").read_text().splitlines()) == 1 + 5
    assert main(["hydrostatics", DESCRIPTION, "-o", str(tmp_path / "c.csv"), "--drafts", "25"]) == 2
    assert "above the depth 19.0 m" in capsys.readouterr().err


def test_export_step(tmp_path, capsys):
    pytest.importorskip("OCP")
    assert main(["export", DESCRIPTION, "-o", str(tmp_path / "h.step"), "--verify"]) == 0
    assert "valid True, closed True" in capsys.readouterr().out
