"""One run of a suite: :class:`RunSpec`, its stable id and its row, and :func:`execute_run`, the
pure work that computes it (a spec and a motion in, its peaks row and netCDF bytes out; the
files are written by :mod:`structures.suites.store`).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import re
import socket
import time
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from isolator.limits import DEFAULT_MAX_STEPS
from structures.config import BuildingConfig
from structures.suites.sources import MOTION_COLUMNS, MotionSource

PEAK_COLUMNS = {
    "record": ("peak_isolator_displacement", "peak_base_shear", "peak_roof_acceleration",
               "peak_storey_drift", "max_temperature", "energy_balance_error", "steps",
               "wall_time"),
    "pair": ("peak_isolator_displacement", "peak_centre_displacement", "corner_bearing",
             "peak_base_shear", "peak_roof_acceleration_x", "peak_roof_acceleration_y",
             "peak_storey_drift_x", "peak_storey_drift_y", "peak_base_rotation",
             "max_temperature", "energy_balance_error", "steps", "wall_time",
             "peaks_up_to_failure", "uplift_bearings", "uplift_steps", "uplift_first_time",
             "uplift_longest"),
}
"""Columns of the peaks table from :func:`structures.analysis.peaks` (SI units, wall time [s]),
by the kind of motion: a record's runs in one direction, a pair's in plan (with the bearings'
lift-off under a vertical component: ``uplift_*``)."""

COLUMNS = {
    kind: ("run_id", *MOTION_COLUMNS[kind], "scale", "record_factor", "multiplier", "model",
           "modifier", "duration", "dt", *PEAK_COLUMNS[kind], "task_time", "status", "reason",
           "worker", "failure", "failed_at")
    for kind in MOTION_COLUMNS
}
"""Columns of the peaks table, one row per run, by the kind of motion: the motion, its scale
(``record_factor`` times ``multiplier``), model and modifier, the peaks (:data:`PEAK_COLUMNS`;
a failed run's up to ``failed_at`` [s], empty when it never ran), then how the run went
(``failure``: one of :data:`FAILURE_KINDS`, empty for a run that finished)."""

FAILURE_KINDS = ("capacity", "convergence", "timeout", "error")
"""Why a run failed: past its displacement capacity, no convergence, past its time limit
(``run_suite(run_timeout=...)``), anything else (an exception, an unreadable motion, a worker
that kept dying)."""

MODEL_COST = {"precise": 2.0, "simplified": 1.5, "constant": 1.0}
"""Relative cost of a time step per friction model (the order in which runs start)."""

STORAGE = ("full", "float32", "peaks")
"""What a run keeps of its result, from most to least (:func:`execute_run`): the Dataset as
netCDF in float64 (``"full"``), the same with every float64 variable as float32 (half the bytes;
the peaks are computed before the cast), or its peaks row only (no netCDF file)."""

NETCDF_ENGINE = "scipy"
"""xarray engine of the result files: netCDF3 written to bytes in memory with scipy only."""


def failure_kind(row: dict[str, Any]) -> str:
    """The :data:`FAILURE_KINDS` entry of a run's row (``""`` if finished), by failure or reason."""
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


def _hash(payload: Any, digits: int) -> str:
    text = json.dumps(payload, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:digits]


def fingerprint(config: BuildingConfig, in_plan: bool = False) -> str:
    """A 12-hex-digit hash of what in a building file changes a run's answer (building, bearings,
    friction, integration and, in plan, the plan), not its ``name``."""
    b = config.building
    digest = _hash({
        "floor_masses": [float(x) for x in b.floor_masses],
        "storey_stiffnesses": [float(x) for x in b.storey_stiffnesses],
        "base_mass": float(b.base_mass),
        "damping": repr(b.damping),
        "n_bearings": config.n_bearings,
        "bearing": config.bearing_geometry,
        "friction": config.friction,
        "integrator": repr(config.integrator),
        "dt": config.dt,
    }, 12)
    if not in_plan:
        return digest
    plan = {f.name: getattr(config.plan, f.name) for f in dataclasses.fields(config.plan)}
    if plan.get("load_eccentricity") is None:  # added later: absent, the ids stay as they were
        plan.pop("load_eccentricity", None)
    return _hash({"building": digest,
                  "plan": {k: v.tolist() if hasattr(v, "tolist") else v
                           for k, v in plan.items()}}, 12)


def analysis_step(requested: float | None, motion_dt: float) -> float:
    """A run's analysis step [s]: the requested one (None: the motion's), at most the motion's."""
    return motion_dt if requested is None else min(float(requested), motion_dt)


def _safe(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]+", "-", text).strip("-") or "record"


@dataclass(frozen=True)
class RunSpec:
    """One run of a suite: the ``motion`` (a record, run in one direction, or a pair, in plan)
    with the sha256 ``digests`` of its files, the friction ``model``, the motion's own
    ``record_factor`` and the suite-wide ``multiplier`` of it [-], the ``modifier`` of the
    friction coefficient [-], the first ``duration`` seconds kept [s] (None: all), the requested
    analysis step ``dt`` [s] (None: the building file's, else the motion's) and the building's
    ``settings`` (:func:`fingerprint`)."""

    motion: MotionSource
    digests: tuple[str, ...]
    model: str
    record_factor: float = 1.0
    multiplier: float = 1.0
    modifier: float = 1.0
    duration: float | None = None
    dt: float | None = None
    settings: str = ""

    @property
    def scale(self) -> float:
        """Amplitude scale factor of the ground motion, ``record_factor * multiplier`` [-]."""
        return self.record_factor * self.multiplier

    @cached_property
    def run_id(self) -> str:
        """Stable id ``<name>_x<scale>_<model>_m<modifier>-<hash>``, e.g.
        ``A-BEN360_x2_precise_m1-3f9a2c1b07``, the hash over everything that changes the answer
        (:meth:`MotionSource.identity`, the exact scale and modifier, truncation, step,
        :func:`fingerprint`)."""
        key = self.motion.identity(self.digests) | {
            name: getattr(self, name) for name in ("model", "record_factor", "multiplier",
                                                   "modifier", "duration", "dt", "settings")}
        return (f"{_safe(self.motion.name)}_x{self.scale:.4g}_{self.model}"
                f"_m{self.modifier:.4g}-{_hash(key, 10)}")

    def row(self) -> dict[str, Any]:
        """The peaks-table row of this run before it runs (peaks and status empty)."""
        return dict.fromkeys(COLUMNS[self.motion.kind]) | {"run_id": self.run_id} | (
            self.motion.columns()) | {
            "scale": self.scale, "record_factor": self.record_factor,
            "multiplier": self.multiplier, "model": self.model, "modifier": self.modifier,
            "duration": self.duration}

    def failure(self, reason: str, row: dict[str, Any] | None = None,
                kind: str = "error") -> dict[str, Any]:
        """The row of a failed run, with its ``reason`` and ``kind`` (:data:`FAILURE_KINDS`)."""
        return (row or self.row()) | {"status": "failed", "reason": reason, "failure": kind}

    def cost(self, motion: Any, config: BuildingConfig) -> int:
        """Estimated cost (steps, or a motion's file bytes, x model weight): longest first."""
        if motion is None:
            try:
                size = sum(os.path.getsize(f) for f in self.motion.files)
            except OSError:
                return 0
            return int(size * MODEL_COST[self.model])
        length = motion.duration if self.duration is None else min(self.duration,
                                                                  motion.duration)
        step = analysis_step(self.dt if self.dt is not None else config.dt, motion.dt)
        return int(length / step * MODEL_COST[self.model])


def stored_enough(row: dict[str, Any], storage: str) -> bool:
    """Whether a finished run's ``row`` keeps at least what ``storage`` asks
    (:data:`STORAGE`: a float64 file serves every request, a float32 one ``"float32"`` and
    ``"peaks"``, a row alone ``"peaks"``); rows written before storage was recorded are full."""
    kept = row.get("storage") or "full"
    return kept in STORAGE and STORAGE.index(kept) <= STORAGE.index(storage)


def as_float32(result: Any) -> Any:
    """The Dataset with its float64 data variables as float32 (coordinates kept)."""
    return result.assign({name: result[name].astype(np.float32)
                          for name, var in result.data_vars.items()
                          if var.dtype == np.float64})


def execute_run(spec: RunSpec, motion: Any, config: BuildingConfig,
                time_limit: float | None = None, max_steps: int = DEFAULT_MAX_STEPS,
                storage: str = "full", design: bool = False,
                ) -> tuple[dict[str, Any], bytes | None]:
    """Compute one run, the work of a Dask task: ``structures.run`` on the record (the building
    in one direction) or the pair (in plan), scaled, truncated, with the friction coefficient
    times the modifier.

    Parameters
    ----------
    spec : RunSpec
        What to run.
    motion : GroundMotion or GroundMotionPair or None
        The motion read from the spec's files (unscaled, untruncated), or None to read it here.
    config : BuildingConfig
        The building file.
    time_limit : float, optional
        Wall-clock limit of the run's integration [s]: past it the run fails with the reason
        ``"timeout after N s: ..."``.
    max_steps : int
        A run of more steps fails with the reason before anything is allocated.
    storage : {"full", "float32", "peaks"}
        What is kept of the result (:data:`STORAGE`); recorded in the row as ``storage``.
    design : bool
        Add the keys of :func:`structures.analysis.design_peaks` to the row (storey heights
        from the plan's ``storey_heights``, if given).

    Returns
    -------
    row : dict
        The peaks-table row (:data:`COLUMNS`, and every key of
        :func:`structures.analysis.peaks`): status ``"done"``, or ``"failed"`` with the
        ``reason`` (any exception, or a run that stopped early, its peaks up to then kept), the
        ``failure`` kind and ``failed_at`` [s].
    data : bytes or None
        The result as netCDF (:data:`NETCDF_ENGINE`), empty with ``storage="peaks"``; None
        for a failed run.
    """
    from structures.analysis import design_peaks, peaks, run

    start = time.perf_counter()
    row = spec.row() | {"worker": f"{socket.gethostname()}:{os.getpid()}"}
    kind = spec.motion.kind
    try:
        if motion is None:
            motion = spec.motion.read()
        if spec.duration is not None:
            motion = motion.truncated(min(spec.duration, motion.duration))
        if spec.scale != 1.0:
            motion = motion.scaled(spec.scale)
        step = analysis_step(spec.dt if spec.dt is not None else config.dt, motion.dt)
        in_plan = kind == "pair"
        building = config.building if in_plan else dataclasses.replace(config.building,
                                                                        plan=None)
        bearing = config.bearing(spec.model)
        bearing = dataclasses.replace(bearing, friction=bearing.friction.scaled(spec.modifier),
                                      axial_load=None)  # each its share of the weight
        result = run(building, bearing, motion, config.integrator,
                     n_bearings=None if in_plan else config.n_bearings, dt=step,
                     time_limit=time_limit, max_steps=max_steps)
        row.update(peaks(result), dt=float(result.attrs["dt"]), storage=storage)
        if design:
            plan = building.plan
            row.update(design_peaks(result, None if plan is None else plan.storey_heights))
        if not result.attrs["success"]:
            row["task_time"] = time.perf_counter() - start
            failure = failure_kind({"failure": row["failure"]})
            reason = f"run stopped early: {result.attrs['message']}"
            if failure == "timeout":
                reason = (f"timeout after {time_limit:g} s: the run was stopped at t = "
                          f"{row['failed_at']:.6g} s of the {kind} (its peaks are those up "
                          "to then)")
            return spec.failure(reason, row, failure), None
        result.attrs.update(building=config.name, run_id=spec.run_id, scale=spec.scale,
                            property_modifier=spec.modifier,
                            building_fingerprint=spec.settings)
        for name, value in spec.motion.columns().items():  # the run's own "record" kept
            result.attrs.setdefault(name, "" if value is None else value)
        if storage == "peaks":
            data = b""
        else:
            if storage == "float32":
                result = as_float32(result)
            data = bytes(result.to_netcdf(engine=NETCDF_ENGINE))
    except Exception as error:  # any failure is this run's, reported, and the suite goes on
        row["task_time"] = time.perf_counter() - start
        return spec.failure(f"{type(error).__name__}: {error}", row), None
    row.update(status="done", task_time=time.perf_counter() - start, failure="")
    return row, data
