"""The two engines of :func:`structures.analysis.run` behind one result: reference and compiled.

``"reference"``
    :func:`structures.integrators.integrate` on :class:`IsolatedShearBuilding` objects: the
    readable specification, one Python call per Newton iteration.
``"compiled"``
    :func:`structures.compiled.integrator.integrate_building`, the same algorithm as one numba
    function; this module packs the model into arrays, runs it and turns its status into the
    reference's result, message or exception.
``"auto"``
    The compiled engine when numba is available and the configuration is one it knows
    (:func:`unsupported` returns None), else the reference.

Both return an :class:`EngineHistory`, from which :func:`structures.analysis.run` builds the
same ``xarray.Dataset``.
"""

from __future__ import annotations

import time as _time
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import CapacityExceeded, TimeLimitExceeded
from isolator.bearing import trial_failure
from isolator.compiled import bearing as cb
from isolator.compiled import kernels
from isolator.compiled.bearing import BEARING_FIELDS
from isolator.compiled.layout import pack_ptv
from isolator.contact_window import window_history
from isolator.friction import ConstantFriction, PTVFriction, PTVFrictionState
from structures.compiled import integrator as compiled
from structures.compiled import workspace
from structures.compiled.choice import ENGINES, choose_engine, select_engine, unsupported
from structures.integrators import HHT, IntegrationResult, Newmark
from structures.isolated_building import IsolatedShearBuilding

__all__ = ["BEARING_FIELDS", "ENGINES", "EngineHistory", "choose_engine", "compiled_history",
           "select_engine", "unsupported", "warm_up", "warm_up_late"]


class EngineHistory(NamedTuple):
    """What an engine hands to the result builder.

    Attributes
    ----------
    result : IntegrationResult
        Time, relative response, iterations, success and message.
    bearing : dict of str to ndarray
        One bearing's committed state at every step, keyed by ``BEARING_FIELDS`` (SI units).
    restoring : ndarray, shape (nt, n)
        Total restoring force (storey springs + all isolators) at every step [N].
    wall_time : float
        Time spent integrating [s], compilation left out.
    engine : str
        ``"reference"`` or ``"compiled"``.
    compile_time : float
        Time spent compiling (or loading from numba's disk cache) before the run [s]; 0.0
        when this process had compiled it already.
    """

    result: IntegrationResult
    bearing: dict[str, np.ndarray]
    restoring: np.ndarray
    wall_time: float
    engine: str
    compile_time: float = 0.0


def _bearing_arrays(model: IsolatedShearBuilding):
    """The bearing packed for the engine: (bearing, ptv, rates, weights, states, heating)."""
    bearing = model.bearing
    friction = bearing.friction
    packed = np.zeros(cb.BEARING_PARAMETERS)
    packed[cb.N_BEARINGS] = model.n_bearings
    packed[cb.YIELD_DISPLACEMENT] = bearing.yield_displacement
    if np.isinf(bearing.effective_radius):
        packed[cb.RESTORING_LAW] = cb.FLAT
    else:
        packed[cb.RESTORING_LAW] = (cb.SPHERICAL if bearing.restoring == "spherical"
                                          else cb.LINEAR)
        packed[cb.EFFECTIVE_RADIUS] = bearing.effective_radius
    load = bearing.axial_load_at(0.0)
    packed[cb.AXIAL_LOAD] = load
    packed[cb.PRESSURE] = load / bearing.contact_area
    packed[cb.INITIAL_MU] = model.element.committed.mu  # as the reference element at rest
    ptv = pack_ptv({})
    rates, weights, states, heating = np.ones(1), np.zeros(1), np.zeros((1, 1)), None
    if isinstance(friction, ConstantFriction):
        packed[cb.FRICTION_MODEL] = cb.CONSTANT
        packed[cb.CONSTANT_MU] = friction.mu
        packed[cb.INITIAL_TEMPERATURE] = friction.initial_temperature
        return packed, ptv, rates, weights, states, heating
    state = model.element.friction_state
    assert isinstance(state, PTVFrictionState)
    heating = state.heating
    code, reference_pressure, rate = friction.factors.kernel_parameters
    values = {
        "initial_temperature": friction.thermal.initial_temperature, "factor_code": code,
        "reference_pressure": reference_pressure, "rate_parameter": rate,
        "mu_t0": friction.mu_t0, "surfaces": float(friction.surfaces),
        **{f"use_{name}": float(name in friction.dependencies)
           for name in ("pressure", "velocity", "temperature")},
    }
    if values["use_pressure"]:  # the pressure is constant: mu_t0 gamma(p) once, bit for bit
        values["mu_t0"] = kernels.cold_friction(code, reference_pressure, rate, friction.mu_t0,
                                                True, False, packed[cb.PRESSURE], 0.0)[0]
        values["use_pressure"] = 0.0
    packed[cb.INITIAL_TEMPERATURE] = friction.thermal.initial_temperature
    packed[cb.SURFACES] = friction.surfaces
    if heating is None:
        packed[cb.FRICTION_MODEL] = cb.COLD_PTV
    else:
        packed[cb.FRICTION_MODEL] = cb.HEATED_PTV
        packed[cb.MIN_LAG] = heating.kernel.min_lag
        packed[cb.FLUX_COEFFICIENT] = heating.coefficient
        values.update(first_point=heating.first_point, spacing=heating.spacing,
                      n_points=heating.n_points, flux_half_width=heating.flux_half_width,
                      average_over_contact=float(heating.average_over_contact),
                      flux_coefficient=heating.coefficient)
        rates = np.ascontiguousarray(heating.kernel.rates, dtype=float)
        weights = np.ascontiguousarray(heating.kernel.weights, dtype=float)
        states = np.zeros((heating.n_points, rates.size))
    return packed, pack_ptv(values), rates, weights, states, heating


