"""Ground-motion suites: records x scale factors x friction models x property modifiers.

A `Suite` is a set of independent runs (:class:`structures.suites.runs.RunSpec`), each with a
stable id. :func:`run_suite` computes them with ``dask.distributed``: on a `LocalCluster` of
this machine by default (worker processes with one thread each, loopback only, no
dashboard), or on any running cluster given its scheduler address, with no other change.

Each run's files are written atomically (:mod:`structures.suites.store`) by the worker that
computed it, or, with ``write="client"``, by this process, so that a remote cluster needs no file
system shared with it. A rerun of the same suite into the same folder skips the runs that are
complete and computes the rest: killing a suite loses at most the runs in flight. A run that fails
(unreadable record, a run stopping early, any exception, a worker that keeps dying) is recorded
with its reason and the others carry on; failures are retried on the next run. A worker lost in the
middle of a batch (:mod:`structures.suites.tasks`) has its batch redone elsewhere by Dask, keeping
the runs of it already stored.

One suite at a time per folder: a second suite into a folder in use refuses at once, or waits
(:mod:`structures.suites.lock`). ``run_timeout`` bounds each run's wall-clock time, checked
inside the run on whichever worker it runs (``structures.analysis.run(time_limit=)``).

Example::

    suite = Suite(load_config("examples/five_storey.toml"), record_files("records/"),
                  models=("precise", "constant"), scales=(1.0, 2.0))
    result = run_suite(suite, "out", n_workers=2)   # or scheduler_address="tcp://host:8786"
    result.peaks.groupby("model")["peak_isolator_displacement"].median()
"""

from __future__ import annotations

import csv
import time
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from contextlib import nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from dcfpb.common.validation import check_choice, check_real
from groundmotions.records import GroundMotion
from isolator.experiments import MODELS
from isolator.limits import DEFAULT_MAX_STEPS
from structures.config import BuildingConfig
from structures.suites.dispatch import SuiteResult, check_run_options, compute_runs, finish
from structures.suites.lock import SuiteLock
from structures.suites.runs import (
    COLUMNS,
    RunSpec,
    config_fingerprint,
    file_digest,
    modified_bearing,
)
from structures.suites.store import RunStore
from structures.suites.tasks import local_cluster

__all__ = ["Suite", "SuiteResult", "check_suite_axes", "local_cluster", "record_files",
           "run_suite"]

RecordFactors = Mapping[str, float] | Callable[[Sequence[GroundMotion]], Any]
_MANIFEST_HEADERS = {"file", "filename", "file_name", "record", "path"}


def record_files(source: str | Path) -> tuple[Path, ...]:
    """The record files of a folder (``*.AT2``, any case) or of a manifest CSV.

    A manifest's first column holds file names relative to its folder; a first row whose first
    cell is ``file`` (``filename``, ``record``, ``path``) is a header. Missing files are kept:
    their runs fail with the reason.
    """
    path = Path(source)
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if p.is_file() and p.suffix.lower() == ".at2")
    elif path.is_file():
        with open(path, newline="", encoding="utf-8") as handle:
            rows = [row for row in csv.reader(handle) if row and row[0].strip()]
        if rows and rows[0][0].strip().lower() in _MANIFEST_HEADERS:
            rows = rows[1:]
        files = [path.parent / row[0].strip() for row in rows
                 if not row[0].lstrip().startswith("#")]
    else:
        raise ValueError(f"{source}: no such folder of records or manifest file.")
    if not files:
        raise ValueError(f"{source}: no record files (*.AT2 in a folder, or rows of a manifest).")
    return tuple(files)


def check_suite_axes(suite: Any, owner: str) -> None:
    """Check and normalise (to tuples) the ``models``, ``scales``, ``property_modifiers``,
    ``duration`` and ``dt`` of a frozen suite (a :class:`Suite` or
    :class:`~structures.suites.pairs.suite.PairSuite`, named ``owner`` in the messages)."""
    models = tuple(check_choice(m, "models", owner, MODELS) for m in suite.models)
    scales = tuple(check_real(s, "scales", owner, low=0.0, low_open=True)
                   for s in suite.scales)
    modifiers = tuple(check_real(m, "property_modifiers", owner, low=0.0, low_open=True)
                      for m in suite.property_modifiers)
    if not (models and scales and modifiers):
        raise ValueError(f"{owner}: 'models', 'scales' and 'property_modifiers' must each "
                         "hold at least one value.")
    for model in models:  # a modified coefficient outside (0, 1] fails here, not later
        for modifier in modifiers:
            modified_bearing(suite.config, model, modifier)
    for name in ("duration", "dt"):
        if getattr(suite, name) is not None:
            check_real(getattr(suite, name), name, owner, low=0.0, low_open=True)
    object.__setattr__(suite, "models", models)
    object.__setattr__(suite, "scales", scales)
    object.__setattr__(suite, "property_modifiers", modifiers)


