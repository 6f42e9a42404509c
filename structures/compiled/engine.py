"""The Python side of the compiled engine: pack a model's view, run it, unpack its histories.

:func:`compiled_run` runs :func:`structures.compiled.integrator.integrate` on an
:class:`~structures.compiled.view.EngineView` and ends as the reference does: a trial the
element cannot evaluate, or a step that does not converge, ends the run with its message; a
step below the heat kernel's shortest lag raises its ``ValueError``. :func:`compiled_history` is
the same run in the form :func:`structures.analysis.run` reads."""

from __future__ import annotations

import time as _time
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import TimeLimitExceeded
from isolator.compiled import element as E
from isolator.compiled.packing import pack_bearings, plate_field, trial_error
from structures.compiled import integrator as compiled
from structures.compiled import workspace as W
from structures.compiled.choice import ENGINES, choose_engine, select_engine, unsupported
from structures.compiled.view import EngineView, engine_view
from structures.integrators import HHT, IntegrationResult, Newmark
from structures.results import EngineHistory

__all__ = ["CHUNK_STEPS", "ENGINES", "CompiledRun",
           "bearing_fields", "choose_engine", "compile_engine", "compiled_history",
           "compiled_run", "select_engine", "unsupported", "warm_up", "warm_up_early",
           "warm_up_late"]

CHUNK_STEPS = 1024
"""Steps the engine takes between two looks at the clock when a run has a time limit."""


class CompiledRun(NamedTuple):
    """What the compiled engine hands back.

    Attributes
    ----------
    result : IntegrationResult
        Time, relative response, iterations, success and message.
    record, restoring : ndarray
        As :class:`structures.compiled.workspace.Outputs`, over the steps taken (the record's
        fields: :func:`bearing_fields`).
    wall_time, compile_time : float
        Time integrating, and compiling or loading the engine first (0.0: already had) [s].
    plate : tuple of ndarray or None
        :func:`isolator.compiled.packing.plate_field` at the end (precise model only).
    """

    result: IntegrationResult
    record: np.ndarray
    restoring: np.ndarray
    wall_time: float
    compile_time: float
    plate: tuple[np.ndarray, np.ndarray] | None


def bearing_fields(record: np.ndarray) -> dict[str, np.ndarray]:
    """The record of :class:`CompiledRun` by field: ``displacement``, ``force``,
    ``friction_force`` (nt, n_b, 2) and ``mu``, ``temperature``, ``heat_flux``,
    ``axial_load`` (nt, n_b) [SI]."""
    return {name: record[:, :, list(columns)] if len(columns) > 1 else record[:, :, columns[0]]
            for name, columns in E.RECORD_FIELDS}


def time_limit_error(limit: float, time: float) -> TimeLimitExceeded:
    """The error of a run past its ``limit`` [s] of wall-clock time, stopped at ``time`` [s]
    of the record (both engines)."""
    return TimeLimitExceeded(f"timeout after {limit:g} s: the integration exceeded its time "
                             f"limit of {limit:g} s (wall clock) at t = {time:.6g} s of the "
                             "record.")


def run_in_chunks(function, arguments: tuple, nt: int, start: float,
                  time_limit: float | None, compile_first=None) -> bool:
    """Run ``function`` through the record: in one call, or with a ``time_limit`` [s] from
    ``start`` (``perf_counter``) in calls of ``CHUNK_STEPS`` steps, looking at the clock between
    them; True when the limit stopped it. ``arguments``: the engine's groups, ``outputs`` last;
    ``compile_first()`` runs first when ``function`` is not compiled yet."""
    info = arguments[-1].info
    steps = np.array([1, nt if time_limit is None else 1], dtype=np.int64)
    if time_limit is None:
        function(*arguments, steps)
        return False
    if compile_first is not None and hasattr(function, "signatures") and not function.signatures:
        compile_first()
        start = _time.perf_counter()
    while steps[1] < nt:
        steps[0], steps[1] = steps[1], min(int(steps[1]) + CHUNK_STEPS, nt)
        function(*arguments, steps)
        if int(info[W.STATUS]) != E.SUCCESS:
            return False
        if steps[1] < nt and _time.perf_counter() - start > time_limit:
            return True
    return False


