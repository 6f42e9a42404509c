"""The run of a suite's runs through Dask into its folder: :func:`compute_runs` (each batch of
one ground motion a task, :mod:`structures.suites.tasks`) and :func:`finish`, which writes the
table of the invocation, its failures and its summary.
"""

from __future__ import annotations

import json
import sys
import time
import uuid
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from dcfpb.common.validation import check_choice, check_int, check_real
from structures.config import BuildingConfig
from structures.suites.runs import RunSpec, execute_run, failure_kind
from structures.suites.store import RunStore, atomic_write
from structures.suites.summary import summarize, write_summary
from structures.suites.tasks import (
    BATCH_SIZE,
    DESIGN_MARK,
    batches,
    client_for,
    compute_and_store,
    run_batch,
)

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["SuiteResult", "check_run_options", "compute_runs", "finish"]


@dataclass
class SuiteResult:
    """What a suite produced: the ``peaks`` table, one row per run in suite order
    (:data:`structures.suites.runs.COLUMNS`), its ``summary``
    (:func:`structures.suites.summary.summarize`), the ``failures`` (``{"run": run id,
    "reason": ...}``), the ``wall_time`` of this invocation [s], the ``out_dir``, the runs
    ``computed`` now and ``skipped`` (complete from before), and the ``runs`` in suite order."""

    peaks: pd.DataFrame
    failures: list[dict[str, str]]
    wall_time: float
    out_dir: Path
    computed: int
    skipped: int
    summary: pd.DataFrame
    runs: list[RunSpec]


def check_run_options(write: str, run_timeout: float | None, max_steps: int,
                      owner: str) -> None:
    """The checks of the options of ``run_suite`` (``owner`` in the messages)."""
    check_choice(write, "write", owner, ("workers", "client"))
    if run_timeout is not None:
        check_real(run_timeout, "run_timeout", owner, low=0.0, low_open=True)
    check_int(max_steps, "max_steps", owner, low=1)


def compute_runs(specs: Sequence[RunSpec], motions: Mapping[Any, Any],
                 unreadable: Mapping[Any, str], config: BuildingConfig, store: RunStore, *,
                 n_workers: int | None, scheduler_address: str | None, write: str,
                 progress: bool, run_timeout: float | None, max_steps: int,
                 ship: bool, storage: str = "full", design: bool = False,
                 keep_failed: Sequence[str] = (), label: str = "suite",
                 ) -> tuple[dict[str, dict[str, Any]], int, int]:
    """Compute the runs not complete in ``store`` and store each as it finishes; return the row
    of every run by run id, and the numbers of runs computed now and complete from before.

    ``motions`` are those read here, by ``spec.motion`` (sent to the workers when ``ship``,
    else each task reads its own); ``unreadable`` the reason of each motion that could not be
    read (its runs fail with it); ``storage`` and ``design`` as
    :func:`~structures.suites.runs.execute_run` takes them (a stored run that keeps less, or
    lacks the design peaks asked, is computed again); a run whose last failure is of a kind
    in ``keep_failed`` (:data:`~structures.suites.runs.FAILURE_KINDS`, e.g. ``"capacity"``, a
    deterministic outcome of the model) keeps it instead of running again; ``label`` names the
    progress bar; the other keywords are those of ``run_suite``.
    """
    from distributed import as_completed
    from tqdm import tqdm

    rows: dict[str, dict[str, Any]] = {}
    pending = []
    mark = DESIGN_MARK if design else ()
    for spec in specs:
        row = store.completed_row(spec.run_id, storage, mark)
        failed = store.failed_row(spec.run_id) if row is None and keep_failed else None
        if row is not None:
            rows[spec.run_id] = row
        elif failed is not None and failure_kind(failed) in keep_failed and all(
                key in failed for key in mark):
            rows[spec.run_id] = failed
        elif spec.motion in unreadable:
            rows[spec.run_id] = store.save_failure(spec.failure(unreadable[spec.motion]))
        else:
            pending.append(spec)
    skipped = sum(row["status"] == "done" for row in rows.values())
    store.log_recovered(run_id for run_id, row in rows.items() if row["status"] == "done")
    counts = {"done": skipped, "failed": len(rows) - skipped}
    bar = tqdm(total=len(specs), initial=len(rows), unit="run", disable=not progress,
               file=sys.stderr, desc=label, postfix=counts)
    try:
        if pending:
            with client_for(n_workers, scheduler_address) as client:
                needed = list(dict.fromkeys(s.motion for s in pending)) if ship else []
                shared = (dict(zip(needed, client.scatter([motions[f] for f in needed],
                                                           hash=False), strict=True))
                          if needed else {})
                token = uuid.uuid4().hex[:8]
                task, extra = ((compute_and_store,
                                (str(store.root.resolve()), run_timeout, max_steps, storage,
                                 design))
                               if write == "workers" else (execute_run,
                                                           (run_timeout, max_steps, storage,
                                                            design)))
                futures = {client.submit(run_batch, task, batch,
                                         shared.get(batch[0].motion), config,
                                         *extra, pure=False,
                                         key=f"dcfpb-{token}-{batch[0].run_id}",
                                         priority=sum(spec.cost(motions.get(spec.motion),
                                                                config) for spec in batch)
                                         ): batch
                           for batch in batches(pending, BATCH_SIZE)}
                for future in as_completed(futures):
                    batch = futures.pop(future)
                    try:
                        outcomes = future.result()
                    except Exception as error:  # e.g. KilledWorker: a worker kept dying
                        reason = f"{type(error).__name__}: {error}"  # runs it saved are kept
                        outcomes = [store.completed_row(spec.run_id, storage, mark)
                                    or store.save_failure(spec.failure(reason))
                                    for spec in batch]
                    future.release()
                    for spec, outcome in zip(batch, outcomes, strict=True):
                        if isinstance(outcome, tuple):  # write="client": results came here
                            row, data = outcome
                            outcome = (store.save_failure(row) if data is None
                                       else store.save_done(row, data))
                        row = rows[spec.run_id] = outcome
                        counts[row["status"]] += 1
                    bar.set_postfix(counts, refresh=False)
                    bar.update(len(batch))
                bar.close()  # before the cluster shuts down (a second or two)
    finally:
        bar.close()
    return rows, len(pending), skipped


def finish(specs: Sequence[RunSpec], rows: dict[str, dict[str, Any]], store: RunStore,
           computed: int, skipped: int, start: float, columns: Sequence[str],
           extra_columns: Sequence[str] = ()) -> SuiteResult:
    """Write ``peaks.csv`` (``columns``), ``failures.json`` and the summary and return the
    result, its ``peaks`` with ``extra_columns`` after ``columns``; ``start`` is the
    invocation's ``time.perf_counter()`` [s]."""
    import pandas as pd

    wall = time.perf_counter() - start
    full = pd.DataFrame([rows[s.run_id] for s in specs], columns=[*columns, *extra_columns])
    table = full[list(columns)]
    failures = [{"run": r["run_id"], "reason": r["reason"]}
                for r in table.to_dict("records") if r["status"] != "done"]
    atomic_write(store.root / "peaks.csv", table.to_csv(index=False).encode())
    atomic_write(store.root / "failures.json", json.dumps(failures, indent=1).encode())
    summary = summarize(table)
    write_summary(summary, store.root)
    return SuiteResult(full, failures, wall, store.root, computed, skipped, summary,
                       list(specs))
