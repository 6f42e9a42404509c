"""The Python side of the plan engine: pack a building in plan, run it, unpack its histories.

:func:`plan_history` returns what :func:`structures.spatial.analysis.spatial_history` returns
(the :class:`~structures.integrators.IntegrationResult`, the bearings' histories of
``BEARING_RECORD``, the total restoring force and the wall time), from
:func:`~structures.compiled.plan.integrator.integrate_plan`, plus the precise model's plate
temperature field (:func:`plate_field`, as :func:`structures.spatial.results.plate_fields`
reads it from the reference's elements). The failure contract is the reference's: a trial the
element cannot evaluate ends the run with its message, a step below the heat kernel's shortest
lag raises its ``ValueError``, a time limit is looked at every ``CHUNK_STEPS`` steps.
"""

from __future__ import annotations

import math
import time as _time
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import CapacityExceeded
from isolator.bearing import trial_failure
from isolator.monitor_grid import GridHeating
from isolator.compiled import kernels
from isolator.compiled import layout as L
from isolator.compiled.bidirectional import bearing as E
from isolator.compiled.bidirectional import grid as G
from isolator.compiled.layout import pack_ptv
from isolator.friction import ConstantFriction, PTVFriction
from structures.compiled.engine import choose_engine, run_in_chunks, run_outcome
from structures.compiled.plan import integrator as compiled
from structures.compiled.plan import workspace as W
from structures.compiled.workspace import (
    FAIL_TIME,
    FAIL_VALUE,
    STATUS,
)
from structures.integrators import HHT, IntegrationResult, Newmark

__all__ = ["PlanHistory", "compile_plan_engine", "plan_history", "plan_unsupported"]


class PlanHistory(NamedTuple):
    """What the plan engine hands to the Dataset builder.

    Attributes
    ----------
    result : IntegrationResult
        Time, relative response, iterations, success and message.
    record : dict of str to ndarray
        The bearings' committed states, ``BEARING_RECORD`` fields, shape (nt, n_b, ...).
    restoring : ndarray, shape (nt, n)
        Total restoring force [N, N m].
    wall_time : float
        Time spent integrating [s], compilation left out.
    plate : tuple of ndarray or None
        The precise model's plate field (positions (n_b, m, 2) [m], temperatures (n_b, m)
        [degC], NaN-padded), None for the other models.
    compile_time : float
        Time spent compiling or loading the engine before the run [s].
    """

    result: IntegrationResult
    record: dict[str, np.ndarray]
    restoring: np.ndarray
    wall_time: float
    plate: tuple[np.ndarray, np.ndarray] | None
    compile_time: float = 0.0


def plan_unsupported(model: object, method: object) -> str | None:
    """Why the plan engine cannot run ``model`` with ``method``, or None when it can."""
    from structures.spatial.isolated import SpatialIsolatedBuilding

    if type(model) is not SpatialIsolatedBuilding:
        return f"the model is a {type(model).__name__}, not a SpatialIsolatedBuilding"
    if not isinstance(method, Newmark | HHT):
        return f"the method {method!r} is not a Newmark or HHT instance"
    bearing = model.bearing
    if bearing.restoring not in ("linear", "spherical"):
        return f"the restoring law {bearing.restoring!r} is unknown to it"
    if type(bearing.friction) not in (ConstantFriction, PTVFriction):
        return f"the friction model {type(bearing.friction).__name__} is unknown to it"
    return None


def _heating(model):
    """The heating object of the first element (all bearings share the layout), or None."""
    return getattr(model.elements[0].friction_state, "heating", None)


