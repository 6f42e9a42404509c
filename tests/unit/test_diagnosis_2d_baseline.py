"""The baseline of the diagnosis in two directions (issue 21): its pre-sliding u_y and the
force channel's lag are fitted continuously from their grids' best point, on the samples after
each test has moved clear of the displacement sensors' noise.

A campaign made by the model itself (a circle and a figure-eight, no noise) with a u_y between
the grid's points, or a lag between them, is calibrated back to them; on the grids alone the
misfit at every direction change was what the transition rule then reported as a gap. About
two seconds.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.diagnosis.baseline import BaselineSpec
from isolator.diagnosis.data import BearingRecord2D, Campaign2D
from isolator.diagnosis.two_directions import (
    _LAG_GRID,
    _YIELD_GRID,
    _calibrate,
    _fit_at,
    _prepare,
    kinematic_state,
    settled,
)

RADIUS, SLIDER, AXIAL, MU = 2.0, 0.3, 1.0e6, 0.05
YIELD, LAG = 5.5e-4, 1.5  # [m] between the grid's points, [samples] on the lag's grid


def _campaign(force=None) -> Campaign2D:
    dt = 0.01
    t = np.arange(0.0, 8.0, dt)
    circle = 0.08 * np.column_stack([np.sin(2 * np.pi * t / 4.0),
                                     1.0 - np.cos(2 * np.pi * t / 4.0)])
    eight = np.column_stack([0.1 * np.sin(2 * np.pi * t / 4.0),
                             0.05 * np.sin(4 * np.pi * t / 4.0)])
    records = []
    for k, u in enumerate((circle, eight)):
        f = np.zeros_like(u) if force is None else force[k]
        records.append(BearingRecord2D(f"{k}", t, u, f, np.full(t.size, AXIAL)))
    return Campaign2D(tuple(records), RADIUS, SLIDER)


def _truth(yield_displacement: float = YIELD, lag: float = LAG) -> Campaign2D:
    d = _prepare(_campaign(), smooth=False)
    ub, z = kinematic_state(d, yield_displacement, lag * d.dt)
    force = AXIAL * (ub / RADIUS + MU * z)
    n = len(d.campaign.tests[0])
    return _campaign((force[:n], force[n:]))


def test_an_off_grid_yield_displacement_is_fitted_between_the_grid_points():
    assert not np.any(np.isclose(_YIELD_GRID, YIELD, rtol=0.05))
    assert np.any(np.isclose(_LAG_GRID, LAG))
    d = _prepare(_truth(), smooth=False)
    base = _calibrate(d, BaselineSpec("constant"))
    assert math.isclose(base.yield_displacement, YIELD, rel_tol=0.02)
    assert math.isclose(base.lag / d.dt, LAG, abs_tol=0.01)
    assert math.isclose(base.mu, MU, rel_tol=1e-3)
    # the misfit left is rounding, not a gap at the direction changes
    assert float(np.max(np.abs(d.force - base.force))) < 1e-3 * MU * AXIAL
    assert not base.at_edge


def test_an_off_grid_lag_is_fitted_between_the_grid_points():
    lag = 1.3  # [samples]: 0.2 from the half-sample grid's nearest point
    assert np.min(np.abs(_LAG_GRID - lag)) > 0.15
    d = _prepare(_truth(lag=lag), smooth=False)
    base = _calibrate(d, BaselineSpec("constant"))
    assert math.isclose(base.lag / d.dt, lag, abs_tol=0.02)
    assert math.isclose(base.yield_displacement, YIELD, rel_tol=0.02)
    assert math.isclose(base.mu, MU, rel_tol=1e-3)


def test_a_test_counts_from_where_it_moved_clear_of_the_sensor_noise():
    tolerance = 1.0e-4  # [m]
    u = np.zeros((8, 2))
    u[:, 0] = [0.0, 4e-5, -6e-5, 9e-5, 1.5e-4, 3e-4, 0.0, 5e-5]  # leaves at the 5th sample
    u[:, 1] = [0.0, 3e-5, 2e-5, -3e-5, 2e-5, 0.0, 0.0, 0.0]
    assert settled(u, tolerance).tolist() == [False] * 4 + [True] * 4  # counted once clear
    assert settled(u, 0.0).tolist() == [False] + [True] * 7  # noise-free: from the 2nd


def test_the_samples_before_a_test_moved_are_left_out_of_the_calibration():
    """A force the displacement cannot account for (the friction turned with a motion below
    the sensors' noise) in a test's first samples does not move the fitted mu."""
    d = _prepare(_truth(), smooth=False)
    d.mu_shape = np.ones(d.n)
    clean = _fit_at(d, YIELD, LAG)
    start = ~d.counted
    assert start.sum() == 2 and start[0]  # each test's first sample (noise-free sensors)
    d.force[start] += 0.5 * MU * AXIAL  # a start-up force the path does not show
    assert math.isclose(_fit_at(d, YIELD, LAG)[1], clean[1], rel_tol=1e-12)


def test_a_given_yield_displacement_is_kept():
    d = _prepare(_truth(), smooth=False)
    base = _calibrate(d, BaselineSpec("constant", yield_displacement=YIELD))
    assert base.yield_displacement == YIELD
    assert math.isclose(base.lag / d.dt, LAG, abs_tol=1e-9)
    assert float(np.max(np.abs(d.force - base.force))) < 1e-3 * MU * AXIAL
