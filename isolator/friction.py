"""Friction models of the sliding surfaces behind one small protocol.

``ConstantFriction``
    The paper's constant model (Eq. 8): mu_c = mu_0 gamma(sigma_d) alpha(v_d) beta(T_0).
``PTVFriction``
    The precise and simplified models (Eq. 7): mu_t = mu_t0 gamma(p) alpha(v) beta(T), with the
    contact temperature T from a heating model (:class:`~isolator.heating.MonitorLine` for the
    precise model, :class:`~isolator.heating.CentrePoint` for the simplified one) and a factor
    set (the paper's Eq. 1-3 or Kumar's).

A model is a frozen parameter object; :meth:`bind` gives the stateful evaluator for one
bearing geometry (contact radius, travel). An evaluator follows the element contract:
``trial(position, velocity, pressure, dt) -> Friction`` is a pure function of the committed
history and the trial, ``commit()`` accepts the last trial (and only then adds its heat), and
``revert()`` forgets it. ``lifted(position, dt) -> Friction`` is the trial of a slider out of
contact (uplift): no friction and no heat, but the step still counts, so a heated plate cools
over it as it does under a slider at rest.

The newest interval's flux enters the current temperature, q_n = mu_n p |v| / surfaces, so
mu_n solves the scalar equation mu = mu_t0 gamma alpha beta(T_base + b q(mu)) by Newton's
method. The velocity derivative includes that coupling.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple, Protocol

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.validation import check_choice, check_int, check_real
from isolator.compiled.kernels import cold_friction, ptv_trial, solve_friction
from isolator.compiled.layout import pack_ptv
from isolator.factors import KumarFactors, PaperFactors, factor_set
from isolator.heating import (
    CentrePoint,
    HeatingLayout,
    MonitorLine,
    SumOfExponentials,
    SurfaceHeating,
    ThermalProperties,
    sum_of_exponentials,
)

DEPENDENCIES = ("pressure", "velocity", "temperature")
REFERENCE_PRESSURE = 60.0e6  # [Pa] 60 N/mm^2, the paper's reference condition
REFERENCE_VELOCITY = 0.4  # [m/s] 400 mm/s


class Friction(NamedTuple):
    """Friction coefficient of a trial state and what the element needs besides.

    Attributes
    ----------
    mu : float
        Friction coefficient [-].
    dmu_dvelocity : float
        Derivative of mu with respect to the signed relative velocity [s/m].
    temperature : float
        Contact temperature [degC] (the initial temperature for models without heating).
    heat_flux : float
        Heat flux into each sliding surface over the trial step [W/m^2].
    """

    mu: float
    dmu_dvelocity: float
    temperature: float
    heat_flux: float


class FrictionState(Protocol):
    """A bound friction model with trial / commit / revert."""

    def trial(self, position: float, velocity: float, pressure: float, dt: float) -> Friction:
        """Friction at a trial displacement [m], velocity [m/s], pressure [Pa], step [s]."""
        ...

    def lifted(self, position: float, dt: float) -> Friction:
        """The trial of a slider out of contact at ``position`` [m] for ``dt`` [s]: mu = 0,
        no heat flux, the contact temperature after the plates cooled over ``dt``."""
        ...

    def commit(self) -> None:
        """Accept the last trial."""
        ...

    def revert(self) -> None:
        """Forget trials back to the last commit."""
        ...


@dataclass(frozen=True)
class ConstantFriction:
    """The constant model, Eq. 8: mu_c = mu_0 gamma(sigma_d) alpha(v_d) beta(T_0).

    Parameters
    ----------
    mu0 : float
        Reference friction coefficient mu_0 [-] at 60 N/mm^2 and 400 mm/s: 0.041 for a
        300 mm slider, 0.038 for a 400 mm slider (see :meth:`for_slider`).
    design_pressure : float
        Design pressure sigma_d [Pa]; default 60 MPa.
    design_velocity : float
        Design maximum velocity v_d [m/s]; default 0.4.
    initial_temperature : float
        Initial temperature T_0 [degC]; default 20.
    factors : str
        Factor set used for Eq. 8, ``"paper"`` by default.
    """

    mu0: float = 0.041
    design_pressure: float = REFERENCE_PRESSURE
    design_velocity: float = REFERENCE_VELOCITY
    initial_temperature: float = 20.0
    factors: str = "paper"

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_real(self.mu0, "mu0", owner, low=0.0, high=1.0, low_open=True)
        check_real(self.design_pressure, "design_pressure", owner, low=0.0, low_open=True)
        check_real(self.design_velocity, "design_velocity", owner, low=0.0)
        check_real(self.initial_temperature, "initial_temperature", owner, low=-273.15,
                   high=1000.0)
        check_choice(self.factors, "factors", owner, ("paper", "kumar"))

    @classmethod
    def for_slider(cls, slider_diameter: float, **kwargs: float) -> ConstantFriction:
        """The paper's mu_0 for a 300 mm (0.041) or 400 mm (0.038) slider.

        Other diameters take the nearer of the two; pass ``mu0`` to override.
        """
        check_real(slider_diameter, "slider_diameter", cls.__name__, low=0.0, low_open=True)
        mu0 = 0.041 if slider_diameter < 0.35 else 0.038
        return cls(**{"mu0": mu0, **kwargs})

    @property
    def mu(self) -> float:
        """The constant friction coefficient mu_c of Eq. 8 [-]."""
        fs = factor_set(self.factors)
        gamma, _ = fs.pressure(self.design_pressure)
        alpha, _ = fs.velocity(self.design_velocity)
        beta, _ = fs.temperature(self.initial_temperature)
        return float(self.mu0 * gamma * alpha * beta)  # Eq. 8

    def bind(self, contact_radius: float, travel: float) -> ConstantFrictionState:
        """A stateless evaluator (the geometry does not matter for a constant mu)."""
        return ConstantFrictionState(self.mu, self.initial_temperature)


class ConstantFrictionState:
    """Evaluator of a constant friction coefficient (no state to commit)."""

    def __init__(self, mu: float, temperature: float) -> None:
        self._friction = Friction(mu, 0.0, temperature, 0.0)

    def trial(self, position: float, velocity: float, pressure: float, dt: float) -> Friction:
        """The constant mu; heat flux is not tracked."""
        return self._friction

    def lifted(self, position: float, dt: float) -> Friction:
        """Out of contact: mu = 0 at the model's temperature."""
        return Friction(0.0, 0.0, self._friction.temperature, 0.0)

    def commit(self) -> None:
        """Nothing to commit."""

    def revert(self) -> None:
        """Nothing to revert."""


