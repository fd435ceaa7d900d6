"""Curves of form: rows equal fl.hydrostatics, the box barge's KMt, refused drafts, outputs."""

import numpy as np
import pytest

import fairlines as fl
from fairlines.curves_of_form import COLUMNS, curves_of_form
from cad_fixtures import EXAMPLE_PARTICULARS as P, box_barge_surface, example_hull_surface


def test_design_draft_row_equals_hydrostatics():
    s = example_hull_surface()
    cof = curves_of_form(s, [5.0, P["draft"], 15.0], lpp=P["lpp"], beam=P["beam"], depth=P["depth"],
                         design_draft=P["draft"])
    row = cof.rows[1]
    h = fl.hydrostatics(s, P["draft"], length=P["lpp"], breadth=P["beam"], midship_x=P["lpp"] / 2).as_dict()
    for key, _ in COLUMNS:
        assert row[key] == h[key], key
    assert cof.design["volume"] == h["volume"]


def test_box_barge_kmt_over_drafts():
    Lb, Bb, Db = 60.0, 12.0, 8.0
    drafts = np.linspace(0.5, Db, 16)
    cof = curves_of_form(box_barge_surface(Lb, Bb, Db), drafts, lpp=Lb, beam=Bb, depth=Db)
    np.testing.assert_allclose(cof.column("kmt"), Bb**2 / (12 * drafts) + drafts / 2, rtol=1e-13)
    np.testing.assert_allclose(cof.column("cb"), 1.0, rtol=1e-13)


def test_trims_give_one_row_each():
    cof = curves_of_form(box_barge_surface(60, 12, 8), [2.0, 4.0], lpp=60, beam=12, depth=8, trims=(0.0, 0.5))
    assert [(r["trim"], r["draft"]) for r in cof.rows] == [(0.0, 2.0), (0.0, 4.0), (0.5, 2.0), (0.5, 4.0)]
    assert cof.column("lcb", 0.5)[0] < cof.column("lcb", 0.0)[0]


def test_drafts_above_the_deck_are_refused():
    with pytest.raises(fl.InvalidInput, match="above the depth"):
        curves_of_form(box_barge_surface(60, 12, 8), [4.0, 9.0], lpp=60, beam=12, depth=8)
    with pytest.raises(fl.InvalidInput, match="highest point"):
        curves_of_form(box_barge_surface(60, 12, 8), [9.0], lpp=60, beam=12)


def test_trimmed_waterplane_above_the_deck_is_refused():
    # box barge L 60, D 8: trim 2 m by the stern raises the waterline at the AP 1 m above T
    barge = box_barge_surface(60, 12, 8)
    curves_of_form(barge, [7.5], lpp=60, beam=12, depth=8)
    curves_of_form(barge, [7.0], lpp=60, beam=12, depth=8, trims=(2.0,))
    with pytest.raises(fl.InvalidInput, match="above the deck"):
        curves_of_form(barge, [7.5], lpp=60, beam=12, depth=8, trims=(2.0,))
    with pytest.raises(fl.InvalidInput, match="fore end"):
        curves_of_form(barge, [7.5], lpp=60, beam=12, depth=8, trims=(-2.0,))


def test_csv_and_plots(tmp_path):
    pytest.importorskip("matplotlib")
    s = example_hull_surface()
    cof = curves_of_form(s, [4.0, 11.0], lpp=P["lpp"], beam=P["beam"], design_draft=11.0)
    cof.write_csv(tmp_path / "c.csv")
    table = np.genfromtxt(tmp_path / "c.csv", delimiter=",", names=True)
    assert table["draft_m"].tolist() == [4.0, 11.0]
    cof.plot(tmp_path / "c.png")
    cof.plot_sac(tmp_path / "s.png", lambda x: np.interp(x, *cof.sac))
    assert (tmp_path / "s.png").stat().st_size > 0
