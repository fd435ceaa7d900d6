"""fairlines.compose raises fl.InvalidInput naming the value and what was expected."""

import pytest

import fairlines as fl
from blend_fixtures import container_ship_composed


def test_unknown_operation_is_invalid_input():
    hull = container_ship_composed().trimmed_surfaces[0][0]
    with pytest.raises(fl.InvalidInput, match=r"operation is 'difference'; expected 'union'"):
        fl.compose([hull], operation="difference")


def test_a_bulb_that_is_not_a_surface_is_invalid_input():
    hull = container_ship_composed().trimmed_surfaces[0][0]
    with pytest.raises(fl.InvalidInput, match=r"hull and bulb are NurbsSurface, str; expected"):
        fl.seam_blend_placement(hull, "bulb")


def test_unknown_bulb_keys_are_invalid_input():
    with pytest.raises(fl.InvalidInput, match=r"bulb section has unknown keys \['size'\]"):
        fl.BulbousBow.from_dict({"size": 1.0}, {})
