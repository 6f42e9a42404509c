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
  is diagnosed ``velocity`` without ``heating`` (it was ``velocity, heating, unexplained``);
- the chosen model carries that heat (:meth:`isolator.diagnosis.decision.Problem.carried`:
  the baseline's own physics, never an effect): its held-out gap is smaller than the law's
  without it, the implied heat is named nowhere, and the JSON (``chosen.baseline_heat``) and
  the report and the printed summary say that the baseline's temperature follows the named
  law's friction power.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from dcfpb.cli.diagnose import _lines
from isolator.diagnosis import diagnose
from isolator.diagnosis.baseline import BaselineSpec, calibrate
from isolator.diagnosis.decision import IMPLIED_HEAT
from isolator.diagnosis.features import kinematic_features
from isolator.diagnosis.implied import implied_heat, temperature_slope
from isolator.diagnosis.report import markdown
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


@pytest.fixture(scope="module")
def diagnosis(folder):
    campaign, spec = load_case(folder)
    return diagnose(campaign, spec)


def test_a_precise_baseline_told_without_velocity_names_velocity_not_heating(diagnosis):
    assert named(diagnosis.verdict) == {"velocity"}, diagnosis.verdict


def test_the_chosen_model_carries_the_heat_the_named_law_implies(diagnosis):
    d = diagnosis
    summary = d.to_json()
    chosen = summary["chosen"]
    heat = chosen["baseline_heat"]
    assert heat["follows_named_laws"] and heat["laws"] == ["velocity"]
    assert heat["refits"] >= 1
    # the model reported is the one carrying the heat, and it fits better held out
    assert chosen["gap_after"] == pytest.approx(heat["gap_after_with"])
    assert chosen["gap_after"] < heat["gap_after_without"]
    assert chosen["shrink"] > heat["shrink_without"]
    # the baseline's physics, not an effect: named nowhere, no parameters of its own
    assert IMPLIED_HEAT not in summary["verdict"] and IMPLIED_HEAT not in chosen["names"]
    assert IMPLIED_HEAT not in chosen["parameters"]
    assert all(e["name"] != IMPLIED_HEAT for e in summary["effects"])
    assert set(chosen["confidence"]) <= {"velocity"}
    # a faster friction heats more: the implied rise is mostly positive, the factor below 1
    assert heat["temperature_factor"][0] < 1.0 and heat["temperature_change"][1] > 0.0
    text = markdown(d, summary, [])
    assert "follows the friction power of the named velocity" in text
    assert "Without it the NRMSE after would be" in text
    printed = _lines(summary)  # what dcfpb diagnose prints
    assert any(line.startswith("baseline heat: The baseline's temperature follows the friction "
                               "power of the named velocity") for line in printed)
