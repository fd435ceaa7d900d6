"""Headless real-Blender tests: package the add-on, then run blender_checks.py in
  - the `bpy` module from PyPI (newest installable, 5.0 on Python 3.11), installed as a 4.2+
    extension from dist/*-extension.zip (the engine comes from the wheel inside it);
  - Debian's `blender` executable (3.4), installed as a legacy add-on from dist/*-legacy.zip
    (and re-installed over itself while running, which must not crash).
A third test runs Debian's Blender with its interface under Xvfb for undo/redo.
`make blender-test` installs both (see the Makefile); the executables can be overridden with
FAIRLINES_BPY_PYTHON and FAIRLINES_BLENDER.
"""

import glob
import json
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHECKS = os.path.join(ROOT, "tests", "blender", "blender_checks.py")
BPY_PYTHON = os.environ.get("FAIRLINES_BPY_PYTHON", os.path.join(ROOT, ".venv-bpy", "bin", "python"))
BLENDER = os.environ.get("FAIRLINES_BLENDER", "blender")


@pytest.fixture(scope="session")
def packages():
    """Build the engine wheel and both add-on zips from this checkout."""
    subprocess.run([sys.executable, os.path.join(ROOT, "tools", "package_addon.py")], check=True,
                   cwd=ROOT)
    ext = glob.glob(os.path.join(ROOT, "dist", "fairlines_blender-*-extension.zip"))
    legacy = glob.glob(os.path.join(ROOT, "dist", "fairlines_blender-*-legacy.zip"))
    assert len(ext) == 1 and len(legacy) == 1
    return {"extension": ext[0], "legacy": legacy[0]}


def _run(cmd, env_extra, tmp_path):
    env = dict(os.environ)
    env.update(env_extra)
    env.pop("PYTHONPATH", None)  # the engine must come from the installed add-on
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=str(tmp_path), timeout=900)
    report = None
    for line in proc.stdout.splitlines():
        if line.startswith("FAIRLINES-CHECKS "):
            report = json.loads(line[len("FAIRLINES-CHECKS "):])
    assert report is not None, "no report from Blender (rc %d)\n%s\n%s" % (
        proc.returncode, proc.stdout[-3000:], proc.stderr[-3000:])
    assert proc.returncode == 0 and "error" not in report, report.get("error", proc.stderr[-3000:])
    # Nothing may escape as a Python traceback, in Blender's own output either.
    assert "Traceback" not in proc.stdout and "Traceback" not in proc.stderr, proc.stdout + proc.stderr
    return report


def test_bpy_module_extension(packages, tmp_path):
    report = _run([BPY_PYTHON, CHECKS, "--zip", packages["extension"], "--mode", "extension",
                   "--tmp", str(tmp_path / "work")],
                  {"BLENDER_USER_RESOURCES": str(tmp_path / "user")}, tmp_path)
    assert report["blender"].startswith(("4.", "5.")) and report["python"].startswith("3.11")
    assert "extensions" in report["engine_from"], report["engine_from"]
    print(json.dumps(report, indent=1))


def test_debian_blender_legacy(packages, tmp_path):
    report = _run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", CHECKS,
                   "--", "--zip", packages["legacy"], "--mode", "legacy", "--tmp", str(tmp_path / "work")],
                  {"BLENDER_USER_SCRIPTS": str(tmp_path / "scripts"),
                   "BLENDER_USER_CONFIG": str(tmp_path / "config")}, tmp_path)
    assert report["blender"].startswith("3.4") and report["python"].startswith("3.11")
    assert "fairlines_engine" in report["engine_from"], report["engine_from"]
    print(json.dumps(report, indent=1))


def test_debian_blender_gui_undo_redo(packages, tmp_path):
    """Undo needs a window: Debian's Blender with its interface under Xvfb. Also shows the
    timer-driven live evaluation in a real event loop (no explicit flush)."""
    report = _run(["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", BLENDER, "--factory-startup",
                   "--python", os.path.join(ROOT, "tests", "blender", "gui_undo_check.py"),
                   "--", "--zip", packages["legacy"]],
                  {"BLENDER_USER_SCRIPTS": str(tmp_path / "scripts"),
                   "BLENDER_USER_CONFIG": str(tmp_path / "config")}, tmp_path)
    assert report["ok"]
    assert abs(report["v_after_undo"] - report["v_short"]) < 1e-6 * report["v_short"]


OUTPUT_CHECKS = os.path.join(ROOT, "tests", "blender", "output_checks.py")


def test_output_nodes_bpy_module(packages, tmp_path):
    """Output nodes and the sweep face in the bpy module, whose Python has the optional extras
    (make blender-deps installs them): each file equals the package's own."""
    report = _run([BPY_PYTHON, OUTPUT_CHECKS, "--zip", packages["extension"], "--tmp", str(tmp_path / "work")],
                  {"BLENDER_USER_RESOURCES": str(tmp_path / "user")}, tmp_path)
    assert "t_export_cad" in report["passed"] and "export_cad" in report, report
    print(json.dumps(report, indent=1))


def test_output_nodes_debian_blender_without_extras(packages, tmp_path):
    """Debian's Blender has none of the extras: the file nodes are red with the pip line."""
    report = _run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", OUTPUT_CHECKS,
                   "--", "--zip", packages["legacy"], "--tmp", str(tmp_path / "work")],
                  {"BLENDER_USER_SCRIPTS": str(tmp_path / "scripts"),
                   "BLENDER_USER_CONFIG": str(tmp_path / "config")}, tmp_path)
    assert report["blender"].startswith("3.4") and len(report["missing_messages"]) == 5, report
