"""Heating over the plate (Eq. 4-6 in 2D) against a direct convolution written apart.

The reference here knows only the paper: a grid point (m s, n s) in the grid's frame is under
the slider when it lies in the square of equal area centred on the slider (|x - p| <= a and
|y - q| <= a, a = sqrt(pi) r / 2, Eq. 5), or the centre point within lambda r (Eq. 6); it takes
the model's flux q_n over each step (t_(n-1), t_n] it is under the slider, and its rise is the
exact Eq. 4 integral of a piecewise-constant flux, 2 c sum q (sqrt(t - t_(m-1)) - sqrt(t - t_m))
(:func:`isolator.heating.exact_rise`). The contact temperature is the mean over the points under
the slider. The model's sum-of-exponentials history must agree to 1e-6 of the rise, on a circle
and a figure-eight; the heat put in must equal the friction work; and only the points ever
under the slider are stored.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest

from isolator.bearing import BearingElement
from isolator.experiments import protocol_bearing
from isolator.heating import ThermalProperties, exact_rise, sum_of_exponentials
from isolator.monitor_grid import GridHeating, MonitorGrid
from isolator.orbits import circle, figure_eight, line
from isolator.testrig import run_orbit

SLIDER = 0.2  # [m]: a 35 x 35 window of 5 mm points
HALF_SIDE = 0.5 * math.sqrt(math.pi) * 0.5 * SLIDER  # Eq. 5
SPACING = 0.005
THERMAL = ThermalProperties()
C = THERMAL.flux_coefficient
ORBITS = {
    "circle": lambda: circle(0.1, 2.0, 1, 0.01),
    "figure8": lambda: figure_eight(0.15, 2.0, 1, 0.01),
}


@functools.cache
def _drive(model: str, orbit_name: str, orientation: float | None):
    """Run the element in two directions through the orbit; keep its heating model."""
    bearing = protocol_bearing(model, slider_diameter=SLIDER, design_velocity=0.4)
    orbit = ORBITS[orbit_name]()
    element = BearingElement(bearing, 2, orientation)
    temperature, flux = np.empty(len(orbit)), np.empty(len(orbit))
    friction = np.empty((len(orbit), 2))
    for i in range(len(orbit)):
        element.set_trial(orbit.displacement[i], orbit.velocity[i], orbit.time[i])
        element.commit()
        s = element.committed
        temperature[i], flux[i], friction[i] = s.temperature, s.heat_flux, s.friction_force
    return bearing, orbit, element.friction_state.heating, temperature, flux, friction


def _frame(orientation, on_plate, flux):
    """The grid's axes: the fixed angle, or along the slider at the first heated step."""
    if orientation is not None:
        c, s = math.cos(math.radians(orientation)), math.sin(math.radians(orientation))
        return np.array([[c, s], [-s, c]])
    first = next(n for n in range(1, flux.size) if flux[n] != 0.0)
    e1 = on_plate[first] / np.linalg.norm(on_plate[first])
    return np.array([e1, [-e1[1], e1[0]]])


def _windows(local):
    """Integer ranges [lo, hi) of the points m s with |m s - p| <= a on each axis."""
    lo = np.ceil((local - HALF_SIDE) / SPACING - 1e-9).astype(int)
    hi = np.floor((local + HALF_SIDE) / SPACING + 1e-9).astype(int) + 1
    return lo, hi


def _lag_weights(time):
    """K[n, m] = 2 c (sqrt(t_n - t_(m-1)) - sqrt(t_n - t_m)) for 1 <= m <= n (Eq. 4)."""
    t = time[:, None]
    start = np.sqrt(np.maximum(t - time[None, :-1], 0.0))
    stop = np.sqrt(np.maximum(t - time[None, 1:], 0.0))
    weights = np.zeros((time.size, time.size))
    weights[:, 1:] = 2.0 * C * (start - stop)
    return weights


