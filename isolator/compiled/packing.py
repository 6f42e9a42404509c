"""The Python side of the compiled element: a bearing and its reference elements packed into the
arrays of :mod:`isolator.compiled.element`, and back (the element's errors in the reference's
words, the plate temperature field). The engine of a building asks here whether a bearing has a
compiled form and never looks at the friction or heating classes itself."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import CapacityExceeded
from isolator.bearing import AxialLoadHistory, DCFPBearing, trial_failure
from isolator.compiled import element as E
from isolator.compiled import kernels
from isolator.compiled import layout as L
from isolator.compiled import plate as P
from isolator.compiled.layout import pack_ptv
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine
from isolator.monitor_grid import GridHeating

__all__ = ["CompiledBearings", "pack_bearings", "plate_field", "trial_error",
           "unsupported_reason"]


class CompiledBearings(NamedTuple):
    """The bearings of a building as the compiled element's arrays.

    Attributes
    ----------
    parameters : ndarray, shape (n_b, PARAMETERS_SIZE)
        One row per bearing (:mod:`isolator.compiled.element`'s ``X`` ...: position [m],
        gravity load [N], multiplicity, the codes of the restoring law and friction model ...).
    ptv : ndarray, shape (n_b, len(PTV_PARAMETERS))
        The friction constants of each bearing (:func:`isolator.compiled.layout.pack_ptv`).
    committed, heat : ndarray, shape (n_b, STATE_SIZE), and PlateHeat
        The elements' committed states at rest; the plates' zero heat histories.
    """

    parameters: np.ndarray
    ptv: np.ndarray
    committed: np.ndarray
    heat: P.PlateHeat


def unsupported_reason(bearing: DCFPBearing) -> str | None:
    """Why the compiled element cannot stand for ``bearing``, or None when it can."""
    if isinstance(bearing.axial_load, AxialLoadHistory):
        return "the axial load varies in time"
    if bearing.restoring not in ("linear", "spherical"):
        return f"the restoring law {bearing.restoring!r} is unknown to it"
    friction = bearing.friction
    if type(friction) is ConstantFriction:
        return None
    if type(friction) is not PTVFriction:
        return f"the friction model {type(friction).__name__} is unknown to it"
    if friction.heating is not None and type(friction.heating) not in (MonitorLine, CentrePoint):
        return f"the heating layout {type(friction.heating).__name__} is unknown to it"
    return None


def _pair(value) -> tuple[float, float]:
    """(x, y) of a state's vector, or (value, 0.0) of a scalar (one direction)."""
    array = np.atleast_1d(np.asarray(value, dtype=float))
    return (float(array[0]), float(array[1]) if array.size > 1 else 0.0)


def _committed_row(state) -> np.ndarray:
    """A reference element's committed state (``BearingState``) as a row."""
    row = np.zeros(E.STATE_SIZE)
    row[E.TIME] = state.time
    row[[E.UX, E.UY]], row[[E.VX, E.VY]] = _pair(state.displacement), _pair(state.velocity)
    row[[E.FX, E.FY]], row[[E.FFX, E.FFY]] = _pair(state.force), _pair(state.friction_force)
    row[[E.ZX, E.ZY]] = _pair(state.z)
    row[E.MU], row[E.TEMPERATURE] = state.mu, state.temperature
    row[E.HEAT_FLUX], row[E.AXIAL_LOAD] = state.heat_flux, state.axial_load
    return row


def pack_bearings(bearing: DCFPBearing, elements: Sequence, positions: np.ndarray,
                  multiplicity: np.ndarray, gravity: np.ndarray,
                  constant_load: bool) -> CompiledBearings:
    """The compiled element's arrays for the bearings of a building at rest.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing of every position (its own axial load is not read).
    elements : sequence of BearingElement
        The model's reference elements at rest, one per row (for the heating's constants and
        the first committed rows).
    positions, multiplicity, gravity : ndarray, shape (n_b, 2), (n_b,), (n_b,)
        Each row's plan position [m], the identical bearings it stands for, and the axial
        load of each at rest [N] (as in :class:`structures.compiled.view.EngineView`).
    constant_load : bool
        The axial loads never change (no overturning, no vertical record): the pressure
        factor of Eq. 7 is then evaluated once per bearing, to the same bits.
    """
    friction = bearing.friction
    n_b = len(elements)
    rows = np.zeros((n_b, E.PARAMETERS_SIZE))
    rows[:, E.X], rows[:, E.Y] = positions[:, 0], positions[:, 1]
    rows[:, E.GRAVITY], rows[:, E.MULTIPLICITY] = gravity, multiplicity
    rows[:, E.YIELD_DISPLACEMENT] = bearing.yield_displacement
    rows[:, E.CONTACT_AREA] = bearing.contact_area
    if math.isinf(bearing.effective_radius):
        rows[:, E.RESTORING_LAW] = E.FLAT
    else:
        rows[:, E.RESTORING_LAW] = E.SPHERICAL if bearing.restoring == "spherical" else E.LINEAR
        rows[:, E.EFFECTIVE_RADIUS] = bearing.effective_radius
    rows[:, E.ORIENTATION], rows[:, E.N_ACROSS] = np.nan, 1.0
    rates, weights, points = np.ones(1), np.zeros(1), 1
    ptv = np.tile(pack_ptv({}), (n_b, 1))
    if isinstance(friction, ConstantFriction):
        rows[:, E.FRICTION_MODEL], rows[:, E.CONSTANT_MU] = E.CONSTANT, friction.mu
        rows[:, E.INITIAL_TEMPERATURE] = friction.initial_temperature
    else:
        rows[:, E.INITIAL_TEMPERATURE] = friction.thermal.initial_temperature
        rows[:, E.FRICTION_MODEL] = E.COLD_PTV
        state = elements[0].friction_state
        heating = state.heating
        if heating is not None:
            grid = isinstance(heating, GridHeating)
            plate = grid or heating.average_over_contact
            rows[:, E.FRICTION_MODEL] = E.PLATE_PTV if plate else E.CENTRE_PTV
            rows[:, E.MIN_LAG] = heating.kernel.min_lag
            rows[:, E.FLUX_COEFFICIENT] = heating.coefficient
            if grid:
                rows[:, E.N_ACROSS] = heating.n_points
                if heating.layout.orientation is not None:
                    rows[:, E.ORIENTATION] = math.radians(heating.layout.orientation)
            elif plate:  # the monitor line in one direction: one row across, e1 along x
                rows[:, E.ORIENTATION] = 0.0
            rates, weights = heating.kernel.rates, heating.kernel.weights
            points = heating.n_points * int(rows[0, E.N_ACROSS]) if plate else 1
        ptv[:] = state.parameters
        if constant_load and state.parameters[L.USE_PRESSURE]:  # mu_t0 gamma(p) once
            cold = state.parameters.copy()
            cold[L.USE_VELOCITY] = 0.0
            for b in range(n_b):
                ptv[b, L.MU_T0] = kernels.cold_friction(
                    cold, float(gravity[b]) / bearing.contact_area, 0.0)[0]
            ptv[:, L.USE_PRESSURE] = 0.0
    committed = np.array([_committed_row(element.committed) for element in elements])
    heat = P.new_plate_heating(n_b, points, np.asarray(rates), np.asarray(weights))
    return CompiledBearings(rows, ptv, committed, heat)


