"""The Nigam-Jennings recurrence against closed-form answers and an independent integrator.

Linear SDOF from rest: u'' + 2 zeta omega u' + omega^2 u = -a_g(t).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import linalg, signal

from groundmotions.bundled import load_bundled
from groundmotions.spectra import (
    nigam_jennings_coefficients,
    peak_ground_values,
    response_spectrum,
    sdof_response,
    spectrum,
)

PERIODS = np.array([0.05, 0.5, 2.0, 5.0])


@pytest.mark.parametrize("damping", [0.0, 0.02, 0.05, 0.2])
def test_step_response_matches_closed_form(damping):
    """Constant ground acceleration a0 from t = 0: the damped step response, exactly.

    u(t) = -(a0 / omega^2) [1 - exp(-zeta omega t) (cos omega_d t + zeta/sqrt(1-zeta^2) sin)]
    v(t) = -(a0 / omega^2) exp(-zeta omega t) omega / sqrt(1 - zeta^2) sin omega_d t
    """
    a0, dt, n = 1.3, 0.01, 2000
    t = np.arange(n)[:, None] * dt
    u, v = sdof_response(np.full(n, a0), dt, PERIODS, damping)
    omega = 2 * np.pi / PERIODS
    root = np.sqrt(1 - damping**2)
    omega_d = omega * root
    decay = np.exp(-damping * omega * t)
    static = a0 / omega**2
    u_exact = -static * (1 - decay * (np.cos(omega_d * t) + damping / root * np.sin(omega_d * t)))
    v_exact = -static * decay * omega / root * np.sin(omega_d * t)
    # The recurrence is exact for this (linear) input: only round-off remains.
    assert np.max(np.abs(u - u_exact) / static) < 1e-9
    assert np.max(np.abs(v - v_exact) / (static * omega)) < 1e-9


def test_harmonic_steady_state_amplitude_and_phase():
    """a_g = a0 sin(Omega t), 5 % damping, after the transient has decayed below 1e-7:
    u = -U sin(Omega t - phi), U = (a0 / omega^2) / sqrt((1 - b^2)^2 + (2 zeta b)^2),
    tan phi = 2 zeta b / (1 - b^2), b = Omega / omega (below and at resonance)."""
    a0, damping, forcing = 0.7, 0.05, 2 * np.pi * 2.0
    ratio = np.array([0.5, 1.0])
    omega = forcing / ratio
    # The samples are joined by straight lines, which lowers the harmonic's amplitude by
    # 1 - sinc^2(Omega dt / 2) ~ (Omega dt)^2 / 12; Omega dt = 2.5e-3 keeps that at 5e-7.
    dt = 2.5e-3 / forcing
    settle = np.log(1e7) / (damping * omega.min())
    n = int(np.ceil((settle + 5 * 2 * np.pi / forcing) / dt)) + 1
    t = np.arange(n) * dt
    u, _ = sdof_response(a0 * np.sin(forcing * t), dt, 2 * np.pi / omega, damping)

    amplitude = (a0 / omega**2) / np.hypot(1 - ratio**2, 2 * damping * ratio)
    phase = np.arctan2(2 * damping * ratio, 1 - ratio**2)
    steady = t >= settle
    u_steady = -amplitude * np.sin(forcing * t[steady, None] - phase)
    np.testing.assert_array_less(np.max(np.abs(u[steady] - u_steady), axis=0) / amplitude, 1e-6)
    np.testing.assert_allclose(np.max(np.abs(u[steady]), axis=0), amplitude, rtol=1e-6)


def test_random_record_matches_scipy_lsim():
    """lsim with linear interpolation of the input (first-order hold) is exact for a
    piecewise-linear input, through the matrix exponential: a fully independent route."""
    rng = np.random.default_rng(20240501)
    dt, n, damping = 0.01, 3000, 0.05
    acceleration = rng.normal(scale=2.0, size=n)
    t = np.arange(n) * dt
    periods = np.array([0.05, 0.3, 1.0, 4.0])
    u, v = sdof_response(acceleration, dt, periods, damping)
    for j, period in enumerate(periods):
        w = 2 * np.pi / period
        system = signal.StateSpace(
            [[0.0, 1.0], [-w * w, -2 * damping * w]], [[0.0], [-1.0]], np.eye(2), np.zeros((2, 1))
        )
        _, y, _ = signal.lsim(system, acceleration, t, interp=True)
        assert np.max(np.abs(u[:, j] - y[:, 0])) < 1e-8 * np.max(np.abs(y[:, 0]))
        assert np.max(np.abs(v[:, j] - y[:, 1])) < 1e-8 * np.max(np.abs(y[:, 1]))


@pytest.mark.parametrize("period", [0.01, 0.2, 1.0, 3.0])
@pytest.mark.parametrize("damping", [0.0, 0.05, 0.3])
def test_coefficients_equal_the_matrix_exponential(period, damping):
    """Closed-form coefficients = exp(M dt) of the system augmented with a linear load."""
    dt = 0.005
    w = 2 * np.pi / period
    m = np.zeros((4, 4))  # state (u, v, p, p'), p' constant over the step
    m[0, 1], m[1, 0], m[1, 1], m[1, 2], m[2, 3] = 1.0, -w * w, -2 * damping * w, 1.0, 1.0
    e = linalg.expm(m * dt)
    expected = np.array([[e[i, 0], e[i, 1], e[i, 2] - e[i, 3] / dt, e[i, 3] / dt] for i in (0, 1)])
    coefficients = nigam_jennings_coefficients(np.array([w]), damping, dt)[:, :, 0]
    scale = np.abs(expected).max(axis=1, keepdims=True)
    np.testing.assert_allclose(coefficients / scale, expected / scale, rtol=0, atol=1e-12)


def test_short_period_sa_tends_to_pga():
    """A rigid oscillator moves with the ground: Sa(T -> 0) -> PGA, exactly at T = 0."""
    motion = load_bundled("elcentro")
    periods = np.array([0.0, 1e-3, 3e-3, 1e-2])
    sa = spectrum(motion, periods).sa
    assert sa[0] == motion.pga
    error = np.abs(sa[1:] / motion.pga - 1)
    assert error[0] < 2e-4
    assert np.all(np.diff(error) > 0)  # converges as T falls


def test_long_period_sd_tends_to_pgd():
    """A very flexible undamped oscillator stands still: its relative displacement is minus
    the ground displacement, so Sd(T -> inf) -> PGD (here to the trapezoid rule's O(dt^2))."""
    motion = load_bundled("elcentro")
    _, _, pgd = peak_ground_values(motion.acceleration, motion.dt)
    sd = response_spectrum(motion.acceleration, motion.dt, [3000.0], damping=0.0).sd[0]
    assert sd == pytest.approx(pgd, rel=1e-3)


def test_peak_ground_velocity_of_a_linear_ramp():
    """a = c t (exactly linear): v = c t^2 / 2 (trapezoid is exact), d = c t^3 / 6 (O(dt^2))."""
    c, dt, n = 0.5, 0.01, 1001
    t = np.arange(n) * dt
    pga, pgv, pgd = peak_ground_values(c * t, dt)
    assert pga == pytest.approx(c * t[-1], rel=1e-14)
    assert pgv == pytest.approx(c * t[-1] ** 2 / 2, rel=1e-12)
    assert pgd == pytest.approx(c * t[-1] ** 3 / 6, rel=1e-4)


def test_bad_inputs_raise_with_the_house_template():
    with pytest.raises(ValueError, match=r"'damping' parameter of response_spectrum .*\[0, 1\)"):
        response_spectrum([0.0, 1.0], 0.01, [1.0], damping=1.0)
    with pytest.raises(ValueError, match=r"'periods' parameter of response_spectrum"):
        response_spectrum([0.0, 1.0], 0.01, [-1.0])
    with pytest.raises(ValueError, match=r"'periods' parameter of sdof_response"):
        sdof_response([0.0, 1.0], 0.01, [0.0])
    with pytest.raises(ValueError, match=r"'dt' parameter of peak_ground_values"):
        peak_ground_values([0.0, 1.0], 0.0)
    with pytest.raises(ValueError, match=r"'acceleration' parameter of response_spectrum"):
        response_spectrum([0.0, np.nan], 0.01, [1.0])
