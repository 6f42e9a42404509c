"""``pressure``: friction depends on the contact pressure (the paper's Eq. 1).

m = (p / p_ref)^-n with p = N / contact area and p_ref the campaign's median pressure. Only
testable when the axial load varies (in time, or from test to test of a campaign). Flexible
form: monotone in log p.
"""

from __future__ import annotations

import numpy as np

from isolator.diagnosis.effects.base import Context, Effect, Parameter, linear


def modulation(n, pressure: np.ndarray, reference: float) -> np.ndarray:
    """m = (p / p_ref)^-n [-] for an exponent ``n`` [-], the contact ``pressure`` p and its
    ``reference`` p_ref [Pa]: the effect's form in one direction and in two."""
    return (pressure / reference) ** (-n)


def _factor(theta, f, c):
    return modulation(theta[0], f.pressure, c.reference_pressure)


def _requires(c: Context) -> str | None:
    if c.pressure_spread < 0.05:
        return "the contact pressure hardly varies (less than 5 %)"
    return None


def _reading(theta, stderr, c):
    return {"pressure_exponent": (*linear(theta, stderr, 0), "-"),
            "reference_pressure": (c.reference_pressure, 0.0, "Pa")}


EFFECT = Effect(
    "pressure", "friction depends on the contact pressure",
    "the friction coefficient falls as the bearing stress rises (Eq. 1)",
    (Parameter("n", 0.2, -2.0, 2.0),), "mu", factor=_factor,
    variable=lambda f, c: np.log(f.pressure / c.reference_pressure), requires=_requires,
    reading=_reading, order=30)