def _method_array(method: Newmark | HHT, tolerance: float, max_iterations: int,
                  max_subdivisions: int) -> np.ndarray:
    return np.array([method.gamma, method.beta, method.alpha, tolerance, max_iterations,
                     max_subdivisions], dtype=float)


CHUNK_STEPS = 1024
"""Steps the engine takes between two looks at the clock when a run has a time limit."""


def time_limit_error(limit: float, time: float) -> TimeLimitExceeded:
    """The error of a run past its ``limit`` [s] of wall-clock time, stopped at ``time`` [s]
    of the record (both engines)."""
    return TimeLimitExceeded(f"timeout after {limit:g} s: the integration exceeded its time "
                             f"limit of {limit:g} s (wall clock) at t = {time:.6g} s of the "
                             "record.")


def _model_error(info: np.ndarray, model: IsolatedShearBuilding, heating) -> CapacityExceeded:
    """The error the reference element raises for the engine's error ``info``: a trial the
    bearing's model cannot evaluate (:func:`isolator.bearing.trial_failure`, which ends the
    run), or, for a sub-step below the heat kernel's shortest lag, the reference's
    ``ValueError`` raised here."""
    status = int(info[workspace.STATUS])
    value = float(info[workspace.FAIL_VALUE])
    if status == cb.STEP_BELOW_MIN_LAG:
        heating.prepare(value)
    detail = (f"at the effective radius {model.bearing.effective_radius!r} m of the "
              "spherical law")
    if status == cb.LEFT_MONITOR_LINE:
        try:
            heating.window(value / model.bearing.friction.surfaces)
        except CapacityExceeded as error:
            detail = str(error)
    return trial_failure(model.bearing, value, float(info[workspace.FAIL_TIME]), detail)


def run_in_chunks(function, arguments: tuple, nt: int, start: float,
                  time_limit: float | None, compile_first=None) -> bool:
    """Run a compiled engine (the planar one or the plan one) through the record: in one
    call, or, with a ``time_limit`` [s] from ``start`` (``perf_counter``), in calls of
    ``CHUNK_STEPS`` steps with a look at the clock between them (the same arithmetic: see
    ``integrate_building``'s ``steps``). True when the limit stopped it. ``arguments`` are
    the engine's groups, ``outputs`` (with its ``info``) last; ``compile_first``, if given, is
    called when ``function`` is not compiled yet, so that the limit is the run's own time."""
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
        if int(info[workspace.STATUS]) != cb.SUCCESS:
            return False
        if steps[1] < nt and _time.perf_counter() - start > time_limit:
            return True
    return False