@pytest.mark.parametrize("orbit_name", ["circle", "figure8"])
@pytest.mark.parametrize("orientation", [None, 20.0])
def test_precise_contact_temperature_equals_direct_convolution(orbit_name, orientation):
    _, orbit, heating, temperature, flux, _ = _drive("precise", orbit_name, orientation)
    on_plate = orbit.displacement / 2.0
    axes = _frame(orientation, on_plate, flux)
    assert np.allclose(heating.axes, axes, rtol=0.0, atol=1e-15)
    lo, hi = _windows(on_plate @ axes.T)
    count = (hi - lo).prod(axis=1)
    overlap = np.prod(np.clip(np.minimum(hi[:, None], hi[None]) - np.maximum(lo[:, None],
                                                                              lo[None]),
                              0, None), axis=2)  # points under the slider at both n and m
    weights = _lag_weights(orbit.time)
    heat = flux.copy()
    heat[0] = 0.0  # sample 0 is a trial of zero length: no heat
    rise = np.array([np.sum(weights[n, :n + 1] * heat[:n + 1] * overlap[n, :n + 1]) / count[n]
                     for n in range(orbit.time.size)])
    model_rise = temperature - THERMAL.initial_temperature
    assert np.max(rise) > 20.0
    assert np.max(np.abs(model_rise - rise)) / np.max(rise) < 1e-6

    # every stored point half a second after the end, by the closed form of its own flux
    # history (half a second: the kernel holds from 1 us, not at the lag 0 of the last step)
    local = heating.point_positions() @ axes.T / SPACING
    index = np.rint(local).astype(int)
    assert np.max(np.abs(local - index)) < 1e-9
    inside = ((index[:, None, 0] >= lo[None, :, 0]) & (index[:, None, 0] < hi[None, :, 0])
              & (index[:, None, 1] >= lo[None, :, 1]) & (index[:, None, 1] < hi[None, :, 1]))
    later = orbit.time[-1] + 0.5
    expected = np.array([exact_rise(orbit.time, heat[1:] * inside[j, 1:], later, THERMAL)
                         for j in range(index.shape[0])])
    got = heating.point_temperatures(0.5) - THERMAL.initial_temperature
    assert np.max(np.abs(got - expected)) / np.max(expected) < 1e-6
    # and they are exactly the points ever under the slider with heat: touched ones only
    union = {(i, k) for n in range(1, flux.size) if heat[n] != 0.0
             for i in range(lo[n, 0], hi[n, 0]) for k in range(lo[n, 1], hi[n, 1])}
    assert {tuple(p) for p in index} == union
    assert heating.stored_points == len(union)


@pytest.mark.parametrize("orbit_name", ["circle", "figure8"])
def test_simplified_centre_point_equals_direct_convolution(orbit_name):
    bearing, orbit, _, temperature, flux, _ = _drive("simplified", orbit_name, None)
    refinement = bearing.friction.heating.refinement
    # Eq. 6, closed (the circle runs on the edge, |u| / 2 = lambda r: slack for rounding)
    covered = np.hypot(*(orbit.displacement / 2.0).T) <= refinement * 0.5 * SLIDER * (1 + 1e-9)
    heat = np.where(covered, flux, 0.0)
    heat[0] = 0.0
    weights = _lag_weights(orbit.time)
    rise = np.array([np.sum(weights[n, :n] * heat[:n])
                     + (weights[n, n] * heat[n] if covered[n] else 0.0)
                     for n in range(orbit.time.size)])
    assert np.max(rise) > 20.0
    model_rise = temperature - THERMAL.initial_temperature
    assert np.max(np.abs(model_rise - rise)) / np.max(rise) < 1e-6


@pytest.mark.parametrize("model", ["precise", "simplified"])
@pytest.mark.parametrize("orbit_name", ["circle", "figure8"])
def test_heat_put_in_equals_friction_work(model, orbit_name):
    """Heat into the two plates, sum of 2 q_n pi r^2 dt_n, against the friction work.

    Rigid-plastic sliding (u_y = 1 um: no pre-sliding part of the return map, where the force
    is below mu N while the flux is not): the heat equals the friction power integrated,
    sum F_friction(t_n) . v_n dt_n, up to the turn of z within a step (1 - cos(phi / 2),
    second order in dt), and the work along the path, integral of F_friction . du, to first
    order in dt (the flux of a step is that of its end sample).
    """
    errors = {}
    for dt in (0.01, 0.005):
        bearing = dataclasses.replace(
            protocol_bearing(model, slider_diameter=SLIDER, design_velocity=0.4),
            yield_displacement=1e-6)
        orbit = {"circle": circle(0.1, 2.0, 1, dt), "figure8": figure_eight(0.15, 2.0, 1, dt)
                 }[orbit_name]
        result = run_orbit(bearing, orbit)
        heat = result.heat_input()
        assert heat == pytest.approx(2.0 * bearing.contact_area * np.sum(
            result.heat_flux[1:] * np.diff(result.time)), rel=1e-12)
        power = np.sum(result.friction_force[1:] * result.velocity[1:], axis=1)
        errors[dt] = (abs(heat / np.sum(power * np.diff(result.time)) - 1.0),
                      abs(heat / result.friction_work() - 1.0))
    assert errors[0.01][0] < 5e-4 and errors[0.005][0] < errors[0.01][0] / 3.0
    assert errors[0.01][1] < 5e-3 and errors[0.005][1] < errors[0.01][1] * 0.6


