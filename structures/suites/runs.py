"""One run of a ground-motion suite: what it is, its stable id, the task that computes it.

A suite (:mod:`structures.suites.suite`) is a set of independent runs, each a record file at a scale
factor under one friction model with one property modifier. This module holds what a single
run needs:

``RunSpec``
    the run's definition and its stable id, a readable name plus a hash of everything that
    changes the answer (record bytes, scale, model, modifier, truncation, step, building);
``modified_bearing``
    the file's bearing with its friction coefficient multiplied by a property modifier
    (upper/lower-bound analyses, lambda_max / lambda_min);
``execute_run``
    the computation of a run, pure: a spec and a record in, the peaks row and the netCDF
    bytes out; the files are written by :mod:`structures.suites.store` (on the worker or on
    the client, see ``structures.suites.suite.run_suite``).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import socket
import time
from dataclasses import dataclass, fields, replace
from functools import cached_property
from pathlib import Path
from typing import Any

from dcfpb.common.validation import check_choice, check_real
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from isolator.experiments import MODELS
from isolator.limits import DEFAULT_MAX_STEPS
from structures.config import BuildingConfig

PEAK_COLUMNS = ("peak_isolator_displacement", "peak_base_shear", "peak_roof_acceleration",
                "peak_storey_drift", "max_temperature", "energy_balance_error", "steps",
                "wall_time")
"""Columns filled from :func:`structures.analysis.peaks` (SI units, wall time [s])."""

COLUMNS = ("run_id", "record", "record_file", "scale", "record_factor", "multiplier", "model",
           "modifier", "duration", "dt", *PEAK_COLUMNS, "task_time", "status", "reason",
           "worker", "failure", "failed_at")
"""Columns of the peaks table, one row per run. A failed run keeps the peaks of the part that
ran (up to ``failed_at`` [s] of the record, empty when it never ran); ``failure`` is its kind,
one of :data:`FAILURE_KINDS` (empty for a run that finished)."""

FAILURE_KINDS = ("capacity", "convergence", "timeout", "error")
"""Why a run failed: a bearing past its displacement capacity; a step that did not converge;
past its time limit (``run_suite(run_timeout=...)``); anything else (an exception, an
unreadable record, a worker that kept dying, a model outside its range)."""


def failure_kind(row: dict[str, Any]) -> str:
    """The :data:`FAILURE_KINDS` entry of a failed run's row (``""`` for a finished run);
    rows written before the ``failure`` column are read from their reason."""
    if row.get("status") == "done":
        return ""
    kind = row.get("failure")
    if isinstance(kind, str) and kind:
        return kind if kind in FAILURE_KINDS else "error"
    reason = str(row.get("reason") or "")
    for kind, marks in (("capacity", ("Capacity exceeded", "displacement_capacity")),
                        ("timeout", ("timeout after",)),
                        ("convergence", ("did not converge",))):
        if any(mark in reason for mark in marks):
            return kind
    return "error"

MODEL_COST = {"precise": 2.0, "simplified": 1.5, "constant": 1.0}
"""Relative cost of a time step per friction model (the order in which runs start)."""

NETCDF_ENGINE = "scipy"
"""xarray engine of the result files: netCDF3 (64-bit offset) written to bytes in memory,
needing only scipy (netCDF4 and h5netcdf are optional and cannot both write to bytes)."""


def config_fingerprint(config: BuildingConfig) -> str:
    """A 12-hex-digit hash of everything in a building file that changes a run's answer.

    The file's ``name`` is left out: renaming a building does not invalidate its results.
    """
    b = config.building
    payload = {
        "floor_masses": [float(x) for x in b.floor_masses],
        "storey_stiffnesses": [float(x) for x in b.storey_stiffnesses],
        "base_mass": float(b.base_mass),
        "damping": repr(b.damping),
        "n_bearings": config.n_bearings,
        "bearing": config.bearing_geometry,
        "friction": config.friction,
        "integrator": repr(config.integrator),
        "dt": config.dt,
    }
    text = json.dumps(payload, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:12]


def file_digest(path: str | Path) -> str:
    """sha256 of a file's bytes (16 hex digits), or ``"missing"`` if it cannot be read."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
    except OSError:
        return "missing"


