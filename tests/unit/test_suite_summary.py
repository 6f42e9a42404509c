"""Suite statistics never drop a failed run silently (structures.suites.summary): each group
counts its runs and its failures by kind beside the statistics over its successful runs."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from structures.suites.runs import failure_kind
from structures.suites.summary import COUNT_COLUMNS, failure_counts, summarize, summary_dict


def _table() -> pd.DataFrame:
    """Four runs at 1 x (one timed out), three at 20 x (all past the capacity: the median of
    the successful ones alone would come out below the 1 x median)."""
    return pd.DataFrame({
        "model": "precise", "modifier": 1.0,
        "multiplier": [1.0] * 4 + [20.0] * 3,
        "status": ["done", "done", "done", "failed", "failed", "failed", "failed"],
        "failure": ["", "", "", "timeout", "capacity", "capacity", "capacity"],
        "reason": None,
        "peak_isolator_displacement": [0.1, 0.2, 0.3, 0.05, 0.61, 0.60, 0.62],
        "peak_base_shear": 1.0, "peak_roof_acceleration": 2.0, "peak_storey_drift": 3.0,
    })


def test_counts_beside_statistics_over_the_successful_runs():
    summary = summarize(_table()).set_index(["multiplier", "quantity"])
    one = summary.loc[(1.0, "peak_isolator_displacement")]
    assert (one["n"], one["n_runs"], one["n_failed"], one["n_timeout"]) == (3, 4, 1, 1)
    assert one["median"] == pytest.approx(0.2) and one["n_capacity"] == 0
    twenty = summary.loc[(20.0, "peak_isolator_displacement")]
    assert (twenty["n"], twenty["n_runs"], twenty["n_failed"], twenty["n_capacity"]) == (
        0, 3, 3, 3)
    assert math.isnan(twenty["median"])  # no statistics from no finished run, but the group
    assert list(summary.columns[-len(COUNT_COLUMNS):]) == list(COUNT_COLUMNS)


def test_summary_dict_and_failure_counts():
    out = summary_dict(summarize(_table()))
    twenty = out["precise, scale x20"]["peak_base_shear"]
    assert twenty["median"] is None and twenty["n_capacity"] == 3 and twenty["n"] == 0
    assert out["precise, scale x1"]["peak_base_shear"]["over"] == "successful runs"
    assert failure_counts(_table()) == {"failed": 4, "capacity": 3, "convergence": 0,
                                        "timeout": 1, "error": 0}


@pytest.mark.parametrize(("row", "kind"), [
    ({"status": "done"}, ""),
    ({"status": "failed", "failure": "model"}, "error"),
    ({"status": "failed", "failure": np.nan, "reason": "run stopped early: Capacity exceeded:"
      " the isolator displacement reached 0.61 m"}, "capacity"),
    ({"status": "failed", "reason": "run stopped early: The isolator displacement reached "
      "5.2 m at t = 1.2 s, beyond the bearing's displacement_capacity 0.6 m"}, "capacity"),
    ({"status": "failed", "reason": "timeout after 3 s: ..."}, "timeout"),
    ({"status": "failed", "reason": "run stopped early: Step 7: Newton iteration did not "
      "converge"}, "convergence"),
    ({"status": "failed", "reason": "KilledWorker: ..."}, "error"),
])
def test_failure_kind_of_new_and_older_rows(row, kind):
    """Rows stored before the ``failure`` column are classified from their reason."""
    assert failure_kind(row) == kind
