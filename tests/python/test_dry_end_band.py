"""The SAC where the keel rises out of the water aft (fairlines.hull BAND_FREE_DRY_DEPTH): the
stations there ask no less fullness than the section family holds, and the buttocks crossing T
over them have no hollow there, judged on the cut buttocks themselves."""

import numpy as np
import pytest

import fairlines as fl
from fairlines import _native
from fairlines.fairness import judge_cut

#: Dry-transom ships of bench_hull's design space (its sample's hulls 65, 35 and 9, rounded) whose
#: buttock at 0.3 B/2 took a hollow lobe of 0.28, 0.23 and 0.63 deg where it crossed T, within 1 %
#: Lpp of the AP, while the SAC asked the last station before the fade for less than the V.
SHIPS = {
    "coaster 96 m": dict(lpp=96.078, breadth=13.738, draft=5.24, depth=8.384, cb=0.748, lcb=46.366),
    "bulk 192 m": dict(lpp=192.162, breadth=32.968, draft=9.688, depth=15.501, cb=0.734, lcb=92.917),
    "beamy 128 m": dict(lpp=128.123, breadth=30.086, draft=8.859, depth=14.174, cb=0.617, lcb=59.654),
}
BUTTOCK = 0.3  # fraction of B/2
#: How far forward of the waterline's aft end the stations are read, fraction of Lpp.
AFT_STRETCH = 0.08


@pytest.fixture(scope="module", params=list(SHIPS))
def ship(request):
    return fl.design_hull(**SHIPS[request.param])


def test_the_ships_have_a_dry_transom(ship):
    """The case this is about: the keel rises out of the water forward of the transom."""
    xa, _ = ship.immersed_range()
    assert xa > ship.description.x_aft + 0.005 * ship.description.principal.lpp


def test_no_station_before_the_fade_asks_less_than_the_family_holds(ship):
    """Outside the end band of depth (where the asked area fades out) every station aft holds
    the SAC's area with a section of the family: the asked fullness is at least the family's
    least (the V). Band-free, the coaster's station 0.106 T deep asked 0.512 against 0.515."""
    pr = ship.description.principal
    xa, _ = ship.immersed_range()
    xs = ship.stations()
    xs = xs[(xs > xa) & (xs < xa + AFT_STRETCH * pr.lpp)]
    read = 0
    for spec in ship.section_specs(xs):
        depth = spec.draft - spec.z_keel
        if depth < _native.END_BAND * pr.draft:
            continue
        asked = spec.half_area / (spec.y_dwl * depth)
        least = _native.section_fullness_bounds(spec)[1]  # (whole flat kept, least, largest)
        assert asked >= least - 1e-9, (spec.x, asked, least)
        read += 1
    assert read >= 3


def test_buttock_crosses_the_waterline_at_a_dry_transom_without_a_hollow(ship):
    """The buttock at 0.3 B/2 turns one way from the transom to where it lands on the bottom
    (at most the issue's two sign changes over the whole cut; three before)."""
    pr = ship.description.principal
    cut = fl.plane_cut(ship.bare_hull_surface(), 1, BUTTOCK * pr.breadth / 2, 401)
    judged = judge_cut(cut)
    at = [(round(i["at"][0], 2), round(i["at"][2], 2)) for i in judged["inflections"]]
    assert judged["sign_changes"] <= 2, at
    near_t = [a for a in at if abs(a[0]) < 0.02 * pr.lpp and abs(a[1] - pr.draft) < 0.1 * pr.draft]
    assert not near_t, near_t
