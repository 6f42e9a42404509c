"""The DCFPB element, its friction and its heat history as arrays, for the compiled engine.

:func:`bearing_trial` and :func:`bearing_commit` are ``BearingElement.set_trial`` and
``commit`` of :mod:`isolator.bearing` for one bearing whose state is a float array (``TIME``
... ``PENDING``) and whose heat history is a tuple of arrays (:func:`new_heating`): the same
return map and restoring law, and the friction of :mod:`isolator.friction` through the same
kernels (``cold_friction``, ``solve_friction``, ``heated_window``, ``ptv_friction``; the step
factors of :func:`isolator.heating.step_factors`). The monitor points under the slider are
held as a group (:mod:`isolator.contact_window`), an exact rearrangement of ``advance_states``
and ``contact_history`` that costs O(K) per step instead of O(points x K). A trial never changes
the history; its heat waits (``PENDING``) for the commit, as in the reference. Errors the
element would raise come back as status codes (``LEFT_MONITOR_LINE`` ...).

The loop that calls them is :mod:`structures.compiled.integrator`; without numba all of it is
Python.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.compiled import layout as L
from isolator.compiled.kernels import (
    cold_friction,
    heated_window,
    jit,
    ptv_friction,
    solve_friction,
)
from isolator.contact_window import (
    advance_window,
    move_window,
    reanchor_window,
    window_history,
)
from isolator.heating import step_factors

# Layout of the ``bearing`` parameter array (all floats).
N_BEARINGS, YIELD_DISPLACEMENT, RESTORING_LAW, EFFECTIVE_RADIUS, AXIAL_LOAD, PRESSURE = range(6)
FRICTION_MODEL, CONSTANT_MU, INITIAL_TEMPERATURE, SURFACES, MIN_LAG, FLUX_COEFFICIENT = range(6, 12)
INITIAL_MU = 12  # friction coefficient of the element at rest, before the first step
BEARING_PARAMETERS = 13

# Codes of RESTORING_LAW and FRICTION_MODEL.
LINEAR, SPHERICAL, FLAT = 0, 1, 2
CONSTANT, COLD_PTV, HEATED_PTV = 0, 1, 2

# A bearing state (committed or trial), as BearingState; then the pending heat of a trial.
TIME, DISPLACEMENT, VELOCITY, FORCE, FRICTION_FORCE, Z, MU, TEMPERATURE, HEAT_FLUX = range(9)
PENDING_DT, PENDING = 9, 10  # the step of a trial's heat, and 1.0 while it waits for commit
STATE_SIZE = 11

# Integer bookkeeping of the heat history: heated and ever-heated point ranges, the window
# held as a group and the commits since it was last re-anchored.
HEATED_LO, HEATED_HI, TOUCHED_LO, TOUCHED_HI, WINDOW_LO, WINDOW_HI, ANCHORED_AGO = range(7)
RANGES_SIZE = 7
REANCHOR_EVERY = 1024  # commits between fresh sums of the window (bounds the round-off drift)
# Heating step factors: the last step prepared, its slot in the table, the next slot to fill;
# then the window's contact history for that slot, valid (1.0) until the window, the slot or
# the history changes (Newton's trials of a step mostly share it).
PREPARED_STEP, SLOT, NEXT_SLOT, RISE, RISE_VALID = range(5)
FACTOR_SLOTS = 32  # distinct step sizes whose factors are kept (one run has about 15)
# Columns of the table's ``slots`` array: the step [s] and 2 c sqrt(dt) [degC m^2 / W].
SLOT_STEP, SLOT_NEWEST = range(2)
# The heat history's arrays travel as one tuple, in this order.
RATES, WEIGHTS, STATES, STAMPS, ACCUMULATOR, OFFSETS, FACTORS, DECAYS, SLOTS, HEAT = range(10)
RANGES = 10

BEARING_FIELDS = ("displacement", "velocity", "force", "friction_force", "mu", "temperature",
                  "heat_flux")
"""Rows of the ``record`` array: the bearing's committed state (one bearing) at every step."""

# Status codes of a trial (and of the run, in the engine's info[STATUS]).
SUCCESS, NOT_CONVERGED, LEFT_MONITOR_LINE, STEP_BELOW_MIN_LAG, BEYOND_RADIUS = range(5)


