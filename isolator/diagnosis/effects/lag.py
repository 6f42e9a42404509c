"""``lag``: a time offset between the force and the displacement channels.

The force channel records the force tau [s] after the displacement it belongs to (a filter,
a separate acquisition): the model is driven by u(t - tau). The baseline calibrates up to
``NUISANCE_LAG_SAMPLES`` samples of offset with its pre-sliding transition; this effect is
the offset over a wide range with a yield displacement of its own, named only beyond
``Thresholds.lag_min_samples``. Acts on the kinematics.
"""

from __future__ import annotations

from isolator.diagnosis.effects.base import Effect, Parameter, exp10

MAX_SAMPLES = 30.0  # the largest offset tried [samples]


def _kinematic(theta, c):
    return {"shift": theta[0] * c.sample_interval, "yield_displacement": 10.0 ** theta[1]}


def _reading(theta, stderr, c):
    return {"lag": (float(theta[0]) * c.sample_interval, float(stderr[0]) * c.sample_interval,
                    "s"),
            "lag_samples": (float(theta[0]), float(stderr[0]), "-"),
            "yield_displacement": (*exp10(theta, stderr, 1), "m")}


EFFECT = Effect(
    "lag", "a time offset between the force and displacement channels",
    "the force and displacement channels are not recorded at the same instant (an "
    "anti-alias filter or a separate acquisition on one of them)",
    (Parameter("samples", 0.0, -MAX_SAMPLES, MAX_SAMPLES,
               starts=(-3.0, 3.0, -6.0, 6.0, -12.0, 12.0)),
     Parameter("log_uy", -3.3, -5.0, -2.6, log=True, starts=(), edge_ok=True)), "kinematics",
    kinematic=_kinematic, reading=_reading, order=90)
