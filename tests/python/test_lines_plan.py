"""Lines plan: its body plan sections against fl.plane_cut, its DXF against the hull, its views
and conventions on the whole example ship (bare and composed) and a Wigley hull."""

import numpy as np
import pytest

import fairlines as fl
from fairlines.lines_plan import STATIONS_PER_LPP, closeup, lines_plan
from cad_fixtures import EXAMPLE_PARTICULARS as P, example_composed_hull, example_hull_surface, wigley_surface

#: Drawn polylines vs plane_cut's 401 samples: both are exact points joined by chords.
CHORD_TOLERANCE = 1e-3


def _dist_to_polyline(points, poly):
    a, b = poly[:-1], poly[1:]
    ab = b - a
    w = np.clip(np.einsum("pkj,kj->pk", points[:, None, :] - a[None], ab) / np.einsum("kj,kj->k", ab, ab), 0, 1)
    return np.min(np.linalg.norm(points[:, None, :] - (a[None] + w[..., None] * ab[None]), axis=2), axis=1)


@pytest.fixture(scope="module")
def ship_plan():
    return lines_plan(example_hull_surface(), **P, name="Panamax container ship")


@pytest.fixture(scope="module")
def composed_plan():
    return lines_plan(example_composed_hull(), **P)


def _drawn(plan, layer, name):
    return [p for p in plan.primitives if getattr(p, "layer", None) == layer and getattr(p, "name", "") == name]


def test_body_plan_sections_equal_plane_cut_frames(ship_plan):
    s = example_hull_surface()
    checked = 0
    for label, x, _ in ship_plan.stations:
        if not 0.0 < x < P["lpp"] or x == P["lpp"] / 2:
            continue
        side = 1.0 if x > P["lpp"] / 2 else -1.0  # aft stations left of the centre line, fore right
        cut = fl.plane_cut(s, 0, x).points[:, 1:]
        (drawn,) = _drawn(ship_plan, "STATIONS", f"ST {label}")
        yz = ship_plan.to_model("body", drawn.points)
        assert np.all(side * yz[:, 0] >= -1e-9)
        yz[:, 0] *= side
        assert _dist_to_polyline(cut, yz).max() < CHORD_TOLERANCE
        assert _dist_to_polyline(yz, cut).max() < CHORD_TOLERANCE
        checked += 1
    assert checked >= 20


def test_whole_ship_fills_the_sheet_width_and_the_body_plan_is_larger(ship_plan):
    lo = min(o[:, 0].min() for o in ship_plan.outline)
    hi = max(o[:, 0].max() for o in ship_plan.outline)
    drawn_mm = (hi - lo) * 1000.0 / ship_plan.scale
    assert drawn_mm > 0.8 * ship_plan.sheet_mm[0]
    assert ship_plan.body_scale < ship_plan.scale
    assert ship_plan.factors["body"] == pytest.approx(ship_plan.scale / ship_plan.body_scale)


def test_title_block_coefficients_from_the_hydrostatics(ship_plan, composed_plan):
    ref = fl.hydrostatics(example_hull_surface(), P["draft"], length=P["lpp"], breadth=P["beam"],
                          midship_x=P["lpp"] / 2)
    h = ship_plan.hydrostatics
    for key in ("cb", "cp", "cm", "wetted_surface"):
        assert h[key] == getattr(ref, key), key
    c = composed_plan.hydrostatics  # the bulb adds volume and wetted surface, not midship area
    assert c["cb"] == pytest.approx(c["volume"] / (P["lpp"] * P["beam"] * P["draft"]), rel=1e-14)
    assert c["cm"] == pytest.approx(ref.cm, rel=1e-12) and c["cp"] == pytest.approx(c["cb"] / c["cm"], rel=1e-12)
    assert c["volume"] > ref.volume and c["wetted_surface"] > ref.wetted_surface


