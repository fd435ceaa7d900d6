"""One error contract for readers and entry points: InvalidInput (a ValueError) naming the file
and row/column or the JSON path, for malformed input and for magnitudes outside the physical
range (with a hint about units)."""

import math

import numpy as np
import pytest

import fairlines as fl
from fairlines import offsets

SERIES60 = "../shared/data/series60_cb080_offsets.csv"


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


@pytest.mark.parametrize(
    "text, fragments",
    [
        ("x,0,2,4+,6\n0,0,1,2,3\n50,4,6,7,8\n100,0,1,1.5,2\n", ["column header '4+'"]),
        ("x,0,2,4\n0,0,1,2\n50,4,abc,7\n100,0,1,1.5\n", ["row 3", "column '2'", "'abc'"]),
        ("x,0,2,4\n0,0,1,2\n50,4,6e3,7\n100,0,1,1.5\n", ["row 3", "metres?"]),
        ("x,0,2,4\n0,0,1,2\n50,4,-1,7\n100,0,1,1.5\n", ["row 3", ">= 0"]),
        ("x,0,2000,4\n0,0,1,2\n50,4,5,7\n100,0,1,1.5\n", ["'2000'", "heights in metres"]),
    ],
    ids=["header", "cell", "units", "negative", "waterline_units"],
)
def test_offsets_table_errors_name_file_row_and_column(tmp_path, text, fragments):
    path = write(tmp_path, "table.csv", text)
    with pytest.raises(fl.InvalidInput) as exc:
        offsets.read_offsets_csv(path, 100.0, 16.0, 6.0)
    assert str(path) in str(exc.value)
    for fragment in fragments:
        assert fragment in str(exc.value)


@pytest.mark.parametrize("lpp, fragment", [(121920.0, "millimetres"), (1e300, "millimetres"), (0.0, "positive"),
                                           (math.nan, "positive"), ("long", "positive")])
def test_reader_dimensions_out_of_range_are_refused(lpp, fragment):
    with pytest.raises(fl.InvalidInput, match=fragment):
        offsets.read_offsets_csv(SERIES60, lpp, 18.757, 7.503)


def test_reader_station_count_is_checked():
    with pytest.raises(fl.InvalidInput, match="n_stations"):
        offsets.read_offsets_csv(SERIES60, 121.92, 18.757, 7.503, n_stations=0)


@pytest.mark.parametrize(
    "text, fragments",
    [
        ("x,y,z\n0,,0\n0,,1\n", ["no stations"]),
        ("x,y,z\n1e300,1,0\n1e300,2,1\n", ["row 2", "is x in metres?"]),
        ("x,y,z\n0,1,0\n0,2,5000\n", ["row 3", "outside the ship"]),
        ("x,y,z\n0,1\n", ["row 2", "expected x,y,z"]),
    ],
    ids=["no_points", "station_overflow", "units", "short_row"],
)
def test_section_list_errors_name_file_and_row(tmp_path, text, fragments):
    path = write(tmp_path, "sections.csv", text)
    with pytest.raises(fl.InvalidInput) as exc:
        offsets.read_sections_csv(path, 100.0, 16.0, 6.0)
    for fragment in fragments:
        assert fragment in str(exc.value)


def test_grid_readers_raise_invalid_input(tmp_path):
    bad = write(tmp_path, "hull.dat", "Zone i=2 j=2 f=point\n0 0 0\n1 0 0\n0 1 zz\n")
    with pytest.raises(fl.InvalidInput, match="line 4"):
        offsets.read_tecplot_hull(bad, 100.0, 16.0, 6.0)
    x = write(tmp_path, "x.dat", "0 1\n0 1\n")
    y = write(tmp_path, "y.dat", "0 0\n1 1\n")
    z = write(tmp_path, "z.dat", "0 0 0\n")
    with pytest.raises(fl.InvalidInput, match="one shape"):
        offsets.read_xyz_grid(x, y, z)


@pytest.mark.parametrize("header", ["Zone i=2222222222222222222222 j=0 f=point", "Zone i=0 j=5 f=point",
                                    "Zone i=100000 j=100000 f=point"])
def test_tecplot_zone_sizes_are_checked_before_reading(tmp_path, header):
    """Found by the Tecplot fuzz harness: an empty zone of absurd width raised a bare ValueError."""
    bad = write(tmp_path, "hull.dat", header + "\n")
    with pytest.raises(fl.InvalidInput, match="line 1: zone i="):
        offsets.read_tecplot(bad)


def test_a_long_section_list_is_checked_quickly(tmp_path):
    # The fold-back check compares every pair of segments; it is vectorised and bounded.
    z = np.linspace(0, 6, offsets.MAX_SECTION_POINTS)
    rows = [f"{x},{2 + np.sin(zz)},{zz}" for x in (0.0, 50.0, 100.0) for zz in z]
    path = write(tmp_path, "long.csv", "x,y,z\n" + "\n".join(rows) + "\n")
    data = offsets.read_sections_csv(path, 100.0, 16.0, 6.0)
    assert len(data.sections) == 3
    too_long = write(tmp_path, "too_long.csv", "x,y,z\n" + "\n".join(f"0,1,{k * 1e-3}" for k in range(offsets.MAX_SECTION_POINTS + 1)))
    with pytest.raises(fl.InvalidInput, match=str(offsets.MAX_SECTION_POINTS)):
        offsets.read_sections_csv(too_long, 100.0, 16.0, 6.0)


# ---- hydrostatics --------------------------------------------------------------------------

def wigley_patch(L=100.0, B=10.0, T=6.25):
    """Half Wigley hull y = (B/2)(1 - (2x/L - 1)^2)(1 - (1 - z/T)^2) from the keel up to z = T,
    exactly: a biquadratic Bezier patch (x = L u, z = T v)."""
    f, g = (0.0, 2.0, 0.0), (0.0, 1.0, 1.0)
    net = np.array([[[L * i / 2, B / 2 * f[i] * g[j], T * j / 2] for j in range(3)] for i in range(3)])
    k = [0, 0, 0, 1, 1, 1]
    return fl.NurbsSurface(2, 2, k, k, net)


def test_hydrostatics_refuses_a_draft_above_the_hull():
    # The hull ends at z = 6.25 m: no waterplane exists above it.
    with pytest.raises(fl.InvalidInput, match="draft"):
        fl.hydrostatics(wigley_patch(), 1.5 * 6.25)
