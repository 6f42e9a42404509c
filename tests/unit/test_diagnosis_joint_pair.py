"""A play beside a friction law (issue 21): the pair fitted jointly and judged together, and in
two directions the play's static friction on an open axis as a share the data choose.

- :func:`isolator.diagnosis.selection.joint_pair_earns`, the one rule of one direction and
  two: the pair over the baseline by the kinematic thresholds, each member over the other
  by ``z_min``, ``name_min`` and ``practical_gain``;
- :func:`isolator.diagnosis.two_directions.play_return_map_2d` with a static ratio (one value
  or one per sample) and the model's ``static_share`` fitted from data made with either
  physics (0: no friction on an open axis, 1: static friction holding it).
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from isolator.diagnosis.data import BearingRecord2D, Campaign2D
from isolator.diagnosis.selection import joint_pair_earns
from isolator.diagnosis.thresholds import Thresholds
from isolator.diagnosis.two_directions import (
    Model2D,
    _prepare,
    play_return_map_2d,
    static_ratio,
)

BASE = SimpleNamespace(lag=0.0)  # the baseline's nuisance lag, all the model's state reads
TH = Thresholds(z_min=2.5, name_min=0.6, practical_gain=0.015, kinematic_z=3.0,
                kinematic_explained=0.6, kinematic_practical=0.03)


def test_a_pair_is_named_when_each_member_earns_its_keep_beside_the_other():
    pair = (19.3, 0.98, 0.34)
    assert joint_pair_earns(pair, (6.9, 0.87, 0.13), (18.2, 0.98, 0.32), TH)
    # the law closes a third of what the play leaves: a stand-in for the play's shape
    assert not joint_pair_earns(pair, (9.1, 0.34, 0.06), (9.8, 0.91, 0.26), TH)
    # the law is not significant beside the play, however much it closes
    assert not joint_pair_earns(pair, (1.2, 0.87, 0.13), (18.2, 0.98, 0.32), TH)
    # the play is too small a force beside the law
    assert not joint_pair_earns(pair, (6.9, 0.87, 0.13), (18.2, 0.98, 0.01), TH)
    # the pair as one must earn its keep over the baseline as a play does
    assert not joint_pair_earns((2.9, 0.98, 0.34), (6.9, 0.87, 0.13), (18.2, 0.98, 0.32), TH)
    assert not joint_pair_earns((19.3, 0.55, 0.34), (6.9, 0.87, 0.13), (18.2, 0.98, 0.32), TH)


def _circle(n: int = 2001, period: float = 2.5, radius: float = 0.1) -> np.ndarray:
    t = np.linspace(0.0, 2.0 * period, n)
    return np.column_stack([radius * np.cos(2 * np.pi * t / period) - radius,
                            radius * np.sin(2 * np.pi * t / period)]), t


def test_an_open_axis_holds_the_restoring_force_by_static_friction():
    """While an axis's gap is open the bearing stands still on it: static friction balances
    the restoring force there (z_j = -u_b,j / (R mu)) and the loaded axis slides with what
    the friction circle leaves; with no static ratio the open axis's z is 0 (as before)."""
    u, _ = _circle()
    x, y = u[:, 0].copy(), u[:, 1].copy()
    ratio = 1.0 / (4.5 * 0.04)
    plain = play_return_map_2d(x, y, 0.002, 0.002, 5e-4)
    zero = play_return_map_2d(x, y, 0.002, 0.002, 5e-4, 0.0)
    assert all(np.array_equal(a, b) for a, b in zip(plain, zero, strict=True))
    ub, z, engaged = play_return_map_2d(x, y, 0.002, 0.002, 5e-4, ratio)
    per_sample = play_return_map_2d(x, y, 0.002, 0.002, 5e-4, np.full(x.size, ratio))
    assert all(np.array_equal(a, b) for a, b in zip((ub, z, engaged), per_sample, strict=True))
    assert np.all(np.hypot(z[:, 0], z[:, 1]) <= 1.0 + 1e-12)
    for j in range(2):
        open_ = engaged[:, j] == 0.0
        assert open_.sum() > 20
        assert np.allclose(z[open_, j], np.clip(-ub[open_, j] * ratio, -1.0, 1.0))
        k = 1 - j
        both = open_ & (engaged[:, k] == 1.0)
        assert np.allclose(np.abs(z[both, k]), np.sqrt(1.0 - z[both, j] ** 2))
    assert np.array_equal(engaged, plain[2]) and np.array_equal(ub, plain[0])


def _campaign(share: float, seed: int = 3) -> tuple[Campaign2D, float]:
    """Two circles behind a play of 4 mm per axis, the force made by the model itself with a
    static ``share`` (mu 0.04, R 4.5 m, 1 MN), plus 0.5 % noise."""
    radius, load, mu = 4.5, 1.0e6, 0.04
    rng = np.random.default_rng(seed)
    records = []
    for k, (size, period) in enumerate(((0.1, 2.5), (0.15, 3.0))):
        u, t = _circle(1501, period, size)
        records.append(BearingRecord2D(f"{k + 1:02d}", t, u, np.zeros_like(u),
                                       np.full(t.size, load)))
    campaign = Campaign2D(tuple(records), radius, 0.25)
    d = _prepare(campaign, smooth=False)
    d.mu_shape = np.ones(d.n)
    model = Model2D(kinematic=("backlash",))
    theta = np.array([mu, math.log10(5e-4), 0.0, 4e-3, 4e-3, share])
    force = model.force(theta, d, BASE)
    force += rng.normal(0.0, 0.005 * mu * load, force.shape)
    first = 0
    made = []
    for r in records:
        made.append(BearingRecord2D(r.name, r.time, r.displacement,
                                    force[first:first + r.time.size], r.axial_force))
        first += r.time.size
    return Campaign2D(tuple(made), radius, 0.25), mu


@pytest.mark.parametrize("share", [0.0, 1.0])
def test_the_data_choose_the_static_share_of_the_play(share):
    """Least squares over the static share from 0.5: a play made without static friction (the
    example campaign's) is fitted near 0, one made with it (the validation truth's) near 1."""
    from isolator.diagnosis.solver import levenberg_marquardt

    campaign, mu = _campaign(share)
    d = _prepare(campaign, smooth=False)
    d.mu_shape = np.ones(d.n)
    model = Model2D(kinematic=("backlash",))
    params = model.layout(d, 5e-4)
    names = [p.name for p in params]
    assert names[-1] == "static_share" and params[-1].edge_ok
    start = np.array([mu, math.log10(5e-4), 0.0, 4e-3, 4e-3, 0.5])
    low = np.array([p.low for p in params])
    high = np.array([p.high for p in params])

    def residual(theta):
        return (d.force - model.force(theta, d, BASE)).ravel() / (mu * 1e6)

    fitted = levenberg_marquardt(residual, start, low, high, max_iterations=40).x
    assert abs(fitted[-1] - share) < 0.15
    assert static_ratio(d, 0.0, mu) == 0.0
    assert math.isclose(static_ratio(d, 1.0, mu), 1.0 / (4.5 * mu))
