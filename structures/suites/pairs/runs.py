"""One run of a suite of pairs: a building in plan under a pair of records.

The counterpart of :mod:`structures.suites.runs` for a building file with a ``[plan]`` table
under two horizontal components (and an optional vertical) read together
(:func:`groundmotions.pairs.read_pair`):

``PairRunSpec``
    the run's definition and its stable id, a readable name plus a hash of everything that
    changes the answer (the bytes of every component, the reading, scale, model, modifier,
    truncation, step, building and plan);
``execute_pair_run``
    the computation of a run, pure: a spec and a pair in, the row of
    :func:`structures.spatial.peaks.plan_peaks` and the netCDF bytes out. It runs exactly what
    ``structures.run(config, pair, model=..., dt=..., scale=...)`` runs (the reference engine,
    each bearing on its gravity share), with the friction coefficient times the modifier.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import socket
import time
from dataclasses import dataclass, fields
from functools import cached_property
from pathlib import Path
from typing import Any

from groundmotions.pairs import GroundMotionPair
from isolator.limits import DEFAULT_MAX_STEPS
from structures.config import BuildingConfig
from structures.spatial.peaks import PLAN_PEAK_KEYS
from structures.suites.runs import (
    NETCDF_ENGINE,
    SuiteRun,
    analysis_step,
    config_fingerprint,
    failure_kind,
    modified_bearing,
)

__all__ = ["PAIR_COLUMNS", "PLAN_PEAK_COLUMNS", "PairRunSpec", "execute_pair_run",
           "plan_fingerprint", "truncated_pair"]

PLAN_PEAK_COLUMNS = tuple(k for k in PLAN_PEAK_KEYS if k not in ("failed_at", "failure"))
"""Columns filled from :func:`structures.spatial.peaks.plan_peaks` (SI units, wall time [s]);
its ``failed_at`` and ``failure`` close the row as in a suite of records."""

PAIR_COLUMNS = ("run_id", "pair", "x_file", "y_file", "z_file", "scale", "record_factor",
                "multiplier", "model", "modifier", "duration", "dt", *PLAN_PEAK_COLUMNS,
                "task_time", "status", "reason", "worker", "failure", "failed_at")
"""Columns of the peaks table of a suite of pairs, one row per run: every key of
:data:`structures.spatial.peaks.PLAN_PEAK_KEYS`, and the rest as
:data:`structures.suites.runs.COLUMNS` (``pair`` and the component files for ``record`` and
``record_file``; ``z_file`` empty for a pair without a vertical)."""


def plan_fingerprint(config: BuildingConfig) -> str:
    """A 12-hex-digit hash of everything in a building file with a ``[plan]`` table that
    changes a run in plan: :func:`structures.suites.runs.config_fingerprint` and the plan."""
    plan = {f.name: getattr(config.plan, f.name) for f in fields(config.plan)}
    payload = {"building": config_fingerprint(config),
               "plan": {k: v.tolist() if hasattr(v, "tolist") else v for k, v in plan.items()}}
    text = json.dumps(payload, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:12]


def truncated_pair(pair: GroundMotionPair, duration: float) -> GroundMotionPair:
    """The first ``duration`` seconds of every component of a pair [s] (all of it when the
    pair is shorter)."""
    return pair if duration >= pair.duration else pair.truncated(duration)


@dataclass(frozen=True)
class PairRunSpec(SuiteRun):
    """One run of a suite of pairs.

    Parameters
    ----------
    pair : str
        The pair's name (unique in its suite).
    x_file, y_file : str
        The horizontal component files (x and y of the plan).
    z_file : str or None
        The vertical component file (positive up), if any.
    digests : tuple of str
        sha256 of each component file's bytes, x, y (and z)
        (:func:`structures.suites.runs.file_digest`).
    read_dt : float or None
        Time step of one-column text records [s] (the manifest's ``dt``).
    units : str or None
        Units of files whose header states none (the manifest's ``units``).
    model : str
        Friction model, ``"precise"``, ``"simplified"`` or ``"constant"``.
    record_factor : float
        Per-pair scale factor (e.g. RotD100 to a target spectrum) [-].
    multiplier : float
        Suite-wide multiplier of the pair factor [-]; the run's scale is their product.
    modifier : float
        Property modifier on the friction coefficient [-]
        (:func:`structures.suites.runs.modified_bearing`).
    duration : float or None
        Keep only the first ``duration`` seconds of the pair [s] (None: all of it).
    dt : float or None
        Requested analysis step [s] (None: the building file's, else the pair's).
    settings : str
        :func:`plan_fingerprint` of the building.
    """

    pair: str
    x_file: str
    y_file: str
    z_file: str | None
    digests: tuple[str, ...]
    read_dt: float | None
    units: str | None
    model: str
    record_factor: float = 1.0
    multiplier: float = 1.0
    modifier: float = 1.0
    duration: float | None = None
    dt: float | None = None
    settings: str = ""

    @property
    def files(self) -> tuple[str, ...]:
        """The component files, x, y (and z)."""
        return (self.x_file, self.y_file) + (() if self.z_file is None else (self.z_file,))

    @cached_property
    def run_id(self) -> str:
        """Stable id: ``<pair>_x<scale>_<model>_m<modifier>-<hash>``, e.g.
        ``CHY023_x1.5_precise_m1-3f9a2c1b07``. The hash covers the components' bytes and
        file names (not their folder), the reading, the exact scale and modifier, the
        truncation, the step and the building with its plan."""
        key: dict[str, Any] = {f.name: getattr(self, f.name) for f in fields(self)}
        for name in ("x_file", "y_file", "z_file"):
            key[name] = None if key[name] is None else Path(key[name]).name
        return self._run_id(self.pair, key)

    def row(self) -> dict[str, Any]:
        """The peaks-table row of this run before it runs (peaks and status empty)."""
        row: dict[str, Any] = dict.fromkeys(PAIR_COLUMNS)
        row.update(run_id=self.run_id, pair=self.pair, x_file=Path(self.x_file).name,
                   y_file=Path(self.y_file).name,
                   z_file=None if self.z_file is None else Path(self.z_file).name,
                   scale=self.scale, record_factor=self.record_factor,
                   multiplier=self.multiplier, model=self.model, modifier=self.modifier,
                   duration=self.duration)
        return row

    # The interface the Dask side asks of a run (structures.suites.tasks).

    @property
    def source(self) -> str:
        """The key of the run's ground motion, the pair's name: the runs of one pair share a
        read and a Dask task."""
        return self.pair

    def read(self) -> GroundMotionPair:
        """The run's pair, unscaled and untruncated (raises if it cannot be read: a missing
        or unreadable component, components of different steps or lengths)."""
        from groundmotions.pairs import read_pair

        return read_pair(self.x_file, self.y_file, self.z_file, name=self.pair,
                         dt=self.read_dt, units=self.units)

    def execute(self, motion: GroundMotionPair | None, config: BuildingConfig,
                time_limit: float | None = None, max_steps: int = DEFAULT_MAX_STEPS,
                ) -> tuple[dict[str, Any], bytes | None]:
        """:func:`execute_pair_run` of this run."""
        return execute_pair_run(self, motion, config, time_limit, max_steps)


def execute_pair_run(spec: PairRunSpec, motion: GroundMotionPair | None,
                     config: BuildingConfig, time_limit: float | None = None,
                     max_steps: int = DEFAULT_MAX_STEPS) -> tuple[dict[str, Any], bytes | None]:
    """Compute one run of a suite of pairs (the work of a Dask task).

    Parameters
    ----------
    spec : PairRunSpec
        What to run.
    motion : GroundMotionPair or None
        The pair read from the spec's files (unscaled, untruncated), or None to read it here.
    config : BuildingConfig
        The building file, with a ``[plan]`` table.
    time_limit : float, optional
        Wall-clock limit of the run's integration [s]: past it the run fails with the reason
        ``"timeout after N s: ..."``.
    max_steps : int
        Refuse a run of more steps: it fails with the reason, before anything is allocated.

    Returns
    -------
    row : dict
        The peaks-table row (:data:`PAIR_COLUMNS`; every key of
        :func:`structures.spatial.peaks.plan_peaks`): status ``"done"``, or ``"failed"``
        with the ``reason`` (any exception, e.g. a pair that cannot be read, or a run that
        stopped early, whose peaks up to then are kept), the ``failure`` kind and the time
        ``failed_at`` [s].
    data : bytes or None
        The result as netCDF (:data:`structures.suites.runs.NETCDF_ENGINE`), None for a
        failed run.
    """
    from structures.spatial.analysis import run_spatial
    from structures.spatial.peaks import plan_peaks

    start = time.perf_counter()
    row = spec.row() | {"worker": f"{socket.gethostname()}:{os.getpid()}"}
    try:
        pair = spec.read() if motion is None else motion
        if spec.duration is not None:
            pair = truncated_pair(pair, spec.duration)
        if spec.scale != 1.0:
            pair = pair.scaled(spec.scale)
        step = analysis_step(spec.dt if spec.dt is not None else config.dt, pair.dt)
        # as structures.run(config, pair): each bearing carries its gravity share
        bearing = dataclasses.replace(modified_bearing(config, spec.model, spec.modifier),
                                      axial_load=None)
        result = run_spatial(config.spatial_building(), bearing, pair, config.integrator,
                             dt=step, time_limit=time_limit, max_steps=max_steps)
        row.update(plan_peaks(result), dt=float(result.attrs["dt"]))
        if not result.attrs["success"]:
            row["task_time"] = time.perf_counter() - start
            kind = failure_kind({"failure": row["failure"]})
            reason = f"run stopped early: {result.attrs['message']}"
            if kind == "timeout":
                reason = (f"timeout after {time_limit:g} s: the run was stopped at t = "
                          f"{row['failed_at']:.6g} s of the pair (its peaks are those up "
                          "to then)")
            return spec.failure(reason, row, kind), None
        result.attrs.update(building=config.name, run_id=spec.run_id, pair=spec.pair,
                            x_file=row["x_file"], y_file=row["y_file"],
                            z_file=row["z_file"] or "", scale=spec.scale,
                            property_modifier=spec.modifier,
                            building_fingerprint=spec.settings)
        data = bytes(result.to_netcdf(engine=NETCDF_ENGINE))
    except Exception as error:  # any failure is this run's, reported, and the suite goes on
        row["task_time"] = time.perf_counter() - start
        return spec.failure(f"{type(error).__name__}: {error}", row), None
    row.update(status="done", task_time=time.perf_counter() - start, failure="")
    return row, data
