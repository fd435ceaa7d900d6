"""The command line and the JSON/OBJ helpers."""

import json
import subprocess
import sys

import numpy as np
import pytest

import fairlines as fl
from fairlines.cli import main
from fairlines.io import curve_to_dict, from_dict, surface_to_dict, tessellate


def test_json_round_trip_is_exact():
    c = fl.circle((1, 2, 3), 2.0)
    s = fl.sphere((0, 0, 0), 1.0)
    t = np.linspace(0, 1, 33)
    c2 = from_dict(json.loads(json.dumps(curve_to_dict(c))))
    s2 = from_dict(json.loads(json.dumps(surface_to_dict(s))))
    assert np.array_equal(c2.evaluate(t), c.evaluate(t))
    assert np.array_equal(s2.evaluate(t, t), s.evaluate(t, t))
    with pytest.raises(ValueError, match="no 'knots' entry"):
        from_dict({"type": "nurbs_curve", "degree": 2})


def test_tessellation_is_closed_on_a_sphere():
    # A sphere tessellated on its parameter grid has area -> 4 pi r^2 (independent check).
    v, f = tessellate(fl.sphere((0, 0, 0), 2.0), 200, 100)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    assert area == pytest.approx(4 * np.pi * 4.0, rel=2e-3)


def test_cli_fit(tmp_path, capsys):
    s = np.linspace(0, 1, 40)
    pts = np.c_[s, np.sin(3 * s)]
    np.savetxt(tmp_path / "p.csv", pts, delimiter=",")
    assert main(["fit", str(tmp_path / "p.csv"), "--n-control", "10", "-o", str(tmp_path / "c.json")]) == 0
    curve = from_dict(json.loads((tmp_path / "c.json").read_text()))
    assert curve.n_control == 10
    assert "max deviation" in capsys.readouterr().out
    # bad input: one line on stderr, exit code 2, no traceback
    assert main(["fit", str(tmp_path / "p.csv"), "--n-control", "99"]) == 2
    err = capsys.readouterr().err
    assert "n_control is 99" in err and "Traceback" not in err


def test_cli_entry_point_runs():
    out = subprocess.run([sys.executable, "-m", "fairlines.cli", "version"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and out.stdout.strip() == fl.__version__