def run_outcome(info: np.ndarray, time: np.ndarray, timed_out: bool, time_limit: float | None,
                tolerance: float, model_error) -> tuple[int, bool, str, float | None, str]:
    """How a compiled run ended, from its ``info``: ``(last step, success, failure kind,
    failed_at [s] or None, message)`` as the reference's; ``model_error()`` gives the element's
    error (``CapacityExceeded``) for its status codes (beyond ``NOT_CONVERGED``)."""
    status, last = int(info[W.STATUS]), int(info[W.LAST_STEP])
    success = status == E.SUCCESS and not timed_out
    failure, failed_at = "", None
    message = "The integration reached the end of the record."
    if timed_out:
        failure, failed_at = "timeout", float(time[last])
        message = f"Step {last}: {time_limit_error(time_limit, failed_at)}"
    elif not success:
        failed_at = float(time[last + 1])
        if status == E.NOT_CONVERGED:
            failure, message = "convergence", failure_message(info, tolerance)
        else:
            error = model_error()
            failure, message = error.kind, f"Step {last + 1}: {error}"
    return last, success, failure, failed_at, message


def failure_message(info: np.ndarray, tolerance: float) -> str:
    """The reference integrator's message for a step that did not converge."""
    t_end, h = info[W.FAIL_TIME], info[W.FAIL_SUBSTEP]
    residual, reference = info[W.FAIL_RESIDUAL], info[W.FAIL_REFERENCE]
    relative = residual / reference if reference > 0.0 else np.inf
    return (
        f"Step {int(info[W.LAST_STEP]) + 1}: Newton iteration did not converge in the "
        f"step to t = {t_end:.6g} s (sub-step of {h:.3g} s after "
        f"{int(info[W.FAIL_DEPTH])} halvings): after "
        f"{int(info[W.FAIL_ITERATIONS])} iterations the residual norm was "
        f"{residual:.3e} N ({relative:.3e} of the force reference {reference:.3e} N; "
        f"tolerance {tolerance:g})."
    )


def _model_error(info: np.ndarray, view: EngineView):
    """The reference element's error for the failure in ``info`` (or its ``ValueError``)."""
    b = int(info[W.FAIL_BEARING])
    return trial_error(view.elements[b], int(info[W.STATUS]),
                       (float(info[W.FAIL_UX]), float(info[W.FAIL_UY])),
                       (float(info[W.FAIL_E1X]), float(info[W.FAIL_E1Y])),
                       float(info[W.FAIL_VALUE]), float(info[W.FAIL_TIME]))


def _model_group(view: EngineView) -> W.Model:
    """The building of ``view`` as the engine's ``Model`` group (C-ordered float arrays)."""
    if view.vertical is None:
        vertical = (np.array([0.0, 1.0]), np.zeros(2))
    else:
        vertical = (view.vertical.time, view.vertical.acceleration)
    return W.Model(*(np.array(m, dtype=float, order="C") for m in (
        view.mass, view.damping, view.stiffness, view.influence, view.overturning,
        view.load_du, view.load_dv, *vertical)))


