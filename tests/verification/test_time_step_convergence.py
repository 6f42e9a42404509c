"""Temperature and EDC converge as the time step is halved (paper test set-up, 3 cycles)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.experiments import protocol_bearing
from isolator.protocols import sine
from isolator.testrig import run_test

STEPS = (0.005, 0.0025, 0.00125)
REFERENCE_STEP = 0.000625


def _run(model, dt):
    history = sine(0.3, 4.26, 3, dt)
    bearing = protocol_bearing(model, design_velocity=2 * math.pi * 0.3 / 4.26)
    result = run_test(bearing, history.time, history.displacement, history.velocity)
    return result, np.array([c.EDC for c in result.characteristics()])


@pytest.mark.slow
@pytest.mark.parametrize("model", ["precise", "simplified"])
def test_temperature_and_edc_converge_as_dt_halves(model):
    reference, edc_reference = _run(model, REFERENCE_STEP)
    grid = np.linspace(0.0, reference.time[-1], 4001)
    t_reference = np.interp(grid, reference.time, reference.temperature)
    temperature_errors, edc_errors = [], []
    for dt in STEPS:
        result, edc = _run(model, dt)
        t = np.interp(grid, result.time, result.temperature)
        temperature_errors.append(float(np.sqrt(np.mean((t - t_reference) ** 2))))
        edc_errors.append(float(np.max(np.abs(edc - edc_reference) / edc_reference)))
    assert np.all(np.diff(temperature_errors) < 0.0), temperature_errors
    assert np.all(np.diff(edc_errors) < 0.0), edc_errors
    assert temperature_errors[-1] < 0.2  # [degC] against a rise of over 100 degC
    assert edc_errors[-1] < 1e-3