def _bearing_arrays(model) -> tuple[np.ndarray, np.ndarray, tuple]:
    """(bearings, ptv, heat) of the engine for ``model`` at rest."""
    bearing, friction = model.bearing, model.bearing.friction
    coordinates = model.building.plan.bearing_coordinates
    rows = np.zeros((model.n_bearings, E.PLATE_PARAMETERS))
    rows[:, E.X], rows[:, E.Y] = coordinates[:, 0], coordinates[:, 1]
    rows[:, E.GRAVITY] = model.gravity_shares
    rows[:, E.YIELD_DISPLACEMENT] = bearing.yield_displacement
    rows[:, E.CONTACT_AREA] = bearing.contact_area
    if math.isinf(bearing.effective_radius):
        rows[:, E.RESTORING_LAW] = E.FLAT
    else:
        rows[:, E.RESTORING_LAW] = E.SPHERICAL if bearing.restoring == "spherical" else E.LINEAR
        rows[:, E.EFFECTIVE_RADIUS] = bearing.effective_radius
    rows[:, E.ORIENTATION] = np.nan
    rates, weights, points = np.ones(1), np.zeros(1), 1
    if isinstance(friction, ConstantFriction):
        rows[:, E.FRICTION_MODEL], rows[:, E.CONSTANT_MU] = E.CONSTANT, friction.mu
        rows[:, E.INITIAL_TEMPERATURE] = friction.initial_temperature
        ptv = pack_ptv({})
    else:
        code, reference_pressure, rate = friction.factors.kernel_parameters
        values = {"initial_temperature": friction.thermal.initial_temperature,
                  "factor_code": code, "reference_pressure": reference_pressure,
                  "rate_parameter": rate, "mu_t0": friction.mu_t0,
                  "surfaces": float(friction.surfaces),
                  **{f"use_{name}": float(name in friction.dependencies)
                     for name in ("pressure", "velocity", "temperature")}}
        rows[:, E.INITIAL_TEMPERATURE] = friction.thermal.initial_temperature
        rows[:, E.SURFACES] = friction.surfaces
        heating = _heating(model)
        rows[:, E.FRICTION_MODEL] = E.COLD_PTV
        if heating is not None:
            grid = isinstance(heating, GridHeating)
            rows[:, E.FRICTION_MODEL] = E.GRID_PTV if grid else E.CENTRE_PTV
            rows[:, E.MIN_LAG] = heating.kernel.min_lag
            rows[:, E.FLUX_COEFFICIENT] = heating.coefficient
            if grid and heating.layout.orientation is not None:
                rows[:, E.ORIENTATION] = math.radians(heating.layout.orientation)
            values.update(first_point=heating.first_point, spacing=heating.spacing,
                          n_points=heating.n_points, flux_half_width=heating.flux_half_width,
                          average_over_contact=float(grid),
                          flux_coefficient=heating.coefficient)
            rates, weights = heating.kernel.rates, heating.kernel.weights
            points = heating.n_points**2 if grid else 1
        ptv = pack_ptv(values)
    heat = E.new_plate_heating(model.n_bearings, points, rates, weights)
    return rows, ptv, heat


def _committed_rows(model) -> np.ndarray:
    """The elements' committed states at rest as the engine's rows."""
    rows = np.zeros((model.n_bearings, E.PLATE_STATE_SIZE))
    for b, state in enumerate(model.committed_states()):
        rows[b, E.TIME] = state.time
        rows[b, [E.UX, E.UY]], rows[b, [E.VX, E.VY]] = state.displacement, state.velocity
        rows[b, [E.FX, E.FY]], rows[b, [E.FFX, E.FFY]] = state.force, state.friction_force
        rows[b, [E.ZX, E.ZY]] = state.z
        rows[b, E.MU], rows[b, E.TEMPERATURE] = state.mu, state.temperature
        rows[b, E.HEAT_FLUX], rows[b, E.AXIAL_LOAD] = state.heat_flux, state.axial_load
    return rows