def run_outcome(info: np.ndarray, time: np.ndarray, timed_out: bool, time_limit: float | None,
                tolerance: float, model_error) -> tuple[int, bool, str, float | None, str]:
    """How a compiled run (planar or in plan) ended, from its ``info`` row: ``(last step,
    success, failure kind, failed_at [s] or None, message)``, the reference integrator's.

    ``model_error()`` gives the element's error (a ``CapacityExceeded``) when the status is
    one of the model's (the bearing codes, shared by both engines, beyond ``NOT_CONVERGED``).
    """
    status, last = int(info[workspace.STATUS]), int(info[workspace.LAST_STEP])
    success = status == cb.SUCCESS and not timed_out
    failure, failed_at = "", None
    message = "The integration reached the end of the record."
    if timed_out:
        failure, failed_at = "timeout", float(time[last])
        message = f"Step {last}: {time_limit_error(time_limit, failed_at)}"
    elif not success:
        failed_at = float(time[last + 1])
        if status == cb.NOT_CONVERGED:
            failure, message = "convergence", failure_message(info, tolerance)
        else:
            error = model_error()
            failure, message = error.kind, f"Step {last + 1}: {error}"
    return last, success, failure, failed_at, message


def failure_message(info: np.ndarray, tolerance: float) -> str:
    """The reference integrator's message for a step that did not converge."""
    t_end, h = info[workspace.FAIL_TIME], info[workspace.FAIL_SUBSTEP]
    residual, reference = info[workspace.FAIL_RESIDUAL], info[workspace.FAIL_REFERENCE]
    relative = residual / reference if reference > 0.0 else np.inf
    return (
        f"Step {int(info[workspace.LAST_STEP]) + 1}: Newton iteration did not converge in the "
        f"step to t = {t_end:.6g} s (sub-step of {h:.3g} s after "
        f"{int(info[workspace.FAIL_DEPTH])} halvings): after "
        f"{int(info[workspace.FAIL_ITERATIONS])} iterations the residual norm was "
        f"{residual:.3e} N ({relative:.3e} of the force reference {reference:.3e} N; "
        f"tolerance {tolerance:g})."
    )


def compiled_history(
    model: IsolatedShearBuilding,
    acceleration: np.ndarray,
    dt: float,
    method: Newmark | HHT,
    *,
    tolerance: float,
    max_iterations: int = 25,
    max_subdivisions: int,
    python: bool = False,
    time_limit: float | None = None,
) -> EngineHistory:
    """Run the compiled engine from rest through ``acceleration`` sampled every ``dt``.

    Parameters
    ----------
    model : IsolatedShearBuilding
        A fresh model (its bearing at rest).
    acceleration : ndarray, shape (nt,)
        Ground acceleration [m/s^2].
    dt : float
        Time step [s].
    method : Newmark or HHT
        Integration method.
    tolerance, max_iterations, max_subdivisions
        As :func:`structures.integrators.integrate`.
    python : bool
        Run the Python original of the top-level loop (tests; slow).
    time_limit : float, optional
        Wall-clock limit of the integration [s] (compilation left out): the engine then runs
        ``CHUNK_STEPS`` steps at a time and, past the limit, the run ends with
        ``success=False``, failure ``"timeout"`` and the steps taken so far.

    A trial the bearing's model cannot evaluate (the slider off the monitor line, the
    spherical law's radius) ends the run with ``success=False`` and the reference's message
    (:func:`isolator.bearing.trial_failure`), as the reference does.

    Raises
    ------
    ValueError
        Where the reference element raises: a (sub-)step shorter than the heating kernel's
        shortest lag.
    """
    acceleration = np.ascontiguousarray(acceleration, dtype=float)
    nt = acceleration.size
    n = model.mass_matrix.shape[0]
    time = dt * np.arange(nt)
    bearing, ptv, rates, weights, states, heating = _bearing_arrays(model)
    method_array = _method_array(method, tolerance, max_iterations, max_subdivisions)
    u, v, a = np.empty((nt, n)), np.empty((nt, n)), np.empty((nt, n))
    record, restoring = np.empty((len(BEARING_FIELDS), nt)), np.empty((nt, n))
    iterations, subdivisions = np.zeros((2, nt - 1), dtype=np.int64)
    info = np.zeros(workspace.INFO_SIZE)
    function = compiled.integrate_building
    if python:
        function = getattr(function, "py_func", function)
    matrices = workspace.Model(*(np.ascontiguousarray(m, dtype=float) for m in (
        model.mass_matrix, model.damping_matrix, model.superstructure_stiffness,
        model.influence)))
    motion = workspace.Motion(acceleration, time)
    settings = workspace.Settings(method_array, bearing, ptv)
    outputs = workspace.Outputs(u, v, a, record, restoring, iterations, subdivisions, info)
    compile_time = 0.0 if python else compile_engine()
    start = _time.perf_counter()
    state = workspace.State(cb.new_heating(rates, weights, states),
                            workspace.new_workspace(n, max_subdivisions))
    timed_out = run_in_chunks(function, (matrices, motion, settings, state, outputs), nt,
                              start, time_limit, warm_up)
    wall = _time.perf_counter() - start
    last, success, failure, failed_at, message = run_outcome(
        info, time, timed_out, time_limit, tolerance,
        lambda: _model_error(info, model, heating))
    kept = slice(0, last + 1)
    absolute = a[kept] + acceleration[kept, None] * np.asarray(model.influence, dtype=float)
    arrays = [time[kept], u[kept], v[kept], a[kept], absolute, iterations[:last],
              subdivisions[:last]]
    for array in arrays:
        array.setflags(write=False)
    result = IntegrationResult(*arrays[:5], success, message, *arrays[5:], method=method,
                               failure=failure, failed_at=failed_at)
    fields = {name: record[i, kept] for i, name in enumerate(BEARING_FIELDS)}
    return EngineHistory(result, fields, restoring[kept], wall, "compiled", compile_time)