def modified_bearing(config: BuildingConfig, model: str, modifier: float = 1.0) -> DCFPBearing:
    """The file's bearing with friction ``model``, its friction coefficient times ``modifier``.

    Parameters
    ----------
    config : BuildingConfig
        The building file.
    model : {"precise", "simplified", "constant"}
        Friction model.
    modifier : float
        Property modification factor on the reference friction coefficient [-]: it multiplies
        ``mu_t0`` of the precise and simplified models (Eq. 7) or ``mu0`` of the constant
        model (Eq. 8), e.g. lambda_max or lambda_min of ASCE 7-16 Sec. 17.2.8.4.

    Raises
    ------
    ValueError
        If ``modifier`` is not > 0, or the modified coefficient leaves (0, 1].
    """
    check_real(modifier, "property_modifier", "modified_bearing", low=0.0, low_open=True)
    bearing = config.bearing(check_choice(model, "model", "modified_bearing", MODELS))
    if modifier == 1.0:
        return bearing
    return replace(bearing, friction=bearing.friction.scaled(modifier))


def analysis_step(requested: float | None, record_dt: float) -> float:
    """The analysis step of a run [s]: the requested step, or the record's when that is finer
    (``run`` cannot take a step longer than the record's). ``None`` means the record's."""
    return record_dt if requested is None else min(float(requested), record_dt)


def _safe(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]+", "-", text).strip("-") or "record"


class SuiteRun:
    """What a run of a suite of records (:class:`RunSpec`) and of pairs
    (:class:`structures.suites.pairs.runs.PairRunSpec`) share: the scale, the form of the id,
    the row of a failure and the cost estimate. A run has the fields ``record_factor``,
    ``multiplier``, ``model``, ``modifier``, ``duration`` and ``dt``, and its ground motion's
    ``files``."""

    record_factor: float
    multiplier: float
    model: str
    modifier: float
    duration: float | None
    dt: float | None

    @property
    def scale(self) -> float:
        """Amplitude scale factor of the ground motion, ``record_factor * multiplier`` [-]."""
        return self.record_factor * self.multiplier

    @property
    def files(self) -> tuple[str, ...]:
        """The files of the run's ground motion."""
        raise NotImplementedError

    def _run_id(self, name: str, key: dict[str, Any]) -> str:
        """``<name>_x<scale>_<model>_m<modifier>-<hash>``, the hash that of ``key`` (JSON)."""
        digest = hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:10]
        return (f"{_safe(name)}_x{self.scale:.4g}_{self.model}_m{self.modifier:.4g}"
                f"-{digest}")

    def row(self) -> dict[str, Any]:
        """The peaks-table row of this run before it runs (peaks and status empty)."""
        raise NotImplementedError

    def failure(self, reason: str, row: dict[str, Any] | None = None,
                kind: str = "error") -> dict[str, Any]:
        """The row of a failed run, with its ``reason`` and ``kind`` (:data:`FAILURE_KINDS`)."""
        return (row or self.row()) | {"status": "failed", "reason": reason, "failure": kind}

    def cost(self, motion, config: BuildingConfig) -> int:
        """Estimated cost, steps (or, for a motion not read here, its files' bytes) x model
        weight: the longest runs start first, so fewer workers idle at the end of the suite."""
        if motion is None:
            try:
                size = sum(os.path.getsize(f) for f in self.files)
            except OSError:
                return 0
            return int(size * MODEL_COST[self.model])
        length = motion.duration if self.duration is None else min(self.duration,
                                                                  motion.duration)
        step = analysis_step(self.dt if self.dt is not None else config.dt, motion.dt)
        return int(length / step * MODEL_COST[self.model])


