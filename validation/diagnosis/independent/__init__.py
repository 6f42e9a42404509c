"""The independent truth model: a bearing test written from physics, apart from the package.

The independent truths import only numpy and the standard library. They share no code with
``isolator``, ``structures``, ``dcfpb``, ``groundmotions`` or ``tests``, so a mistake in the
package cannot be repeated in the data the package's diagnosis is judged on. They are
deliberately plain: one Python loop over the samples, closed forms where they exist, and the
equations in the docstrings of their modules. They make the ``independent`` cases of the
outside panel (:mod:`validation.diagnosis.outside`).

Units are SI at every argument (m, s, N, Pa, degC); the paper's N/mm^2 and mm/s appear only
inside its factors (Nishimoto et al., "SSB part 2: friction models", Eq. 1-8).

The model is in two modules; their public names are importable from here:

- :mod:`~validation.diagnosis.independent.bearing`: the bearing (restoring laws,
  transitions, the friction coefficient's factors, heating on the monitor line, Eq. 1-5
  and 7);
- :mod:`~validation.diagnosis.independent.rig`: the test machine (the tests, the play, the
  force channel's lag, a campaign with its rests, :func:`simulate`) and the measurement noise
  (:func:`noise`).

:mod:`~validation.diagnosis.independent.checks` holds their closed-form self-checks
(:func:`checks`)::

    python -m validation.diagnosis.independent
"""

from __future__ import annotations

from validation.diagnosis.independent.bearing import (
    CONDUCTIVITY,
    DIFFUSIVITY,
    HEAT_COEFFICIENT,
    MU_T0,
    REFERENCE_SPEED,
    REFERENCE_TEMPERATURE,
    SPACING,
    TRANSITIONS,
    Bearing,
    Breakaway,
    Plate,
    Velocity,
    Wear,
    alpha,
    beta,
    bouc_wen_step,
    gamma,
)
from validation.diagnosis.independent.checks import checks
from validation.diagnosis.independent.rig import Test, noise, simulate, sine_test

__all__ = [
    "CONDUCTIVITY",
    "DIFFUSIVITY",
    "HEAT_COEFFICIENT",
    "MU_T0",
    "REFERENCE_SPEED",
    "REFERENCE_TEMPERATURE",
    "SPACING",
    "TRANSITIONS",
    "Bearing",
    "Breakaway",
    "Plate",
    "Test",
    "Velocity",
    "Wear",
    "alpha",
    "beta",
    "bouc_wen_step",
    "checks",
    "gamma",
    "noise",
    "simulate",
    "sine_test",
]
