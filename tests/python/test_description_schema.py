"""docs/hull_description.schema.json against the loader (fairlines.description): the schema is a
valid draft 2020-12 schema; every description the project writes (the examples, designed hulls,
`fairlines import`) validates; and malformed descriptions are refused by both the schema and
the loader with fl.InvalidInput (at load, or for the checks the loader leaves to the build,
when the hull is built)."""

from __future__ import annotations

import pytest
from jsonschema import Draft202012Validator

import fairlines as fl
from fairlines.description import HullDescription
from schema_fixtures import (DESIGNS, EXAMPLES, both, designed_description, documented_example, drop, example,
                             example_description, imported_description, put, schema, schema_error_paths,
                             schema_errors)

BC = "basic_curves"
#: How a description names a unit: (m ... ), (m^2 ...), (deg), (-), (1/m), the curve's unit, or true / false.
UNIT_MARKS = ("(m", "(deg", "(-)", "(1/m", "m^2", "m^3", "curve's unit", "true")

#: Malformed descriptions (edits of the container ship example) the loader refuses at load.
REFUSED_AT_LOAD = {
    # wrong type
    "Lpp as text": put(("principal", "Lpp"), "244.8"),
    "Lpp as a boolean": put(("principal", "Lpp"), True),
    "station count not an integer": put(("stations", "count"), 61.5),
    "monotone not a boolean": put((BC, "dwl", "monotone"), "yes"),
    "point not a pair": put((BC, "profile", "points"), [[244.8, 11.0, 0.0]]),
    "ends not an object": put(("ends",), [-6.12, 247.7]),
    "design not an object": put(("design",), ["lpp", 244.8]),
    # negative or zero lengths and coefficients
    "negative breadth": put(("principal", "B"), -32.25),
    "zero draught": put(("principal", "T"), 0.0),
    "length in millimetres": put(("principal", "Lpp"), 244800.0),
    "negative bulb aft length": put(("bulb", "shape", "aft_length"), -1.0),
    "negative Kracht coefficient": put(("bulb", "kracht", "c_bb"), -0.18),
    "negative displacement volume": put(("bulb", "displacement_volume"), -56000.0),
    "zero fit weight": put((BC, "dwl", "fit_weight"), 0.0),
    "negative fairness weight e3": put((BC, "dwl", "e3"), -1.0),
    "fairness weight e3 beyond 1e4": put((BC, "dwl", "e3"), 1e5),
    "negative least curvature": put((BC, "dwl", "convex"), [[50.0, 100.0, -0.01]]),
    "negative least curvature where met": put((BC, "sac", "convex_where_met"), [[50.0, 100.0, -0.01]]),
    "convex where met on the waterline": put((BC, "dwl", "convex_where_met"), [[50.0, 100.0, 0.0]]),
    "section fullness above 1": put((BC, "sac", "fullness_fit", 0, 1), 1.5),
    # unknown keys
    "unknown top-level key": put(("range",), {"x_start": 0.0, "x_end": 244.8}),
    "unknown principal key": put(("principal", "Cb"), 0.65),
    "unknown curve key": put((BC, "deck", "flatto"), 174.3),
    "unknown Kracht coefficient": put(("bulb", "kracht", "c_lp"), 0.025),
    "unknown skinning key": put(("skinning", "junctions"), True),
    "sac alias on the deck": put((BC, "deck", "volume"), 56000.0),
    "fullness fit on the waterline": put((BC, "dwl", "fullness_fit"), [[100.0, 0.9]]),
    # missing required keys
    "missing principal": drop(("principal",)),
    "missing depth": drop(("principal", "D")),
    "missing basic curves": drop((BC,)),
    "missing sac": drop((BC, "sac")),
    "flat part without its value": drop((BC, "deck", "value")),
    # angles out of range
    "end angle of 90 deg": put((BC, "deck", "alphaE"), 90.0),
    "end angle of -120 deg": put((BC, "deck", "alphaB"), -120.0),
    # bad enum values and integer ranges
    "unknown basic curve": put((BC, "fos"), {"value": 3.6}),
    "section controls above 64": put(("sections", "n_control"), 100),
    "station count below 5": put(("stations", "count"), 4),
    "spans 0": put((BC, "sac", "spans"), 0),
    "bulb sections below 8": put(("bulb", "shape", "sections"), 4),
    "three station positions": put(("stations",), {"x": [0.0, 100.0, 200.0]}),
    "201 breaks": put((BC, "profile", "breaks"), [float(x) for x in range(201)]),
    # one of two, not both
    "station count and positions": put(("stations", "x"), [0.0, 50.0, 100.0, 200.0]),
    "spans and n_control": put((BC, "sac", "n_control"), 27),
    "skinning weights both 0": put(("skinning",), {"e2": 0.0, "e3": 0.0}),
    "skinning knuckles not a list": put(("skinning", "knuckles"), 100.0),
    "ruled skin aft of text": put(("skinning", "ruled_aft_of"), "transom"),
    "unknown aft end condition": put(("skinning", "aft_end"), "natural"),
    # given sections
    "given section point not a pair": put(("sections", "given"), [{"x": 100.0, "points": [[1.0, 19.0], [2.0], [0.0, 0.0]]}]),
    "given section negative half-breadth": put(("sections", "given"), [{"x": 100.0, "points": [[1.0, 19.0], [-2.0, 5.0], [0.0, 0.0]]}]),
    "given section of two points": put(("sections", "given"), [{"x": 100.0, "points": [[1.0, 19.0], [0.0, 0.0]]}]),
    "given section without x": put(("sections", "given"), [{"points": [[1.0, 19.0], [2.0, 5.0], [0.0, 0.0]]}]),
    "skeg without its thickness": put(("skeg",), {"x_aft": 9.7, "x_fore": 41.7}),
    "skeg of negative thickness": put(("skeg",), {"x_aft": 9.7, "x_fore": 41.7, "half_thickness": -0.5}),
    "dome without its depth": put(("dome",), {"x_aft": 190.0, "x_fore": 215.0, "half_breadth": 3.0}),
    "dome of no breadth": put(("dome",), {"x_aft": 190.0, "x_fore": 215.0, "depth": 4.0, "half_breadth": 0.0}),
    "unknown skeg key": put(("skeg",), {"x_aft": 9.7, "x_fore": 41.7, "half_thickness": 0.5, "depth": 3.0}),
    "unknown given section key": put(("sections", "given"), [{"x": 100.0, "y": [1.0], "points": [[1.0, 19.0], [2.0, 5.0], [0.0, 0.0]]}]),
    "negative given smoothing": put(("sections", "given_smoothing"), -0.1),
    "given smoothing above 100": put(("sections", "given_smoothing"), 1e3),
    "given smoothing not a number": put(("sections", "given_smoothing"), "smooth"),
}

