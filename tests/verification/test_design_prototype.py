"""The virtual prototype test of ASCE/SEI 7-16 Sec. 17.8 (structures.design.prototype): on the
constant model the loop is rigid-plastic, EDC = 4 mu W D, so every cycle's mu is the model's and
lambda_test is 1; on the simplified model heating lowers mu cycle by cycle."""

from __future__ import annotations

from pathlib import Path

import pytest

from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction
from structures.config import load_config
from structures.design import prototype_test

ROOT = Path(__file__).resolve().parents[2]


def test_constant_model_gives_its_mu_in_every_cycle():
    friction = ConstantFriction(mu0=0.05)
    bearing = DCFPBearing(effective_radius=4.5, slider_diameter=0.3, axial_load=2.0e6,
                          friction=friction, yield_displacement=1e-7)
    result = prototype_test(bearing, 0.3, 0.36, 3.0, dt=3.0 / 400)
    assert [c.block for c in result.cycles[:3]] == ["0.25 D_M"] * 3
    assert len(result.cycles) == 5 * 3 + 10  # items 2a, 3 and 4 (10 cycles)
    # The first cycle starts from rest: its loop is closed on a first sample of zero force, and
    # the trapezoid loses mu W du / 2 there (0.2 % at 400 steps per cycle). The others lose
    # only the sampling of the reversals (6e-5).
    first, *others = result.cycles
    assert first.mu == pytest.approx(friction.mu, rel=3e-3)
    for cycle in others:
        edc, q_d = cycle.EDC, cycle.Q_d
        assert cycle.mu == pytest.approx(friction.mu, rel=1e-4)
        assert edc == pytest.approx(4 * friction.mu * 2.0e6 * cycle.D, rel=1e-4)
        assert q_d == pytest.approx(friction.mu * 2.0e6, rel=1e-4)
    assert result.nominal_mu == pytest.approx(friction.mu, rel=1e-4)
    assert result.lambda_test_max == pytest.approx(1.0, abs=1e-6)
    assert result.lambda_test_min == pytest.approx(1.0, abs=1e-6)
    lam = result.property_modification(ae_max=1.1)
    assert lam.test_max == pytest.approx(1.0, abs=1e-6)
    assert result.to_dict()["cycle_units"]["Q_d"] == "N"


def test_simplified_model_spreads_mu_over_the_cycles():
    config = load_config(ROOT / "examples" / "five_storey.toml")
    result = prototype_test(config, 0.25, 0.3, 3.0, model="simplified", dt=3.0 / 40)
    at_dm = [c.mu for c in result.cycles if c.block == "1.0 D_M"]
    assert at_dm[0] > at_dm[1] > at_dm[2]  # the plates heat
    assert result.lambda_test_max > 1.0 > result.lambda_test_min
    assert result.all_cycles_max > result.lambda_test_max
    assert "lambda_test,max" in result.table()
