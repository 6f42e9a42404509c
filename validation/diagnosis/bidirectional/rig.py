"""The bidirectional truth's test machine: actuators, play, lag, campaigns and measurement.

Part of the bidirectional truth (:mod:`validation.diagnosis.bidirectional`); numpy, the standard
library and its siblings only. One plain Python loop over the samples.

The test machine
----------------
Two horizontal actuators follow the commanded orbit (:mod:`~.orbits`); a vertical jack holds
the axial load N(t); a two-axis load cell measures the horizontal force.

- **Actuator dynamics** (a nuisance): each actuator follows its command through a second-order
  filter, x'' + 2 zeta w x' + w^2 x = w^2 u_cmd(t) (natural frequency f = w / 2 pi, damping
  zeta), integrated with RK4 on a fine grid and read by linear interpolation. The displacement
  channels measure the actuators' actual motion, not the command.
- **Play per axis** (the effect ``backlash``) of total width b_x, b_y between the actuators and
  the bearing: on each axis the bearing follows the actuator only when that axis's gap is
  closed, |u_a - u_b| <= b / 2 per axis; an open axis stands still and its load cell reads 0.
  An open axis carries no load, so the friction's component on it balances the restoring
  force there: z_j = -F_r,j / (mu N) (the other component then kept within |z| <= 1, so
  that the friction on the loaded axis feels the static friction on the open one). When the
  axis closes again the force on it rebuilds from zero through the transition, as in one
  direction. Each test starts with the gaps centred. The bearing's velocity is the
  actuator's on each axis that moved during the step, 0 on an axis that stood still.
- **Lag** of the force channels (the effect ``lag`` from 5 samples, a nuisance below 1.5):
  the bearing is simulated on the sample times shifted by -tau, so a fractional lag is exact;
  the displacement channels keep t_i.

A campaign keeps one heating field: a test begins ``rest_before`` seconds after the previous
ended (None: the plates are cold), its travel carries the ``travel`` wear, and each test
adds its rise to its own initial temperature.

Measurement (:func:`measure`)
-----------------------------
Sampling (the sample interval of the test), noise on each channel (white, AR(1) or
band-limited, :func:`noise`), converter quantisation (a 16-bit converter over a channel range,
:func:`quantise`), sensor faults (spikes, a stuck run of samples, a gain error of a few per
cent on one axis).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from validation.diagnosis.bidirectional.bearing import (
    REFERENCE_TEMPERATURE,
    Bearing2D,
    HeatField,
    pressure_factor,
    restoring_force,
    temperature_factor,
    transition_step,
)
from validation.diagnosis.bidirectional.orbits import Orbit


@dataclass(frozen=True)
class Test2D:
    """One test: the commanded ``orbit``, the sample interval ``dt`` [s], the axial load
    N [N] (a number or a function of time), the initial temperature [degC] and the rest
    since the previous test [s] (None: the plates are cold)."""

    orbit: Orbit
    dt: float
    axial: float | Callable[[np.ndarray], np.ndarray]
    initial_temperature: float = 20.0
    rest_before: float | None = None

    @property
    def time(self) -> np.ndarray:
        """The sample times [s] from 0."""
        return np.arange(round(self.orbit.duration / self.dt) + 1) * self.dt

    def axial_load(self, t: np.ndarray) -> np.ndarray:
        """N(t) [N]."""
        if callable(self.axial):
            return np.asarray(self.axial(np.asarray(t, dtype=float)), dtype=float)
        return np.full(np.shape(t), float(self.axial))


@dataclass(frozen=True)
class Rig:
    """The test machine's own behaviour: the force channels' ``lag`` [s] and the actuators'
    second-order dynamics (``actuator_frequency`` [Hz], None: ideal; ``actuator_damping``)."""

    lag: float = 0.0
    actuator_frequency: float | None = None
    actuator_damping: float = 0.7


def actuator_motion(orbit: Orbit, rig: Rig, end: float) -> tuple[Callable, Callable]:
    """The actuators' actual displacement and velocity as functions of time (the command
    through the second-order filter of ``rig``, or the command itself)."""
    if rig.actuator_frequency is None:
        return orbit.displacement, orbit.velocity
    w = 2.0 * math.pi * rig.actuator_frequency
    z = rig.actuator_damping
    h = min(1.0 / (40.0 * rig.actuator_frequency), 1.0e-3)
    t = np.arange(round(end / h) + 2) * h
    command = np.vstack([orbit.displacement(t), np.zeros((1, 2))])

    def rate(x, v, u):
        return v, w * w * (u - x) - 2.0 * z * w * v

    x, v = np.zeros(2), np.zeros(2)
    xs, vs = np.zeros((t.size, 2)), np.zeros((t.size, 2))
    for i in range(t.size - 1):
        u0, u1 = command[i], command[i + 1]
        um = 0.5 * (u0 + u1)
        k1 = rate(x, v, u0)
        k2 = rate(x + 0.5 * h * k1[0], v + 0.5 * h * k1[1], um)
        k3 = rate(x + 0.5 * h * k2[0], v + 0.5 * h * k2[1], um)
        k4 = rate(x + h * k3[0], v + h * k3[1], u1)
        x = x + h / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        v = v + h / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        xs[i + 1], vs[i + 1] = x, v

    def disp(tt):
        tt = np.asarray(tt, dtype=float)
        return np.column_stack([np.interp(tt, t, xs[:, 0]), np.interp(tt, t, xs[:, 1])])

    def vel(tt):
        tt = np.asarray(tt, dtype=float)
        return np.column_stack([np.interp(tt, t, vs[:, 0]), np.interp(tt, t, vs[:, 1])])

    return disp, vel


@dataclass
class _Campaign:
    field: HeatField | None
    clock: float = 0.0
    travel: float = 0.0


def _run_test(bearing: Bearing2D, test: Test2D, k: int, rig: Rig,
              state: _Campaign) -> dict[str, np.ndarray]:
    t_rec = test.time
    t = t_rec - rig.lag
    disp_f, vel_f = actuator_motion(test.orbit, rig, float(t_rec[-1]))
    moving = t >= 0.0
    tc = np.where(moving, t, 0.0)
    ua = np.where(moving[:, None], disp_f(tc), 0.0)
    va = np.where(moving[:, None], vel_f(tc), 0.0)
    axial = test.axial_load(np.maximum(t, 0.0))
    n = t.size
    half = 0.5 * np.asarray(bearing.play, dtype=float)
    has_play = bool(np.any(half > 0.0))
    u_y = bearing.yield_displacement
    start = state.clock
    sigma_nominal = bearing.weight / bearing.area
    gamma_nominal = pressure_factor(sigma_nominal)
    beta_reference = temperature_factor(REFERENCE_TEMPERATURE)
    heat = state.field if bearing.heating else None

    out = {"force": np.zeros((n, 2)), "bearing": np.zeros((n, 2)), "mu": np.zeros(n),
           "temperature": np.zeros(n), "restoring": np.zeros((n, 2)), "z": np.zeros((n, 2)),
           "engaged": np.zeros((n, 2)), "speed": np.zeros(n)}
    ub = np.zeros(2)
    z = np.zeros(2)
    mu_previous = bearing.mu0
    for i in range(n):
        a = ua[i]
        new = ub.copy()
        touching = np.ones(2, dtype=bool)
        if has_play:
            for j in range(2):
                if a[j] - ub[j] > half[j]:
                    new[j] = a[j] - half[j]
                elif ub[j] - a[j] > half[j]:
                    new[j] = a[j] + half[j]
                else:
                    touching[j] = half[j] == 0.0
                    if half[j] == 0.0:
                        new[j] = a[j]
        else:
            new = a.copy()
        du = new - ub
        vb = np.where(du != 0.0, va[i], 0.0)
        speed = float(math.hypot(vb[0], vb[1]))
        travel = state.travel
        step = float(math.hypot(du[0], du[1]))
        state.travel += step
        load = float(axial[i])
        sigma = load / bearing.area
        mu = bearing.mu0
        if bearing.speed is not None:
            mu *= bearing.speed.factor(speed)
        if bearing.pressure:
            mu *= pressure_factor(sigma) / gamma_nominal
        temperature = test.initial_temperature
        if heat is not None:
            if i > 0 and step > 0.0:
                dt = float(t[i] - t[i - 1])
                heat.add(start + float(t[i - 1]), start + float(t[i]), 0.25 * (ub + new),
                         mu_previous * sigma * step / dt / 2.0)
            temperature += heat.contact_rise(start + float(t[i]), 0.5 * new)
            mu *= temperature_factor(temperature) / beta_reference
        if bearing.wear is not None:
            mu *= bearing.wear.factor(k, travel)
        restoring_new = restoring_force(bearing, new, load)
        z = transition_step(bearing.transition, z, du, u_y)
        for j in range(2):  # an open axis carries no load: friction balances F_r on it
            if not touching[j]:
                z[j] = max(-1.0, min(1.0, -restoring_new[j] / (mu * load)))
                other = z[1 - j]
                if z[j] * z[j] + other * other > 1.0:
                    z[1 - j] = math.copysign(math.sqrt(max(1.0 - z[j] * z[j], 0.0)), other)
        ub = new
        force = restoring_new + mu * load * z
        out["force"][i] = np.where(touching, force, 0.0)
        out["bearing"][i] = ub
        out["mu"][i] = mu
        out["temperature"][i] = temperature
        out["restoring"][i] = np.where(touching, restoring_new, 0.0)
        out["z"][i] = z
        out["engaged"][i] = touching
        out["speed"][i] = speed
        mu_previous = mu
    state.clock = start + float(t[-1])
    out["time"] = t_rec
    out["displacement"] = disp_f(t_rec)
    out["velocity"] = vel_f(t_rec)
    out["axial_force"] = test.axial_load(t_rec)
    return out


def simulate(bearing: Bearing2D, tests: Sequence[Test2D], rig: Rig | None = None) -> list[dict]:
    """The clean channels of every test of a campaign, in run order.

    Parameters
    ----------
    bearing : Bearing2D
        The truth bearing.
    tests : sequence of Test2D
        The campaign's tests in run order.
    rig : Rig or None
        The test machine (lag [s], actuator dynamics); None: an ideal machine.

    Returns
    -------
    list of dict
        Per test: ``time`` [s] (n,), ``displacement`` (n, 2) [m] (the actuators' actual
        motion), ``velocity`` (n, 2) [m/s], ``axial_force`` (n,) [N], ``force`` (n, 2) [N]
        (the load cell, lagged), and the truth's histories at the force channels' instants:
        ``bearing`` (n, 2), ``mu``, ``temperature`` [degC], ``restoring`` (n, 2), ``z``
        (n, 2), ``engaged`` (n, 2), ``speed`` [m/s].
    """
    rig = rig or Rig()
    if rig.lag < 0.0:
        raise ValueError("lag must be >= 0")
    state = _Campaign(HeatField(bearing.contact_radius) if bearing.heating else None)
    outputs = []
    for k, test in enumerate(tests):
        if k > 0:
            if test.rest_before is None:
                state.field = HeatField(bearing.contact_radius) if bearing.heating else None
                state.clock = 0.0
            else:
                state.clock += float(test.rest_before) + rig.lag
        outputs.append(_run_test(bearing, test, k, rig, state))
    return outputs


# --- measurement ------------------------------------------------------------------------------


def noise(rng: np.random.Generator, n: int, sigma: float, kind: str = "white",
          rho: float = 0.0, band: float = 0.2) -> np.ndarray:
    """Zero-mean noise of standard deviation ``sigma``: ``white``, ``ar1`` (lag-one correlation
    ``rho``, stationary from the first sample) or ``band`` (white noise with the spectrum above
    ``band`` times the Nyquist frequency removed, rescaled to ``sigma``)."""
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


def quantise(x: np.ndarray, full_scale: float, bits: int = 16) -> np.ndarray:
    """``x`` read by a converter of ``bits`` bits over +-``full_scale``: rounded to its step
    2 full_scale / 2^bits and clipped to the range."""
    lsb = 2.0 * full_scale / 2**bits
    return np.clip(np.round(np.asarray(x) / lsb) * lsb, -full_scale, full_scale - lsb)


@dataclass(frozen=True)
class Measurement:
    """The measurement chain of a case (all nuisance, never labelled).

    force_noise : standard deviation of the force noise [N]; ``kind``, ``rho`` its colour.
    displacement_noise : [m], white. velocity_noise : [m/s], white (None: no velocity
    columns). axial_noise : relative, white (None: no axial-force column).
    bits : converter resolution; ``force_range`` [N] and ``displacement_range`` [m] the
    converters' full scales (None: no quantisation).
    spikes : number of single-sample spikes on the force channels, of ``spike_size`` times
    the RMS force. stuck : length of one run of samples where a force channel holds its
    value (0: none). gain : (channel, relative error), e.g. ("force_y", 0.02).
    """

    force_noise: float
    kind: str = "white"
    rho: float = 0.0
    displacement_noise: float = 2.0e-5
    velocity_noise: float | None = None
    axial_noise: float | None = None
    bits: int = 16
    force_range: float | None = None
    displacement_range: float | None = None
    spikes: int = 0
    spike_size: float = 0.3
    stuck: int = 0
    gain: tuple[str, float] | None = None


def measure(clean: dict, chain: Measurement, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """The columns of the two-direction test file: ``time``, ``displacement_x/y``,
    ``force_x/y`` and, where the chain has them, ``velocity_x/y`` and ``axial_force``,
    with the measurement chain's noise, faults and quantisation."""
    n = clean["time"].size
    out = {"time": clean["time"]}
    for j, axis in enumerate("xy"):
        d = clean["displacement"][:, j] + rng.normal(0.0, chain.displacement_noise, n)
        if chain.displacement_range is not None:
            d = quantise(d, chain.displacement_range, chain.bits)
        out[f"displacement_{axis}"] = d
    rms = float(np.sqrt(np.mean(np.sum(clean["force"] ** 2, axis=1))))
    for j, axis in enumerate("xy"):
        f = clean["force"][:, j] + noise(rng, n, chain.force_noise, chain.kind, chain.rho)
        if chain.spikes:
            where = rng.choice(np.arange(5, n - 5), size=chain.spikes, replace=False)
            f[where] += rng.choice([-1.0, 1.0], size=chain.spikes) * chain.spike_size * rms
        if chain.stuck and axis == "x":
            first = int(rng.integers(n // 4, 3 * n // 4))
            f[first:first + chain.stuck] = f[first]
        out[f"force_{axis}"] = f
    if chain.gain is not None:
        name, error = chain.gain
        out[name] = out[name] * (1.0 + error)
    if chain.force_range is not None:
        for axis in "xy":
            out[f"force_{axis}"] = quantise(out[f"force_{axis}"], chain.force_range, chain.bits)
    if chain.axial_noise is not None:
        out["axial_force"] = clean["axial_force"] * (1.0 + rng.normal(0.0, chain.axial_noise, n))
    if chain.velocity_noise is not None:
        for j, axis in enumerate("xy"):
            out[f"velocity_{axis}"] = clean["velocity"][:, j] + rng.normal(
                0.0, chain.velocity_noise, n)
    return out
