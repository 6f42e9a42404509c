"""Time-history analysis of a shear building on DCFPB isolators under a ground motion.

:func:`run` builds the dynamic model, integrates it with Newmark or HHT-alpha, records the
isolators' state at every committed step and returns an ``xarray.Dataset`` (time x floor) with
the energy balance. :func:`peaks` reduces it to the numbers engineers look at first.

Two engines give the same result: :func:`reference_history`, the integrator of
:mod:`structures.integrators` on the model objects (the readable specification), and the
compiled engine of :mod:`structures.compiled.engine` (the same algorithm as one numba function,
about a hundred times faster), which ``run`` uses whenever it can.
"""

from __future__ import annotations

import math
import time as _time
from typing import Any

import numpy as np

from dcfpb.common.validation import check_real
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from structures.compiled.engine import (
    BEARING_FIELDS,
    EngineHistory,
    compiled_history,
    select_engine,
    time_limit_error,
)
from structures.integrators import HHT, Newmark, as_method, integrate
from structures.isolated_building import IsolatedShearBuilding
from structures.limits import DEFAULT_MAX_STEPS, building_fields, check_run
from structures.results import response_dataset
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


def reference_history(model: IsolatedShearBuilding, acceleration: np.ndarray, step: float,
                      integrator: str | Newmark | HHT, *, tolerance: float,
                      max_iterations: int = 25, max_subdivisions: int,
                      time_limit: float | None = None) -> EngineHistory:
    """The reference engine: :func:`integrate` on the model, recording the bearing at each
    committed step (the arguments as :func:`structures.compiled.engine.compiled_history`; the
    ``time_limit`` [s] is checked after every step)."""
    nt = acceleration.size
    deadline = np.inf
    record = {name: np.empty(nt) for name in BEARING_FIELDS}
    restoring = np.empty((nt, model.mass_matrix.shape[0]))
    element = model.element

    def on_commit(k: int, t: float, u: np.ndarray, v: np.ndarray, a: np.ndarray) -> None:
        state = element.committed
        for name in BEARING_FIELDS:
            record[name][k] = getattr(state, name)
        restoring[k] = model.superstructure_stiffness @ u
        restoring[k, 0] += model.n_bearings * state.force
        if _time.perf_counter() > deadline:  # ends the run, this step kept
            raise time_limit_error(time_limit, t)

    on_commit(0, 0.0, np.zeros(restoring.shape[1]), None, None)
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
    return EngineHistory(result, record, restoring[:kept], wall, "reference", compile_time)


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
    motion: GroundMotion,
    integrator: str | Newmark | HHT = "newmark",
    *,
    n_bearings: int = 1,
    dt: float | None = None,
    tolerance: float = 1e-8,
    max_subdivisions: int = 6,
    engine: str = "auto",
    floor_spectra: bool = False,
    time_limit: float | None = None,
    max_steps: int = DEFAULT_MAX_STEPS,
):
    """Run a time-history analysis.

    Parameters
    ----------
    building : ShearBuilding
        The superstructure and base slab.
    bearing : DCFPBearing
        One isolator; its axial load becomes W / n_bearings.
    motion : GroundMotion
        Ground acceleration [m/s^2] (scale it first with ``motion.scaled``).
    integrator : {"newmark", "hht"} or Newmark or HHT
        Time integration method (default Newmark average acceleration).
    n_bearings : int
        Identical bearings sharing the weight.
    dt : float, optional
        Analysis step [s], at most the record's (finer steps interpolate the record linearly).
        Default: the record's step divided into the fewest equal parts of at most 5 ms
        (:func:`default_step`).
    tolerance, max_subdivisions
        Passed to :func:`structures.integrators.integrate`.
    engine : {"auto", "compiled", "reference"}
        ``"reference"``: :func:`structures.integrators.integrate` on the model objects (the
        specification); ``"compiled"``: the same algorithm as one numba function
        (:mod:`structures.compiled.integrator`); ``"auto"`` (default): the compiled engine whenever
        numba is available and it supports the configuration. Both give the same Dataset.
    floor_spectra : bool
        Add the 5 %-damped floor response spectra and the record's spectrum
        (:func:`structures.floor_spectra.with_floor_spectra`: ``floor_spectrum``,
        ``ground_spectrum``, coordinate ``period``).
    time_limit : float, optional
        Wall-clock limit of the integration [s] (compiling the engine is not counted). Past
        it the run ends as a failure (``failure = "timeout"``) with the histories so far:
        the reference engine looks at the clock after every step, the compiled one after
        every ``CHUNK_STEPS`` steps (:func:`structures.compiled.engine.compiled_history`).
        Default: none.
    max_steps : int
        Most time steps the run may take (default 2,000,000, see :mod:`isolator.limits`):
        a longer run, or one whose histories would not fit in the memory available, is
        refused before anything is allocated (:func:`structures.limits.check_run`).

    Returns
    -------
    xarray.Dataset
        Dimensions ``time``, ``floor`` (0 = base slab, 1..n) and ``storey`` (1..n); variables
        ``displacement``, ``velocity``, ``absolute_acceleration`` (time, floor),
        ``storey_drift``, ``storey_shear`` (time, storey), ``isolator_displacement``,
        ``isolator_force`` (all bearings), ``base_shear``, ``friction_force``, ``mu``,
        ``temperature``, ``heat_flux``, ``ground_acceleration`` and the energies
        ``energy_input``, ``energy_kinetic``, ``energy_damping``, ``energy_strain``,
        ``energy_friction``, ``energy_error`` (time). Attributes describe the model and the
        run, including ``success``, ``message``, ``energy_balance_error`` and ``engine``.

        A run that fails ends there, for every friction model and both engines alike: a
        bearing beyond its ``displacement_capacity`` (a committed step past it, or a trial
        the precise model's monitor line no longer covers), a step that does not converge,
        or the ``time_limit``. The Dataset then holds the histories up to the failure, with
        ``success = 0``, the reason in ``message``, ``failure`` (``"capacity"``,
        ``"convergence"``, ``"timeout"``, ``"model"``), ``failed_at`` [s] and
        ``peaks_up_to_failure = 1`` (:func:`structures.results.response_dataset`).
    """

    check_run(motion, default_step(motion.dt) if dt is None else dt,
              building_fields(building.n_storeys), max_steps=max_steps)
    model = IsolatedShearBuilding(building, bearing, n_bearings)
    acceleration, step = resampled_record(motion, dt)
    method = as_method(integrator)
    if select_engine(engine, model, method) == "compiled":
        history = compiled_history(model, acceleration, step, method, tolerance=tolerance,
                                   max_subdivisions=max_subdivisions, time_limit=time_limit)
    else:
        history = reference_history(model, acceleration, step, method, tolerance=tolerance,
                                    max_subdivisions=max_subdivisions, time_limit=time_limit)
    result, record = history.result, history.bearing
    kept = result.time.size
    n = model.n_bearings
    isolator = {"force": n * record["force"], "friction_force": n * record["friction_force"],
                "mu": record["mu"], "temperature": record["temperature"],
                "heat_flux": record["heat_flux"]}
    dataset = response_dataset(
        model, motion, step, acceleration[:kept], result.displacement, result.velocity,
        result.absolute_acceleration, isolator, integrator=repr(result.method),
        success=result.success, message=result.message, failure=result.failure,
        failed_at=result.failed_at,
        attrs={"newton_iterations": int(result.iterations.sum()),
               "subdivisions": int(result.subdivisions.sum()),
               "wall_time": history.wall_time, "compile_time": history.compile_time,
               "engine": history.engine},
        restoring=history.restoring,
    )
    if floor_spectra:
        from structures.floor_spectra import with_floor_spectra

        dataset = with_floor_spectra(dataset, motion)
    return dataset


