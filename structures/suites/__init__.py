"""Ground-motion suites through Dask, one result file per run (:mod:`~structures.suites.suite`),
and the statistics of their peaks (:mod:`~structures.suites.summary`)."""

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
