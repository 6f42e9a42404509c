"""A building file with a [plan] table runs in plan under a pair (with its floor spectra per
direction), and in one direction under one record, with a warning; the example file in one
direction runs as before (no plan)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import structures
from dcfpb.common.errors import InputWarning
from groundmotions.synthetic import synthetic_pair

PLAN_FILE = """
name = "three storeys in plan"
[building]
floor_masses = [400e3, 400e3, 400e3]
fixed_base_period = 0.5
base_mass = 500e3
[bearing]
effective_radius = 2.5
slider_diameter = 0.3
[friction]
model = "constant"
[analysis]
dt = 0.01
[plan]
bearing_coordinates = [[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0]]
eccentricity = [1.2, 0.0]
dimensions = [12.0, 10.0]
storey_heights = 3.5
"""


@pytest.fixture
def plan_file(tmp_path: Path) -> Path:
    path = tmp_path / "plan.toml"
    path.write_text(PLAN_FILE, encoding="utf-8")
    return path


def _pair():
    return synthetic_pair("kanai-tajimi", 5, duration=2.0, dt=0.01, target_pga=3.0,
                          ground_frequency=15.0, ground_damping=0.6)


def test_a_plan_file_runs_in_plan_under_a_pair(plan_file):
    result = structures.run(plan_file, _pair())
    assert result.attrs["success"] and result.attrs["building"] == "three storeys in plan"
    assert result.attrs["n_bearings"] == 4 and result.attrs["overturning"] == 1
    assert list(result["direction"].values) == ["x", "y"]
    assert np.abs(result["rotation"].values).max() > 0.0  # e_x = 1.2 m turns it
    assert result.attrs["energy_balance_error"] < 1e-6
    assert np.allclose(result["axial_load"].values[0].sum(),
                       structures.load_config(plan_file).building.weight, rtol=1e-12)


def test_a_plan_file_runs_in_one_direction_under_one_record(plan_file):
    with pytest.warns(InputWarning, match="runs under one record"):
        result = structures.run(plan_file, _pair().x, engine="reference")
    assert result.attrs["success"] and result.attrs["n_bearings"] == 4
    assert list(result["direction"].values) == ["x"]  # one direction: the one Dataset layout
    assert "rotation" not in result and list(result["bearing_count"].values) == [4]


def test_a_pair_runs_the_floor_spectra_in_plan(plan_file):
    """Floor spectra in plan (refused before the one building): one per floor and direction,
    the ground's per component; at period 0 the peak absolute accelerations and the PGAs."""
    pair = _pair()
    result = structures.run(plan_file, pair, floor_spectra=True)
    assert result["floor_spectrum"].dims == ("floor", "direction", "period")
    assert result["ground_spectrum"].dims == ("direction", "period")
    peaks = np.abs(result["absolute_acceleration"]).max("time").values
    assert np.array_equal(result["floor_spectrum"].isel(period=0).values, peaks)
    assert list(result["ground_spectrum"].isel(period=0).values) == [pair.x.pga, pair.y.pga]
