"""The held-out scheme of a campaign in two directions (issue 21): a test whose speeds lie
outside every other test's is held out in alternate blocks of itself, for every model.

Held out whole, such a test asks a speed law to extrapolate: on the speed + pressure tune
variants the slow last test (a circle of 8-20 s beside squares and figure-eights at 0.14-0.7
m/s) drove the law's low-speed drop to the top of its range (0.95, true 0.44-0.5) whenever
it was held out, and a law the campaign determines well (fitted on every test within 0.02 of
the truth) was not named. Milliseconds.
"""

from __future__ import annotations

import numpy as np

from isolator.diagnosis.two_directions import _speeds_apart


def _speeds(centre: float, spread: float = 0.2, n: int = 400) -> np.ndarray:
    """A test's speed history [m/s]: from rest up to ``centre`` and about it."""
    ramp = np.linspace(0.0, centre, 40)
    return np.concatenate([ramp, centre * (1.0 + spread * np.sin(np.linspace(0, 20, n)))])


def test_a_slow_test_below_every_other_is_apart():
    assert _speeds_apart([_speeds(0.2), _speeds(0.15), _speeds(0.03)]) == [2]


def test_a_fast_test_above_every_other_is_apart():
    assert _speeds_apart([_speeds(0.6), _speeds(0.1), _speeds(0.12)]) == [0]


def test_overlapping_speeds_keep_leave_one_test_out():
    assert _speeds_apart([_speeds(0.2, 0.5), _speeds(0.1, 0.5), _speeds(0.05, 1.0)]) == []


def test_the_start_from_rest_does_not_count_as_a_low_speed():
    # every test starts from rest; only the speeds above a tenth of the peak are compared
    assert _speeds_apart([_speeds(0.2, 0.05), _speeds(0.03, 0.05)]) == [0, 1]
