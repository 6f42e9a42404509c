"""The double concave friction pendulum bearing (DCFPB) element.

Horizontal force for a relative displacement u and velocity v of the two concave plates:

    F = N u / R_eff + mu(p, v, T) N z,

with N the axial load, R_eff the effective radius, p = N / (pi r^2) the contact pressure and z
in [-1, 1] the hysteretic variable of an elastic-plastic return map with a small yield
displacement u_y (rigid-plastic sliding as u_y -> 0).

:class:`DCFPBearing` holds the frozen parameters; :meth:`DCFPBearing.element` gives a
:class:`BearingElement` with the state contract of OpenSees elements: ``set_trial(u, v, time)``
returns the force and the consistent tangent (d F / d u and d F / d v, the latter from
d mu / d v), ``commit()`` accepts the trial (and only then adds its heat), ``revert()`` drops it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import CapacityExceeded, InputError
from dcfpb.common.validation import check_array, check_choice, check_real
from isolator.friction import ConstantFriction, PTVFriction


@dataclass(frozen=True)
class AxialLoadHistory:
    """An axial load that varies in time, linearly interpolated (held constant outside).

    Parameters
    ----------
    time : array_like
        Increasing times [s].
    load : array_like
        Compressive axial load at those times [N]; zero or negative means uplift.
    """

    time: np.ndarray
    load: np.ndarray

    def __post_init__(self) -> None:
        owner = type(self).__name__
        time = check_array(self.time, "time", owner, min_length=1)
        load = check_array(self.load, "load", owner, min_length=1)
        if time.shape != load.shape:
            raise ValueError(
                f"The 'load' parameter of {owner} must have the length of 'time' "
                f"({time.size}). Got {load.size} instead."
            )
        if np.any(np.diff(time) <= 0.0):
            raise ValueError(f"The 'time' parameter of {owner} must be strictly increasing.")
        object.__setattr__(self, "time", time)
        object.__setattr__(self, "load", load)

    def at(self, time: float) -> float:
        """Axial load at ``time`` [N]."""
        return float(np.interp(time, self.time, self.load))


class BearingTrial(NamedTuple):
    """Force and consistent tangent of a trial state.

    Attributes
    ----------
    force : float
        Horizontal force F [N].
    stiffness : float
        d F / d u [N/m].
    damping : float
        d F / d v [N s/m], from the velocity dependence of mu.
    """

    force: float
    stiffness: float
    damping: float


class BearingState(NamedTuple):
    """Everything worth recording about a (trial or committed) state of the element."""

    time: float
    displacement: float
    velocity: float
    force: float
    friction_force: float
    z: float
    mu: float
    temperature: float
    heat_flux: float
    axial_load: float


@dataclass(frozen=True)
class DCFPBearing:
    """Parameters of a double concave friction pendulum bearing.

    Parameters
    ----------
    effective_radius : float
        Effective radius R_eff [m]; ``inf`` for a flat slider (no restoring stiffness).
    slider_diameter : float
        Slider diameter [m]; the contact radius is half of it.
    axial_load : float or AxialLoadHistory or None
        Compressive axial load N [N], constant or varying in time. None (the default) for a
        bearing placed in a building, whose weight shared by its bearings is the load
        (:class:`structures.isolated_building.IsolatedShearBuilding`); a bearing test needs one.
    friction : ConstantFriction or PTVFriction
        Friction model of the sliding surfaces (required).
    yield_displacement : float
        Yield displacement u_y of the return map [m]; default 0.5 mm.
    displacement_capacity : float
        Largest relative displacement of the plates [m]; sizes the precise model's monitor
        line. Default 0.6 m.
    restoring : str
        Restoring force law: ``"linear"`` N u / R_eff (the paper's), or ``"spherical"``
        N u / sqrt(R_eff^2 - u^2) (OpenSees FPBearingPTV's).
    """

    effective_radius: float
    slider_diameter: float
    axial_load: float | AxialLoadHistory | None = None
    friction: ConstantFriction | PTVFriction | None = None
    yield_displacement: float = 5.0e-4
    displacement_capacity: float = 0.6
    restoring: str = "linear"

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_real(self.effective_radius, "effective_radius", owner, low=0.0, low_open=True,
                   allow_inf=True)
        check_real(self.slider_diameter, "slider_diameter", owner, low=0.0, low_open=True,
                   high=10.0)
        if self.axial_load is not None and not isinstance(self.axial_load, AxialLoadHistory):
            check_real(self.axial_load, "axial_load", owner, low=0.0, low_open=True)
        if not isinstance(self.friction, ConstantFriction | PTVFriction):
            raise TypeError(
                f"The 'friction' parameter of {owner} must be a ConstantFriction or a "
                f"PTVFriction. Got {self.friction!r} instead."
            )
        check_real(self.yield_displacement, "yield_displacement", owner, low=0.0,
                   low_open=True, high=0.1)
        check_real(self.displacement_capacity, "displacement_capacity", owner, low=0.0,
                   low_open=True, high=10.0)
        check_choice(self.restoring, "restoring", owner, ("linear", "spherical"))
        if self.restoring == "spherical" and not (
            self.displacement_capacity < self.effective_radius
        ):
            raise ValueError(
                f"The 'displacement_capacity' parameter of {owner} must be below the "
                f"effective radius {self.effective_radius:g} m for the spherical law. "
                f"Got {self.displacement_capacity!r} instead."
            )

    @property
    def contact_radius(self) -> float:
        """Contact radius r = slider radius [m]."""
        return 0.5 * self.slider_diameter

    @property
    def contact_area(self) -> float:
        """Contact area pi r^2 [m^2]."""
        return math.pi * self.contact_radius**2

    def axial_load_at(self, time: float) -> float:
        """Axial load N at ``time`` [N]."""
        if self.axial_load is None:
            raise InputError(
                f"This {type(self).__name__} has no axial load: give 'axial_load' [N] (a "
                "positive float or an AxialLoadHistory), or place it in a building, whose "
                "weight shared by its bearings is the load.")
        if isinstance(self.axial_load, AxialLoadHistory):
            return self.axial_load.at(time)
        return float(self.axial_load)

    def pressure_at(self, time: float) -> float:
        """Contact pressure p = N / (pi r^2) at ``time`` [Pa]."""
        return self.axial_load_at(time) / self.contact_area

    @property
    def pendulum_stiffness(self) -> float:
        """Post-yield stiffness N / R_eff at the initial axial load [N/m]."""
        return self.axial_load_at(0.0) / self.effective_radius

    def element(self) -> BearingElement:
        """A new element at rest (u = 0, z = 0, t = 0) with an unheated surface."""
        return BearingElement(self)


def beyond_capacity_message(displacement: float, time: float, capacity: float, *,
                            trial: bool = False, detail: str = "") -> str:
    """The message of a run ended by a bearing beyond its displacement capacity.

    One wording for every friction model and both engines, and for the check of the
    committed steps (:func:`structures.results.response_dataset`).

    Parameters
    ----------
    displacement : float
        The isolator displacement that exceeded the capacity [m].
    time : float
        When [s].
    capacity : float
        The bearing's ``displacement_capacity`` [m].
    trial : bool
        The displacement is a trial of a step that could not be evaluated (the step was not
        committed), not a committed one.
    detail : str
        What the model said, e.g. the precise model's monitor line.
    """
    where = " in a trial of the step" if trial else ""
    detail = f" ({detail[:1].lower()}{detail[1:].rstrip('.')})" if detail else ""
    return (f"Capacity exceeded: the isolator displacement reached {abs(displacement):.4g} m "
            f"at t = {time:.6g} s{where}, beyond the bearing's displacement_capacity "
            f"{capacity:g} m{detail}: the bearing would hit its restrainer, so the response "
            "from then on is not physical.")


def trial_failure(bearing: DCFPBearing, displacement: float, time: float,
                  detail: str) -> CapacityExceeded:
    """The error of a trial displacement [m] at ``time`` [s] the bearing's model cannot
    evaluate (the slider off the monitor line, beyond the spherical law's radius): a
    capacity failure when it is beyond the displacement capacity, else a ``"model"``
    failure (the model's range is shorter than the capacity). ``detail`` says what the
    model refused. Both engines raise or report it in these words."""
    capacity = bearing.displacement_capacity
    if abs(displacement) > capacity:
        return CapacityExceeded(beyond_capacity_message(displacement, time, capacity,
                                                        trial=True, detail=detail))
    return CapacityExceeded(
        f"At t = {time:.6g} s a trial isolator displacement of {abs(displacement):.4g} m, "
        f"within the displacement_capacity {capacity:g} m, is outside the bearing model's "
        f"range: {detail}", kind="model")


class BearingElement:
    """Stateful DCFPB element: set_trial / commit / revert.

    A trial is a pure function of the committed state and the trial arguments, so Newton
    iterations may call :meth:`set_trial` as often as they like.
    """

    def __init__(self, bearing: DCFPBearing) -> None:
        self.bearing = bearing
        self._friction = bearing.friction.bind(bearing.contact_radius,
                                               bearing.displacement_capacity)
        self._radius = bearing.effective_radius
        self._spherical = bearing.restoring == "spherical"
        self._yield = bearing.yield_displacement
        t0 = bearing.friction.thermal.initial_temperature if isinstance(
            bearing.friction, PTVFriction) else bearing.friction.initial_temperature
        n0 = bearing.axial_load_at(0.0)
        # at rest: mu at zero speed and the initial temperature (a trial of zero length adds
        # no heat and leaves nothing to commit)
        mu0 = self._friction.trial(0.0, 0.0, n0 / bearing.contact_area, 0.0).mu if n0 > 0 else 0.0
        self._friction.revert()
        self._committed = BearingState(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, mu0, t0, 0.0, n0)
        self._trial = self._committed

    @property
    def committed(self) -> BearingState:
        """The last committed state."""
        return self._committed

    @property
    def trial_state(self) -> BearingState:
        """The state of the last trial (equals the committed state after commit/revert)."""
        return self._trial

    @property
    def friction_state(self):
        """The bound friction evaluator (gives access to the heating model)."""
        return self._friction

    def _restoring(self, u: float, n: float, time: float) -> tuple[float, float]:
        if math.isinf(self._radius):
            return 0.0, 0.0
        if self._spherical:
            squared = self._radius**2 - u * u
            if not squared > 0.0:
                raise trial_failure(self.bearing, u, time, f"at the effective radius "
                                    f"{self._radius!r} m of the spherical law")
            root = math.sqrt(squared)
            return n * u / root, n * self._radius**2 / root**3
        return n * u / self._radius, n / self._radius

    def set_trial(self, displacement: float, velocity: float, time: float) -> BearingTrial:
        """Force and tangent at a trial displacement [m], velocity [m/s] and time [s].

        Raises
        ------
        ValueError
            If ``time`` is before the last committed time.
        dcfpb.common.errors.CapacityExceeded
            If the model cannot evaluate the displacement (the slider off the precise
            model's monitor line, at the spherical law's radius); an integration ends there
            with ``success=False`` (:func:`trial_failure`).
        """
        c = self._committed
        dt = time - c.time
        if dt < 0.0:
            raise ValueError(
                f"The trial time {time!r} s of BearingElement.set_trial is before the last "
                f"committed time {c.time!r} s."
            )
        n = self.bearing.axial_load_at(time)
        z = c.z + (displacement - c.displacement) / self._yield
        dz_du = 1.0 / self._yield
        if abs(z) >= 1.0:
            z, dz_du = math.copysign(1.0, z), 0.0
        try:
            if n <= 0.0:  # uplift: no contact, no force, no heat; the plates cool
                friction = self._friction.lifted(displacement, dt)
            else:
                friction = self._friction.trial(displacement, velocity,
                                                n / self.bearing.contact_area, dt)
        except CapacityExceeded as error:
            raise trial_failure(self.bearing, displacement, time, str(error)) from None
        if n <= 0.0:
            restoring = stiffness = n = 0.0
        else:
            restoring, stiffness = self._restoring(displacement, n, time)
        friction_force = friction.mu * n * z
        force = restoring + friction_force
        self._trial = BearingState(time, displacement, velocity, force, friction_force, z,
                                   friction.mu, friction.temperature, friction.heat_flux, n)
        return BearingTrial(force, stiffness + friction.mu * n * dz_du,
                            n * z * friction.dmu_dvelocity)

    def commit(self) -> None:
        """Accept the last trial: its state becomes the committed state, its heat is added."""
        self._friction.commit()
        self._committed = self._trial

    def revert(self) -> None:
        """Drop the last trial and return to the committed state exactly."""
        self._friction.revert()
        self._trial = self._committed
