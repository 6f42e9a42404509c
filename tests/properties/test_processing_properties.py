"""Properties of processing and scaling that hold for any record (hypothesis)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from groundmotions.processing import (
    arias_intensity,
    baseline_corrected,
    filtered,
    resampled,
    significant_duration,
    velocity_and_displacement,
    zero_residuals,
)
from groundmotions.records import GroundMotion
from groundmotions.scaling import TargetSpectrum, scale_suite

accelerations = arrays(
    np.float64,
    st.integers(min_value=40, max_value=200),
    elements=st.floats(-20.0, 20.0, allow_nan=False, allow_subnormal=False),
)
steps = st.sampled_from([0.005, 0.01, 0.02, 0.025])
fast = settings(max_examples=30, deadline=None)

PROCESSES = {
    "baseline_corrected": lambda m: baseline_corrected(m, 2),
    "zero_residuals": lambda m: zero_residuals(m, 5),
    "filtered": lambda m: filtered(m, low=0.5, high=0.2 / m.dt, order=2),
    "resampled finer": lambda m: resampled(m, m.dt / 3),
    "resampled coarser": lambda m: resampled(m, 2 * m.dt),
}


@fast
@given(accelerations, steps, st.sampled_from(sorted(PROCESSES)))
def test_processing_never_mutates_its_input(acc, dt, name):
    motion = GroundMotion(acc, dt, "x", {"station": "S"}, ("read",))
    before = motion.acceleration.copy()
    out = PROCESSES[name](motion)
    np.testing.assert_array_equal(motion.acceleration, before)
    assert motion.processing == ("read",) and motion.metadata == {"station": "S"}
    assert out is not motion and out.acceleration is not motion.acceleration
    assert out.processing[:-1] == ("read",) and len(out.processing) == 2
    assert out.metadata == motion.metadata and out.metadata is not motion.metadata
    assert not out.acceleration.flags.writeable


@fast
@given(accelerations, steps, st.floats(0.01, 100.0))
def test_processing_is_linear_in_the_record(acc, dt, k):
    """Each correction and filter is a linear operator: process(k a) = k process(a)."""
    motion = GroundMotion(acc, dt)
    for process in PROCESSES.values():
        np.testing.assert_allclose(process(motion.scaled(k)).acceleration,
                                   k * process(motion).acceleration,
                                   rtol=1e-9, atol=1e-9 * k * (1 + motion.pga))


@fast
@given(accelerations, steps)
def test_zero_residuals_always_ends_at_rest(acc, dt):
    motion = zero_residuals(GroundMotion(acc, dt))
    velocity, displacement = velocity_and_displacement(motion.acceleration, dt)
    scale = 1.0 + np.max(np.abs(acc))
    assert abs(velocity[-1]) < 1e-10 * scale * motion.duration
    assert abs(displacement[-1]) < 1e-10 * scale * motion.duration**2


@fast
@given(accelerations, steps, st.integers(2, 6))
def test_resample_round_trip_is_exact(acc, dt, factor):
    motion = GroundMotion(acc, dt)
    fine = resampled(motion, dt / factor)
    assert fine.npts == factor * (motion.npts - 1) + 1
    back = resampled(fine, dt, anti_alias=False)
    np.testing.assert_array_equal(back.acceleration, motion.acceleration)
    assert back.npts == motion.npts and back.dt == dt


@fast
@given(accelerations, steps, st.floats(0.05, 0.45), st.floats(0.55, 1.0))
def test_arias_is_non_decreasing_and_durations_are_ordered(acc, dt, start, stop):
    times, cumulative = arias_intensity(GroundMotion(acc, dt))
    assert np.all(np.diff(cumulative) >= 0.0)
    if cumulative[-1] > 0.0:
        inner = significant_duration(GroundMotion(acc, dt), start, stop)
        outer = significant_duration(GroundMotion(acc, dt), start / 2, (1 + stop) / 2)
        assert 0.0 <= inner <= outer + 1e-12 <= times[-1] + 1e-12


TARGET = TargetSpectrum([0.05, 0.3, 1.0, 3.0], [5.0, 9.0, 4.0, 1.0])
SMALL = arrays(np.float64, st.integers(min_value=30, max_value=80),
               elements=st.floats(-5.0, 5.0, allow_nan=False, allow_subnormal=False)
               ).filter(lambda a: np.ptp(a) > 1e-3)


@settings(max_examples=15, deadline=None)
@given(st.lists(SMALL, min_size=1, max_size=3), st.floats(0.01, 100.0), st.floats(0.01, 10.0))
def test_scaling_is_linear_in_records_and_target(records, k, c):
    """Scaling k times the records to c times the target gives factors c / k times as large,
    and the same scaled records to round-off (targets up to 9.2 g, any factor: max_factor=None
    turns the bounds on factors off)."""
    motions = [GroundMotion(a, 0.01, f"r{i}") for i, a in enumerate(records)]
    base = scale_suite(motions, TARGET, (0.1, 1.5), n_periods=8, max_factor=None)
    target = TargetSpectrum(TARGET.periods, c * TARGET.sa)
    other = scale_suite([m.scaled(k) for m in motions], target, (0.1, 1.5), n_periods=8,
                        max_factor=None)
    np.testing.assert_allclose(other.scale_factors, base.scale_factors * c / k, rtol=1e-9)
    assert abs(base.min_ratio - 1.0) < 1e-12 and abs(other.min_ratio - 1.0) < 1e-12
    for a, b in zip(base.motions, other.motions, strict=True):
        np.testing.assert_allclose(b.acceleration, c * a.acceleration, rtol=1e-9,
                                   atol=1e-12 * c * (1.0 + a.pga))
