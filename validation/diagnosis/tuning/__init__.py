"""The tuning panel: 42 cases from three truth sources, labels kept apart.

Each *scenario* (a set of true effects) is made twice, once for each half: the **tune** half
is the only one the thresholds are chosen on (:mod:`validation.diagnosis.tune`), the **test**
half is the one the scores are reported on (:mod:`validation.diagnosis.score`). The two cases
of a pair differ in their truth source and in nuisance: amplitude (0.05-0.4 m), sampling
(100-500 Hz), white or coloured noise (0.3-1.5 % of the nominal friction force), a channel lag
of up to 1.5 samples, the pre-sliding transition (rigid-plastic, elastic-plastic 0.1-2 mm,
smooth Bouc-Wen), campaigns of one to four files, a velocity and an axial-force column or not.

The panel is written by three modules, whose public names are all importable from here:
:mod:`~validation.diagnosis.tuning.sources` (the records and the three truth sources),
:mod:`~validation.diagnosis.tuning.cases` (the 42 cases) and
:mod:`~validation.diagnosis.tuning.write` (the measurement noise, the label rule, the files and
:func:`write_panel`). Its own numpy-only truth model is
:mod:`~validation.diagnosis.tuning.truths`; the outside panel
(:mod:`validation.diagnosis.outside`) has another, written apart.

Truth sources:

- ``independent``: :mod:`validation.diagnosis.tuning.truths` (numpy only, written from
  the paper and physics; shares no code with the package);
- ``opensees``: OpenSees singleFPBearing (Coulomb, VelDependent) and FPBearingPTV through
  :func:`structures.opensees.bearing.run_opensees_test`;
- ``package``: our own element (:func:`structures.diagnosis.truths.element_truth`).

Label rule: an effect is labelled when its own contribution to the clean force (the truth
with it less the truth without it) has an RMS of at least 3 % of the RMS force; physics left
unlabelled contributes at most 1 % (both are computed and stored with the labels, in
``design``). A channel lag of up to 1.5 samples and the transition's shape are nuisance,
never labelled.

Written to ``folder/case_NN/``: ``test_01.csv`` ... (time, displacement, force, and velocity,
axial_force where the case has them), ``manifest.csv`` (the files in run order with the
axial load where there is no column, the initial temperature and the rest before each test)
and ``bearing.json`` (what a user would type: effective radius, slider diameter, baseline,
``without``, axial load). ``folder/labels.json`` holds the labels; ``folder/panel.json`` the
seed. Case numbers are shuffled so that neither the number nor the files tell the truth.

    python -m validation.diagnosis.tuning FOLDER [--seed 2026] [--half tune|test]
"""

from __future__ import annotations

from validation.diagnosis.tuning.cases import (
    BIG,
    CASES,
    DAMPER,
    EXP_VELOCITY,
    HEAT_SET,
    ONE,
    PAIR,
    PRESSURE_SET,
    SINE_SET,
    VARYING,
    VARYING_STRONG,
    VELOCITY_SET,
    WEAR_SET,
)
from validation.diagnosis.tuning.sources import (
    AREA,
    LABEL_MIN,
    MU0,
    RADIUS,
    SLIDER,
    SOURCES,
    UNLABELLED_MAX,
    Case,
    Test,
    W,
    independent,
    opensees,
    package,
)
from validation.diagnosis.tuning.write import (
    contributions,
    main,
    measured,
    opensees_available,
    write_panel,
)

__all__ = [
    "AREA",
    "BIG",
    "CASES",
    "DAMPER",
    "EXP_VELOCITY",
    "HEAT_SET",
    "LABEL_MIN",
    "MU0",
    "ONE",
    "PAIR",
    "PRESSURE_SET",
    "RADIUS",
    "SINE_SET",
    "SLIDER",
    "SOURCES",
    "UNLABELLED_MAX",
    "VARYING",
    "VARYING_STRONG",
    "VELOCITY_SET",
    "WEAR_SET",
    "Case",
    "Test",
    "W",
    "contributions",
    "independent",
    "main",
    "measured",
    "opensees",
    "opensees_available",
    "package",
    "write_panel",
]
