"""Ground-motion suites: records x scale factors x friction models through Dask, one result
file per run (:mod:`~structures.suites.suite`, :mod:`~structures.suites.runs`,
:mod:`~structures.suites.store`), the same for a building in plan under pairs of records
(:mod:`~structures.suites.pairs.suite`, :mod:`~structures.suites.pairs.runs`) and the
statistics of their peaks (:mod:`~structures.suites.summary`)."""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "Suite": "structures.suites.suite",
    "run_suite": "structures.suites.suite",
    "record_files": "structures.suites.suite",
    "summarize": "structures.suites.summary",
    "PairSuite": "structures.suites.pairs.suite",
    "pair_sources": "structures.suites.pairs.suite",
    "run_pair_suite": "structures.suites.pairs.suite",
}
__all__ = [
    "PairSuite",
    "Suite",
    "pair_sources",
    "record_files",
    "run_pair_suite",
    "run_suite",
    "summarize",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
