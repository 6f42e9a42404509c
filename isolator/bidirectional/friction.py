"""The friction models of :mod:`isolator.friction` for a slider moving in 2D.

A bidirectional evaluator follows the element contract of the planar ones with vector
arguments: ``trial(position, velocity, pressure, dt) -> PlateFriction`` is a pure function of
the committed history and the trial, ``commit()`` adds the trial's heat and ``revert()`` drops
it. Eq. 7 and 8 take the speed |v| of the vector velocity; the heat flux q = mu p |v| / surfaces
enters the monitor points under the slider, which sits at u / surfaces on each plate.

- The constant model (Eq. 8) does not see the position: the planar evaluator is used as is,
  with the speed (:class:`RadialFrictionState`).
- The simplified model (Eq. 6) has one point at the plate centre, covered while the slider
  centre is within lambda r of it: only the distance |u| / surfaces matters, so the planar
  centre point and kernel (:func:`~isolator.compiled.kernels.ptv_trial`) are driven with that
  distance (exact in any direction).
- The precise model (Eq. 5, 7) reads the contact temperature from a grid over the plate
  (:class:`~isolator.bidirectional.heating.GridHeating`) and solves Eq. 7 with the planar kernel
  :func:`~isolator.compiled.kernels.ptv_friction`, the newest interval's flux included.

Both heated models are :class:`PTVPlateState`, which calls the kernels itself rather than the
planar evaluator: :meth:`isolator.friction.PTVFrictionState.trial` returns d mu / dv as
``copysign(dmu_dspeed, v)``, which drops the sign of a negative d mu / d|v| (hot plates at
speed, where the newest flux lowers mu more than alpha raises it), and the 2D tangent needs the
signed value (``test_tangents_against_finite_differences`` holds it to central differences).

The derivative of mu with respect to the velocity vector is dmu/d|v| v / |v|.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from isolator.bidirectional.heating import GridHeating, MonitorGrid
from isolator.compiled.kernels import cold_friction, ptv_friction, ptv_trial, solve_friction
from isolator.compiled.layout import pack_ptv
from isolator.friction import REFERENCE_PRESSURE, ConstantFriction, PTVFriction
from isolator.heating import MonitorLine, SurfaceHeating, sum_of_exponentials


class PlateFriction(NamedTuple):
    """Friction coefficient of a 2D trial state and what the element needs besides.

    Attributes
    ----------
    mu : float
        Friction coefficient [-].
    dmu_dvelocity : ndarray, shape (2,)
        Gradient of mu with respect to the relative velocity vector [s/m].
    temperature : float
        Contact temperature [degC].
    heat_flux : float
        Heat flux into each sliding surface over the trial step [W/m^2].
    """

    mu: float
    dmu_dvelocity: np.ndarray
    temperature: float
    heat_flux: float


def _direction(velocity: np.ndarray, speed: float) -> np.ndarray:
    return velocity / speed if speed > 0.0 else np.zeros(2)


class RadialFrictionState:
    """The planar evaluator of the constant model (Eq. 8) driven by |u| and the speed |v|."""

    def __init__(self, model: ConstantFriction, contact_radius: float, travel: float) -> None:
        self.planar = model.bind(contact_radius, travel)

    def trial(self, position: np.ndarray, velocity: np.ndarray, pressure: float,
              dt: float) -> PlateFriction:
        """Friction at a trial displacement [m] and velocity [m/s] (vectors), pressure [Pa]
        and step [s]."""
        speed = math.hypot(velocity[0], velocity[1])
        friction = self.planar.trial(math.hypot(position[0], position[1]), speed, pressure, dt)
        return PlateFriction(friction.mu, friction.dmu_dvelocity * _direction(velocity, speed),
                             friction.temperature, friction.heat_flux)

    def lifted(self, position: np.ndarray, dt: float) -> PlateFriction:
        """Out of contact: mu = 0 at the model's temperature."""
        friction = self.planar.lifted(math.hypot(position[0], position[1]), dt)
        return PlateFriction(0.0, np.zeros(2), friction.temperature, 0.0)

    def commit(self) -> None:
        """Accept the last trial."""
        self.planar.commit()

    def revert(self) -> None:
        """Forget the last trial."""
        self.planar.revert()


