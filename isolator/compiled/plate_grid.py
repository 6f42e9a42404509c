"""The precise model's monitor grid over a plate, held for the compiled engine in array form.

:class:`~isolator.plate_heating.GridHeating` stores a history G_j (K exponential terms) for
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

from isolator.compiled.kernels import jit

# The heat history's arrays travel as one tuple (:func:`isolator.compiled.plate.new_plate_heating`),
# in this order; the per-bearing ones have the bearing first.
RATES, WEIGHTS, STATES, STAMPS, MARKS, PENDING_LIST, ACCUMULATORS, OFFSETS = range(8)
CACHE_KEYS, CACHE_VALUES, CACHE_STATE, SCALARS, FACTORS, DECAYS, SLOTS, TABLE = range(8, 16)
WINDOWS = 16

UNTOUCHED, PENDING_MARK = -1, -2  # ``marks`` of a point never heated, and of one waiting
CACHE_SLOTS = 64  # decay vectors kept per move (a power of two)
# Layout of ``cache_state``: the bearing and the time the cached decay vectors are for.
CACHE_BEARING, CACHE_TIME = range(2)


@jit
def _decay_vector(stamp, time, bearing, heat):
    """exp(-s_k (time - stamp)) for this bearing and time: a row of the cache."""
    rates, cache_keys = heat[RATES], heat[CACHE_KEYS]
    cache_values, cache_state = heat[CACHE_VALUES], heat[CACHE_STATE]
    if cache_state[CACHE_BEARING] != bearing or cache_state[CACHE_TIME] != time:
        for slot in range(cache_keys.shape[0]):
            cache_keys[slot] = -1.0
        cache_state[CACHE_BEARING], cache_state[CACHE_TIME] = bearing, time
    slot = int(stamp * 1048576.0) & (cache_keys.shape[0] - 1)
    if cache_keys[slot] != stamp:
        elapsed = time - stamp
        for k in range(rates.shape[0]):
            cache_values[slot, k] = math.exp(-rates[k] * elapsed)
        cache_keys[slot] = stamp
    return cache_values[slot]


@jit
def _leave(b, j, time, heat):
    """Point ``j`` of bearing ``b`` leaves the window at ``time``: it keeps G_j = A + C_j."""
    rates, states, stamps = heat[RATES], heat[STATES], heat[STAMPS]
    accumulator, offsets = heat[ACCUMULATORS][b], heat[OFFSETS][b]
    decay = _decay_vector(stamps[b, j], time, b, heat)
    for k in range(rates.shape[0]):
        carried = states[b, j, k] * decay[k]
        offsets[k] -= carried
        states[b, j, k] = accumulator[k] + carried
    stamps[b, j] = time


@jit
def _enter(b, j, time, heat):
    """Point ``j`` of bearing ``b`` enters the window at ``time``: it keeps C_j = G_j - A."""
    rates, states, stamps = heat[RATES], heat[STATES], heat[STAMPS]
    marks, pending = heat[MARKS], heat[PENDING_LIST]
    accumulator, offsets = heat[ACCUMULATORS][b], heat[OFFSETS][b]
    if stamps[b, j] < 0.0:  # never touched: G = 0
        for k in range(rates.shape[0]):
            states[b, j, k] = -accumulator[k]
            offsets[k] -= accumulator[k]
    else:
        decay = _decay_vector(stamps[b, j], time, b, heat)
        for k in range(rates.shape[0]):
            value = states[b, j, k] * decay[k] - accumulator[k]
            states[b, j, k] = value
            offsets[k] += value
    stamps[b, j] = time
    if marks[b, j] == UNTOUCHED:  # waits for the next heated commit to be numbered
        marks[b, j] = PENDING_MARK
        count = pending[b, 0]
        pending[b, count + 1] = j
        pending[b, 0] = count + 1


@jit
def move_grid_window(b, n, old, new, time, heat):
    """Make the rectangle ``new`` the window of bearing ``b`` in place of ``old`` at ``time``.

    ``old`` and ``new`` are (i_lo, i_hi, k_lo, k_hi) (either may be empty); ``n`` points per
    axis; ``heat`` is the tuple of :func:`isolator.compiled.plate.new_plate_heating`.
    """
    a0, a1, b0, b1 = old[0], old[1], old[2], old[3]
    c0, c1, d0, d1 = new[0], new[1], new[2], new[3]
    for i in range(a0, a1):  # old points not in the new rectangle
        if i < c0 or i >= c1:
            for k in range(b0, b1):
                _leave(b, i * n + k, time, heat)
        else:
            for k in range(b0, min(b1, d0)):
                _leave(b, i * n + k, time, heat)
            for k in range(max(b0, d1), b1):
                _leave(b, i * n + k, time, heat)
    for i in range(c0, c1):  # new points not in the old rectangle
        if i < a0 or i >= a1:
            for k in range(d0, d1):
                _enter(b, i * n + k, time, heat)
        else:
            for k in range(d0, min(d1, b0)):
                _enter(b, i * n + k, time, heat)
            for k in range(max(d0, b1), d1):
                _enter(b, i * n + k, time, heat)


@jit
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
    rates, states, stamps = heat[RATES], heat[STATES], heat[STAMPS]
    offsets = heat[OFFSETS][b]
    for k in range(rates.shape[0]):
        offsets[k] = 0.0
    for i in range(window[0], window[1]):
        for kk in range(window[2], window[3]):
            j = i * n + kk
            decay = _decay_vector(stamps[b, j], time, b, heat)
            for k in range(rates.shape[0]):
                states[b, j, k] *= decay[k]
                offsets[k] += states[b, j, k]
            stamps[b, j] = time
