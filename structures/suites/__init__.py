"""Ground-motion suites: records or pairs of records x scale factors x friction models x property
modifiers through Dask, one result file per run (:mod:`~structures.suites.suite`; the motions
:mod:`~structures.suites.sources`, the runs :mod:`~structures.suites.runs`, their files
:mod:`~structures.suites.store`) and the statistics of their peaks
(:mod:`~structures.suites.summary`)."""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "Suite": "structures.suites.suite",
    "run_suite": "structures.suites.suite",
    "MotionSource": "structures.suites.sources",
    "motion_sources": "structures.suites.sources",
    "RunSpec": "structures.suites.runs",
    "execute_run": "structures.suites.runs",
    "summarize": "structures.suites.summary",
}
__all__ = [
    "MotionSource",
    "RunSpec",
    "Suite",
    "execute_run",
    "motion_sources",
    "run_suite",
    "summarize",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