def trial_error(element, status: int, displacement: tuple[float, float],
                axes: tuple[float, float], value: float, time: float) -> CapacityExceeded:
    """The reference ``element``'s error, a ``CapacityExceeded`` the run ends with
    (:func:`isolator.bearing.trial_failure`), for a trial the compiled one could not evaluate.

    ``status`` is ``LEFT_MONITOR_LINE``, ``STEP_BELOW_MIN_LAG`` or ``BEYOND_RADIUS``;
    ``displacement`` the trial's (x, y) [m], ``axes`` its frame's e1 (precise model), ``value``
    its step and ``time`` its time [s]. Raises the reference's ``ValueError`` for a step below
    the heating kernel's shortest lag.
    """
    heating = getattr(element.friction_state, "heating", None)
    if status == E.STEP_BELOW_MIN_LAG:
        heating.factors(value) if isinstance(heating, GridHeating) else heating.prepare(value)
    bearing = element.bearing
    detail = (f"at the effective radius {bearing.effective_radius!r} m of the "
              "spherical law")
    if status == E.LEFT_MONITOR_LINE:
        on_plate = np.asarray(displacement) / bearing.friction.surfaces
        try:
            if isinstance(heating, GridHeating):
                heating.window(on_plate, np.array([[axes[0], axes[1]], [-axes[1], axes[0]]]))
            else:
                heating.window(float(on_plate[0]))
        except CapacityExceeded as error:
            detail = str(error)
    return trial_failure(bearing, math.hypot(*displacement), time, detail)


def plate_field(compiled: CompiledBearings) -> tuple[np.ndarray, np.ndarray] | None:
    """The precise model's stored monitor points after a run, in the reference's order of
    storage: positions (n_b, m, 2) [m] on the plate and temperatures (n_b, m) [degC],
    NaN-padded; None for the other friction models."""
    parameters, ptv, heat = compiled.parameters, compiled.ptv, compiled.heat
    if int(parameters[0, E.FRICTION_MODEL]) != E.PLATE_PTV:
        return None
    n_across = int(parameters[0, E.N_ACROSS])
    first, spacing = ptv[0, L.FIRST_POINT], ptv[0, L.SPACING]
    across_first = first if n_across > 1 else 0.0
    coefficient = ptv[0, L.FLUX_COEFFICIENT]
    initial_temperature = float(parameters[0, E.INITIAL_TEMPERATURE])
    marks = heat.marks
    n_b = marks.shape[0]
    chosen = [np.flatnonzero(marks[b] >= 0) for b in range(n_b)]
    size = max((c.size for c in chosen), default=0)
    positions, temperatures = np.full((n_b, size, 2), np.nan), np.full((n_b, size), np.nan)
    for b, points in enumerate(chosen):
        i, k = points // n_across, points % n_across
        order = np.lexsort((k, i, marks[b, points]))
        points, i, k = points[order], i[order], k[order]
        scalars, held = heat.scalars[b], heat.windows[b, P.HELD]
        inside = (i >= held[0]) & (i < held[1]) & (k >= held[2]) & (k < held[3])
        P.field_temperatures(points, inside, scalars[P.HEAT_TIME], initial_temperature,
                             coefficient, heat.rates, heat.weights, heat.states[b],
                             heat.stamps[b], heat.accumulators[b], temperatures[b, :points.size])
        local = np.column_stack([first + spacing * i, across_first + spacing * k])
        e1x, e1y = scalars[P.E1X], scalars[P.E1Y]
        positions[b, :points.size] = local @ np.array([[e1x, e1y], [-e1y, e1x]])
    return positions, temperatures
