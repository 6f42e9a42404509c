"""The bidirectional DCFPB element, its 2D friction and heating as arrays, for the compiled
engine of the building in plan.

:func:`plate_trial` and :func:`plate_commit` are ``BidirectionalElement.set_trial`` (with the
trial's axial load) and ``commit`` of :mod:`isolator.bidirectional.element` for bearing ``b`` of a
building, its state a row of the ``committed`` / ``trial`` arrays (``TIME`` ... ``AXIAL_LOAD``,
then the trial's tangents and pending heat), operation for operation: the isotropic return map,
the linear / spherical / flat restoring law, uplift (no load: no force, no heat), and the
friction of :mod:`isolator.bidirectional.friction` through the planar kernels (``cold_friction``,
``solve_friction``, ``heated_window``, ``ptv_friction``; the step factors of
:func:`isolator.heating.step_factors`, exact for every step size):

- constant (Eq. 8): mu_c, no heat;
- PTV without heating: Eq. 7 at the initial temperature, with the trial's pressure;
- simplified (Eq. 6): the centre point at the distance |u| / surfaces, its history updated as
  ``advance_states`` does, bit for bit;
- precise: the monitor grid, held as a group under the slider
  (:mod:`isolator.compiled.bidirectional.grid`),
  an exact rearrangement of :class:`~isolator.bidirectional.heating.GridHeating` (round-off apart),
  with its frame fixed by the motion at the first heated commit as the reference's.

Each heated bearing has its own heat clock (``HEAT_TIME``), advanced by the committed steps
that reach its heating, as the reference's heating objects keep theirs (a step in uplift does
not). Errors the element would raise come back as status codes, with what the adapter needs
to word them (``STEP_BELOW_MIN_LAG``, ``LEFT_MONITOR_LINE``, ``BEYOND_RADIUS``).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.compiled import layout as L
from isolator.compiled.bidirectional.grid import (
    ACCUMULATORS,
    CACHE_SLOTS,
    DECAYS,
    FACTORS,
    OFFSETS,
    RATES,
    SCALARS,
    SLOTS,
    STATES,
    TABLE,
    UNTOUCHED,
    WEIGHTS,
    WINDOWS,
    inlined,
    mark_heated,
    move_grid_window,
    reanchor_grid_window,
)
from isolator.compiled.kernels import (
    cold_friction,
    heated_window,
    ptv_friction,
    solve_friction,
)
from isolator.contact_window import advance_window, window_history
from isolator.friction import REFERENCE_PRESSURE
from isolator.heating import step_factors

# Layout of a row of the ``bearings`` parameter array (one row per bearing; floats).
X, Y, GRAVITY, YIELD_DISPLACEMENT, RESTORING_LAW, EFFECTIVE_RADIUS, CONTACT_AREA = range(7)
FRICTION_MODEL, CONSTANT_MU, INITIAL_TEMPERATURE, SURFACES, MIN_LAG = range(7, 12)
FLUX_COEFFICIENT, ORIENTATION = 12, 13  # the grid's fixed angle [rad], NaN: follows the motion
PLATE_PARAMETERS = 14

# Codes of RESTORING_LAW and FRICTION_MODEL.
LINEAR, SPHERICAL, FLAT = 0, 1, 2
CONSTANT, COLD_PTV, CENTRE_PTV, GRID_PTV = 0, 1, 2, 3

# A bearing state (committed or trial) as PlanarState; then the trial's tangents, its pending
# heat and its frame (the grid's e1 a trial would fix).
TIME, UX, UY, VX, VY, FX, FY, FFX, FFY, ZX, ZY, MU, TEMPERATURE, HEAT_FLUX, AXIAL_LOAD = range(15)
KXX, KXY, KYX, KYY, CXX, CXY, CYX, CYY = range(15, 23)
PENDING_DT, PENDING, AXIS_X, AXIS_Y = range(23, 27)
PLATE_STATE_SIZE = 27

PLATE_FIELDS = (("displacement", (UX, UY)), ("force", (FX, FY)),
                ("friction_force", (FFX, FFY)), ("mu", (MU,)), ("temperature", (TEMPERATURE,)),
                ("heat_flux", (HEAT_FLUX,)), ("axial_load", (AXIAL_LOAD,)))
"""What is recorded of a bearing (``structures.spatial_results.BEARING_RECORD``): the state
columns of each field."""

# Per-bearing scalars of the heat history (``heat[SCALARS][b]``).
HEAT_TIME, RISE, RISE_VALID, RISE_STEP, FRAME_FIXED, E1X, E1Y = range(7)
HEAT_COMMITS, ANCHORED_AGO = 7, 8
SCALARS_SIZE = 9
# Rows of ``heat[WINDOWS][b]`` (int64, 4 columns i_lo, i_hi, k_lo, k_hi): the window held as
# a group, and the last trial's.
HELD, TRIAL_WINDOW = range(2)
# The step-factor table shared by the bearings (``heat[TABLE]``) and its ``heat[SLOTS]`` rows.
PREPARED_STEP, SLOT, NEXT_SLOT = range(3)
SLOT_STEP, SLOT_NEWEST = range(2)
FACTOR_SLOTS = 32
REANCHOR_EVERY = 1024  # heated commits between fresh sums of a window (bounds its drift)

# Status codes of a trial (and of a run).
SUCCESS, NOT_CONVERGED, LEFT_MONITOR_LINE, STEP_BELOW_MIN_LAG, BEYOND_RADIUS = range(5)


def new_plate_heating(n_bearings: int, points: int, rates: np.ndarray,
                      weights: np.ndarray) -> tuple[np.ndarray, ...]:
    """The heat history of ``n_bearings`` plates as one tuple indexed by ``RATES`` ...
    ``WINDOWS`` of :mod:`isolator.compiled.bidirectional.grid`.

    ``points`` monitor points per plate (n x n for the grid, 1 for the centre point), ``rates``
    [1/s] and ``weights`` [s^-0.5] of the kernel, shape (K,). Zero history, unheated, no frame.
    Made in Python and handed to the engine, which allocates nothing.
    """
    k = rates.shape[0]
    table = np.array([-1.0, 0.0, 0.0])
    return (np.array(rates, dtype=float, order="C"), np.array(weights, dtype=float, order="C"),
            np.zeros((n_bearings, points, k)), np.full((n_bearings, points), -1.0),
            np.full((n_bearings, points), UNTOUCHED, dtype=np.int64),
            np.zeros((n_bearings, points + 1), dtype=np.int64), np.zeros((n_bearings, k)),
            np.zeros((n_bearings, k)), np.full(CACHE_SLOTS, -1.0), np.zeros((CACHE_SLOTS, k)),
            np.array([-1.0, -1.0]), np.zeros((n_bearings, SCALARS_SIZE)),
            np.zeros((FACTOR_SLOTS, 2, k)), np.zeros((FACTOR_SLOTS, k)),
            np.full((FACTOR_SLOTS, 2), -1.0), table,
            np.zeros((n_bearings, 2, 4), dtype=np.int64))


@inlined
def prepare_step(dt, coefficient, min_lag, heat):
    """The slot of the step factors of ``dt`` [s] in the shared table, computed if new; -1
    when ``dt`` is below the kernel's shortest lag (the reference's ValueError)."""
    table, slots = heat[TABLE], heat[SLOTS]
    if dt == table[PREPARED_STEP]:
        return int(table[SLOT])
    if dt < min_lag:
        return -1
    for slot in range(slots.shape[0]):
        if slots[slot, SLOT_STEP] == dt:
            table[PREPARED_STEP], table[SLOT] = dt, slot
            return slot
    slot = int(table[NEXT_SLOT])
    table[NEXT_SLOT] = (slot + 1) % slots.shape[0]
    slots[slot, SLOT_NEWEST] = step_factors(heat[RATES], heat[WEIGHTS], coefficient, dt,
                                            heat[FACTORS][slot], heat[DECAYS][slot])
    slots[slot, SLOT_STEP] = dt
    table[PREPARED_STEP], table[SLOT] = dt, slot
    return slot


@inlined
def _grid_rise(b, sx, sy, vx, vy, dt, slot, parameters, ptv, trial, heat):
    """GridHeating.trial for the slider at (sx, sy) on the plate [m]: (rise, points under the
    slider, inside the grid); the frame goes to ``trial[AXIS_X]``, the window to the
    bearing's ``TRIAL_WINDOW``, and the held window follows it once the frame is fixed."""
    scalars, windows = heat[SCALARS][b], heat[WINDOWS][b]
    if scalars[FRAME_FIXED] != 0.0:
        e1x, e1y = scalars[E1X], scalars[E1Y]
    elif not math.isnan(parameters[ORIENTATION]):
        e1x, e1y = math.cos(parameters[ORIENTATION]), math.sin(parameters[ORIENTATION])
    else:  # plate_frame: along the position, else the velocity, else x
        e1x, e1y = 1.0, 0.0
        size = math.hypot(sx, sy)
        if size > 0.0:
            e1x, e1y = sx / size, sy / size
        else:
            size = math.hypot(vx, vy)
            if size > 0.0:
                e1x, e1y = vx / size, vy / size
    trial[AXIS_X], trial[AXIS_Y] = e1x, e1y
    n = int(ptv[L.N_POINTS])
    along = e1x * sx + e1y * sy
    across = -e1y * sx + e1x * sy
    i_lo, i_hi, inside_i = heated_window(along, ptv[L.FIRST_POINT], ptv[L.SPACING], n,
                                         ptv[L.FLUX_HALF_WIDTH], True)
    k_lo, k_hi, inside_k = heated_window(across, ptv[L.FIRST_POINT], ptv[L.SPACING], n,
                                         ptv[L.FLUX_HALF_WIDTH], True)
    if not (inside_i and inside_k):
        return 0.0, 0, False
    window = windows[TRIAL_WINDOW]
    window[0], window[1], window[2], window[3] = i_lo, i_hi, k_lo, k_hi
    points = max(i_hi - i_lo, 0) * max(k_hi - k_lo, 0)
    if scalars[FRAME_FIXED] == 0.0:
        return 0.0, points, True  # nothing stored before the first heated commit
    held = windows[HELD]
    if i_lo != held[0] or i_hi != held[1] or k_lo != held[2] or k_hi != held[3]:
        move_grid_window(b, n, held, window, scalars[HEAT_TIME], heat)
        held[0], held[1], held[2], held[3] = i_lo, i_hi, k_lo, k_hi
        scalars[RISE_VALID] = 0.0
    if scalars[RISE_VALID] == 0.0 or scalars[RISE_STEP] != dt:
        scalars[RISE] = window_history(heat[ACCUMULATORS][b], heat[OFFSETS][b],
                                       heat[DECAYS][slot], points)
        scalars[RISE_VALID], scalars[RISE_STEP] = 1.0, dt
    return scalars[RISE], points, True


