"""The heat a named friction law implies for a baseline that heats (issue 21, one direction).

A precise baseline told ``--without velocity`` computes its heat input with a mu that lacks the
speed effect, so its temperature factor is off by a share that follows the missing law. Once
the law is named, a ``heating`` beside it must earn its keep over the law *with the heat it
implies* (:mod:`isolator.diagnosis.implied`), else it is only the baseline's own heat computed
with the wrong mu:

- :func:`isolator.diagnosis.implied.implied_heat`: none for a baseline that does not heat; no
  change for the baseline's own friction power; a friction lower than the baseline's heats
  less, so the implied temperature factor rises, by the paper's -0.007 per degC, linearly in
  the change;
- a campaign of the full precise model (our own element) told ``precise --without velocity``
  is diagnosed ``velocity`` without ``heating`` (it was ``velocity, heating, unexplained``).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from isolator.diagnosis import diagnose
from isolator.diagnosis.baseline import BaselineSpec, calibrate
from isolator.diagnosis.features import kinematic_features
from isolator.diagnosis.implied import implied_heat, temperature_slope
from validation.diagnosis.outside.cases import Case, S
from validation.diagnosis.outside.write import _write_case
from validation.diagnosis.score import load_case, named

# the package's full precise model (Eq. 7), told precise without velocity: tune variant VA6
# of validation/diagnosis/variants_1d.py (ASCE-like tests after nights, 200 Hz)
CASE = Case("VA6", ("velocity",), "tune", "package", "full precise model, told precise without "
            "velocity", (S(0.1, 4.26, 3), S(0.2, 4.26, 3), S(0.02, 8.4, 2)),
            {"dependencies": ("pressure", "temperature"), "u_y": 3.0e-4}, dt=0.005,
            noise=0.006, baseline="precise", without=("velocity",))


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    out = tmp_path_factory.mktemp("implied") / "case"
    _write_case(CASE, out, np.random.default_rng([2026, 1005]))
    return out


def test_the_implied_heat_follows_the_change_of_friction_power(folder):
    campaign, spec = load_case(folder)
    assert json.loads((folder / "bearing.json").read_text())["without"] == ["velocity"]
    features, _ = kinematic_features(campaign)
    fitted = calibrate(campaign, features, spec)
    assert implied_heat(campaign, fitted.features, BaselineSpec("constant")) is None
    assert implied_heat(campaign, fitted.features,
                        BaselineSpec("precise", ("heating",))) is None
    log_change = implied_heat(campaign, fitted.features, spec)
    n = len(fitted.features)
    assert np.allclose(log_change(np.ones(n)), 0.0)
    cooler = log_change(np.full(n, 0.8))  # 20 % less friction power: a cooler contact
    assert np.all(cooler >= -1e-12) and cooler.max() > 0.0
    assert np.allclose(log_change(np.full(n, 0.6)), 2.0 * cooler, rtol=1e-6, atol=1e-12)
    assert temperature_slope() == pytest.approx(-0.007)


def test_a_precise_baseline_told_without_velocity_names_velocity_not_heating(folder):
    campaign, spec = load_case(folder)
    d = diagnose(campaign, spec)
    assert named(d.verdict) == {"velocity"}, d.verdict
