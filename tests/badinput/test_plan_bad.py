"""A bad plan is refused before any work, naming the field and what is allowed.

Building files: the example (``examples/five_storey.toml``) with a ``[plan]`` table added,
one key of it wrong at a time, through :func:`structures.config.load_config` (and, for one
case, ``dcfpb run``: exit status 2). Objects: :class:`structures.plan.Plan`,
:class:`structures.shear_building.ShearBuilding` with a plan and the model
(:class:`structures.isolated_building.IsolatedShearBuilding`), each with one parameter wrong.
A plan whose bearings cannot carry the weight (the centre of mass outside where the linear
distribution keeps every bearing in compression, or bearings on one line) is refused.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError
from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction
from structures.config import ConfigError, load_config
from structures.isolated_building import IsolatedShearBuilding
from structures.plan import Plan
from structures.shear_building import ModalDamping, ShearBuilding

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
SQUARE = [[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0]]
GOOD_PLAN = {
    "bearing_coordinates": "[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], [0.0, -5.0], "
                           "[0.0, 5.0]]",
    "eccentricity": "[1.0, 0.5]",
    "dimensions": "[12.0, 10.0]",
    "storey_heights": "3.5",
}


def _file(tmp_path: Path, **changes: str | None) -> Path:
    plan = {**GOOD_PLAN, **changes}
    lines = [f"{key} = {value}" for key, value in plan.items() if value is not None]
    path = tmp_path / "plan.toml"
    path.write_text(EXAMPLE.read_text(encoding="utf-8") + "\n[plan]\n" + "\n".join(lines)
                    + "\n", encoding="utf-8")
    return path


def test_the_good_plan_loads_and_the_file_in_one_direction_has_none(tmp_path):
    config = load_config(_file(tmp_path))
    assert config.plan is not None and config.n_bearings == 6
    assert config.building.gravity_shares.min() > 0.0
    assert load_config(EXAMPLE).plan is None


BAD = {
    "coordinates not pairs": ({"bearing_coordinates": "[1.0, 2.0, 3.0]"},
                              ("[plan] 'bearing_coordinates'", "[x, y] pairs", "Got")),
    "a coordinate of three": ({"bearing_coordinates": "[[0.0, 0.0], [1.0, 0.0, 2.0], [0.0, 1.0]]"},
                              ("'bearing_coordinates'", "at index 1")),
    "two bearings": ({"bearing_coordinates": "[[0.0, 0.0], [1.0, 0.0]]"},
                     ("'bearing_coordinates'", "3 to 10000", "Got 2 pairs")),
    "colinear": ({"bearing_coordinates": "[[-6.0, 0.0], [-3.0, 0.0], [0.0, 0.0], [2.0, 0.0], "
                                         "[4.0, 0.0], [6.0, 0.0]]"},
                 ("'bearing_coordinates'", "not all on one line")),
    "cannot carry": ({"eccentricity": "[9.0, 0.0]", "dimensions": "[30.0, 10.0]"},
                     ("cannot carry the weight", "'eccentricity'", "bearing 0")),
    "eccentricity of a string": ({"eccentricity": '"left"'},
                                 ("[plan] 'eccentricity'", "Got \"left\" (a string)")),
    "eccentricity per floor of 2": ({"eccentricity": "[[0.0, 0.0], [1.0, 0.0]]"},
                                    ("'eccentricity'", "one per floor (5)", "Got 2 pairs")),
    "negative dimension": ({"dimensions": "[12.0, -1.0]"},
                           ("[plan] 'dimensions'", "(0, 10000]", "Got -1.0")),
    "heights per storey of 2": ({"storey_heights": "[3.0, 3.0]"},
                                ("[plan] 'storey_heights'", "one value per storey (5,")),
    "zero height": ({"storey_heights": "0.0"}, ("'storey_heights'", "(0, 1000]")),
    "no dimensions for the inertia": ({"dimensions": None},
                                      ("[plan] 'torsional_stiffnesses' is needed", "'dimensions'")),
    "unknown key": ({"eccentricty": "[0.0, 0.0]"}, ("unknown key(s) 'eccentricty'", "[plan]")),
    "no coordinates": ({"bearing_coordinates": None}, ("[plan] needs 'bearing_coordinates'",)),
    "two bearings at one point": (
        {"bearing_coordinates": "[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], "
                                "[6.0, 5.0005], [0.0, 5.0]]"},
        ("[plan] 'bearing_coordinates' must give each bearing its own point",
         "at least 1 mm apart", "Got bearings 2 and 4 both at (6, 5) m", "0.5 mm apart")),
    "bearing beyond the slab": (
        {"bearing_coordinates": "[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], "
                                "[0.0, -5.0], [9.0, 5.0]]"},
        ("[plan] 'bearing_coordinates' must lie within the slab of 'dimensions' (12, 10) m",
         "bearings 0 at (-6, -5) m and 5 at (9, 5) m, 15 m apart along x",
         "the plan's a = 12 m")),
    "eccentricity beyond the plan": (
        {"eccentricity": "[0.5, 6.0]"},
        ("[plan] 'eccentricity' must put the centre of mass within the slab",
         "Got (0.5, 6) m, 11 m along y from bearing 0 at (-6, -5) m", "the plan's b = 10 m")),
    "eccentricity of a floor beyond the plan": (
        {"eccentricity": "[[0.0, 0.0], [0.0, 0.0], [-7.0, 0.0], [0.0, 0.0], [0.0, 0.0]]"},
        ("[plan] 'eccentricity'", "Got (-7, 0) m of floor 3", "13 m along x from bearing 1")),
    "base eccentricity beyond the plan": (
        {"base_eccentricity": "[0.0, -5.5]"},
        ("[plan] 'base_eccentricity' must put the centre of mass", "Got (0, -5.5) m",
         "10.5 m along y")),
    "count disagrees": ({}, ("[bearing] 'count'", "number of [plan] 'bearing_coordinates' (6)",
                             "Got 4")),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_plan_files_are_refused(tmp_path, case):
    changes, expected = BAD[case]
    path = _file(tmp_path, **changes)
    if case == "count disagrees":
        path.write_text(path.read_text().replace("count = 6", "count = 4"))
    with pytest.raises(ConfigError) as error:
        load_config(path)
    message = str(error.value)
    assert str(path) in message
    for text in expected:
        assert text in message, (text, message)


def test_the_command_line_refuses_a_plan_that_cannot_carry_the_weight(tmp_path, capsys):
    path = _file(tmp_path, eccentricity="[0.0, 7.0]", dimensions="[12.0, 20.0]")
    assert main(["run", str(path), "--record", str(RECORD)]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and "cannot carry the weight" in captured.err


def _building(plan: Plan | None = None, **damping) -> ShearBuilding:
    return ShearBuilding.from_period([4e5, 4e5], 0.4, base_mass=5e5, plan=plan, **damping)


def test_objects_refuse_bad_parameters_naming_them():
    with pytest.raises(InputError, match="'bearing_coordinates' parameter of Plan"):
        Plan([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    with pytest.raises(InputError, match=r"'storey_heights' parameter of Plan .* \(0, 1000\]"):
        Plan(SQUARE, storey_heights=-3.0)
    with pytest.raises(InputError, match="'base_inertia' parameter of Plan"):
        Plan(SQUARE, base_inertia=0.0)
    with pytest.raises(InputError, match=r"'floor_inertias' parameter of Plan must hold one "
                                         r"value per storey \(2\)"):
        _building(Plan(SQUARE, floor_inertias=[1e6], base_inertia=1e6,
                       dimensions=(12.0, 10.0)))
    with pytest.raises(InputError, match="cannot carry the weight"):
        _building(Plan(SQUARE, eccentricity=(0.0, -9.0), dimensions=(12.0, 10.0)))
    with pytest.raises(InputError, match="one ratio for every mode"):
        _building(Plan(SQUARE, dimensions=(12.0, 10.0)), damping=ModalDamping((0.02, 0.03)))
    in_plan = _building(Plan(SQUARE, dimensions=(12.0, 10.0)))
    bearing = DCFPBearing(2.5, 0.3, friction=ConstantFriction())
    with pytest.raises(InputError, match="'storey_heights' parameter of Plan is needed"):
        IsolatedShearBuilding(in_plan, bearing)
    with pytest.raises(TypeError, match="'vertical' parameter"):
        IsolatedShearBuilding(in_plan, bearing, overturning=False, vertical=[0.0, 1.0])


def test_bearings_on_the_slab_edge_and_a_centre_of_mass_inside_are_accepted(tmp_path):
    path = _file(tmp_path, eccentricity="[0.0, 0.0]", dimensions="[12.0, 10.0]",
                 bearing_coordinates="[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], "
                                     "[0.0, -5.0], [0.0, 5.0]]")
    assert load_config(path).n_bearings == 6
    # bearings 0.9 m apart: their own points; the slab off the centre of stiffness is allowed
    path = _file(tmp_path, bearing_coordinates="[[-2.0, -5.0], [10.0, -5.0], [10.0, 5.0], "
                                               "[-2.0, 5.0], [4.0, -5.0], [4.9, -5.0]]",
                 eccentricity="[3.0, 0.0]")
    assert load_config(path).n_bearings == 6


BEARING_BAD = {
    "capacity beyond the radius": (
        ("displacement_capacity = 0.6", "displacement_capacity = 3.0"),
        ("[bearing] 'displacement_capacity' must be at most 0.5 x 'effective_radius' = 2.25 m",
         "u / R_eff = 0.667", "slope 42 degrees", "Got 3 instead")),
    "capacity at the radius": (
        ("displacement_capacity = 0.6", "displacement_capacity = 4.5"),
        ("'displacement_capacity'", "slope 90 degrees", "impossible at 1", "Got 4.5")),
    "default capacity beyond a small radius": (
        ("effective_radius = 4.5", "effective_radius = 1.0"),
        ("'displacement_capacity' must be at most 0.5 x 'effective_radius' = 0.5 m",
         "Got 0.6 (the default) instead")),
    "slider wider than the radius": (
        ("slider_diameter = 0.3", "slider_diameter = 5.0"),
        ("[bearing] 'slider_diameter' must be below the 'effective_radius' 4.5 m", "Got 5")),
}


@pytest.mark.parametrize("case", sorted(BEARING_BAD))
def test_bearing_geometry_beyond_what_the_radius_permits_is_refused(tmp_path, case):
    (old, new), expected = BEARING_BAD[case]
    text = EXAMPLE.read_text(encoding="utf-8")
    if case == "default capacity beyond a small radius":
        text = text.replace("displacement_capacity = 0.6", "")
    assert old in text
    path = tmp_path / "bearing.toml"
    path.write_text(text.replace(old, new), encoding="utf-8")
    with pytest.raises(ConfigError) as error:
        load_config(path)
    message = str(error.value)
    assert message.startswith(str(path))
    for part in expected:
        assert part in message, (part, message)


def test_a_flat_slider_has_no_radius_bound(tmp_path):
    text = EXAMPLE.read_text(encoding="utf-8").replace("effective_radius = 4.5",
                                                       "effective_radius = inf")
    path = tmp_path / "flat.toml"
    path.write_text(text, encoding="utf-8")
    assert load_config(path).bearing_geometry["effective_radius"] == float("inf")
