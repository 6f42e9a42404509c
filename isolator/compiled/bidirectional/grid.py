"""The precise model's monitor grid over a plate, held for the compiled engine in array form.

:class:`~isolator.bidirectional.heating.GridHeating` stores a history G_j (K exponential terms) for
every point ever heated and, per trial, decays and sums the points under the slider (about
2,800 for a 300 mm slider at 5 mm spacing: 140,000 terms per trial). Here the points under the
slider are carried as one group, as :mod:`isolator.contact_window` does on a line, so a trial
costs O(K) and a step O(K) plus O(K) per point entering or leaving the square under the slider:

- the grid is dense over the plate's reachable square, ``points`` = n x n, point ``(i, k)`` at
  flat index ``j = i n + k`` (``i`` along the grid's first axis e1, ``k`` along e2);
- a point outside the window keeps ``B_j`` = G_j at its ``stamp`` and decays implicitly
  (G_j(t) = exp(-s (t - tau_j)) B_j); ``stamp < 0`` marks a point never touched (G = 0);
- the window keeps, per point, ``C_j`` = G_j(tau_j) - A(tau_j), with the ``accumulator`` A of
  a point heated at every step and the ``offsets`` E = sum_j exp(-s (t - tau_j)) C_j, so the
  window's column sums are W A + E (:func:`~isolator.contact_window.window_history`);
- the window is a rectangle of indices, so a move touches only the difference of two
  rectangles (:func:`move_grid_window`).

The decay factors exp(-s (t - tau_j)) of the points that move depend on tau_j alone, and the
points of a row or column entered or left together share it: a small cache keyed by the stamp
(``cache_keys``, ``cache_values``, valid for one bearing and one time) makes a move cost one
set of K exponentials per distinct stamp, not per point.

Which points the reference stores (the plate temperature field of a run) is kept too: a point
entering the window is put on a ``pending`` list, and the next commit that heats the window
gives it the number of that commit (``marks``); the reference's order of storage is then the
order of (mark, i, k).

All times are the heat history's own clock (the sum of the committed heated steps, as
``GridHeating``'s), never the element's. Every function is a compiled kernel with a
plain-Python twin (:mod:`isolator.compiled.kernels`).
"""

from __future__ import annotations

import math

from isolator.compiled import kernels
from isolator.compiled.kernels import jit

if kernels.COMPILED:  # pragma: no cover - depends on the environment
    import numba

    def inlined(function):
        """Compiled and inlined into its caller at numba's level: a call that takes the heat
        tuple otherwise pays a reference count on each of its arrays (~0.2 us a call)."""
        return numba.njit(cache=True, nogil=True, no_cfunc_wrapper=True,
                          inline="always")(function)
else:  # pragma: no cover
    inlined = jit


# The heat history's arrays travel as one tuple
# (:func:`isolator.compiled.bidirectional.bearing.new_plate_heating`),
# in this order; the per-bearing ones have the bearing first.
RATES, WEIGHTS, STATES, STAMPS, MARKS, PENDING_LIST, ACCUMULATORS, OFFSETS = range(8)
CACHE_KEYS, CACHE_VALUES, CACHE_STATE, SCALARS, FACTORS, DECAYS, SLOTS, TABLE = range(8, 16)
WINDOWS = 16

UNTOUCHED, PENDING_MARK = -1, -2  # ``marks`` of a point never heated, and of one waiting
UNDERFLOW = 745.2  # exp(-x) rounds to 0.0 beyond it (libm's underflow path is slow)
CACHE_SLOTS = 64  # decay vectors kept per move (a power of two)
# Layout of ``cache_state``: the bearing and the time the cached decay vectors are for.
CACHE_BEARING, CACHE_TIME = range(2)


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
def _leave(b, first, count, stride, time, rates, states, stamps, accumulator, offsets,
           cache_keys, cache_values, cache_state):
    """Points ``first + m stride``, m < ``count``, of bearing ``b`` (2D ``states`` of that
    bearing) leave the window at ``time``: each keeps G_j = A + exp(-s (t - tau_j)) C_j."""
    slot, previous = 0, -2.0
    for m in range(count):
        j = first + m * stride
        if stamps[j] != previous:
            previous = stamps[j]
            slot = _decay_slot(previous, time, b, rates, cache_keys, cache_values, cache_state)
        for k in range(rates.shape[0]):
            carried = states[j, k] * cache_values[slot, k]
            offsets[k] -= carried
            states[j, k] = accumulator[k] + carried
        stamps[j] = time


