"""The tuning panel's own truth model, written from the paper and physics (numpy only).

This module imports only numpy and the standard library: nothing of ``isolator``,
``structures``, ``dcfpb`` or ``groundmotions``, so a mistake in the package cannot be shared
by the data it is judged on. It is deliberately plain: one Python loop over samples.

A bearing test machine imposes an *actuator* displacement history u_a(t) and records the
horizontal force through the load cell. Conventions (SI throughout; the paper's N/mm^2 and
mm/s inside its factors only):

- **Load train.** With a play (backlash) of total width b the bearing's displacement u_b
  follows u_a only when the gap is closed on one side, |u_a - u_b| = b/2; while the gap is
  open the bearing stands still and the load cell reads zero. When contact is made again the
  bearing's friction force starts from zero (the pre-sliding state restarts at z = 0).
- **Transition** of the hysteretic variable z with the bearing's displacement increments du:
  ``rigid-plastic``: z = sign of the bearing's velocity (held through v = 0): the force
  reverses on the sample after the displacement peak (the paper's own friction form);
  ``elastic-plastic``: z <- clip(z + du / u_y, -1, 1);
  ``smooth``: Bouc-Wen with n = 2, beta = gamma = 1/2: dz/du = (1 - z^2) / u_y when loading
  (z du > 0), 1 / u_y when unloading, integrated in 20 sub-steps.
- **Friction** mu = mu0 x velocity x pressure x temperature x breakaway x direction factors:
  velocity ``paper``: Eq. 2 normalised at 400 mm/s, alpha(v) / alpha(0.4 m/s);
  ``exponential``: 1 - a exp(-|v| / v_c); ``stribeck``: 1 + a exp(-(|v| / v_c)^2);
  pressure: Eq. 1, gamma(sigma) / gamma(sigma_nominal), sigma = N / (pi r^2) in N/mm^2;
  temperature: Eq. 3, beta(T) / beta(T0), T the contact temperature from Eq. 4-5 (below);
  breakaway: 1 + b_s max(0, 1 - s / d), s the bearing's travel since its last reversal (a
  linear fade, unlike the library's exponential); direction: 1 + a sign(z).
- **Heating** (Eq. 4-5, the paper's precise model): monitor points every 5 mm along the line
  of sliding on each plate; the slider centre is at u_b / 2 on each plate of a double concave
  bearing; a point is heated when within sqrt(pi) r / 2 of it, by q = mu p |v| / 2; its
  temperature is the exact integral of the piecewise-constant flux,
  dT(t_n) = c sum_k q_k 2 (sqrt(t_n - t_(k-1)) - sqrt(t_n - t_k)), c = sqrt(D) / (k sqrt(pi)),
  k = 16 W/(m degC), D = 4.07e-6 m^2/s; the contact temperature is the mean over the heated
  points. The flux of a step uses the friction coefficient of the step before (explicit).
  Tests of a campaign may share the plate: a rest between them is a gap in time with no flux.
- **Normal force and restoring force.** ``linear``: F = N u_b / R + mu N z. ``spherical``:
  the restoring force N u_b / sqrt(R^2 - u_b^2) and the normal force on the surface
  N + F u_b / R (solved by fixed-point iteration), so
  F = N u_b / sqrt(R^2 - u_b^2) + mu (N + F u_b / R) z.
- **Channels.** The force channel may lag the displacement channel by tau: the clean force is
  computed on a grid ten times finer and read at t - tau. Measurement noise is white or
  coloured (AR(1)) on the force and the displacement.

Checks (:func:`checks`): a rigid-plastic flat slider's loop dissipates 4 mu N A per cycle; a
constant flux on a half-space heats a point by 2 q sqrt(D t / pi) / k::

    python -c "from validation.diagnosis.tuning.truths import checks; checks()"
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

CONDUCTIVITY = 16.0  # k [W/(m degC)]
DIFFUSIVITY = 4.07e-6  # D [m^2/s]
HEAT_C = math.sqrt(DIFFUSIVITY) / (CONDUCTIVITY * math.sqrt(math.pi))
SPACING = 0.005  # [m] monitor points of the precise model
REFERENCE_SPEED = 0.4  # [m/s] where the paper's alpha is 1 (Eq. 7's mu_t0 is at 400 mm/s)


def gamma(sigma_pa: float) -> float:
    """Eq. 1 with sigma in Pa."""
    return 2.03 * (sigma_pa / 1.0e6) ** -0.19 + 0.068


def alpha(speed: float) -> float:
    """Eq. 2 with the speed in m/s."""
    return 1.0 - 0.55 * math.exp(-0.019 * abs(speed) * 1000.0)


def beta(temperature: float) -> float:
    """Eq. 3 with T in degC."""
    return 1.13 * math.exp(-0.007 * temperature)


@dataclass
class Truth:
    """What a truth bearing is (see the module docstring); lengths in m, forces in N."""

    weight: float
    radius: float = 4.5
    slider_diameter: float = 0.3
    mu0: float = 0.041
    transition: str = "elastic-plastic"
    yield_displacement: float = 5.0e-4
    geometry: str = "linear"
    velocity: tuple | None = None
    pressure: bool = False
    heating: bool = False
    breakaway: tuple | None = None
    direction: float = 0.0
    backlash: float = 0.0
    initial_temperature: float = 20.0

    @property
    def contact_radius(self) -> float:
        return 0.5 * self.slider_diameter

    @property
    def area(self) -> float:
        return math.pi * self.contact_radius**2


def _transition_step(kind: str, z: float, du: float, velocity: float, u_y: float) -> float:
    if kind == "rigid-plastic":
        return z if velocity == 0.0 else math.copysign(1.0, velocity)
    if kind == "elastic-plastic":
        return min(1.0, max(-1.0, z + du / u_y))
    if kind == "smooth":
        h = du / 20.0
        for _ in range(20):
            slope = (1.0 - z * z) if z * h > 0.0 else 1.0
            z = min(1.0, max(-1.0, z + slope * h / u_y))
        return z
    raise ValueError(f"unknown transition {kind!r}")


def _velocity_factor(spec: tuple | None, speed: float) -> float:
    if spec is None:
        return 1.0
    if spec[0] == "paper":
        return alpha(speed) / alpha(REFERENCE_SPEED)
    if spec[0] == "exponential":
        return 1.0 - spec[1] * math.exp(-speed / spec[2])
    if spec[0] == "stribeck":
        return 1.0 + spec[1] * math.exp(-((speed / spec[2]) ** 2))
    raise ValueError(f"unknown velocity law {spec!r}")


class Plate:
    """The precise model's monitor line on one plate, with its whole flux history."""

    def __init__(self, reach: float, contact_radius: float) -> None:
        half = reach + contact_radius + SPACING
        self.points = np.arange(-half, half + 1e-12, SPACING)
        self.window = math.sqrt(math.pi) * contact_radius / 2.0
        self.times: list[float] = []
        self.fluxes: list[np.ndarray] = []

    def heated(self, centre: float) -> np.ndarray:
        return np.abs(self.points - centre) <= self.window + 1e-12

    def temperature_rise(self, time: float, mask: np.ndarray) -> float:
        """Mean rise over the points ``mask`` at ``time`` from the committed history."""
        if len(self.times) < 2 or not mask.any():
            return 0.0
        t = np.asarray(self.times)
        roots = np.sqrt(np.maximum(time - t, 0.0))
        weights = 2.0 * np.diff(t) / (roots[:-1] + roots[1:] + 1e-300)
        q = np.asarray(self.fluxes[1:])[:, mask]
        return float(HEAT_C * np.mean(weights @ q))

    def add(self, time: float, flux: np.ndarray | None) -> None:
        """The flux over the interval ending at ``time`` (None: no flux)."""
        self.times.append(time)
        self.fluxes.append(np.zeros(self.points.size) if flux is None else flux)


