"""The baseline of the diagnosis in two directions (issue 21): its pre-sliding u_y is fitted
continuously from its grid's best point (the force channel's lag stays on its half-sample
grid).

A campaign made by the model itself (a circle and a figure-eight, no noise) with a u_y between
the grid's points and a lag on its grid is calibrated back to them; on the grid alone the
misfit at every direction change was what the transition rule then reported as a gap. About
a second.
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
    _prepare,
    kinematic_state,
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


def _truth() -> Campaign2D:
    d = _prepare(_campaign(), smooth=False)
    ub, z = kinematic_state(d, YIELD, LAG * d.dt)
    force = AXIAL * (ub / RADIUS + MU * z)
    n = len(d.campaign.tests[0])
    return _campaign((force[:n], force[n:]))


def test_an_off_grid_yield_displacement_is_fitted_between_the_grid_points():
    assert not np.any(np.isclose(_YIELD_GRID, YIELD, rtol=0.05))
    assert np.any(np.isclose(_LAG_GRID, LAG))
    d = _prepare(_truth(), smooth=False)
    base = _calibrate(d, BaselineSpec("constant"))
    assert math.isclose(base.yield_displacement, YIELD, rel_tol=0.02)
    assert math.isclose(base.lag / d.dt, LAG, abs_tol=1e-9)
    assert math.isclose(base.mu, MU, rel_tol=1e-3)
    # the misfit left is rounding, not a gap at the direction changes
    assert float(np.max(np.abs(d.force - base.force))) < 1e-3 * MU * AXIAL
    assert not base.at_edge


def test_a_given_yield_displacement_is_kept():
    d = _prepare(_truth(), smooth=False)
    base = _calibrate(d, BaselineSpec("constant", yield_displacement=YIELD))
    assert base.yield_displacement == YIELD
    assert math.isclose(base.lag / d.dt, LAG, abs_tol=1e-9)
    assert float(np.max(np.abs(d.force - base.force))) < 1e-3 * MU * AXIAL
