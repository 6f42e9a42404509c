"""The sim-to-real gap of a bearing model: where it lies, which effect explains it, how far
it shrinks.

Given measured bearing histories (displacement, force, axial force; :mod:`.data`) and a
baseline friction model (:mod:`.baseline`), :func:`diagnose` calibrates the baseline, locates
its held-out residual (:mod:`.where`), tries a library of candidate effects (:mod:`.effects`)
fitted on part of the data and judged on held-out data (:mod:`.fitting`, :mod:`.selection`),
and reports the verdict with the gap before and after (:mod:`.summary`, :mod:`.report`).
"""

from isolator.diagnosis.baseline import BASELINE_MODELS, REMOVABLE_EFFECTS, BaselineSpec
from isolator.diagnosis.data import (
    BearingRecord,
    Campaign,
    DataError,
    load_campaign,
    read_record,
)
from isolator.diagnosis.effects import EFFECT_NAMES, LIBRARY
from isolator.diagnosis.pipeline import Diagnosis, diagnose, reselect

__all__ = [
    "BASELINE_MODELS",
    "EFFECT_NAMES",
    "LIBRARY",
    "REMOVABLE_EFFECTS",
    "BaselineSpec",
    "BearingRecord",
    "Campaign",
    "DataError",
    "Diagnosis",
    "diagnose",
    "load_campaign",
    "read_record",
    "reselect",
]
