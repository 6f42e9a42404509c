"""The DCFPB element in two directions against the element in one and closed forms.

- A sine along any direction gives the force of the element in one direction (along the line,
  zero across), mu, temperature and heat flux, for the constant, simplified and precise models
  (1e-9).
- A rigid-plastic circular orbit at constant speed: |F_friction| = mu N, tangential to the
  path, energy per cycle mu N times the path, the restoring force conservative.
- The 2x2 tangents d F / d u and d F / d v against central differences.
- Trials are pure, revert restores the committed state and history exactly.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from isolator.bearing import BearingElement, DCFPBearing, isotropic_return_map
from isolator.experiments import protocol_bearing
from isolator.friction import ConstantFriction
from isolator.orbits import circle, line
from isolator.protocols import sine
from isolator.testrig import path_integral, run_orbit, run_test

N = 60e6 * math.pi * 0.15**2  # 60 N/mm^2 on a 300 mm slider [N]
MODELS = ("constant", "simplified", "precise")


def _relative(got, expected, scale=None):
    scale = np.max(np.abs(expected)) if scale is None else scale
    return float(np.max(np.abs(np.asarray(got) - np.asarray(expected))) / scale)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("angle", [0.0, 30.0, 45.0, 90.0])
def test_a_line_at_any_angle_is_the_element_in_one_direction(model, angle):
    """Two cycles of the paper's 300 mm slider at 60 N/mm^2, 0.2 m, 2 s (0.63 m/s)."""
    bearing = protocol_bearing(model, slider_diameter=0.3, design_velocity=0.63)
    history_x = sine(0.2, 2.0, 2, 0.02)
    one_direction = run_test(bearing, history_x.time, history_x.displacement,
                      history_x.velocity)
    result = run_orbit(bearing, line(0.2, 2.0, 2, 0.02, angle=angle))
    direction = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    t0 = 20.0
    assert _relative(result.force, np.outer(one_direction.force, direction)) < 1e-9
    assert _relative(result.mu, one_direction.mu, np.max(one_direction.mu)) < 1e-9
    heated = max(float(np.max(one_direction.temperature - t0)), 1e-300)
    assert _relative(result.temperature, one_direction.temperature, heated) < 1e-9
    flux = one_direction.heat_flux
    assert _relative(result.heat_flux, flux, max(np.max(flux), 1e-300)) < 1e-9
    if model != "constant":
        assert np.max(one_direction.temperature) > t0 + 30.0  # the history did heat the plates
    # the per-axis characteristics along the line are the ones in one direction
    if angle == 0.0:
        for got, expected in zip(result.characteristics("x"), one_direction.characteristics(),
                                 strict=True):
            assert abs(got.EDC / expected.EDC - 1.0) < 1e-9
            assert abs(got.Keff / expected.Keff - 1.0) < 1e-9


def test_spherical_law_along_a_line_is_the_one_in_one_direction():
    bearing = DCFPBearing(2.0, 0.3, N, ConstantFriction(mu0=0.04), restoring="spherical",
                          displacement_capacity=0.5)
    history = sine(0.4, 2.0, 1, 0.02)
    one_direction = run_test(bearing, history.time, history.displacement, history.velocity)
    result = run_orbit(bearing, line(0.4, 2.0, 1, 0.02, angle=30.0))
    direction = np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    assert _relative(result.force, np.outer(one_direction.force, direction)) < 1e-9


@functools.cache
def _rigid_plastic_circle():
    """A constant-mu bearing (u_y = 1 um) on 2 turns of R = 0.15 m in 2 s, 2000 steps a turn."""
    friction = ConstantFriction(mu0=0.05)
    bearing = DCFPBearing(4.5, 0.3, N, friction, yield_displacement=1e-6)
    orbit = circle(0.15, 2.0, 2, 1e-3)
    return bearing, orbit, run_orbit(bearing, orbit), friction.mu


