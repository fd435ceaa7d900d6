"""Pre-processor: readers, hydrostatics of the input and of the rebuilt surface,
form parameters, poor data. Truth comes from the Wigley hull's exact coefficients, the
published particulars of the reference hulls (data README), and independent computation paths
(Simpson vs. trapezoid, NURBS quadrature vs. a triangle mesh)."""

import os
import pathlib

import numpy as np
import pytest

from fairlines import offsets, preprocess as pp
from import_fixtures import wigley_table_csv

# The reference hulls live next to the repository (../shared/data; see its README.md).
DATA = pathlib.Path(os.environ.get(
    "FAIRLINES_DATA", pathlib.Path(__file__).resolve().parents[3] / "shared" / "data"))
SERIES60 = DATA / "series60_cb080_offsets.csv"

# Series 60 parent Cb 0.80 proportions (Todd 1963): L/B 6.5, B/T 2.5, Lpp 400 ft. The table's
# bilge confirms B/T: a circular bilge tangent to the tan-line offset 0.85 (B/2) meets the
# 0.075 T waterline at 0.970 (B/2) only for B/T = 2.5.
S60_LPP = 121.92
S60_B = S60_LPP / 6.5
S60_T = S60_B / 2.5

# Relative accuracy of a skinned surface's coefficients on an analytic hull of 9 waterlines.
SKIN_TOL = 1e-3
# Relative agreement asked of the NURBS quadrature and the fine triangle mesh of the same surface.
MESH_AGREEMENT = 5e-4


def wigley_csv(path, L=100.0, B=10.0, T=6.25, n_st=21, n_wl=9):
    """Absolute offsets table of the Wigley hull y = B/2 (1 - (2 xi/L)^2)(1 - (zeta/T)^2)."""
    x = np.linspace(0, L, n_st)
    z = np.linspace(0, T, n_wl)
    xi = x - L / 2
    hb = B / 2 * (1 - (2 * xi / L) ** 2)[:, None] * (1 - ((T - z) / T) ** 2)[None, :]
    lines = ["x," + ",".join(f"{v:.6f}" for v in z)]
    lines += [f"{xv:.6f}," + ",".join(f"{v:.9f}" for v in row) for xv, row in zip(x, hb)]
    path.write_text("\n".join(lines) + "\n")
    return L, B, T


@pytest.fixture(scope="module")
def wigley(tmp_path_factory):
    p = tmp_path_factory.mktemp("wigley") / "wigley.csv"
    L, B, T = wigley_csv(p)
    return offsets.read_offsets_csv(p, L, B, T)


@pytest.fixture(scope="module")
def series60():
    data = offsets.read_offsets_csv(SERIES60, S60_LPP, S60_B, S60_T)
    rb = pp.rebuild(data)
    return data, rb


@pytest.fixture(scope="module")
def dtmb():
    data = offsets.read_dtmb5415(DATA / "dtmb5415")
    return data, pp.rebuild(data)


@pytest.fixture(scope="module")
def kcs():
    data = offsets.read_kcs(DATA / "kcs")
    return data, pp.rebuild(data)


# ---- integration rules ----------------------------------------------------------------------

def test_simpson_is_exact_for_quadratics_on_irregular_spacing_and_cubics_on_even():
    x = np.array([0.0, 0.3, 1.0, 1.2, 2.5, 2.6, 4.0])
    f = 5 * x ** 2 - x + 3
    assert pp.simpson(f, x) == pytest.approx(5 * 4.0 ** 3 / 3 - 8.0 + 12.0, rel=1e-12)
    assert pp.simpson(f[:-1], x[:-1]) == pytest.approx(5 * 2.6 ** 3 / 3 - 2.6 ** 2 / 2 + 3 * 2.6, rel=1e-12)
    xe = np.linspace(0, 2, 9)
    assert pp.simpson(xe ** 3, xe) == pytest.approx(4.0, rel=1e-12)


# ---- Wigley: exact coefficients ---------------------------------------------------------------

