"""The sim-to-real gap of a bearing model: where it lies, which effect explains it, how far
it shrinks (:func:`diagnose` on measured tests, :mod:`.data`; the steps: :mod:`.pipeline`).
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