class PTVPlateState:
    """The precise and simplified models (Eq. 4-7) for a slider moving in 2D.

    The precise model reads the contact temperature from a monitor grid on each plate
    (:class:`~isolator.bidirectional.heating.GridHeating`); the simplified one from the planar
    centre
    point (:class:`~isolator.heating.SurfaceHeating`) at the distance |u| / surfaces; a model
    without heating stays at its initial temperature. Eq. 7 is solved by the planar kernels with
    the newest interval's flux included, so d mu / d|v| keeps its sign (it is negative where
    the newest flux cools the friction faster than the speed raises it).

    Parameters
    ----------
    model : PTVFriction
        The friction model.
    contact_radius : float
        Contact radius r [m].
    travel : float
        Largest relative displacement of the plates [m].
    orientation : float or None
        Fixed angle of the grid's first axis from x [deg]; None follows the motion
        (:class:`~isolator.bidirectional.heating.MonitorGrid`).
    """

    def __init__(self, model: PTVFriction, contact_radius: float, travel: float,
                 orientation: float | None = None) -> None:
        self.model = model
        self._surfaces = float(model.surfaces)
        code, reference_pressure, rate = model.factors.kernel_parameters
        self._cold = (code, reference_pressure, rate, model.mu_t0,
                      "pressure" in model.dependencies, "velocity" in model.dependencies)
        self._use_temperature = "temperature" in model.dependencies
        self.heating: GridHeating | SurfaceHeating | None = None
        constants = {}
        if model.heating is not None:
            kernel = sum_of_exponentials(model.kernel_min_lag, model.kernel_max_lag,
                                         model.kernel_tolerance)
            plate_travel = travel / model.surfaces
            if isinstance(model.heating, MonitorLine):
                self.heating = GridHeating(MonitorGrid.from_line(model.heating, orientation),
                                           contact_radius, plate_travel, model.thermal, kernel)
            else:
                self.heating = SurfaceHeating(model.heating, contact_radius, plate_travel,
                                              model.thermal, kernel)
            h = self.heating
            constants = {"first_point": h.first_point, "spacing": h.spacing,
                         "n_points": h.n_points, "flux_half_width": h.flux_half_width,
                         "average_over_contact": isinstance(h, GridHeating),
                         "flux_coefficient": h.coefficient}
        self._parameters = pack_ptv({
            **constants, "initial_temperature": model.thermal.initial_temperature,
            "factor_code": code, "reference_pressure": reference_pressure,
            "rate_parameter": rate, "mu_t0": model.mu_t0, "use_pressure": self._cold[4],
            "use_velocity": self._cold[5], "use_temperature": self._use_temperature,
            "surfaces": self._surfaces})
        self._pending: tuple | None = None

    def trial(self, position: np.ndarray, velocity: np.ndarray, pressure: float,
              dt: float) -> PlateFriction:
        """Friction at a trial relative displacement [m] and velocity [m/s] (vectors), contact
        pressure [Pa] and step since the last commit [s]."""
        speed = math.hypot(velocity[0], velocity[1])
        heating = self.heating
        self._pending = None
        if heating is None or dt <= 0.0:  # no heating or no time: as the planar evaluator
            mu_cold, dmu_cold = cold_friction(*self._cold, pressure, speed)
            mu, dmu_dspeed, temperature = solve_friction(
                self._cold[0], mu_cold, dmu_cold, self._use_temperature,
                self.model.thermal.initial_temperature, 0.0, 0.0)
            flux = mu * pressure * speed / self._surfaces
        elif isinstance(heating, GridHeating):
            on_plate = np.asarray(position, dtype=float) / self._surfaces
            grid = heating.trial(on_plate, dt, hint=np.asarray(velocity, dtype=float))
            _, _, newest = heating.factors(dt)
            mu, dmu_dspeed, temperature, flux = ptv_friction(
                grid.rise, grid.points > 0, self._parameters, newest, pressure, speed)
            self._pending = (dt, grid, flux)
        else:
            if dt != heating.prepared_step:
                heating.prepare(dt)
            distance = math.hypot(position[0], position[1]) / self._surfaces
            mu, dmu_dspeed, temperature, flux, lo, hi, _ = ptv_trial(
                heating.states, heating.weighted_decay, self._parameters, distance,
                heating.newest_coefficient, pressure, speed)
            self._pending = (dt, (lo, hi), flux)
        return PlateFriction(mu, dmu_dspeed * _direction(velocity, speed), temperature, flux)

    def lifted(self, position: np.ndarray, dt: float) -> PlateFriction:
        """Out of contact at ``position`` [m] for ``dt`` [s]: mu = 0 and no heat flux; the
        step is staged with zero flux, so the commit advances the plates' heat clock by ``dt``
        and they cool as under a slider at rest (the temperature returned is the contact
        temperature under ``position``). As the planar evaluator's ``lifted``: the trial at
        zero speed and the reference pressure, where no heat enters whatever mu."""
        friction = self.trial(position, np.zeros(2), REFERENCE_PRESSURE, dt)
        if self._pending is not None:
            self._pending = (*self._pending[:2], 0.0)
        return PlateFriction(0.0, np.zeros(2), friction.temperature, 0.0)

    def commit(self) -> None:
        """Add the last trial's heat to the plates' history."""
        if self.heating is not None and self._pending is not None:
            self.heating.commit(*self._pending)
        self._pending = None

    def revert(self) -> None:
        """Forget the last trial; the history is untouched."""
        self._pending = None


PlateFrictionState = RadialFrictionState | PTVPlateState


def bind_plate_friction(model: ConstantFriction | PTVFriction, contact_radius: float,
                        travel: float, orientation: float | None = None) -> PlateFrictionState:
    """The 2D evaluator of a friction model for a slider of ``contact_radius`` [m].

    Parameters
    ----------
    model : ConstantFriction or PTVFriction
        The friction model (the same objects as the planar element's).
    contact_radius : float
        Contact radius r [m].
    travel : float
        Largest relative displacement of the plates the grid must cover [m].
    orientation : float or None
        The precise model's grid orientation [deg] (see :class:`MonitorGrid`); ignored by the
        other models, which see no direction.
    """
    if isinstance(model, PTVFriction):
        return PTVPlateState(model, contact_radius, travel, orientation)
    return RadialFrictionState(model, contact_radius, travel)
