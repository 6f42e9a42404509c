"""Time-history analysis of a shear building on DCFPB isolators under a ground motion: one
record for a building in one direction, a pair (x, y and optionally a vertical) for a building
in plan.

:func:`run` builds the dynamic model (:class:`~structures.isolated_building.IsolatedShearBuilding`),
integrates it with Newmark or HHT-alpha, records every bearing position at each committed step
and returns an ``xarray.Dataset`` (:func:`structures.results.response_dataset`) with the energy
balance. :func:`peaks` reduces it to the numbers engineers look at first.

Two engines give the same result: :func:`reference_history`, the integrator of
:mod:`structures.integrators` on the model objects (the readable specification), and the
compiled engine of :mod:`structures.compiled` (the same algorithm as one numba function),
which ``run`` uses whenever it can.
"""

from __future__ import annotations

import math
import time as _time
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from structures.compiled.engine import compiled_history, select_engine, time_limit_error
from structures.integrators import HHT, Newmark, as_method, integrate
from structures.isolated_building import IsolatedShearBuilding
from structures.limits import DEFAULT_MAX_STEPS, building_fields, check_run
from structures.results import (
    BEARING_RECORD,
    EngineHistory,
    response_dataset,
    temperature_fields,
)
from structures.shear_building import ShearBuilding

DEFAULT_MAX_STEP = 0.005
"""Largest default analysis step [s]: the step of the example building file, at which the
bearing's EDC and temperature have converged to 0.1 % and 0.2 degC
(tests/verification/test_time_step_convergence.py) and the building agrees with OpenSees."""


def default_step(record_dt: float) -> float:
    """The default analysis step: the record's, divided into the fewest equal parts of at most
    :data:`DEFAULT_MAX_STEP` (0.02 s -> 0.005 s; 0.005 s and finer records keep theirs) [s]."""
    return record_dt / math.ceil(record_dt / DEFAULT_MAX_STEP - 1e-6)


def resampled_record(motion: GroundMotion, dt: float | None) -> tuple[np.ndarray, float]:
    """The record on the analysis step ``dt`` (None: :func:`default_step`): the record's own,
    or a finer one by linear interpolation (exact for the piecewise-linear record the
    integrators assume)."""
    if dt is None:
        dt = default_step(motion.dt)
    if abs(dt - motion.dt) <= 1e-12 * motion.dt:
        return np.asarray(motion.acceleration, dtype=float), float(motion.dt)
    check_real(dt, "dt", "run", low=0.0, high=motion.dt, low_open=True)
    n = int(np.floor(motion.duration / dt + 1e-9)) + 1
    t = dt * np.arange(n)
    return np.interp(t, motion.time, motion.acceleration), float(dt)


def ground_record(motion: GroundMotion | GroundMotionPair,
                  dt: float | None) -> tuple[np.ndarray, float]:
    """The horizontal ground acceleration on the analysis step (:func:`resampled_record`):
    shape (nt,) for a record, (nt, 2) for a pair [m/s^2]; and the step [s]."""
    if isinstance(motion, GroundMotionPair):
        x, step = resampled_record(motion.x, dt)
        y, _ = resampled_record(motion.y, step)
        return np.column_stack([x, y]), step
    return resampled_record(motion, dt)


def reference_history(model: IsolatedShearBuilding, acceleration: np.ndarray, step: float,
                      integrator: str | Newmark | HHT, *, tolerance: float,
                      max_iterations: int = 25, max_subdivisions: int,
                      time_limit: float | None = None) -> EngineHistory:
    """The reference engine: :func:`integrate` on the model, recording every bearing position
    at each committed step (the arguments as
    :func:`structures.compiled.engine.compiled_history`; the ``time_limit`` [s] is checked
    after every step)."""
    nt, positions = acceleration.shape[0], len(model.elements)
    record = {name: np.zeros((nt, positions, size) if size else (nt, positions))
              for name, size in BEARING_RECORD.items()}
    restoring = np.zeros((nt, model.mass_matrix.shape[0]))
    dofs = model.level_dofs
    # sum_b T_b^T (m_b F_b) as one product: the (n_b 2) forces times (n_b 2, dofs)
    transposed = np.asarray(model.transformations)[..., :dofs].reshape(-1, dofs)
    multiplicity = np.asarray(model.multiplicity, dtype=float)[:, None]
    columns = [(name, record[name], size) for name, size in BEARING_RECORD.items()]
    deadline = np.inf

    def on_commit(k: int, t: float, u: np.ndarray, *_: np.ndarray) -> None:
        for i, state in enumerate(model.committed_states()):
            for name, values, size in columns:
                value = getattr(state, name)
                if size and isinstance(value, float):  # one direction: x only
                    values[k, i, 0] = value
                else:
                    values[k, i] = value
        restoring[k] = model.superstructure_stiffness @ u
        restoring[k, :dofs] += (record["force"][k] * multiplicity).ravel() @ transposed
        if _time.perf_counter() > deadline:  # ends the run, this step kept
            raise time_limit_error(time_limit, t)

    on_commit(0, 0.0, np.zeros(restoring.shape[1]))
    compile_time = compile_kernels()
    start = _time.perf_counter()
    if time_limit is not None:
        deadline = start + time_limit
    result = integrate(model, acceleration, step, integrator, tolerance=tolerance,
                       max_iterations=max_iterations, max_subdivisions=max_subdivisions,
                       on_commit=on_commit)
    wall = _time.perf_counter() - start
    kept = result.time.size
    record = {name: values[:kept] for name, values in record.items()}
    return EngineHistory(result, record, restoring[:kept], wall, "reference", compile_time,
                         temperature_fields(model))


