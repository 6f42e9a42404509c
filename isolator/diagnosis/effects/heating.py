"""``heating``: friction falls as the contact heats (the paper's Eq. 3 and 4-6).

m = exp(-a dT / 100 degC) with dT = (1 - w) dT_line + w dT_centre, the contact-temperature
rise from the measured friction power (Eq. 4-6) on the precise model's monitor line and at the
simplified model's centre point (lambda = 0.5). a / 100 is the thermal sensitivity [1/degC]
(Eq. 3 has 0.007) and w the weight of the centre point, a shape parameter: the flux is
measured, so it needs no scale. Flexible form: monotone in dT.
"""

from __future__ import annotations

import numpy as np

from isolator.diagnosis.effects.base import Context, Effect, Parameter, linear

TEMPERATURE_SCALE = 100.0  # [degC] the parameter a is the log-factor per 100 degC


def rise(theta, f, c: Context) -> np.ndarray:
    """The contact-temperature rise the effect reads [degC]."""
    w = theta[1] if len(theta) > 1 else 0.0
    return (1.0 - w) * f.temperature_rise + w * f.centre_rise


def modulation(a, rise: np.ndarray) -> np.ndarray:
    """m = exp(-a dT / 100 degC) [-] for a log-factor ``a`` per 100 degC and a contact-
    temperature ``rise`` dT [degC]: the effect's form in one direction and in two."""
    return np.exp(-a * rise / TEMPERATURE_SCALE)


def _factor(theta, f, c):
    return modulation(theta[0], rise(theta, f, c))


def _requires(c: Context) -> str | None:
    if c.largest_rise < 1.0:
        return "the friction power heats the contact by less than 1 degC"
    return None


def _reading(theta, stderr, c):
    a, sa = linear(theta, stderr, 0)
    return {"thermal_sensitivity": (a / TEMPERATURE_SCALE, sa / TEMPERATURE_SCALE, "1/degC"),
            "centre_weight": (*linear(theta, stderr, 1), "-"),
            "largest_rise": (c.largest_rise, 0.0, "degC")}


EFFECT = Effect(
    "heating", "friction falls as the contact heats (thermal sensitivity)",
    "the sliding surface heats under the friction power (Eq. 4-6) and its friction "
    "coefficient falls with the contact temperature (Eq. 3)",
    (Parameter("a", 0.5, -3.0, 5.0), Parameter("w", 0.2, 0.0, 1.0, edge_ok=True)), "mu",
    factor=_factor, variable=lambda f, c: f.temperature_rise, requires=_requires,
    reading=_reading, order=10)
