"""Property modification factors of ASCE/SEI 7-16 Sec. 17.2.8.4 (structures.design.properties):
lambda assembled from its parts by hand, applied to every friction model, and the warning where
a test factor that includes heating meets a model that computes heating."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from dcfpb.common.errors import InputWarning
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine
from structures.config import load_config
from structures.design import PropertyModification, Site, elf

ROOT = Path(__file__).resolve().parents[2]


def test_lambda_assembled_from_its_parts():
    lam = PropertyModification(ae_max=1.2, ae_min=0.9, test_max=1.3, test_min=0.8,
                               spec_max=1.15, spec_min=0.85)
    # Eq. 17.2-1/2: (1 + 0.75 (1.2 - 1)) 1.3 1.15 and (1 - 0.75 (1 - 0.9)) 0.8 0.85
    assert lam.lambda_max == pytest.approx(1.15 * 1.3 * 1.15, rel=1e-15)  # 1.719250
    assert lam.lambda_min == pytest.approx(0.925 * 0.8 * 0.85, rel=1e-15)  # 0.629
    assert lam.factor("upper") == lam.lambda_max and lam.factor("lower") == lam.lambda_min
    assert len(lam.limit_notes()) == 2  # 1.72 < 1.8 and 0.629 > 0.6: both named
    assert "17.2.8.4" in lam.limit_notes()[0]


def test_overall_values_and_defaults():
    lam = PropertyModification.overall(1.8, 0.6)
    assert (lam.lambda_max, lam.lambda_min) == (1.8, 0.6)
    assert lam.limit_notes() == []
    nominal = PropertyModification()
    assert (nominal.lambda_max, nominal.lambda_min) == (1.0, 1.0)
    assert lam.to_dict()["lambda_max"] == 1.8


@pytest.mark.parametrize("friction, key", [
    (ConstantFriction(mu0=0.04), "mu0"),
    (PTVFriction(mu_t0=0.075, heating=None), "mu_t0"),
])
def test_applied_to_the_reference_coefficient_without_warning(friction, key):
    lam = PropertyModification.overall(1.8, 0.6, test_includes_heating=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no heating model: nothing to warn
        upper, lower = lam.apply(friction, "upper"), lam.apply(friction, "lower")
    assert getattr(upper, key) == pytest.approx(1.8 * getattr(friction, key), rel=1e-15)
    assert getattr(lower, key) == pytest.approx(0.6 * getattr(friction, key), rel=1e-15)


@pytest.mark.parametrize("heating", [MonitorLine(), CentrePoint(refinement=0.5)])
def test_heating_counted_twice_is_named(heating):
    friction = PTVFriction(mu_t0=0.075, heating=heating)
    lam = PropertyModification(test_max=1.5, test_min=0.7, ae_max=1.3,
                               test_includes_heating=True)
    with pytest.warns(InputWarning, match="counts heating twice"):
        scaled = lam.apply(friction, "upper")
    assert scaled.mu_t0 == pytest.approx(0.075 * lam.lambda_max)


def test_named_heating_part_is_left_to_the_simulation():
    precise = PTVFriction(mu_t0=0.075, heating=MonitorLine())
    lam = PropertyModification(test_max=1.5, test_min=0.7, ae_max=1.3, test_heating_max=1.25,
                               test_heating_min=0.8)
    assert lam.includes_heating
    with pytest.warns(InputWarning, match="left to the simulation"):
        upper = lam.apply(precise, "upper")
    with pytest.warns(InputWarning, match="left to the simulation"):
        lower = lam.apply(precise, "lower")
    assert upper.mu_t0 == pytest.approx(0.075 * (1.225 * 1.5) / 1.25, rel=1e-14)
    assert lower.mu_t0 == pytest.approx(0.075 * 0.7 / 0.8, rel=1e-14)
    constant = ConstantFriction(mu0=0.04)  # no heating in the model: the whole factor
    assert lam.apply(constant, "upper").mu0 == pytest.approx(0.04 * 1.225 * 1.5, rel=1e-14)


def test_elf_warns_of_lambda_outside_the_limits():
    config = load_config(ROOT / "examples" / "five_storey_plan.toml")
    with pytest.warns(InputWarning, match="17.2.8.4") as record:
        result = elf(config, Site(1.5, 0.6), PropertyModification.overall(1.5, 0.8), R=2.0)
    assert len(record) == 2
    assert len([n for n in result.notes if "17.2.8.4" in n]) == 2
