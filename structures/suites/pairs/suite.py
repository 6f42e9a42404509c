"""Suites of pairs: a building in plan under pairs of records x scale factors x friction models
x property modifiers, run as suites of single records are (:mod:`structures.suites.suite`).

A building file with a ``[plan]`` table (:mod:`structures.spatial.plan_schema`) runs under each
pair of a manifest (:func:`pair_sources`: the CSV of :func:`groundmotions.read_pair_manifest`,
columns ``name, x, y[, z, dt, units]``). Each run is a :class:`~structures.suites.pairs.runs.
PairRunSpec` whose row holds the peaks of :func:`structures.spatial.peaks.plan_peaks`. The same
machinery as the single records: Dask (a local cluster or a scheduler address), each run's files
written atomically, reruns keep complete runs, a pair that cannot be read or run is recorded with
its reason while the others carry on (:mod:`structures.suites.dispatch`), ``run_timeout``, one
suite per folder (:mod:`structures.suites.lock`).

Scale factors: per pair, a mapping by pair name, or a hook given the readable pairs in order,
e.g. the factors of the ASCE 7-16 scaling of the suite on RotD100
(:func:`groundmotions.scale_suite`); ``scales`` multiplies them.

Example::

    suite = PairSuite(load_config("examples/five_storey_plan.toml"),
                      pair_sources("pairs/manifest.csv"), models=("constant",))
    result = run_pair_suite(suite, "out", n_workers=2)
    result.peaks.groupby("model")["peak_isolator_displacement"].median()
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from contextlib import nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.pairs.pair import manifest_rows
from isolator.experiments import MODELS
from isolator.limits import DEFAULT_MAX_STEPS
from structures.config import BuildingConfig
from structures.suites.dispatch import SuiteResult, check_run_options, compute_runs, finish
from structures.suites.lock import SuiteLock
from structures.suites.pairs.runs import PAIR_COLUMNS, PairRunSpec, plan_fingerprint
from structures.suites.runs import file_digest
from structures.suites.store import RunStore
from structures.suites.suite import check_suite_axes
from structures.suites.summary import PLAN_QUANTITIES

__all__ = ["PairSource", "PairSuite", "pair_sources", "run_pair_suite"]

PairFactors = Mapping[str, float] | Callable[[Sequence[GroundMotionPair]], Any]


@dataclass(frozen=True)
class PairSource:
    """Where a pair's components are, and how to read them (one row of a manifest).

    Parameters
    ----------
    name : str
        The pair's name.
    x, y : str
        Horizontal component files (x and y of the plan), absolute paths.
    z : str, optional
        Vertical component file (positive up).
    dt : float, optional
        Time step of one-column text records [s].
    units : str, optional
        Units of files whose header states none.
    """

    name: str
    x: str
    y: str
    z: str | None = None
    dt: float | None = None
    units: str | None = None


def pair_sources(manifest: str | Path) -> tuple[PairSource, ...]:
    """The pairs listed in a manifest CSV, without reading their files.

    The manifest of :func:`groundmotions.pairs.read_pair_manifest`, read by
    :func:`groundmotions.pairs.pair.manifest_rows`: a header row naming the
    columns ``name``, ``x``, ``y`` (required), ``z``, ``dt`` [s] and ``units``; paths relative
    to the manifest's folder; blank lines and lines starting with ``#`` skipped. A manifest
    that cannot be understood is an error before any work; a component that is missing or
    cannot be read, or a pair whose components disagree, is not: its runs fail with the
    reason and the others carry on.

    Raises
    ------
    InputError
        No such file, an empty manifest, an unknown, missing or repeated column, a row of the
        wrong number of cells, an empty required cell, a repeated pair name, a bad ``dt``;
        the message starts with ``"<manifest>, line <n>"``.
    """
    sources = []
    for row in manifest_rows(manifest):
        paths = {role: str(file.absolute()) for role, file in row.files.items()}  # for workers
        sources.append(PairSource(row.name, paths["x"], paths["y"], paths.get("z"), row.dt,
                                  row.units))
    return tuple(sources)


@dataclass(frozen=True)
class PairSuite:
    """Pairs x scale multipliers x friction models x property modifiers on a building in plan.

    Parameters
    ----------
    config : BuildingConfig
        A building file with a ``[plan]`` table (:func:`structures.config.load_config`).
    pairs : sequence of PairSource
        The pairs (:func:`pair_sources`), of distinct names.
    models : sequence of str
        Friction models among ``"precise"``, ``"simplified"``, ``"constant"``.
    scales : sequence of float
        Suite-wide multipliers of the per-pair factors [-].
    property_modifiers : sequence of float
        Factors on the reference friction coefficient [-].
    pair_factors : mapping or callable, optional
        Per-pair scale factors [-] (one factor for every component of a pair): a mapping by
        pair name, or a hook called with the readable pairs (in order) that returns their
        factors as a sequence or as a mapping by pair name, e.g.
        ``lambda pairs: scale_suite(pairs, target, period_range).scale_factors``
        (:func:`groundmotions.scale_suite`, on RotD100). Default 1.
    duration : float, optional
        Keep only the first ``duration`` seconds of each pair [s].
    dt : float, optional
        Analysis step [s]; default the building file's; a pair with a finer step is run at
        its own step (the ``dt`` column says which).

    Raises
    ------
    InputError
        A building file without a ``[plan]`` table, no pairs, or two pairs of one name.
    """

    config: BuildingConfig
    pairs: Sequence[PairSource]
    models: Sequence[str] = MODELS
    scales: Sequence[float] = (1.0,)
    property_modifiers: Sequence[float] = (1.0,)
    pair_factors: PairFactors | None = field(default=None, repr=False)
    duration: float | None = None
    dt: float | None = None

    def __post_init__(self) -> None:
        owner = "PairSuite"
        if self.config.plan is None:
            raise InputError(f"{owner}: the building {self.config.name!r} has no [plan] "
                             "table; a suite of pairs runs a building in plan.")
        pairs = tuple(self.pairs)
        if not pairs or not all(isinstance(p, PairSource) for p in pairs):
            raise InputError(f"The 'pairs' parameter of {owner} must be a non-empty sequence "
                             f"of PairSource (pair_sources(manifest)). Got {self.pairs!r}.")
        twice = sorted(n for n, k in Counter(p.name for p in pairs).items() if k > 1)
        if twice:
            raise InputError(f"{owner}: the pair names must differ. Got {twice} more than once.")
        object.__setattr__(self, "pairs", pairs)
        check_suite_axes(self, owner)

    def read(self) -> tuple[dict[str, GroundMotionPair], dict[str, str]]:
        """Read the pairs: ``({name: pair}, {name: reason it cannot be read})``."""
        from groundmotions.pairs import read_pair

        pairs, unreadable = {}, {}
        for source in self.pairs:
            try:
                pairs[source.name] = read_pair(source.x, source.y, source.z, name=source.name,
                                               dt=source.dt, units=source.units)
            except Exception as error:  # reported per run; the others go on
                unreadable[source.name] = f"{type(error).__name__}: {error}"
        return pairs, unreadable

    def _factors(self, pairs: dict[str, GroundMotionPair], read: bool) -> dict[str, float]:
        given = self.pair_factors
        if given is None:
            return {}
        names = [s.name for s in self.pairs if s.name in pairs or not read]
        if callable(given):
            answer = given([pairs[n] for n in names]) if names else {}
            if not isinstance(answer, Mapping):
                values = list(answer)
                if len(values) != len(names):
                    raise ValueError(f"The pair-factor hook returned {len(values)} factors "
                                     f"for {len(names)} pairs.")
                answer = dict(zip(names, values, strict=True))
            given = answer
        missing = [n for n in names if n not in given]
        if missing:
            raise ValueError(f"No scale factor given for the pair(s) {missing}.")
        return {n: check_real(given[n], "pair_factors", "PairSuite", low=0.0, low_open=True)
                for n in names}

    def plan(self, *, read: bool = True
             ) -> tuple[list[PairRunSpec], dict[str, GroundMotionPair], dict[str, str]]:
        """The runs, in table order (pair, multiplier, model, modifier), the readable pairs
        and the reasons of the unreadable ones, by pair name.

        With ``read=False`` the pairs are read only if a pair-factor hook needs them;
        otherwise both dicts are empty and each run reads its pair where it runs.
        """
        read = read or callable(self.pair_factors)
        pairs, unreadable = self.read() if read else ({}, {})
        factors = self._factors(pairs, read)
        settings = plan_fingerprint(self.config)
        specs = []
        for source in self.pairs:
            files = (source.x, source.y) + (() if source.z is None else (source.z,))
            digests = tuple(file_digest(f) for f in files)
            specs += [PairRunSpec(source.name, source.x, source.y, source.z, digests,
                                  source.dt, source.units, model,
                                  factors.get(source.name, 1.0), multiplier, modifier,
                                  self.duration, self.dt, settings)
                      for multiplier in self.scales for model in self.models
                      for modifier in self.property_modifiers]
        twice = sorted(i for i, n in Counter(s.run_id for s in specs).items() if n > 1)
        if twice:
            raise ValueError(f"The suite holds the same run more than once (a scale or "
                             f"modifier given twice): {twice[:3]}.")
        return specs, pairs, unreadable


def run_pair_suite(suite: PairSuite, out_dir: str | Path, *, n_workers: int | None = None,
                   scheduler_address: str | None = None, write: str = "workers",
                   progress: bool = True, run_timeout: float | None = None,
                   lock: bool = True, wait_lock: float = 0.0,
                   max_steps: int = DEFAULT_MAX_STEPS) -> SuiteResult:
    """Compute a suite of pairs, or finish one that was interrupted.

    Parameters
    ----------
    suite : PairSuite
        The runs.
    out_dir : str or Path
        Result folder (:mod:`structures.suites.store`); complete runs in it are kept.
    n_workers, scheduler_address, write, progress, lock, wait_lock, max_steps
        As :func:`structures.suites.suite.run_suite` (``wait_lock`` [s]).
    run_timeout : float, optional
        Wall-clock limit of each run's integration [s]; a run past it is recorded as
        failed, ``"timeout after N s"``, and the suite goes on.

    Returns
    -------
    SuiteResult
        ``peaks`` with the columns :data:`structures.suites.pairs.runs.PAIR_COLUMNS`, the
        ``summary`` of :data:`structures.suites.summary.PLAN_QUANTITIES`. Also written:
        ``peaks.csv``, ``failures.json``, ``summary.csv``, ``summary.parquet``.

    Raises
    ------
    structures.suites.lock.SuiteLocked
        When another suite writes into ``out_dir``.
    """
    check_run_options(write, run_timeout, max_steps, "run_pair_suite")
    with SuiteLock(out_dir, wait=wait_lock) if lock else nullcontext():
        start = time.perf_counter()
        store = RunStore(out_dir)
        store.clean_temporary()
        ship = write == "client" or callable(suite.pair_factors)  # pairs read here, sent
        specs, pairs, unreadable = suite.plan(read=ship)
        rows, computed, skipped = compute_runs(
            specs, pairs, unreadable, suite.config, store, n_workers=n_workers,
            scheduler_address=scheduler_address, write=write, progress=progress,
            run_timeout=run_timeout, max_steps=max_steps, ship=ship)
        return finish(specs, rows, store, computed, skipped, start, PAIR_COLUMNS,
                      PLAN_QUANTITIES)
