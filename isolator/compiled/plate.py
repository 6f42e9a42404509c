"""The precise model's monitor points on a plate, held for the compiled element in array form.

The points form a rectangle of ``n_along`` x ``n_across``, point ``(i, k)`` at flat index
``j = i n_across + k`` (``i`` along the frame's e1, ``k`` along e2): the n x n grid of
:class:`~isolator.monitor_grid.GridHeating`, or the line of
:class:`~isolator.heating.SurfaceHeating` (``n_across = 1``, e1 along x). The points under the
slider all take the same flux, so they are held as one group: a trial costs O(K) (K
exponential terms) and a step O(K) plus O(K) per point entering or leaving the window:

- a point outside the window keeps ``B_j`` = G_j at its ``stamp`` tau_j and decays implicitly,
  G_j(t) = exp(-s (t - tau_j)) B_j; ``stamp < 0`` marks a point never touched (G = 0);
- an ``accumulator`` A holds the history of a point heated at every step since t = 0,
  A <- exp(-s dt) A + q (1 - exp(-s dt)) / s (:func:`advance_window`);
- a point inside keeps ``C_j`` = G_j(tau_j) - A(tau_j), and the ``offsets``
  E(t) = sum_j exp(-s (t - tau_j)) C_j, so the history part of the contact temperature over the
  window's W points is sum_k w_k exp(-s_k dt) (W A_k + E_k) / W (:func:`window_history`);
- a move touches only the difference of two rectangles (:func:`move_window`), the decay factors
  of points sharing a stamp computed once (a small cache keyed by stamp, for one bearing and
  time); :func:`reanchor_window` re-forms E every ``REANCHOR_EVERY`` heated commits against drift.

A point entering the window waits on ``pending`` until the next commit that heats the window
gives it that commit's number (``marks``): the reference's order of storage is that of
(mark, i, k). All times are the heat history's clock (the committed heated steps' sum), not the
element's. These are exact rearrangements of the reference's updates: only round-off differs.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from isolator.compiled.kernels import jit_unmanaged
from isolator.heating import step_factors

UNTOUCHED, PENDING_MARK = -1, -2  # ``marks`` of a point never heated, and of one waiting
UNDERFLOW = 745.2  # exp(-x) rounds to 0.0 beyond it (libm's underflow path is slow)
CACHE_SLOTS = 64  # decay vectors kept per move (a power of two)
# Layout of ``cache_state``: the bearing and the time the cached decay vectors are for.
CACHE_BEARING, CACHE_TIME = range(2)

# Per-bearing scalars of the heat history (``heat.scalars[b]``).
HEAT_TIME, RISE, RISE_VALID, RISE_STEP, FRAME_FIXED, E1X, E1Y = range(7)
HEAT_COMMITS, ANCHORED_AGO = 7, 8
SCALARS_SIZE = 9
# Rows of ``heat.windows[b]`` (int64, 4 columns i_lo, i_hi, k_lo, k_hi): the window held as
# a group, and the last trial's.
HELD, TRIAL_WINDOW = range(2)
# The step-factor table shared by the bearings (``heat.table``) and its ``heat.slots`` rows.
PREPARED_STEP, SLOT, NEXT_SLOT = range(3)
SLOT_STEP, SLOT_NEWEST = range(2)
FACTOR_SLOTS = 32  # distinct step sizes whose factors are kept (one run has about 15)
REANCHOR_EVERY = 1024  # heated commits between fresh sums of a window (bounds its drift)


class PlateHeat(NamedTuple):
    """The heat history of the plates of every bearing row (K exponential terms, ``points``
    monitor points per plate); the compiled functions take its arrays one by one.

    Attributes
    ----------
    rates, weights : ndarray, shape (K,)
        The kernel's s_k [1/s] and w_k [s^-0.5].
    states, stamps : ndarray, shape (n_b, points, K), (n_b, points)
        B_j or C_j of each point (module docstring) [W s^0.5 / m^2], and when it was last
        brought up to date on the heat clock [s] (-1: never).
    marks, pending : ndarray of int64, shape (n_b, points), (n_b, points + 1)
        The heated commit that stored each point (or ``UNTOUCHED``, ``PENDING_MARK``); the
        points waiting for a mark: their number, then their indices.
    accumulators, offsets : ndarray, shape (n_b, K)
        A and E of each plate's window.
    cache_keys, cache_values, cache_state : ndarray, shape (CACHE_SLOTS,), (CACHE_SLOTS, K), (2,)
        Decay vectors exp(-s (t - tau)) by stamp tau, for one bearing and time.
    scalars : ndarray, shape (n_b, SCALARS_SIZE)
        ``HEAT_TIME`` ... ``ANCHORED_AGO`` of each plate.
    factors, decays, slots : ndarray, shape (S, 2, K), (S, K), (S, 2), S = FACTOR_SLOTS
        Per step size: exp(-s dt) and (1 - exp(-s dt)) / s; w exp(-s dt); the step [s] and
        2 c sqrt(dt) [degC m^2 / W].
    table : ndarray, shape (3,)
        ``PREPARED_STEP``, ``SLOT``, ``NEXT_SLOT``.
    windows : ndarray of int64, shape (n_b, 2, 4)
        The window held (``HELD``) and the last trial's (``TRIAL_WINDOW``) of each plate.
    """

    rates: np.ndarray
    weights: np.ndarray
    states: np.ndarray
    stamps: np.ndarray
    marks: np.ndarray
    pending: np.ndarray
    accumulators: np.ndarray
    offsets: np.ndarray
    cache_keys: np.ndarray
    cache_values: np.ndarray
    cache_state: np.ndarray
    scalars: np.ndarray
    factors: np.ndarray
    decays: np.ndarray
    slots: np.ndarray
    table: np.ndarray
    windows: np.ndarray


def new_plate_heating(n_bearings: int, points: int, rates: np.ndarray,
                      weights: np.ndarray) -> PlateHeat:
    """The heat history of ``n_bearings`` plates of ``points`` monitor points each
    (n_along x n_across; 1 for the centre point) for the kernel's ``rates`` [1/s] and
    ``weights`` [s^-0.5], shape (K,): zero history, unheated, no frame."""
    k = rates.shape[0]
    return PlateHeat(
        np.array(rates, dtype=float, order="C"), np.array(weights, dtype=float, order="C"),
        np.zeros((n_bearings, points, k)), np.full((n_bearings, points), -1.0),
        np.full((n_bearings, points), UNTOUCHED, dtype=np.int64),
        np.zeros((n_bearings, points + 1), dtype=np.int64), np.zeros((n_bearings, k)),
        np.zeros((n_bearings, k)), np.full(CACHE_SLOTS, -1.0), np.zeros((CACHE_SLOTS, k)),
        np.array([-1.0, -1.0]), np.zeros((n_bearings, SCALARS_SIZE)),
        np.zeros((FACTOR_SLOTS, 2, k)), np.zeros((FACTOR_SLOTS, k)),
        np.full((FACTOR_SLOTS, 2), -1.0), np.array([-1.0, 0.0, 0.0]),
        np.zeros((n_bearings, 2, 4), dtype=np.int64))


@jit_unmanaged
def prepare_step(dt, coefficient, min_lag, rates, weights, factors, decays, slots, table):
    """The slot of the step factors of ``dt`` [s] in the shared table (``PlateHeat``'s
    arrays), computed if new (:func:`isolator.heating.step_factors`); -1 when ``dt`` is below
    the kernel's shortest lag (the reference's ValueError)."""
    if dt == table[PREPARED_STEP]:
        return np.int64(table[SLOT])
    if dt < min_lag:
        return np.int64(-1)
    for slot in range(slots.shape[0]):
        if slots[slot, SLOT_STEP] == dt:
            table[PREPARED_STEP], table[SLOT] = dt, slot
            return np.int64(slot)
    slot = np.int64(table[NEXT_SLOT])
    table[NEXT_SLOT] = (slot + 1) % slots.shape[0]
    slots[slot, SLOT_NEWEST] = step_factors(rates, weights, coefficient, dt, factors[slot],
                                            decays[slot])
    slots[slot, SLOT_STEP] = dt
    table[PREPARED_STEP], table[SLOT] = dt, slot
    return slot


@jit_unmanaged
def advance_window(accumulator, offsets, step, flux):
    """One committed step of the window: every point in it takes the ``flux`` [W/m^2]; ``step``
    as for :func:`~isolator.compiled.kernels.advance_states`; points outside are untouched."""
    decay = step[0]
    gain = step[1]
    for k in range(accumulator.shape[0]):
        accumulator[k] = accumulator[k] * decay[k] + flux * gain[k]
        offsets[k] *= decay[k]


@jit_unmanaged
def window_history(accumulator, offsets, weighted_decay, points):
    """:func:`~isolator.compiled.kernels.contact_history` of a window of ``points`` points:
    sum_k w_k exp(-s_k dt) (points A_k + E_k) / points [W s^0.5 / m^2]; 0 for an empty one."""
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


@jit_unmanaged
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


@jit_unmanaged
def move_window(b, n_across, old, new, time, rates, states, stamps, accumulator, offsets, keys,
                values, cache, marks, pending):
    """Make the rectangle ``new`` the window of bearing ``b`` in place of ``old`` at ``time``.

    ``old`` and ``new`` are (i_lo, i_hi, k_lo, k_hi) (either may be empty); ``n_across``
    points per column; the arrays are ``PlateHeat``'s, those of the bearing (``states`` ...
    ``pending``) its rows. Points leaving keep G_j = A + exp(-s (t - tau_j)) C_j, points
    entering C_j = G_j - A; four passes over lines of points sharing their stamps (the old
    points, then the new, each by whole columns, then rows of the columns both hold).
    """
    n_terms = rates.shape[0]
    a0, a1, b0, b1 = old[0], old[1], old[2], old[3]
    c0, c1, d0, d1 = new[0], new[1], new[2], new[3]
    if a1 <= a0 or b1 <= b0:  # an empty rectangle holds no column
        a0 = a1 = b0 = b1 = 0
    both_lo, both_hi = max(a0, c0), min(a1, c1)
    for phase in range(4):
        entering = phase >= 2
        columns = phase % 2 == 0
        if phase == 0:  # the lines of this pass and the rectangle they must not be in
            lo, hi, out_lo, out_hi, along_lo, along_hi = a0, a1, c0, c1, b0, b1
        elif phase == 1:
            lo, hi, out_lo, out_hi, along_lo, along_hi = b0, b1, d0, d1, both_lo, both_hi
        elif phase == 2:
            lo, hi, out_lo, out_hi, along_lo, along_hi = c0, c1, a0, a1, d0, d1
        else:
            lo, hi, out_lo, out_hi, along_lo, along_hi = d0, d1, b0, b1, both_lo, both_hi
        if along_hi <= along_lo:
            continue
        for line in range(lo, hi):
            if out_lo <= line < out_hi:
                continue
            if columns:  # the points (line, k), k in [along_lo, along_hi)
                first, stride = line * n_across + along_lo, 1
            else:  # the points (i, line), i in [along_lo, along_hi)
                first, stride = along_lo * n_across + line, n_across
            slot, previous = 0, -2.0
            for m in range(along_hi - along_lo):
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


@jit_unmanaged
def reanchor_window(b, n_across, window, time, rates, states, stamps, offsets, keys, values,
                    cache):
    """Re-stamp bearing ``b``'s window points at ``time`` and sum E afresh (bounds drift);
    the arrays as for :func:`move_window`."""
    for k in range(rates.shape[0]):
        offsets[k] = 0.0
    for i in range(window[0], window[1]):
        for j in range(i * n_across + window[2], i * n_across + window[3]):
            slot = _decay_slot(stamps[j], time, b, rates, keys, values, cache)
            for k in range(rates.shape[0]):
                states[j, k] *= values[slot, k]
                offsets[k] += states[j, k]
            stamps[j] = time


@jit_unmanaged
def field_temperatures(points, inside, time, initial_temperature, coefficient, rates, weights,
                       states, stamps, accumulator, out):
    """Temperatures [degC] of a bearing's stored ``points`` (flat indices) at the heat clock's
    ``time`` into ``out``: T0 + coefficient sum_k w_k G_jk, G_j = exp(-s (t - tau_j)) B_j, plus
    A for a point in the window (``inside``); the arrays as for :func:`move_window`."""
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
