"""Friction models of the sliding surfaces: a strategy the bearing element asks for mu.

``ConstantFriction``
    The paper's constant model (Eq. 8): mu_c = mu_0 gamma(sigma_d) alpha(v_d) beta(T_0).
``PTVFriction``
    The precise and simplified models (Eq. 7): mu_t = mu_t0 gamma(p) alpha(|v|) beta(T), with
    the contact temperature T from a layout of monitor points (:class:`~isolator.heating.
    MonitorLine` for the precise model, :class:`~isolator.heating.CentrePoint` for the
    simplified one) and a factor set (the paper's Eq. 1-3 or Kumar's).

A model is a frozen parameter object with a ``name``, an ``initial_temperature`` [degC] and
``scaled(factor)`` (the model with its friction coefficient times a factor); :meth:`bind`
gives the stateful evaluator for one bearing geometry (contact radius, travel)
in one or two horizontal dimensions, as an OpenSees ``FrictionModel`` serves its bearing. An
evaluator (:class:`FrictionState`) keeps the element contract: ``trial(position, velocity,
pressure, dt) -> Friction`` (vectors as (x, y) pairs; a one-dimensional bearing moves along x)
is a pure function of the committed history and the trial, ``commit()`` accepts the last trial
(and only then adds its heat), ``revert()`` forgets it, and ``lifted(position, dt)`` is the
trial of a slider out of contact: no friction and no heat, while the plates cool over the
step as under a slider at rest. Eq. 7 and 8 take the speed |v|; the element forms the
gradient d mu / d v = d mu / d|v| v / |v|.

The newest interval's flux enters the current temperature, q_n = mu_n p |v| / surfaces, so
mu_n solves the scalar equation mu = mu_t0 gamma alpha beta(T_base + b q(mu)) by Newton's
method, and d mu / d|v| includes that coupling (it is negative on a hot plate at speed).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import NamedTuple, Protocol

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.validation import check_choice, check_int, check_real
from isolator.compiled.kernels import cold_friction, solve_friction
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
    """Friction coefficient of a trial state and what the element needs besides.

    Attributes
    ----------
    mu : float
        Friction coefficient [-].
    dmu_dspeed : float
        Derivative of mu with respect to the sliding speed |v| [s/m].
    temperature : float
        Contact temperature [degC] (the initial temperature for models without heating).
    heat_flux : float
        Heat flux into each sliding surface over the trial step [W/m^2].
    """

    mu: float
    dmu_dspeed: float
    temperature: float
    heat_flux: float


class FrictionState(Protocol):
    """A bound friction model with trial / commit / revert (see the module docstring)."""

    def trial(self, position: Pair, velocity: Pair, pressure: float, dt: float) -> Friction:
        """Friction at a trial relative displacement [m] and velocity [m/s] of the plates,
        contact pressure [Pa] and step since the last commit [s]."""
        ...

    def lifted(self, position: Pair, dt: float) -> Friction:
        """The trial of a slider out of contact at ``position`` [m] for ``dt`` [s]: mu = 0,
        no heat flux, the contact temperature after the plates cooled over ``dt``."""
        ...

    def commit(self) -> None:
        """Accept the last trial."""
        ...

    def revert(self) -> None:
        """Forget trials back to the last commit."""
        ...

    def temperature_field(self) -> tuple[np.ndarray, np.ndarray] | None:
        """Positions (m, 2) [m] on a plate and temperatures (m,) [degC] of the monitor
        points after the last commit; None for a model without a field of them."""
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


class ConstantFrictionState:
    """Evaluator of a constant friction coefficient (no state to commit)."""

    def __init__(self, mu: float, temperature: float) -> None:
        self._friction = Friction(mu, 0.0, temperature, 0.0)

    def trial(self, position: Pair, velocity: Pair, pressure: float, dt: float) -> Friction:
        """The constant mu; heat flux is not tracked."""
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

    def bind(self, contact_radius: float, travel: float, dimension: int = 1,
             orientation: float | None = None) -> PTVFrictionState:
        """The stateful evaluator for a slider of ``contact_radius`` [m].

        ``travel`` [m] is the largest relative displacement of the plates the monitor points
        must cover; ``dimension`` 1 (a bearing moving along x: the precise model's monitor
        line) or 2 (in the plane: the precise model's monitor grid, its first axis at
        ``orientation`` [deg] from x, None following the motion).
        """
        return PTVFrictionState(self, contact_radius, travel, dimension, orientation)


class PTVFrictionState:
    """Evaluator of :class:`PTVFriction` for one bearing (see the module docstring).

    The contact temperature comes from the model's layout of monitor points on each plate:
    the centre point (simplified model) in any dimension; the precise model's line along x for
    a bearing in one dimension and its grid over the plate for a bearing in two
    (:class:`~isolator.monitor_grid.GridHeating`). Both are driven through the same two calls,
    ``friction_trial`` (Eq. 7 solved with the newest interval's flux) and ``commit_trial``.
    """

    def __init__(self, model: PTVFriction, contact_radius: float, travel: float,
                 dimension: int = 1, orientation: float | None = None) -> None:
        check_int(dimension, "dimension", "PTVFriction.bind", low=1, high=2)
        self.model = model
        self._surfaces = float(model.surfaces)
        code, reference_pressure, rate = model.factors.kernel_parameters
        self._cold = (code, reference_pressure, rate, model.mu_t0,
                      "pressure" in model.dependencies, "velocity" in model.dependencies)
        self._use_temperature = "temperature" in model.dependencies
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
        self._parameters = pack_ptv({
            **constants, "initial_temperature": model.thermal.initial_temperature,
            "factor_code": code, "reference_pressure": reference_pressure,
            "rate_parameter": rate, "mu_t0": model.mu_t0, "use_pressure": self._cold[4],
            "use_velocity": self._cold[5], "use_temperature": self._use_temperature,
            "surfaces": self._surfaces})
        self._pending: tuple[float, float] | None = None

    def trial(self, position: Pair, velocity: Pair, pressure: float, dt: float) -> Friction:
        """Friction at a trial relative displacement [m] and velocity [m/s] of the plates
        ((x, y) pairs), contact pressure p = N / (pi r^2) [Pa] and step since the last
        commit [s]. The slider sits at ``position`` / surfaces on each plate."""
        speed = speed_of(velocity)
        heating = self.heating
        self._pending = None
        if heating is None or dt <= 0.0:  # no heating, or no time: Eq. 7 at T_0
            mu_cold, dmu_cold = cold_friction(*self._cold, pressure, speed)
            mu, dmu_dspeed, temperature = solve_friction(
                self._cold[0], mu_cold, dmu_cold, self._use_temperature,
                self.model.thermal.initial_temperature, 0.0, 0.0)
            return Friction(mu, dmu_dspeed, temperature, mu * pressure * speed / self._surfaces)
        on_plate = (position[0] / self._surfaces, position[1] / self._surfaces)
        mu, dmu_dspeed, temperature, flux = heating.friction_trial(
            on_plate, velocity, pressure, speed, dt, self._parameters)
        self._pending = (dt, flux)
        return Friction(mu, dmu_dspeed, temperature, flux)

    def lifted(self, position: Pair, dt: float) -> Friction:
        """Out of contact at ``position`` [m] for ``dt`` [s]: mu = 0 and no heat flux; the
        step is staged with zero flux, so the commit advances the heat history by ``dt`` and
        the plates cool as under a slider at rest (the contact temperature returned is theirs
        under ``position``). Evaluated as the trial at zero speed, where the flux mu p |v| is
        zero whatever mu and the temperature does not depend on the pressure, which is
        therefore taken as the reference one."""
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
        """The monitor points' positions (m, 2) [m] on a plate and temperatures (m,) [degC]
        after the last commit: the precise model's line or grid (None for the others)."""
        return None if self.heating is None else self.heating.temperature_field()
