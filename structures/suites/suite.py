"""Ground-motion suites: records or pairs x scale factors x friction models x property modifiers.

A :class:`Suite` is a set of independent runs of one building (records run it in one
direction, pairs in plan). :func:`run_suite` computes them with ``dask.distributed``, on a local
or a running cluster, each run's files written atomically (:mod:`structures.suites.store`).
Rerunning a suite into its folder computes only the runs not complete, so a killed suite or a
lost worker loses at most the runs in flight; a failed run is recorded with its reason and
retried next time, the others carry on. One suite at a time per folder
(:mod:`structures.suites.lock`).

Example::

    suite = Suite(load_config("examples/five_storey.toml"), motion_sources("records/"),
                  models=("precise", "constant"), scales=(1.0, 2.0))
    result = run_suite(suite, "out", n_workers=2)   # or scheduler_address="tcp://host:8786"
    result.peaks.groupby("model")["peak_isolator_displacement"].median()
"""

from __future__ import annotations

import time
import warnings
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from contextlib import nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from dcfpb.common.errors import InputError, InputTypeError, InputWarning
from dcfpb.common.validation import check_choice, check_instance, check_path, check_real
from isolator.experiments import MODELS
from isolator.limits import DEFAULT_MAX_STEPS
from structures.config import BuildingConfig
from structures.suites.dispatch import SuiteResult, check_run_options, compute_runs, finish
from structures.suites.lock import SuiteLock
from structures.suites.runs import COLUMNS, FAILURE_KINDS, STORAGE, RunSpec, fingerprint
from structures.suites.sources import MotionSource
from structures.suites.store import RunStore

__all__ = ["Suite", "SuiteResult", "check_modifiers", "run_suite"]

Factors = Mapping[Any, float] | Callable[[Sequence[Any]], Any]


def _lookup(factors: Mapping[Any, float], source: MotionSource, name: str) -> float | None:
    """A motion's factor keyed by its source, record path, file name or stem, or name."""
    files = (source.files[0], Path(source.files[0]).name) if source.kind == "record" else ()
    for key in (source, *files, source.name, name):
        if key in factors:
            return factors[key]
    return None


def check_modifiers(config: BuildingConfig, models: Sequence[str], modifiers: Sequence[float],
                    *, name: str = "property_modifiers", owner: str = "Suite") -> None:
    """Check that each property modifier keeps the friction coefficient of each model of the
    building file ``config`` in (0, 1].

    Parameters
    ----------
    config : BuildingConfig
        The building file.
    models : sequence of str
        Friction models of the suite.
    modifiers : sequence of float
        Factors on the reference friction coefficient [-], each > 0.
    name, owner : str
        How the modifiers and their owner are called, for the message (e.g. ``"--modifiers"``
        and ``"dcfpb suite"``).

    Raises
    ------
    InputError
        Naming ``name``, the model, its reference coefficient, the allowed range of the
        modifier and the value given.
    """
    for model in models:
        if model not in MODELS:  # refused by name where the models are checked
            continue
        friction = config.bearing(model).friction
        for modifier in modifiers:
            check_real(modifier, name, owner, low=0.0, low_open=True)
            try:
                friction.scaled(modifier)
            except InputError as error:
                reference = next(((key, getattr(friction, key)) for key in ("mu0", "mu_t0")
                                  if isinstance(getattr(friction, key, None), float)), None)
                if reference is None:
                    allowed, why = "a factor the friction model accepts", f" ({error})"
                else:
                    key, mu = reference
                    allowed = f"in (0, {1.0 / mu:.4g}]"
                    why = (f": it multiplies the {model} model's {key!r} = {mu:g}, which must stay "
                           "in (0, 1]")
                raise InputError(f"The {name!r} parameter of {owner} must be {allowed}{why}. "
                                 f"Got {modifier!r} instead.") from None


