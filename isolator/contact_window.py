"""The heat history of a monitor line held for the points under the slider as one group.

:class:`~isolator.heating.SurfaceHeating` keeps a state vector G_j (K exponential terms) for
every monitor point and, at every step, advances all the points ever heated
(:func:`~isolator.compiled.kernels.advance_states`, O(points x K)) and averages the ones under the
slider afresh for every trial (:func:`~isolator.compiled.kernels.contact_history`, O(window x K)).
The points under the slider all take the same flux, so they can be carried as a group (this
module), and the cost per step becomes O(K) plus O(K) for each point that enters or leaves the
window:

- a point outside the window keeps ``B_j``, its G at its ``stamp`` tau_j, and only decays:
  G_j(t) = exp(-s (t - tau_j)) B_j;
- an ``accumulator`` A(t) holds the history of a point heated at every step since t = 0,
  A <- exp(-s dt) A + q (1 - exp(-s dt)) / s (the update of :func:`advance_states`);
- a point inside the window keeps ``C_j`` = G_j(tau_j) - A(tau_j), so that
  G_j(t) = A(t) + exp(-s (t - tau_j)) C_j, and the window holds
  ``offsets`` E(t) = sum_j exp(-s (t - tau_j)) C_j;
- the column sums over the window are W A + E, and the history part of the contact
  temperature (``contact_history``) is sum_k w_k exp(-s_k dt) (W A_k + E_k) / W.

When the slider moves, the points leaving the window get G_j back and those entering get their
C_j, at the time of the last commit (trials never change the history's time). These are exact
rearrangements of SurfaceHeating's update: only the round-off differs (relative 1e-13 on the
examples), and :func:`reanchor_window` re-forms E from the points every so often so that it
cannot drift. ``states`` is the (points, K) array holding B_j or C_j; ``touched`` is the range of
points ever in the window (the others are zero). Every function is a compiled kernel with a
plain-Python twin (see :mod:`isolator.compiled.kernels`).
"""

from __future__ import annotations

import math

from isolator.compiled.kernels import jit


@jit
def _leave(states, stamps, accumulator, offsets, rates, j, time):
    """Point ``j`` leaves the window at ``time`` [s]: its G_j = A + exp(-s dt) C_j is kept."""
    elapsed = time - stamps[j]
    for k in range(rates.shape[0]):
        carried = states[j, k] if elapsed == 0.0 else states[j, k] * math.exp(
            -rates[k] * elapsed)
        offsets[k] -= carried
        states[j, k] = accumulator[k] + carried
    stamps[j] = time


@jit
def _enter(states, stamps, accumulator, offsets, rates, j, time, untouched):
    """Point ``j`` enters the window at ``time`` [s]: it keeps C_j = G_j - A."""
    elapsed = time - stamps[j]
    for k in range(rates.shape[0]):
        if untouched:
            value = 0.0
        elif elapsed == 0.0:
            value = states[j, k]
        else:
            value = states[j, k] * math.exp(-rates[k] * elapsed)
        states[j, k] = value - accumulator[k]
        offsets[k] += states[j, k]
    stamps[j] = time


@jit
def move_window(states, stamps, accumulator, offsets, rates, lo, hi, new_lo, new_hi,
                touched_lo, touched_hi, time):
    """Make ``[new_lo, new_hi)`` the window in place of ``[lo, hi)`` at ``time`` [s].

    ``time`` is the time of the last commit. Returns the ever-touched range
    ``(touched_lo, touched_hi)`` grown by the new window.
    """
    for j in range(lo, hi):
        if j < new_lo or j >= new_hi:
            _leave(states, stamps, accumulator, offsets, rates, j, time)
    for j in range(new_lo, new_hi):
        if j < lo or j >= hi:
            _enter(states, stamps, accumulator, offsets, rates, j, time,
                   j < touched_lo or j >= touched_hi)
    if new_hi > new_lo:
        touched_lo, touched_hi = min(touched_lo, new_lo), max(touched_hi, new_hi)
    return touched_lo, touched_hi


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
    """:func:`~isolator.compiled.kernels.contact_history` of the window of ``points`` points.

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
def reanchor_window(states, stamps, offsets, rates, lo, hi, time):
    """Re-stamp the window's points at ``time`` [s] and sum E afresh (bounds its round-off)."""
    for k in range(offsets.shape[0]):
        offsets[k] = 0.0
    for j in range(lo, hi):
        elapsed = time - stamps[j]
        for k in range(offsets.shape[0]):
            if elapsed != 0.0:
                states[j, k] *= math.exp(-rates[k] * elapsed)
            offsets[k] += states[j, k]
        stamps[j] = time