def _lookup(factors: Mapping[str, float], path: Path, name: str) -> float | None:
    for key in (str(path), path.name, path.stem, name):
        if key in factors:
            return factors[key]
    return None


@dataclass(frozen=True)
class Suite:
    """Records x scale multipliers x friction models x property modifiers on one building.

    Parameters
    ----------
    config : BuildingConfig
        The building file (:func:`structures.config.load_config`).
    records : sequence of str or Path
        Record files (:func:`record_files`).
    models : sequence of str
        Friction models among ``"precise"``, ``"simplified"``, ``"constant"``.
    scales : sequence of float
        Suite-wide multipliers of the per-record factors [-] (plain scale factors when no
        ``record_factors`` are given).
    property_modifiers : sequence of float
        Factors on the reference friction coefficient [-], e.g. ``(lambda_min, 1.0,
        lambda_max)`` (:func:`structures.suites.runs.modified_bearing`).
    record_factors : mapping or callable, optional
        Per-record scale factors [-]: a mapping keyed by path, file name or stem, or a hook
        called with the readable records (in order) that returns their factors as a
        sequence or as a mapping keyed by record name, e.g. an adapter of
        ``groundmotions.scaling.scale_suite``. Default 1.
    duration : float, optional
        Keep only the first ``duration`` seconds of each record [s].
    dt : float, optional
        Analysis step [s]; default the building file's. A record with a finer step is run at
        its own step (the ``dt`` column says which).
    """

    config: BuildingConfig
    records: Sequence[str | Path]
    models: Sequence[str] = MODELS
    scales: Sequence[float] = (1.0,)
    property_modifiers: Sequence[float] = (1.0,)
    record_factors: RecordFactors | None = field(default=None, repr=False)
    duration: float | None = None
    dt: float | None = None

    def __post_init__(self) -> None:
        owner = "Suite"
        records = tuple(Path(r).absolute() for r in self.records)  # workers may be elsewhere
        if not records:
            raise ValueError(f"The 'records' parameter of {owner} must name at least one "
                             "record file. Got none.")
        object.__setattr__(self, "records", records)
        check_suite_axes(self, owner)

    def read(self) -> tuple[dict[str, GroundMotion], dict[str, str]]:
        """Read the records: ``({file: motion}, {file: reason it cannot be read})``."""
        from groundmotions.readers import read_record

        motions, unreadable = {}, {}
        for path in self.records:
            try:
                motions[str(path)] = read_record(path)
            except Exception as error:  # reported per run; the others go on
                unreadable[str(path)] = f"{type(error).__name__}: {error}"
        return motions, unreadable

    def _factors(self, motions: dict[str, GroundMotion], read: bool) -> dict[str, float]:
        given = self.record_factors
        if given is None:
            return {}
        readable = [p for p in self.records if str(p) in motions or not read]
        if callable(given):
            answer = given([motions[str(p)] for p in readable])
            if not isinstance(answer, Mapping):
                values = list(answer)
                if len(values) != len(readable):
                    raise ValueError(f"The record-factor hook returned {len(values)} factors "
                                     f"for {len(readable)} records.")
                answer = {str(p): v for p, v in zip(readable, values, strict=True)}
            given = answer
        factors = {str(p): _lookup(given, p, motions[str(p)].name if read else p.stem)
                   for p in readable}
        missing = [Path(p).name for p, v in factors.items() if v is None]
        if missing:
            raise ValueError(f"No scale factor given for the record(s) {missing}.")
        return {p: check_real(v, "record_factors", "Suite", low=0.0, low_open=True)
                for p, v in factors.items()}

    def plan(self, *, read: bool = True
             ) -> tuple[list[RunSpec], dict[str, GroundMotion], dict[str, str]]:
        """The runs, in table order (record, multiplier, model, modifier), the readable
        records and the reasons of the unreadable ones.

        With ``read=False`` the records are read only if a record-factor hook needs them;
        otherwise both dicts are empty and each run reads its record where it runs.
        """
        read = read or callable(self.record_factors)
        motions, unreadable = self.read() if read else ({}, {})
        factors = self._factors(motions, read)
        settings = config_fingerprint(self.config)
        specs = [
            RunSpec(str(path), file_digest(path), model, factors.get(str(path), 1.0),
                    multiplier, modifier, self.duration, self.dt, settings)
            for path in self.records for multiplier in self.scales
            for model in self.models for modifier in self.property_modifiers
        ]
        twice = sorted(i for i, n in Counter(s.run_id for s in specs).items() if n > 1)
        if twice:
            raise ValueError(f"The suite holds the same run more than once (a record, scale or "
                             f"modifier given twice): {twice[:3]}.")
        return specs, motions, unreadable


