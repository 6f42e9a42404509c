"""The bidirectional truth's bearing: vector friction, its coefficient and the 2D heating field.

Part of the bidirectional truth (:mod:`validation.diagnosis.bidirectional`), written from the
paper (Nishimoto et al., "SSB part 2: friction models", Eq. 1-6) and from physics. It imports
only numpy and the standard library: it shares no code with ``isolator``, ``structures``,
``groundmotions``, ``dcfpb`` or the one-direction truth in
:mod:`validation.diagnosis.independent`, so that neither the package's element nor the 1D truth
can pass a mistake on to the data the two-direction diagnosis is judged on.

Units are SI at every argument (m, s, N, Pa, degC); the paper's N/mm^2 and mm/s appear only
inside its factors.

The bearing
-----------
The horizontal force is a vector, F = F_r(u) + mu(t) N z(t), with u the bearing's relative
displacement (x, y) and z the friction direction vector, |z| <= 1:

- restoring force: ``linear`` F_r = N u / R (R = inf: a flat slider, F_r = 0), or
  ``spherical`` F_r = N u / sqrt(R^2 - |u|^2) (no normal-force coupling);
- transitions of z with the bearing's displacement step du (vectors):

  - ``rigid-plastic``: z = du / |du| while sliding, held when du = 0 (the force turns with
    the sliding direction at once);
  - ``elastic-plastic`` (a radial return map): z_trial = z + du / u_y; z = z_trial /
    max(1, |z_trial|). On a circular orbit z settles on the unit circle, lagging the sliding
    direction by a small angle;
  - ``smooth``: the isotropic Bouc-Wen law with n = 2 and beta = gamma = 1/2,
    dz = (du - z max(z . du, 0)) / u_y: loading shrinks the growth of z along z as
    1 - |z|^2, unloading is elastic. Integrated with sub-steps of at most u_y / 20 (midpoint
    rule, at most 200 per sample). On a line it is tanh loading and linear unloading.

The friction coefficient
------------------------
mu = mu0 x velocity x pressure x temperature x wear factors, each optional:

- velocity, on the speed |v| (the norm of the bearing's velocity vector): ``exp``
  1 - (1 - ratio) exp(-|v| / speed) or ``paper`` Eq. 2 alpha(|v|) / alpha(0.4 m/s);
- pressure: Eq. 1 gamma(sigma) / gamma(sigma_nominal), sigma = N / (pi r^2);
- temperature: Eq. 3 beta(T) / beta(20 degC), T the mean contact temperature (below);
- wear: ``step`` 1 - amount k for the k-th test of the campaign (k = 0, 1, ...), or
  ``travel`` 1 - amount S / travel_scale, S the travel accumulated over the campaign [m].

The heating field (Eq. 4-6 on the plate surface)
------------------------------------------------
Each concave plate of the double concave bearing sees the slider's centre at u / 2 and takes
half the frictional power per unit area, q = mu p |v| / 2 (p = N / (pi r^2)), on the contact
disc of radius r (Eq. 5 with the disc instead of the paper's square of equal area: in two
directions there is no line of sliding to put monitor points on). Every point of the plate
surface conducts into the half-space below it, as in Eq. 4 (no lateral conduction, as in the
paper), so a point P heated by the piecewise-constant flux history reaches

    dT(P, t) = c sum_j q_j [|P - c_j| <= r] 2 (sqrt(t - t_(j-1)) - sqrt(t - t_j)),
    c = sqrt(D) / (k sqrt(pi)),

with c_j the disc's centre during step j (its mid position). The contact temperature is the
mean of the field over the disc at the slider's present centre c; because each step heats a
uniform disc, that mean is a direct sum over the whole flux history with the overlap of two
discs, A(|c - c_j|) / (pi r^2), the lens area of two circles of radius r:

    A(d) = 2 r^2 acos(d / 2r) - (d / 2) sqrt(4 r^2 - d^2)   (0 for d >= 2r).

:meth:`HeatField.field` gives the field itself at any set of points (the check compares the
lens sum with a grid of monitor points). k = 16 W/(m degC) and D = 4.07e-6 m^2/s (JSME, as the
paper).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

CONDUCTIVITY = 16.0  # k [W/(m degC)]
DIFFUSIVITY = 4.07e-6  # D [m^2/s]
HEAT_COEFFICIENT = math.sqrt(DIFFUSIVITY) / (CONDUCTIVITY * math.sqrt(math.pi))
REFERENCE_SPEED = 0.4  # [m/s]
REFERENCE_TEMPERATURE = 20.0  # [degC]
TRANSITIONS = ("rigid-plastic", "elastic-plastic", "smooth")


def pressure_factor(sigma: float) -> float:
    """Eq. 1, gamma(sigma) with sigma in Pa (the paper's N/mm^2 inside)."""
    return 2.03 * (sigma / 1.0e6) ** -0.19 + 0.068


def speed_factor(speed: float) -> float:
    """Eq. 2, alpha(v) with the speed in m/s (the paper's mm/s inside)."""
    return 1.0 - 0.55 * math.exp(-0.019 * abs(speed) * 1000.0)


def temperature_factor(temperature: float) -> float:
    """Eq. 3, beta(T) with T in degC."""
    return 1.13 * math.exp(-0.007 * temperature)


@dataclass(frozen=True)
class SpeedLaw:
    """Velocity dependence on the speed |v| [m/s]: ``exp`` or ``paper`` (module docstring)."""

    law: str = "exp"
    ratio: float = 0.5  # mu_slow / mu_fast
    speed: float = 0.02  # [m/s]

    def factor(self, v: float) -> float:
        """The factor at the speed ``v`` [m/s]."""
        if self.law == "exp":
            return 1.0 - (1.0 - self.ratio) * math.exp(-abs(v) / self.speed)
        if self.law == "paper":
            return speed_factor(v) / speed_factor(REFERENCE_SPEED)
        raise ValueError(f"unknown speed law {self.law!r}")


@dataclass(frozen=True)
class WearLaw:
    """Friction changing over a campaign: ``step`` 1 - amount k (k-th test from 0) or
    ``travel`` 1 - amount S / travel_scale (S the campaign's travel so far [m])."""

    kind: str = "step"
    amount: float = 0.05
    travel_scale: float = 1.0  # [m]

    def factor(self, test_index: int, travel: float) -> float:
        """The factor of test ``test_index`` after the travel ``travel`` [m]."""
        if self.kind == "step":
            return 1.0 - self.amount * test_index
        if self.kind == "travel":
            return 1.0 - self.amount * travel / self.travel_scale
        raise ValueError(f"unknown wear kind {self.kind!r}")


@dataclass(frozen=True)
class Bearing2D:
    """A two-direction truth bearing (module docstring).

    weight : nominal axial load W [N] (the reference of the pressure factor).
    radius : effective radius R [m] (``math.inf``: a flat slider).
    slider_diameter : [m].
    mu0 : friction coefficient at the references.
    restoring : ``"linear"`` or ``"spherical"``.
    transition, yield_displacement : the transition of z and u_y [m].
    speed : a :class:`SpeedLaw` or None.
    pressure, heating : whether Eq. 1 / Eq. 3-5 act.
    wear : a :class:`WearLaw` or None.
    play : total play (b_x, b_y) [m] between the actuators and the bearing, per axis.
    """

    weight: float
    radius: float = 4.5
    slider_diameter: float = 0.3
    mu0: float = 0.041
    restoring: str = "linear"
    transition: str = "elastic-plastic"
    yield_displacement: float = 5.0e-4
    speed: SpeedLaw | None = None
    pressure: bool = False
    heating: bool = False
    wear: WearLaw | None = None
    play: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        if self.transition not in TRANSITIONS:
            raise ValueError(f"unknown transition {self.transition!r}")
        if self.restoring not in ("linear", "spherical"):
            raise ValueError(f"unknown restoring law {self.restoring!r}")

    @property
    def contact_radius(self) -> float:
        """r [m]."""
        return 0.5 * self.slider_diameter

    @property
    def area(self) -> float:
        """pi r^2 [m^2]."""
        return math.pi * self.contact_radius**2


# --- the heating field ---------------------------------------------------------------------


def lens_area(distance: np.ndarray, radius: float) -> np.ndarray:
    """Overlap area [m^2] of two discs of radius ``radius`` whose centres are ``distance``
    apart."""
    d = np.minimum(np.abs(np.asarray(distance, dtype=float)), 2.0 * radius)
    return 2.0 * radius**2 * np.arccos(d / (2.0 * radius)) - 0.5 * d * np.sqrt(
        np.maximum(4.0 * radius**2 - d * d, 0.0))


class HeatField:
    """One plate's surface temperature field, the direct sum over its whole flux history.

    Each step with heat is stored as (t_start, t_end, centre x, centre y, q): the disc of
    radius r around the centre took the flux q [W/m^2] from t_start to t_end [s].
    """

    def __init__(self, contact_radius: float) -> None:
        self.radius = contact_radius
        self._n = 0
        self._data = np.zeros((5, 4096))

    def add(self, t_start: float, t_end: float, centre: np.ndarray, flux: float) -> None:
        """Heat the disc around ``centre`` [m] with ``flux`` [W/m^2] over [t_start, t_end]."""
        if flux <= 0.0 or t_end <= t_start:
            return
        if self._n == self._data.shape[1]:
            self._data = np.concatenate([self._data, np.zeros_like(self._data)], axis=1)
        self._data[:, self._n] = (t_start, t_end, centre[0], centre[1], flux)
        self._n += 1

    def _weights(self, time: float) -> tuple[np.ndarray, ...]:
        t0, t1, cx, cy, q = self._data[:, : self._n]
        # 2 (sqrt(t - t0) - sqrt(t - t1)) written without cancellation
        w = 2.0 * (t1 - t0) / (np.sqrt(np.maximum(time - t0, 0.0))
                               + np.sqrt(np.maximum(time - t1, 0.0)) + 1e-300)
        return w * q, cx, cy

    def contact_rise(self, time: float, centre: np.ndarray) -> float:
        """Mean rise [degC] at ``time`` of the field over the disc around ``centre``."""
        if self._n == 0:
            return 0.0
        wq, cx, cy = self._weights(time)
        share = lens_area(np.hypot(cx - centre[0], cy - centre[1]), self.radius) / (
            math.pi * self.radius**2)
        return HEAT_COEFFICIENT * float(np.dot(wq, share))

    def field(self, time: float, points: np.ndarray) -> np.ndarray:
        """The rise [degC] at ``time`` at each of ``points`` (shape (m, 2), plate coordinates
        [m])."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        if self._n == 0:
            return np.zeros(len(points))
        wq, cx, cy = self._weights(time)
        inside = np.hypot(points[:, :1] - cx, points[:, 1:2] - cy) <= self.radius + 1e-12
        return HEAT_COEFFICIENT * (inside.astype(float) @ wq)


# --- transitions and the force ---------------------------------------------------------------


def transition_step(kind: str, z: np.ndarray, du: np.ndarray, u_y: float) -> np.ndarray:
    """z after the bearing's displacement step ``du`` [m] (module docstring)."""
    step = float(math.hypot(du[0], du[1]))
    if step == 0.0:
        return z
    if kind == "rigid-plastic":
        return du / step
    if kind == "elastic-plastic":
        trial = z + du / u_y
        size = math.hypot(trial[0], trial[1])
        return trial / size if size > 1.0 else trial
    parts = min(200, max(1, math.ceil(step / (u_y / 20.0))))
    h = du / parts

    def rate(zz: np.ndarray) -> np.ndarray:
        return (h - zz * max(float(zz @ h), 0.0)) / u_y

    z = z.copy()
    for _ in range(parts):
        z = z + rate(z + 0.5 * rate(z))
    size = math.hypot(z[0], z[1])
    return z / size if size > 1.0 else z


def restoring_force(bearing: Bearing2D, u: np.ndarray, n: float) -> np.ndarray:
    """F_r [N] (vector) at the bearing's displacement ``u`` [m] under the axial load ``n``
    [N]."""
    if math.isinf(bearing.radius):
        return np.zeros(2)
    if bearing.restoring == "spherical":
        return n * u / math.sqrt(bearing.radius**2 - float(u @ u))
    return n * u / bearing.radius
