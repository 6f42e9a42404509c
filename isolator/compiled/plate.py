"""The precise model's monitor points on a plate, held for the compiled element in array form.

The points form a rectangle of ``n_along`` x ``n_across`` points, point ``(i, k)`` at flat
index ``j = i n_across + k`` (``i`` along the frame's first axis e1, ``k`` along e2): the
monitor grid of :class:`~isolator.bidirectional.heating.GridHeating` is a square of n x n, the
monitor line of :class:`~isolator.heating.SurfaceHeating` is the same code with one row
across (``n_across = 1``, e1 along x). The reference stores a history G_j (K exponential
terms) for every point heated and, per trial, decays and sums the points under the slider
(about 2,800 on a grid, 53 on a line, for a 300 mm slider at 5 mm spacing). Here the points
under the slider all take the same flux, so they are carried as one group, and a trial costs
O(K) and a step O(K) plus O(K) per point entering or leaving the rectangle under the slider:

- a point outside the window keeps ``B_j`` = G_j at its ``stamp`` and decays implicitly
  (G_j(t) = exp(-s (t - tau_j)) B_j); ``stamp < 0`` marks a point never touched (G = 0);
- an ``accumulator`` A(t) holds the history of a point heated at every step since t = 0,
  A <- exp(-s dt) A + q (1 - exp(-s dt)) / s (:func:`advance_window`);
- a point inside the window keeps ``C_j`` = G_j(tau_j) - A(tau_j), and the ``offsets``
  E(t) = sum_j exp(-s (t - tau_j)) C_j, so the window's column sums are W A + E and the history
  part of the contact temperature is sum_k w_k exp(-s_k dt) (W A_k + E_k) / W
  (:func:`window_history`);
- the window is a rectangle of indices, so a move touches only the difference of two
  rectangles (:func:`move_window`); :func:`reanchor_window` re-forms E from the points every
  ``REANCHOR_EVERY`` heated commits, so that its round-off cannot drift.

The decay factors exp(-s (t - tau_j)) of the points that move depend on tau_j alone, and the
points of a row or column entered or left together share it: a small cache keyed by the stamp
(valid for one bearing and one time) makes a move cost one set of K exponentials per distinct
stamp, not per point.

Which points the reference stores (the plate temperature field of a run) is kept too: a point
entering the window is put on a ``pending`` list, and the next commit that heats the window
gives it the number of that commit (``marks``); the reference's order of storage is then the
order of (mark, i, k) (:func:`field_temperatures`).

All times are the heat history's own clock (the sum of the committed heated steps), never
the element's. These are exact rearrangements of the reference's updates: only the round-off
differs. Every function is a compiled kernel with a plain-Python twin
(:mod:`isolator.compiled.kernels`).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.compiled.kernels import jit
from isolator.heating import step_factors

# The heat history's arrays travel as one tuple (:func:`new_plate_heating`), in this order;
# the per-bearing ones have the bearing first.
RATES, WEIGHTS, STATES, STAMPS, MARKS, PENDING_LIST, ACCUMULATORS, OFFSETS = range(8)
CACHE_KEYS, CACHE_VALUES, CACHE_STATE, SCALARS, FACTORS, DECAYS, SLOTS, TABLE = range(8, 16)
WINDOWS = 16

UNTOUCHED, PENDING_MARK = -1, -2  # ``marks`` of a point never heated, and of one waiting
UNDERFLOW = 745.2  # exp(-x) rounds to 0.0 beyond it (libm's underflow path is slow)
CACHE_SLOTS = 64  # decay vectors kept per move (a power of two)
# Layout of ``cache_state``: the bearing and the time the cached decay vectors are for.
CACHE_BEARING, CACHE_TIME = range(2)

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
FACTOR_SLOTS = 32  # distinct step sizes whose factors are kept (one run has about 15)
REANCHOR_EVERY = 1024  # heated commits between fresh sums of a window (bounds its drift)


def new_plate_heating(n_bearings: int, points: int, rates: np.ndarray,
                      weights: np.ndarray) -> tuple[np.ndarray, ...]:
    """The heat history of ``n_bearings`` plates as one tuple indexed by ``RATES`` ...
    ``WINDOWS``.

    ``points`` monitor points per plate (n_along x n_across; 1 for the centre point),
    ``rates`` [1/s] and ``weights`` [s^-0.5] of the kernel, shape (K,). Zero history,
    unheated, no frame. Made in Python and handed to the engine, which allocates nothing.
    """
    k = rates.shape[0]
    return (np.array(rates, dtype=float, order="C"), np.array(weights, dtype=float, order="C"),
            np.zeros((n_bearings, points, k)), np.full((n_bearings, points), -1.0),
            np.full((n_bearings, points), UNTOUCHED, dtype=np.int64),
            np.zeros((n_bearings, points + 1), dtype=np.int64), np.zeros((n_bearings, k)),
            np.zeros((n_bearings, k)), np.full(CACHE_SLOTS, -1.0), np.zeros((CACHE_SLOTS, k)),
            np.array([-1.0, -1.0]), np.zeros((n_bearings, SCALARS_SIZE)),
            np.zeros((FACTOR_SLOTS, 2, k)), np.zeros((FACTOR_SLOTS, k)),
            np.full((FACTOR_SLOTS, 2), -1.0), np.array([-1.0, 0.0, 0.0]),
            np.zeros((n_bearings, 2, 4), dtype=np.int64))


@jit
def prepare_step(dt, coefficient, min_lag, heat):
    """The slot of the step factors of ``dt`` [s] in the shared table, computed if new
    (:func:`isolator.heating.step_factors`); -1 when ``dt`` is below the kernel's shortest
    lag (the reference's ValueError)."""
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


@jit
def advance_window(accumulator, offsets, step, flux):
    """One committed step of the window: every point in it takes the flux ``q`` [W/m^2].

    ``step`` stacks exp(-s_k dt) and (1 - exp(-s_k dt)) / s_k, shape (2, K), as for
    :func:`~isolator.compiled.kernels.advance_states`; points outside the window are untouched
    (their decay is implied by their stamps).
    """
    decay = step[0]
    gain = step[1]
    for k in range(accumulator.shape[0]):
        accumulator[k] = accumulator[k] * decay[k] + flux * gain[k]
        offsets[k] *= decay[k]


@jit
def window_history(accumulator, offsets, weighted_decay, points):
    """:func:`~isolator.compiled.kernels.contact_history` of a window of ``points`` points.

    sum_k w_k exp(-s_k dt) (points A_k + E_k) / points [W s^0.5 / m^2]; 0 for an empty window.
    """
    if points <= 0:
        return 0.0
    n_terms = weighted_decay.shape[0]
    s0 = s1 = s2 = s3 = 0.0  # four independent sums: a single one is bound by add latency
    unrolled = n_terms - n_terms % 4
    for k in range(0, unrolled, 4):
        s0 += (points * accumulator[k] + offsets[k]) * weighted_decay[k]
        s1 += (points * accumulator[k + 1] + offsets[k + 1]) * weighted_decay[k + 1]
        s2 += (points * accumulator[k + 2] + offsets[k + 2]) * weighted_decay[k + 2]
        s3 += (points * accumulator[k + 3] + offsets[k + 3]) * weighted_decay[k + 3]
    for k in range(unrolled, n_terms):
        s0 += (points * accumulator[k] + offsets[k]) * weighted_decay[k]
    return ((s0 + s1) + (s2 + s3)) / points


@jit
def _decay_slot(stamp, time, bearing, rates, cache_keys, cache_values, cache_state):
    """The row of ``cache_values`` holding exp(-s_k (time - stamp)) for this bearing and
    time (computed if it is not there)."""
    if cache_state[CACHE_BEARING] != bearing or cache_state[CACHE_TIME] != time:
        for slot in range(cache_keys.shape[0]):
            cache_keys[slot] = -1.0
        cache_state[CACHE_BEARING], cache_state[CACHE_TIME] = bearing, time
    slot = int(stamp * 1048576.0) & (cache_keys.shape[0] - 1)
    if cache_keys[slot] != stamp:
        elapsed = time - stamp
        for k in range(rates.shape[0]):
            exponent = rates[k] * elapsed  # beyond 745.2, exp(-x) is 0.0: skip libm's
            cache_values[slot, k] = 0.0 if exponent > UNDERFLOW else math.exp(-exponent)
        cache_keys[slot] = stamp
    return slot


@jit
def _move_points(b, first, count, stride, time, entering, heat):
    """Points ``first + m stride``, m < ``count``, of bearing ``b`` leave the window at
    ``time`` (each keeps G_j = A + exp(-s (t - tau_j)) C_j) or enter it (``entering``: each
    keeps C_j = G_j - A; those never heated wait on the ``pending`` list)."""
    rates, states, stamps = heat[RATES], heat[STATES][b], heat[STAMPS][b]
    accumulator, offsets = heat[ACCUMULATORS][b], heat[OFFSETS][b]
    keys, values, cache = heat[CACHE_KEYS], heat[CACHE_VALUES], heat[CACHE_STATE]
    marks, pending = heat[MARKS][b], heat[PENDING_LIST][b]
    n_terms = rates.shape[0]
    slot, previous = 0, -2.0
    for m in range(count):
        j = first + m * stride
        if entering and stamps[j] < 0.0:  # never touched: G = 0
            for k in range(n_terms):
                states[j, k] = -accumulator[k]
                offsets[k] -= accumulator[k]
        else:
            if stamps[j] != previous:
                previous = stamps[j]
                slot = _decay_slot(previous, time, b, rates, keys, values, cache)
            if entering:
                for k in range(n_terms):
                    value = states[j, k] * values[slot, k] - accumulator[k]
                    states[j, k] = value
                    offsets[k] += value
            else:
                for k in range(n_terms):
                    carried = states[j, k] * values[slot, k]
                    offsets[k] -= carried
                    states[j, k] = accumulator[k] + carried
        stamps[j] = time
        if entering and marks[j] == UNTOUCHED:  # waits for the next heated commit
            marks[j] = PENDING_MARK
            size = pending[0] + 1
            pending[size] = j
            pending[0] = size


@jit
def move_window(b, n_across, old, new, time, heat):
    """Make the rectangle ``new`` the window of bearing ``b`` in place of ``old`` at ``time``.

    ``old`` and ``new`` are (i_lo, i_hi, k_lo, k_hi) (either may be empty); ``n_across``
    points per column.
    """
    a0, a1, b0, b1 = old[0], old[1], old[2], old[3]
    c0, c1, d0, d1 = new[0], new[1], new[2], new[3]
    if a1 <= a0 or b1 <= b0:  # an empty rectangle holds no column
        a0 = a1 = b0 = b1 = 0
    # the old points not in the new rectangle: whole columns (contiguous in memory), then
    # the rows of the columns both hold (strided by a column); then the new points the same way
    both_lo, both_hi = max(a0, c0), min(a1, c1)
    for i in range(a0, a1):
        if (i < c0 or i >= c1) and b1 > b0:
            _move_points(b, i * n_across + b0, b1 - b0, 1, time, False, heat)
    if both_hi > both_lo:
        for k in range(b0, b1):
            if k < d0 or k >= d1:
                _move_points(b, both_lo * n_across + k, both_hi - both_lo, n_across, time,
                             False, heat)
    for i in range(c0, c1):
        if (i < a0 or i >= a1) and d1 > d0:
            _move_points(b, i * n_across + d0, d1 - d0, 1, time, True, heat)
    if both_hi > both_lo:
        for k in range(d0, d1):
            if k < b0 or k >= b1:
                _move_points(b, both_lo * n_across + k, both_hi - both_lo, n_across, time,
                             True, heat)


@jit
def reanchor_window(b, n_across, window, time, heat):
    """Re-stamp bearing ``b``'s window points at ``time`` and sum E afresh (bounds drift)."""
    rates, states, stamps = heat[RATES], heat[STATES][b], heat[STAMPS][b]
    keys, values, cache = heat[CACHE_KEYS], heat[CACHE_VALUES], heat[CACHE_STATE]
    offsets = heat[OFFSETS][b]
    for k in range(rates.shape[0]):
        offsets[k] = 0.0
    for i in range(window[0], window[1]):
        for j in range(i * n_across + window[2], i * n_across + window[3]):
            slot = _decay_slot(stamps[j], time, b, rates, keys, values, cache)
            for k in range(rates.shape[0]):
                states[j, k] *= values[slot, k]
                offsets[k] += states[j, k]
            stamps[j] = time


@jit
def window_rise(b, n_across, i_lo, i_hi, k_lo, k_hi, dt, slot, heat):
    """The history part of the contact temperature under the window ``[i_lo, i_hi) x
    [k_lo, k_hi)`` of bearing ``b`` after a trial step ``dt`` [s] (step factors in ``slot``),
    [W s^0.5 / m^2]; the window becomes the trial's and, once heat is stored, the held one."""
    scalars, windows = heat[SCALARS][b], heat[WINDOWS][b]
    window = windows[TRIAL_WINDOW]
    window[0], window[1], window[2], window[3] = i_lo, i_hi, k_lo, k_hi
    if scalars[FRAME_FIXED] == 0.0:
        return 0.0  # nothing stored before the first heated commit
    held = windows[HELD]
    if i_lo != held[0] or i_hi != held[1] or k_lo != held[2] or k_hi != held[3]:
        move_window(b, n_across, held, window, scalars[HEAT_TIME], heat)
        held[0], held[1], held[2], held[3] = i_lo, i_hi, k_lo, k_hi
        scalars[RISE_VALID] = 0.0
    if scalars[RISE_VALID] == 0.0 or scalars[RISE_STEP] != dt:
        points = max(i_hi - i_lo, 0) * max(k_hi - k_lo, 0)
        scalars[RISE] = window_history(heat[ACCUMULATORS][b], heat[OFFSETS][b],
                                       heat[DECAYS][slot], points)
        scalars[RISE_VALID], scalars[RISE_STEP] = 1.0, dt
    return scalars[RISE]


@jit
def _mark_heated(b, n_across, window, number, heat):
    """The points waiting in bearing ``b``'s pending list that are in ``window`` take the
    mark ``number`` (the heated commit that stores them); the others wait again."""
    marks, pending = heat[MARKS], heat[PENDING_LIST]
    i_lo, i_hi, k_lo, k_hi = window[0], window[1], window[2], window[3]
    for p in range(1, pending[b, 0] + 1):
        j = pending[b, p]
        i, k = j // n_across, j % n_across
        if i_lo <= i < i_hi and k_lo <= k < k_hi:
            marks[b, j] = number
        else:
            marks[b, j] = UNTOUCHED
    pending[b, 0] = 0


@jit
def commit_window(b, n_across, dt, slot, flux, e1x, e1y, heat):
    """One committed step ``dt`` [s] of bearing ``b``'s plate: the trial's window takes
    ``flux`` [W/m^2] (none when it is 0 or the window is empty); the first heated commit fixes
    the frame (e1x, e1y)."""
    scalars, windows = heat[SCALARS][b], heat[WINDOWS][b]
    window = windows[TRIAL_WINDOW]
    points = max(window[1] - window[0], 0) * max(window[3] - window[2], 0)
    if flux != 0.0 and points > 0:
        if scalars[FRAME_FIXED] == 0.0:
            scalars[FRAME_FIXED], scalars[E1X], scalars[E1Y] = 1.0, e1x, e1y
        held = windows[HELD]
        if (window[0] != held[0] or window[1] != held[1] or window[2] != held[2]
                or window[3] != held[3]):
            move_window(b, n_across, held, window, scalars[HEAT_TIME], heat)
            held[0], held[1], held[2], held[3] = window[0], window[1], window[2], window[3]
        scalars[HEAT_COMMITS] += 1.0
        _mark_heated(b, n_across, window, int(scalars[HEAT_COMMITS]), heat)
    else:
        flux = 0.0
    advance_window(heat[ACCUMULATORS][b], heat[OFFSETS][b], heat[FACTORS][slot], flux)
    scalars[HEAT_TIME] += dt
    scalars[RISE_VALID] = 0.0
    if scalars[FRAME_FIXED] != 0.0:
        scalars[ANCHORED_AGO] += 1.0
        if scalars[ANCHORED_AGO] >= REANCHOR_EVERY:
            reanchor_window(b, n_across, windows[HELD], scalars[HEAT_TIME], heat)
            scalars[ANCHORED_AGO] = 0.0


@jit
def field_temperatures(b, points, inside, time, initial_temperature, coefficient, heat, out):
    """Temperatures [degC] of bearing ``b``'s stored ``points`` (flat indices) at the heat
    clock's ``time`` into ``out``: T0 + coefficient sum_k w_k G_jk, with G_j = exp(-s (t -
    tau_j)) B_j for a point out of the window and that plus the accumulator A for one in it
    (``inside``); the plate field of a run, one pass over the points."""
    rates, weights, states, stamps = heat[RATES], heat[WEIGHTS], heat[STATES][b], heat[STAMPS][b]
    accumulator = heat[ACCUMULATORS][b]
    for m in range(points.shape[0]):
        j = points[m]
        elapsed = time - stamps[j]
        total = 0.0
        for k in range(rates.shape[0]):
            exponent = elapsed * rates[k]
            history = 0.0 if exponent > UNDERFLOW else states[j, k] * math.exp(-exponent)
            if inside[m]:
                history += accumulator[k]
            total += history * weights[k]
        out[m] = initial_temperature + coefficient * total
