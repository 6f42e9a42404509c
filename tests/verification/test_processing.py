"""Record processing against closed-form answers: drift removal, filter gains, resampling,
Arias intensity and significant duration."""

from __future__ import annotations

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.bundled import load_bundled
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

ELCENTRO = load_bundled("elcentro")


def _sine_amplitude(motion: GroundMotion, frequency: float, margin: float = 5.0) -> float:
    """Amplitude of the ``frequency`` [Hz] component, by least squares away from the ends."""
    t = motion.time
    keep = (t > margin) & (t < t[-1] - margin)
    basis = np.column_stack([np.sin(2 * np.pi * frequency * t), np.cos(2 * np.pi * frequency * t)])
    coefficients = np.linalg.lstsq(basis[keep], motion.acceleration[keep], rcond=None)[0]
    return float(np.hypot(*coefficients))


# ------------------------------------------------------------------------- baseline correction


def test_linear_drift_in_acceleration_is_removed_exactly():
    """Least squares is linear and reproduces polynomials: removing a degree-1 fit from
    record + (c0 + c1 t) gives the same as from the record alone, and a pure drift goes to 0."""
    t = ELCENTRO.time
    drift = 0.05 - 0.004 * t  # [m/s^2]
    drifted = GroundMotion(ELCENTRO.acceleration + drift, ELCENTRO.dt, "drifted")
    np.testing.assert_allclose(baseline_corrected(drifted).acceleration,
                               baseline_corrected(ELCENTRO).acceleration, rtol=0, atol=1e-12)
    pure = baseline_corrected(GroundMotion(drift, ELCENTRO.dt))
    assert np.max(np.abs(pure.acceleration)) < 1e-13
    # What remains is orthogonal to 1 and t.
    corrected = baseline_corrected(drifted).acceleration
    assert abs(corrected.sum()) < 1e-9 and abs((corrected * t).sum()) < 1e-8


def test_baseline_order_zero_removes_the_mean_and_says_so():
    out = baseline_corrected(ELCENTRO, order=0)
    np.testing.assert_allclose(out.acceleration, ELCENTRO.acceleration
                               - ELCENTRO.acceleration.mean(), atol=1e-14)
    assert out.processing[-1] == "baseline corrected: least-squares polynomial of degree 0 removed"
    assert ELCENTRO.baseline_corrected(2).processing[-1].endswith("degree 2 removed")


@pytest.mark.parametrize("order", [3, 4, 6, 10])
def test_zero_residuals_ends_at_rest(order):
    out = zero_residuals(ELCENTRO, order=order)
    velocity, displacement = velocity_and_displacement(out.acceleration, out.dt)
    assert velocity[0] == displacement[0] == 0.0
    assert abs(velocity[-1]) < 1e-12 and abs(displacement[-1]) < 1e-11
    _, before = velocity_and_displacement(ELCENTRO.acceleration, ELCENTRO.dt)
    assert abs(before[-1]) > 0.02  # there was something to correct
    assert "zero residuals" in out.processing[-1]


def test_zero_residuals_order_3_removes_a_linear_drift_exactly():
    """A record at rest at its end plus a linear acceleration drift: the order-3 correction
    (a straight line in acceleration, fixed by the two end conditions) is the drift itself."""
    at_rest = zero_residuals(ELCENTRO)
    drift = 0.02 + 0.001 * ELCENTRO.time
    recovered = zero_residuals(GroundMotion(at_rest.acceleration + drift, ELCENTRO.dt))
    np.testing.assert_allclose(recovered.acceleration, at_rest.acceleration, rtol=0, atol=1e-12)
    again = zero_residuals(at_rest)  # already at rest: nothing changes
    np.testing.assert_allclose(again.acceleration, at_rest.acceleration, rtol=0, atol=1e-14)