@jit
def _enter(b, first, count, stride, time, rates, states, stamps, accumulator, offsets,
           cache_keys, cache_values, cache_state, marks, pending):
    """Points ``first + m stride``, m < ``count``, of bearing ``b`` enter the window at
    ``time``: each keeps C_j = G_j - A; those never heated wait on the ``pending`` list."""
    slot, previous = 0, -2.0
    for m in range(count):
        j = first + m * stride
        if stamps[j] < 0.0:  # never touched: G = 0
            for k in range(rates.shape[0]):
                states[j, k] = -accumulator[k]
                offsets[k] -= accumulator[k]
        else:
            if stamps[j] != previous:
                previous = stamps[j]
                slot = _decay_slot(previous, time, b, rates, cache_keys, cache_values,
                                   cache_state)
            for k in range(rates.shape[0]):
                value = states[j, k] * cache_values[slot, k] - accumulator[k]
                states[j, k] = value
                offsets[k] += value
        stamps[j] = time
        if marks[j] == UNTOUCHED:  # waits for the next heated commit to be numbered
            marks[j] = PENDING_MARK
            count = pending[0] + 1
            pending[count] = j
            pending[0] = count


@jit
def move_grid_window(b, n, old, new, time, heat):
    """Make the rectangle ``new`` the window of bearing ``b`` in place of ``old`` at ``time``.

    ``old`` and ``new`` are (i_lo, i_hi, k_lo, k_hi) (either may be empty); ``n`` points per
    axis; ``heat`` is the tuple of
    :func:`isolator.compiled.bidirectional.bearing.new_plate_heating`.
    """
    rates, states, stamps = heat[RATES], heat[STATES][b], heat[STAMPS][b]
    accumulator, offsets = heat[ACCUMULATORS][b], heat[OFFSETS][b]
    keys, values, cache = heat[CACHE_KEYS], heat[CACHE_VALUES], heat[CACHE_STATE]
    marks, pending = heat[MARKS][b], heat[PENDING_LIST][b]
    a0, a1, b0, b1 = old[0], old[1], old[2], old[3]
    c0, c1, d0, d1 = new[0], new[1], new[2], new[3]
    if a1 <= a0 or b1 <= b0:  # an empty rectangle holds no column
        a0 = a1 = b0 = b1 = 0
    # the old points not in the new rectangle: whole columns (contiguous in memory), then
    # the rows of the columns both hold (strided by a column)
    both_lo, both_hi = max(a0, c0), min(a1, c1)
    for i in range(a0, a1):
        if (i < c0 or i >= c1) and b1 > b0:
            _leave(b, i * n + b0, b1 - b0, 1, time, rates, states, stamps, accumulator,
                   offsets, keys, values, cache)
    if both_hi > both_lo:
        for k in range(b0, b1):
            if k < d0 or k >= d1:
                _leave(b, both_lo * n + k, both_hi - both_lo, n, time, rates, states, stamps,
                       accumulator, offsets, keys, values, cache)
    # the new points not in the old rectangle, the same way
    for i in range(c0, c1):
        if (i < a0 or i >= a1) and d1 > d0:
            _enter(b, i * n + d0, d1 - d0, 1, time, rates, states, stamps, accumulator,
                   offsets, keys, values, cache, marks, pending)
    if both_hi > both_lo:
        for k in range(d0, d1):
            if k < b0 or k >= b1:
                _enter(b, both_lo * n + k, both_hi - both_lo, n, time, rates, states, stamps,
                       accumulator, offsets, keys, values, cache, marks, pending)


@inlined
def mark_heated(b, n, window, number, heat):
    """The points waiting in bearing ``b``'s pending list that are in ``window`` take the
    mark ``number`` (the heated commit that stores them); the others wait again."""
    marks, pending = heat[MARKS], heat[PENDING_LIST]
    i_lo, i_hi, k_lo, k_hi = window[0], window[1], window[2], window[3]
    for p in range(1, pending[b, 0] + 1):
        j = pending[b, p]
        i, k = j // n, j % n
        if i_lo <= i < i_hi and k_lo <= k < k_hi:
            marks[b, j] = number
        else:
            marks[b, j] = UNTOUCHED
    pending[b, 0] = 0


@jit
def reanchor_grid_window(b, n, window, time, heat):
    """Re-stamp bearing ``b``'s window points at ``time`` and sum E afresh (bounds drift)."""
    rates, states, stamps = heat[RATES], heat[STATES][b], heat[STAMPS][b]
    keys, values, cache = heat[CACHE_KEYS], heat[CACHE_VALUES], heat[CACHE_STATE]
    offsets = heat[OFFSETS][b]
    for k in range(rates.shape[0]):
        offsets[k] = 0.0
    for i in range(window[0], window[1]):
        for j in range(i * n + window[2], i * n + window[3]):
            slot = _decay_slot(stamps[j], time, b, rates, keys, values, cache)
            for k in range(rates.shape[0]):
                states[j, k] *= values[slot, k]
                offsets[k] += states[j, k]
            stamps[j] = time


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
