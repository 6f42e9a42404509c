"""The sim-to-real gap of a bearing model: where it lies, which effect explains it, how far
it shrinks.

:func:`diagnose` takes measured tests (:mod:`.data`, in one direction or in two; tests in two
directions diagnosed by :mod:`.two_directions`) and a baseline (:mod:`.baseline`); its steps are in
:mod:`.pipeline`, the method for users in ``docs/diagnosis.md``. :func:`load_campaign` here
reads tests in one direction or in two, told apart by their headers.
"""

from isolator.diagnosis.baseline import BASELINE_MODELS, REMOVABLE_EFFECTS, BaselineSpec
from isolator.diagnosis.data import (
    BearingRecord,
    BearingRecord2D,
    Campaign,
    Campaign2D,
    DataError,
    read_record,
)
from isolator.diagnosis.data import load_any_campaign as load_campaign
from isolator.diagnosis.effects import EFFECT_NAMES, LIBRARY
from isolator.diagnosis.pipeline import Diagnosis, diagnose, reselect

__all__ = [
    "BASELINE_MODELS",
    "EFFECT_NAMES",
    "LIBRARY",
    "REMOVABLE_EFFECTS",
    "BaselineSpec",
    "BearingRecord",
    "BearingRecord2D",
    "Campaign",
    "Campaign2D",
    "DataError",
    "Diagnosis",
    "diagnose",
    "load_campaign",
    "read_record",
    "reselect",
]