@dataclass(frozen=True)
class RunSpec(SuiteRun):
    """One run of a suite.

    Parameters
    ----------
    record_file : str
        Path of the record file.
    record_digest : str
        sha256 of the file's bytes (see :func:`file_digest`).
    model : str
        Friction model, ``"precise"``, ``"simplified"`` or ``"constant"``.
    record_factor : float
        Per-record scale factor (e.g. to a target spectrum) [-].
    multiplier : float
        Suite-wide multiplier of the record factor [-]; the run's scale is their product.
    modifier : float
        Property modifier on the friction coefficient [-] (:func:`modified_bearing`).
    duration : float or None
        Keep only the first ``duration`` seconds of the record [s] (None: all of it).
    dt : float or None
        Requested analysis step [s] (None: the building file's, else the record's).
    settings : str
        :func:`config_fingerprint` of the building.
    """

    record_file: str
    record_digest: str
    model: str
    record_factor: float = 1.0
    multiplier: float = 1.0
    modifier: float = 1.0
    duration: float | None = None
    dt: float | None = None
    settings: str = ""

    @property
    def files(self) -> tuple[str, ...]:
        """The record file."""
        return (self.record_file,)

    @property
    def record(self) -> str:
        """The record's name: its file name without the extension."""
        return Path(self.record_file).stem

    @cached_property
    def run_id(self) -> str:
        """Stable id: ``<record>_x<scale>_<model>_m<modifier>-<hash>``, e.g.
        ``A-BEN360_x2_precise_m1-3f9a2c1b07``. The hash covers the record's bytes (not its
        folder), the exact scale and modifier, the truncation, the step and the building."""
        key = {f.name: getattr(self, f.name) for f in fields(self)}
        key["record_file"] = Path(self.record_file).name
        return self._run_id(self.record, key)

    def row(self) -> dict[str, Any]:
        """The peaks-table row of this run before it runs (peaks and status empty)."""
        row: dict[str, Any] = dict.fromkeys(COLUMNS)
        row.update(run_id=self.run_id, record=self.record,
                   record_file=Path(self.record_file).name, scale=self.scale,
                   record_factor=self.record_factor, multiplier=self.multiplier,
                   model=self.model, modifier=self.modifier, duration=self.duration)
        return row

    # What the Dask side (structures.suites.tasks, .dispatch) asks of any run of a suite.

    @property
    def source(self) -> str:
        """The key of the run's ground motion, its record file: the runs of one source share
        a read and a Dask task."""
        return self.record_file

    def read(self) -> GroundMotion:
        """The run's record, unscaled and untruncated (raises if it cannot be read)."""
        from groundmotions.readers import read_record

        return read_record(self.record_file)

    def execute(self, motion: GroundMotion | None, config: BuildingConfig,
                time_limit: float | None = None, max_steps: int = DEFAULT_MAX_STEPS,
                ) -> tuple[dict[str, Any], bytes | None]:
        """:func:`execute_run` of this run."""
        return execute_run(self, motion, config, time_limit, max_steps)


def execute_run(spec: RunSpec, motion: GroundMotion | None, config: BuildingConfig,
                time_limit: float | None = None, max_steps: int = DEFAULT_MAX_STEPS,
                ) -> tuple[dict[str, Any], bytes | None]:
    """Compute one run (the work of a Dask task).

    Parameters
    ----------
    spec : RunSpec
        What to run.
    motion : GroundMotion or None
        The record read from ``spec.record_file`` (unscaled, untruncated), or None to read
        it here.
    config : BuildingConfig
        The building file.
    time_limit : float, optional
        Wall-clock limit of the run's integration [s] (``run(time_limit=...)``): past it
        the run fails with the reason ``"timeout after N s: ..."``.
    max_steps : int
        Refuse a run of more steps (``run(max_steps=...)``; a record whose DT is wrong): it
        fails with the reason, before anything is allocated.

    Returns
    -------
    row : dict
        The peaks-table row: status ``"done"``, or ``"failed"`` with the ``reason`` (any
        exception, e.g. an unreadable record, or a run that stopped early: ``success == 0``
        in the result attributes, in which case the peaks of the part that ran are kept)
        and the ``failure`` kind and time ``failed_at`` [s].
    data : bytes or None
        The result as netCDF (:data:`NETCDF_ENGINE`), None for a failed run.
    """
    from groundmotions.readers import read_record
    from structures.analysis import peaks, run

    start = time.perf_counter()
    row = spec.row() | {"worker": f"{socket.gethostname()}:{os.getpid()}"}
    try:
        if motion is None:
            motion = read_record(spec.record_file)
        if spec.duration is not None:
            motion = motion.truncated(min(spec.duration, motion.duration))
        if spec.scale != 1.0:
            motion = motion.scaled(spec.scale)
        step = analysis_step(spec.dt if spec.dt is not None else config.dt, motion.dt)
        bearing = modified_bearing(config, spec.model, spec.modifier)
        result = run(config.building, bearing, motion, config.integrator,
                     n_bearings=config.n_bearings, dt=step, time_limit=time_limit,
                     max_steps=max_steps)
        row.update(peaks(result), dt=float(result.attrs["dt"]))
        if not result.attrs["success"]:
            row["task_time"] = time.perf_counter() - start
            kind = failure_kind({"failure": row["failure"]})
            reason = f"run stopped early: {result.attrs['message']}"
            if kind == "timeout":
                reason = (f"timeout after {time_limit:g} s: the run was stopped at t = "
                          f"{row['failed_at']:.6g} s of the record (its peaks are those up "
                          "to then)")
            return spec.failure(reason, row, kind), None
        result.attrs.update(run_id=spec.run_id, record_file=row["record_file"],
                            scale=spec.scale, property_modifier=spec.modifier,
                            building_fingerprint=spec.settings)
        data = bytes(result.to_netcdf(engine=NETCDF_ENGINE))
    except Exception as error:  # any failure is this run's, reported, and the suite goes on
        row["task_time"] = time.perf_counter() - start
        return spec.failure(f"{type(error).__name__}: {error}", row), None
    row.update(status="done", task_time=time.perf_counter() - start, failure="")
    return row, data
