"""The kernels of the diagnosis in two directions (issue 21) against the package's element.

The return map along an orbit is the element's (:func:`isolator.bearing.isotropic_return_map`
step by step), the play per axis is one direction's play on each axis (no force while a gap
is open), the fractional shift of a channel is the
cubic interpolation of :func:`isolator.diagnosis.kinematics.shifted`, and the model's force is
the element's force on the same orbit to rounding.
"""

from __future__ import annotations

import numpy as np

from isolator.bearing import DCFPBearing, isotropic_return_map
from isolator.diagnosis.kinematics import play_return_map, shifted
from isolator.diagnosis.two_directions import (
    play_return_map_2d,
    return_map_2d,
    shift_uniform,
)
from isolator.friction import ConstantFriction
from isolator.orbits import orbit
from isolator.testrig import run_orbit


def test_return_map_is_the_elements():
    rng = np.random.default_rng(1)
    u = np.cumsum(rng.normal(0.0, 2e-4, (400, 2)), axis=0)
    u[0] = 0.0
    zx, zy = return_map_2d(u[:, 0].copy(), u[:, 1].copy(), 5e-4)
    z = np.zeros(2)
    for i in range(1, u.shape[0]):
        du = u[i] - u[i - 1]
        z = np.array(isotropic_return_map(z[0], z[1], du[0], du[1], 5e-4)[:2])
        assert np.allclose([zx[i], zy[i]], z, atol=1e-12)


def test_play_per_axis_is_one_directions_play_on_a_line():
    """Along x the play of two directions is one direction's (the bearing standing still and
    no force while the gap is open); with no gap it is the plain return map."""
    t = np.linspace(0.0, 4.0, 801)
    x = 0.01 * np.sin(2 * np.pi * t) + 0.002 * np.sin(2 * np.pi * 3.1 * t)
    ub, z, engaged = play_return_map_2d(x, np.zeros_like(x), 0.002, 0.001, 3e-4)
    ub1, z1, engaged1 = play_return_map(x, 0.002, 3e-4, 0.0, 0.05)
    assert np.array_equal(ub[:, 0], ub1) and np.array_equal(z[:, 0], z1)
    assert np.array_equal(engaged[:, 0], engaged1) and engaged1.min() == 0.0
    rng = np.random.default_rng(2)
    u = np.cumsum(rng.normal(0.0, 2e-4, (400, 2)), axis=0)
    u[0] = 0.0
    ub, z, engaged = play_return_map_2d(u[:, 0].copy(), u[:, 1].copy(), 0.0, 0.0, 5e-4)
    zx, zy = return_map_2d(u[:, 0].copy(), u[:, 1].copy(), 5e-4)
    assert np.array_equal(z, np.column_stack([zx, zy])) and np.array_equal(ub, u)
    assert engaged.min() == 1.0


def test_fractional_shift_is_cubic_interpolation():
    t = np.arange(600) * 0.01
    u = 0.1 * np.sin(2 * np.pi * t / 2.0) + 0.02 * np.sin(2 * np.pi * t / 0.7)
    for samples in (-2.5, 0.3, 4.0):
        ours = shift_uniform(u, samples)
        theirs = shifted(t, u, samples * 0.01)
        assert np.max(np.abs(ours - theirs)[10:-10]) < 1e-5 * np.ptp(u)


def test_the_models_force_is_the_elements_on_an_orbit():
    bearing = DCFPBearing(2.0, 0.25, axial_load=1e6, friction=ConstantFriction(0.06),
                          yield_displacement=3e-4, displacement_capacity=0.3)
    o = orbit("square", 0.07, 3.0, 1, 0.01)
    result = run_orbit(bearing, o)
    u = np.array(o.displacement)
    zx, zy = return_map_2d(u[:, 0].copy(), u[:, 1].copy(), 3e-4)
    force = 1e6 * (u / 2.0 + result.mu[:, None] * np.column_stack([zx, zy]))
    assert np.max(np.abs(force - result.force)) < 1e-6