def test_wigley_offsets_give_exact_coefficients(wigley):
    h = pp.offsets_hydrostatics(wigley)
    # Simpson is exact for the Wigley hull's quadratic offsets in both directions.
    assert h.cb == pytest.approx(4 / 9, rel=1e-9)
    for k in ("cm", "cwp", "cp"):
        assert getattr(h, k) == pytest.approx(2 / 3, rel=1e-9)
    assert h.lcb_pct == pytest.approx(0, abs=1e-9)
    assert h.vcb == pytest.approx(5 * 6.25 / 8, rel=1e-9)  # KB = 5T/8


def test_wigley_rebuilt_surface_matches_exact_and_mesh(wigley):
    rb = pp.rebuild(wigley)
    hs = pp.surface_hydrostatics(rb.surfaces, wigley.draft, wigley.lpp, wigley.beam)
    hm = pp.mesh_hydrostatics(pp.surface_meshes(rb.surfaces), wigley.draft, wigley.lpp, wigley.beam)
    # The skinned surface reproduces the quadratic hull to the accuracy of its shape-preserving
    # section curves (third order in the waterline spacing: 0.05 % on 9 waterlines).
    assert hs.cb == pytest.approx(4 / 9, rel=SKIN_TOL)
    assert hs.cm == pytest.approx(2 / 3, rel=SKIN_TOL)
    assert hs.cwp == pytest.approx(2 / 3, rel=SKIN_TOL)
    for k in ("volume", "vcb", "waterplane_area", "wetted_surface"):
        assert getattr(hm, k) == pytest.approx(getattr(hs, k), rel=MESH_AGREEMENT)
    assert rb.deviation["max"] < 1e-4 * wigley.beam


def test_triangle_mesh_of_a_box_is_exact():
    """An independent check of the mesh path: a half box (L x B/2 x D) clipped at T."""
    L, B, D, T = 10.0, 4.0, 3.0, 2.0
    ys, zs = np.linspace(0, B / 2, 5), np.linspace(0, D, 7)
    # One structured grid around the section: bottom (y out at z = 0), then side up.
    sec = np.concatenate([np.column_stack([ys, np.zeros_like(ys)]),
                          np.column_stack([np.full(len(zs) - 1, B / 2), zs[1:]])])
    grid = np.array([np.column_stack([np.full(len(sec), x), sec]) for x in np.linspace(0, L, 6)])
    h = pp.mesh_hydrostatics([pp.grid_mesh(grid)], T, L, B)
    assert h.volume == pytest.approx(L * B * T, rel=1e-12)
    assert h.vcb == pytest.approx(T / 2, rel=1e-12)
    assert h.lcb == pytest.approx(L / 2, rel=1e-12)
    assert h.waterplane_area == pytest.approx(L * B, rel=1e-12)
    assert h.midship_area == pytest.approx(B * T, rel=1e-12)
    assert h.wetted_surface == pytest.approx(L * B + 2 * L * T, rel=1e-12)


# ---- Series 60 Cb 0.80 ---------------------------------------------------------------------

# Published coefficients are quoted to 3 decimals; the issue asks for 0.5 %.
COEFF_TOL = 0.005
LCB_TOL_PCT = 0.2


@pytest.mark.parametrize("quoted, lcb_pct", [("LCB 2.5 % Lpp forward", 2.5), ("LCB .5 % Lpp aft", -0.5),
                                               ("LCB ..5 % Lpp forward", None), ("LCB 2.5. % Lpp forward", None)])
def test_a_malformed_figure_in_a_header_comment_is_not_read(quoted, lcb_pct):
    """A header comment is read for the coefficients it quotes; a figure that is not a number
    there ('..5', found by fuzz/fuzz_offsets_csv.py) is left unread, not a ValueError."""
    assert offsets._published_from_comments([f"# Cp 0.805, {quoted}"]).get("lcb_pct") == lcb_pct


def test_series60_reader_reads_header_and_converts(series60):
    data, _ = series60
    assert data.published == {"cp": 0.805, "cm": 0.994, "cwp": 0.864, "lcb_pct": 2.5}
    xs = [s.x for s in data.sections]
    assert xs[0] == 0.0 and xs[-1] == pytest.approx(S60_LPP)  # AP first, FP at Lpp
    mid = data.sections[int(np.argmin(np.abs(np.array(xs) - S60_LPP / 2)))]
    assert mid.points[0].tolist() == [0.0, 0.0]
    assert mid.points[:, 0].max() == pytest.approx(S60_B / 2)
    # The tan-line column is scaled by its max_half_beam 0.85: flat of bottom 0.85 B/2.
    assert mid.points[1] == pytest.approx([0.85 * S60_B / 2, 0.0])