def test_exact_integrals_of_a_linear_acceleration():
    """a = c t: v = c t^2 / 2 and d = c t^3 / 6 exactly at every sample."""
    dt, c = 0.01, 0.7
    t = np.arange(501) * dt
    velocity, displacement = velocity_and_displacement(c * t, dt)
    np.testing.assert_allclose(velocity, c * t**2 / 2, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(displacement, c * t**3 / 6, rtol=1e-12, atol=1e-15)


# ----------------------------------------------------------------------------------- filters


def _two_sines(f_low: float, f_high: float, dt: float = 0.005, duration: float = 40.0):
    t = np.arange(round(duration / dt) + 1) * dt
    acc = 1.0 * np.sin(2 * np.pi * f_low * t) + 0.5 * np.sin(2 * np.pi * f_high * t)
    return GroundMotion(acc, dt, "two sines")


def test_low_pass_keeps_the_sine_below_and_removes_the_one_above():
    out = filtered(_two_sines(1.0, 20.0), high=5.0)
    assert _sine_amplitude(out, 1.0) == pytest.approx(1.0, rel=0.01)
    assert _sine_amplitude(out, 20.0) < 0.01 * 0.5


def test_high_pass_and_band_pass():
    high = filtered(_two_sines(0.1, 5.0), low=1.0)
    assert _sine_amplitude(high, 0.1) < 0.01 * 1.0
    assert _sine_amplitude(high, 5.0) == pytest.approx(0.5, rel=0.01)
    band = filtered(_two_sines(0.1, 20.0).scaled(1.0), low=1.0, high=8.0)
    assert _sine_amplitude(band, 0.1) < 0.01 and _sine_amplitude(band, 20.0) < 0.005


def test_gain_at_the_corner_is_one_half_and_no_phase_shift():
    """sosfiltfilt squares the Butterworth magnitude: 1/2 at the corner, with zero phase."""
    motion = _two_sines(2.0, 2.0)  # one sine of amplitude 1.5
    out = filtered(motion, high=2.0, order=4)
    t = out.time
    keep = (t > 5) & (t < t[-1] - 5)
    basis = np.column_stack([np.sin(2 * np.pi * 2.0 * t), np.cos(2 * np.pi * 2.0 * t)])
    sin_part, cos_part = np.linalg.lstsq(basis[keep], out.acceleration[keep], rcond=None)[0]
    assert sin_part == pytest.approx(0.75, rel=1e-3)
    assert abs(cos_part) < 1e-3
    assert out.processing[-1] == ("filtered: zero-phase Butterworth low-pass 2 Hz, order 4 "
                                  "(forward-backward)")


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"high": 25.0}, ["'high'", "(0, 25)", "25.0"]),
        ({"low": -1.0}, ["'low'", "(0, 25)", "-1.0"]),
        ({"low": 5.0, "high": 2.0}, ["'high'", "(5, 25)", "2.0"]),
        ({}, ["'low' and 'high'", "both be None"]),
        ({"high": 5.0, "order": 0}, ["'order'", "[1, 10]"]),
    ],
)
def test_filter_errors_name_the_parameter_range_and_value(kwargs, words):
    with pytest.raises(ValueError) as error:
        filtered(ELCENTRO, **kwargs)  # dt = 0.02 s: Nyquist 25 Hz
    for word in words:
        assert word in str(error.value)


def test_too_short_a_record_for_the_filter_is_a_clear_error():
    """sosfiltfilt pads 3 (2 n_sections + 1) samples at each end: 15 for order 4."""
    with pytest.raises(ValueError, match=r"must have more than 15 samples for this filter "
                       r"order\. Got 10 instead\."):
        filtered(GroundMotion(np.ones(10), 0.01), high=5.0)


# ---------------------------------------------------------------------------------- resampling


@pytest.mark.parametrize("factor", [2, 4, 5])
def test_finer_then_back_recovers_the_record(factor):
    fine = resampled(ELCENTRO, ELCENTRO.dt / factor)
    assert fine.npts == factor * (ELCENTRO.npts - 1) + 1
    np.testing.assert_array_equal(fine.acceleration[::factor], ELCENTRO.acceleration)
    back = resampled(fine, ELCENTRO.dt, anti_alias=False)
    np.testing.assert_array_equal(back.acceleration, ELCENTRO.acceleration)
    assert back.dt == ELCENTRO.dt
    assert len(back.processing) == len(ELCENTRO.processing) + 2


def test_finer_resampling_is_exact_for_the_piecewise_linear_record():
    """Linear interpolation adds no content: the Arias intensity (exact a^2 integral) and the
    final velocity are unchanged, and a non-integer ratio lands between samples linearly."""
    fine = ELCENTRO.resampled(ELCENTRO.dt / 3)
    assert arias_intensity(fine)[1][-1] == pytest.approx(arias_intensity(ELCENTRO)[1][-1],
                                                         rel=1e-12)
    v_fine, _ = velocity_and_displacement(fine.acceleration, fine.dt)
    v, _ = velocity_and_displacement(ELCENTRO.acceleration, ELCENTRO.dt)
    assert v_fine[-1] == pytest.approx(v[-1], rel=1e-9, abs=1e-15)
    odd = ELCENTRO.resampled(0.0075)
    np.testing.assert_allclose(odd.acceleration, np.interp(odd.time, ELCENTRO.time,
                                                           ELCENTRO.acceleration), atol=1e-14)


