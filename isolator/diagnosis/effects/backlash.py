"""``backlash``: a dead band (play) in the load train between the actuator and the bearing.

The displacement channel measures the actuator. With a play of total width b the bearing
follows the actuator only once the gap has closed: u_b stays within b / 2 of u, and while the
gap is open no force is transmitted (the load cell reads zero) and the bearing stands still.
When contact is made again the bearing's force rebuilds through its pre-sliding transition
from zero (:func:`isolator.diagnosis.kinematics.play_return_map`), with a pre-sliding yield
displacement of its own (the baseline's u_y has absorbed part of the play). Acts on the
kinematics, before the return map.
"""

from __future__ import annotations

from isolator.diagnosis.effects.base import Effect, Parameter, exp10


def _kinematic(theta, c):
    return {"half_width": 0.5 * 10.0 ** theta[0], "yield_displacement": 10.0 ** theta[1]}


def _reading(theta, stderr, c):
    return {"width": (*exp10(theta, stderr, 0), "m"),
            "yield_displacement": (*exp10(theta, stderr, 1), "m")}


EFFECT = Effect(
    "backlash", "a dead band (play) between the actuator and the bearing",
    "a play in the load train: after each reversal the actuator travels the width of the "
    "gap before it pushes the bearing again, and no force is transmitted meanwhile",
    (Parameter("log_b", -2.6, -3.7, -1.5, log=True, starts=(-3.2, -2.2)),
     Parameter("log_uy", -3.7, -5.0, -2.6, log=True, starts=(-4.5, -3.0), edge_ok=True)),
    "kinematics",
    kinematic=_kinematic, reading=_reading, order=80)
