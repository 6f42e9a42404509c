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
``revert()`` forgets it.

The newest interval's flux enters the current temperature, q_n = mu_n p |v| / surfaces, so
mu_n solves the scalar equation mu = mu_t0 gamma alpha beta(T_base + b q(mu)) by Newton's
method. The velocity derivative includes that coupling.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple, Protocol

import numpy as np

from dcfpb.validation import check_choice, check_int, check_real
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
        """Friction for a trial relative displacement [m], velocity [m/s], pressure [Pa], step [s]."""
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

    def commit(self) -> None:
        """Nothing to commit."""

    def revert(self) -> None:
        """Nothing to revert."""


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
    kernel_min_lag : float
        Shortest time step the heating kernel must resolve [s]; default 1e-6.
    """

    mu_t0: float = 0.075
    heating: HeatingLayout | None = field(default_factory=MonitorLine)
    factors: PaperFactors | KumarFactors | str = "paper"
    dependencies: tuple[str, ...] = DEPENDENCIES
    thermal: ThermalProperties = field(default_factory=ThermalProperties)
    surfaces: int = 2
    kernel_min_lag: float = 1.0e-6

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
        self._factors = model.factors
        self._use = {name: name in model.dependencies for name in DEPENDENCIES}
        self._surfaces = model.surfaces
        self._heating: SurfaceHeating | None = None
        if model.heating is not None:
            kernel: SumOfExponentials = sum_of_exponentials(min_lag=model.kernel_min_lag)
            self._heating = SurfaceHeating(
                model.heating, contact_radius, travel / model.surfaces, model.thermal, kernel
            )
        self._pending: tuple[float, slice, float] | None = None

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
        m = self.model
        speed = abs(velocity)
        gamma = self._factors.pressure(pressure)[0] if self._use["pressure"] else 1.0
        alpha, dalpha = self._factors.velocity(speed) if self._use["velocity"] else (1.0, 0.0)
        mu_cold = m.mu_t0 * gamma * alpha  # Eq. 7 without beta
        temperature = m.thermal.initial_temperature
        if self._heating is None or dt <= 0.0:
            beta, dbeta = (
                self._factors.temperature(temperature) if self._use["temperature"] else (1.0, 0.0)
            )
            mu = mu_cold * beta
            self._pending = None
            return Friction(mu, m.mu_t0 * gamma * dalpha * beta * np.sign(velocity),
                            temperature, mu * pressure * speed / self._surfaces)
        base, newest, heated = self._heating.trial(position / self._surfaces, dt)
        flux_per_mu = pressure * speed / self._surfaces  # q = mu p |v| / surfaces (Eq. 5)
        a = newest * flux_per_mu  # dT/dmu through the newest interval
        mu, beta, dbeta = self._solve(mu_cold, base, a)
        temperature = base + a * mu
        # d mu / d|v|: explicit velocity factor plus the heat-flux coupling through T.
        coupling = mu_cold * dbeta
        dmu_dspeed = (m.mu_t0 * gamma * dalpha * beta + coupling * newest * pressure * mu
                      / self._surfaces) / (1.0 - coupling * a)
        flux = mu * flux_per_mu
        self._pending = (dt, heated, flux)
        return Friction(mu, dmu_dspeed * np.sign(velocity), temperature, flux)

    def _solve(self, mu_cold: float, base: float, a: float) -> tuple[float, float, float]:
        """Solve mu = mu_cold beta(base + a mu) by Newton's method; return mu, beta, dbeta."""
        if not self._use["temperature"]:
            return mu_cold, 1.0, 0.0
        beta, dbeta = self._factors.temperature(base)
        mu = mu_cold * beta
        for _ in range(30):
            beta, dbeta = self._factors.temperature(base + a * mu)
            residual = mu - mu_cold * beta
            step = residual / (1.0 - mu_cold * dbeta * a)
            mu -= step
            if abs(step) <= 1e-15 * abs(mu):
                break
        beta, dbeta = self._factors.temperature(base + a * mu)
        return mu, beta, dbeta

    def commit(self) -> None:
        """Add the last trial's heat to the history."""
        if self._heating is not None and self._pending is not None:
            dt, heated, flux = self._pending
            self._heating.commit(dt, heated, flux)
        self._pending = None

    def revert(self) -> None:
        """Forget the last trial; the heat history is untouched."""
        self._pending = None