def simulate(truth: Truth, time: np.ndarray, actuator: np.ndarray, *,
             axial: np.ndarray | None = None, plate: Plate | None = None,
             start_time: float = 0.0) -> dict[str, np.ndarray]:
    """The clean histories of one test: time, bearing displacement, force, axial force, mu.

    Parameters
    ----------
    truth : Truth
    time, actuator : ndarray
        Sample times [s] and the actuator's displacement [m] (starting at rest, near 0).
    axial : ndarray, optional
        Axial load at each sample [N] (default: the truth's weight).
    plate : Plate, optional
        The heating history of earlier tests (updated in place); ``start_time`` [s] is this
        test's start on the plate's clock.
    """
    n = time.size
    axial = np.full(n, truth.weight) if axial is None else np.asarray(axial, float)
    if truth.heating and plate is None:
        plate = Plate(float(np.max(np.abs(actuator))) / 2.0, truth.contact_radius)
    if plate is not None:
        # the rest since the previous test (or the start of the history) has no flux
        plate.add(start_time + time[0], None)
    half = 0.5 * truth.backlash
    force = np.zeros(n)
    mu_out = np.full(n, truth.mu0)
    bearing = np.zeros(n)
    ub = float(actuator[0])
    z = 0.0
    last_dir = 0.0
    reversal_at = ub
    mu_prev = truth.mu0
    previous_contact = True
    bearing[0] = ub
    for i in range(1, n):
        dt = float(time[i] - time[i - 1])
        ua = float(actuator[i])
        if ua - ub > half:
            new, contact = ua - half, True
        elif ub - ua > half:
            new, contact = ua + half, True
        else:  # inside the gap (always "in contact" without a play)
            new, contact = ub, half == 0.0
        du = new - ub
        velocity = du / dt
        if contact and not previous_contact:
            z = 0.0  # the friction force rebuilds from zero at re-engagement
        if du != 0.0:
            direction = math.copysign(1.0, du)
            if direction != last_dir:
                reversal_at = ub
                last_dir = direction
        z = _transition_step(truth.transition, z, du, velocity, truth.yield_displacement)
        ub = new
        travel = abs(ub - reversal_at)
        speed = abs(velocity)
        mu = truth.mu0 * _velocity_factor(truth.velocity, speed)
        if truth.pressure:
            mu *= gamma(axial[i] / truth.area) / gamma(truth.weight / truth.area)
        if truth.breakaway is not None:
            mu *= 1.0 + truth.breakaway[0] * max(0.0, 1.0 - travel / truth.breakaway[1])
        if truth.direction and z:
            mu *= 1.0 + truth.direction * math.copysign(1.0, z)
        if plate is not None:
            now = start_time + float(time[i])
            mask = plate.heated(ub / 2.0)
            q = np.zeros(plate.points.size)
            q[mask] = mu_prev * (axial[i] / truth.area) * speed / 2.0
            plate.add(now, q)
            rise = plate.temperature_rise(now, mask)
            if truth.heating:
                mu *= beta(truth.initial_temperature + rise) / beta(truth.initial_temperature)
        mu_prev = mu
        nload = axial[i]
        if math.isinf(truth.radius):
            f = mu * nload * z
        elif truth.geometry == "spherical":
            restoring = nload * ub / math.sqrt(truth.radius**2 - ub**2)
            f = restoring + mu * nload * z
            for _ in range(30):
                f = restoring + mu * (nload + f * ub / truth.radius) * z
        else:
            f = nload * ub / truth.radius + mu * nload * z
        force[i] = f if contact else 0.0
        mu_out[i] = mu
        bearing[i] = ub
        previous_contact = contact
    return {"time": time, "bearing": bearing, "force": force, "axial_force": axial,
            "mu": mu_out}


