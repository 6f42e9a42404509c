"""``breakaway``: a static friction peak at each reversal (and at the start of motion).

m = 1 + b exp(-s / d), s the travel since the last reversal: a peak b >= 0 (static friction
above kinetic; a dip after each reversal is a play or a lag, and a fit at b = 0 is not named)
fading over a length d of 1 to 50 mm (shorter is the pre-sliding transition the baseline
calibrates, longer some other drift). Flexible form: monotone in s.
"""

from __future__ import annotations

import numpy as np

from isolator.diagnosis.effects.base import Effect, Parameter, exp10, linear


def _factor(theta, f, c):
    return 1.0 + theta[0] * np.exp(-f.since_reversal / 10.0 ** theta[1])


def _reading(theta, stderr, c):
    return {"peak_ratio": (*linear(theta, stderr, 0), "-"),
            "decay_length": (*exp10(theta, stderr, 1), "m")}


EFFECT = Effect(
    "breakaway", "a static friction peak at each reversal",
    "static friction above kinetic friction: a peak each time sliding starts again, fading "
    "over a length of travel",
    (Parameter("b", 0.3, 0.0, 5.0), Parameter("log_d", -2.3, -3.0, -1.3, log=True)), "mu",
    factor=_factor, variable=lambda f, c: f.since_reversal, reading=_reading, order=40)
