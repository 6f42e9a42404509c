"""The helpers that replaced repeated code (issue 19, second round of merges): the comma-separated
numbers of the command line, the JSON cleaner, the slider contact, the resultant and the path
integral give what each copy they replaced gave."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from dcfpb.common.errors import InputError
from dcfpb.common.files import json_safe
from dcfpb.common.validation import parse_floats
from isolator.bearing import DCFPBearing, slider_contact_area
from isolator.characteristics import path_integral
from isolator.diagnosis.data import Campaign
from isolator.friction import ConstantFriction
from structures.results import resultant


@pytest.mark.parametrize(("text", "count", "expected"), [
    ("1,1.5", None, (1.0, 1.5)), (" 2 ", None, (2.0,)), ("1,2,", None, (1.0, 2.0)),
    ("0.2,0.25", 2, (0.2, 0.25)),
])
def test_parse_floats_reads_the_numbers(text, count, expected):
    assert parse_floats(text, "--flag", count=count) == expected


@pytest.mark.parametrize(("text", "form", "count", "message"), [
    ("1,x", "", None, "--flag must be numbers separated by commas. Got '1,x'."),
    ("", "", None, "--flag needs at least one value. Got ''."),
    ("1.2", "MAX,MIN", 2, "--flag must be MAX,MIN, two numbers separated by a comma. Got '1.2'."),
    ("1,nan", "MAX,MIN", 2, "--flag must be MAX,MIN, two numbers separated by a comma."),
    ("a,b", "S_MS,S_M1[,T_L]", None, "--flag must be S_MS,S_M1[,T_L], numbers separated by "
                                     "commas."),
])
def test_parse_floats_names_the_flag_and_the_form(text, form, count, message):
    with pytest.raises(InputError) as error:
        parse_floats(text, "--flag", form, count=count)
    assert message in str(error.value)


def test_json_safe_makes_json_of_nan_numpy_and_tuples():
    data = {"a": float("nan"), 1: (np.float64(2.5), np.int64(3)), "b": np.array([1.0, np.inf]),
            "c": [{"d": -math.inf}], "e": np.array([4.0]), "f": np.array(5.0), "g": "text"}
    clean = json_safe(data)
    assert clean == {"a": None, "1": [2.5, 3], "b": [1.0, None], "c": [{"d": None}], "e": [4.0],
                     "f": 5.0, "g": "text"}
    json.dumps(clean, allow_nan=False)
    assert type(clean["1"][1]) is int


def test_the_slider_contact_is_one_for_a_bearing_and_a_campaign():
    bearing = DCFPBearing(effective_radius=3.0, slider_diameter=0.3,
                          friction=ConstantFriction(0.05), axial_load=1e6)
    assert bearing.contact_radius == 0.15
    assert bearing.contact_area == math.pi * 0.15**2 == slider_contact_area(0.3)
    assert Campaign.contact_area is DCFPBearing.contact_area


def test_resultant_of_one_and_two_directions():
    assert np.array_equal(resultant(np.array([[-3.0], [2.0]])), [3.0, 2.0])
    assert np.array_equal(resultant(np.array([[[3.0, 4.0]], [[0.0, -1.0]]])), [[5.0], [1.0]])


def test_path_integral_of_one_and_two_directions():
    u = np.array([0.0, 1.0, 2.0])
    f = np.array([1.0, 3.0, 5.0])
    assert path_integral(u, f) == 0.5 * (1.0 + 3.0) + 0.5 * (3.0 + 5.0)
    both = path_integral(np.column_stack([u, u]), np.column_stack([f, f]))
    assert both == 2 * path_integral(u, f)
