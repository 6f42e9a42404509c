"""The effects of the diagnosis where the answer is known: the library, the play operator,
the channel lag, the spherical geometry, the flexible forms and the transition window.

Each synthetic test is made by our element (:func:`isolator.testrig.run_test`) or by a closed
form, with the effect put in by hand, and the diagnosis must recover the parameter it was
made with.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.bearing import DCFPBearing
from isolator.diagnosis import BearingRecord, Campaign, diagnose
from isolator.diagnosis.effects import ACTS_ON, EFFECT_NAMES, LIBRARY, effects_named
from isolator.diagnosis.flexible import knots, ramps
from isolator.diagnosis.kinematics import hysteretic_variable, play_return_map, shifted
from isolator.friction import ConstantFriction
from isolator.protocols import sine
from isolator.testrig import run_test

D, R = 0.3, 4.5
N = 60e6 * np.pi * 0.15**2
MU = 0.05


def test_library_has_the_ten_effects_each_declaring_where_it_acts():
    assert EFFECT_NAMES == ("heating", "velocity", "pressure", "breakaway", "wear", "stiffness",
                            "asymmetry", "backlash", "geometry", "lag")
    for effect in LIBRARY:
        assert effect.acts_on in ACTS_ON and effect.physical_reading
        assert all(p.low < p.high and p.low <= p.initial <= p.high for p in effect.parameters)
    assert {e.name for e in LIBRARY if e.acts_on == "kinematics"} == {"backlash", "lag"}
    assert {e.name for e in LIBRARY if e.acts_on == "force"} == {"stiffness", "geometry"}
    with pytest.raises(ValueError, match="Unknown effect"):
        effects_named(["friction"])


def test_play_operator_transmits_no_force_while_the_gap_is_crossed():
    """A flat slider behind a play of 4 mm, u_y 0.1 mm: after each reversal the spring
    unloads over u_y, the gap is crossed with no force over 4 mm, then the force builds up
    again over 2 u_y; the loop's energy is that of a stroke shortened by the gap."""
    t = np.linspace(0.0, 4.0, 8001)
    u = 0.02 * np.sin(2.0 * np.pi * t / 2.0)
    half, u_y = 2e-3, 1e-4
    ub, z, engaged = play_return_map(u, half, u_y, 0.0, MU)
    assert np.all(np.abs(u - ub) <= half + 1e-12)
    assert np.all(z[engaged == 0.0] == 0.0)
    peak, trough = int(np.argmax(u[:4000])), int(np.argmin(u[:4000]))
    back = u[peak] - u[peak:trough]
    crossing = engaged[peak:trough] == 0.0
    assert back[crossing].min() >= u_y * 0.99
    assert back[crossing].max() == pytest.approx(u_y + 2 * half, abs=2e-5)
    force = MU * N * z
    cycle = slice(2000, 6001)
    energy = np.trapezoid(force[cycle], u[cycle])
    assert energy == pytest.approx(4 * MU * N * (0.02 - half - u_y), rel=0.02)
    # no play: the return map itself
    _, z0, e0 = play_return_map(u, 0.0, u_y, 0.0, MU)
    assert np.all(e0 == 1.0)
    assert np.max(np.abs(z0 - hysteretic_variable(u, u_y))) < 1e-12


def test_fractional_shift_of_a_sine_is_the_sine_shifted():
    t = np.arange(0.0, 4.0, 0.01)
    u = 0.1 * np.sin(2.0 * np.pi * 0.5 * t)
    moved = shifted(t, u, 0.013)
    inner = slice(5, -5)
    assert np.max(np.abs(moved[inner] - 0.1 * np.sin(np.pi * (t[inner] - 0.013)))) < 1e-7
    assert np.array_equal(shifted(t, u, 0.0), u)


