"""The monitor line's heat history held as a group equals the point-by-point one.

``isolator.contact_window`` rearranges ``advance_states`` / ``contact_history`` exactly; on a
random walk of the slider with random fluxes, uneven steps and steps without heat, the contact
history and every point's state agree to round-off, in the compiled and the Python forms.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator import contact_window as cw
from isolator.compiled.kernels import advance_states, contact_history
from isolator.heating import step_factors, sum_of_exponentials


def _point_state(states, stamps, accumulator, rates, j, lo, hi, time):
    """G_j at ``time`` from the group form (for the check)."""
    decay = np.exp(-rates * (time - stamps[j]))
    return accumulator + decay * states[j] if lo <= j < hi else decay * states[j]


@pytest.mark.parametrize("python", [False, True], ids=["compiled", "python"])
def test_group_form_equals_point_by_point(python):
    kernel = sum_of_exponentials()
    rates, weights = kernel.rates, kernel.weights
    n_points, n_terms = 120, rates.size
    functions = {name: getattr(cw, name) for name in (
        "move_window", "advance_window", "window_history", "reanchor_window")}
    if python:
        functions = {name: getattr(f, "py_func", f) for name, f in functions.items()}
    rng = np.random.default_rng(3)
    points = np.zeros((n_points, n_terms))  # the reference: advance_states
    touched = (n_points, 0)
    states, stamps = np.zeros((n_points, n_terms)), np.zeros(n_points)
    accumulator, offsets = np.zeros(n_terms), np.zeros(n_terms)
    lo = hi = 0
    group_touched = (n_points, 0)
    step, weighted = np.empty((2, n_terms)), np.empty(n_terms)
    time, centre = 0.0, 60.0
    for n in range(600):
        dt = 0.005 if n % 7 else 0.0025  # uneven steps, as after a halving
        step_factors(rates, weights, 1.0, dt, step, weighted)
        for _ in range(3):  # Newton's trials move the window back and forth
            centre = float(np.clip(centre + rng.normal(0.0, 1.5), 25.0, 95.0))
            new_lo, new_hi = int(centre) - 20, int(centre) + 21
            group_touched = functions["move_window"](states, stamps, accumulator, offsets, rates,
                                                     lo, hi, new_lo, new_hi, *group_touched,
                                                     time)
            lo, hi = new_lo, new_hi
            expected = contact_history(points, weighted, lo, hi)
            got = functions["window_history"](accumulator, offsets, weighted, hi - lo)
            assert got == pytest.approx(expected, rel=1e-12, abs=1e-300)
        flux = 0.0 if n % 11 == 0 else float(rng.uniform(1e4, 1e6))
        touched = advance_states(points, step, *touched, lo, hi, flux)
        functions["advance_window"](accumulator, offsets, step, flux)
        time += dt
        if n % 97 == 0:
            functions["reanchor_window"](states, stamps, offsets, rates, lo, hi, time)
    scale = np.abs(points).max(axis=0)
    for j in range(n_points):
        state = _point_state(states, stamps, accumulator, rates, j, lo, hi, time)
        assert np.all(np.abs(state - points[j]) <= 1e-11 * scale + 1e-300), j
    assert group_touched == touched
    assert math.isclose(float(offsets.sum()), float(sum(
        (_point_state(states, stamps, accumulator, rates, j, lo, hi, time) - accumulator).sum()
        for j in range(lo, hi))), rel_tol=1e-9)


def test_an_empty_window_has_no_history():
    assert cw.window_history(np.ones(3), np.ones(3), np.ones(3), 0) == 0.0
