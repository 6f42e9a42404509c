"""``velocity``: friction depends on the sliding speed (the paper's Eq. 2).

m = 1 - a exp(-|v| / v_c): friction a fraction a lower at rest than at speed (PTFE-like,
a > 0) or higher (Stribeck, a < 0), with a transition velocity v_c. Flexible form: monotone
in log |v|.
"""

from __future__ import annotations

import numpy as np

from isolator.diagnosis.effects.base import Effect, Parameter, exp10, linear

SPEED_FLOOR = 1.0e-4  # [m/s] the flexible form's variable is log10(|v| + this)


def modulation(a, v_c, speed: np.ndarray) -> np.ndarray:
    """m = 1 - a exp(-|v| / v_c) [-] for a low-speed drop ``a`` [-], a transition velocity
    ``v_c`` [m/s] and the sliding ``speed`` |v| [m/s]: the effect's form in one direction and
    in two (on the speed of the orbit)."""
    return 1.0 - a * np.exp(-speed / v_c)


def _factor(theta, f, c):
    return modulation(theta[0], 10.0 ** theta[1], f.speed)


def _reading(theta, stderr, c):
    return {"low_speed_drop": (*linear(theta, stderr, 0), "-"),
            "transition_velocity": (*exp10(theta, stderr, 1), "m/s")}


EFFECT = Effect(
    "velocity", "friction depends on the sliding speed",
    "the friction coefficient changes with the sliding velocity (Eq. 2: lower at low speed "
    "for PTFE-like liners; a Stribeck peak when higher)",
    (Parameter("a", 0.3, -2.0, 0.95), Parameter("log_vc", -1.3, -3.0, 0.5, log=True)), "mu",
    factor=_factor, variable=lambda f, c: np.log10(f.speed + SPEED_FLOOR),
    reading=_reading, order=20)
