"""The outside panel: 48 cases in 24 scenario pairs, designed apart from the tuning, labels
kept apart.

Each *scenario* (a set of true effects, possibly none) is made twice: one case goes to the
**tune** half (the only half thresholds may be chosen on), the other to the **test** half (the
half scores are reported on). The two cases of a pair share the labelled effects and differ in
their truth source and in nuisance: amplitudes (0.02-0.4 m), sampling (100-500 Hz), white,
AR(1) or band-limited noise (0.3-1.5 % of the nominal friction force mu0 W on the force,
0.01-0.05 mm on the displacement), a channel lag of up to 1.5 samples, the pre-sliding
transition (rigid-plastic, elastic-plastic 0.1-1.5 mm, smooth Bouc-Wen), campaigns of one to
four tests (sines at several amplitudes and periods, ASCE-like 3-cycle sines at 4.26 s, a slow
wind-like test at about 15 mm/s), a velocity column or not, an axial-force column or not.

The panel is written by four modules, whose public names are all importable from here:
:mod:`~validation.diagnosis.outside.cases` (the records and the 48 cases),
:mod:`~validation.diagnosis.outside.sources` (the three truth sources),
:mod:`~validation.diagnosis.outside.labels` (the label rule and the design record) and
:mod:`~validation.diagnosis.outside.write` (the measurement noise, the files and
:func:`write_panel`). It is never used to choose anything: the thresholds are chosen on the
tuning panel (:mod:`validation.diagnosis.tuning`).

Truth sources
-------------
``independent``
    :mod:`validation.diagnosis.independent` (numpy only, written from the paper and from
    physics; it shares no code with the package).
``opensees``
    OpenSees ``singleFPBearing`` / ``flatSliderBearing`` (Coulomb, VelDependent) and
    ``FPBearingPTV`` through
    :func:`structures.opensees.bearing.run_opensees_test`; instrument effects (lag, noise) are
    applied to its output.
``package``
    Our own element with the truths' extra physics,
    :func:`structures.diagnosis.truths.element_truth`.

Label rule
----------
An effect is labelled when its own contribution to the clean force, the truth with it less the
truth without it (everything else equal, no noise), has an RMS of at least 3 % of the RMS
force over the campaign (``design.contribution``). Physics the truth has but the label and the
told baseline do not (singleFPBearing's normal-force coupling N = W + F u / R at small u / R,
FPBearingPTV's spherical restoring law at R = 4.5 m, the independent precise model's
differences from the package's) contributes at most 1 % (``design.unlabelled``). The share
left after refitting the friction level of the truth without the effect (what a calibrated
mu could absorb) is stored too (``design.contribution_refit``). Instrument nuisance (a lag of
up to 1.5 samples, the noise, the transition's shape) is never labelled.

Files
-----
Each ``folder/case_NN/`` holds the test files, ``manifest.csv`` and ``bearing.json`` (what a
user tells the diagnosis); ``folder/labels.json`` holds the labels, ``folder/panel.json`` the
seed (see :mod:`~validation.diagnosis.outside.write`).

    python -m validation.diagnosis.outside FOLDER [--seed 2026] [--half tune|test] [--no-opensees]
"""

from __future__ import annotations

from validation.diagnosis.outside.cases import (
    AREA,
    ASCE,
    AXIAL_NOISE,
    CASES,
    DAMPER,
    EFFECTS,
    EP,
    HALVES,
    HEAT,
    HEAT_SET,
    ISSUE21_PAIRS,
    ISSUE21_TRUTHS,
    LABEL_MIN,
    MU0,
    NIGHT,
    NIGHTS_PRECISE,
    PAIR,
    PRECISE_BASE,
    PRESSURE,
    PRESSURES,
    RADIUS,
    SINE_SET,
    SLIDER,
    SOURCES,
    UNLABELLED_MAX,
    VARYING,
    VELOCITY_NOISE,
    VELOCITY_SET,
    WEAR_SET,
    Case,
    S,
    Sine,
    W,
    axial_load,
    check_design,
    rest_before,
)
from validation.diagnosis.outside.labels import contributions, design_record
from validation.diagnosis.outside.sources import (
    SOURCE_FUNCTIONS,
    independent,
    independent_truth_bearing,
    opensees,
    package,
)
from validation.diagnosis.outside.write import (
    load_labels,
    main,
    measured,
    opensees_available,
    write_panel,
)

__all__ = [
    "AREA",
    "ASCE",
    "AXIAL_NOISE",
    "CASES",
    "DAMPER",
    "EFFECTS",
    "EP",
    "HALVES",
    "HEAT",
    "HEAT_SET",
    "ISSUE21_PAIRS",
    "ISSUE21_TRUTHS",
    "LABEL_MIN",
    "MU0",
    "NIGHT",
    "NIGHTS_PRECISE",
    "PAIR",
    "PRECISE_BASE",
    "PRESSURE",
    "PRESSURES",
    "RADIUS",
    "SINE_SET",
    "SLIDER",
    "SOURCES",
    "SOURCE_FUNCTIONS",
    "UNLABELLED_MAX",
    "VARYING",
    "VELOCITY_NOISE",
    "VELOCITY_SET",
    "WEAR_SET",
    "Case",
    "S",
    "Sine",
    "W",
    "axial_load",
    "check_design",
    "contributions",
    "design_record",
    "independent",
    "independent_truth_bearing",
    "load_labels",
    "main",
    "measured",
    "opensees",
    "opensees_available",
    "package",
    "rest_before",
    "write_panel",
]