@dataclass(frozen=True)
class Suite:
    """Motions x scale multipliers x friction models x property modifiers on one building.

    Parameters
    ----------
    config : BuildingConfig
        The building file (:func:`structures.config.load_config`); for pairs, one with a
        ``[plan]`` table.
    motions : sequence of MotionSource, str or Path
        Records or pairs, not mixed (:func:`~structures.suites.sources.motion_sources`; a path
        is a record file); pairs of distinct names.
    models : sequence of str
        Friction models among ``"precise"``, ``"simplified"``, ``"constant"`` (default all).
    scales : sequence of float
        Suite-wide multipliers of the per-motion factors [-].
    property_modifiers : sequence of float
        Factors on the reference friction coefficient (``mu_t0``, or ``mu0`` of the constant
        model) [-], e.g. ``(lambda_min, 1.0, lambda_max)`` (ASCE 7-16 Sec. 17.2.8.4).
    factors : mapping or callable, optional
        Per-motion scale factors [-] (default 1): a mapping keyed by a record's path, file name
        or stem, or a pair's name; or a hook given the readable motions in order and returning
        their factors as a sequence or such a mapping, e.g. ``lambda motions:
        scale_suite(motions, target, period_range).scale_factors``.
    duration, dt : float, optional
        The first ``duration`` seconds of each motion kept [s]; the analysis step [s] (default
        the building file's; a motion with a finer step runs at its own).

    Raises
    ------
    InputError
        No motions, records and pairs mixed, two pairs of one name, pairs on a building file
        without a ``[plan]`` table, a model, scale or modifier out of range (a modified friction
        coefficient outside (0, 1] among them).

    Warns
    -----
    InputWarning
        Records on a building file with a ``[plan]`` table (they run it in one direction).
    """

    config: BuildingConfig
    motions: Sequence[MotionSource | str | Path]
    models: Sequence[str] = MODELS
    scales: Sequence[float] = (1.0,)
    property_modifiers: Sequence[float] = (1.0,)
    factors: Factors | None = field(default=None, repr=False)
    duration: float | None = None
    dt: float | None = None

    def __post_init__(self) -> None:
        owner = "Suite"
        check_instance(self.config, "config", owner, BuildingConfig,
                       "a BuildingConfig (structures.load_config)")
        for name in ("motions", "models", "scales", "property_modifiers"):
            value = getattr(self, name)
            if isinstance(value, str | bytes) or not hasattr(value, "__iter__"):
                raise InputTypeError(f"The {name!r} parameter of {owner} must be a sequence. "
                                     f"Got {value!r:.80} instead.")
        motions = tuple(m if isinstance(m, MotionSource) else MotionSource.record(m)
                        for m in self.motions)
        if not motions:
            raise InputError(f"The 'motions' parameter of {owner} must name at least one "
                             "record file or pair (motion_sources). Got none.")
        kinds = {m.kind for m in motions}
        if len(kinds) > 1:
            raise InputError(f"The 'motions' parameter of {owner} must be all records or all "
                             "pairs: a suite runs its building in one direction or in plan.")
        object.__setattr__(self, "motions", motions)
        twice = sorted(n for n, k in Counter(m.name for m in motions).items() if k > 1)
        if self.kind == "pair" and twice:
            raise InputError(f"{owner}: the pair names must differ. Got {twice} more than once.")
        if self.kind == "pair" and self.config.plan is None:
            raise InputError(f"{owner}: the building {self.config.name!r} has no [plan] "
                             "table; a suite of pairs runs a building in plan.")
        if self.kind == "record" and self.config.plan is not None:
            warnings.warn(InputWarning(
                f"The building {self.config.name!r} has a [plan] table but the suite runs it "
                "under single records: each runs it in one direction (x) on its bearings' "
                "count; give pairs of records (dcfpb suite --pairs) to run it in plan."),
                stacklevel=3)
        models = tuple(check_choice(m, "models", owner, MODELS) for m in self.models)
        for name in ("scales", "property_modifiers"):
            object.__setattr__(self, name, tuple(
                check_real(v, name, owner, low=0.0, low_open=True) for v in getattr(self, name)))
        object.__setattr__(self, "models", models)
        if not (self.models and self.scales and self.property_modifiers):
            raise InputError(f"{owner}: 'models', 'scales' and 'property_modifiers' must each "
                             "hold at least one value.")
        check_modifiers(self.config, self.models, self.property_modifiers)
        for name in ("duration", "dt"):
            if getattr(self, name) is not None:
                check_real(getattr(self, name), name, owner, low=0.0, low_open=True)

    @property
    def kind(self) -> str:
        """``"record"`` (the building runs in one direction) or ``"pair"`` (in plan)."""
        return self.motions[0].kind

    def read(self) -> tuple[dict[MotionSource, Any], dict[MotionSource, str]]:
        """Read the motions: ``({source: motion}, {source: reason it cannot be read})``."""
        motions, unreadable = {}, {}
        for source in self.motions:
            try:
                motions[source] = source.read()
            except Exception as error:  # reported per run; the others go on
                unreadable[source] = f"{type(error).__name__}: {error}"
        return motions, unreadable

    def _factors(self, motions: dict[MotionSource, Any], read: bool
                 ) -> dict[MotionSource, float]:
        given = self.factors
        if given is None:
            return {}
        readable = [s for s in self.motions if s in motions or not read]
        if callable(given):
            answer = given([motions[s] for s in readable]) if readable else {}
            if not isinstance(answer, Mapping):
                values = list(answer)
                if len(values) != len(readable):
                    raise InputError(f"The factor hook returned {len(values)} factors for "
                                     f"{len(readable)} {self.kind}s.")
                answer = dict(zip(readable, values, strict=True))
            given = answer
        factors = {s: _lookup(given, s, motions[s].name if read else s.name) for s in readable}
        missing = [s.name for s, v in factors.items() if v is None]
        if missing:
            raise InputError(f"No scale factor given for the {self.kind}(s) {missing}.")
        return {s: check_real(v, "factors", "Suite", low=0.0, low_open=True)
                for s, v in factors.items()}

    def runs(self, *, read: bool = True
             ) -> tuple[list[RunSpec], dict[MotionSource, Any], dict[MotionSource, str]]:
        """The runs in table order (motion, multiplier, model, modifier), the readable motions
        and the reasons of the unreadable ones. With ``read=False`` the motions are read only if
        a factor hook needs them (else both dicts are empty and each run reads its own)."""
        read = read or callable(self.factors)
        motions, unreadable = self.read() if read else ({}, {})
        factors = self._factors(motions, read)
        settings = fingerprint(self.config, in_plan=self.kind == "pair")
        specs = [RunSpec(source, digests, model, factors.get(source, 1.0), multiplier,
                         modifier, self.duration, self.dt, settings)
                 for source in self.motions for digests in (source.digests(),)
                 for multiplier in self.scales for model in self.models
                 for modifier in self.property_modifiers]
        twice = sorted(i for i, n in Counter(s.run_id for s in specs).items() if n > 1)
        if twice:
            raise InputError(f"The suite holds the same run more than once (a {self.kind}, "
                             f"scale or modifier given twice): {twice[:3]}.")
        return specs, motions, unreadable