def test_series60_input_coefficients_against_published(series60):
    data, _ = series60
    h = pp.offsets_hydrostatics(data)
    assert h.cp == pytest.approx(0.805, rel=COEFF_TOL)
    assert h.cm == pytest.approx(0.994, rel=COEFF_TOL)
    assert abs(h.lcb_pct - 2.5) <= LCB_TOL_PCT
    # The table's own area_fraction column is an independent record of the section areas.
    frac = np.array([e["area_fraction"] for e in data.offsets["extra"]])
    ok = np.array([c["station"] for c in h.area_fraction_check])
    assert ok.tolist() == ["AP"]  # its 0.100 contradicts its own zero offsets below 0.75 T
    keep = np.array([lab != "AP" for lab in data.offsets["labels"]])
    assert np.max(np.abs(h.section_areas[keep] / h.midship_area - frac[keep])) < pp.AREA_FRACTION_TOL


def test_series60_cwp_is_the_tables_own_waterline(series60):
    """The table's 1.00 waterline integrates to Cwp 0.871-0.874 between the perpendiculars, 1.1 %
    above the quoted 0.864; we check the Simpson value against the trapezoid rule on the same
    column (an independent path) and keep the gap to the quoted value visible."""
    data, _ = series60
    h = pp.offsets_hydrostatics(data)
    k = int(np.flatnonzero(np.isclose(data.offsets["z"], S60_T))[0])
    x, y = data.offsets["x"], data.offsets["half_breadths"][:, k]
    trap = 2 * np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)) / (S60_LPP * S60_B)
    assert h.cwp == pytest.approx(trap, rel=COEFF_TOL)
    assert h.cwp / 0.864 - 1 == pytest.approx(0.011, abs=0.002)


def test_series60_rebuilt_surface(series60):
    data, rb = series60
    hs = pp.surface_hydrostatics(rb.surfaces, S60_T, S60_LPP, S60_B, roles=rb.roles)
    assert hs.cp == pytest.approx(0.805, rel=COEFF_TOL)
    assert hs.cm == pytest.approx(0.994, rel=COEFF_TOL)
    assert abs(hs.lcb_pct - 2.5) <= LCB_TOL_PCT
    assert rb.deviation["rms"] <= 0.001 * S60_B
    assert rb.deviation["n_points"] == sum(len(s.points) for s in data.sections)
    hm = pp.mesh_hydrostatics(pp.surface_meshes(rb.surfaces), S60_T, S60_LPP, S60_B)
    for k in ("volume", "lcb", "vcb", "waterplane_area", "wetted_surface"):
        assert getattr(hm, k) == pytest.approx(getattr(hs, k), rel=MESH_AGREEMENT)