#: Malformed descriptions the loader reads but the build refuses (InvalidInput or its subclass
#: InfeasibleFormParameters) the first time the hull's geometry is asked for.
REFUSED_AT_BUILD = {
    "entrance angle of 95 deg": put((BC, "dwl", "entrance_angle"), 95.0),
    "volume and Area": put((BC, "sac", "Area"), 56448.0),
    "lcf and xC": put((BC, "dwl", "xC"), 115.0),
    "end angle and end slope": put((BC, "profile", "alphaB"), -12.0),
    "negative volume": put((BC, "sac", "volume"), -56448.0),
    "negative waterplane area": put((BC, "dwl", "waterplane_area"), -6444.0),
}

#: Malformed descriptions of the free-text fields: refused by both.
TEXT_REFUSED = {
    "name not text": put(("name",), 5),
    "notes not text": put(("notes",), ["a", "list"]),
}

#: Unusual but valid descriptions: null for 'not given', aliases, one of two alternatives.
ACCEPTED = {
    "no bulb (null)": put(("bulb",), None),
    "no design (null)": put(("design",), None),
    "lcb null": put((BC, "sac", "lcb"), None),
    "n_control instead of spans": both(drop((BC, "sac", "spans")), put((BC, "sac", "n_control"), 27)),
    "station positions": put(("stations",), {"x": [-6.0, 0.0, 60.0, 120.0, 180.0, 244.8, 247.0]}),
    "e3 fairness only": put(("skinning",), {"e2": 0.0, "e3": 1.0}),
    "a ruled stern": put(("skinning", "ruled_aft_of"), 5.0),
    "no ruled stern (null)": put(("skinning", "ruled_aft_of"), None),
    "a free aft end": put(("skinning", "aft_end"), "free"),
    "constant deadrise curve": put((BC, "deadrise"), {"value": 5.0}),
    "a skeg": put(("skeg",), {"x_aft": 9.7, "x_fore": 41.7, "half_thickness": 0.77, "fillet": 7.7, "end_length": 6.2}),
    "a square sternpost": put(("skeg",), {"x_aft": 9.7, "x_fore": 41.7, "half_thickness": 0.77}),
    "no skeg (null)": put(("skeg",), None),
    "a sonar dome": put(("dome",), {"x_aft": 190.0, "x_fore": 215.0, "depth": 4.0, "half_breadth": 3.0}),
    "a given section": put(("sections", "given"), [{"x": 100.0, "points": [[16.1, 19.0], [16.1, 2.0], [14.0, 0.0], [0.0, 0.0]]}]),
    "a given section smoothed": both(put(("sections", "given"), [{"x": 100.0, "points": [[16.1, 19.0], [16.1, 2.0], [14.0, 0.0], [0.0, 0.0]]}]),
                                     put(("sections", "given_smoothing"), 0.1)),
    "a sheer": put((BC, "sheer"), {"yB": 20.0, "yE": 21.0, "value": 19.0, "flat_from": 60.0, "flat_to": 180.0}),
    "a largest breadth": put(("principal", "B_max"), 33.0),
    "bulb with defaults only": put(("bulb",), {}),
    "dwl entrance angle alias": both(drop((BC, "dwl", "yE")), put((BC, "dwl", "entrance_angle"), 15.0)),
}


