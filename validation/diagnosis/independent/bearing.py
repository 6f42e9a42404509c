"""The independent truth's bearing: its friction coefficient, heating and hysteresis.

Part of the independent truths (:mod:`validation.diagnosis.independent`), written from
the paper and from physics. Like the rest of them, this module imports only numpy and the
standard library: it shares no code with ``isolator``, ``structures``, ``dcfpb``,
``groundmotions`` or ``tests``, so a mistake in the package cannot be repeated in the data the
package's diagnosis is judged on. The test machine that drives this bearing is
:mod:`validation.diagnosis.independent.rig`.

Units are SI at every argument (m, s, N, Pa, degC); the paper's N/mm^2 and mm/s appear only
inside its factors (Nishimoto et al., "SSB part 2: friction models", Eq. 1-8).

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
"""

from __future__ import annotations

import math
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


def bouc_wen_step(zeta: float, du: float, u_y: float, c_plus: float, c_minus: float) -> float:
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


def transition_step(kind: str, zeta: float, du: float, u_y: float, c_plus: float,
                    c_minus: float) -> float:
    """zeta after a step du of the bearing with the transition ``kind`` (module docstring)."""
    if kind == "rigid-plastic":
        if du > 0.0:
            return c_plus
        if du < 0.0:
            return -c_minus
        return zeta
    if kind == "elastic-plastic":
        return min(c_plus, max(-c_minus, zeta + du / u_y))
    return bouc_wen_step(zeta, du, u_y, c_plus, c_minus)


# --- the force -------------------------------------------------------------------------------


def restoring_force(bearing: Bearing, u: float, n: float) -> float:
    """F_r(u_b, N) [N] of the bearing's restoring law at u_b = ``u`` [m], N = ``n`` [N]."""
    if math.isinf(bearing.radius):
        return 0.0
    if bearing.restoring == "spherical":
        return n * u / math.sqrt(bearing.radius**2 - u * u)
    return n * u / bearing.radius


def bearing_force(bearing: Bearing, u: float, n: float, mu: float, zeta: float) -> float:
    """The horizontal force F [N] at u_b = ``u`` [m], N = ``n`` [N], mu and zeta (with the
    normal-force coupling of the spherical law solved per sample, see the module docstring)."""
    restoring = restoring_force(bearing, u, n)
    if bearing.restoring == "spherical" and not math.isinf(bearing.radius):
        return (restoring + mu * zeta * n) / (1.0 - mu * zeta * u / bearing.radius)
    return restoring + mu * n * zeta