def compile_kernels() -> float:
    """Compile the friction and heating kernels the reference element calls, unless this
    process has them; the time it took [s] (kept out of the run's ``wall_time``)."""
    from isolator.compiled.kernels import ptv_trial, warm_up

    if not getattr(ptv_trial, "signatures", True):  # numba, nothing compiled yet
        start = _time.perf_counter()
        warm_up()
        return _time.perf_counter() - start
    return 0.0


def run(
    building: ShearBuilding,
    bearing: DCFPBearing,
    motion: GroundMotion | GroundMotionPair,
    integrator: str | Newmark | HHT = "newmark",
    *,
    n_bearings: int | None = None,
    dt: float | None = None,
    tolerance: float = 1e-8,
    max_subdivisions: int = 6,
    engine: str = "auto",
    floor_spectra: bool = False,
    time_limit: float | None = None,
    max_steps: int = DEFAULT_MAX_STEPS,
    overturning: bool = True,
    grid_orientation: float | None = None,
):
    """Run a time-history analysis.

    Parameters
    ----------
    building : ShearBuilding
        The superstructure and base slab; with a plan, the building in plan.
    bearing : DCFPBearing
        The bearing of every position; its axial load becomes the building's weight shared by
        the bearings (see :class:`~structures.isolated_building.IsolatedShearBuilding`).
    motion : GroundMotion or GroundMotionPair
        Ground acceleration [m/s^2] (scale it first with ``motion.scaled``): one record for a
        building in one direction; a pair (x and y of the plan, optionally a vertical z,
        positive up) for a building in plan.
    integrator : {"newmark", "hht"} or Newmark or HHT
        Time integration method (default Newmark average acceleration).
    n_bearings : int, optional
        Identical bearings sharing the weight in one direction (default 1); in plan, the
        plan's positions (leave it out).
    dt : float, optional
        Analysis step [s], at most the record's (finer steps interpolate the record linearly).
        Default: the record's step divided into the fewest equal parts of at most 5 ms
        (:func:`default_step`).
    tolerance, max_subdivisions
        Passed to :func:`structures.integrators.integrate`.
    engine : {"auto", "compiled", "reference"}
        ``"reference"``: :func:`structures.integrators.integrate` on the model objects (the
        specification); ``"compiled"``: the same algorithm as one numba function;
        ``"auto"`` (default): the compiled engine whenever numba is available and it supports
        the configuration. Both give the same Dataset.
    floor_spectra : bool
        Add the 5 %-damped floor response spectra per direction and the record's spectrum
        (:func:`structures.floor_spectra.with_floor_spectra`: ``floor_spectrum``,
        ``ground_spectrum``, coordinate ``period``).
    time_limit : float, optional
        Wall-clock limit of the integration [s] (compiling the engine is not counted). Past
        it the run ends as a failure (``failure = "timeout"``) with the histories so far:
        the reference engine looks at the clock after every step, the compiled one after
        every ``CHUNK_STEPS`` steps. Default: none.
    max_steps : int
        Most time steps the run may take (default 2,000,000, see :mod:`isolator.limits`):
        a longer run, or one whose histories would not fit in the memory available, is
        refused before anything is allocated (:func:`structures.limits.check_run`).
    overturning : bool
        In plan, load the bearings with the overturning moment of the floors' inertia forces
        (needs the plan's ``storey_heights``). Default True.
    grid_orientation : float, optional
        The precise model's monitor grid orientation in plan [deg] (None: follows the motion).

    Returns
    -------
    xarray.Dataset
        See :func:`structures.results.response_dataset`. Attributes describe the model and the
        run, including ``success``, ``message``, ``energy_balance_error`` and ``engine``.

        A run that fails ends there, for every friction model and both engines alike: a
        bearing beyond its ``displacement_capacity`` (a committed step past it, or a trial
        the precise model's monitor points no longer cover), a step that does not converge,
        or the ``time_limit``. The Dataset then holds the histories up to the failure, with
        ``success = 0``, the reason in ``message``, ``failure`` (``"capacity"``,
        ``"convergence"``, ``"timeout"``, ``"model"``), ``failed_at`` [s] and
        ``peaks_up_to_failure = 1``.
    """
    pair = isinstance(motion, GroundMotionPair)
    if not isinstance(building, ShearBuilding):
        raise InputTypeError(f"The 'building' parameter of run must be a ShearBuilding. Got "
                             f"{building!r} instead.")
    if not pair and not isinstance(motion, GroundMotion):
        raise InputTypeError(f"The 'motion' parameter of run must be a GroundMotion or a "
                             f"GroundMotionPair. Got {motion!r} instead.")
    if pair != (building.plan is not None):
        has = "has a" if building.plan is not None else "has no"
        raise InputError(
            "A building in plan runs under a pair of records (GroundMotionPair) and a building "
            f"in one direction under one record: the building {has} plan and the motion is "
            f"{'a pair' if pair else 'one record'}.")
    first = motion.x if pair else motion
    fields = building_fields(building.n_storeys, building.level_dofs,
                             len(building.bearing_positions))
    check_run(first, default_step(first.dt) if dt is None else dt, fields, max_steps=max_steps)
    model = IsolatedShearBuilding(building, bearing, n_bearings, overturning=overturning,
                                  vertical=motion.z if pair else None,
                                  grid_orientation=grid_orientation)
    acceleration, step = ground_record(motion, dt)
    method = as_method(integrator)
    options = {"tolerance": tolerance, "max_subdivisions": max_subdivisions,
               "time_limit": time_limit}
    if select_engine(engine, model, method) == "compiled":
        history = compiled_history(model, acceleration, step, method, **options)
    else:
        history = reference_history(model, acceleration, step, method, **options)
    result = history.result
    dataset = response_dataset(
        model, motion, step, acceleration[:result.time.size], result.displacement,
        result.velocity, result.absolute_acceleration, history.bearings,
        integrator=repr(result.method), success=result.success, message=result.message,
        failure=result.failure, failed_at=result.failed_at, restoring=history.restoring,
        plate=history.plate,
        attrs={"newton_iterations": int(result.iterations.sum()),
               "subdivisions": int(result.subdivisions.sum()),
               "wall_time": history.wall_time, "compile_time": history.compile_time,
               "engine": history.engine})
    if floor_spectra:
        from structures.floor_spectra import with_floor_spectra

        dataset = with_floor_spectra(dataset, motion)
    return dataset