def test_circular_orbit_rigid_plastic_closed_forms():
    _, orbit, result, mu = _rigid_plastic_circle()
    second = orbit.segment_slices("circle")[1]
    friction = result.friction_force[second]
    # magnitude mu N at every sample, not only on average
    assert np.max(np.abs(np.hypot(*friction.T) / (mu * N) - 1.0)) < 1e-12
    # tangential: behind the velocity by at most half a step's turn (z follows the chord)
    phi = 2.0 * np.pi / 2000
    velocity = result.velocity[second]
    cosine = np.sum(friction * velocity, axis=1) / (mu * N * np.hypot(*velocity.T))
    assert np.max(np.arccos(np.clip(cosine, -1.0, 1.0))) < 0.5 * phi * 1.01
    # energy per turn: mu N times the path; the discrete loop is the closed form
    # n 2 R sin(phi/2) (1 + cos phi) / 2 (chords and trapezoids), 1 - 7 phi^2 / 24 of 2 pi R
    energy = result.dissipated_energy(second)
    discrete = mu * N * 2000 * 2 * 0.15 * math.sin(phi / 2) * (1 + math.cos(phi)) / 2
    assert energy == pytest.approx(discrete, rel=1e-7)
    assert energy == pytest.approx(mu * N * 2 * np.pi * 0.15, rel=7 * phi**2 / 24 * 1.1)
    # the restoring force N u / R is conservative: no work over a closed turn
    restoring = result.force[second] - friction
    assert abs(path_integral(result.displacement[second], restoring)) < 1e-12 * energy
    assert np.allclose(restoring, N / 4.5 * result.displacement[second], rtol=1e-12,
                       atol=1e-12 * N * 0.15 / 4.5)


def test_circular_orbit_per_axis_characteristics():
    """Each axis of a circle is a sine loop; the two share a turn's energy equally (the last
    loop of each axis: the first x loop opens with the lead-in)."""
    _, orbit, result, mu = _rigid_plastic_circle()
    x, y = result.characteristics("x"), result.characteristics(1)
    assert len(x) == 2 and len(y) == 2
    energy = result.dissipated_energy(orbit.segment_slices("circle")[1])
    for loop in (x[-1], y[-1]):
        assert abs(loop.EDC / (0.5 * energy) - 1.0) < 1e-4
    # F_x = A cos(theta) - B sin(theta - delta), A = N R / R_eff, B = mu N, z behind the
    # tangent by delta = phi / 2 (along the step's chord): a swing of 2 hypot(A + B sin delta,
    # B cos delta)
    a, b, delta = N * 0.15 / 4.5, mu * N, np.pi / 2000
    swing = 2 * math.hypot(a + b * math.sin(delta), b * math.cos(delta))
    assert x[-1].Fmax - x[-1].Fmin == pytest.approx(swing, rel=1e-5)


def _fd_tangents(element, u, v, t, h_u=1e-9, h_v=1e-7):
    stiffness, damping = np.empty((2, 2)), np.empty((2, 2))
    for j in range(2):
        e = np.eye(2)[j]
        plus = element.set_trial(u + h_u * e, v, t).force
        minus = element.set_trial(u - h_u * e, v, t).force
        stiffness[:, j] = (plus - minus) / (2 * h_u)
        plus = element.set_trial(u, v + h_v * e, t).force
        minus = element.set_trial(u, v - h_v * e, t).force
        damping[:, j] = (plus - minus) / (2 * h_v)
    return stiffness, damping


def _element_on_a_curve(model: str, steps: int = 12) -> tuple[BearingElement, float]:
    bearing = protocol_bearing(model, slider_diameter=0.3)
    element = BearingElement(bearing, 2)
    t = 0.0
    for n in range(steps):
        t = 0.01 * n
        theta = 0.3 * n
        element.set_trial(0.002 * n * np.array([math.cos(theta), math.sin(theta)]),
                          0.3 * np.array([-math.sin(theta), math.cos(theta)]), t)
        element.commit()
    return element, t


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("state", ["sliding", "elastic"])
def test_tangents_against_finite_differences(model, state):
    element, t = _element_on_a_curve(model)
    u0 = element.committed.displacement
    # sliding: onward along a new direction; elastic: a step back smaller than u_y
    du = np.array([0.004, -0.003]) if state == "sliding" else -2e-4 * element.committed.z
    u, v, time = u0 + du, np.array([0.25, -0.2]), t + 0.01
    trial = element.set_trial(u, v, time)
    sliding = math.hypot(*(element.committed.z + du / 5e-4)) >= 1.0
    assert sliding == (state == "sliding")
    stiffness, damping = _fd_tangents(element, u, v, time)
    assert np.allclose(trial.stiffness, stiffness, rtol=1e-6, atol=1e-6 * N / 5e-4)
    assert np.allclose(trial.damping, damping, rtol=1e-5, atol=1e-6 * N)
    if model != "constant":
        assert np.max(np.abs(trial.damping)) > 1e3  # mu depends on the speed