def design_columns(rows: Any) -> tuple[str, ...]:
    """The keys of :func:`structures.analysis.design_peaks` in the first row that has them
    (per-storey drift ratios included), in their order."""
    from structures.analysis import DESIGN_PEAKS

    for row in rows:
        if "isolator_displacement" in row:
            return tuple(k for k in row if k in DESIGN_PEAKS or k.startswith("drift_ratio_"))
    return DESIGN_PEAKS


def run_suite(suite: Suite, out_dir: str | Path, *, n_workers: int | None = None,
              scheduler_address: str | None = None, write: str = "workers",
              progress: bool = True, run_timeout: float | None = None, lock: bool = True,
              wait_lock: float = 0.0, max_steps: int = DEFAULT_MAX_STEPS,
              storage: str = "full", design_peaks: bool = False,
              keep_failed: Sequence[str] = (), label: str = "suite") -> SuiteResult:
    """Compute a suite into ``out_dir``, or finish one that was interrupted.

    Parameters
    ----------
    suite : Suite
        The runs.
    out_dir : str or Path
        Result folder (:mod:`structures.suites.store`); the complete runs already in it are kept.
    n_workers : int, optional
        Worker processes of the local cluster (default: the number of CPUs).
    scheduler_address : str, optional
        Address of a running scheduler, e.g. ``"tcp://10.0.0.5:8786"``, whose workers can import
        this package; ``n_workers`` is then ignored.
    write : {"workers", "client"}
        Who writes a run's files: the worker that computed it (the folder under the same path on
        every worker), or this process, serially (any cluster, no shared file system).
    progress : bool
        Show a progress bar (runs done, failed, ETA) on stderr.
    label : str
        The progress bar's name (default ``"suite"``).
    run_timeout : float, optional
        Wall-clock limit of each run's integration [s] (``structures.analysis.run(time_limit=)``):
        a run past it fails, ``"timeout after N s"``, with its peaks up to then.
    lock, wait_lock : bool, float
        Hold the folder's lock (:class:`~structures.suites.lock.SuiteLock`; False when the caller
        holds it), and how long to wait for a folder locked by another suite [s] (0: refuse).
    max_steps : int
        A run of more steps fails before anything is allocated (:mod:`isolator.limits`).
    storage : {"full", "float32", "peaks"}
        What each run keeps (:data:`structures.suites.runs.STORAGE`): its result as netCDF in
        float64 (default) or float32, or its peaks row only.
    design_peaks : bool
        Add the keys of :func:`structures.analysis.design_peaks` to every run's row and, after
        the suite's columns, to ``peaks`` (not to ``peaks.csv``).
    keep_failed : sequence of str
        Failure kinds (:data:`structures.suites.runs.FAILURE_KINDS`) a stored failed run keeps
        instead of running again (default none: every failed run is retried), e.g.
        ``("capacity",)``: past the bearings' capacity the same run fails the same way.

    Returns
    -------
    SuiteResult
        ``peaks`` with the columns of the suite's kind (:data:`structures.suites.runs.COLUMNS`);
        also written: ``peaks.csv``, ``failures.json``, ``summary.csv``, ``summary.parquet``.

    Raises
    ------
    structures.suites.lock.SuiteLocked
        When another suite writes into ``out_dir``.
    """
    check_instance(suite, "suite", "run_suite", Suite, "a Suite")
    check_path(out_dir, "out_dir", "run_suite")
    check_run_options(write, run_timeout, max_steps, "run_suite")
    storage = check_choice(storage, "storage", "run_suite", STORAGE)
    if not isinstance(design_peaks, bool):
        raise InputTypeError(f"The 'design_peaks' parameter of run_suite must be True or "
                             f"False. Got {design_peaks!r} instead.")
    with SuiteLock(out_dir, wait=wait_lock) if lock else nullcontext():
        start = time.perf_counter()
        store = RunStore(out_dir)
        store.clean_temporary()
        ship = write == "client" or callable(suite.factors)  # motions read here, sent
        specs, motions, unreadable = suite.runs(read=ship)
        rows, computed, skipped = compute_runs(
            specs, motions, unreadable, suite.config, store, n_workers=n_workers,
            scheduler_address=scheduler_address, write=write, progress=progress,
            run_timeout=run_timeout, max_steps=max_steps, ship=ship, storage=storage,
            design=design_peaks, keep_failed=tuple(
                check_choice(k, "keep_failed", "run_suite", FAILURE_KINDS)
                for k in keep_failed), label=label)
        return finish(specs, rows, store, computed, skipped, start, COLUMNS[suite.kind],
                      extra_columns=tuple(
                          k for k in design_columns(rows.values())
                          if k not in COLUMNS[suite.kind]) if design_peaks else ())