def eq7(
    pressure: ArrayLike,
    speed: ArrayLike,
    temperature: ArrayLike,
    *,
    mu_t0: float,
    factors: PaperFactors | KumarFactors,
    dependencies: tuple[str, ...] = DEPENDENCIES,
) -> np.ndarray:
    """Eq. 7 as written in the paper, in plain numpy: mu_t = mu_t0 gamma(p) alpha(v) beta(T).

    The readable reference of the compiled kernels (:func:`isolator.compiled.kernels.ptv_friction`
    solves the same law with the contact temperature depending on mu through the newest flux;
    ``tests/verification/test_friction_reference.py`` holds them to this function).

    Parameters
    ----------
    pressure : array_like
        Contact pressure p [Pa].
    speed : array_like
        Sliding speed |v| [m/s].
    temperature : array_like
        Contact temperature T [degC].
    mu_t0 : float
        Friction coefficient at the reference condition [-].
    factors : PaperFactors or KumarFactors
        The dependency factors gamma, alpha and beta (Eq. 1-3).
    dependencies : tuple of str
        The active dependencies; a factor left out is 1.

    Returns
    -------
    numpy.ndarray
        mu_t [-], broadcast over the inputs.
    """
    pressure, speed, temperature = np.broadcast_arrays(
        np.asarray(pressure, dtype=float), np.abs(np.asarray(speed, dtype=float)),
        np.asarray(temperature, dtype=float))
    mu = np.full(pressure.shape, float(mu_t0))
    if "pressure" in dependencies:
        mu = mu * np.asarray(factors.pressure(pressure)[0])
    if "velocity" in dependencies:
        mu = mu * np.asarray(factors.velocity(speed)[0])
    if "temperature" in dependencies:
        mu = mu * np.asarray(factors.temperature(temperature)[0])
    return mu


