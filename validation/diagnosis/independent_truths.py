"""Independent truths for the diagnosis's validation panel: a bearing test written from physics.

This module imports only numpy and the standard library. It shares no code with ``isolator``,
``structures``, ``dcfpb``, ``groundmotions`` or ``tests``, so a mistake in the package cannot
be repeated in the data the package's diagnosis is judged on. It is deliberately plain: one
Python loop over the samples, closed forms where they exist, and the equations below.

Units are SI at every argument (m, s, N, Pa, degC); the paper's N/mm^2 and mm/s appear only
inside its factors (Nishimoto et al., "SSB part 2: friction models", Eq. 1-8).

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

The bearing
-----------
F = F_r(u_b, N) + mu(t) N zeta(t) (``linear``), with

- ``linear`` restoring F_r = N u_b / R (the paper's form; R = inf: a flat slider, F_r = 0);
- ``spherical`` (geometry): F_r = N u_b / sqrt(R^2 - u_b^2) and the normal force on the
  surface carries the horizontal force's share, N_eff = N + F u_b / R, so
  F = F_r + mu zeta (N + F u_b / R), which is linear in F and solved per sample:
  F = (F_r + mu zeta N) / (1 - mu zeta u_b / R).

The hysteretic variable zeta lies in [-c_minus, c_plus] with c_plus = 1 + a, c_minus = 1 - a
(a = 0 unless the friction is asymmetric: mu(+) / mu(-) = (1 + a) / (1 - a), a friction
capacity that depends on the sliding direction). Transitions, with du the bearing's
displacement increment of a step:

- ``rigid-plastic``: zeta = +c_plus when du > 0, -c_minus when du < 0, held when du = 0: the
  force reverses at the sample after the displacement peak;
- ``elastic-plastic`` (return map): zeta_i = clip(zeta_(i-1) + du / u_y, -c_minus, c_plus);
- ``smooth`` (Bouc-Wen, n = 2): with z = zeta / c (c the cap on zeta's side of 0),
  dz/du = (1 - |z|^2 sgn(du z)) / (c u_y). Integrated exactly: loading (du z >= 0)
  z = tanh(atanh(z0) + du / (c u_y)); unloading z = tan(atan(z0) + du / (c u_y)) until z
  reaches 0, then loading on the other side. (A sub-stepped integration agrees; see checks.)

The friction coefficient
------------------------
mu(t) = mu0 x velocity x pressure x temperature x breakaway x wear factors, each optional:

- velocity, with |v| the bearing's speed (the actuator's analytic speed while engaged, 0 in
  the gap): ``paper`` Eq. 2 alpha(v) = 1 - 0.55 exp(-0.019 v[mm/s]) (optionally normalised,
  alpha(v) / alpha(0.4 m/s)); ``exp``: 1 - (1 - r) exp(-|v| / v_c), r = mu_slow / mu_fast;
  ``stribeck``: 1 + s exp(-(|v| / v_s)^2), friction higher at low speed;
- pressure: Eq. 1 gamma(sigma) = 2.03 sigma^-0.19 + 0.068, sigma = N / (pi r^2) in N/mm^2,
  ``normalised`` gamma(sigma) / gamma(sigma_nominal) or ``paper`` (raw, Eq. 7);
- temperature: Eq. 3 beta(T) = 1.13 exp(-0.007 T), ``normalised`` beta(T) / beta(20 degC) or
  ``paper`` (raw, Eq. 7); T is the contact temperature (below);
- breakaway: a static peak after each reversal (and at the start of motion) as a function of
  the travel s since the last reversal, ``linear`` 1 + b max(0, 1 - s / d) or ``gauss``
  1 + b exp(-(s / d)^2) (neither is exponential);
- wear: ``step`` 1 - delta k for the k-th test of the campaign in run order (k = 0, 1, ...),
  or ``power`` 1 + c (S / S_total)^p, S the bearing's travel accumulated over the campaign.

The precise model of the paper (Eq. 7) is mu0 = mu_t0 = 0.075 with the three raw factors.

Heating (Eq. 4-5, the paper's precise model)
--------------------------------------------
Monitor points every 5 mm along the line of sliding on each plate of the double concave
bearing (x_i = 5 mm i). The slider centre is at u_b / 2 on each plate; each plate takes the
flux q = mu p |v| / 2 (p = N / (pi r^2)) at the points within sqrt(pi) r / 2 of the centre
(the half side of the square of equal area). The contact temperature is
T = T0 + the mean rise of the points under the slider. With the flux piecewise constant over
the steps, the rise of a point is the exact integral of Eq. 4,

    dT(t_n) = c sum_j q_j 2 (sqrt(t_n - t_(j-1)) - sqrt(t_n - t_j)),  c = sqrt(D) / (k sqrt(pi)),

k = 16 W/(m degC), D = 4.07e-6 m^2/s, summed directly over the whole history (no kernel
approximation). Step j's flux uses the friction coefficient of the sample before (explicit
coupling) and the step's mean speed |du| / dt at the step's mid position. Since a step heats
a contiguous run of points uniformly, the mean over the points under the slider at t_n is
computed from the overlap of the two runs, which is the same sum over points, vectorised.
A campaign keeps one plate: a test begins ``rest_before`` seconds after the previous one ended
(no flux in between), so the earlier tests' heat decays as the half-space solution says; each
test adds its rise to its own initial temperature T0.

Measurement
-----------
White, AR(1) (coloured, lag-one correlation rho) or band-limited noise on the force (as a
fraction of the nominal friction force mu0 W), the displacement, the velocity and the axial
force channels (:func:`noise`).

Checks
------
``python -m validation.diagnosis.independent_truths`` runs :func:`checks`: a rigid-plastic flat
slider dissipates 4 mu W A per cycle (and 4 mu W (A - b/2) with a play b); a constant flux on
a half-space heats by 2 q sqrt(D t / pi) / k; the closed-form Bouc-Wen matches a sub-stepped
integration; a frictionless spherical surface gives W u / sqrt(R^2 - u^2); an integer lag is
a shift of the samples.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

CONDUCTIVITY = 16.0  # k [W/(m degC)] (0.016 W/(mm degC), JSME data book, as the paper)
DIFFUSIVITY = 4.07e-6  # D [m^2/s] (4.07 mm^2/s)
HEAT_COEFFICIENT = math.sqrt(DIFFUSIVITY) / (CONDUCTIVITY * math.sqrt(math.pi))  # c of Eq. 4
SPACING = 0.005  # [m] monitor points of the precise model
REFERENCE_SPEED = 0.4  # [m/s] alpha's reference (400 mm/s)
REFERENCE_TEMPERATURE = 20.0  # [degC] beta's reference
MU_T0 = 0.075  # Eq. 7
TRANSITIONS = ("rigid-plastic", "elastic-plastic", "smooth")
_EDGE = 1.0e-9  # [m] slack of the closed heating window (a point exactly on the edge is in)


# --- the paper's factors (Eq. 1-3) ---------------------------------------------------------


def gamma(sigma: float) -> float:
    """Eq. 1, sigma in Pa (converted to N/mm^2)."""
    return 2.03 * (sigma / 1.0e6) ** -0.19 + 0.068


def alpha(speed: float) -> float:
    """Eq. 2, speed in m/s (converted to mm/s)."""
    return 1.0 - 0.55 * math.exp(-0.019 * abs(speed) * 1000.0)


def beta(temperature: float) -> float:
    """Eq. 3, temperature in degC."""
    return 1.13 * math.exp(-0.007 * temperature)


# --- the bearing's description --------------------------------------------------------------


@dataclass(frozen=True)
class Velocity:
    """Velocity dependence of mu.

    law : ``"paper"`` (Eq. 2, raw), ``"paper-normalised"`` (Eq. 2 / its value at 0.4 m/s),
    ``"exp"`` (1 - (1 - ratio) exp(-|v| / speed), ratio = mu_slow / mu_fast) or
    ``"stribeck"`` (1 + peak exp(-(|v| / speed)^2)).
    """

    law: str
    ratio: float = 0.5
    speed: float = 0.02  # [m/s]
    peak: float = 0.5

    def factor(self, v: float) -> float:
        v = abs(v)
        if self.law == "paper":
            return alpha(v)
        if self.law == "paper-normalised":
            return alpha(v) / alpha(REFERENCE_SPEED)
        if self.law == "exp":
            return 1.0 - (1.0 - self.ratio) * math.exp(-v / self.speed)
        if self.law == "stribeck":
            return 1.0 + self.peak * math.exp(-((v / self.speed) ** 2))
        raise ValueError(f"unknown velocity law {self.law!r}")


@dataclass(frozen=True)
class Breakaway:
    """Static peak after each reversal: ``linear`` 1 + peak max(0, 1 - s / length) or
    ``gauss`` 1 + peak exp(-(s / length)^2), s the travel since the reversal [m]."""

    shape: str
    peak: float
    length: float

    def factor(self, s: float) -> float:
        if self.shape == "linear":
            return 1.0 + self.peak * max(0.0, 1.0 - s / self.length)
        if self.shape == "gauss":
            return 1.0 + self.peak * math.exp(-((s / self.length) ** 2))
        raise ValueError(f"unknown breakaway shape {self.shape!r}")


@dataclass(frozen=True)
class Wear:
    """Friction changing over a campaign: ``step`` 1 - amount k (k-th test, from 0) or
    ``power`` 1 + amount (S / campaign_travel)^power (S the travel so far [m])."""

    kind: str
    amount: float
    power: float = 0.5
    campaign_travel: float = 1.0

    def factor(self, test_index: int, travel: float) -> float:
        if self.kind == "step":
            return 1.0 - self.amount * test_index
        if self.kind == "power":
            return 1.0 + self.amount * (max(travel, 0.0) / self.campaign_travel) ** self.power
        raise ValueError(f"unknown wear kind {self.kind!r}")


@dataclass(frozen=True)
class Bearing:
    """A truth bearing; see the module docstring.

    weight : nominal axial load W [N] (the reference of the pressure factor and of the noise).
    radius : effective radius R [m]; ``math.inf`` for a flat slider.
    restoring : ``"linear"`` or ``"spherical"``.
    transition, yield_displacement : the transition and u_y [m].
    pressure, temperature : None, ``"normalised"`` or ``"paper"``.
    asymmetry : a, mu(+) / mu(-) = (1 + a) / (1 - a).
    backlash : total width b of the play [m].
    """

    weight: float
    radius: float = 4.5
    slider_diameter: float = 0.3
    mu0: float = 0.041
    restoring: str = "linear"
    transition: str = "elastic-plastic"
    yield_displacement: float = 5.0e-4
    velocity: Velocity | None = None
    pressure: str | None = None
    temperature: str | None = None
    breakaway: Breakaway | None = None
    wear: Wear | None = None
    asymmetry: float = 0.0
    backlash: float = 0.0

    def __post_init__(self) -> None:
        if self.transition not in TRANSITIONS:
            raise ValueError(f"unknown transition {self.transition!r}")
        if self.restoring not in ("linear", "spherical"):
            raise ValueError(f"unknown restoring law {self.restoring!r}")
        if not -1.0 < self.asymmetry < 1.0:
            raise ValueError("asymmetry must lie in (-1, 1)")

    @property
    def contact_radius(self) -> float:
        return 0.5 * self.slider_diameter

    @property
    def area(self) -> float:
        return math.pi * self.contact_radius**2


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


# --- heating ---------------------------------------------------------------------------------


class Plate:
    """One plate's monitor line and its whole flux history (see the module docstring).

    Every step with heat is stored as (t_start, t_end, first point, last point, q): the step
    heats the points first..last (indices of x_i = SPACING i) with the flux q [W/m^2].
    """

    def __init__(self, contact_radius: float, spacing: float = SPACING) -> None:
        self.half_width = math.sqrt(math.pi) * contact_radius / 2.0
        self.spacing = spacing
        self._n = 0
        self._data = np.zeros((5, 1024))  # rows: t_start, t_end, first, last, q

    def window(self, centre: float) -> tuple[int, int]:
        """First and last index of the points within the half width of ``centre``."""
        first = math.ceil((centre - self.half_width - _EDGE) / self.spacing)
        last = math.floor((centre + self.half_width + _EDGE) / self.spacing)
        return first, last

    def add(self, t_start: float, t_end: float, centre: float, flux: float) -> None:
        """Heat the points under ``centre`` with ``flux`` from ``t_start`` to ``t_end``."""
        if flux <= 0.0 or t_end <= t_start:
            return
        if self._n == self._data.shape[1]:
            self._data = np.concatenate([self._data, np.zeros_like(self._data)], axis=1)
        first, last = self.window(centre)
        self._data[:, self._n] = (t_start, t_end, first, last, flux)
        self._n += 1

    def rise(self, time: float, centre: float) -> float:
        """Mean temperature rise at ``time`` of the points under ``centre`` [degC]."""
        if self._n == 0:
            return 0.0
        t0, t1, first, last, q = self._data[:, : self._n]
        a, b = self.window(centre)
        overlap = np.minimum(last, b) - np.maximum(first, a) + 1.0
        use = overlap > 0.0
        if not use.any():
            return 0.0
        t0, t1, q, overlap = t0[use], t1[use], q[use], overlap[use]
        # 2 (sqrt(t - t0) - sqrt(t - t1)) without cancellation
        weights = 2.0 * (t1 - t0) / (np.sqrt(time - t0) + np.sqrt(np.maximum(time - t1, 0.0)))
        return HEAT_COEFFICIENT * float(np.dot(q * overlap, weights)) / (b - a + 1)


# --- transitions -----------------------------------------------------------------------------


def _bouc_wen(zeta: float, du: float, u_y: float, c_plus: float, c_minus: float) -> float:
    """Exact n = 2 Bouc-Wen step (see the module docstring)."""
    if du == 0.0:
        return zeta
    cap = c_plus if (zeta > 0.0 or (zeta == 0.0 and du > 0.0)) else c_minus
    z = zeta / cap
    if z * du >= 0.0:  # loading on this side of 0
        z = min(max(z, -1.0 + 1e-15), 1.0 - 1e-15)
        return cap * math.tanh(math.atanh(z) + du / (cap * u_y))
    # unloading towards 0: tan law until z = 0, the rest loads the other side
    to_zero = -math.atan(z) * cap * u_y  # the increment (sign of du) that brings z to 0
    if abs(du) <= abs(to_zero):
        return cap * math.tan(math.atan(z) + du / (cap * u_y))
    rest = du - to_zero
    other = c_plus if rest > 0.0 else c_minus
    return other * math.tanh(rest / (other * u_y))


def _transition(kind: str, zeta: float, du: float, u_y: float, c_plus: float,
                c_minus: float) -> float:
    if kind == "rigid-plastic":
        if du > 0.0:
            return c_plus
        if du < 0.0:
            return -c_minus
        return zeta
    if kind == "elastic-plastic":
        return min(c_plus, max(-c_minus, zeta + du / u_y))
    return _bouc_wen(zeta, du, u_y, c_plus, c_minus)


# --- the simulation ------------------------------------------------------------------------


@dataclass
class _Campaign:
    """What carries over from test to test: the plate, the clock, the travel."""

    plate: Plate | None
    clock: float = 0.0
    travel: float = 0.0


def _restoring(bearing: Bearing, u: float, n: float) -> float:
    if math.isinf(bearing.radius):
        return 0.0
    if bearing.restoring == "spherical":
        return n * u / math.sqrt(bearing.radius**2 - u * u)
    return n * u / bearing.radius


def _force(bearing: Bearing, u: float, n: float, mu: float, zeta: float) -> float:
    restoring = _restoring(bearing, u, n)
    if bearing.restoring == "spherical" and not math.isinf(bearing.radius):
        return (restoring + mu * zeta * n) / (1.0 - mu * zeta * u / bearing.radius)
    return restoring + mu * n * zeta


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
            zeta = -_restoring(bearing, ub, load) / (mu * load)
            zeta = min(c_plus, max(-c_minus, zeta))
        was_touching = touching
        zeta = _transition(bearing.transition, zeta, du, u_y, c_plus, c_minus)
        ub = new
        force = _force(bearing, ub, load, mu, zeta) if touching else 0.0
        out["force"][i] = force
        out["bearing"][i] = ub
        out["mu"][i] = mu
        out["temperature"][i] = temperature
        out["restoring"][i] = _restoring(bearing, ub, load) if touching else 0.0
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


# --- sanity checks -------------------------------------------------------------------------


def _loop_energy(force: np.ndarray, displacement: np.ndarray) -> float:
    """Energy dissipated along a closed path, the trapezoidal integral of F du [J]."""
    return float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(displacement)))


def checks(verbose: bool = True) -> dict[str, float]:
    """Run the sanity checks of the module docstring; return each relative error."""
    errors = {}
    w, mu, amp = 1.0e6, 0.05, 0.1
    # 1. rigid-plastic flat slider: EDC = 4 mu W A (second cycle)
    flat = Bearing(w, radius=math.inf, mu0=mu, transition="rigid-plastic")
    test = sine_test(amp, 2.0, 2, 0.001, w)
    out = simulate(flat, [test])[0]
    second = out["time"] >= 2.0 - 1e-9
    edc = _loop_energy(out["force"][second], out["displacement"][second])
    errors["edc rigid-plastic"] = abs(edc / (4 * mu * w * amp) - 1.0)
    # ... and with a play b: the bearing travels A - b/2 each way
    play = Bearing(w, radius=math.inf, mu0=mu, transition="rigid-plastic", backlash=0.004)
    out = simulate(play, [test])[0]
    edc = _loop_energy(out["force"][second], out["displacement"][second])
    errors["edc with play"] = abs(edc / (4 * mu * w * (amp - 0.002)) - 1.0)
    # 2. constant flux on a half-space: 2 q sqrt(D t / pi) / k
    plate = Plate(0.15)
    q, steps = 1.0e5, np.linspace(0.0, 10.0, 101)
    for a, b in itertools.pairwise(steps):
        plate.add(float(a), float(b), 0.0, q)
    exact = 2.0 * q * math.sqrt(DIFFUSIVITY * 10.0 / math.pi) / CONDUCTIVITY
    errors["half-space flux"] = abs(plate.rise(10.0, 0.0) / exact - 1.0)
    # after a rest: the solution of a pulse, 2 q (sqrt(t) - sqrt(t - 10)) sqrt(D / pi) / k
    later = 2.0 * q * (math.sqrt(40.0) - math.sqrt(30.0)) * math.sqrt(DIFFUSIVITY / math.pi)
    errors["half-space pulse"] = abs(plate.rise(40.0, 0.0) / (later / CONDUCTIVITY) - 1.0)
    # 3. Bouc-Wen closed form against 2000 explicit sub-steps per step
    u = 0.004 * np.sin(np.linspace(0.0, 4.0 * math.pi, 400))
    z_exact, z_sub, worst = 0.0, 0.0, 0.0
    for du in np.diff(u):
        z_exact = _bouc_wen(z_exact, float(du), 1.0e-3, 1.2, 0.8)
        for _ in range(2000):
            h = du / 2000.0
            cap = 1.2 if (z_sub > 0.0 or (z_sub == 0.0 and h > 0.0)) else 0.8
            z = z_sub / cap
            z_sub += cap * (1.0 - z * z * math.copysign(1.0, h * z)) * h / (cap * 1.0e-3)
        worst = max(worst, abs(z_exact - z_sub))
    errors["bouc-wen sub-steps"] = worst
    # 4. a frictionless spherical surface
    sphere = Bearing(w, radius=1.5, mu0=1e-12, restoring="spherical")
    out = simulate(sphere, [sine_test(0.4, 4.0, 0.25, 0.01, w)])[0]
    u_end = out["bearing"][-1]
    errors["spherical restoring"] = abs(out["force"][-1] / (w * u_end / math.sqrt(1.5**2 - u_end
                                                                                   ** 2)) - 1)
    # 5. an integer lag is a shift of the samples
    pendulum = Bearing(w, mu0=mu)
    test = sine_test(0.1, 2.0, 1, 0.01, w)
    base = simulate(pendulum, [test])[0]["force"]
    late = simulate(pendulum, [test], lag=0.03)[0]["force"]
    errors["integer lag"] = float(np.max(np.abs(late[3:] - base[:-3]))) / (mu * w)
    if verbose:
        for name, value in errors.items():
            print(f"{name:22s} {value:.2e}")
    return errors


if __name__ == "__main__":
    checks()
