"""The verdict of the diagnosis (issue 21): a nuisance fitted at the edge of its range is a
finding, a lag is named only as a channel can have it, and a residual far above the noise
inside the transition windows is never ``none``.

Synthetic campaigns from closed forms (F = N u / R + mu N z with z from the return map), so
the answer is known; about 5 s in all.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.diagnosis import BearingRecord, Campaign, diagnose
from isolator.diagnosis.baseline import BaselineFit, BaselineSpec, nuisance_edges
from isolator.diagnosis.kinematics import hysteretic_variable
from isolator.protocols import sine

D, R = 0.3, 4.5
N = 60e6 * np.pi * 0.15**2
MU = 0.05


def _record(force_of, amplitude, period, cycles=3, dt=0.01, noise=0.005, seed=0):
    h = sine(amplitude, period, cycles, dt)
    rng = np.random.default_rng(seed)
    force = force_of(h) + rng.normal(0.0, noise * MU * N, h.time.size)
    return BearingRecord(f"t{seed}", h.time,
                         h.displacement + rng.normal(0.0, 2e-5, h.time.size), force,
                         np.full(h.time.size, N), h.velocity)


def _fit(u_y=5e-4, lag_samples=0.0, fixed=None):
    return BaselineFit(BaselineSpec("constant", yield_displacement=fixed),
                       {"mu": MU, "yield_displacement": u_y}, None, 0, lag_samples * 0.01,
                       0.01, (1e-5, 2.5e-3))


def test_nuisance_edges_name_a_yield_displacement_at_the_top_and_a_lag_at_its_bound():
    assert nuisance_edges(_fit()) == {}
    assert nuisance_edges(_fit(u_y=2.5e-3)) == {"yield_displacement": "top"}
    assert nuisance_edges(_fit(u_y=2.5e-3, fixed=2.5e-3)) == {}  # given, not calibrated
    assert nuisance_edges(_fit(u_y=1e-5)) == {}  # the rigid-plastic limit is a reading
    assert nuisance_edges(_fit(lag_samples=-2.0)) == {"lag": "lead"}
    assert nuisance_edges(_fit(lag_samples=1.99)) == {"lag": "late"}


def test_a_speed_effect_at_several_periods_is_not_named_a_lag():
    def force(h):
        z = hysteretic_variable(h.displacement, 5e-4)
        mu = MU * (1.0 - 0.5 * np.exp(-np.abs(h.velocity) / 0.06))
        return N * h.displacement / R + mu * N * z

    tests = tuple(_record(force, 0.1, period, seed=k)
                  for k, period in enumerate((1.2, 3.0, 8.0)))
    summary = diagnose(Campaign(tests, R, D), "constant").to_json()
    assert "lag" not in summary["verdict"], summary["verdict"]
    assert summary["verdict"][0] == "velocity", summary["verdict"]
    nuisance = summary["nuisance"]
    assert nuisance["yield_displacement"]["range"] == pytest.approx([1e-5, 2.5e-3])
    assert nuisance["lag"]["plausible_max"] == pytest.approx(0.1)


def test_a_force_leading_the_displacement_is_not_named_a_lag():
    def leading(h):
        fine = sine(float(np.max(np.abs(h.displacement))), 2.5, 3, 0.001)
        z = hysteretic_variable(fine.displacement, 5e-4)
        clean = N * fine.displacement / R + MU * N * z
        return np.interp(h.time + 0.06, fine.time, clean, right=clean[-1])

    tests = tuple(_record(leading, a, 2.5, seed=k) for k, a in enumerate((0.1, 0.15, 0.2)))
    summary = diagnose(Campaign(tests, R, D), "constant").to_json()
    assert "lag" not in summary["verdict"], summary["verdict"]
    assert summary["nuisance"]["lag_candidate"]["force_leads"]
    assert summary["nuisance"]["lag"]["at_edge"] == "lead"


def test_a_residual_far_above_the_noise_in_the_transition_windows_is_never_none():
    def peaked(h):  # a static peak of 80 % fading over 1.5 mm after each reversal
        u = h.displacement
        z = hysteretic_variable(u, 2e-4)
        turns = np.r_[0, np.flatnonzero(np.diff(np.sign(np.diff(u))) != 0) + 1]
        travel = np.empty(u.size)
        for a, b in zip(turns, [*turns[1:], u.size], strict=True):
            travel[a:b] = np.abs(u[a:b] - u[a])
        return MU * N * z * (1.0 + 0.8 * np.clip(1.0 - travel / 1.5e-3, 0.0, None))

    tests = tuple(_record(peaked, a, 2.0, dt=0.004, seed=k) for k, a in enumerate((0.05, 0.08)))
    d = diagnose(Campaign(tests, float("inf"), D), "constant",
                 exclude=("breakaway", "backlash"))
    summary = d.to_json()
    assert summary["verdict"] != ["none"], summary["transition"]
    assert "transition" in d.selection.findings
    assert summary["transition"]["gap"] and summary["transition"]["score"] > 4.0
    assert "transition windows" in summary["unexplained"]["statement"]
