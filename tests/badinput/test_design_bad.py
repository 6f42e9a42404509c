"""Bad input to the design layer raises InputError naming the argument."""

from __future__ import annotations

from pathlib import Path

import pytest

from dcfpb.common.errors import InputError
from structures.config import load_config
from structures.design import PropertyModification, Site, elf, prototype_test

ROOT = Path(__file__).resolve().parents[2]
LAM = PropertyModification.overall(1.8, 0.6)


@pytest.fixture(scope="module")
def planar():
    return load_config(ROOT / "examples" / "five_storey.toml")


@pytest.mark.parametrize("kwargs, name", [
    ({"overall_max": 1.8, "overall_min": 1.2}, "overall_min"),
    ({"overall_max": 0.9, "overall_min": 0.6}, "overall_max"),
    ({"overall_max": 1.8}, "overall_min"),
    ({"test_min": 1.2}, "test_min"),
    ({"ae_max": 0.9}, "ae_max"),
    ({"spec_min": 0.0}, "spec_min"),
    ({"spec_max": -1.0}, "spec_max"),
    ({"test_max": 1.2, "overall_max": 1.8, "overall_min": 0.6}, "test_max"),
    ({"test_max": 1.2, "test_heating_max": 1.3}, "test_heating_max"),
    ({"test_min": 0.8, "test_heating_min": 0.7}, "test_heating_min"),
    ({"adjustment": 1.5}, "adjustment"),
])
def test_property_modification_names_the_bad_factor(kwargs, name):
    with pytest.raises(InputError, match=repr(name)):
        PropertyModification(**kwargs)


@pytest.mark.parametrize("args, name", [
    ((1.5, -0.6), "S_M1"), ((0.0, 0.6), "S_MS"), ((1.5, 0.6, -1.0), "T_L"),
    ((150.0, 0.6), "S_MS"),  # 150 g: a value in % or cm/s^2
])
def test_site_names_the_bad_value(args, name):
    with pytest.raises(InputError, match=repr(name)):
        Site(*args)


@pytest.mark.parametrize("kwargs, name", [
    ({"R": -1.0}, "R"), ({"R": 2.0, "mu": 1.5}, "mu"), ({"R": 2.0, "I_e": 2.0}, "I_e"),
    ({"R": 2.0, "storey_heights": [3.5, 3.5]}, "storey_heights"),
    ({"R": 2.0, "storey_heights": -3.0}, "storey_heights"),
    ({"R": 2.0, "model": "magic"}, "model"),
    ({"R": 2.0, "wind_base_shear": -1.0}, "wind_base_shear"),
    ({"R": 2.0, "abrupt_transition": "yes"}, "abrupt_transition"),
])
def test_elf_names_the_bad_argument(planar, kwargs, name):
    kwargs = {"storey_heights": 3.5, **kwargs}
    with pytest.raises(InputError, match=repr(name)):
        elf(planar, Site(1.5, 0.6), LAM, **kwargs)


def test_elf_needs_storey_heights_in_one_direction(planar):
    with pytest.raises(InputError, match="'storey_heights'"):
        elf(planar, Site(1.5, 0.6), LAM, R=2.0)


def test_elf_refuses_lambda_that_is_no_property_modification(planar):
    with pytest.raises(InputError, match="'lambda_'"):
        elf(planar, Site(1.5, 0.6), 1.8, R=2.0, storey_heights=3.5)
    with pytest.raises(InputError, match="'site'"):
        elf(planar, 0.6, LAM, R=2.0, storey_heights=3.5)


def test_elf_refuses_lambda_that_takes_mu_past_one(planar):
    with pytest.raises(InputError, match="'lambda_'"):
        elf(planar, Site(1.5, 0.6), PropertyModification.overall(9.0, 0.6), R=2.0, mu=0.2,
            storey_heights=3.5)


@pytest.mark.parametrize("args, kwargs, name", [
    ((0.3, 0.2, 3.0), {}, "D_TM"), ((-0.3, 0.36, 3.0), {}, "D_M"),
    ((0.3, 0.36, 0.0), {}, "T_M"), ((0.3, 0.7, 3.0), {}, "D_TM"),
    ((0.3, 0.36, 3.0), {"item2": "b"}, "item2"),
])
def test_prototype_names_the_bad_argument(planar, args, kwargs, name):
    with pytest.raises(InputError, match=repr(name)):
        prototype_test(planar, *args, model="constant", **kwargs)