@dataclass(frozen=True)
class PTVFriction:
    """Pressure, velocity and temperature dependent friction, Eq. 7.

    Parameters
    ----------
    mu_t0 : float
        Friction coefficient at 60 N/mm^2, 400 mm/s and 20 degC [-]; default 0.075.
    heating : MonitorLine, CentrePoint or None
        Monitor points for the contact temperature: ``MonitorLine()`` is the precise model,
        ``CentrePoint(refinement=0.5)`` the simplified one. None disables heating.
    factors : PaperFactors or KumarFactors or str
        Dependency factor set; ``"paper"`` (Eq. 1-3) by default.
    dependencies : tuple of str
        Which of ``"pressure"``, ``"velocity"``, ``"temperature"`` act; all by default.
    thermal : ThermalProperties
        Conductivity, diffusivity and initial temperature of the plates.
    surfaces : int
        Sliding surfaces sharing the relative displacement: 2 for a DCFPB (the slider travels
        u/2 over each plate and each takes q = mu p v / 2), 1 for a single concave bearing.
    kernel_min_lag, kernel_max_lag : float
        Range of time lags over which the heating kernel holds [s]: steps down to 1e-6 s and
        histories up to 1e4 s (2.8 h) by default.
    kernel_tolerance : float
        Largest relative error of the heating kernel on that range [-]; default 1e-7.
    """

    mu_t0: float = 0.075
    heating: HeatingLayout | None = field(default_factory=MonitorLine)
    factors: PaperFactors | KumarFactors | str = "paper"
    dependencies: tuple[str, ...] = DEPENDENCIES
    thermal: ThermalProperties = field(default_factory=ThermalProperties)
    surfaces: int = 2
    kernel_min_lag: float = 1.0e-6
    kernel_max_lag: float = 1.0e4
    kernel_tolerance: float = 1.0e-7

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_real(self.mu_t0, "mu_t0", owner, low=0.0, high=1.0, low_open=True)
        if isinstance(self.factors, str):
            object.__setattr__(self, "factors", factor_set(self.factors))
        if not isinstance(self.factors, PaperFactors | KumarFactors):
            raise TypeError(
                f"The 'factors' parameter of {owner} must be 'paper', 'kumar' or a factor set. "
                f"Got {self.factors!r} instead."
            )
        if not isinstance(self.heating, MonitorLine | CentrePoint | None):
            raise TypeError(
                f"The 'heating' parameter of {owner} must be a MonitorLine, a CentrePoint or "
                f"None. Got {self.heating!r} instead."
            )
        object.__setattr__(self, "dependencies", tuple(self.dependencies))
        for name in self.dependencies:
            check_choice(name, "dependencies", owner, DEPENDENCIES)
        check_int(self.surfaces, "surfaces", owner, low=1, high=2)
        check_real(self.kernel_min_lag, "kernel_min_lag", owner, low=1e-9, high=1e-2)
        check_real(self.kernel_max_lag, "kernel_max_lag", owner, low=1.0, high=1e9)
        check_real(self.kernel_tolerance, "kernel_tolerance", owner, low=1e-12, high=1e-3)

    @property
    def heats(self) -> bool:
        """Whether the contact temperature is tracked."""
        return self.heating is not None

    def bind(self, contact_radius: float, travel: float) -> PTVFrictionState:
        """The stateful evaluator for a slider of ``contact_radius`` [m].

        ``travel`` [m] is the largest relative displacement of the plates the monitor line
        must cover.
        """
        return PTVFrictionState(self, contact_radius, travel)