def test_series60_form_parameters(series60):
    data, rb = series60
    fp = pp.form_parameters(rb.surfaces, data, roles=rb.roles)
    # Parallel middle body: the table's offsets are 1.000 at every waterline from station 6 to 11.
    assert fp["FOS"]["x_aft"] <= (20 - 11) / 20 * S60_LPP and fp["FOS"]["x_fwd"] >= (20 - 6) / 20 * S60_LPP
    assert fp["bow"]["kind"] == "none"
    sac = np.array(fp["SAC"]["area"])
    assert sac.max() == pytest.approx(0.994 * S60_B * S60_T, rel=COEFF_TOL)
    mid = fp["sections"][len(fp["sections"]) // 2]
    assert mid["fob_half_width"] == pytest.approx(0.85 * S60_B / 2, rel=0.02)
    assert mid["half_breadth_dwl"] == pytest.approx(S60_B / 2, rel=1e-3)
    # Flat bottom kept flat: the shape-preserving sections do not dip below the baseline.
    assert min(s["keel_z"] for s in fp["sections"]) > -pp.DOME_MIN_DEPTH * S60_T


# ---- DTMB 5415 ------------------------------------------------------------------------------

def test_dtmb5415_reader_frame(dtmb):
    data, _ = dtmb
    main, bow, transom = data.grids
    assert [g.role for g in data.grids] == ["hull", "bow (sonar dome)", "transom"]
    assert main.points[:, :, 0].min() == pytest.approx(-0.005, abs=0.01)  # AP at x = 0
    # The main grid ends where the bow grid begins (no overlap counted twice).
    assert main.points[-1, :, 0] == pytest.approx(bow.points[0, :, 0])
    # Stem at the waterline near the FP, x = Lpp.
    stem = bow.points[-1]
    assert np.interp(data.draft, stem[:, 2], stem[:, 0]) == pytest.approx(data.lpp, abs=0.01 * data.lpp)


def test_dtmb5415_volume_and_dome(dtmb):
    data, rb = dtmb
    hs = pp.surface_hydrostatics(rb.surfaces, data.draft, data.lpp, data.beam, roles=rb.roles)
    assert hs.volume == pytest.approx(0.554, rel=0.01)
    assert np.isfinite(hs.lcb_pct)
    hi = pp.input_hydrostatics(data)
    assert hi.volume == pytest.approx(0.554, rel=0.01)
    hm = pp.mesh_hydrostatics(pp.surface_meshes(rb.surfaces), data.draft, data.lpp, data.beam)
    for k in ("volume", "lcb", "vcb", "waterplane_area", "wetted_surface"):
        assert getattr(hm, k) == pytest.approx(getattr(hs, k), rel=MESH_AGREEMENT)
    fp = pp.form_parameters(rb.surfaces, data, roles=rb.roles)
    assert fp["bow"]["kind"] == "sonar dome"
    assert fp["bow"]["depth_below_baseline"] == pytest.approx(0.121, rel=0.05)


# ---- KCS ------------------------------------------------------------------------------------

def test_kcs_volume_wetted_surface_and_bulb(kcs):
    data, rb = kcs
    hs = pp.surface_hydrostatics(rb.surfaces, data.draft, data.lpp, data.beam, roles=rb.roles)
    assert hs.volume == pytest.approx(52030.0, rel=0.005)
    assert abs(hs.lcb_pct - (-1.48)) <= LCB_TOL_PCT
    # Published bare-hull S/L^2 0.178; the NMRI grid's wetted surface comes out 1.3 % above it.
    assert hs.wetted_surface / data.lpp ** 2 == pytest.approx(0.178, rel=0.02)
    hm = pp.mesh_hydrostatics(pp.surface_meshes(rb.surfaces), data.draft, data.lpp, data.beam)
    for k in ("volume", "lcb", "vcb", "waterplane_area", "wetted_surface"):
        assert getattr(hm, k) == pytest.approx(getattr(hs, k), rel=MESH_AGREEMENT)
    fp = pp.form_parameters(rb.surfaces, data, roles=rb.roles)
    assert fp["bow"]["kind"] == "bulb"
    assert 0.0 < fp["bow"]["c_lpr"] < 0.05 and 0.0 < fp["bow"]["c_abt"] < 0.2
    assert "bulb" in rb.roles


def test_kcs_frame_conversion(kcs):
    data, _ = kcs
    pts = data.all_points()
    assert pts[:, 2].min() == pytest.approx(0.0, abs=1e-3 * data.draft)  # keel on the baseline
    assert pts[:, 1].min() >= 0
    fore = data.grids[1].points
    assert fore[:, :, 0].max() > data.lpp  # stem above the waterline and bulb forward of the FP


# ---- readers and poor data --------------------------------------------------------------------

def _table(tmp_path, rows, header="x,0,1,2,3"):
    p = tmp_path / "t.csv"
    p.write_text(header + "\n" + "\n".join(rows) + "\n")
    return p


BOX_ROWS = ["0,0.5,1,1,1", "5,1,2,2,2", "10,1,2,2,2", "15,1,2,2,2", "20,0.5,1,1,1"]


def test_unsorted_and_duplicate_stations(tmp_path):
    good = offsets.read_offsets_csv(_table(tmp_path, BOX_ROWS), 20, 4, 2)
    shuffled = [BOX_ROWS[k] for k in (3, 0, 4, 2, 1)] + [BOX_ROWS[2]]
    data = offsets.read_offsets_csv(_table(tmp_path, shuffled), 20, 4, 2)
    assert any("sorted" in n for n in data.notes) and any("merged" in n for n in data.notes)
    assert pp.offsets_hydrostatics(data).volume == pytest.approx(pp.offsets_hydrostatics(good).volume)
    with pytest.raises(ValueError, match=r"station '10' appears twice with different"):
        offsets.read_offsets_csv(_table(tmp_path, BOX_ROWS + ["10,1,2,2,1.9"]), 20, 4, 2)


def test_missing_and_bad_cells(tmp_path):
    rows = list(BOX_ROWS)
    rows[2] = "10,1,,2,2"
    data = offsets.read_offsets_csv(_table(tmp_path, rows), 20, 4, 2)
    assert any("station '10'" in n and "blank" in n for n in data.notes)
    assert len(data.sections[2].points) == len(data.sections[1].points) - 1
    rows[2] = "10,1,abc,2,2"
    with pytest.raises(ValueError, match=r"row 4, column '1' is 'abc'; expected a number"):
        offsets.read_offsets_csv(_table(tmp_path, rows), 20, 4, 2)
    rows[2] = "10,1,-2,2,2"
    with pytest.raises(ValueError, match=r"row 4, column '1' is -2.0; expected a half-breadth >= 0"):
        offsets.read_offsets_csv(_table(tmp_path, rows), 20, 4, 2)
    rows[2] = "10,,,,"
    with pytest.raises(ValueError, match=r"station '10' has no half-breadths"):
        offsets.read_offsets_csv(_table(tmp_path, rows), 20, 4, 2)
    with pytest.raises(ValueError, match=r"two waterline columns at z = 1"):
        offsets.read_offsets_csv(_table(tmp_path, BOX_ROWS, header="x,0,1,1,3"), 20, 4, 2)
    with pytest.raises(ValueError, match=r"stations run from x = 0 to 20 m but Lpp is 10 m"):
        offsets.read_offsets_csv(_table(tmp_path, BOX_ROWS), 10, 4, 2)
    (tmp_path / "bin.csv").write_bytes(b"\x00\xff\xfe")
    with pytest.raises(ValueError, match=r"bin.csv is not a text file"):
        offsets.read_offsets_csv(tmp_path / "bin.csv", 20, 4, 2)
    with pytest.raises(ValueError, match=r"draft is -2"):
        offsets.read_offsets_csv(_table(tmp_path, BOX_ROWS), 20, 4, -2)


def _sections_csv(tmp_path, sections):
    p = tmp_path / "s.csv"
    p.write_text("x,y,z\n" + "\n".join(f"{x},{y},{z}" for x, pts in sections for y, z in pts) + "\n")
    return p


def test_sections_reader_and_fold_back(tmp_path):
    sec = [(0, 0), (1.5, 0.2), (2, 1), (2, 2)]
    data = offsets.read_sections_csv(_sections_csv(tmp_path, [(10, sec), (0, sec), (5, sec)]), 10, 4, 1.5)
    assert [s.x for s in data.sections] == [0, 5, 10] and any("sorted" in n for n in data.notes)
    h = pp.input_hydrostatics(data)
    area = 2 * (0.5 * 1.5 * 0.2 + 0.5 * (1.5 + 2) * 0.8 + 2 * 0.5)  # trapezoids up to z = 1.5
    assert h.midship_area == pytest.approx(area)
    assert h.volume == pytest.approx(area * 10)
    folded = [(0, 0), (2, 0.5), (2, 1.5), (1, 0.2), (1, 2)]
    with pytest.raises(ValueError, match=r"station x=5 folds back: segment 1 crosses segment 3"):
        offsets.read_sections_csv(_sections_csv(tmp_path, [(0, sec), (5, folded), (10, sec)]), 10, 4, 1.5)
    with pytest.raises(ValueError, match=r"repeats point 2"):
        offsets.read_sections_csv(_sections_csv(tmp_path, [(0, sec), (5, [(0, 0), (1, 1), (1, 1), (2, 2)])]),
                                  10, 4, 1.5)


def test_knuckle_is_kept_sharp(tmp_path):
    """A hard-chine section: flat-ish bottom with deadrise, chine knuckle, vertical side."""
    chine = [(0, 0), (0.6, 0.1), (1.2, 0.2), (1.8, 0.3), (2.0, 0.9), (2.0, 1.5), (2.0, 2.1)]
    assert offsets.knuckles(np.array(chine, float)).tolist() == [3]
    data = offsets.read_sections_csv(_sections_csv(tmp_path, [(x, chine) for x in (0, 4, 8, 12, 16)]), 16, 4, 1.5)
    grid = pp.sections_grid(data)
    # The chine point itself is a grid line: no rounding of the knuckle.
    assert np.min(np.linalg.norm(grid[2, :, 1:] - np.array([1.8, 0.3]), axis=1)) < 1e-12
    rb = pp.rebuild(data)
    assert rb.deviation["max"] < 1e-3 * data.beam
    # A knuckle next to an end point does not displace the end point.
    early = np.array([(0, 0), (0.1, 0), (0.3, 0.8), (0.5, 1.6), (0.6, 2.4)], float)
    assert offsets.knuckles(early).tolist() == [1]
    res = pp.resample_section(early, 9)
    assert res[0].tolist() == [0.0, 0.0] and res[-1] == pytest.approx([0.6, 2.4])
    assert np.min(np.linalg.norm(res - early[1], axis=1)) < 1e-12


def test_tecplot_reader_crlf(tmp_path):
    p = tmp_path / "z.dat"
    pts = [(i * 0.1, j * 0.2, -0.01 * i) for j in range(3) for i in range(2)]
    p.write_bytes(("Variables = \"X\", \"Y\", \"Z\"\r\nZone i= 2 j= 3 f=point\r\n"
                   + "".join(f"{x} {y} {z}\r\n" for x, y, z in pts)).encode())
    (zone,) = offsets.read_tecplot(p)
    assert zone.shape == (2, 3, 3)
    assert zone[1, 2].tolist() == pytest.approx([0.1, 0.4, -0.01])
    p.write_bytes(b"Zone i= 2 j= 3 f=point\r\n0 0 0\r\n1 1 1\r\n")
    with pytest.raises(ValueError, match=r"zone 1 has 2 points; expected i\*j = 6"):
        offsets.read_tecplot(p)


def test_xyz_grid_reader_and_bad_shapes(tmp_path):
    for c, v in zip("xyz", (1.0, 2.0, 3.0)):
        np.savetxt(tmp_path / f"{c}.dat", np.full((3, 4), v))
    g = offsets.read_xyz_grid(tmp_path / "x.dat", tmp_path / "y.dat", tmp_path / "z.dat")
    assert g.points.shape == (3, 4, 3)
    np.savetxt(tmp_path / "z.dat", np.ones((3, 5)))
    with pytest.raises(ValueError, match=r"expected one shape"):
        offsets.read_xyz_grid(tmp_path / "x.dat", tmp_path / "y.dat", tmp_path / "z.dat")


def test_hull_data_round_trip(tmp_path, series60):
    data, _ = series60
    back = offsets.hull_data_from_dict(offsets.hull_data_to_dict(data))
    assert pp.offsets_hydrostatics(back).volume == pytest.approx(pp.offsets_hydrostatics(data).volume)
    with pytest.raises(ValueError, match=r"no 'lpp' entry"):
        offsets.hull_data_from_dict({"name": "x"})


def test_grid_deviation_projection_agrees_with_closest_point(kcs):
    """The vectorised Gauss-Newton foot points of the deviation report against the engine's
    closest_point on a sample of the least-squares faired KCS afterbody."""
    data, rb = kcs
    s, g = rb.surfaces[3], data.grids[3].points.reshape(-1, 3)
    assert rb.names[3] == "afterbody"
    sample = g[::97]
    direct = np.array([np.linalg.norm(s.closest_point(p)[2] - p) for p in sample])
    uv = np.array([s.closest_point(p)[:2] for p in sample])
    proj = np.linalg.norm(pp.project_points(s, sample, uv[:, 0] + 1e-3, uv[:, 1] - 1e-3) - sample, axis=1)
    assert proj == pytest.approx(direct, abs=1e-9 * data.lpp)
    # Least-squares fairing of the grids: a real but small deviation, reported with its place.
    assert 0 < rb.deviation["rms"] < 1e-3 * data.beam
    assert rb.deviation["max_at"]["block"] in rb.names


def test_series60_editable_description(series60):
    """The forebody as basic curves with form parameters (the editable forebody description)."""
    data, rb = series60
    fp = pp.form_parameters(rb.surfaces, data, roles=rb.roles)
    desc = pp.hull_description(fp, data)
    bc = desc["basic_curves"]
    assert set(bc) == {"sac", "dwl", "deck", "profile", "fos", "fob", "deck_angle", "bottom_angle"}
    assert desc["range"]["x_start"] == pytest.approx(S60_LPP / 2)
    # Midship values: the midship section area, the half beam, the flat bottom of 0.85 B/2.
    assert bc["sac"]["value"] == pytest.approx(0.994 * S60_B * S60_T, rel=COEFF_TOL)
    assert bc["dwl"]["value"] == pytest.approx(S60_B / 2)
    assert bc["fob"]["value"] == pytest.approx(0.85 * S60_B / 2, rel=0.02)
    assert bc["bottom_angle"]["value"] == pytest.approx(-90, abs=0.5)  # flat bottom
    assert bc["deck_angle"]["value"] == pytest.approx(0, abs=0.5)  # wall-sided midship
    # Forebody volume from the description against the surface cut at midships (independent).
    x_end = desc["range"]["x_end"]
    xs = np.linspace(S60_LPP / 2, x_end, 81)
    areas = [2 * sum(pp._polyline_area(p, S60_T) for p in pp.section_at(rb.surfaces, x)) for x in xs]
    assert bc["sac"]["volume"] == pytest.approx(pp.simpson(np.array(areas), xs), rel=2e-3)
    for name, c in bc.items():
        xs_pts = [p[0] for p in c["points"]]
        assert all(c["flat_to"] < x < c.get("x_end", x_end) for x in xs_pts), name


def test_blank_cells_above_a_stations_highest_offset_are_filled_along_the_waterlines(tmp_path):
    """Midships (x 50 m) without its 7.5 and 9 m cells: they are read off their waterlines, the
    cubic through two stations either side, equal to the Wigley hull's wall side B/2 = 5 m (it
    ended the section at T, so the deck there fell to T); the end stations' blanks stay blank."""
    data = offsets.read_offsets_csv(wigley_table_csv(tmp_path, {"50000": ["7500", "9000"], "0": ["7500"],
                                                                     "5000": ["9000"]}),
                                    lpp=100.0, beam=10.0, draft=6.25)
    mid = next(s for s in data.sections if s.x == 50.0)
    assert np.allclose(mid.points[-2:], [[5.0, 7.5], [5.0, 9.0]], atol=1e-9)
    # next to the closed end: the quadratic through the end's 0 and two stations forward, 0.95 m
    assert np.allclose(next(s for s in data.sections if s.x == 5.0).points[-1], [0.95, 9.0], atol=1e-9)
    assert any("station '50000': 2 blank cell(s) at z = 7.5, 9 m below its lowest or above its highest offset filled" in n
               for n in data.notes)
    assert any("station '0'" in n and "left out" in n for n in data.notes)


def test_a_blank_keel_cell_is_read_off_the_keel_line_not_taken_for_a_flat_bottom(tmp_path):
    """x 40 m without its 0 m cell: the keel line reads 0 on both sides, so the section starts on
    the centre plane at the base as the Wigley hull's does (left out, its lowest offset 0.5 m
    above base read as a flat of bottom there, and the profile stepped up by 0.5 m)."""
    data = offsets.read_offsets_csv(wigley_table_csv(tmp_path, {"40000": ["0"]}), lpp=100.0, beam=10.0, draft=6.25)
    sec = next(s for s in data.sections if s.x == 40.0)
    assert sec.points[0].tolist() == [0.0, 0.0]