_WARMING_UP = False  # set while warm_up runs its own small model through the engine


def compile_engine() -> float:
    """Compile the engine (or load it from numba's disk cache) unless this process has it.

    Returns the time it took [s], 0.0 when there was nothing to do (without numba, or compiled
    already). A run calls it before starting its clock, so that ``wall_time`` measures the
    analysis alone and ``compile_time`` the one-off cost.
    """
    function = compiled.integrate_building
    if _WARMING_UP or not hasattr(function, "signatures") or function.signatures:
        return 0.0  # warming up already, plain Python (no numba), or compiled in this process
    return warm_up()


def warm_up_late() -> float:
    """Compile (or load) the parts of the engine its compilation reaches last, for the very
    argument types the engine calls them with; return the time [s].

    In the order :func:`warm_up` needs them: the window moves of the heat history, its sum
    and the friction of the heated model (late in the bearing's trial), then the bearing's
    commit (after the whole Newton step). :mod:`structures.compiled.ahead` has this process
    do them while the second one works through the rest, which then finds them in the cache.
    Every call is made on a resting bearing and changes nothing that matters.
    """
    from isolator.compiled.kernels import ptv_friction

    start = _time.perf_counter()
    arrays = workspace.new_workspace(1, 0)
    heating = cb.new_heating(np.ones(1), np.zeros(1), np.zeros((1, 1)))
    cb._move_window(heating, 0, 1, 0.0)
    window_history(heating[cb.ACCUMULATOR], heating[cb.OFFSETS], heating[cb.DECAYS][0], 1)
    ptv = pack_ptv({"surfaces": 2.0})
    ptv_friction(0.0, True, ptv, 0.0, 6.0e7, 0.1)
    cb.bearing_commit(np.zeros(cb.BEARING_PARAMETERS), arrays[workspace.COMMITTED],
                      arrays[workspace.TRIAL], heating)  # nothing pending: a copy
    return _time.perf_counter() - start


def warm_up() -> float:
    """Compile (or load from the disk cache) the engine and the kernels; return the time [s]."""
    from isolator.bearing import DCFPBearing
    from structures.shear_building import ModalDamping, ShearBuilding

    global _WARMING_UP
    start = _time.perf_counter()
    building = ShearBuilding(np.array([1.0e5]), np.array([1.0e8]), 1.0e5, ModalDamping())
    # The engine's argument types are the same for every friction model; without heating no
    # heat kernel is fitted (scipy's nnls) before the compilation can start.
    bearing = DCFPBearing(2.0, 0.3, None, PTVFriction(heating=None))
    model = IsolatedShearBuilding(building, bearing)
    _WARMING_UP = True
    try:
        compiled_history(model, np.array([0.0, 1.0, 0.0]), 0.01, Newmark(), tolerance=1e-8,
                         max_subdivisions=2)
    finally:
        _WARMING_UP = False
    return _time.perf_counter() - start
