"""The independent truth's test machine: the tests, the campaign and the measurement noise.

Part of the independent truths (:mod:`validation.diagnosis.independent`), written from
the paper and from physics. Like the rest of them, this module imports only numpy, the
standard library and its sibling :mod:`validation.diagnosis.independent.bearing` (the bearing
it drives): it shares no code with ``isolator``, ``structures``, ``dcfpb``, ``groundmotions``
or ``tests``. It is deliberately plain: one Python loop over the samples.

Units are SI at every argument (m, s, N, Pa, degC).

The test machine
----------------
An actuator imposes a displacement history u_a(t) (the *measured displacement channel*); a
load cell measures the horizontal force F (the *force channel*); a vertical jack holds the
axial load N(t). Time starts at 0 with everything at rest (u_a(t < 0) = 0).

- **Play (backlash)** of total width b between actuator and bearing: the bearing's own
  displacement u_b follows u_a only when the gap is closed on one side, so |u_a - u_b| <= b/2
  always. While the gap is open the load cell reads 0 and the bearing stands still (its
  friction holds it; the designs keep |u_b| / R < mu so that a pendulum does not slide back
  by itself). At the sample where contact is made again, the hysteretic variable restarts
  from the value that gives zero force at the bearing's position, zeta = -F_r(u_b) / (mu N),
  and the force then rebuilds through the transition. The test starts with the gap centred.
- **Lag**: the force channel records the force tau seconds late. The bearing is simulated on
  the sample times shifted by -tau (driven by u_a(t_i - tau)), so a fractional lag is exact
  without interpolation; the displacement channel keeps u_a(t_i).

A campaign keeps one plate (see the bearing's heating): a test begins ``rest_before`` seconds
after the previous one ended (no flux in between), so the earlier tests' heat decays as the
half-space solution says; each test adds its rise to its own initial temperature T0.

Measurement
-----------
White, AR(1) (coloured, lag-one correlation rho) or band-limited noise on the force (as a
fraction of the nominal friction force mu0 W), the displacement, the velocity and the axial
force channels (:func:`noise`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from validation.diagnosis.independent.bearing import (
    REFERENCE_TEMPERATURE,
    Bearing,
    Plate,
    bearing_force,
    beta,
    gamma,
    restoring_force,
    transition_step,
)

# --- the tests -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Test:
    """One test: sample times [s] (from 0), the actuator's displacement u_a(t) [m] and velocity
    [m/s] as functions of time (valid for t >= 0), the axial load N(t) [N], the initial
    temperature [degC] and the rest since the previous test [s] (None: the plates are cold,
    the heat of earlier tests is forgotten)."""

    time: np.ndarray
    displacement: Callable[[np.ndarray], np.ndarray]
    velocity: Callable[[np.ndarray], np.ndarray]
    axial: Callable[[np.ndarray], np.ndarray]
    initial_temperature: float = 20.0
    rest_before: float | None = None


def sine_test(amplitude: float, period: float, cycles: float, dt: float, axial: float |
              Callable = 1.0, **kwargs) -> Test:
    """u_a = A sin(2 pi t / T) for ``cycles`` periods sampled every ``dt`` (a constant axial
    load [N] or a function of time)."""
    n = round(cycles * period / dt)
    omega = 2.0 * math.pi / period
    load = axial if callable(axial) else (lambda t, w=float(axial): np.full(np.shape(t), w))
    return Test(np.arange(n + 1) * dt, lambda t: amplitude * np.sin(omega * t),
                lambda t: amplitude * omega * np.cos(omega * t), load, **kwargs)


# --- the simulation ------------------------------------------------------------------------


@dataclass
class _Campaign:
    """What carries over from test to test: the plate, the clock, the travel."""

    plate: Plate | None
    clock: float = 0.0
    travel: float = 0.0


def _run_test(bearing: Bearing, test: Test, k: int, lag: float,
              state: _Campaign) -> dict[str, np.ndarray]:
    """One test of a campaign (state carries the plate, the clock and the travel)."""
    t_rec = np.asarray(test.time, dtype=float)
    t = t_rec - lag  # the bearing's state that the force channel records at t_rec
    moving = t >= 0.0
    tc = np.where(moving, t, 0.0)
    ua = np.where(moving, test.displacement(tc), 0.0)
    va = np.where(moving, test.velocity(tc), 0.0)
    axial = np.asarray(test.axial(np.maximum(t, 0.0)), dtype=float)
    n = t.size
    c_plus, c_minus = 1.0 + bearing.asymmetry, 1.0 - bearing.asymmetry
    half = 0.5 * bearing.backlash
    u_y = bearing.yield_displacement
    plate = state.plate if bearing.temperature else None
    start = state.clock
    w = bearing.weight
    gamma_nominal = gamma(w / bearing.area)
    beta_reference = beta(REFERENCE_TEMPERATURE)

    out = {name: np.zeros(n) for name in ("force", "bearing", "mu", "temperature", "restoring",
                                          "zeta", "engaged")}
    ub = 0.0
    zeta = 0.0
    was_touching = half == 0.0  # a play starts centred: the first contact is an engagement
    direction = 0.0  # sliding direction (0 before the first motion)
    since_reversal = 0.0
    mu_previous = bearing.mu0
    for i in range(n):
        # kinematics: the play
        if half == 0.0:
            new, touching = float(ua[i]), True
        elif ua[i] - ub > half:
            new, touching = float(ua[i]) - half, True
        elif ub - ua[i] > half:
            new, touching = float(ua[i]) + half, True
        else:
            new, touching = ub, False
        du = new - ub
        speed = abs(float(va[i])) if (half == 0.0 or du != 0.0) else 0.0
        if du != 0.0:
            d = 1.0 if du > 0.0 else -1.0
            if d != direction:
                direction, since_reversal = d, 0.0
            since_reversal += abs(du)
        travel = state.travel
        state.travel += abs(du)
        # friction coefficient (heating uses the previous sample's mu: explicit)
        mu = bearing.mu0
        if bearing.velocity is not None:
            mu *= bearing.velocity.factor(speed)
        load = float(axial[i])
        sigma = load / bearing.area
        if bearing.pressure == "normalised":
            mu *= gamma(sigma) / gamma_nominal
        elif bearing.pressure == "paper":
            mu *= gamma(sigma)
        temperature = test.initial_temperature
        if plate is not None:
            if i > 0 and du != 0.0:  # the step's flux at its mean speed and mid position
                dt = float(t[i] - t[i - 1])
                flux = mu_previous * sigma * abs(du) / dt / 2.0
                plate.add(start + float(t[i - 1]), start + float(t[i]), 0.5 * (ub + new) / 2.0,
                          flux)
            temperature += plate.rise(start + float(t[i]), new / 2.0)
            if bearing.temperature == "normalised":
                mu *= beta(temperature) / beta_reference
            else:
                mu *= beta(temperature)
        if bearing.breakaway is not None and direction != 0.0:
            mu *= bearing.breakaway.factor(since_reversal)
        if bearing.wear is not None:
            mu *= bearing.wear.factor(k, travel)
        # hysteresis (at an engagement the force restarts from zero)
        if touching and not was_touching:
            zeta = -restoring_force(bearing, ub, load) / (mu * load)
            zeta = min(c_plus, max(-c_minus, zeta))
        was_touching = touching
        zeta = transition_step(bearing.transition, zeta, du, u_y, c_plus, c_minus)
        ub = new
        force = bearing_force(bearing, ub, load, mu, zeta) if touching else 0.0
        out["force"][i] = force
        out["bearing"][i] = ub
        out["mu"][i] = mu
        out["temperature"][i] = temperature
        out["restoring"][i] = restoring_force(bearing, ub, load) if touching else 0.0
        out["zeta"][i] = zeta
        out["engaged"][i] = float(touching)
        mu_previous = mu
    state.clock = start + float(t[-1])
    out["time"] = t_rec
    out["displacement"] = np.asarray(test.displacement(t_rec), dtype=float)
    out["velocity"] = np.asarray(test.velocity(t_rec), dtype=float)
    out["axial_force"] = np.asarray(test.axial(t_rec), dtype=float)
    return out


def simulate(bearing: Bearing, tests: Sequence[Test], *, lag: float = 0.0) -> list[dict]:
    """The clean channels of every test of a campaign, in run order.

    Parameters
    ----------
    bearing : Bearing
        The truth.
    tests : sequence of Test
        The campaign's tests in run order (their rests and initial temperatures).
    lag : float
        Delay of the force channel [s] (>= 0).

    Returns
    -------
    list of dict
        Per test: ``time``, ``displacement`` (actuator), ``velocity`` (actuator),
        ``axial_force``, ``force`` (the load cell, lagged), and the truth's own histories at
        the force channel's instants: ``bearing`` (u_b), ``mu``, ``temperature``,
        ``restoring``, ``zeta``, ``engaged``.
    """
    if lag < 0.0:
        raise ValueError("lag must be >= 0")
    state = _Campaign(Plate(bearing.contact_radius) if bearing.temperature else None)
    outputs = []
    for k, test in enumerate(tests):
        if k > 0:
            if test.rest_before is None:  # cold plates: forget the heat
                state.plate = Plate(bearing.contact_radius) if bearing.temperature else None
                state.clock = 0.0
            else:
                state.clock += float(test.rest_before) + lag
        outputs.append(_run_test(bearing, test, k, lag, state))
        # the next test's clock: its t = 0 comes rest_before after this test's last sample
        # (the shifted grid ended lag earlier, hence + lag above)
    return outputs


# --- measurement noise ---------------------------------------------------------------------


def noise(rng: np.random.Generator, n: int, sigma: float, kind: str = "white",
          rho: float = 0.0, band: float = 0.2) -> np.ndarray:
    """Zero-mean noise of standard deviation ``sigma``: ``white``; ``ar1`` (coloured,
    x_i = rho x_(i-1) + sqrt(1 - rho^2) e_i, stationary from the first sample); ``band``
    (white noise with the spectrum above ``band`` times the Nyquist frequency removed,
    rescaled to ``sigma``)."""
    if sigma == 0.0:
        return np.zeros(n)
    white = rng.standard_normal(n)
    if kind == "white":
        return sigma * white
    if kind == "ar1":
        out = np.empty(n)
        out[0] = white[0]
        scale = math.sqrt(1.0 - rho * rho)
        for i in range(1, n):
            out[i] = rho * out[i - 1] + scale * white[i]
        return sigma * out
    if kind == "band":
        spectrum = np.fft.rfft(white)
        spectrum[int(band * spectrum.size) + 1:] = 0.0
        out = np.fft.irfft(spectrum, n)
        return sigma * out / np.std(out)
    raise ValueError(f"unknown noise kind {kind!r}")
