"""Properties of records and spectra that hold for any record (hypothesis)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from groundmotions.records import GroundMotion
from groundmotions.spectra import peak_ground_values, response_spectrum, sdof_response, spectrum

PERIODS = np.array([0.0, 0.05, 0.3, 1.0, 3.0])

accelerations = arrays(
    np.float64,
    st.integers(min_value=2, max_value=120),
    # magnitudes below 1e-100 give subnormal spectra, whose rounding no relative bound covers
    elements=st.floats(-20.0, 20.0, allow_nan=False, allow_subnormal=False).map(
        lambda x: 0.0 if abs(x) < 1e-100 else x),
)
steps = st.floats(1e-3, 0.05)
factors = st.floats(-50.0, 50.0, allow_nan=False).filter(lambda k: abs(k) > 1e-3)
dampings = st.floats(0.0, 0.5)

fast = settings(max_examples=40, deadline=None)


@fast
@given(accelerations, steps)
def test_negated_twice_is_the_original(acc, dt):
    motion = GroundMotion(acc, dt, "x")
    twice = motion.negated().negated()
    np.testing.assert_array_equal(twice.acceleration, motion.acceleration)
    assert twice.processing == ("negated", "negated")
    assert motion.processing == ()


@fast
@given(accelerations, steps, factors)
def test_scaled_multiplies_and_round_trips(acc, dt, k):
    motion = GroundMotion(acc, dt)
    scaled = motion.scaled(k)
    np.testing.assert_array_equal(scaled.acceleration, k * motion.acceleration)
    assert scaled.pga == abs(k) * motion.pga
    assert scaled.dt == motion.dt and scaled.npts == motion.npts
    back = scaled.scaled(1.0 / k)
    np.testing.assert_allclose(back.acceleration, motion.acceleration, rtol=1e-14, atol=1e-300)


@fast
@given(accelerations, steps, st.floats(0.0, 1.0))
def test_truncated_keeps_the_prefix(acc, dt, fraction):
    motion = GroundMotion(acc, dt)
    duration = dt + fraction * (motion.duration - dt)
    short = motion.truncated(duration)
    assert 2 <= short.npts <= motion.npts
    assert short.duration <= duration + 1e-9 * dt
    assert duration - short.duration < dt * (1 + 1e-9)
    np.testing.assert_array_equal(short.acceleration, motion.acceleration[: short.npts])


@fast
@given(accelerations, steps, factors, dampings)
def test_spectrum_is_linear_in_the_record(acc, dt, k, damping):
    """Sa of k a equals |k| Sa of a (and Sd, Sv likewise): the oscillator is linear."""
    base = response_spectrum(acc, dt, PERIODS, damping)
    scaled = response_spectrum(k * acc, dt, PERIODS, damping)
    for got, ref in ((scaled.sa, base.sa), (scaled.sd, base.sd), (scaled.sv, base.sv)):
        np.testing.assert_allclose(got, abs(k) * ref, rtol=1e-10, atol=1e-12 * abs(k) * ref.max())


@fast
@given(accelerations, steps, dampings)
def test_negated_record_has_the_same_spectrum_and_a_negated_response(acc, dt, damping):
    motion = GroundMotion(acc, dt)
    np.testing.assert_array_equal(
        spectrum(motion.negated(), PERIODS, damping).sa, spectrum(motion, PERIODS, damping).sa
    )
    u, v = sdof_response(acc, dt, PERIODS[1:], damping)
    u_neg, v_neg = sdof_response(-acc, dt, PERIODS[1:], damping)
    np.testing.assert_array_equal(u_neg, -u)
    np.testing.assert_array_equal(v_neg, -v)


@fast
@given(accelerations, accelerations, steps, dampings)
def test_response_superposes(a1, a2, dt, damping):
    n = min(a1.size, a2.size)
    a1, a2 = a1[:n], a2[:n]
    u1, _ = sdof_response(a1, dt, PERIODS[1:], damping)
    u2, _ = sdof_response(a2, dt, PERIODS[1:], damping)
    u12, _ = sdof_response(a1 + a2, dt, PERIODS[1:], damping)
    scale = max(np.abs(u1).max(), np.abs(u2).max(), 1e-300)
    np.testing.assert_allclose(u12, u1 + u2, rtol=0, atol=1e-10 * scale)


@fast
@given(accelerations, steps, dampings, st.integers(1, 30))
def test_leading_quiet_samples_only_delay_the_response(acc, dt, damping, lead):
    """From rest, a record that starts at zero and is preceded by zeros gives the same
    response, shifted: the recurrence is time invariant."""
    acc = np.concatenate(([0.0], acc))
    u, v = sdof_response(acc, dt, PERIODS[1:], damping)
    u_late, v_late = sdof_response(np.concatenate((np.zeros(lead), acc)), dt, PERIODS[1:], damping)
    np.testing.assert_array_equal(u_late[:lead], 0.0)
    np.testing.assert_allclose(u_late[lead:], u, rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(v_late[lead:], v, rtol=1e-12, atol=1e-300)


@fast
@given(accelerations, steps, dampings)
def test_pseudo_spectra_relations_and_rigid_limit(acc, dt, damping):
    s = response_spectrum(acc, dt, PERIODS, damping)
    omega = 2 * np.pi / PERIODS[1:]
    np.testing.assert_allclose(s.sv[1:], omega * s.sd[1:], rtol=1e-14)
    np.testing.assert_allclose(s.sa[1:], omega * s.sv[1:], rtol=1e-14)
    assert s.sa[0] == np.max(np.abs(acc))
    assert s.sd[0] == 0.0 and s.sv[0] == 0.0


@fast
@given(accelerations, steps, factors)
def test_peak_ground_values_scale_with_the_record(acc, dt, k):
    pga, pgv, pgd = peak_ground_values(acc, dt)
    kpga, kpgv, kpgd = peak_ground_values(k * acc, dt)
    np.testing.assert_allclose(
        [kpga, kpgv, kpgd], np.abs(k) * np.array([pga, pgv, pgd]), rtol=1e-12
    )
    assert pgv <= pga * (acc.size - 1) * dt * (1 + 1e-12)  # |v| <= integral of |a|
