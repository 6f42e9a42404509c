"""``backlash``: a dead band (play) in the load train between the actuator and the bearing.

The displacement channel measures the actuator. With a play of width b the bearing stays
within b / 2 of it; while the gap is open the bearing stands still and the load cell reads
zero, and once it closes the force rebuilds from zero through a pre-sliding transition with
a yield displacement of its own, since the baseline's u_y has absorbed part of the play
(:func:`isolator.diagnosis.kinematics.play_return_map`). Acts on the kinematics.
"""

from __future__ import annotations

from isolator.diagnosis.effects.base import Effect, Parameter, exp10

SCAN = 0.01  # log10 step of the width's grid (2.3 %): the fit's gradient in it is zero


def _kinematic(theta, c):
    return {"half_width": 0.5 * 10.0 ** theta[0], "yield_displacement": 10.0 ** theta[1]}


def _reading(theta, stderr, c):
    return {"width": (*exp10(theta, stderr, 0), "m"),
            "yield_displacement": (*exp10(theta, stderr, 1), "m")}


EFFECT = Effect(
    "backlash", "a dead band (play) between the actuator and the bearing",
    "a play in the load train: after each reversal the actuator travels the width of the "
    "gap before it pushes the bearing again, and no force is transmitted meanwhile",
    (Parameter("log_b", -2.6, -3.7, -1.5, log=True, starts=(-3.2, -2.2), scan=SCAN),
     Parameter("log_uy", -3.7, -5.0, -2.6, log=True, starts=(-4.5, -3.0), edge_ok=True)),
    "kinematics",
    kinematic=_kinematic, reading=_reading, order=80)