def test_return_map_tangent_is_the_derivative_of_the_map():
    z0, du, uy = np.array([0.6, 0.7]), np.array([3e-4, -1e-4]), 5e-4

    def mapped(increment):
        values = isotropic_return_map(*z0, *increment, uy)
        return np.array(values[:2]), np.reshape(values[2:], (2, 2))

    z, tangent = mapped(du)
    assert math.hypot(*z) == pytest.approx(1.0, abs=1e-15)
    h = 1e-10
    numeric = np.column_stack([
        (mapped(du + h * e)[0] - mapped(du - h * e)[0]) / (2 * h) for e in np.eye(2)])
    assert np.allclose(tangent, numeric, rtol=1e-6, atol=1e-3)


@pytest.mark.parametrize("model", MODELS)
def test_trials_are_pure_and_revert_is_exact(model):
    element, t = _element_on_a_curve(model)
    twin, _ = _element_on_a_curve(model)
    u = element.committed.displacement + np.array([0.003, 0.001])
    v, time = np.array([0.3, 0.1]), t + 0.01
    first = element.set_trial(u, v, time)
    for wild in ([0.05, -0.02], [-0.01, 0.04], [0.0, 0.0]):  # Newton wandering about
        element.set_trial(np.asarray(wild), -v, time + 0.02)
    again = element.set_trial(u, v, time)
    assert np.array_equal(first.force, again.force)
    assert np.array_equal(first.stiffness, again.stiffness)
    assert np.array_equal(first.damping, again.damping)
    element.set_trial([0.04, 0.04], v, time)
    element.revert()
    assert element.trial_state is element.committed
    # after the wandering and the revert, the history goes on as if none of it had happened
    for n in range(1, 6):
        theta = 0.4 * n
        step = (np.array([0.01 * math.cos(theta), 0.01 * math.sin(theta)]),
                np.array([0.4, -0.2]), t + 0.01 * n)
        a, b = element.set_trial(*step), twin.set_trial(*step)
        element.commit()
        twin.commit()
        assert np.array_equal(a.force, b.force)
        assert element.committed.temperature == twin.committed.temperature


@pytest.mark.parametrize("model", ["simplified", "precise"])
def test_a_lifted_bearing_cools_as_one_at_rest(model):
    """Uplift stops the heat, not the heat clock: an orbit, a 1 s hold at its start (zero
    speed), the orbit again; lifted off (N = 0) during the hold or still loaded, the plates
    take no heat and cool alike, and the second orbit starts from the same temperatures."""
    from dataclasses import replace

    from isolator.bearing import AxialLoadHistory

    loaded = protocol_bearing(model, slider_diameter=0.3, design_velocity=0.63)
    n = loaded.axial_load_at(0.0)
    lifted = replace(loaded, axial_load=AxialLoadHistory(
        np.array([0.0, 1.0, 1.001, 1.999, 2.0, 3.0]), np.array([n, n, 0.0, 0.0, n, n])))
    dt, amplitude, omega = 0.005, 0.1, 2 * math.pi
    temperatures = []
    for bearing in (loaded, lifted):
        element, history = BearingElement(bearing, 2), []
        for time in np.arange(1, 601) * dt:
            tau = time - 1.0 if time > 2.0 else min(time, 1.0)
            moving = time < 1.0 or time > 2.0
            u = amplitude * np.array([math.sin(omega * tau), math.cos(omega * tau) - 1.0])
            v = amplitude * omega * np.array([math.cos(omega * tau), -math.sin(omega * tau)])
            element.set_trial(u, v if moving else np.zeros(2), time)
            element.commit()
            history.append(element.committed.temperature)
        temperatures.append(np.array(history))
    np.testing.assert_allclose(temperatures[1], temperatures[0], rtol=1e-12, atol=0.0)
    assert temperatures[1][199] - temperatures[1][397] > 2.0  # from t = 1.0 to 1.99 s: cooled
