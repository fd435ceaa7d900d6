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


# ---- a composed hull (bare hull, bulb and blend: fairlines.hydrostatics_composed) ----------
#: Trims (m by the stern) at which a composed hull's measures are checked; 8 m inclines the
#: waterplane 1.9 deg on the example's Lpp, so a wrong sign of the rotation moves its volume by
#: about 2 % and its LCB by 0.2 m.
TRIMS = (0.0, 8.0, -3.0)


@pytest.mark.parametrize("trim", TRIMS)
def test_a_composed_hulls_waterplane_is_the_surfaces(trim):
    """Without a bulb the composed hull's waterplane, cut from its patches by the inclined plane,
    is what the engine's quadrature on the surface gives (true area and moments in the plane,
    LCF the x of F)."""
    s = example_hull_surface()
    from fairlines.hydrostatics_composed import composed_waterplane
    h = composed_waterplane(fl.compose([s]), P["draft"], lpp=P["lpp"], trim=trim)
    q = fl.hydrostatics(s, P["draft"], length=P["lpp"], breadth=P["beam"], trim=trim, trim_length=P["lpp"])
    for key in ("waterplane_area", "inertia_t", "inertia_l"):
        assert h[key] == pytest.approx(getattr(q, key), rel=3e-5), key
    assert h["lcf"] == pytest.approx(q.lcf, abs=1e-5 * P["lpp"])


@pytest.mark.parametrize("trim", TRIMS)
def test_the_mesh_below_a_trimmed_waterplane_is_the_surfaces(trim):
    """A fine mesh of the bare hull, measured below the inclined waterplane in its rotated frame
    and brought back, holds the engine's trimmed volume, LCB and VCB (the mesh's chords cost
    about 2e-4 of the volume at this resolution)."""
    from fairlines.hydrostatics_composed import mesh_below
    s = example_hull_surface()
    m = mesh_below(fl.compose([s], hull_u=192, hull_v=80), P["draft"], lpp=P["lpp"], trim=trim)
    q = fl.hydrostatics(s, P["draft"], length=P["lpp"], breadth=P["beam"], trim=trim, trim_length=P["lpp"])
    assert m["volume"] == pytest.approx(q.volume, rel=5e-4)
    assert m["lcb"] == pytest.approx(q.lcb, abs=5e-5 * P["lpp"])
    assert m["vcb"] == pytest.approx(q.vcb, abs=5e-4 * P["draft"])


def test_a_bulbed_ships_curves_hold_its_bulb():
    """The example ship's curves of form composed: at every draft at least the bare hull's volume,
    and at T the composed mesh's own figures (a different integral: the whole mesh, not the
    surface plus the bulb's share) within the mesh's chords (2.6e-3 of the volume at the
    default resolution); the waterplane at T is the bare hull's (the bulb lies under it)."""
    from cad_fixtures import example_hull
    hull = example_hull()
    composed = hull.composed_hull()
    drafts = [4.0, P["draft"], 15.0]
    cof = curves_of_form(composed, drafts, lpp=P["lpp"], beam=P["beam"], depth=P["depth"], design_draft=P["draft"])
    bare = curves_of_form(hull.bare_hull_surface(), drafts, lpp=P["lpp"], beam=P["beam"])
    assert all(c > b for c, b in zip(cof.column("volume"), bare.column("volume")))
    mesh = fl.mesh_hydrostatics(composed.mesh, P["draft"])
    assert cof.rows[1]["volume"] == pytest.approx(mesh.volume, rel=3e-3)
    assert cof.rows[1]["lcb"] == pytest.approx(mesh.lcb, abs=1e-3 * P["lpp"])
    assert cof.rows[1]["waterplane_area"] == pytest.approx(bare.rows[1]["waterplane_area"], rel=1e-5)
    assert cof.design["volume"] == cof.rows[1]["volume"]
