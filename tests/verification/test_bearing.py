"""The DCFPB element against closed forms: rigid-plastic loops, pendulum stiffness, tangents."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.bearing import AxialLoadHistory, DCFPBearing
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine
from isolator.testrig import run_test

N = 60e6 * math.pi * 0.15**2  # 60 N/mm^2 on a 300 mm slider [N]


def _sine(amplitude=0.2, period=4.0, cycles=2, dt=0.002):
    t = np.arange(0.0, cycles * period + dt / 2, dt)
    w = 2 * np.pi / period
    return t, amplitude * np.sin(w * t), amplitude * w * np.cos(w * t)


def _loop_energy(u, f):
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(u)))


@pytest.mark.parametrize("yield_displacement", [1e-4, 1e-5])
def test_rigid_plastic_loop_dissipates_4_mu_N_D(yield_displacement):
    """A flat slider (R = inf) with constant friction: EDC = 4 mu N D per cycle."""
    friction = ConstantFriction(mu0=0.05)
    bearing = DCFPBearing(math.inf, 0.3, N, friction, yield_displacement=yield_displacement)
    t, u, v = _sine(dt=5e-4)
    res = run_test(bearing, t, u, v)
    one_cycle = t <= 4.0 + 1e-12
    edc = _loop_energy(u[one_cycle], res.force[one_cycle])
    mu = friction.mu
    # the elastic branch of the return map removes 2 mu N u_y per reversal pair
    expected = 4 * mu * N * 0.2 - 4 * mu * N * yield_displacement
    assert edc == pytest.approx(expected, rel=2e-3)
    assert np.max(np.abs(res.force)) == pytest.approx(mu * N, rel=1e-12)


def test_post_yield_stiffness_is_N_over_R():
    bearing = DCFPBearing(4.5, 0.3, N, ConstantFriction(mu0=0.04))
    t, u, v = _sine(amplitude=0.3, cycles=1)
    res = run_test(bearing, t, u, v)
    loading = (v > 0) & (u > -0.2) & (u < 0.25) & (t > 1.0)
    slope = np.polyfit(u[loading], res.force[loading], 1)[0]
    assert slope == pytest.approx(N / 4.5, rel=1e-9)


def test_spherical_restoring_law_matches_formula():
    bearing = DCFPBearing(2.0, 0.3, N, ConstantFriction(mu0=0.04), restoring="spherical",
                          displacement_capacity=0.5)
    el = bearing.element()
    u = 0.4
    trial = el.set_trial(u, 0.1, 1.0)
    mu = bearing.friction.mu
    assert trial.force == pytest.approx(N * u / math.sqrt(4.0 - u * u) + mu * N, rel=1e-12)


@pytest.mark.parametrize(
    "friction",
    [PTVFriction(heating=MonitorLine()), PTVFriction(heating=CentrePoint()),
     PTVFriction(heating=None), ConstantFriction()],
    ids=["precise", "simplified", "no-heating", "constant"],
)
def test_consistent_tangent_matches_finite_differences(friction):
    bearing = DCFPBearing(4.5, 0.3, N, friction)
    el = bearing.element()
    t, u, v = _sine(amplitude=0.25, cycles=1, dt=0.005)
    for i in range(1, 150):  # heat the surface a little first
        el.set_trial(u[i], v[i], t[i])
        el.commit()
    time, u0, v0 = t[150], u[150], v[150]  # sliding, away from a reversal (|v| has a kink)
    trial = el.set_trial(u0, v0, time)
    h_u, h_v = 1e-7, 1e-6
    du = (el.set_trial(u0 + h_u, v0, time).force - el.set_trial(u0 - h_u, v0, time).force) / (
        2 * h_u)
    dv = (el.set_trial(u0, v0 + h_v, time).force - el.set_trial(u0, v0 - h_v, time).force) / (
        2 * h_v)
    assert trial.stiffness == pytest.approx(du, rel=1e-6)
    assert trial.damping == pytest.approx(dv, rel=1e-5, abs=1e-3)


def test_time_varying_axial_load_scales_the_force():
    """F = N(t) (u / R + mu z): double the load, double the force at the same state."""
    load = AxialLoadHistory(np.array([0.0, 10.0]), np.array([N, 2 * N]))
    bearing = DCFPBearing(4.5, 0.3, load, ConstantFriction(mu0=0.04))
    t, u, v = _sine(amplitude=0.2, period=10.0, cycles=1, dt=0.01)
    res = run_test(bearing, t, u, v)
    n_t = np.interp(t, [0.0, 10.0], [N, 2 * N])
    mu = bearing.friction.mu
    sliding = np.isclose(np.abs(res.friction_force), mu * n_t, rtol=1e-12, atol=0.0)
    assert np.mean(sliding) > 0.9
    assert np.allclose(res.axial_load, n_t)


def test_uplift_gives_no_force_and_no_heat():
    load = AxialLoadHistory(np.array([0.0, 1.0, 1.001, 2.0]), np.array([N, N, -1.0, -1.0]))
    bearing = DCFPBearing(4.5, 0.3, load, PTVFriction(heating=CentrePoint()))
    t, u, v = _sine(amplitude=0.1, period=2.0, cycles=1, dt=0.005)
    res = run_test(bearing, t, u, v)
    after = t > 1.01
    assert np.all(res.force[after] == 0.0) and np.all(res.heat_flux[after] == 0.0)


def test_negative_time_step_is_refused():
    el = DCFPBearing(4.5, 0.3, N, ConstantFriction()).element()
    el.set_trial(0.01, 0.1, 1.0)
    el.commit()
    with pytest.raises(ValueError, match="before the last committed time"):
        el.set_trial(0.02, 0.1, 0.5)


def _cycle_hold_cycle(amplitude=0.1, period=1.0, hold=1.0, dt=0.005):
    """A sine cycle, a hold at u = 0 (v = 0) for ``hold`` [s], another cycle: t, u, v."""
    t = np.round(np.arange(0.0, 2 * period + hold + dt / 2, dt) / dt) * dt
    phase = np.where(t < period, t, np.where(t <= period + hold, period, t - hold))
    omega = 2 * math.pi / period
    moving = (t < period) | (t > period + hold)
    return t, amplitude * np.sin(omega * phase), np.where(moving, amplitude * omega
                                                          * np.cos(omega * phase), 0.0)


@pytest.mark.parametrize("model", ["simplified", "precise"])
def test_a_lifted_bearing_cools_as_one_at_rest(model):
    """Uplift stops the heat, not the clock: held still for 1 s between two heating cycles,
    a bearing lifted off (N = 0) and one still loaded both take no heat (zero speed), so
    their plates cool alike and the next cycle starts from the same temperature. (The lifted
    plates used to keep their temperature and lose the hold's time.)"""
    from dataclasses import replace

    from isolator.experiments import protocol_bearing

    loaded = protocol_bearing(model, slider_diameter=0.3, design_velocity=0.63)
    n = loaded.axial_load_at(0.0)
    lifted = replace(loaded, axial_load=AxialLoadHistory(
        np.array([0.0, 1.0, 1.001, 1.999, 2.0, 3.0]), np.array([n, n, 0.0, 0.0, n, n])))
    t, u, v = _cycle_hold_cycle()
    a, b = run_test(loaded, t, u, v), run_test(lifted, t, u, v)
    hold = (t > 1.0) & (t < 2.0)
    assert np.all(b.axial_load[hold] == 0.0) and np.all(b.force[hold] == 0.0)
    assert np.all(b.heat_flux[hold] == 0.0)
    np.testing.assert_allclose(b.temperature, a.temperature, rtol=1e-12, atol=0.0)
    at_lift, at_landing = np.searchsorted(t, [1.0, 1.995])
    assert b.temperature[at_lift] - b.temperature[at_landing] > 2.0  # it did cool
    after = t > 2.0
    np.testing.assert_allclose(b.mu[after], a.mu[after], rtol=1e-12, atol=0.0)