class PTVFrictionState:
    """Evaluator of :class:`PTVFriction` for one bearing; see the module docstring."""

    def __init__(self, model: PTVFriction, contact_radius: float, travel: float) -> None:
        self.model = model
        self._kernel_parameters = model.factors.kernel_parameters
        self._use_pressure = "pressure" in model.dependencies
        self._use_velocity = "velocity" in model.dependencies
        self._use_temperature = "temperature" in model.dependencies
        self._initial_temperature = model.thermal.initial_temperature
        self._surfaces = float(model.surfaces)
        self._heating: SurfaceHeating | None = None
        if model.heating is not None:
            kernel: SumOfExponentials = sum_of_exponentials(
                model.kernel_min_lag, model.kernel_max_lag, model.kernel_tolerance)
            self._heating = SurfaceHeating(
                model.heating, contact_radius, travel / model.surfaces, model.thermal, kernel
            )
        self._pending: tuple[float, tuple[int, int], float] | None = None
        if self._heating is not None:  # constant arguments of the fused kernel, packed once
            h = self._heating
            code, reference_pressure, rate = self._kernel_parameters
            self._parameters = pack_ptv({
                "first_point": h.first_point, "spacing": h.spacing, "n_points": h.n_points,
                "flux_half_width": h.flux_half_width,
                "average_over_contact": h.average_over_contact,
                "initial_temperature": self._initial_temperature,
                "flux_coefficient": h.coefficient, "factor_code": code,
                "reference_pressure": reference_pressure, "rate_parameter": rate,
                "mu_t0": model.mu_t0, "use_pressure": self._use_pressure,
                "use_velocity": self._use_velocity, "use_temperature": self._use_temperature,
                "surfaces": self._surfaces})

    @property
    def heating(self) -> SurfaceHeating | None:
        """The surface heating model (None without heating)."""
        return self._heating

    def trial(self, position: float, velocity: float, pressure: float, dt: float) -> Friction:
        """Friction at a trial relative displacement, velocity, contact pressure and step.

        Parameters
        ----------
        position : float
            Relative displacement of the two plates u [m] (the slider is at u / surfaces on
            each plate).
        velocity : float
            Relative velocity of the plates v [m/s].
        pressure : float
            Contact pressure p = N / (pi r^2) [Pa].
        dt : float
            Time since the last commit [s].
        """
        speed = abs(velocity)
        code, reference_pressure, rate = self._kernel_parameters
        heating = self._heating
        if heating is None or dt <= 0.0:
            mu_cold, dmu_cold = cold_friction(code, reference_pressure, rate, self.model.mu_t0,
                                              self._use_pressure, self._use_velocity, pressure,
                                              speed)
            mu, dmu_dspeed, temperature = solve_friction(
                code, mu_cold, dmu_cold, self._use_temperature, self._initial_temperature, 0.0,
                0.0)
            flux = mu * pressure * speed / self._surfaces
            self._pending = None
        else:
            if dt != heating.prepared_step:
                heating.prepare(dt)
            mu, dmu_dspeed, temperature, flux, lo, hi, inside = ptv_trial(
                heating.states, heating.weighted_decay, self._parameters,
                position / self._surfaces, heating.newest_coefficient, pressure, speed,
            )
            if not inside:
                heating.window(position / self._surfaces)  # raises with the full message
            self._pending = (dt, (lo, hi), flux)
        # d mu / d v = d mu / d|v| sign(v); d mu / d|v| is negative on a hot plate at speed
        return Friction(mu, math.copysign(1.0, velocity) * dmu_dspeed if velocity else 0.0,
                        temperature, flux)

    def lifted(self, position: float, dt: float) -> Friction:
        """Out of contact at ``position`` [m] for ``dt`` [s]: mu = 0 and no heat flux; the
        step is staged with zero flux, so the commit advances the heat history by ``dt`` and
        the plates cool as under a slider at rest (the contact temperature returned is theirs
        at the window under ``position``). Evaluated as the trial at zero speed, where the flux
        mu p |v| is zero whatever mu and the temperature does not depend on the pressure,
        which is therefore taken as the reference one."""
        friction = self.trial(position, 0.0, REFERENCE_PRESSURE, dt)
        if self._pending is not None:
            self._pending = (*self._pending[:2], 0.0)
        return Friction(0.0, 0.0, friction.temperature, 0.0)

    def commit(self) -> None:
        """Add the last trial's heat to the history."""
        if self._heating is not None and self._pending is not None:
            dt, heated, flux = self._pending
            self._heating.commit(dt, heated, flux)
        self._pending = None

    def revert(self) -> None:
        """Forget the last trial; the heat history is untouched."""
        self._pending = None
