"""The Dask side of a suite (:func:`structures.suites.suite.run_suite`): the cluster, and the
tasks, each a batch of runs of one record or pair computed and stored one by one; a batch redone
after its worker was lost keeps the runs it stored already (:func:`compute_and_store`).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from dcfpb.common.validation import check_int
from isolator.limits import DEFAULT_MAX_STEPS
from structures.config import BuildingConfig
from structures.suites.runs import RunSpec, execute_run
from structures.suites.store import RunStore


def local_cluster(n_workers: int | None = None) -> Any:
    """A ``distributed.LocalCluster`` of ``n_workers`` single-thread processes (default: the
    number of CPUs) on the loopback interface, without a dashboard (the scheduler's HTTP server
    gets a free port instead of 8787, so suites side by side do not compete for it)."""
    from distributed import LocalCluster

    workers = (os.cpu_count() or 1) if n_workers is None else n_workers
    workers = check_int(workers, "n_workers", "local_cluster", low=1)
    return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                        host="127.0.0.1", dashboard_address=None,
                        scheduler_kwargs={"dashboard_address": "127.0.0.1:0"})


@contextmanager
def client_for(n_workers: int | None, scheduler_address: str | None) -> Iterator[Any]:
    """A Dask client of ``scheduler_address``, or of a new :func:`local_cluster` of
    ``n_workers``, closed with its cluster on leaving."""
    from distributed import Client

    if scheduler_address:
        with Client(scheduler_address) as client:
            yield client
        return
    with local_cluster(n_workers) as cluster, Client(cluster) as client:
        yield client


BATCH_SIZE = 6
"""Runs of one ground motion handed to a worker as one task (see :func:`run_batch`)."""


def compute_and_store(spec: RunSpec, motion: Any, config: BuildingConfig,
                       out_dir: str, time_limit: float | None = None,
                       max_steps: int = DEFAULT_MAX_STEPS) -> dict[str, Any]:
    """The task of ``write="workers"``: compute a run and write its files where it ran, unless
    it is complete in the folder already (a batch redone after a lost worker)."""
    store = RunStore(out_dir)
    row = store.completed_row(spec.run_id)
    if row is not None:
        return row
    row, data = execute_run(spec, motion, config, time_limit, max_steps)
    return store.save_failure(row) if data is None else store.save_done(row, data)


def run_batch(task: Any, specs: list[RunSpec], motion: Any, config: BuildingConfig,
              *extra: Any) -> list[Any]:
    """One Dask task: ``task`` (:func:`compute_and_store`, or
    :func:`~structures.suites.runs.execute_run` when the client writes) of each run of one
    ground motion in turn, the motion read once for all (one that cannot be read is left to
    each run, which fails with the reader's reason)."""
    if motion is None:
        try:
            motion = specs[0].motion.read()
        except Exception:
            motion = None
    return [task(spec, motion, config, *extra) for spec in specs]


def batches(pending: list[RunSpec], size: int) -> list[list[RunSpec]]:
    """The pending runs grouped by ``spec.motion``, in chunks of at most ``size`` runs."""
    groups: dict[Any, list[RunSpec]] = {}
    for spec in pending:
        groups.setdefault(spec.motion, []).append(spec)
    return [group[i:i + size] for group in groups.values() for i in range(0, len(group), size)]