def test_the_schema_is_a_valid_2020_12_schema():
    Draft202012Validator.check_schema(schema())


def test_every_property_has_a_description_with_its_unit():
    """The schema doubles as the format reference: each property says what it is, each leaf its unit."""
    missing = []

    def walk(node, path):  # the format's own properties, not those of the rules (not / if / then)
        for name, sub in node.get("properties", {}).items():
            text = sub.get("description", "")
            if not text or ("properties" not in sub and not any(u in text for u in UNIT_MARKS)):
                missing.append("/".join(path + (name,)))
            walk(sub, path + (name,))
        for name, sub in node.get("$defs", {}).items():
            walk(sub, path + (name,))

    walk(schema(), ())
    assert not missing


def test_the_container_ship_example_validates():
    assert schema_errors(example("container_ship.json")) == []


@pytest.mark.parametrize("name", EXAMPLES)
def test_each_example_is_valid_to_schema_and_loader(name):
    doc = example(name)
    HullDescription.from_dict(doc)
    assert schema_errors(doc) == []


@pytest.mark.parametrize("name", list(DESIGNS))
def test_designed_hull_json_validates(name):
    assert schema_errors(designed_description(name)) == []


def test_imported_ship_description_validates(tmp_path):
    assert schema_errors(imported_description(tmp_path)) == []


def test_the_documented_minimal_example_validates():
    assert schema_errors(documented_example()) == []


def test_the_documented_minimal_example_builds():
    """It builds into a hull whose volume lies inside its box Lpp B T."""
    doc = documented_example()
    p = doc["principal"]
    assert 0 < fl.Hull.from_json(doc).hydrostatics().volume < p["Lpp"] * p["B"] * p["T"]


@pytest.mark.parametrize("case", list(ACCEPTED))
def test_schema_accepts_valid_variant(case):
    assert schema_errors(ACCEPTED[case](example_description())) == []


@pytest.mark.parametrize("case", list(ACCEPTED))
def test_loader_accepts_valid_variant(case):
    HullDescription.from_dict(ACCEPTED[case](example_description()))


@pytest.mark.parametrize("case", list(REFUSED_AT_LOAD) + list(REFUSED_AT_BUILD) + list(TEXT_REFUSED))
def test_schema_refuses_malformed_where_it_was_edited(case):
    """A complaint points at the edited key, at an object that holds it, or inside its new value."""
    edit = {**REFUSED_AT_LOAD, **REFUSED_AT_BUILD, **TEXT_REFUSED}[case]
    paths = schema_error_paths(edit(example_description()))
    n = len(edit.path)
    assert any(p[:n] == edit.path or edit.path[:len(p)] == p for p in paths), paths


@pytest.mark.parametrize("case", list(REFUSED_AT_LOAD))
def test_loader_refuses_malformed(case):
    with pytest.raises(fl.InvalidInput):
        fl.Hull.from_json(REFUSED_AT_LOAD[case](example_description()))


@pytest.mark.parametrize("case", list(REFUSED_AT_BUILD))
def test_build_refuses_malformed(case):
    hull = fl.Hull.from_json(REFUSED_AT_BUILD[case](example_description()))
    with pytest.raises(fl.InvalidInput):
        hull.bare_hull_surface()


@pytest.mark.parametrize("case", list(TEXT_REFUSED))
def test_loader_and_schema_refuse_text_fields_that_are_not_text(case):
    doc = TEXT_REFUSED[case](example_description())
    assert schema_errors(doc)
    with pytest.raises(fl.InvalidInput, match="expected text"):
        fl.Hull.from_json(doc)