def compiled_run(view: EngineView, acceleration: np.ndarray, step: float,
                 method: Newmark | HHT, *, tolerance: float, max_iterations: int = 25,
                 max_subdivisions: int, time_limit: float | None = None,
                 python: bool = False, with_plate: bool = True) -> CompiledRun:
    """Run the compiled engine from rest through ``acceleration`` sampled every ``step``.

    Parameters
    ----------
    view : EngineView
        The model (:func:`~structures.compiled.view.engine_view` of a fresh one); not changed.
    acceleration : ndarray, shape (nt, c)
        Ground acceleration of the c horizontal components [m/s^2].
    step : float
        Analysis step [s].
    method, tolerance, max_iterations, max_subdivisions
        As :func:`structures.integrators.integrate` (Newmark or HHT).
    time_limit : float, optional
        Wall-clock limit [s], compilation left out: past it the run ends with
        ``success=False``, failure ``"timeout"`` and the steps taken so far.
    python, with_plate : bool
        Run the Python original of the loop (tests; slow); read the precise model's plate
        field at the end (else ``CompiledRun.plate`` is None).

    Raises
    ------
    ValueError
        For a (sub-)step shorter than the heating kernel's shortest lag, as the reference.
    """
    acceleration = np.array(acceleration, dtype=float, order="C")  # writable: one type
    nt, n = acceleration.shape[0], view.mass.shape[0]
    time = step * np.arange(nt)
    bearings = pack_bearings(view.bearing, view.elements, view.positions, view.multiplicity,
                             view.gravity, not view.with_overturning and view.vertical is None)
    method_array = np.array([method.gamma, method.beta, method.alpha, tolerance,
                             max_iterations, max_subdivisions], dtype=float)
    flags = np.array([float(view.level_dofs), float(view.with_overturning),
                      float(view.vertical is not None)])
    n_b = bearings.parameters.shape[0]
    u, v, a = np.empty((nt, n)), np.empty((nt, n)), np.empty((nt, n))
    record, restoring = np.empty((nt, n_b, E.RECORD_SIZE)), np.empty((nt, n))
    iterations, subdivisions = np.zeros((2, nt - 1), dtype=np.int64)
    info = np.zeros(W.INFO_SIZE)
    outputs = W.Outputs(u, v, a, record, restoring, iterations, subdivisions, info)
    function = compiled.integrate
    if python:
        function = getattr(function, "py_func", function)
    compile_time = 0.0 if python else compile_engine()
    start = _time.perf_counter()
    workspace = W.new_workspace(n, acceleration.shape[1], n_b, max_subdivisions)
    workspace[W.COMMITTED][:] = bearings.committed
    state = W.State(bearings.heat, workspace)
    settings = W.Settings(method_array, bearings.parameters, bearings.ptv, flags)
    timed_out = run_in_chunks(function, (_model_group(view), W.Motion(acceleration, time),
                                         settings, state, outputs), nt, start, time_limit,
                              warm_up)
    wall = _time.perf_counter() - start
    last, success, failure, failed_at, message = run_outcome(
        info, time, timed_out, time_limit, tolerance, lambda: _model_error(info, view))
    kept = slice(0, last + 1)
    absolute = a[kept] + acceleration[kept] @ np.asarray(view.influence, dtype=float).T
    arrays = [time[kept], u[kept], v[kept], a[kept], absolute, iterations[:last],
              subdivisions[:last]]
    for array in arrays:
        array.setflags(write=False)
    result = IntegrationResult(*arrays[:5], success, message, *arrays[5:], method=method,
                               failure=failure, failed_at=failed_at)
    return CompiledRun(result, record[kept], restoring[kept], wall, compile_time,
                       plate_field(bearings) if with_plate else None)


def compiled_history(model, acceleration: np.ndarray, dt: float, method: Newmark | HHT, *,
                     tolerance: float, max_iterations: int = 25, max_subdivisions: int,
                     python: bool = False, time_limit: float | None = None) -> EngineHistory:
    """:func:`compiled_run` of a fresh isolated building through ``acceleration`` [m/s^2], (nt,)
    in one direction or (nt, 2) in plan, every ``dt`` [s], as the history
    :func:`structures.analysis.run` reads (the other arguments as :func:`compiled_run`)."""
    acceleration = np.asarray(acceleration, dtype=float)
    run = compiled_run(engine_view(model), acceleration.reshape(acceleration.shape[0], -1), dt,
                       method, tolerance=tolerance, max_iterations=max_iterations,
                       max_subdivisions=max_subdivisions, time_limit=time_limit, python=python)
    return EngineHistory(run.result, bearing_fields(run.record), run.restoring, run.wall_time,
                         "compiled", run.compile_time, run.plate)


_WARMING_UP = False  # set while warm_up runs its own small model through the engine


def compile_engine() -> float:
    """Compile the engine (or load it from numba's disk cache) unless this process has it;
    the time [s], 0.0 with nothing to do. A run calls it before starting its clock."""
    function = compiled.integrate
    if _WARMING_UP or not hasattr(function, "signatures") or function.signatures:
        return 0.0  # warming up already, plain Python (no numba), or compiled in this process
    return warm_up()


