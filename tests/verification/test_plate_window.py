"""The monitor points' heat history held as a group equals the point-by-point one.

``isolator.compiled.plate`` rearranges ``advance_states`` / ``contact_history`` exactly; on a
random walk of the slider along a line (one row across) and over a grid, with random fluxes,
uneven steps and steps without heat, the contact history and every point's state agree to
round-off, in the compiled and the Python forms.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.compiled import plate as P
from isolator.compiled.kernels import advance_states, contact_history
from isolator.heating import step_factors, sum_of_exponentials


def _point_state(heat, j, window, n_across, time):
    """G_j at ``time`` from the group form (for the check)."""
    rates = heat.rates
    stamp = heat.stamps[0, j]
    if stamp < 0.0:
        return np.zeros(rates.size)
    decay = np.exp(-rates * (time - stamp))
    i, k = divmod(j, n_across)
    inside = window[0] <= i < window[1] and window[2] <= k < window[3]
    state = decay * heat.states[0, j]
    return heat.accumulators[0] + state if inside else state


def _rows(window, n_across):
    """Flat indices of a window's points."""
    return [i * n_across + k for i in range(window[0], window[1])
            for k in range(window[2], window[3])]


@pytest.mark.parametrize("n_across", [1, 9], ids=["line", "grid"])
@pytest.mark.parametrize("python", [False, True], ids=["compiled", "python"])
def test_group_form_equals_point_by_point(python, n_across):
    kernel = sum_of_exponentials()
    rates, weights = kernel.rates, kernel.weights
    n_along, n_terms = 120, rates.size
    points = n_along * n_across
    functions = {name: getattr(P, name) for name in (
        "move_window", "advance_window", "window_history", "reanchor_window")}
    if python:
        functions = {name: getattr(f, "py_func", f) for name, f in functions.items()}
    rng = np.random.default_rng(3)
    reference = np.zeros((points, n_terms))  # the reference: advance_states on every point
    heat = P.new_plate_heating(1, points, rates, weights)
    held = np.zeros(4, dtype=np.int64)
    step, weighted = np.empty((2, n_terms)), np.empty(n_terms)
    time, centre = 0.0, 60.0
    for n in range(400):
        dt = 0.005 if n % 7 else 0.0025  # uneven steps, as after a halving
        step_factors(rates, weights, 1.0, dt, step, weighted)
        for _ in range(3):  # Newton's trials move the window back and forth
            centre = float(np.clip(centre + rng.normal(0.0, 1.5), 25.0, 95.0))
            across = int(rng.integers(0, 3)) if n_across > 1 else 0
            new = np.array([int(centre) - 20, int(centre) + 21, across,
                            across + (6 if n_across > 1 else 1)], dtype=np.int64)
            functions["move_window"](0, n_across, held, new, time, heat.rates, heat.states[0],
                                     heat.stamps[0], heat.accumulators[0], heat.offsets[0],
                                     heat.cache_keys, heat.cache_values, heat.cache_state,
                                     heat.marks[0], heat.pending[0])
            held[:] = new
            rows = _rows(held, n_across)
            expected = float(np.sum(reference[rows], axis=0) @ weighted) / len(rows)
            got = functions["window_history"](heat.accumulators[0], heat.offsets[0], weighted,
                                              len(rows))
            assert got == pytest.approx(expected, rel=1e-12, abs=1e-300)
        flux = 0.0 if n % 11 == 0 else float(rng.uniform(1e4, 1e6))
        if n_across == 1:  # the kernel in one direction on the line itself
            lo, hi = int(held[0]), int(held[1])
            advance_states(reference, step, 0, points, lo, hi, flux)
            assert contact_history(reference, weighted, lo, hi) == pytest.approx(
                float(np.sum(reference[lo:hi], axis=0) @ weighted) / (hi - lo), rel=1e-13)
        else:
            inside = np.zeros(points, dtype=bool)
            inside[_rows(held, n_across)] = True
            reference[inside] = reference[inside] * step[0] + flux * step[1]
            reference[~inside] *= step[0]
        functions["advance_window"](heat.accumulators[0], heat.offsets[0], step, flux)
        time += dt
        if n % 97 == 0:
            functions["reanchor_window"](0, n_across, held, time, heat.rates, heat.states[0],
                                         heat.stamps[0], heat.offsets[0], heat.cache_keys,
                                         heat.cache_values, heat.cache_state)
    scale = np.abs(reference).max(axis=0)
    for j in range(points):
        state = _point_state(heat, j, held, n_across, time)
        assert np.all(np.abs(state - reference[j]) <= 1e-11 * scale + 1e-300), j


def test_an_empty_window_has_no_history():
    assert P.window_history(np.ones(3), np.ones(3), np.ones(3), 0) == 0.0
