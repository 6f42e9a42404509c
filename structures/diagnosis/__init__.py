"""The diagnosis at building level: a building run's bearing histories as the diagnosis reads
them (:mod:`~structures.diagnosis.adapter`) and the truth models of its validation panels
(:mod:`~structures.diagnosis.truths`)."""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "bearing_records": "structures.diagnosis.adapter",
    "bearing_campaign": "structures.diagnosis.adapter",
}
__all__ = [
    "bearing_campaign",
    "bearing_records",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
