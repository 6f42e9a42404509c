"""What an effect of the diagnosis is: its parameters, where it acts, its physical reading.

An :class:`Effect` is one candidate explanation of the gap between a calibrated baseline and
measured bearing tests. It acts where the physics acts: on the **kinematics** (the
displacement the bearing really undergoes: a play, a channel offset), on the **friction
coefficient**, mu(t) = c mu_base(t) m(t) with m a function of the effect's own variable, or
on the **force** (a restoring stiffness other than N / R_eff, the spherical geometry).
Parameters are fitted on a scale where they are of order one, scale parameters as log10.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from dcfpb.common.errors import InputError

ACTS_ON = ("kinematics", "mu", "force")


@dataclass(frozen=True)
class Parameter:
    """A fitted parameter of an effect, on its fitting scale.

    Attributes
    ----------
    name : str
        Name on the fitting scale.
    initial, low, high : float
        Start value and bounds, of log10 of the value when ``log``.
    log : bool
        Whether the parameter is fitted as log10 of its value.
    starts : tuple of float
        Further start values of a multistart fit.
    edge_ok : bool
        Whether a fit at a bound is still a physical reading (a weight at 0 or 1, a
        rigid-plastic transition, a linear drift); otherwise an effect fitted at a bound is
        not named, since the data ask for more than its physics gives.
    unit : str
        Unit of the value on the fitting scale (the parameters of tests in two directions
        are read as fitted).
    scan : float
        For a parameter whose effect moves in whole samples (a play's width: the force
        changes only when a gap's edge crosses a sample, so a finite-difference gradient is
        zero), the step of a grid over its range on which each start of a fit is scanned
        first, on its fitting scale (0: not scanned; :func:`isolator.diagnosis.fitting.fit`).
    """

    name: str
    initial: float
    low: float
    high: float
    log: bool = False
    starts: tuple[float, ...] = ()
    edge_ok: bool = False
    unit: str = "-"
    scan: float = 0.0

    def at_bound(self, value: float) -> bool:
        """Whether ``value`` (fitting scale) sits at a bound (within 0.5 % of the range)."""
        margin = 0.005 * (self.high - self.low)
        return not self.edge_ok and (value <= self.low + margin or value >= self.high - margin)


@dataclass(frozen=True)
class Context:
    """Campaign-wide constants the effects scale their parameters with.

    Attributes
    ----------
    reference_pressure, pressure_spread : float
        Median contact pressure [Pa]; ratio of its 95th to its 5th percentile, less one [-].
    reference_displacement, campaign_travel : float
        99th percentile of |u| [m]; total travel of the campaign [m].
    effective_radius : float
        R_eff the user gave [m] (inf for a flat slider).
    largest_rise : float
        Largest contact-temperature rise from the measured friction power [degC].
    sample_interval : float
        Median sampling interval [s].
    yield_displacement, nominal_mu, channel_lag : float
        The calibrated baseline's u_y [m], mean mu [-] and lag of the force channel [s].
    tests : int
        Number of tests.
    kinematics : object or None
        The contiguous histories (:class:`isolator.diagnosis.fitting.Kinematics`) on which
        kinematic effects recompute the return map.
    """

    reference_pressure: float
    pressure_spread: float
    reference_displacement: float
    campaign_travel: float
    effective_radius: float
    largest_rise: float
    sample_interval: float = 0.01
    yield_displacement: float = 5.0e-4
    nominal_mu: float = 0.05
    tests: int = 1
    channel_lag: float = 0.0
    kinematics: object | None = field(default=None, compare=False, repr=False)

    @classmethod
    def of(cls, features, effective_radius: float, **known) -> Context:
        """The constants of a campaign's :class:`~isolator.diagnosis.features.Features`;
        ``known`` sets the others."""
        p5, p50, p95 = np.percentile(features.pressure, [5, 50, 95])
        return cls(float(p50), float(p95 / p5 - 1.0),
                   float(np.percentile(np.abs(features.displacement), 99)),
                   float(features.campaign_travel.max()), float(effective_radius),
                   float(features.temperature_rise.max()), **known)


Modulation = Callable[[np.ndarray, object, Context], np.ndarray]
Requirement = Callable[[Context], "str | None"]
Reading = Callable[[np.ndarray, np.ndarray, Context], dict[str, tuple[float, float, str]]]


@dataclass(frozen=True)
class Effect:
    """One candidate: its parameters, where it acts, and how it reads.

    Attributes
    ----------
    name, description, physical_reading : str
        Name in the verdict, one line for reports, what the effect is physically.
    parameters : tuple of Parameter
        Its own parameters (the fit adds the baseline's scale c).
    acts_on : {"kinematics", "mu", "force"}
        Where it acts; the hooks below that act there must not all be None.
    factor, extra : callable or None
        ``factor(theta, features, context) -> m`` [-] multiplying mu, and
        ``extra(theta, features, context) -> e`` [N] added to the force.
    transform : callable or None
        ``transform(theta, features, context, pendulum, friction) -> force`` [N] from the
        pendulum force and the friction force mu N z.
    kinematic : callable or None
        ``kinematic(theta, context) -> {"shift": s, "half_width": h, "yield_displacement": y}``
        (any of them): a further lag of the force channel [s], a play's half width [m], a
        yield displacement [m]; the return map and the pendulum force are recomputed.
    variable : callable or None
        ``variable(features, context) -> x``: the variable of its flexible monotone form
        (:mod:`isolator.diagnosis.flexible`).
    requires : callable or None
        ``requires(context) -> reason or None``: why the campaign cannot show the effect.
    reading : callable or None
        ``reading(theta, stderr, context) -> {name: (value, stderr, unit)}``.
    order : int
        Position in the library's listing.
    """

    name: str
    description: str
    physical_reading: str
    parameters: tuple[Parameter, ...]
    acts_on: str
    factor: Modulation | None = None
    extra: Modulation | None = None
    transform: Callable | None = None
    kinematic: Callable | None = None
    variable: Callable | None = None
    requires: Requirement | None = None
    reading: Reading | None = None
    order: int = 100

    def __post_init__(self) -> None:
        if self.acts_on not in ACTS_ON:
            raise InputError(f"The 'acts_on' parameter of Effect {self.name!r} must be one of "
                             f"{ACTS_ON}. Got {self.acts_on!r} instead.")
        hooks = {"kinematics": (self.kinematic,), "mu": (self.factor,),
                 "force": (self.extra, self.transform)}[self.acts_on]
        if all(h is None for h in hooks):
            raise InputError(f"Effect {self.name!r} acts on {self.acts_on} but defines none of "
                             "the hooks that act there.")

    def untestable(self, context: Context) -> str | None:
        """Why the data cannot show this effect, or None when it can."""
        return None if self.requires is None else self.requires(context)

    def physical_parameters(self, theta: np.ndarray, stderr: np.ndarray,
                            context: Context) -> dict[str, tuple[float, float, str]]:
        """``{name: (value, standard error, unit)}`` in engineering terms."""
        if self.reading is not None:
            return self.reading(theta, stderr, context)
        return {p.name: (float(theta[i]), float(stderr[i]), "-")
                for i, p in enumerate(self.parameters)}


def linear(theta: np.ndarray, stderr: np.ndarray, i: int) -> tuple[float, float]:
    """(value, standard error) of a linear parameter."""
    return float(theta[i]), float(stderr[i])


def exp10(theta: np.ndarray, stderr: np.ndarray, i: int) -> tuple[float, float]:
    """(value, standard error) of a log10 parameter (delta method)."""
    value = 10.0 ** float(theta[i])
    return value, value * float(np.log(10.0)) * float(stderr[i])