def test_storage_grows_with_the_path_not_the_plate():
    """A sine along x: the stored points are the swept band, whatever the plate's size, and a
    line at 30 degrees stores the same band (the grid follows the motion)."""
    counts = {}
    for capacity in (0.3, 3.0):
        for angle in (0.0, 30.0):
            bearing = protocol_bearing("precise", slider_diameter=SLIDER,
                                       displacement_capacity=capacity)
            result = run_orbit(bearing, line(0.2, 2.0, 1, 0.02, angle=angle))
            counts[capacity, angle] = (result.stored_points, result.temperature)
    columns = (math.floor((0.1 + HALF_SIDE) / SPACING + 1e-9)
               - math.ceil((-0.1 - HALF_SIDE) / SPACING - 1e-9) + 1)
    rows = 2 * math.floor(HALF_SIDE / SPACING) + 1
    for stored, temperature in counts.values():
        assert stored == columns * rows
        assert np.allclose(temperature, counts[0.3, 0.0][1], rtol=1e-12, atol=0.0)
    # a longer path stores more, in proportion to the area swept
    small = run_orbit(protocol_bearing("precise", slider_diameter=SLIDER),
                      circle(0.05, 2.0, 1, 0.02)).stored_points
    large = run_orbit(protocol_bearing("precise", slider_diameter=SLIDER),
                      circle(0.2, 2.0, 1, 0.02)).stored_points
    swept = (np.pi * (0.1 + HALF_SIDE) ** 2 + 4 * HALF_SIDE * 0.1) / SPACING**2
    assert small < large < 1.05 * swept
    assert large < (2 * 0.6 / SPACING) ** 2 / 3  # far from the grid over the plate


def test_grid_history_on_a_random_walk_equals_direct_convolution():
    """The grid alone: uneven steps, steps without heat, the slider leaving an area for long
    and coming back (the lazy decay of stored points)."""
    grid = GridHeating(MonitorGrid(0.01, orientation=0.0), 0.05, 0.3, THERMAL,
                       sum_of_exponentials())
    rng = np.random.default_rng(7)
    n_steps, spacing = 300, 0.01
    steps = rng.uniform(2e-3, 3e-2, n_steps)
    fluxes = rng.uniform(1e5, 1e6, n_steps) * (rng.uniform(size=n_steps) > 0.2)
    positions = np.cumsum(rng.normal(0.0, 0.006, (n_steps, 2)), axis=0)
    positions -= positions.mean(axis=0)
    times = np.concatenate([[0.0], np.cumsum(steps)])
    model = []
    for dt, q, p in zip(steps, fluxes, positions, strict=True):
        trial = grid.trial(p, dt)
        model.append(C * trial.rise)  # the history part at the trial's time
        grid.commit(dt, trial, q)
    half = 0.5 * math.sqrt(math.pi) * 0.05  # Eq. 5
    worst = 0.0
    for n in range(1, n_steps):
        lo = np.ceil((positions[n] - half) / spacing - 1e-9).astype(int)
        hi = np.floor((positions[n] + half) / spacing + 1e-9).astype(int) + 1
        i, k = np.meshgrid(np.arange(lo[0], hi[0]), np.arange(lo[1], hi[1]), indexing="ij")
        points = spacing * np.column_stack([i.ravel(), k.ravel()])
        gap = np.abs(points[:, None, :] - positions[None, :n, :])  # (points, steps, 2)
        under = np.all(gap <= half + 1e-9 * spacing, axis=2)
        rises = [exact_rise(times[:n + 1], fluxes[:n] * under[j], times[n + 1], THERMAL)
                 for j in range(points.shape[0])]
        expected = float(np.mean(rises))
        if expected > 1e-3:
            worst = max(worst, abs(model[n] - expected) / expected)
    assert worst < 1e-6
    assert grid.stored_points < 1000  # the walk's footprint, not the plate's 69 x 69 points
