"""``asymmetry``: friction differs between the two sliding directions.

m = 1 + a sign(z): mu(+) / mu(-) = (1 + a) / (1 - a) (a tilted or anisotropic sliding surface,
a self-energising band brake).
"""

from __future__ import annotations

import numpy as np

from isolator.diagnosis.effects.base import Effect, Parameter


def _factor(theta, f, c):
    return 1.0 + theta[0] * np.sign(f.z)


def _reading(theta, stderr, c):
    a, sa = float(theta[0]), float(stderr[0])
    return {"direction_ratio": ((1.0 + a) / (1.0 - a), 2.0 * sa / (1.0 - a) ** 2, "-")}


EFFECT = Effect(
    "asymmetry", "friction differs between the two sliding directions",
    "the friction coefficient depends on the direction of sliding (a tilted or anisotropic "
    "surface, a self-energising brake band)",
    (Parameter("a", 0.0, -0.9, 0.9),), "mu", factor=_factor, reading=_reading, order=70)
