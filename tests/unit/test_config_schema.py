"""The building file's rules, one by one (:mod:`structures.config_schema`,
:func:`structures.config.load_config`): types, ranges, arrays, keys, warnings and encodings."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from dcfpb.common.errors import InputError, InputWarning
from structures.config import ConfigError, ConfigWarning, load_config
from structures.config_schema import Array, Choice, Either, Integer, Number, Where
from structures.integrators import HHT, Newmark

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
HERE = Where(Path("b.toml"), "bearing", "count")

MINIMAL = """
[building]
floor_masses = [1e5, 1e5]
fixed_base_period = 0.3
base_mass = 1e5
[bearing]
effective_radius = 2.0
slider_diameter = 0.3
"""


def _file(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "b.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _message(excinfo) -> str:
    return str(excinfo.value)


def test_errors_and_warnings_are_the_projects():
    assert issubclass(ConfigError, InputError) and issubclass(ConfigError, ValueError)
    assert issubclass(ConfigWarning, InputWarning) and issubclass(ConfigWarning, UserWarning)


@pytest.mark.parametrize("value", [6, 1, 10_000])
def test_integer_accepts_integers_in_range(value):
    assert Integer(1, 10_000).check(value, HERE) == value


@pytest.mark.parametrize(("value", "kind"), [(2.7, "a float"), (6.0, "a float"),
                                             (True, "a boolean"), ("6", "a string"),
                                             ([6], "an array"), ({"n": 6}, "a table"),
                                             (0, "an integer"), (10_001, "an integer")])
def test_integer_refuses_everything_else(value, kind):
    with pytest.raises(ConfigError) as excinfo:
        Integer(1, 10_000).check(value, HERE)
    assert _message(excinfo).startswith("b.toml: [bearing] 'count' must be an integer in "
                                        "[1, 10000]. Got ")
    assert f"({kind}) instead." in _message(excinfo)


@pytest.mark.parametrize("value", [True, False, "0.3", [0.3], float("nan"), float("inf"),
                                   -0.1, 0.0, 10.5])
def test_number_refuses_booleans_strings_arrays_nan_inf_and_out_of_range(value):
    with pytest.raises(ConfigError, match=r"must be a number in \(0, 10\]"):
        Number(low=0.0, low_open=True, high=10.0).check(value, HERE)


def test_number_takes_integers_and_floats_unchanged():
    spec = Number(low=0.0, low_open=True, high=10.0)
    assert spec.check(3, HERE) == 3 and type(spec.check(3, HERE)) is int
    assert spec.check(10.0, HERE) == 10.0


def test_number_with_inf_allowed():
    spec = Number(low=1e-3, high=1e4, allow_inf=True)
    assert spec.check(float("inf"), HERE) == float("inf")
    with pytest.raises(ConfigError):
        spec.check(float("-inf"), HERE)
    with pytest.raises(ConfigError):
        spec.check(2e4, HERE)


def test_interval_text():
    assert Number(low=0.0, low_open=True).interval == "(0, inf)"
    assert Number(low=-273.15, high=1000.0).interval == "[-273.15, 1000]"
    assert Number(low=0.0, high=1.0, high_open=True).interval == "[0, 1)"


def test_choice_names_the_choices():
    with pytest.raises(ConfigError, match=r'one of "newmark", "hht". Got "euler" \(a string\)'):
        Choice(("newmark", "hht")).check("euler", HERE)
    with pytest.raises(ConfigError, match=r"Got \[\] \(an array\)"):
        Choice(("newmark", "hht")).check([], HERE)


def test_array_checks_kind_length_and_every_item():
    spec = Array(Number(low=0.0, low_open=True), what="kg")
    assert spec.check([1.0, 2], HERE) == [1.0, 2]
    with pytest.raises(ConfigError, match=r"Got \[1, 2\] \(an array\) at index 1 instead"):
        spec.check([1.0, [1, 2]], HERE)
    with pytest.raises(ConfigError, match=r"Got true \(a boolean\) at index 0"):
        spec.check([True], HERE)
    with pytest.raises(ConfigError, match="Got 0 values instead"):
        spec.check([], HERE)
    with pytest.raises(ConfigError, match="Got 2 values instead"):
        Array(Integer(1, 5), length=3).check([1, 2], HERE)


def test_either_picks_by_type():
    spec = Either((Number(low=0.0, high=1.0, high_open=True),
                   Array(Number(low=0.0, high=1.0, high_open=True))))
    assert spec.check(0.05, HERE) == 0.05 and spec.check([0.05, 0.02], HERE) == [0.05, 0.02]
    with pytest.raises(ConfigError, match=r"a number in \[0, 1\) or an array"):
        spec.check("0.05", HERE)
    with pytest.raises(ConfigError, match="at index 1"):
        spec.check([0.05, 2.0], HERE)


def test_minimal_file_takes_the_defaults(tmp_path):
    config = load_config(_file(tmp_path, MINIMAL))
    assert config.n_bearings == 1 and config.dt is None and config.name == "b"
    assert isinstance(config.integrator, Newmark) and config.friction == {"model": "precise"}


def test_the_example_loads_as_before():
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the example has no setting without effect
        config = load_config(EXAMPLE)
    assert config.n_bearings == 6 and config.dt == 0.005
    assert config.bearing_geometry == {"effective_radius": 4.5, "slider_diameter": 0.3,
                                       "yield_displacement": 0.0005,
                                       "displacement_capacity": 0.6}
    assert config.friction == {"model": "precise", "mu_t0": 0.075, "refinement": 0.5,
                               "design_velocity": 0.4, "initial_temperature": 20.0}
    assert config.building.fixed_base_modes().periods[0] == pytest.approx(0.5, rel=1e-12)


@pytest.mark.parametrize(("key", "value", "model"), [("refinement", 3.0, "precise"),
                                                     ("design_velocity", -1.0, "simplified"),
                                                     ("mu0", 0.0, "precise"),
                                                     ("mu_t0", 1.5, "constant")])
def test_every_friction_parameter_is_checked_whatever_the_model(tmp_path, key, value, model):
    text = MINIMAL + f'[friction]\nmodel = "{model}"\n{key} = {value}\n'
    with pytest.raises(ConfigError, match=rf"\[friction\] '{key}' must be a number in"):
        load_config(_file(tmp_path, text))


def test_unknown_key_names_the_closest_allowed_one(tmp_path):
    with pytest.raises(ConfigError, match=r"unknown key\(s\) 'effective_raduis' \(did you mean "
                       r"'effective_radius'\?\) in \[bearing\]; allowed: \["):
        load_config(_file(tmp_path, MINIMAL.replace("effective_radius", "effective_raduis")))


@pytest.mark.parametrize(("extra", "key"), [
    ('[analysis]\nalpha = -0.1\n', "'alpha' is ignored"),
    ('[analysis]\nintegrator = "newmark"\nalpha = -0.1\n', "'alpha' is ignored"),
    ("[building.damping]\nratio = 0.05\n", "'ratio' is ignored"),
    ('[building.damping]\nkind = "modal"\nmodes = [1, 2]\n', "'modes' is ignored"),
    ('[building.damping]\nkind = "modal"\nratio = 0.05\nratios = 0.02\n', "'ratios' is ignored"),
])
def test_settings_without_effect_are_warned_about(tmp_path, extra, key):
    with pytest.warns(ConfigWarning, match=key):
        load_config(_file(tmp_path, MINIMAL + extra))


def test_stiffnesses_beside_a_period_warn_that_the_period_is_ignored(tmp_path):
    text = MINIMAL.replace("fixed_base_period = 0.3", "fixed_base_period = 0.3\n"
                           "storey_stiffnesses = [1e8, 1e8]")
    with pytest.warns(ConfigWarning, match=r"\[building\] 'fixed_base_period' is ignored"):
        config = load_config(_file(tmp_path, text))
    assert list(config.building.storey_stiffnesses) == [1e8, 1e8]


def test_hht_takes_the_files_alpha(tmp_path):
    config = load_config(_file(tmp_path, MINIMAL + '[analysis]\nintegrator = "hht"\n'
                                          "alpha = -0.2\n"))
    assert isinstance(config.integrator, HHT) and config.integrator.alpha == -0.2
    from dcfpb.cli.run import integrator_from_args

    assert integrator_from_args(config, "hht", None).alpha == -0.2  # not the default -0.05
    assert integrator_from_args(config, "hht", -0.1).alpha == -0.1


@pytest.mark.parametrize(("extra", "match"), [
    ('[building.damping]\nkind = "modal"\nratio = [0.02, 0.03, 0.04]\n',
     r"'ratio' must hold one ratio per mode \(2\)"),
    ("[building.damping]\nmodes = [1, 3]\n", r"2 distinct mode numbers in \[1, 2\]"),
])
def test_damping_rules_between_keys(tmp_path, extra, match):
    with pytest.raises(ConfigError, match=match):
        load_config(_file(tmp_path, MINIMAL + extra))


def test_single_storey_rayleigh_default_modes_are_refused_with_the_way_out(tmp_path):
    text = MINIMAL.replace("[1e5, 1e5]", "[1e5]")
    with pytest.raises(ConfigError, match=r"Got \[1, 2\] \(an array\) \(the default\)"):
        load_config(_file(tmp_path, text))
    load_config(_file(tmp_path, text + '[building.damping]\nkind = "modal"\n'))


def test_missing_keys_are_named(tmp_path):
    with pytest.raises(ConfigError, match=r"\[building\] needs 'storey_stiffnesses' or "
                       "'fixed_base_period'"):
        load_config(_file(tmp_path, MINIMAL.replace("fixed_base_period = 0.3", "")))
    with pytest.raises(ConfigError, match=r"\[bearing\] needs 'slider_diameter'"):
        load_config(_file(tmp_path, MINIMAL.replace("slider_diameter = 0.3", "")))


def test_encodings(tmp_path):
    path = tmp_path / "b.toml"
    path.write_bytes(b"\xef\xbb\xbf" + MINIMAL.encode())
    assert load_config(path).n_bearings == 1
    path.write_bytes(('name = "Gebäude"\n' + MINIMAL).encode("latin-1"))
    with pytest.raises(ConfigError, match=r"not UTF-8 text \(byte 0xe4 at offset 11\); save "
                       "it as UTF-8"):
        load_config(path)
    path.write_bytes(b"\xef\xbb\xbf" + b'name = "\xe4"\n' + MINIMAL.encode())
    with pytest.raises(ConfigError, match=r"byte 0xe4 at offset 11\)"):  # counted from the BOM
        load_config(path)


def test_deep_nesting_and_huge_files_are_refused(tmp_path):
    path = _file(tmp_path, "name = " + "[" * 5000 + "]" * 5000 + "\n" + MINIMAL)
    with pytest.raises(ConfigError, match="nested too deeply"):
        load_config(path)
    with path.open("wb") as handle:
        handle.truncate(10_000_001)
    with pytest.raises(ConfigError, match="is not a building file"):
        load_config(path)


def test_a_table_where_none_belongs_is_an_unknown_key(tmp_path):
    text = MINIMAL + "[bearing.extra]\n"
    with pytest.raises(ConfigError, match=r"unknown key\(s\) 'extra' in \[bearing\]"):
        load_config(_file(tmp_path, text))