def lagged(truth: Truth, time: np.ndarray, displacement_of, lag: float,
           axial_of=None) -> dict[str, np.ndarray]:
    """``simulate`` on a grid ten times finer, the force read ``lag`` seconds late.

    ``displacement_of(t)`` and ``axial_of(t)`` (optional) give the actuator's displacement
    [m] and the axial load [N] at any time.
    """
    dt = float(np.median(np.diff(time)))
    fine = np.arange(time[0], time[-1] + 0.5 * dt / 10.0, dt / 10.0)
    axial = None if axial_of is None else axial_of(fine)
    clean = simulate(truth, fine, displacement_of(fine), axial=axial)
    out = {k: np.interp(time, fine, v) for k, v in clean.items() if k != "time"}
    out["force"] = np.interp(time - lag, fine, clean["force"], left=0.0)
    out["time"] = time
    return out


def noise(rng: np.random.Generator, n: int, sigma: float, colour: float = 0.0) -> np.ndarray:
    """White (colour 0) or AR(1) noise of standard deviation ``sigma`` with lag-one
    correlation ``colour``."""
    white = rng.normal(0.0, sigma, n)
    if colour == 0.0:
        return white
    out = np.empty(n)
    out[0] = white[0]
    scale = math.sqrt(1.0 - colour**2)
    for i in range(1, n):
        out[i] = colour * out[i - 1] + scale * white[i]
    return out


def checks() -> None:
    """Print the self-checks of the module docstring against their closed forms."""
    t = np.arange(0.0, 4.0 + 1e-9, 0.001)
    u = 0.1 * np.sin(2.0 * math.pi * t / 2.0)
    flat = Truth(weight=1.0e6, radius=math.inf, mu0=0.05, transition="rigid-plastic")
    out = simulate(flat, t, u)
    cycle = t >= 2.0
    edc = float(np.trapezoid(out["force"][cycle], u[cycle]))
    print(f"rigid-plastic EDC {edc:.1f} J against 4 mu N A = {4 * 0.05 * 1e6 * 0.1:.1f} J")
    plate = Plate(0.0, 0.15)
    plate.add(0.0, None)
    for k in range(1, 101):
        plate.add(k * 0.1, np.full(plate.points.size, 1.0e5))
    rise = plate.temperature_rise(10.0, np.ones(plate.points.size, bool))
    exact = 2 * 1.0e5 * math.sqrt(DIFFUSIVITY * 10.0 / math.pi) / CONDUCTIVITY
    print(f"constant flux on a half-space: {rise:.6f} degC against {exact:.6f} degC")