def new_heating(rates, weights, states):
    """The heat history's arrays, as one tuple indexed by ``RATES`` ... ``RANGES``.

    ``rates``, ``weights`` [1/s], [s^-0.5]: the kernel's exponentials (K,); ``states`` (points,
    K): the monitor points, zero (they hold B_j or C_j of :mod:`isolator.contact_window`).
    Made in Python and handed to the engine, which allocates nothing.
    """
    n_terms = rates.shape[0]
    ranges = np.zeros(RANGES_SIZE, dtype=np.int64)
    ranges[TOUCHED_LO] = states.shape[0]
    return (rates, weights, states, np.zeros(states.shape[0]), np.zeros(n_terms),
            np.zeros(n_terms), np.zeros((FACTOR_SLOTS, 2, n_terms)),
            np.zeros((FACTOR_SLOTS, n_terms)), np.full((FACTOR_SLOTS, 2), -1.0),
            np.array([-1.0, 0.0, 0.0, 0.0, 0.0]), ranges)


@jit
def _prepare_heating(dt, coefficient, min_lag, heating):
    """SurfaceHeating.prepare: select the step factors of ``dt`` [s], computing them if new.

    ``heating`` is the tuple of :func:`new_heating`.

    Returns False when ``dt`` is below the kernel's shortest lag (nothing is changed then).
    """
    slots, heat = heating[SLOTS], heating[HEAT]
    if dt < min_lag:
        return False
    heat[PREPARED_STEP] = dt
    for slot in range(slots.shape[0]):
        if slots[slot, SLOT_STEP] == dt:
            if heat[SLOT] != slot:
                heat[SLOT], heat[RISE_VALID] = slot, 0.0
            return True
    slot = int(heat[NEXT_SLOT])
    heat[NEXT_SLOT] = (slot + 1) % slots.shape[0]
    slots[slot, SLOT_NEWEST] = step_factors(heating[RATES], heating[WEIGHTS], coefficient, dt,
                                            heating[FACTORS][slot], heating[DECAYS][slot])
    slots[slot, SLOT_STEP] = dt
    heat[SLOT], heat[RISE_VALID] = slot, 0.0
    return True


@jit
def _move_window(heating, lo, hi, time):
    """Hold the points ``[lo, hi)`` as the window from ``time`` [s] (the last commit)."""
    ranges = heating[RANGES]
    ranges[TOUCHED_LO], ranges[TOUCHED_HI] = move_window(
        heating[STATES], heating[STAMPS], heating[ACCUMULATOR], heating[OFFSETS],
        heating[RATES], ranges[WINDOW_LO], ranges[WINDOW_HI], lo, hi, ranges[TOUCHED_LO],
        ranges[TOUCHED_HI], time)
    ranges[WINDOW_LO], ranges[WINDOW_HI] = lo, hi
    heating[HEAT][RISE_VALID] = 0.0


