"""The sim-to-real gap of a bearing model: where it lies, which effect explains it, how far
it shrinks.

:func:`diagnose` takes measured tests (:mod:`.data`) and a baseline (:mod:`.baseline`); its
steps are in :mod:`.pipeline`, the method for users in ``docs/diagnosis.md``.
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