@inlined
def _friction(b, ux, uy, vx, vy, dt, pressure, speed, parameters, ptv, trial, heat):
    """PlateFriction of a loaded trial: (mu, d mu / d|v|, temperature, flux, status)."""
    model = int(parameters[FRICTION_MODEL])
    if model == CONSTANT:
        return parameters[CONSTANT_MU], 0.0, parameters[INITIAL_TEMPERATURE], 0.0, SUCCESS
    code = int(ptv[L.FACTOR_CODE])
    if model == COLD_PTV or dt <= 0.0:
        mu_cold, dmu_cold = cold_friction(code, ptv[L.REFERENCE_PRESSURE], ptv[L.RATE_PARAMETER],
                                          ptv[L.MU_T0], ptv[L.USE_PRESSURE] != 0.0,
                                          ptv[L.USE_VELOCITY] != 0.0, pressure, speed)
        mu, dmu_dspeed, temperature = solve_friction(code, mu_cold, dmu_cold,
                                                     ptv[L.USE_TEMPERATURE] != 0.0,
                                                     ptv[L.INITIAL_TEMPERATURE], 0.0, 0.0)
        return mu, dmu_dspeed, temperature, mu * pressure * speed / ptv[L.SURFACES], SUCCESS
    slot = prepare_step(dt, parameters[FLUX_COEFFICIENT], parameters[MIN_LAG], heat)
    if slot < 0:
        trial[PENDING_DT] = dt
        return 0.0, 0.0, 0.0, 0.0, STEP_BELOW_MIN_LAG
    surfaces = ptv[L.SURFACES]
    if model == CENTRE_PTV:  # ptv_trial on the distance from the centre
        lo, hi, _ = heated_window(math.hypot(ux, uy) / surfaces, ptv[L.FIRST_POINT],
                                  ptv[L.SPACING], int(ptv[L.N_POINTS]), ptv[L.FLUX_HALF_WIDTH],
                                  False)
        states, decays = heat[STATES], heat[DECAYS]
        rise = 0.0
        for k in range(decays.shape[1]):
            rise += states[b, 0, k] * decays[slot, k]
        window = heat[WINDOWS][b, TRIAL_WINDOW]
        window[0], window[1] = lo, hi
        heated = hi > lo
    else:
        rise, points, inside = _grid_rise(b, ux / surfaces, uy / surfaces, vx, vy, dt, slot,
                                          parameters, ptv, trial, heat)
        if not inside:
            return 0.0, 0.0, 0.0, 0.0, LEFT_MONITOR_LINE
        heated = points > 0
    mu, dmu_dspeed, temperature, flux = ptv_friction(rise, heated, ptv,
                                                     heat[SLOTS][slot, SLOT_NEWEST], pressure,
                                                     speed)
    trial[PENDING_DT], trial[PENDING] = dt, 1.0
    return mu, dmu_dspeed, temperature, flux, SUCCESS