def run_suite(suite: Suite, out_dir: str | Path, *, n_workers: int | None = None,
              scheduler_address: str | None = None, write: str = "workers",
              progress: bool = True, run_timeout: float | None = None, lock: bool = True,
              wait_lock: float = 0.0, max_steps: int = DEFAULT_MAX_STEPS) -> SuiteResult:
    """Compute a suite, or finish one that was interrupted.

    Parameters
    ----------
    suite : Suite
        The runs.
    out_dir : str or Path
        Result folder (:mod:`structures.suites.store` for its layout); complete runs already
        in it are kept, not computed again.
    n_workers : int, optional
        Worker processes of the local cluster (default: the number of CPUs).
    scheduler_address : str, optional
        Address of a running scheduler, e.g. ``"tcp://10.0.0.5:8786"``; its workers must be
        able to import this package. ``n_workers`` is then ignored.
    write : {"workers", "client"}
        Who writes a run's files: the worker that computed it (default; the folder must be
        reachable under the same path by the workers, as on this machine or a cluster with a
        shared file system), or this process, to which every result then travels (any
        cluster, but the writing is serial).
    progress : bool
        Show a progress bar (runs done, failed, ETA) on stderr.
    run_timeout : float, optional
        Wall-clock limit of each run's integration [s] (default: none). A run past it is
        recorded as failed, ``"timeout after N s"``, with its peaks up to then, and the
        suite goes on. The run looks at the clock itself (see the module docstring).
    lock : bool
        Hold the folder's lock (:class:`~structures.suites.lock.SuiteLock`); False when the
        caller holds it.
    wait_lock : float
        How long to wait for a folder locked by another suite [s]; 0 refuses at once.
    max_steps : int
        A run of more steps fails with its step count, before anything is allocated
        (default 2,000,000; :mod:`isolator.limits`).

    Returns
    -------
    SuiteResult
        Also written: ``peaks.csv``, ``failures.json``, ``summary.csv``, ``summary.parquet``.

    Raises
    ------
    structures.suites.lock.SuiteLocked
        When another suite writes into ``out_dir``.
    """
    check_run_options(write, run_timeout, max_steps, "run_suite")
    with SuiteLock(out_dir, wait=wait_lock) if lock else nullcontext():
        return _run_suite(suite, out_dir, n_workers, scheduler_address, write, progress,
                          run_timeout, max_steps)


def _run_suite(suite: Suite, out_dir: str | Path, n_workers: int | None,
               scheduler_address: str | None, write: str, progress: bool,
               run_timeout: float | None, max_steps: int) -> SuiteResult:
    """:func:`run_suite` with the folder locked."""
    start = time.perf_counter()
    store = RunStore(out_dir)
    store.clean_temporary()
    ship = write == "client" or callable(suite.record_factors)  # records read here, sent
    specs, motions, unreadable = suite.plan(read=ship)
    rows, computed, skipped = compute_runs(
        specs, motions, unreadable, suite.config, store, n_workers=n_workers,
        scheduler_address=scheduler_address, write=write, progress=progress,
        run_timeout=run_timeout, max_steps=max_steps, ship=ship)
    return finish(specs, rows, store, computed, skipped, start, COLUMNS)
