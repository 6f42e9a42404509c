"""The bidirectional panel and its truth model: bearing tests in two directions, written apart
from the package.

The truth model imports only numpy and the standard library (its self-checks also compare it
with the one-direction truth :mod:`validation.diagnosis.independent`). It shares no code with
``isolator``, ``structures``, ``groundmotions`` or ``dcfpb``. Units are SI (m, s, N, Pa, degC).

- :mod:`~validation.diagnosis.bidirectional.bearing`: the bearing, a vector friction force of
  magnitude mu N (rigid-plastic, elastic-plastic radial return or smooth isotropic Bouc-Wen),
  the linear or spherical restoring force, the friction coefficient on the speed |v|, the
  pressure, the heating field of the plate (Eq. 4-5 over the contact disc) and wear;
- :mod:`~validation.diagnosis.bidirectional.orbits`: circular, figure-eight, square and
  earthquake orbits (a PEER pair from ``../shared/groundmotions/pairs`` or a synthetic pair);
- :mod:`~validation.diagnosis.bidirectional.rig`: the test machine (the actuators' dynamics,
  a play per axis, the force channels' lag, campaigns) and the measurement chain (sampling,
  noise colours, quantisation, spikes, a stuck run, a gain error);
- :mod:`~validation.diagnosis.bidirectional.checks`: the self-checks;
- :mod:`~validation.diagnosis.bidirectional.cases` and
  :mod:`~validation.diagnosis.bidirectional.write`: the panel (its cases, label rule and
  files).

    python -m validation.diagnosis.bidirectional --checks
    python -m validation.diagnosis.bidirectional FOLDER [--seed 2026] [--half tune|test]
"""

from __future__ import annotations

from validation.diagnosis.bidirectional.bearing import (
    Bearing2D,
    HeatField,
    SpeedLaw,
    WearLaw,
    lens_area,
    transition_step,
)
from validation.diagnosis.bidirectional.cases import CASES, EFFECTS, HALVES, Case, Run
from validation.diagnosis.bidirectional.checks import TOLERANCES, checks
from validation.diagnosis.bidirectional.orbits import (
    Orbit,
    circular,
    earthquake,
    figure_eight,
    square,
)
from validation.diagnosis.bidirectional.rig import (
    Measurement,
    Rig,
    Test2D,
    measure,
    noise,
    quantise,
    simulate,
)
from validation.diagnosis.bidirectional.write import (
    COLUMNS,
    contributions,
    load_labels,
    make_tests,
    truth,
    write_panel,
)

__all__ = [
    "CASES",
    "COLUMNS",
    "EFFECTS",
    "HALVES",
    "TOLERANCES",
    "Bearing2D",
    "Case",
    "HeatField",
    "Measurement",
    "Orbit",
    "Rig",
    "Run",
    "SpeedLaw",
    "Test2D",
    "WearLaw",
    "checks",
    "circular",
    "contributions",
    "earthquake",
    "figure_eight",
    "lens_area",
    "load_labels",
    "make_tests",
    "measure",
    "noise",
    "quantise",
    "simulate",
    "square",
    "transition_step",
    "truth",
    "write_panel",
]