def test_dxf_passes_audit_and_its_dwl_lies_on_the_design_waterline(ship_plan, tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    path = tmp_path / "lines.dxf"
    ship_plan.save(path)
    doc = ezdxf.readfile(str(path))
    assert len(doc.audit().errors) == 0
    splines = doc.modelspace().query('SPLINE[layer=="DWL"]')
    assert len(splines) >= 1
    s = example_hull_surface()
    for sp in splines:
        pts = np.array([[p.x, p.y] for p in sp.construction_tool().points(np.linspace(0, sp.construction_tool().max_t, 60))])
        xy = ship_plan.to_model("plan", pts)
        for x, y in xy:
            q = np.array([x, y, P["draft"]])
            assert np.linalg.norm(s.closest_point(q)[2] - q) < 1e-3


def test_composed_hull_plan_draws_the_bulb_beyond_the_fp(composed_plan):
    c = example_composed_hull()
    nose = c.mesh.vertices[:, 0].max()
    labels = [n for n, x, cuts in composed_plan.stations if x > P["lpp"] and cuts]
    assert labels, "no station through the bulb ahead of the FP"
    outline_x = max(o[:, 0].max() for o in composed_plan.outline)
    assert outline_x == pytest.approx(nose, abs=1e-6)
    assert any(np.abs(o[:, 1]).max() < 1e-9 and o[:, 0].max() > P["lpp"] for o in composed_plan.outline)


def test_whole_ship_body_plan_aft_left_fore_right():
    plan = lines_plan(wigley_surface(), lpp=100.0, beam=10.0, draft=6.25, depth=10.0)
    nums = [float(n) for n, _, _ in plan.stations]
    assert nums[0] == 0.0 and nums[-1] == STATIONS_PER_LPP
    xb = plan.offsets["body"][0]
    for n, _, _ in plan.stations:
        for prim in _drawn(plan, "STATIONS", f"ST {n}"):
            side = np.sign(prim.points[:, 0] - xb)
            if float(n) < STATIONS_PER_LPP / 2:
                assert np.all(side <= 0)
            elif float(n) > STATIONS_PER_LPP / 2:
                assert np.all(side >= 0)


def test_bow_closeup_has_quarter_stations_and_a_larger_scale(ship_plan):
    plan = closeup(example_hull_surface(), "bow", **P)
    assert plan.scale < ship_plan.scale
    assert any(float(n) % 1 == 0.25 for n, _, _ in plan.stations)


def test_svg_pdf_written(ship_plan, tmp_path):
    pytest.importorskip("matplotlib")
    for suffix, head in ((".svg", b"<?xml"), (".pdf", b"%PDF")):
        ship_plan.save(tmp_path / f"l{suffix}")
        assert (tmp_path / f"l{suffix}").read_bytes()[:5].startswith(head)


def test_bad_input_is_named():
    with pytest.raises(fl.InvalidInput, match="draft 20.0 m is above depth 19.0 m"):
        lines_plan(example_hull_surface(), lpp=244.8, beam=32.25, draft=20.0, depth=19.0)
    with pytest.raises(fl.InvalidInput, match="suffix"):
        lines_plan(example_hull_surface(), **P).save("x.doc")


def test_waterplane_from_the_dwl_section_agrees_with_quadrature(ship_plan):
    from fairlines.lines_plan import waterplane_from_sections
    dwl = [cuts for label, _, cuts in ship_plan.waterlines if label == "DWL"][0]
    w = waterplane_from_sections(dwl)
    h = fl.hydrostatics(example_hull_surface(), P["draft"])
    for key in ("waterplane_area", "lcf", "inertia_t", "inertia_l"):
        assert w[key] == pytest.approx(getattr(h, key), rel=1e-5), key


def test_composed_title_block_has_waterplane_and_metacentres(composed_plan):
    h = composed_plan.hydrostatics
    assert "quadrature" in h["source"] and "mesh" in h["source"] and h["kmt"] == pytest.approx(h["vcb"] + h["inertia_t"] / h["volume"])


def test_example_writes_the_drawings(tmp_path, monkeypatch, capsys):
    import runpy
    import sys
    from cad_fixtures import ROOT
    pytest.importorskip("matplotlib")
    monkeypatch.setattr(sys, "argv", ["lines_plan.py", "--out", str(tmp_path), "--docs", str(tmp_path)])
    runpy.run_path(str(ROOT / "examples" / "lines_plan.py"), run_name="__main__")
    text = capsys.readouterr().out
    assert "lines plan at 1:" in text and "KMt" in text
    for name in ("lines_plan.png", "lines_plan.pdf", "lines_plan.dxf", "lines_plan_bow.png", "lines_plan_stern.png",
                 "curves_of_form.csv", "sac.png"):
        assert (tmp_path / "lines" / name).stat().st_size > 1000


def _drawn_label_boxes(plan, layers):
    """(text, box in paper pixels) of the labels on `layers` as matplotlib draws them."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from fairlines.lines_render import figure
    from fairlines.lines_sheet import Text

    fig = figure(plan)
    renderer = FigureCanvasAgg(fig).get_renderer()
    texts = [p for p in plan.primitives if isinstance(p, Text)]
    drawn = fig.axes[0].texts
    assert [t.text for t in texts] == [d.get_text() for d in drawn]
    return [(t.text, d.get_window_extent(renderer)) for t, d in zip(texts, drawn) if t.layer in layers]


def _kcs_plan():
    from import_fixtures import read

    desc = fl.import_design(read("kcs"))
    pr = desc["principal"]
    return lines_plan(fl.Hull.from_json(desc).composed_hull(), lpp=pr["Lpp"], beam=pr["B"], draft=pr["T"], depth=pr["D"])


@pytest.mark.parametrize("which", ["bare", "composed", "kcs"])
def test_waterline_and_station_numbers_stand_clear_of_each_other(which, ship_plan, composed_plan):
    """Every numbered waterline has its number in the half-breadth plan, and no two waterline or
    station numbers overlap as matplotlib draws them (its text extents, descent included). KCS's
    waterlines crowd in one column where they are furthest apart: drawn there at one x (before),
    its 8 and 10 overlapped and its numbers read as a smudge at 60 dpi."""
    plan = {"bare": ship_plan, "composed": composed_plan}.get(which) or _kcs_plan()
    boxes = _drawn_label_boxes(plan, ("WATERLINES", "STATIONS"))
    numbered = {label for label, _, cuts in plan.waterlines if label != "DWL" and cuts}
    assert numbered <= {text for text, _ in boxes}
    for i, (ta, a) in enumerate(boxes):
        for tb, b in boxes[i + 1:]:
            assert not a.overlaps(b), (ta, tb, a, b)


def test_a_station_through_a_point_of_the_hull_takes_no_number(composed_plan):
    """Station 20.5 of the composed example cuts the bulb at its nose, a point (under 1 cm across):
    it was numbered at the centre line, among the aft stations' numbers."""
    from fairlines.lines_sheet import Text

    (cuts,) = [c for label, _, c in composed_plan.stations if label == "20.5"]
    assert np.ptp(np.concatenate(cuts)[:, 1:], axis=0).max() < 0.01
    numbers = [p.text for p in composed_plan.primitives if isinstance(p, Text) and p.layer == "STATIONS"]
    assert "20.5" not in numbers and "20" in numbers


def test_title_block_figures_of_a_model_keep_four_significant_digits():
    """A 5 m Wigley model: its volume (4/9 L B T = 0.3472 m3) reads to four significant digits in
    the title block, as do its displacement and MCT1cm (0.3 m3 and 0.0 t m/cm before)."""
    lpp, beam, draft = 5.0, 0.5, 0.3125
    plan = lines_plan(wigley_surface(lpp, beam, draft, 0.5), lpp=lpp, beam=beam, draft=draft, depth=0.5)
    texts = [p.text for p in plan.primitives if getattr(p, "layer", None) == "TITLE" and hasattr(p, "text")]
    value = {key: texts[texts.index(key) + 1] for key in ("Vol", "Displ.", "MCT1cm")}
    assert value["Vol"] == "0.3472 m3"
    assert float(value["Vol"].split()[0]) == pytest.approx(4.0 / 9.0 * lpp * beam * draft, rel=2e-4)
    for key, name in (("Displ.", "displacement"), ("MCT1cm", "mct1cm")):
        shown = value[key].split()[0]
        assert len(shown.replace(".", "").lstrip("0")) >= 4, value[key]
        assert float(shown) == pytest.approx(plan.hydrostatics[name], rel=1e-3)
