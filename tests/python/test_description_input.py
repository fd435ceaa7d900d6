"""The hull-description loader refuses absurd or mistaken input by JSON path: lengths outside
the physical range (with a units hint), unknown keys anywhere (with the nearest valid one),
station counts beyond the limit, and JSON that is not an object. The loader is the
description module of the hull designer; these tests run where it exists."""

import copy
import json

import pytest

import fairlines as fl

description = pytest.importorskip("fairlines.description")

BASE = {
    "principal": {"Lpp": 100.0, "B": 16.0, "T": 6.0, "D": 9.0},
    "basic_curves": {"profile": {"value": 0.0}, "dwl": {"value": 8.0}, "deck": {"value": 8.0},
                     "sac": {"value": 90.0}},
}


def refused(mutate):
    d = copy.deepcopy(BASE)
    mutate(d)
    with pytest.raises(fl.InvalidInput) as exc:
        description.HullDescription.from_dict(d)
    return str(exc.value)


def test_the_base_description_is_accepted():
    description.HullDescription.from_dict(copy.deepcopy(BASE))


@pytest.mark.parametrize("lpp", [1e300, 244800.0])
def test_lengths_beyond_the_physical_range_hint_at_units(lpp):
    msg = refused(lambda d: d["principal"].__setitem__("Lpp", lpp))
    assert "principal.Lpp" in msg and "millimetres" in msg


def test_unknown_skinning_key_names_the_nearest():
    msg = refused(lambda d: d.__setitem__("skinning", {"e22": 1.0}))
    assert "e22" in msg and "did you mean 'e2'" in msg


def test_a_ruled_skin_beyond_the_hulls_ends_names_them():
    msg = refused(lambda d: d.__setitem__("skinning", {"ruled_aft_of": 120.0}))
    assert "skinning.ruled_aft_of is 120.0" in msg and "0 .. 100 m" in msg


def test_a_knuckle_off_the_stations_names_the_nearest_station():
    d = copy.deepcopy(BASE)
    d["stations"], d["skinning"] = {"x": [0.0, 20.0, 50.0, 80.0, 100.0]}, {"knuckles": [49.0]}
    with pytest.raises(fl.InvalidInput, match=r"skinning.knuckles\[0\] is 49 m; expected the x of a station \(the nearest is 50 m\)"):
        fl.Hull.from_json(json.dumps(d)).bare_hull_surface()


def test_an_unknown_aft_end_condition_names_the_choices():
    msg = refused(lambda d: d.__setitem__("skinning", {"aft_end": "natural"}))
    assert "skinning.aft_end is 'natural'; expected 'free' or 'not_a_knot'" in msg


def test_a_not_a_knot_aft_end_next_to_a_ruled_stern_is_refused_naming_both():
    d = copy.deepcopy(BASE)
    d["skinning"] = {"aft_end": "not_a_knot", "ruled_aft_of": 10.0}
    with pytest.raises(fl.InvalidInput, match="skinning.aft_end is 'not_a_knot' but the skin is only C0 at the station "
                                              "next to the aft end"):
        fl.Hull.from_json(json.dumps(d)).bare_hull_surface()


def test_unknown_top_level_key_names_the_nearest():
    msg = refused(lambda d: d.__setitem__("principle", {}))
    assert "principle" in msg and "did you mean 'principal'" in msg


def test_station_count_beyond_the_limit_is_refused():
    assert "stations.count" in refused(lambda d: d.__setitem__("stations", {"count": 10**7}))


def test_json_that_is_not_an_object_is_invalid_input():
    with pytest.raises(fl.InvalidInput, match="JSON object"):
        fl.Hull.from_json("[1,2,3]")