def _parts(stage: str) -> list:
    """The engine's callees as (function, example arguments of the engine's types), by
    ``stage``: ``"window"`` and ``"step"`` the plate functions the bearings' trials and their
    commit both call (the window's move, the step's factors), ``"trials"`` the trials,
    ``"linear"`` the Newton matrix's pieces and the plate field, ``"commit"`` the commit."""
    from isolator.compiled import plate
    from structures.compiled import lapack, linear

    heat = plate.new_plate_heating(1, 1, np.ones(1), np.zeros(1))
    states, rows, square = np.zeros((1, E.STATE_SIZE)), np.zeros((3, 1)), np.zeros((1, 1))
    parameters = np.zeros((1, E.PARAMETERS_SIZE))
    pivots, vector = np.zeros(1, dtype=np.int32), np.zeros(1)
    window = heat.windows[0, plate.HELD]
    return {
        "step": [(plate.prepare_step, (1.0, 1.0, 1.0, heat.rates, heat.weights, heat.factors,
                                       heat.decays, heat.slots, heat.table))],
        "window": [
            (plate.move_window, (0, 1, window, window, 0.0, heat.rates, heat.states[0],
                                 heat.stamps[0], heat.accumulators[0], heat.offsets[0],
                                 heat.cache_keys, heat.cache_values, heat.cache_state,
                                 heat.marks[0], heat.pending[0]))],
        "trials": [(E.set_trials, (0.0, np.zeros((1, E.MOTION_SIZE)), parameters, parameters,
                                   states, states, *heat))],
        "linear": [
            (linear.woodbury, (square, rows, rows, 1, 1.0, 1.0, vector, vector, rows)),
            (linear.effective_inverse, (1.0, square, square, square, 1.0, 1.0, 1.0, square,
                                        square, square, pivots)),
            (linear.add_block, (rows, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0)),
            (linear.interpolate, (1.0, vector, vector)),
            (lapack.solve, (square, vector, vector, square, pivots)),
            (plate.field_temperatures, (np.zeros(1, dtype=np.int64),
                                        np.zeros(1, dtype=np.bool_), 1.0, 1.0, 1.0, heat.rates,
                                        heat.weights, heat.states[0], heat.stamps[0],
                                        heat.accumulators[0], vector))],
        "commit": [(E.commit_trials, (parameters, states, states, *heat))]}[stage]


def _compile_parts(*stages: str) -> float:
    """Compile (or load) the :func:`_parts` of ``stages`` for the engine's argument types,
    without running them; the time it took [s]."""
    start = _time.perf_counter()
    for stage in stages:
        for function, arguments in _parts(stage):
            if hasattr(function, "compile"):
                function.compile(tuple(_typeof(argument) for argument in arguments))
    return _time.perf_counter() - start


def warm_up_early(shared_done: Callable[[], None] | None = None) -> float:
    """Compile (or load) the bearings' trials (:func:`isolator.compiled.element.set_trials`
    and its callees) for the engine's argument types, the window's move that the commit shares
    with them first (``shared_done()`` is called once it is in the cache); the time [s]. See
    :mod:`structures.compiled.ahead`: the second process meanwhile compiles the step's factors
    (:func:`warm_up_late`), which the trials call only later."""
    start = _time.perf_counter()
    _compile_parts("window")
    if shared_done is not None:
        shared_done()
    _compile_parts("trials")
    return _time.perf_counter() - start


def warm_up_late(before_commit: Callable[[], None] | None = None) -> float:
    """Compile (or load) the engine's callees other than the bearings' trials, the step's
    factors first; the time [s]. ``before_commit()`` is called before the commit
    (:func:`isolator.compiled.element.commit_trials`), whose window's move
    :func:`warm_up_early` compiles first: a second process waits there for it to be in the
    cache rather than compile it too."""
    start = _time.perf_counter()
    _compile_parts("step", "linear")
    if before_commit is not None:
        before_commit()
    _compile_parts("commit")
    return _time.perf_counter() - start


def _typeof(value):
    """numba's type of an argument as compiled code passes it (integers as int64)."""
    from numba import typeof, types

    if isinstance(value, int):
        return types.int64
    return typeof(value)


def warm_up() -> float:
    """Compile (or load from the disk cache) the engine and the kernels; return the time [s]."""
    from isolator.bearing import DCFPBearing
    from isolator.friction import PTVFriction
    from structures.isolated_building import IsolatedShearBuilding
    from structures.shear_building import ModalDamping, ShearBuilding

    global _WARMING_UP
    start = _time.perf_counter()
    building = ShearBuilding(np.array([1.0e5]), np.array([1.0e8]), 1.0e5, ModalDamping())
    # The engine's argument types are the same for every model and friction; without heating
    # no heat kernel is fitted (scipy's nnls) before the compilation can start.
    bearing = DCFPBearing(2.0, 0.3, None, PTVFriction(heating=None))
    model = IsolatedShearBuilding(building, bearing)
    _WARMING_UP = True
    try:
        compiled_run(engine_view(model), np.array([[0.0], [1.0], [0.0]]), 0.01, Newmark(),
                     tolerance=1e-8, max_subdivisions=2)
    finally:
        _WARMING_UP = False
    return _time.perf_counter() - start