def test_coarser_with_anti_alias_removes_what_would_fold_back():
    """From dt = 0.005 s to 0.02 s (Nyquist 25 Hz): a 40 Hz sine would alias to 10 Hz; the
    anti-alias filter removes it and keeps a 2 Hz sine to 1 %."""
    motion = _two_sines(2.0, 40.0)
    coarse = resampled(motion, 0.02)
    assert coarse.npts == 2001 and coarse.dt == 0.02
    assert _sine_amplitude(coarse, 2.0) == pytest.approx(1.0, rel=0.01)
    assert _sine_amplitude(coarse, 10.0) < 0.005 * 0.5
    aliased = resampled(motion, 0.02, anti_alias=False)
    assert _sine_amplitude(aliased, 10.0) == pytest.approx(0.5, rel=0.01)
    assert "anti-alias low-pass 20 Hz" in coarse.processing[-1]


def test_resample_errors():
    with pytest.raises(ValueError, match="'dt' parameter of resampled must be a float in"):
        resampled(ELCENTRO, 0.0)
    with pytest.raises(ValueError, match="'dt'"):
        resampled(ELCENTRO, 40.0)
    with pytest.raises(TypeError, match="'motion' parameter of resampled must be a GroundMotion"):
        resampled(ELCENTRO.acceleration, 0.01)


# ------------------------------------------------------------------------ Arias and duration


def test_arias_intensity_of_a_sine_matches_the_closed_form():
    """a = A sin(w t) on [0, T]: I_A = pi / (2 g) A^2 (T / 2 - sin(2 w T) / (4 w))."""
    amplitude, omega, dt = 2.0, 2 * np.pi * 1.3, 0.001
    t = np.arange(10_001) * dt
    times, cumulative = arias_intensity(GroundMotion(amplitude * np.sin(omega * t), dt))
    exact = np.pi / (2 * STANDARD_GRAVITY) * amplitude**2 * (
        times / 2 - np.sin(2 * omega * times) / (4 * omega))
    # The samples are joined by straight lines, which lowers the mean square of a sine by
    # about (omega dt)^2 / 6 (1.1e-5 here).
    bound = (omega * dt) ** 2 / 6
    np.testing.assert_allclose(cumulative, exact, rtol=0, atol=1.2 * bound * exact[-1])
    assert cumulative[-1] == pytest.approx(exact[-1] * (1 - bound), rel=0.1 * bound)


def test_arias_intensity_is_exact_for_a_linear_record():
    """a = c t: integral of a^2 = c^2 T^3 / 3, exactly, whatever the step."""
    c, dt = 0.3, 0.05
    t = np.arange(201) * dt
    _, cumulative = arias_intensity(GroundMotion(c * t, dt))
    exact = np.pi / (2 * STANDARD_GRAVITY) * c**2 * t**3 / 3
    np.testing.assert_allclose(cumulative, exact, rtol=1e-12, atol=1e-16)


def test_significant_duration_of_a_sine_burst():
    """Quiet, then a 10 s sine burst from t = 5 s, then quiet: the Arias intensity grows (nearly)
    linearly during the burst, so D5-75 = 0.70 x 10 s and D5-95 = 0.90 x 10 s, to within the
    sin(2 w t) / (4 w) ripple of the integral (< 0.02 s at 5 Hz)."""
    dt = 0.002
    t = np.arange(20_001) * dt
    burst = (t >= 5.0) & (t <= 15.0)
    motion = GroundMotion(np.where(burst, 3.0 * np.sin(2 * np.pi * 5.0 * (t - 5.0)), 0.0), dt)
    assert significant_duration(motion, 0.05, 0.75) == pytest.approx(7.0, abs=0.02)
    assert significant_duration(motion) == pytest.approx(9.0, abs=0.02)
    # From the first sample (the intensity is already 0 there) to the end of the burst.
    assert significant_duration(motion, 0.0, 1.0) == pytest.approx(15.0, abs=dt)


def test_significant_duration_of_el_centro():
    """Published D5-95 of El Centro 1940 N-S is about 24 s."""
    assert 22.0 < significant_duration(ELCENTRO) < 26.0
    assert significant_duration(ELCENTRO, 0.05, 0.75) < significant_duration(ELCENTRO)


def test_significant_duration_errors():
    with pytest.raises(ValueError, match=r"'stop' parameter of significant_duration must be a "
                       r"float in \(0.5, 1\]"):
        significant_duration(ELCENTRO, 0.5, 0.4)
    with pytest.raises(ValueError, match="'start'"):
        significant_duration(ELCENTRO, -0.1, 0.9)
    with pytest.raises(ValueError, match="non-zero Arias intensity"):
        significant_duration(GroundMotion(np.zeros(10), 0.01))
