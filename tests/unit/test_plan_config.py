"""A building file with a [plan] table runs in plan under a pair, and in its planar form under
one record; the planar example file runs as before (no plan)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import structures
from dcfpb.common.errors import InputError
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


def test_a_plan_file_runs_planar_under_one_record(plan_file):
    result = structures.run(plan_file, _pair().x, engine="reference")
    assert result.attrs["success"] and result.attrs["n_bearings"] == 4
    assert "direction" not in result.dims


def test_a_pair_refuses_what_the_plan_run_does_not_do(plan_file):
    with pytest.raises(InputError, match="floor_spectra"):
        structures.run(plan_file, _pair(), floor_spectra=True)
