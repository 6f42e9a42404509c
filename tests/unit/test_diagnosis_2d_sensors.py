"""The diagnosis in two directions calibrates its sensors' faults and gains as nuisance
(issue 21, the bidirectional tune variants).

A campaign made by the model itself (a circle and a figure-eight, white force noise) is
measured through a faulty chain: the y displacement sensor reading 2.5 % high, the x load
cell stuck for 20 samples and two spikes of a fifth of the peak force. Each is a nuisance the
panel declares; left in, together they held a residual of 2-3 % of the RMS force that the
verdict read as a gap (``unexplained`` where ``none`` was due). Checked: the faults are found
and bridged, none on clean data; the gain is read on the right channel (a load cell's gain on
the load cell, a displacement sensor's on the displacement), none on clean data; the verdict
on the faulty campaign is ``none`` with notes saying what was corrected. About 5 s.
"""

from __future__ import annotations

import re

import numpy as np

from isolator.diagnosis.baseline import BaselineSpec
from isolator.diagnosis.data import BearingRecord2D, Campaign2D
from isolator.diagnosis.two_directions import (
    _calibrate,
    _channel_gain,
    _fault_summary,
    _prepare,
    _repair_faults,
    diagnose_2d,
    kinematic_state,
)

RADIUS, SLIDER, AXIAL, MU = 2.0, 0.3, 1.0e6, 0.05
YIELD, LAG = 5.0e-4, 0.5  # [m], [samples]
NOISE = 0.005 * MU * AXIAL  # [N]
STUCK = (300, 320)  # samples of the first test's x force held at one reading
SPIKES = ((1, 120), (1, 610))  # (test, sample) of the y force's spikes, off its reversals


def _orbits() -> tuple[np.ndarray, list[np.ndarray]]:
    dt = 0.01
    t = np.arange(0.0, 8.0, dt)
    circle = 0.08 * np.column_stack([np.sin(2 * np.pi * t / 4.0),
                                     1.0 - np.cos(2 * np.pi * t / 4.0)])
    eight = np.column_stack([0.1 * np.sin(2 * np.pi * t / 4.0),
                             0.06 * np.sin(4 * np.pi * t / 4.0)])
    return t, [circle, eight]


def _campaign(displacement_gain: float = 0.0, force_gain: float = 0.0,
              faults: bool = False, seed: int = 3) -> Campaign2D:
    """The model's campaign with noise, measured through the chain asked for."""
    t, orbits = _orbits()
    clean = Campaign2D(tuple(BearingRecord2D(f"{k}", t, u, np.zeros_like(u),
                                             np.full(t.size, AXIAL))
                             for k, u in enumerate(orbits)), RADIUS, SLIDER)
    d = _prepare(clean, smooth=False)
    ub, z = kinematic_state(d, YIELD, LAG * d.dt)
    force = AXIAL * (ub / RADIUS + MU * z)
    rng = np.random.default_rng(seed)
    records = []
    for k, u in enumerate(orbits):
        f = force[d.test == k] + rng.normal(0.0, NOISE, (t.size, 2))
        f[:, 1] *= 1.0 + force_gain
        if faults:
            if k == 0:
                f[STUCK[0]:STUCK[1], 0] = f[STUCK[0], 0]
            for test, i in SPIKES:
                if test == k:
                    f[i, 1] += 0.2 * np.max(np.abs(f))
        measured = u * np.array([1.0, 1.0 + displacement_gain])
        records.append(BearingRecord2D(f"{k}", t, measured, f, np.full(t.size, AXIAL)))
    return Campaign2D(tuple(records), RADIUS, SLIDER)


def _gain(campaign: Campaign2D):
    d = _prepare(campaign, smooth=False)
    return _channel_gain(d, _calibrate(d, BaselineSpec("constant")))


def test_a_stuck_run_and_spikes_are_found_and_bridged():
    repaired, notes = _repair_faults(_campaign(faults=True))
    assert len(notes) == 2
    assert "force_x stuck at 3.000 s (20 samples)" in notes[0]
    assert re.search(r"force_y spike at \d+\.\d{3} s, \d+\.\d{3} s$", notes[1])
    truth = _campaign()
    for got, want in zip(repaired.tests, truth.tests, strict=True):
        error = np.abs(got.force - want.force)
        assert error.max() < 6.0 * NOISE  # bridged to within the noise
    assert _repair_faults(truth)[1] == []


def test_the_fault_note_lists_a_few_faults_of_a_kind_and_counts_the_rest():
    said = [("force_x", "spike", f"{0.1 * k:.3f} s") for k in range(1, 11)]
    said.append(("force_y", "stuck", "2.000 s (20 samples)"))
    assert _fault_summary(said) == ("force_x spike at 0.100 s, 0.200 s, 0.300 s, 0.400 s and "
                                    "6 more; force_y stuck at 2.000 s (20 samples)")


def test_a_sensor_gain_is_read_on_its_own_channel():
    found = _gain(_campaign(displacement_gain=0.025))
    assert found is not None and found.corrected
    assert found.channel == "displacement_y"
    assert abs(found.gain - 0.025) < 0.005
    assert np.all(np.abs(found.per_test - 0.025) < 0.01)
    found = _gain(_campaign(force_gain=0.03))
    assert found is not None and found.channel == "force_y"
    assert abs(found.gain - 0.03) < 0.005
    assert _gain(_campaign()) is None


def test_faults_and_a_displacement_gain_are_nuisance_not_a_gap():
    result = diagnose_2d(_campaign(displacement_gain=0.025, faults=True), "constant")
    assert result.verdict == ["none"]
    notes = " ".join(result.notes)
    assert "sensor faults bridged" in notes
    read = re.search(r"the y displacement channel reads \+(\d\.\d) %", notes)
    assert read and 2.0 <= float(read.group(1)) <= 3.0
