"""Friction models of the sliding surfaces: the strategy a bearing element asks for mu [-].

:class:`ConstantFriction` is the paper's constant model (Eq. 8), :class:`PTVFriction` its
precise and simplified models (Eq. 7, the contact temperature from monitor points, Eq. 4-6).
A model is frozen parameters; ``bind`` gives the evaluator (:class:`FrictionState`) of one
bearing in one or two directions: ``trial`` is a pure function of the committed history and the
trial, ``commit`` accepts it (and only then adds its heat), ``revert`` forgets it, ``lifted`` is
the trial of a slider out of contact.

Eq. 7 and 8 take the speed |v| [m/s]. The newest interval's flux q_n = mu_n p |v| / surfaces
enters the current temperature, so mu_n solves mu = mu_t0 gamma alpha beta(T_base + b q(mu)) by
Newton's method, and d mu / d|v| includes that coupling.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import NamedTuple, Protocol

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.validation import check_choice, check_instance, check_int, check_real
from isolator.compiled.kernels import initial_friction
from isolator.compiled.layout import pack_ptv
from isolator.factors import KumarFactors, PaperFactors, factor_set
from isolator.heating import (
    CentrePoint,
    HeatingLayout,
    MonitorLine,
    SurfaceHeating,
    ThermalProperties,
    sum_of_exponentials,
)
from isolator.monitor_grid import GridHeating, MonitorGrid

Pair = tuple[float, float]
"""An (x, y) vector [m] or [m/s]."""

DEPENDENCIES = ("pressure", "velocity", "temperature")
REFERENCE_PRESSURE = 60.0e6  # [Pa] 60 N/mm^2, the paper's reference condition
REFERENCE_VELOCITY = 0.4  # [m/s] 400 mm/s


class Friction(NamedTuple):
    """A trial's friction: the coefficient ``mu`` [-], its derivative ``dmu_dspeed`` with respect
    to the sliding speed |v| [s/m], the contact ``temperature`` [degC] (the initial one for a
    model without heating) and the ``heat_flux`` into each sliding surface over the trial step
    [W/m^2]."""

    mu: float
    dmu_dspeed: float
    temperature: float
    heat_flux: float


class FrictionState(Protocol):
    """A bound friction model with trial / commit / revert."""

    def trial(self, position: Pair, velocity: Pair, pressure: float, dt: float) -> Friction:
        """Friction at a trial relative displacement [m] and velocity [m/s] of the plates ((x, y)
        pairs; along x in one direction), contact pressure [Pa] and step since the last commit
        [s]."""
        ...

    def lifted(self, position: Pair, dt: float) -> Friction:
        """The trial of a slider out of contact at ``position`` [m] for ``dt`` [s]: mu = 0, no
        heat flux, the contact temperature of the plates cooled over ``dt``."""
        ...

    def commit(self) -> None:
        """Accept the last trial."""
        ...

    def revert(self) -> None:
        """Forget trials back to the last commit."""
        ...

    def temperature_field(self) -> tuple[np.ndarray, np.ndarray] | None:
        """Positions (m, 2) [m] on a plate and temperatures (m,) [degC] of the monitor points
        after the last commit; None for a model without a field of them."""
        ...


class FrictionModel(Protocol):
    """The friction strategy a :class:`~isolator.bearing.DCFPBearing` takes: frozen
    parameters that bind to an evaluator."""

    @property
    def name(self) -> str:
        """What the model is called in results and tables."""
        ...

    @property
    def initial_temperature(self) -> float:
        """Temperature of the plates before any sliding [degC]."""
        ...

    def bind(self, contact_radius: float, travel: float, dimension: int = 1,
             orientation: float | None = None) -> FrictionState:
        """The evaluator for a slider of ``contact_radius`` [m] whose plates move up to
        ``travel`` [m] apart, in ``dimension`` 1 or 2 directions."""
        ...

    def scaled(self, factor: float) -> FrictionModel:
        """The model with its friction coefficient times ``factor`` [-] (a property
        modification factor, ASCE 7-16 Sec. 17.2.8.4)."""
        ...

    def nominal_mu(self, pressure: float, velocity: float) -> float:
        """The nominal (cold) friction coefficient [-] at a contact ``pressure`` [Pa] and a
        sliding ``velocity`` [m/s], at the initial temperature (no heating). Optional: a model
        without it has no nominal coefficient for the design layer."""
        ...


def speed_of(velocity: Pair) -> float:
    """|v| of an (x, y) velocity [m/s] (exactly |v_x| when v_y = 0)."""
    vx, vy = velocity
    return abs(vx) if vy == 0.0 else math.hypot(vx, vy)


@dataclass(frozen=True)
class ConstantFriction:
    """The constant model, Eq. 8: mu_c = mu_0 gamma(sigma_d) alpha(v_d) beta(T_0).

    Parameters
    ----------
    mu0 : float
        Friction coefficient mu_0 at 60 N/mm^2 and 400 mm/s [-]: 0.041 for a 300 mm slider, 0.038
        for a 400 mm one (:meth:`for_slider`).
    design_pressure, design_velocity : float
        Design pressure sigma_d [Pa] and design maximum velocity v_d [m/s].
    initial_temperature : float
        T_0 [degC].
    factors : {"paper", "kumar"}
        The factor set of Eq. 8.
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
        """The paper's mu_0 for a 300 mm (0.041) or 400 mm (0.038) slider, the nearer of the two
        for another diameter [m]; ``mu0`` in ``kwargs`` overrides it."""
        check_real(slider_diameter, "slider_diameter", cls.__name__, low=0.0, low_open=True)
        mu0 = 0.041 if slider_diameter < 0.35 else 0.038
        return cls(**{"mu0": mu0, **kwargs})

    @property
    def name(self) -> str:
        """The model's name: ``"constant"``."""
        return "constant"

    @property
    def mu(self) -> float:
        """The constant friction coefficient mu_c of Eq. 8 [-]."""
        fs = factor_set(self.factors)
        gamma, _ = fs.pressure(self.design_pressure)
        alpha, _ = fs.velocity(self.design_velocity)
        beta, _ = fs.temperature(self.initial_temperature)
        return float(self.mu0 * gamma * alpha * beta)  # Eq. 8

    def bind(self, contact_radius: float, travel: float, dimension: int = 1,
             orientation: float | None = None) -> ConstantFrictionState:
        """A stateless evaluator (neither the geometry nor the dimension matter)."""
        return ConstantFrictionState(self.mu, self.initial_temperature)

    def scaled(self, factor: float) -> ConstantFriction:
        """The model with mu_0, and so mu_c, times ``factor`` [-]."""
        check_real(factor, "factor", "ConstantFriction.scaled", low=0.0, low_open=True)
        return replace(self, mu0=self.mu0 * factor)

    def nominal_mu(self, pressure: float, velocity: float) -> float:
        """mu_c (Eq. 8) [-], whatever the ``pressure`` [Pa] and ``velocity`` [m/s]."""
        return self.mu


