"""The pieces of the diagnosis shared by tests in one and in two directions (issues 19, 21).

The materiality rule and the verdict, the channel-lag rule, the per-test lag's parabola, the
block-bootstrap confidence, the nuisance edges and the forms of the effects on mu are one
definition each, called by :mod:`isolator.diagnosis.decision` (one direction) and by
:mod:`isolator.diagnosis.two_directions`; checked here on small arrays (the tests: well under
a second; the imports take a few).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.diagnosis import two_directions
from isolator.diagnosis.baseline import RIGID_PLASTIC_LIMIT, YIELD_DISPLACEMENT_MAX, edges_of
from isolator.diagnosis.decision import LAG_PLAUSIBLE_MAX, grid_minima, lag_reason
from isolator.diagnosis.effects import heating, pressure, velocity, wear
from isolator.diagnosis.selection import block_z, material, paired_z, verdict_of
from isolator.diagnosis.thresholds import Thresholds
from isolator.diagnosis.uncertainty import block_confidence

TH = Thresholds()
RANGE = (RIGID_PLASTIC_LIMIT, YIELD_DISPLACEMENT_MAX)


def test_verdict_and_materiality():
    assert verdict_of([], False) == ["none"]
    assert verdict_of([], True) == ["unexplained"]
    assert verdict_of(["lag"], False) == ["lag"]
    assert verdict_of(["backlash", "heating"], True) == ["backlash", "heating", "unexplained"]
    big = 1.0 + 2.0 * TH.none_margin + 1.0
    assert material(big, 2.0 * TH.practical_none, TH.practical_none, TH)
    assert not material(1.0, 2.0 * TH.practical_none, TH.practical_none, TH)  # noise alone
    assert not material(big, 0.5 * TH.practical_none, TH.practical_none, TH)  # too small


def test_block_z_is_the_paired_statistic():
    rng = np.random.default_rng(3)
    before = rng.uniform(1.0, 2.0, 40)
    after = before - rng.normal(0.1, 0.05, 40)
    d = before - after
    assert math.isclose(block_z(d), d.sum() / (np.sqrt(d.size) * np.std(d, ddof=1)))
    assert paired_z(before, after) == block_z(d)
    assert block_z(np.array([1.0])) == 0.0


def test_lag_rule_is_a_channels():
    dt = 0.005
    assert lag_reason(8.0, dt, np.array([8.1, 7.9]), TH) is None
    assert "leads" in lag_reason(-8.0, dt, np.zeros(0), TH)  # a speed effect's phase
    far = lag_reason((LAG_PLAUSIBLE_MAX + 0.05) / dt, dt, np.zeros(0), TH)
    assert "plausibly" in far
    assert "varies" in lag_reason(8.0, dt, np.array([5.0, 8.0, 11.0]), TH)  # not one lag
    assert lag_reason(0.5 * TH.lag_min_samples, dt, np.zeros(0), TH) is not None


def test_grid_minima_find_a_parabolas_vertex():
    grid = np.arange(-3.0, 3.25, 0.5)
    sse = np.column_stack([(grid - 0.8) ** 2 + 1.0, (grid + 1.3) ** 2])
    assert np.allclose(grid_minima(grid, sse, 0.5), [0.8, -1.3])
    edge = np.column_stack([(grid - 5.0) ** 2])
    assert grid_minima(grid, edge, 0.5)[0] == 3.0  # at the end of the grid: that end


def test_block_confidence():
    ref = np.full(30, 2.0)
    noise = np.full(30, 1.0)
    assert block_confidence(ref, np.full(30, 1.0), noise, 0.5) == 1.0  # closes it all
    assert block_confidence(ref, ref.copy(), noise, 0.5) == 0.0  # closes nothing
    assert math.isnan(block_confidence(ref[:1], ref[:1], noise[:1], 0.5))


def test_nuisance_edges():
    assert edges_of(YIELD_DISPLACEMENT_MAX, RANGE, 0.0) == {"yield_displacement": "top"}
    assert edges_of(YIELD_DISPLACEMENT_MAX, RANGE, 0.0, calibrated=False) == {}
    assert edges_of(1e-4, RANGE, 2.0) == {"lag": "late"}
    assert edges_of(1e-4, RANGE, -2.0) == {"lag": "lead"}
    assert edges_of(1e-4, RANGE, 1.5) == {}


class _Orbit:
    """What the 2D effects read of an orbit campaign."""

    temperature_rise = np.linspace(0.0, 60.0, 50)
    speed = np.linspace(0.0, 0.4, 50)
    pressure = np.linspace(20e6, 30e6, 50)
    mean_pressure = 25e6
    travel = np.linspace(0.0, 40.0, 50)


def test_effects_on_mu_have_one_form_in_both_directions():
    d = _Orbit()
    lib = two_directions.LIBRARY_2D
    assert np.array_equal(lib["heating"].factor(np.array([0.7]), d),
                          heating.modulation(0.7, d.temperature_rise))
    assert np.allclose(lib["heating"].factor(np.array([0.7]), d),
                       np.exp(-0.007 * d.temperature_rise))
    assert np.allclose(lib["velocity"].factor(np.array([0.3, 0.05]), d),
                       velocity.modulation(0.3, 0.05, d.speed))
    assert np.allclose(velocity.modulation(0.3, 0.05, d.speed),
                       1.0 - 0.3 * np.exp(-d.speed / 0.05))
    assert np.allclose(lib["pressure"].factor(np.array([0.2]), d),
                       (d.pressure / d.mean_pressure) ** -0.2)
    assert np.allclose(pressure.modulation(0.2, d.pressure, d.mean_pressure),
                       (d.pressure / d.mean_pressure) ** -0.2)
    # in one direction and in two: the change over the campaign, travel and scale as shares
    # of the campaign's travel (a wear linear in the travel is not at a bound of the change)
    share = d.travel / d.travel[-1]
    per_campaign = wear.modulation(-0.1, share, 0.5, per_campaign=True)
    assert math.isclose(per_campaign[-1], 0.9) and per_campaign[0] == 1.0
    assert np.allclose(lib["wear"].factor(np.array([-0.1, 0.5]), d), per_campaign)
    assert np.allclose(lib["wear"].factor(np.array([-0.1, 20.0]), d), 1.0 - 0.1 * share,
                       atol=3e-3)


def test_a_yield_displacement_at_the_top_is_a_finding_in_two_directions():
    """As in one direction, unless a play is named or the named effects (u_y refitted with
    them) move it off the top: a lag can pull the baseline's u_y there."""
    from isolator.diagnosis.baseline import BaselineSpec

    empty = np.zeros((0, 2))
    base = two_directions.Baseline2D(BaselineSpec("constant"), 0.05, YIELD_DISPLACEMENT_MAX,
                                     0.0, empty, empty, empty, [], 0,
                                     {"yield_displacement": "top"})
    assert two_directions._yield_at_top(base, None, [])
    assert not two_directions._yield_at_top(base, None, ["backlash"])

    def chosen(u_y):
        model = two_directions.Model2D(kinematic=("lag",), free=True)
        return two_directions.Judged(model, np.array([0.05, math.log10(u_y), 0.01]),
                                     np.zeros(3), [], empty, empty)

    assert not two_directions._yield_at_top(base, chosen(3e-4), ["lag"])
    assert two_directions._yield_at_top(base, chosen(YIELD_DISPLACEMENT_MAX), ["lag"])
