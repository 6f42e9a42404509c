"""Orbits of the 2D virtual test machine: their shapes, exact velocities and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.experiments import protocol_bearing
from isolator.orbits import (
    ORBITS,
    Orbit,
    circle,
    figure_eight,
    line,
    orbit,
    rotation,
    square,
)
from isolator.protocols import sine
from isolator.testrig import run_test


def test_circle_keeps_its_radius_and_speed():
    o = circle(0.2, 2.0, 2, 0.01)
    turns = o.segment_slices("circle")
    assert len(turns) == 2
    u, v = o.displacement[turns[0].start:], o.velocity[turns[0].start + 1:]
    assert np.allclose(np.hypot(*u.T), 0.2, rtol=1e-14)
    assert np.allclose(np.hypot(*v.T), 0.2 * 2 * np.pi / 2.0, rtol=1e-14)
    assert np.allclose(np.sum(u[1:] * v, axis=1), 0.0, atol=1e-14)  # tangential
    lead = o.segment_slices("lead-in")[0]
    assert np.array_equal(o.displacement[0], [0.0, 0.0])
    assert np.array_equal(o.displacement[lead.stop - 1], [0.2, 0.0])
    assert np.array_equal(o.velocity[lead.stop - 1], [0.0, 0.0])  # the lead-in ends at rest
    assert np.array_equal(o.displacement[-1], [0.2, 0.0])  # whole turns end where they began


@pytest.mark.parametrize("make", [
    lambda: circle(0.1, 2.0, 1, 0.01),
    lambda: figure_eight(0.1, 2.0, 1, 0.01, ratio=0.7),
    lambda: line(0.1, 2.0, 1, 0.01, angle=30.0),
])
def test_smooth_orbits_velocity_is_the_derivative(make):
    """Central differences of the displacement against the mean of the end velocities (a
    block's joining sample keeps the velocity of the block before: it is left out)."""
    o = make()
    blocks = [slice(s + (s > 0), e) for label, s, e in o.segments if label != "lead-in"]
    for block in blocks:
        du = np.diff(o.displacement[block], axis=0) / np.diff(o.time[block])[:, None]
        mean = 0.5 * (o.velocity[block][1:] + o.velocity[block][:-1])
        assert np.max(np.abs(du - mean)) < 1e-3 * np.max(np.abs(o.velocity))


def test_figure_eight_passes_the_centre_twice_a_cycle():
    o = figure_eight(0.15, 2.0, 1, 0.01, ratio=0.5)
    at_centre = np.flatnonzero(np.hypot(*o.displacement.T) < 1e-12)
    assert list(at_centre) == [0, len(o) // 2, len(o) - 1]
    assert np.max(o.displacement[:, 0]) == pytest.approx(0.15)
    assert np.max(o.displacement[:, 1]) == pytest.approx(0.075)


def test_square_runs_through_its_corners_at_constant_speed():
    o = square(0.1, 2.0, 1, 0.01, angle=0.0)
    corners = [[0.1, 0.1], [-0.1, 0.1], [-0.1, -0.1], [0.1, -0.1]]
    for corner in corners:
        assert np.min(np.hypot(*(o.displacement - corner).T)) < 1e-15
    assert np.allclose(np.hypot(*o.velocity[1:].T), 8 * 0.1 / 2.0, rtol=1e-14)
    assert o.path_length == pytest.approx(0.1 + 8 * 0.1, rel=1e-12)
    assert np.max(np.abs(o.displacement)) == pytest.approx(0.1, rel=1e-15)


def test_line_is_the_sine_in_one_direction_along_its_direction():
    o, s = line(0.2, 2.0, 2, 0.02, angle=45.0), sine(0.2, 2.0, 2, 0.02)
    direction = np.array([math.cos(math.pi / 4), math.sin(math.pi / 4)])
    assert np.array_equal(o.time, s.time)
    assert np.array_equal(o.displacement, np.outer(s.displacement, direction))
    assert np.array_equal(o.velocity, np.outer(s.velocity, direction))
    assert o.segments == (("line", 0, 101), ("line", 100, 201))  # one block per cycle


def test_angle_rotates_the_whole_orbit():
    a, b = square(0.1, 2.0, 1, 0.01), square(0.1, 2.0, 1, 0.01, angle=30.0)
    assert np.allclose(b.displacement, a.displacement @ rotation(30.0).T, atol=1e-16)
    assert np.allclose(b.velocity, a.velocity @ rotation(30.0).T, atol=1e-15)


def test_orbit_dispatches_by_name():
    assert ORBITS == ("circle", "figure8", "square", "line")
    for kind in ORBITS:
        o = orbit(kind, 0.1, 2.0, 1, 0.01, angle=10.0)
        assert isinstance(o, Orbit) and o.name in (kind, "figure_eight")
        assert o.displacement.shape == (len(o), 2)
    with pytest.raises(ValueError, match="'kind' parameter of orbit must be one of"):
        orbit("ellipse", 0.1, 2.0, 1, 0.01)


@pytest.mark.parametrize(("call", "message"), [
    (lambda: circle(-0.1, 2.0, 1, 0.01), "'radius' parameter of circle"),
    (lambda: circle(0.1, 2.0, 0, 0.01), "'cycles' parameter of circle"),
    (lambda: figure_eight(0.1, 2.0, 1, 0.5), "'dt' parameter of figure_eight"),
    (lambda: figure_eight(0.1, 2.0, 1, 0.01, ratio=0.0), "'ratio' parameter of figure_eight"),
    (lambda: square(0.1, float("nan"), 1, 0.01), "'period' parameter of square"),
    (lambda: line(0.1, 2.0, 1, 0.01, angle=400.0), "'angle' parameter of line"),
    (lambda: circle(0.1, 2.0, 10**7, 0.1), "past the limit"),
])
def test_bad_orbit_parameters_are_named(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_rig_refuses_an_orbit_beyond_the_capacity_and_bad_shapes():
    bearing = protocol_bearing("constant", displacement_capacity=0.3)
    o = circle(0.31, 2.0, 1, 0.05)
    with pytest.raises(ValueError, match=r"displacement_capacity 0\.3 m"):
        run_test(bearing, o.time, o.displacement, o.velocity)
    with pytest.raises(ValueError, match=r"shape \(41, 2\)"):
        run_test(bearing, o.time[:41], o.displacement[:41].T.reshape(-1, 1))
    small = circle(0.1, 2.0, 1, 0.05)
    by_gradient = run_test(bearing, small.time, small.displacement)  # v = np.gradient
    assert by_gradient.force.shape == (len(small), 2)
