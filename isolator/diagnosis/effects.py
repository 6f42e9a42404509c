"""The library of candidate effects: physically meaningful extensions of the baseline.

Every candidate changes the calibrated baseline's force

    F = N u / R_eff + c mu_b(t) N z(t)

by a factor m(t) on the friction coefficient and/or an extra force e(t), given the data's own
kinematics (``c`` is the baseline's scale, refitted with every candidate):

``heating``
    m = exp(-a dT / 100 degC) with dT = (1 - w) dT_line + w dT_centre, the contact-temperature
    rise from the measured friction power (Eq. 4-6) on the precise model's monitor line and
    at the simplified model's centre point (lambda = 0.5); a / 100 is the thermal
    sensitivity [1/degC] (Eq. 3 has 0.007), w the weight of the centre point, a shape
    parameter: the flux is measured, so it needs no scale, and with an exponential law a flux
    scale could not be told from the sensitivity anyway.
``velocity``
    m = 1 - a exp(-|v| / v_c): friction a fraction a lower at rest than at speed (PTFE-like,
    a > 0) or higher (Stribeck, a < 0), with a transition velocity v_c.
``pressure``
    m = (p / p_ref)^-n with p = N / contact area and p_ref the campaign's median pressure.
    Only testable when the axial load varies.
``breakaway``
    m = 1 + b exp(-s / d), s the travel since the last reversal: a static friction peak b
    at each reversal (and at the start of motion) that fades over a length d.
``wear``
    m = 1 + a g(S), S the travel accumulated over the campaign (tests in the order run),
    g rising from 0 to 1 over the campaign, exponentially with a travel scale tau S_total
    (linear as tau grows): a drift of friction by a fraction a.
``stiffness``
    e = k N u: a restoring stiffness other than N / R_eff, per unit axial load
    (k = 1 / R_true - 1 / R_eff; reported with the apparent effective radius).
``asymmetry``
    m = 1 + a sign(z): friction differs between the two sliding directions, mu(+) / mu(-)
    = (1 + a) / (1 - a) (a tilted or anisotropic sliding surface, a self-energising band).

Parameters are given on a scale where they are of order one; nonlinear scale parameters are
fitted as their base-10 logarithm. :func:`physical_parameters` turns a fit into the values
engineers read, with units.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from isolator.diagnosis.features import Features

TEMPERATURE_SCALE = 100.0  # [degC] the heating parameter is the log-factor per 100 degC


@dataclass(frozen=True)
class Parameter:
    """A fitted parameter of a candidate, on its fitting scale.

    Attributes
    ----------
    name : str
        Name on the fitting scale.
    initial, low, high : float
        Start value and bounds (of log10 of the value when ``log``).
    log : bool
        Whether the parameter is fitted as log10 of its value.
    """

    name: str
    initial: float
    low: float
    high: float
    log: bool = False


@dataclass(frozen=True)
class Context:
    """Campaign-wide constants the candidates scale their parameters with.

    Attributes
    ----------
    reference_pressure : float
        Median contact pressure [Pa].
    pressure_spread : float
        Ratio of the 95th to the 5th percentile of the pressure, less one [-].
    reference_displacement : float
        99th percentile of |u| [m].
    campaign_travel : float
        Total travel of the campaign [m].
    effective_radius : float
        R_eff [m] (inf for a flat slider).
    largest_rise : float
        Largest contact-temperature rise [degC].
    """

    reference_pressure: float
    pressure_spread: float
    reference_displacement: float
    campaign_travel: float
    effective_radius: float
    largest_rise: float

    @classmethod
    def of(cls, features: Features, effective_radius: float) -> Context:
        """The constants of a whole campaign."""
        p5, p50, p95 = np.percentile(features.pressure, [5, 50, 95])
        return cls(float(p50), float(p95 / p5 - 1.0),
                   float(np.percentile(np.abs(features.displacement), 99)),
                   float(features.campaign_travel.max()), float(effective_radius),
                   float(features.temperature_rise.max()))


Modulation = Callable[[np.ndarray, Features, Context], np.ndarray]
Requirement = Callable[[Context], str | None]


@dataclass(frozen=True)
class Effect:
    """One candidate: its parameters, a factor on mu and/or an extra force.

    Attributes
    ----------
    name : str
        Name used in the verdict.
    description : str
        One line for reports.
    parameters : tuple of Parameter
        Its own parameters (the baseline's scale is added by the fit).
    factor : callable or None
        ``factor(theta, features, context) -> m`` [-].
    extra : callable or None
        ``extra(theta, features, context) -> e`` [N].
    requires : callable or None
        ``requires(context) -> reason or None``: why the campaign cannot show the effect.
    """

    name: str
    description: str
    parameters: tuple[Parameter, ...]
    factor: Modulation | None = None
    extra: Modulation | None = None
    requires: Requirement | None = None

    def untestable(self, context: Context) -> str | None:
        """Why the data cannot show this effect, or None when it can."""
        return None if self.requires is None else self.requires(context)


def _varying_pressure(c: Context) -> str | None:
    if c.pressure_spread < 0.05:
        return "the contact pressure hardly varies (less than 5 %)"
    return None


def _some_heat(c: Context) -> str | None:
    if c.largest_rise < 1.0:
        return "the friction power heats the contact by less than 1 degC"
    return None


def _heating(theta, f, c):
    rise = (1.0 - theta[1]) * f.temperature_rise + theta[1] * f.centre_rise
    return np.exp(-theta[0] * rise / TEMPERATURE_SCALE)


def _velocity(theta, f, c):
    return 1.0 - theta[0] * np.exp(-f.speed / 10.0 ** theta[1])


def _pressure(theta, f, c):
    return (f.pressure / c.reference_pressure) ** (-theta[0])


def _breakaway(theta, f, c):
    return 1.0 + theta[0] * np.exp(-f.since_reversal / 10.0 ** theta[1])


def _wear(theta, f, c):
    tau = 10.0 ** theta[1]
    share = f.campaign_travel / max(c.campaign_travel, 1e-12)
    growth = -np.expm1(-share / tau) / -math.expm1(-1.0 / tau)
    return 1.0 + theta[0] * growth


def _stiffness(theta, f, c):
    return theta[0] * f.axial_force * f.displacement / c.reference_displacement


def _asymmetry(theta, f, c):
    return 1.0 + theta[0] * np.sign(f.z)


LIBRARY: tuple[Effect, ...] = (
    Effect("heating", "friction falls as the contact heats (thermal sensitivity)",
           (Parameter("a", 0.5, -3.0, 5.0), Parameter("w", 0.2, 0.0, 1.0)), factor=_heating,
           requires=_some_heat),
    Effect("velocity", "friction depends on the sliding speed",
           (Parameter("a", 0.3, -2.0, 0.95), Parameter("log_vc", -1.3, -3.0, 0.5, log=True)),
           factor=_velocity),
    Effect("pressure", "friction depends on the contact pressure",
           (Parameter("n", 0.2, -2.0, 2.0),), factor=_pressure, requires=_varying_pressure),
    Effect("breakaway", "a static friction peak at each reversal",
           (Parameter("b", 0.3, -0.9, 5.0), Parameter("log_d", -2.3, -4.0, -0.7, log=True)),
           factor=_breakaway),
    Effect("wear", "friction drifts with the travel accumulated over the campaign",
           (Parameter("a", -0.1, -0.9, 3.0), Parameter("log_tau", 0.0, -1.3, 1.3, log=True)),
           factor=_wear),
    Effect("stiffness", "a restoring stiffness other than N / R_eff",
           (Parameter("k", 0.0, -1.0, 1.0),), extra=_stiffness),
    Effect("asymmetry", "friction differs between the two sliding directions",
           (Parameter("a", 0.0, -0.9, 0.9),), factor=_asymmetry),
)
EFFECT_NAMES = tuple(e.name for e in LIBRARY)


def effects_named(names: Sequence[str]) -> tuple[Effect, ...]:
    """The library's effects called ``names``, in that order."""
    table = {e.name: e for e in LIBRARY}
    unknown = [n for n in names if n not in table]
    if unknown:
        raise ValueError(f"Unknown effect(s) {unknown}; the library has {list(EFFECT_NAMES)}.")
    return tuple(table[n] for n in names)


def physical_parameters(effect: Effect, theta: np.ndarray, stderr: np.ndarray,
                        context: Context) -> dict[str, tuple[float, float, str]]:
    """``{name: (value, standard error, unit)}`` of a fitted effect, in engineering terms.

    ``theta`` and ``stderr`` are on the fitting scale (see :class:`Parameter`); errors of a
    log parameter go through the delta method.
    """
    def linear(i: int) -> tuple[float, float]:
        return float(theta[i]), float(stderr[i])

    def exp10(i: int) -> tuple[float, float]:
        value = 10.0 ** float(theta[i])
        return value, value * math.log(10.0) * float(stderr[i])

    name = effect.name
    if name == "heating":
        a, sa = linear(0)
        return {"thermal_sensitivity": (a / TEMPERATURE_SCALE, sa / TEMPERATURE_SCALE,
                                        "1/degC"),
                "centre_weight": (*linear(1), "-"),
                "largest_rise": (context.largest_rise, 0.0, "degC")}
    if name == "velocity":
        return {"low_speed_drop": (*linear(0), "-"), "transition_velocity": (*exp10(1), "m/s")}
    if name == "pressure":
        return {"pressure_exponent": (*linear(0), "-"),
                "reference_pressure": (context.reference_pressure, 0.0, "Pa")}
    if name == "breakaway":
        return {"peak_ratio": (*linear(0), "-"), "decay_length": (*exp10(1), "m")}
    if name == "wear":
        tau, stau = exp10(1)
        total = context.campaign_travel
        return {"change_over_campaign": (*linear(0), "-"),
                "travel_scale": (tau * total, stau * total, "m"),
                "campaign_travel": (total, 0.0, "m")}
    if name == "stiffness":
        k, sk = linear(0)
        per_load = k / context.reference_displacement
        out = {"stiffness_per_axial_load": (per_load, sk / context.reference_displacement,
                                            "1/m")}
        inverse = 1.0 / context.effective_radius + per_load
        if inverse > 0.0:
            out["apparent_effective_radius"] = (
                1.0 / inverse, sk / context.reference_displacement / inverse**2, "m")
        return out
    if name == "asymmetry":
        a, sa = linear(0)
        ratio = (1.0 + a) / (1.0 - a)
        return {"direction_ratio": (ratio, 2.0 * sa / (1.0 - a) ** 2, "-")}
    return {p.name: (float(theta[i]), float(stderr[i]), "-")
            for i, p in enumerate(effect.parameters)}