@inlined
def plate_trial(b, ux, uy, vx, vy, time, load, bearings, ptv, committed, trial, heat):
    """BidirectionalElement.set_trial of bearing ``b`` at the axial ``load`` [N]: fills the
    row ``trial[b]`` (state, tangents ``KXX`` ... ``CYY``); returns the status."""
    parameters, c, t = bearings[b], committed[b], trial[b]
    dt = time - c[TIME]
    yield_displacement = parameters[YIELD_DISPLACEMENT]
    px = c[ZX] + (ux - c[UX]) / yield_displacement  # isotropic_return_map
    py = c[ZY] + (uy - c[UY]) / yield_displacement
    size = math.hypot(px, py)
    if size >= 1.0:
        zx, zy = px / size, py / size
        scale = yield_displacement * size
        dxx, dxy = (1.0 - zx * zx) / scale, (0.0 - zx * zy) / scale
        dyx, dyy = (0.0 - zy * zx) / scale, (1.0 - zy * zy) / scale
    else:
        zx, zy = px, py
        dxx, dxy, dyx, dyy = 1.0 / yield_displacement, 0.0, 0.0, 1.0 / yield_displacement
    t[PENDING] = 0.0
    n = load
    rx = ry = kxx = kxy = kyx = kyy = 0.0
    if n <= 0.0:  # uplift: no contact, no force, no heat; the plates cool (``lifted``)
        _, _, temperature, _, status = _friction(
            b, ux, uy, 0.0, 0.0, dt, REFERENCE_PRESSURE, 0.0, parameters, ptv, t, heat)
        if status != SUCCESS:
            t[UX], t[UY] = ux, uy
            return status
        mu, dmu_dspeed, flux, n = 0.0, 0.0, 0.0, 0.0
        ex = ey = 0.0
    else:
        speed = math.hypot(vx, vy)
        mu, dmu_dspeed, temperature, flux, status = _friction(
            b, ux, uy, vx, vy, dt, n / parameters[CONTACT_AREA], speed, parameters, ptv, t, heat)
        if status != SUCCESS:
            t[UX], t[UY] = ux, uy
            return status
        ex, ey = (vx / speed, vy / speed) if speed > 0.0 else (0.0, 0.0)
        law = int(parameters[RESTORING_LAW])
        radius = parameters[EFFECTIVE_RADIUS]
        if law == SPHERICAL:
            squared = radius**2 - (ux * ux + uy * uy)
            if not squared > 0.0:
                t[UX], t[UY] = ux, uy
                return BEYOND_RADIUS
            root = math.sqrt(squared)
            cube = root**3
            rx, ry = n * ux / root, n * uy / root
            kxx, kxy = n * (1.0 / root + ux * ux / cube), n * (0.0 / root + ux * uy / cube)
            kyx, kyy = n * (0.0 / root + uy * ux / cube), n * (1.0 / root + uy * uy / cube)
        elif law == LINEAR:
            rx, ry = n * ux / radius, n * uy / radius
            kxx = kyy = n / radius
    mu_n = mu * n
    ffx, ffy = mu_n * zx, mu_n * zy
    t[TIME], t[UX], t[UY], t[VX], t[VY] = time, ux, uy, vx, vy
    t[FX], t[FY], t[FFX], t[FFY], t[ZX], t[ZY] = rx + ffx, ry + ffy, ffx, ffy, zx, zy
    t[MU], t[TEMPERATURE], t[HEAT_FLUX], t[AXIAL_LOAD] = mu, temperature, flux, n
    t[KXX], t[KXY], t[KYX], t[KYY] = kxx + mu_n * dxx, kxy + mu_n * dxy, kyx + mu_n * dyx, \
        kyy + mu_n * dyy
    dvx, dvy = dmu_dspeed * ex, dmu_dspeed * ey
    t[CXX], t[CXY], t[CYX], t[CYY] = n * (zx * dvx), n * (zx * dvy), n * (zy * dvx), \
        n * (zy * dvy)
    return SUCCESS