class ConstantFrictionState:
    """Evaluator of a constant friction coefficient (no state to commit)."""

    def __init__(self, mu: float, temperature: float) -> None:
        self._friction = Friction(mu, 0.0, temperature, 0.0)

    def trial(self, position: Pair, velocity: Pair, pressure: float, dt: float) -> Friction:
        """The constant mu, without heat flux."""
        return self._friction

    def lifted(self, position: Pair, dt: float) -> Friction:
        """Out of contact: mu = 0 at the model's temperature."""
        return Friction(0.0, 0.0, self._friction.temperature, 0.0)

    def commit(self) -> None:
        """Nothing to commit."""

    def revert(self) -> None:
        """Nothing to revert."""

    def temperature_field(self) -> None:
        """No monitor points."""
        return None


def eq7(
    pressure: ArrayLike,
    speed: ArrayLike,
    temperature: ArrayLike,
    *,
    mu_t0: float,
    factors: PaperFactors | KumarFactors,
    dependencies: tuple[str, ...] = DEPENDENCIES,
) -> np.ndarray:
    """Eq. 7 in plain numpy, mu_t = mu_t0 gamma(p) alpha(|v|) beta(T) [-], broadcast over the
    inputs: the reference of :func:`isolator.compiled.kernels.ptv_friction`.

    Parameters
    ----------
    pressure, speed, temperature : array_like
        Contact pressure p [Pa], sliding speed |v| [m/s] and contact temperature T [degC].
    mu_t0 : float
        Friction coefficient at the reference condition [-].
    factors : PaperFactors or KumarFactors
        The dependency factors gamma, alpha and beta (Eq. 1-3).
    dependencies : tuple of str
        The active dependencies; a factor left out is 1.
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
        Friction coefficient at 60 N/mm^2, 400 mm/s and 20 degC [-].
    heating : MonitorLine, CentrePoint or None
        Monitor points of the contact temperature: ``MonitorLine()`` for the precise model,
        ``CentrePoint(refinement=0.5)`` for the simplified one; None for no heating.
    factors : PaperFactors, KumarFactors or {"paper", "kumar"}
        Dependency factors; ``"paper"`` is Eq. 1-3.
    dependencies : tuple of str
        Which of ``"pressure"``, ``"velocity"``, ``"temperature"`` act.
    thermal : ThermalProperties
        Conductivity, diffusivity and initial temperature of the plates.
    surfaces : {1, 2}
        Sliding surfaces sharing the relative displacement: 2 for a DCFPB (the slider travels u/2
        over each plate and each takes q = mu p v / 2), 1 for a single concave bearing.
    kernel_min_lag, kernel_max_lag, kernel_tolerance : float
        Time lags [s] over which the heating kernel holds (by default steps down to 1e-6 s,
        histories up to 1e4 s) and its largest relative error there [-].
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
        check_instance(self.factors, "factors", owner, PaperFactors | KumarFactors,
                       "'paper', 'kumar' or a factor set")
        check_instance(self.heating, "heating", owner, MonitorLine | CentrePoint | None,
                       "a MonitorLine, a CentrePoint or None")
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

    @property
    def name(self) -> str:
        """``"precise"`` (a monitor line), ``"simplified"`` (the centre point) or
        ``"ptv-no-heating"``."""
        if self.heating is None:
            return "ptv-no-heating"
        return "precise" if self.heating.average_over_contact else "simplified"

    @property
    def initial_temperature(self) -> float:
        """Temperature of the plates before any sliding [degC]."""
        return self.thermal.initial_temperature

    def scaled(self, factor: float) -> PTVFriction:
        """The model with mu_t0, and so mu at every state, times ``factor`` [-]."""
        check_real(factor, "factor", "PTVFriction.scaled", low=0.0, low_open=True)
        return replace(self, mu_t0=self.mu_t0 * factor)

    def nominal_mu(self, pressure: float, velocity: float) -> float:
        """Eq. 7 [-] at ``pressure`` [Pa], ``velocity`` [m/s] and the initial temperature (the
        cold, nominal value: no heating)."""
        return float(eq7(pressure, velocity, self.initial_temperature, mu_t0=self.mu_t0,
                         factors=self.factors, dependencies=self.dependencies))

    def bind(self, contact_radius: float, travel: float, dimension: int = 1,
             orientation: float | None = None) -> PTVFrictionState:
        """The evaluator for a slider of ``contact_radius`` [m] whose plates move up to
        ``travel`` [m] apart, in ``dimension`` 1 (along x; the precise model's monitor line) or 2
        (the precise model's monitor grid, its first axis at ``orientation`` [deg] from x, None
        following the motion)."""
        return PTVFrictionState(self, contact_radius, travel, dimension, orientation)


class PTVFrictionState:
    """Evaluator of :class:`PTVFriction` for one bearing: the contact temperature from the
    centre point, the monitor line along x (one direction) or the monitor grid (two directions,
    :class:`~isolator.monitor_grid.GridHeating`)."""

    def __init__(self, model: PTVFriction, contact_radius: float, travel: float,
                 dimension: int = 1, orientation: float | None = None) -> None:
        check_int(dimension, "dimension", "PTVFriction.bind", low=1, high=2)
        self.model = model
        self._surfaces = float(model.surfaces)
        code, reference_pressure, rate = model.factors.kernel_parameters
        self.heating: SurfaceHeating | GridHeating | None = None
        constants = {}
        if model.heating is not None:
            kernel = sum_of_exponentials(model.kernel_min_lag, model.kernel_max_lag,
                                         model.kernel_tolerance)
            plate_travel = travel / model.surfaces
            if dimension == 2 and model.heating.average_over_contact:
                grid = MonitorGrid.from_line(model.heating, orientation)
                self.heating = GridHeating(grid, contact_radius, plate_travel, model.thermal,
                                           kernel)
            else:
                self.heating = SurfaceHeating(model.heating, contact_radius, plate_travel,
                                              model.thermal, kernel)
            constants = self.heating.constants()
        self.parameters = pack_ptv({
            **constants, "initial_temperature": model.thermal.initial_temperature,
            "factor_code": code, "reference_pressure": reference_pressure,
            "rate_parameter": rate, "mu_t0": model.mu_t0, "surfaces": self._surfaces,
            **{f"use_{name}": name in model.dependencies
               for name in DEPENDENCIES}})
        """The constants of the compiled kernels (:func:`~isolator.compiled.layout.pack_ptv`):
        the one place a model's parameters become the kernels'."""
        self._pending: tuple[float, float] | None = None

    def trial(self, position: Pair, velocity: Pair, pressure: float, dt: float) -> Friction:
        """Friction at a trial relative displacement [m] and velocity [m/s] of the plates ((x, y)
        pairs), contact pressure p = N / (pi r^2) [Pa] and step since the last commit [s]; the
        slider sits at ``position`` / surfaces on each plate."""
        speed = speed_of(velocity)
        heating = self.heating
        self._pending = None
        if heating is None or dt <= 0.0:  # no heating, or no time: Eq. 7 at T_0
            mu, dmu_dspeed, temperature = initial_friction(self.parameters, pressure, speed)
            return Friction(mu, dmu_dspeed, temperature, mu * pressure * speed / self._surfaces)
        on_plate = (position[0] / self._surfaces, position[1] / self._surfaces)
        mu, dmu_dspeed, temperature, flux = heating.friction_trial(
            on_plate, velocity, pressure, speed, dt, self.parameters)
        self._pending = (dt, flux)
        return Friction(mu, dmu_dspeed, temperature, flux)

    def lifted(self, position: Pair, dt: float) -> Friction:
        """Out of contact at ``position`` [m] for ``dt`` [s]: mu = 0, no heat flux; the commit
        advances the heat history by ``dt`` (the plates cool), and the temperature [degC] is the
        plates' under ``position``."""
        friction = self.trial(position, (0.0, 0.0), REFERENCE_PRESSURE, dt)
        if self._pending is not None:
            self._pending = (self._pending[0], 0.0)
        return Friction(0.0, 0.0, friction.temperature, 0.0)

    def commit(self) -> None:
        """Add the last trial's heat to the plates' history."""
        if self.heating is not None and self._pending is not None:
            self.heating.commit_trial(*self._pending)
        self._pending = None

    def revert(self) -> None:
        """Forget the last trial; the heat history is untouched."""
        self._pending = None

    def temperature_field(self) -> tuple[np.ndarray, np.ndarray] | None:
        """The precise model's monitor points on a plate, positions (m, 2) [m] and temperatures
        (m,) [degC], after the last commit (None for the other models)."""
        return None if self.heating is None else self.heating.temperature_field()