def peaks(result) -> dict[str, Any]:
    """Peak responses of a run (SI units) and the run's bookkeeping.

    The peaks are those of the histories the Dataset holds: for a failed run, up to the
    failure, which the keys ``peaks_up_to_failure`` (bool), ``failed_at`` (time [s], None
    for a run that finished) and ``failure`` (the reason's kind, ``""`` for none) say.
    """
    roof = result["absolute_acceleration"].isel(floor=-1)
    return {
        "peak_isolator_displacement": float(np.abs(result["isolator_displacement"]).max()),
        "peak_base_shear": float(np.abs(result["base_shear"]).max()),
        "peak_roof_acceleration": float(np.abs(roof).max()),
        "peak_storey_drift": float(np.abs(result["storey_drift"]).max()),
        "max_temperature": float(result["temperature"].max()),
    } | run_bookkeeping(result)


def run_bookkeeping(result) -> dict[str, Any]:
    """What every run's peaks carry besides the peaks (a planar run's or one in plan):
    ``energy_balance_error``, ``steps``, ``wall_time`` [s], ``peaks_up_to_failure``,
    ``failed_at`` [s] (None for a run that finished) and ``failure`` (``""`` for none)."""
    failed = not result.attrs["success"]
    failed_at = result.attrs.get("failed_at")
    return {
        "energy_balance_error": float(result.attrs["energy_balance_error"]),
        "steps": int(result.attrs["steps"]),
        "wall_time": float(result.attrs["wall_time"]),
        "peaks_up_to_failure": failed,
        "failed_at": float(failed_at) if failed and failed_at is not None else None,
        "failure": str(result.attrs.get("failure", "error" if failed else "")),
    }