def _resultant(values: np.ndarray) -> np.ndarray:
    """The length of the vectors along the last axis (the value itself for one direction)."""
    return np.abs(values[..., 0]) if values.shape[-1] == 1 else np.hypot(values[..., 0],
                                                                          values[..., 1])


def peaks(result) -> dict[str, Any]:
    """Peak responses of a run (SI units) and the run's bookkeeping.

    The peaks are those of the histories the Dataset holds: for a failed run, up to the
    failure, which the keys ``peaks_up_to_failure`` (bool), ``failed_at`` (time [s], None
    for a run that finished) and ``failure`` (the reason's kind, ``""`` for none) say.

    Returns
    -------
    dict
        ``peak_isolator_displacement`` [m], the largest (resultant) displacement of any
        bearing; ``peak_base_shear`` [N], resultant; ``max_temperature`` [degC], the highest
        contact temperature of any bearing; in one direction ``peak_roof_acceleration``
        [m/s^2], absolute, and ``peak_storey_drift`` [m], over the storeys; in plan instead
        ``peak_roof_acceleration_x``/``_y`` and ``peak_storey_drift_x``/``_y``, and
        ``peak_centre_displacement`` [m] (the base slab at the plan's reference point),
        ``corner_bearing`` (the index of the bearing with the largest displacement) and
        ``peak_base_rotation`` [rad]; then ``energy_balance_error``, ``steps``,
        ``wall_time`` [s], ``peaks_up_to_failure``, ``failed_at`` [s], ``failure``.
    """
    reach = _resultant(result["bearing_displacement"].values).max(axis=0)
    roof = np.abs(result["absolute_acceleration"].isel(floor=-1).values).max(axis=0)
    drift = np.abs(result["storey_drift"].values).max(axis=(0, 1))
    values: dict[str, Any] = {"peak_isolator_displacement": float(reach.max())}
    base_shear = float(_resultant(result["base_shear"].values).max())
    if result.sizes["direction"] == 1:
        values |= {"peak_base_shear": base_shear, "peak_roof_acceleration": float(roof[0]),
                   "peak_storey_drift": float(drift[0])}
    else:
        values |= {
            "peak_centre_displacement": float(
                _resultant(result["displacement"].isel(floor=0).values).max()),
            "corner_bearing": int(np.argmax(reach)),
            "peak_base_shear": base_shear,
            "peak_roof_acceleration_x": float(roof[0]),
            "peak_roof_acceleration_y": float(roof[1]),
            "peak_storey_drift_x": float(drift[0]),
            "peak_storey_drift_y": float(drift[1]),
            "peak_base_rotation": float(np.abs(result["rotation"].isel(floor=0).values).max()),
        }
    values["max_temperature"] = float(result["temperature"].max())
    failed = not result.attrs["success"]
    failed_at = result.attrs.get("failed_at")
    return values | {
        "energy_balance_error": float(result.attrs["energy_balance_error"]),
        "steps": int(result.attrs["steps"]),
        "wall_time": float(result.attrs["wall_time"]),
        "peaks_up_to_failure": failed,
        "failed_at": float(failed_at) if failed and failed_at is not None else None,
        "failure": str(result.attrs.get("failure", "error" if failed else "")),
    }
