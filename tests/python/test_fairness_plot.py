"""Curvature combs: spine geometry against circles and lines, the plot of an analytic hull."""

import pathlib

import numpy as np
import pytest

import fairlines as fl
from cad_fixtures import wigley_surface
from fairlines.fairness_plot import comb_spines, write_fairness_plot

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "container_ship.json"


def test_comb_spines_of_a_circle_point_away_from_its_centre():
    r, scale = 5.0, 2.0
    t = np.linspace(0.0, np.pi, 181)
    pts = np.column_stack([r * np.cos(t), r * np.sin(t)])
    base, tip = comb_spines(pts, np.full(len(t), 1.0 / r), scale)
    assert np.allclose(base, pts)
    assert np.allclose(np.linalg.norm(tip, axis=1), r + scale / r, atol=1e-9)


def test_comb_spines_of_a_straight_line_have_no_length():
    pts = np.column_stack([np.linspace(0, 10, 50), np.linspace(0, 3, 50)])
    base, tip = comb_spines(pts, np.zeros(50), 100.0)
    assert np.allclose(base, tip)


def test_the_wigley_hull_has_no_sign_change_in_any_cut(tmp_path):
    """Every waterline, buttock and frame of a Wigley hull (to its draft) is convex: a parabola,
    or the lower arc of a level set of a product of concave functions. No inflection marked."""
    out = tmp_path / "wigley.png"
    judged = write_fairness_plot(wigley_surface(depth=6.25), out, title="Wigley")
    assert out.stat().st_size > 10_000
    assert {k: sum(j["sign_changes"] for j in v) for k, v in judged.items()} == {"waterline": 0, "buttock": 0, "frame": 0}
    assert all(len(v) >= 5 for v in judged.values())


def test_the_fairness_plot_refuses_an_unknown_format(tmp_path):
    with pytest.raises(fl.InvalidInput, match="expected a .png, .svg or .pdf"):
        write_fairness_plot(wigley_surface(), tmp_path / "combs.bmp")


def test_command_line_draws_the_combs_and_lists_the_sign_changes(tmp_path, capsys):
    import pathlib

    from fairlines.cli import main

    example = pathlib.Path(__file__).resolve().parents[2] / "examples" / "container_ship.json"
    out = tmp_path / "combs.svg"
    assert main(["fairness", str(example), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert out.stat().st_size > 10_000
    assert "waterline z =" in text and "total: waterlines" in text


def test_command_line_refuses_a_missing_description(tmp_path, capsys):
    from fairlines.cli import main

    assert main(["fairness", str(tmp_path / "none.json"), "-o", str(tmp_path / "c.png")]) == 2
    assert "none.json" in capsys.readouterr().err


def test_a_tight_round_end_does_not_shrink_the_other_combs():
    """The example's lowest plotted waterline starts at the keel with a round end of curvature
    0.46 1/m, 15 times its view's 99th percentile: its spines run out of the frame, and the view
    stays within VIEW_COMBS comb lengths of the cuts (its y axis reached 175 m for a half-breadth
    of 16 m)."""
    from fairlines.fairness_plot import COMB_LENGTH, VIEW_COMBS, fairness_figure

    surface = fl.Hull.from_json(EXAMPLE.read_text()).bare_hull_surface()
    fig, _ = fairness_figure(surface)
    ax = next(a for a in fig.axes if a.get_title().startswith("half-breadth plan"))
    margin = 1.5 * VIEW_COMBS * COMB_LENGTH * 260.0  # 260 m: the waterlines' extent in x; 1.5: the view's pad
    assert ax.get_ylim()[1] < 16.125 + margin
    assert ax.get_ylim()[0] > -margin
