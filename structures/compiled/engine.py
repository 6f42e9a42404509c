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
    arguments, bearings = _loop_arguments(view, acceleration, step, method, tolerance,
                                          max_iterations, max_subdivisions)
    function = compiled.run
    if python:  # its callees compiled: bound here, as they are for the compiled loop
        function = getattr(compiled.integrate, "py_func", compiled.integrate)
        bind_callees(*_separate_calls()[:-1])
    compile_time = 0.0 if python else compile_engine()
    start = _time.perf_counter()
    time, outputs = arguments[1].time, arguments[-1]
    u, v, a, record, restoring = outputs[:5]
    iterations, subdivisions, info = outputs[5:]
    timed_out = run_in_chunks(function, arguments, time.shape[0], start, time_limit, warm_up)
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


def _loop_arguments(view: EngineView, acceleration: np.ndarray, step: float,
                    method: Newmark | HHT, tolerance: float, max_iterations: int,
                    max_subdivisions: int) -> tuple[tuple, object]:
    """The loop's groups for a run of :func:`compiled_run` from rest, ``(model, motion,
    settings, state, outputs)``, and the packed bearings (``acceleration``: C-ordered)."""
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
    workspace = W.new_workspace(n, acceleration.shape[1], n_b, max_subdivisions)
    workspace[W.COMMITTED][:] = bearings.committed
    state = W.State(bearings.heat, workspace)
    settings = W.Settings(method_array, bearings.parameters, bearings.ptv, flags)
    return (_model_group(view), W.Motion(acceleration, time), settings, state,
            outputs), bearings


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
    function = compiled.run
    if _WARMING_UP or not hasattr(function, "signatures") or function.signatures:
        return 0.0  # warming up already, plain Python (no numba), or compiled in this process
    return warm_up()


def _parts(stage: str) -> list:
    """The engine's compiled functions as (function, example arguments of the engine's types)
    by ``stage``: ``"window"`` the plate's window moves, ``"friction"`` the friction of a
    trial, ``"step"`` the step's factors (which the trials and the commit both inline),
    ``"trials"`` the bearings' trials, ``"linear"`` the Newton matrix's pieces, ``"solve"``
    the first sample's solve and the plate field, ``"commit"`` the commit, ``"loop"`` the
    loop's own pieces and the loop (:func:`_loop_parts`)."""
    if stage == "loop":
        return _loop_parts()
    from isolator.compiled import kernels, plate
    from structures.compiled import lapack, linear

    heat = plate.new_plate_heating(1, 1, np.ones(1), np.zeros(1))
    states, rows, square = np.zeros((1, E.STATE_SIZE)), np.zeros((3, 1)), np.zeros((1, 1))
    parameters = np.zeros((1, E.PARAMETERS_SIZE))
    pivots, vector = np.zeros(1, dtype=np.int32), np.zeros(1)
    window = heat.windows[0, plate.HELD]
    return {
        "window": [
            (plate.move_window, (0, 1, window, window, 0.0, heat.rates, heat.states[0],
                                 heat.stamps[0], heat.accumulators[0], heat.offsets[0],
                                 heat.cache_keys, heat.cache_values, heat.cache_state,
                                 heat.marks[0], heat.pending[0])),
            (plate.reanchor_window, (0, 1, window, 0.0, heat.rates, heat.states[0],
                                     heat.stamps[0], heat.offsets[0], heat.cache_keys,
                                     heat.cache_values, heat.cache_state))],
        "friction": [(kernels.initial_friction, (parameters[0], 1.0, 1.0)),
                     (kernels.ptv_friction, (0.0, True, parameters[0], 0.0, 1.0, 1.0))],
        "step": [(plate.prepare_step, (1.0, 1.0, 1.0, heat.rates, heat.weights, heat.factors,
                                       heat.decays, heat.slots, heat.table))],
        "trials": [(E.set_trials, (0.0, np.zeros((1, E.MOTION_SIZE)), parameters, parameters,
                                   states, states, *heat))],
        "linear": [
            (linear.woodbury, (square, rows, rows, 1, 1.0, 1.0, vector, vector, rows)),
            (linear.effective_inverse, (1.0, square, square, square, 1.0, 1.0, 1.0, square,
                                        square, square, pivots)),
            (linear.add_block, (rows, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0)),
            (linear.interpolate, (1.0, vector, vector))],
        "solve": [
            (lapack.solve, (square, vector, vector, square, pivots)),
            (plate.field_temperatures, (np.zeros(1, dtype=np.int64),
                                        np.zeros(1, dtype=np.bool_), 1.0, 1.0, 1.0, heat.rates,
                                        heat.weights, heat.states[0], heat.stamps[0],
                                        heat.accumulators[0], vector))],
        "commit": [(plate.advance_window, (vector, vector, square, 1.0)),
                   (E.commit_trials, (parameters, states, states, *heat))]}[stage]


def _separate_calls() -> list:
    """The functions the engine calls as code of their own (:mod:`isolator.compiled.linking`),
    as their stand-ins, each after those it calls."""
    return [E.MOVE_WINDOW, E.REANCHOR_WINDOW, E.INITIAL_FRICTION, E.PTV_FRICTION,
            compiled.WOODBURY, compiled.EFFECTIVE_INVERSE, compiled.SOLVE, compiled.SET_TRIALS,
            compiled.COMMIT_TRIALS, compiled.START, compiled.REPORT_FAILURE, compiled.INTEGRATE]