def plate_field(heat: tuple, ptv: np.ndarray,
                initial_temperature: float) -> tuple[np.ndarray, np.ndarray]:
    """The grid's stored points after the run, in the reference's order of storage: positions
    (n_b, m, 2) [m] on the plate and temperatures (n_b, m) [degC], NaN-padded."""
    n, first, spacing = int(ptv[L.N_POINTS]), ptv[L.FIRST_POINT], ptv[L.SPACING]
    coefficient = ptv[L.FLUX_COEFFICIENT]
    marks = heat[G.MARKS]
    n_b = marks.shape[0]
    chosen = [np.flatnonzero(marks[b] >= 0) for b in range(n_b)]
    size = max((c.size for c in chosen), default=0)
    positions, temperatures = np.full((n_b, size, 2), np.nan), np.full((n_b, size), np.nan)
    for b, points in enumerate(chosen):
        i, k = points // n, points % n
        order = np.lexsort((k, i, marks[b, points]))
        points, i, k = points[order], i[order], k[order]
        scalars, held = heat[G.SCALARS][b], heat[G.WINDOWS][b, E.HELD]
        inside = (i >= held[0]) & (i < held[1]) & (k >= held[2]) & (k < held[3])
        G.field_temperatures(b, points, inside, scalars[E.HEAT_TIME], initial_temperature,
                             coefficient, heat, temperatures[b, :points.size])
        local = first + spacing * np.column_stack([i, k]).astype(float)
        e1x, e1y = scalars[E.E1X], scalars[E.E1Y]
        positions[b, :points.size] = local @ np.array([[e1x, e1y], [-e1y, e1x]])
    return positions, temperatures


def _model_error(info: np.ndarray, model):
    """The reference's error for the engine's failure ``info`` (ValueError raised here)."""
    status, b = int(info[STATUS]), int(info[W.FAIL_BEARING])
    element = model.elements[b]
    heating = element.friction_state.heating if status != E.BEYOND_RADIUS else None
    if status == E.STEP_BELOW_MIN_LAG:
        value = float(info[FAIL_VALUE])
        heating.factors(value) if isinstance(heating, GridHeating) else heating.prepare(value)
    u = np.array([info[W.FAIL_UX], info[W.FAIL_UY]])
    detail = (f"at the effective radius {model.bearing.effective_radius!r} m of the "
              "spherical law")
    if status == E.LEFT_MONITOR_LINE:
        on_plate = u / model.bearing.friction.surfaces
        axes = np.array([[info[W.FAIL_E1X], info[W.FAIL_E1Y]],
                         [-info[W.FAIL_E1Y], info[W.FAIL_E1X]]])
        try:
            heating.window(on_plate, axes)
        except CapacityExceeded as error:
            detail = str(error)
    return trial_failure(element.bearing, math.hypot(*u), float(info[FAIL_TIME]), detail)