def _test(force_from, amplitude=0.15, period=2.5, cycles=3, dt=0.01, noise=0.005, seed=0):
    h = sine(amplitude, period, cycles, dt)
    rng = np.random.default_rng(seed)
    force = force_from(h) + rng.normal(0.0, noise * MU * N, h.time.size)
    return BearingRecord("t", h.time, h.displacement + rng.normal(0.0, 2e-5, h.time.size),
                         force, np.full(h.time.size, N), h.velocity)


def _element(h, radius=R, u_y=5e-4):
    bearing = DCFPBearing(radius, D, N, ConstantFriction(MU), yield_displacement=u_y)
    return run_test(bearing, h.time, h.displacement, h.velocity).force


def _late(lag):
    """The element's force recorded ``lag`` seconds late (made 10 x finer, then sampled)."""
    def force(h):
        amplitude = float(np.max(np.abs(h.displacement)))
        fine = sine(amplitude, 2.5, 3, 0.001)
        return np.interp(h.time - lag, fine.time, _element(fine), left=0.0)
    return force


def test_a_channel_lag_within_two_samples_is_calibrated_to_a_fraction_of_a_sample():
    tests = tuple(_test(_late(0.013), amplitude=a, seed=k)
                  for k, a in enumerate((0.1, 0.15, 0.2)))
    summary = diagnose(Campaign(tests, R, D), "constant").to_json()
    assert summary["lag"]["samples"] == pytest.approx(1.3, abs=0.1)
    assert summary["verdict"] == ["none"]


def test_a_large_lag_is_named_with_its_size():
    tests = tuple(_test(_late(0.06), amplitude=a, seed=k)
                  for k, a in enumerate((0.1, 0.15, 0.2)))
    summary = diagnose(Campaign(tests, R, D), "constant").to_json()
    assert "lag" in summary["verdict"], summary["verdict"]
    assert summary["lag"]["named"] and summary["lag"]["samples"] == pytest.approx(6.0, abs=0.3)


def test_backlash_is_named_with_its_width():
    def played(h):
        _, z, _ = play_return_map(h.displacement, 1.5e-3, 2e-4, 0.0, MU)
        return MU * N * z

    tests = tuple(_test(played, amplitude=a, seed=k) for k, a in enumerate((0.05, 0.1)))
    summary = diagnose(Campaign(tests, math.inf, D), "constant").to_json()
    assert summary["verdict"][0] == "backlash", summary["verdict"]
    backlash = next(e for e in summary["effects"] if e["name"] == "backlash")
    assert backlash["parameters"]["width"] == pytest.approx(3e-3, rel=0.1)
    assert summary["chosen"]["shrink"] > 0.7  # the rest is the noise floor


def test_spherical_geometry_is_named_on_a_small_radius():
    radius = 1.5

    def spherical(h):
        u = h.displacement
        z = hysteretic_variable(u, 5e-4)
        return (N * u / np.sqrt(radius**2 - u**2) + MU * N * z) / (1 - MU * z * u / radius)

    tests = tuple(_test(spherical, amplitude=a, seed=k) for k, a in enumerate((0.3, 0.4)))
    summary = diagnose(Campaign(tests, radius, D), "constant").to_json()
    named = [v for v in summary["verdict"] if v != "unexplained"]
    assert named == ["geometry"], summary["verdict"]
    assert summary["chosen"]["parameters"]["geometry"]["geometry_factor"] == pytest.approx(
        1.0, abs=0.1)


def test_flexible_basis_is_monotone_and_spans_a_step():
    x = np.linspace(0.0, 10.0, 101)
    positions = knots(x, np.array([5.0]))
    basis = ramps(x, positions)
    assert np.all(np.diff(basis, axis=0) >= 0.0)  # every ramp rises with x
    step = np.zeros(positions.size - 1)
    step[np.flatnonzero(np.isclose(positions[:-1], 5.0))[0]] = -0.3
    m = np.exp(basis @ step)
    assert m[x < 5.0].max() == pytest.approx(1.0) and m[x > 5.0 + 1e-6].max() == pytest.approx(
        math.exp(-0.3))
