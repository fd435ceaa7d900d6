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


@pytest.mark.parametrize("command", [["lines", "-o", "l.svg"], ["hydrostatics", "-o", "c.csv"], ["export", "-o", "h.step"]])
@pytest.mark.parametrize("content, says", [(None, "cannot be read: No such file"), ("{not json", "is not valid JSON"),
                                           ("[1, 2]", "holds a JSON list; expected a JSON object"),
                                           ('{"name": 1}', "has neither 'principal' nor 'type'")])
def test_an_unreadable_hull_file_is_named_without_a_traceback(tmp_path, capsys, command, content, says):
    path = tmp_path / "hull.json"
    if content is not None:
        path.write_text(content)
    args = [command[0], str(path), command[1], str(tmp_path / command[2])]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert f"fairlines {command[0]}: hull file {str(path)!r} {says}" in err and "Traceback" not in err


@pytest.mark.parametrize("args", [["lines", DESCRIPTION, "-o", "{missing}/l.svg"],
                                  ["hydrostatics", DESCRIPTION, "-o", "c.csv", "--plot", "{missing}/c.png"],
                                  ["mesh", DESCRIPTION, "--size", "3", "-o", "{missing}/m.vtu"]])
def test_an_output_into_a_missing_folder_is_refused_before_the_work(tmp_path, capsys, args):
    missing = tmp_path / "no such folder"
    args = [a.format(missing=missing) if "{missing}" in a else (str(tmp_path / a) if a.endswith(".csv") else a) for a in args]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert f"the output's folder {str(missing)!r} does not exist" in err and ".." not in err  # no progress: nothing ran


@pytest.mark.parametrize("drafts", ["1:5:0", "1:5", "abc", "5:1:1"])
def test_a_malformed_draft_range_names_the_option(tmp_path, capsys, drafts):
    assert main(["hydrostatics", DESCRIPTION, "-o", str(tmp_path / "c.csv"), "--drafts", drafts]) == 2
    assert f"--drafts is {drafts!r}; expected FROM:TO:STEP" in capsys.readouterr().err


def test_export_composes_a_ship_without_a_bulb(tmp_path, capsys):
    """--compose on a designed ship with no bulb: its bare hull closed by deck, transom and centre
    plane, a valid closed solid (it once asked for a bulb section)."""
    pytest.importorskip("OCP")
    design = tmp_path / "coaster.json"
    assert main(["design", "--lpp", "100", "--breadth", "16", "--draft", "6", "--depth", "9", "--cb", "0.75", "--lcb", "51",
                 "-o", str(design)]) == 0
    assert main(["export", str(design), "--compose", "-o", str(tmp_path / "c.step"), "--verify"]) == 0
    assert "valid True, closed True" in capsys.readouterr().out


def test_design_places_a_sonar_dome_where_the_command_line_says(tmp_path):
    import json

    design = tmp_path / "frigate.json"
    assert main(["design", "--lpp", "140", "--breadth", "17", "--draft", "5.5", "--depth", "10", "--cb", "0.5",
                 "--lcb", "67.2", "--sonar-dome", "--sonar-dome-nose", "110", "-o", str(design)]) == 0
    assert json.loads(design.read_text())["dome"]["x_fore"] == 110.0


def test_a_trim_that_sinks_the_deck_names_the_trim(tmp_path, capsys):
    """Default drafts from T/10 to the deck at every trim: a trim of 100 m leaves none (the
    message once listed 19 negative drafts the user never gave)."""
    assert main(["hydrostatics", DESCRIPTION, "-o", str(tmp_path / "c.csv"), "--trims", "0,100"]) == 2
    err = capsys.readouterr().err
    assert "--trims holds 100 m, at which the deck dips below T/10" in err and "drafts are" not in err


def test_a_bulbed_description_is_measured_and_drawn_with_its_bulb(tmp_path, capsys):
    """The example has a bulb: hydrostatics takes the composed ship unless --bare asks
    for the bare hull, whose rows are fl.hydrostatics of its surface; the bulb adds volume at
    every draft and moves the LCB forward."""
    import numpy as np

    import fairlines as fl
    from cad_fixtures import example_hull_surface

    rows = {}
    for flag in ([], ["--bare"]):
        out = tmp_path / f"c{len(flag)}.csv"
        assert main(["hydrostatics", DESCRIPTION, *flag, "-o", str(out), "--drafts", "6,11"]) == 0
        rows[bool(flag)] = np.genfromtxt(out, delimiter=",", names=True)
    assert "bulbous bow and blend composed" in capsys.readouterr().out
    bare = fl.hydrostatics(example_hull_surface(), 11.0, length=244.8, breadth=32.25, midship_x=122.4)
    assert rows[True]["volume_m3"][1] == pytest.approx(bare.volume, rel=1e-9)  # the CSV's 10 digits
    assert np.all(rows[False]["volume_m3"] > rows[True]["volume_m3"])
    assert np.all(rows[False]["LCB_m"] > rows[True]["LCB_m"])


def test_a_bulbed_design_prints_and_draws_the_ship_with_its_bulb(tmp_path, capsys):
    """fairlines design prints the ship's figures with its bulb (Cb as asked, the bare hull's
    volume beside them); its lines take the composed ship unless --bare asks for the bare hull."""
    pytest.importorskip("matplotlib")
    design = tmp_path / "bulbed.json"
    assert main(["design", "--lpp", "120", "--breadth", "20", "--draft", "7", "--depth", "10", "--cb", "0.7",
                 "--lcb", "61", "--bulb", "-o", str(design)]) == 0
    out = capsys.readouterr().out
    assert "Cb 0.7000" in out and "with the bulb (bare hull" in out
    assert main(["lines", str(design), "-o", str(tmp_path / "l.svg")]) == 0
    assert "bulbous bow and blend composed" in capsys.readouterr().out
    assert main(["lines", str(design), "--bare", "-o", str(tmp_path / "b.svg")]) == 0
    assert "composed" not in capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["lines", str(design), "--bare", "--compose", "-o", str(tmp_path / "x.svg")])
    assert "argument --compose: not allowed with argument --bare" in capsys.readouterr().err