@inlined
def plate_commit(b, bearings, ptv, committed, trial, heat):
    """BidirectionalElement.commit of bearing ``b``: the trial becomes the committed state and
    its heat enters the plate's history."""
    t = trial[b]
    if t[PENDING] != 0.0:
        parameters = bearings[b]
        dt, flux = t[PENDING_DT], t[HEAT_FLUX]
        slot = prepare_step(dt, parameters[FLUX_COEFFICIENT], parameters[MIN_LAG], heat)
        step = heat[FACTORS][slot]
        scalars, windows = heat[SCALARS][b], heat[WINDOWS][b]
        window = windows[TRIAL_WINDOW]
        if int(parameters[FRICTION_MODEL]) == CENTRE_PTV:  # advance_states on one point
            states = heat[STATES]
            heated = window[1] > window[0] and flux != 0.0
            for k in range(step.shape[1]):
                if heated:
                    states[b, 0, k] = states[b, 0, k] * step[0, k] + flux * step[1, k]
                else:
                    states[b, 0, k] *= step[0, k]
        else:
            n = int(ptv[L.N_POINTS])
            points = max(window[1] - window[0], 0) * max(window[3] - window[2], 0)
            if flux != 0.0 and points > 0:
                if scalars[FRAME_FIXED] == 0.0:
                    scalars[FRAME_FIXED], scalars[E1X], scalars[E1Y] = 1.0, t[AXIS_X], t[AXIS_Y]
                held = windows[HELD]
                if (window[0] != held[0] or window[1] != held[1] or window[2] != held[2]
                        or window[3] != held[3]):
                    move_grid_window(b, n, held, window, scalars[HEAT_TIME], heat)
                    held[0], held[1], held[2], held[3] = window[0], window[1], window[2], \
                        window[3]
                scalars[HEAT_COMMITS] += 1.0
                mark_heated(b, n, window, int(scalars[HEAT_COMMITS]), heat)
            else:
                flux = 0.0
            advance_window(heat[ACCUMULATORS][b], heat[OFFSETS][b], step, flux)
            scalars[HEAT_TIME] += dt
            scalars[RISE_VALID] = 0.0
            if scalars[FRAME_FIXED] != 0.0:
                scalars[ANCHORED_AGO] += 1.0
                if scalars[ANCHORED_AGO] >= REANCHOR_EVERY:
                    reanchor_grid_window(b, n, windows[HELD], scalars[HEAT_TIME], heat)
                    scalars[ANCHORED_AGO] = 0.0
    t[PENDING] = 0.0
    c = committed[b]
    for i in range(AXIAL_LOAD + 1):
        c[i] = t[i]