@jit
def bearing_trial(displacement, velocity, time, bearing, ptv, committed, trial, heating):
    """BearingElement.set_trial of one bearing: fills ``trial``.

    Returns
    -------
    force [N], stiffness d F / d u [N/m], damping d F / d v [N s/m], status : float, float,
    float, int
        ``status`` is SUCCESS or the code of the error the element would raise.
    """
    dt = time - committed[TIME]
    n = bearing[AXIAL_LOAD]
    yield_displacement = bearing[YIELD_DISPLACEMENT]
    z = committed[Z] + (displacement - committed[DISPLACEMENT]) / yield_displacement
    dz_du = 1.0 / yield_displacement
    if abs(z) >= 1.0:
        z, dz_du = math.copysign(1.0, z), 0.0

    model = int(bearing[FRICTION_MODEL])
    trial[PENDING] = 0.0
    speed = abs(velocity)
    if model == CONSTANT:
        mu, dmu_dspeed, flux = bearing[CONSTANT_MU], 0.0, 0.0
        temperature = bearing[INITIAL_TEMPERATURE]
    elif model == COLD_PTV or dt <= 0.0:
        mu_cold, dmu_cold = cold_friction(int(ptv[L.FACTOR_CODE]), ptv[L.REFERENCE_PRESSURE],
                                          ptv[L.RATE_PARAMETER], ptv[L.MU_T0],
                                          ptv[L.USE_PRESSURE] != 0.0, ptv[L.USE_VELOCITY] != 0.0,
                                          bearing[PRESSURE], speed)
        mu, dmu_dspeed, temperature = solve_friction(int(ptv[L.FACTOR_CODE]), mu_cold, dmu_cold,
                                                     ptv[L.USE_TEMPERATURE] != 0.0,
                                                     bearing[INITIAL_TEMPERATURE], 0.0, 0.0)
        flux = mu * bearing[PRESSURE] * speed / bearing[SURFACES]
    else:  # the heated model: only it touches the heating arrays
        heat, ranges = heating[HEAT], heating[RANGES]
        if dt != heat[PREPARED_STEP] and not _prepare_heating(
                dt, bearing[FLUX_COEFFICIENT], bearing[MIN_LAG], heating):
            trial[PENDING_DT] = dt
            return 0.0, 0.0, 0.0, STEP_BELOW_MIN_LAG
        # ptv_trial, with contact_history formed from the window held as a group
        average_over_contact = ptv[L.AVERAGE_OVER_CONTACT] != 0.0
        lo, hi, inside = heated_window(displacement / bearing[SURFACES], ptv[L.FIRST_POINT],
                                       ptv[L.SPACING], int(ptv[L.N_POINTS]),
                                       ptv[L.FLUX_HALF_WIDTH], average_over_contact)
        if not inside:
            trial[DISPLACEMENT] = displacement
            return 0.0, 0.0, 0.0, LEFT_MONITOR_LINE
        window_lo, window_hi = (lo, hi) if average_over_contact else (0, 1)
        if window_lo != ranges[WINDOW_LO] or window_hi != ranges[WINDOW_HI]:
            _move_window(heating, window_lo, window_hi, committed[TIME])
        slot = int(heat[SLOT])
        if heat[RISE_VALID] == 0.0:
            heat[RISE] = window_history(heating[ACCUMULATOR], heating[OFFSETS],
                                        heating[DECAYS][slot], window_hi - window_lo)
            heat[RISE_VALID] = 1.0
        rise = heat[RISE]
        mu, dmu_dspeed, temperature, flux = ptv_friction(
            rise, hi > lo, ptv, heating[SLOTS][slot, SLOT_NEWEST], bearing[PRESSURE], speed)
        ranges[HEATED_LO], ranges[HEATED_HI] = lo, hi
        trial[PENDING_DT], trial[PENDING] = dt, 1.0
    # d mu / d v = d mu / d|v| sign(v); d mu / d|v| is negative on a hot plate at speed
    dmu_dvelocity = math.copysign(1.0, velocity) * dmu_dspeed if velocity != 0.0 else 0.0

    law = int(bearing[RESTORING_LAW])
    radius = bearing[EFFECTIVE_RADIUS]
    if law == FLAT:
        restoring, stiffness = 0.0, 0.0
    elif law == SPHERICAL:
        squared = radius**2 - displacement * displacement
        if not squared > 0.0:
            trial[DISPLACEMENT] = displacement
            return 0.0, 0.0, 0.0, BEYOND_RADIUS
        root = math.sqrt(squared)
        restoring, stiffness = n * displacement / root, n * radius**2 / root**3
    else:
        restoring, stiffness = n * displacement / radius, n / radius
    friction_force = mu * n * z
    force = restoring + friction_force
    trial[TIME], trial[DISPLACEMENT], trial[VELOCITY] = time, displacement, velocity
    trial[FORCE], trial[FRICTION_FORCE], trial[Z] = force, friction_force, z
    trial[MU], trial[TEMPERATURE], trial[HEAT_FLUX] = mu, temperature, flux
    return force, stiffness + mu * n * dz_du, n * z * dmu_dvelocity, SUCCESS


@jit
def bearing_commit(bearing, committed, trial, heating):
    """BearingElement.commit: the trial becomes the committed state, its heat is added."""
    if trial[PENDING] != 0.0:
        heat, ranges = heating[HEAT], heating[RANGES]
        dt = trial[PENDING_DT]
        if dt != heat[PREPARED_STEP]:
            _prepare_heating(dt, bearing[FLUX_COEFFICIENT], bearing[MIN_LAG], heating)
        step = heating[FACTORS][int(heat[SLOT])]
        heated_lo, heated_hi, flux = ranges[HEATED_LO], ranges[HEATED_HI], trial[HEAT_FLUX]
        if heated_hi <= heated_lo or flux == 0.0:  # advance_states: no point takes heat
            flux = 0.0
        elif heated_lo != ranges[WINDOW_LO] or heated_hi != ranges[WINDOW_HI]:
            _move_window(heating, heated_lo, heated_hi, committed[TIME])  # the heated group
        advance_window(heating[ACCUMULATOR], heating[OFFSETS], step, flux)
        heat[RISE_VALID] = 0.0
        ranges[ANCHORED_AGO] += 1
        if ranges[ANCHORED_AGO] >= REANCHOR_EVERY:
            reanchor_window(heating[STATES], heating[STAMPS], heating[OFFSETS], heating[RATES],
                            ranges[WINDOW_LO], ranges[WINDOW_HI], trial[TIME])
            ranges[ANCHORED_AGO] = 0
    trial[PENDING] = 0.0
    for i in range(PENDING_DT):
        committed[i] = trial[i]


@jit
def record_state(column, state):
    """A column of the record (one step): the bearing ``state`` in the order of
    ``BEARING_FIELDS``."""
    column[0], column[1] = state[DISPLACEMENT], state[VELOCITY]
    column[2], column[3] = state[FORCE], state[FRICTION_FORCE]
    column[4], column[5], column[6] = state[MU], state[TEMPERATURE], state[HEAT_FLUX]
