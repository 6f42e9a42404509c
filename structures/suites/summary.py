"""Statistics of a suite's peaks per group of runs (friction model, property modifier, scale
multiplier): mean, median and 84th percentile (linear between order statistics, numpy's default)
over the runs that finished, beside the counts of runs and failures by kind. A failed run is
never dropped silently: the runs past the bearings' capacity are the strongest, so a group with
failures understates its responses; a group whose runs all failed has NaN statistics.
"""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from structures.suites.runs import FAILURE_KINDS, failure_kind
from structures.suites.store import atomic_write

if TYPE_CHECKING:
    import pandas as pd

QUANTITIES = {
    "peak_isolator_displacement": "m",
    "peak_centre_displacement": "m",
    "peak_base_shear": "N",
    "peak_roof_acceleration": "m/s^2",
    "peak_roof_acceleration_x": "m/s^2",
    "peak_roof_acceleration_y": "m/s^2",
    "peak_storey_drift": "m",
    "peak_storey_drift_x": "m",
    "peak_storey_drift_y": "m",
    "peak_base_rotation": "rad",
    "max_temperature": "degC",
}
"""Peak responses summarised, with their units, when among a peaks table's columns: those of
:func:`structures.analysis.peaks`, in one direction or in plan."""

GROUP_KEYS = ("model", "modifier", "multiplier")
COUNT_COLUMNS = ("n_runs", "n_failed", *(f"n_{kind}" for kind in FAILURE_KINDS))
"""Counts beside the statistics: runs of the group, failed runs, and those by kind."""
SUMMARY_COLUMNS = (*GROUP_KEYS, "quantity", "units", "n", "mean", "median", "p84",
                   *COUNT_COLUMNS)
STATISTICS_OVER = "successful runs"
"""What the statistics are over (the label the reports print)."""


def summarize(peaks: pd.DataFrame) -> pd.DataFrame:
    """Mean, median and 84th percentile of a peaks table's (``SuiteResult.peaks``) responses
    per group of runs: a tidy table, one row per group and quantity, columns ``model``,
    ``modifier``, ``multiplier``, ``quantity``, ``units``, ``n`` (the finished runs), ``mean``,
    ``median``, ``p84`` [SI] (NaN when none finished), then :data:`COUNT_COLUMNS`."""
    import pandas as pd

    quantities = {q: units for q, units in QUANTITIES.items() if q in peaks.columns}
    rows = []
    for key, group in peaks.groupby(list(GROUP_KEYS), sort=False):
        done = group[group["status"] == "done"]
        kinds = [failure_kind(row) for row in group.to_dict("records")]
        counts = {"n_runs": len(group), "n_failed": len(group) - len(done)} | {
            f"n_{kind}": kinds.count(kind) for kind in FAILURE_KINDS}
        for quantity, units in quantities.items():
            values = np.asarray(done[quantity], dtype=float)
            statistics = dict.fromkeys(("mean", "median", "p84"), float("nan"))
            if values.size:
                statistics = {"mean": float(np.mean(values)),
                              "median": float(np.median(values)),
                              "p84": float(np.percentile(values, 84.0))}
            rows.append(dict(zip(GROUP_KEYS, key, strict=True)) | {
                "quantity": quantity, "units": units, "n": int(values.size)} | statistics
                | counts)
    return pd.DataFrame(rows, columns=list(SUMMARY_COLUMNS))


def group_labels(table: pd.DataFrame, separator: str = ", ") -> list[str]:
    """A label per row of ``table``: the model, then the modifier and multiplier if they vary,
    e.g. ``"precise"`` or ``"precise, modifier 1.2, scale x2"``."""
    show_modifier = table["modifier"].nunique() > 1
    show_scale = table["multiplier"].nunique() > 1
    labels = []
    for model, modifier, multiplier in zip(table["model"], table["modifier"],
                                           table["multiplier"], strict=True):
        parts = [str(model)]
        if show_modifier:
            parts.append(f"modifier {modifier:.4g}")
        if show_scale:
            parts.append(f"scale x{multiplier:.4g}")
        labels.append(separator.join(parts))
    return labels


def summary_dict(summary: pd.DataFrame) -> dict[str, Any]:
    """The summary as JSON-ready ``{group label: {quantity: {n, mean, median, p84, units, over,
    n_runs, n_failed, n_capacity, ...}}}`` (:func:`group_labels`, :data:`STATISTICS_OVER`; None
    for a statistic without a finished run)."""
    out: dict[str, Any] = {}
    for label, row in zip(group_labels(summary), summary.to_dict("records"), strict=True):
        out.setdefault(label, {})[row["quantity"]] = {
            "n": int(row["n"]),
            **{k: None if not np.isfinite(row[k]) else float(row[k])
               for k in ("mean", "median", "p84")},
            "units": row["units"], "over": STATISTICS_OVER,
            **{k: int(row[k]) for k in COUNT_COLUMNS}}
    return out


def failure_counts(peaks: pd.DataFrame) -> dict[str, int]:
    """Failed runs of a peaks table by kind (:data:`FAILURE_KINDS`), and ``"failed"`` in all."""
    kinds = [failure_kind(row) for row in peaks.to_dict("records")]
    return {"failed": sum(map(bool, kinds))} | {kind: kinds.count(kind)
                                                 for kind in FAILURE_KINDS}


def write_summary(summary: pd.DataFrame, out_dir: str | Path) -> list[Path]:
    """Write ``summary.csv`` and, with pyarrow (the ``suite`` extra; else a ``UserWarning``),
    ``summary.parquet`` to ``out_dir``, atomically; return the paths written."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = [out / "summary.csv"]
    atomic_write(written[0], summary.to_csv(index=False).encode())
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        warnings.warn("pyarrow is not installed: summary.parquet not written (install the "
                      "'suite' extra: pip install 'dcfpb[suite]').", UserWarning, stacklevel=2)
        return written
    written.append(out / "summary.parquet")
    atomic_write(written[1], summary.to_parquet(index=False, engine="pyarrow"))
    return written
