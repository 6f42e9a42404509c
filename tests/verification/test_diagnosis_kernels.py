"""The diagnosis's building blocks against answers known exactly.

The return map of an imposed history is the element's; a noise-free constant-friction or
precise-model test calibrates back to the parameters that made it; the contact-temperature
rise under the element's own heat flux is the element's temperature; reversals, travel and
noise levels of a sine are what the sine says; the solver finds a known minimum.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.optimize import least_squares

from isolator.bearing import DCFPBearing
from isolator.diagnosis import BaselineSpec, BearingRecord, Campaign
from isolator.diagnosis.baseline import calibrate
from isolator.diagnosis.features import contact_temperature_rise, kinematic_features
from isolator.diagnosis.fitting import HoldOut
from isolator.diagnosis.kinematics import (
    hysteretic_variable,
    noise_std,
    reversal_travel,
    turning_points,
)
from isolator.diagnosis.solver import levenberg_marquardt
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import MonitorLine
from isolator.protocols import sine
from isolator.testrig import run_test

D, R = 0.3, 4.5
N = 60e6 * np.pi * 0.15**2


def _campaign(bearing, amplitudes=(0.1, 0.2), cycles=3):
    tests = []
    for k, amplitude in enumerate(amplitudes):
        h = sine(amplitude, 2.5, cycles, 0.01)
        r = run_test(bearing, h.time, h.displacement, h.velocity)
        tests.append(BearingRecord(f"t{k}", r.time, r.displacement, r.force,
                                   np.full(r.time.size, N), r.velocity))
    return Campaign(tuple(tests), R, D)


def test_return_map_is_the_elements():
    bearing = DCFPBearing(R, D, N, ConstantFriction(0.05), yield_displacement=8e-4)
    h = sine(0.15, 2.5, 2, 0.01)
    r = run_test(bearing, h.time, h.displacement, h.velocity)
    z = hysteretic_variable(h.displacement, 8e-4)
    assert np.max(np.abs(z * r.mu * N - r.friction_force)) <= 1e-9 * N


def test_constant_baseline_calibrates_back_exactly():
    friction = ConstantFriction(0.05)
    campaign = _campaign(DCFPBearing(R, D, N, friction, yield_displacement=5e-4))
    features, _ = kinematic_features(campaign)
    fit = calibrate(campaign, features, BaselineSpec("constant"))
    assert fit.parameters["mu"] == pytest.approx(friction.mu, rel=1e-4)
    assert fit.parameters["yield_displacement"] == pytest.approx(5e-4, rel=0.05)
    residual = fit.features.force - fit.features.baseline_force
    assert np.sqrt(np.mean(residual**2)) < 1e-3 * friction.mu * N


def test_precise_baseline_calibrates_mu_t0_back():
    campaign = _campaign(DCFPBearing(R, D, N, PTVFriction(0.06)), amplitudes=(0.15, 0.25))
    features, _ = kinematic_features(campaign)
    fit = calibrate(campaign, features, BaselineSpec("precise"))
    assert fit.parameters["mu_t0"] == pytest.approx(0.06, rel=2e-3)
    assert fit.iterations >= 2  # heating makes mu(t) not proportional to mu_t0
    residual = fit.features.force - fit.features.baseline_force
    assert np.sqrt(np.mean(residual**2)) < 5e-3 * 0.06 * N


def test_temperature_rise_under_the_elements_flux_is_its_temperature():
    friction = PTVFriction(0.05, heating=MonitorLine(), dependencies=())
    bearing = DCFPBearing(R, D, N, friction)
    h = sine(0.2, 2.5, 3, 0.01)
    r = run_test(bearing, h.time, h.displacement, h.velocity)
    rise = contact_temperature_rise(r.time, r.displacement / 2.0, r.heat_flux, MonitorLine(),
                                    0.15, friction.thermal)
    assert r.temperature.max() > 100.0
    assert np.max(np.abs(rise + 20.0 - r.temperature)) <= 1e-9 * r.temperature.max()


def test_reversals_travel_and_noise_of_a_noisy_sine():
    rng = np.random.default_rng(3)
    t = np.arange(0.0, 10.0, 0.01)
    u = 0.2 * np.sin(2.0 * np.pi * t / 2.5) + rng.normal(0.0, 5e-5, t.size)
    assert noise_std(u, order=4) == pytest.approx(5e-5, rel=0.1)
    turns = turning_points(u, 6.0 * 5e-5)
    assert turns.size == 9  # the start and eight peaks
    peaks = np.arange(1, 9) * 125 - 62.5  # samples of the true peaks
    assert np.max(np.abs(turns[1:] - peaks)) <= 12
    since, travel, half = reversal_travel(u, turns)
    assert travel[-1] == pytest.approx(0.8 * 4, rel=0.01)
    assert half.max() == 8 and since.min() == 0.0


def test_holdout_schemes():
    bearing = DCFPBearing(R, D, N, ConstantFriction(0.05))
    two, _ = kinematic_features(_campaign(bearing))
    assert HoldOut.of(two).scheme == "alternate cycles"
    three, _ = kinematic_features(_campaign(bearing, amplitudes=(0.1, 0.15, 0.2), cycles=2))
    holdout = HoldOut.of(three)
    assert holdout.scheme == "leave-one-test-out" and len(holdout.folds) == 3
    every = np.concatenate([held for _, held in holdout.folds])
    assert np.array_equal(np.sort(every), np.arange(len(three)))
    many, _ = kinematic_features(_campaign(bearing, amplitudes=np.linspace(0.05, 0.2, 8),
                                           cycles=2))
    assert HoldOut.of(many).scheme == "tests held out in 6 groups"


def test_solver_finds_a_known_minimum_within_bounds():
    x = np.linspace(0.0, 5.0, 4000)
    y = 2.0 * np.exp(-0.7 * x) + 0.3 * np.sin(3.0 * x)

    def residual(p):
        return p[0] * np.exp(-p[1] * x) + p[2] * np.sin(p[3] * x) - y

    low, high = np.array([0.0, 0.0, -1.0, 2.5]), np.array([5.0, 3.0, 1.0, 3.5])
    ours = levenberg_marquardt(residual, np.array([1.0, 0.2, 0.0, 2.9]), low, high)
    assert ours.x == pytest.approx([2.0, 0.7, 0.3, 3.0], abs=1e-6)
    bounded = levenberg_marquardt(residual, np.array([1.0, 0.2, 0.0, 2.9]), low,
                                  np.array([5.0, 0.5, 1.0, 3.5]))
    scipy = least_squares(residual, [1.0, 0.2, 0.0, 2.9],
                          bounds=(low, np.array([5.0, 0.5, 1.0, 3.5])))
    assert bounded.x[1] == pytest.approx(0.5)  # held at the bound
    assert bounded.cost == pytest.approx(2.0 * scipy.cost, rel=1e-6)


def test_negated_campaign_gives_the_same_gap_and_verdict():
    """Negating displacement and force is a change of sign convention, not of physics; the
    direction ratio of the asymmetry candidate inverts."""
    from isolator.diagnosis import diagnose

    friction = PTVFriction(0.06, heating=None, dependencies=("velocity",))
    campaign = _campaign(DCFPBearing(R, D, N, friction), amplitudes=(0.05, 0.1, 0.2))
    rng = np.random.default_rng(5)
    noisy = tuple(BearingRecord(t.name, t.time, t.displacement,
                                t.force + rng.normal(0.0, 0.005 * 0.06 * N, len(t)),
                                t.axial_force, t.velocity) for t in campaign.tests)
    flipped = tuple(BearingRecord(t.name, t.time, -t.displacement, -t.force, t.axial_force,
                                  -t.velocity) for t in noisy)
    a = diagnose(Campaign(noisy, R, D), "constant").to_json()
    b = diagnose(Campaign(flipped, R, D), "constant").to_json()
    assert a["verdict"] == b["verdict"] == ["velocity"]
    assert a["gap"]["value"] == pytest.approx(b["gap"]["value"], rel=1e-6)
    assert a["chosen"]["gap_after"] == pytest.approx(b["chosen"]["gap_after"], rel=1e-4)
    ratio = {s["name"]: s for s in a["effects"]}["asymmetry"]["parameters"]["direction_ratio"]
    flip = {s["name"]: s for s in b["effects"]}["asymmetry"]["parameters"]["direction_ratio"]
    assert ratio * flip == pytest.approx(1.0, rel=1e-3)
    again = diagnose(Campaign(noisy, R, D), "constant").to_json()
    again.pop("wall_time"), a.pop("wall_time")
    assert json.dumps(again, sort_keys=True) == json.dumps(a, sort_keys=True)  # deterministic