def _loop_parts() -> list:
    """The loop's own pieces as :func:`_parts` gives the others (its start and failure
    report), with the loop's arguments."""
    view, acceleration, step, method = _warm_up_run(constant=True)
    (model, motion, settings, state, outputs), _ = _loop_arguments(
        view, np.array(acceleration, dtype=float, order="C"), step, method, 1e-8, 25, 2)
    ws = state.workspace
    dofs = ws[W.DOFS]
    return [
        (compiled.start, (1, 1, model.mass, model.influence, motion.ground,
                          ws[W.MASS_INFLUENCE], dofs[W.P_C], dofs[W.Q_C], dofs[W.LOAD],
                          dofs[W.A_C], ws[W.LAPACK_WORK], ws[W.PIVOTS])),
        (compiled.report_failure, (outputs.info, ws[W.TRIAL], 1, 1, 1.0, 1.0, 1, 1, 1.0, 1.0)),
        (compiled.integrate, (model, motion, settings, state, outputs,
                              np.zeros(2, dtype=np.int64)))]


def _argument_types(function) -> tuple:
    """numba's types of ``function``'s arguments in the engine (from :func:`_parts`)."""
    for stage in ("window", "friction", "step", "trials", "linear", "solve", "commit", "loop"):
        for candidate, arguments in _parts(stage):
            if candidate is function:
                return tuple(_typeof(argument) for argument in arguments)
    raise KeyError(function)


def bind_callees(*calls, placeholder: bool = False) -> float:
    """Bind the functions that the engine calls as code of their own (default: all of them,
    :func:`_separate_calls`, each after those it calls): compiled or loaded, as a process must
    before it compiles or loads their callers; the time [s]. ``placeholder``: stand-ins that
    end the process when called, for those not bound yet, so that a process that compiles for
    numba's cache only need not compile them (it must not run the engine afterwards)."""
    from isolator.compiled.linking import bind, bind_placeholder

    start = _time.perf_counter()
    for call in calls or _separate_calls():
        if hasattr(call, "function"):  # without numba: nothing to bind
            (bind_placeholder if placeholder else bind)(call,
                                                        _argument_types(call.function))
    return _time.perf_counter() - start


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
    """The caller's share of a cold engine (:mod:`structures.compiled.ahead`), compiled (or
    loaded) and bound in this process: the window's moves (then ``shared_done()``), the trial's
    friction, the bearings' trials (:func:`isolator.compiled.element.set_trials`), their
    commit, the first sample's solve and the loop's start and failure report; the time [s]."""
    start = _time.perf_counter()
    bind_callees(E.MOVE_WINDOW)
    if shared_done is not None:
        shared_done()
    bind_callees(E.INITIAL_FRICTION, E.PTV_FRICTION, compiled.SET_TRIALS, E.REANCHOR_WINDOW)
    _compile_parts("commit")
    bind_callees(compiled.COMMIT_TRIALS, compiled.SOLVE, compiled.START,
                 compiled.REPORT_FAILURE)
    _compile_parts("solve")
    return _time.perf_counter() - start


def warm_up_late() -> float:
    """The second process's share of a cold engine, for numba's cache only (this process must
    not run the engine afterwards): the step's factors first (the trials inline them), the
    Newton matrix's pieces and the loop with its entry from Python (:func:`compile_loop`:
    what it calls from the caller's share is bound to placeholders here); the time [s]."""
    start = _time.perf_counter()
    _compile_parts("step")
    bind_callees(compiled.WOODBURY, compiled.EFFECTIVE_INVERSE)
    _compile_parts("linear")
    compile_loop()
    return _time.perf_counter() - start


def _typeof(value):
    """numba's type of an argument as compiled code passes it (integers as int64)."""
    from numba import typeof, types

    if isinstance(value, bool):
        return types.boolean
    if isinstance(value, int):
        return types.int64
    return typeof(value)


def _warm_up_run(constant: bool = False) -> tuple:
    """The warm-up's model and record: ``compiled_run``'s arguments (the engine's argument types
    are the same for every model and friction; without heating no heat kernel is fitted,
    scipy's nnls, before the compilation can start; ``constant``: with constant friction,
    whose packing calls no compiled friction)."""
    from isolator.bearing import DCFPBearing
    from isolator.friction import ConstantFriction, PTVFriction
    from structures.isolated_building import IsolatedShearBuilding
    from structures.shear_building import ModalDamping, ShearBuilding

    building = ShearBuilding(np.array([1.0e5]), np.array([1.0e8]), 1.0e5, ModalDamping())
    friction = ConstantFriction() if constant else PTVFriction(heating=None)
    bearing = DCFPBearing(2.0, 0.3, None, friction)
    model = IsolatedShearBuilding(building, bearing)
    return engine_view(model), np.array([[0.0], [1.0], [0.0]]), 0.01, Newmark()


def compile_loop() -> float:
    """Compile the engine's loop (:func:`structures.compiled.integrator.integrate`) and its
    entry from Python (``run``) for their argument types and write them to numba's cache,
    without running them and without the functions the loop calls as code of their own: those
    this process has not bound yet are bound to placeholders (:func:`bind_callees`), so this
    process must not run the engine afterwards (:mod:`structures.compiled.ahead`); the time
    [s]."""
    start = _time.perf_counter()
    if hasattr(compiled.integrate, "compile"):
        types = _argument_types(compiled.integrate)
        bind_callees(*_separate_calls()[:-1], placeholder=True)
        compiled.integrate.compile(types)
        bind_callees(compiled.INTEGRATE)
        compiled.run.compile(types)
    return _time.perf_counter() - start


def warm_up() -> float:
    """Compile (or load from the disk cache) the engine and the kernels; return the time [s]."""
    global _WARMING_UP
    start = _time.perf_counter()
    view, acceleration, step, method = _warm_up_run()
    bind_callees()
    _WARMING_UP = True
    try:
        compiled_run(view, acceleration, step, method, tolerance=1e-8, max_subdivisions=2)
    finally:
        _WARMING_UP = False
    return _time.perf_counter() - start