def plan_history(model, acceleration: np.ndarray, step: float, method: Newmark | HHT, *,
                 tolerance: float, max_iterations: int = 25, max_subdivisions: int,
                 time_limit: float | None = None, python: bool = False) -> PlanHistory:
    """Run the plan engine from rest through ``acceleration`` (x, y) sampled every ``step``.

    Parameters
    ----------
    model : SpatialIsolatedBuilding
        A fresh model (its bearings at rest); it is not changed.
    acceleration : ndarray, shape (nt, 2)
        Ground acceleration (x, y) on the analysis steps [m/s^2].
    step : float
        Analysis step [s].
    method : Newmark or HHT
        Integration method.
    tolerance, max_iterations, max_subdivisions
        As :func:`structures.integrators.integrate`.
    time_limit : float, optional
        Wall-clock limit of the integration [s] (compilation left out): past it the run ends
        with ``success=False``, failure ``"timeout"`` and the steps taken so far.
    python : bool
        Run the Python original of the loop (tests; slow).

    Raises
    ------
    ValueError
        Where the reference element raises: a (sub-)step shorter than the heating kernel's
        shortest lag.
    """
    acceleration = np.array(acceleration, dtype=float, order="C")  # writable: one type
    nt, n = acceleration.shape[0], model.mass_matrix.shape[0]
    time = step * np.arange(nt)
    bearings, ptv, heat = _bearing_arrays(model)
    method_array = np.array([method.gamma, method.beta, method.alpha, tolerance,
                             max_iterations, max_subdivisions], dtype=float)
    vertical = model.vertical
    if vertical is None:
        vertical_arrays = (np.array([0.0, 1.0]), np.zeros(2))
    else:
        vertical_arrays = (vertical.time, vertical.acceleration)
    # the model's overturning arrays, as its axial_loads and restoring_force use them
    matrices = W.PlanModel(*(np.array(m, dtype=float, order="C") for m in (
        model.mass_matrix, model.damping_matrix, model.superstructure_stiffness,
        model.influence, model.overturning_matrix, model.load_du, model.load_dv,
        *vertical_arrays)))
    flags = np.array([float(model.overturning), float(vertical is not None)])
    n_b = model.n_bearings
    u, v, a = np.empty((nt, n)), np.empty((nt, n)), np.empty((nt, n))
    record, restoring = np.empty((nt, n_b, E.PLATE_STATE_SIZE)), np.empty((nt, n))
    iterations, subdivisions = np.zeros((2, nt - 1), dtype=np.int64)
    info = np.zeros(W.PLAN_INFO_SIZE)
    outputs = W.PlanOutputs(u, v, a, record, restoring, iterations, subdivisions, info)
    function = compiled.integrate_plan
    if python:
        function = getattr(function, "py_func", function)
    compile_time = 0.0 if python else compile_plan_engine()
    start = _time.perf_counter()
    workspace = W.new_plan_workspace(n, n_b, max_subdivisions)
    workspace[W.COMMITTED][:] = _committed_rows(model)
    state = W.PlanState(heat, workspace)
    timed_out = run_in_chunks(function, (matrices, W.PlanMotion(acceleration, time),
                                         W.PlanSettings(method_array, bearings, ptv, flags),
                                         state, outputs), nt, start, time_limit,
                              warm_up_plan)
    wall = _time.perf_counter() - start
    last, success, failure, failed_at, message = run_outcome(
        info, time, timed_out, time_limit, tolerance, lambda: _model_error(info, model))
    kept = slice(0, last + 1)
    absolute = a[kept] + acceleration[kept] @ np.asarray(model.influence, dtype=float).T
    arrays = [time[kept], u[kept], v[kept], a[kept], absolute, iterations[:last],
              subdivisions[:last]]
    for array in arrays:
        array.setflags(write=False)
    result = IntegrationResult(*arrays[:5], success, message, *arrays[5:], method=method,
                               failure=failure, failed_at=failed_at)
    fields = {name: record[kept][:, :, list(columns)] if len(columns) > 1
              else record[kept][:, :, columns[0]] for name, columns in E.PLATE_FIELDS}
    plate = None
    if int(bearings[0, E.FRICTION_MODEL]) == E.GRID_PTV:
        plate = plate_field(heat, ptv, float(bearings[0, E.INITIAL_TEMPERATURE]))
    return PlanHistory(result, fields, restoring[kept], wall, plate, compile_time)


_WARMING_UP = False


def compile_plan_engine() -> float:
    """Compile (or load from numba's disk cache) the plan engine unless this process has it;
    the time it took [s] (0.0 without numba or when compiled already)."""
    function = compiled.integrate_plan
    if _WARMING_UP or not kernels.COMPILED or function.signatures:
        return 0.0
    return warm_up_plan()


def warm_up_plan() -> float:
    """Compile (or load) the plan engine on a small building; return the time [s]."""
    from isolator.bearing import DCFPBearing
    from structures.shear_building import ModalDamping, ShearBuilding
    from structures.spatial.building import SpatialBuilding
    from structures.spatial.isolated import SpatialIsolatedBuilding
    from structures.spatial.plan import Plan

    global _WARMING_UP
    start = _time.perf_counter()
    building = ShearBuilding(np.array([1.0e5]), np.array([1.0e8]), 1.0e5, ModalDamping())
    plan = Plan([[-1.0, -1.0], [1.0, -1.0], [0.0, 1.0]], dimensions=(2.0, 2.0),
                storey_heights=3.0)
    bearing = DCFPBearing(2.0, 0.3, None, PTVFriction(heating=None))
    model = SpatialIsolatedBuilding(SpatialBuilding(building, plan), bearing)
    _WARMING_UP = True
    try:
        plan_history(model, np.zeros((3, 2)), 0.01, Newmark(), tolerance=1e-8,
                     max_subdivisions=2)
    finally:
        _WARMING_UP = False
    return _time.perf_counter() - start


def select_plan_engine(engine: str, model: object, method: object) -> str:
    """The engine of :func:`structures.spatial.analysis.run_spatial`:
    :func:`structures.compiled.engine.choose_engine` on :func:`plan_unsupported`."""
    return choose_engine(engine, plan_unsupported(model, method), "run_spatial")
