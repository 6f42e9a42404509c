"""Bearings lifted off by a strong vertical component are reported (issue 22): the steps per
bearing, the first time and the longest lift-off in the Dataset's attributes, in the peaks and
as one warning line of ``dcfpb run``."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import structures
from dcfpb.cli import main
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from structures.analysis import peaks
from structures.results import UpliftWarning, uplift_record

PLAN_FILE = """
name = "two storeys"
[building]
floor_masses = [400e3, 400e3]
fixed_base_period = 0.3
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
dimensions = [12.0, 10.0]
storey_heights = 3.5
"""
DT = 0.01
N = 300  # 3 s


def _component(values: np.ndarray, name: str) -> GroundMotion:
    return GroundMotion(values, DT, name)


def _pair(vertical_g: float) -> GroundMotionPair:
    t = DT * np.arange(N)
    x = _component(2.0 * np.sin(2 * math.pi * 0.8 * t), "x")
    y = _component(1.0 * np.sin(2 * math.pi * 0.6 * t), "y")
    # positive up; the bearings carry W (1 + a_z / g): below -g they lift off
    z = _component(vertical_g * STANDARD_GRAVITY * np.sin(2 * math.pi * 2.0 * t), "z")
    return GroundMotionPair(x, y, z, name="strong vertical")


@pytest.fixture(scope="module")
def plan_file(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("uplift") / "plan.toml"
    path.write_text(PLAN_FILE, encoding="utf-8")
    return path


def test_uplift_record_counts_first_and_longest():
    load = np.array([[1.0, 1.0], [0.0, 1.0], [-2.0, 1.0], [1.0, 1.0], [-1.0, 1.0], [1.0, 1.0]])
    record = uplift_record(load, 0.5)
    assert record["uplift_steps"] == [3, 0]
    assert record["uplift_first_time"] == [0.5, -1.0]  # -1: never lifted
    assert record["uplift_longest"] == [1.0, 0.0]


def test_a_strong_vertical_lifts_the_bearings_and_the_run_says_so(plan_file):
    result = structures.run(plan_file, _pair(1.5))
    assert result.attrs["success"]
    lifted = result["axial_load"].values <= 0.0
    steps = lifted.sum(axis=0)
    assert steps.min() > 10  # a_z below -g for about a quarter of each cycle
    assert result.attrs["uplift_steps"] == steps.tolist()
    first = DT * np.argmax(lifted, axis=0)
    assert np.allclose(result.attrs["uplift_first_time"], first)
    p = peaks(result)
    assert p["uplift_bearings"] == 4 and p["uplift_steps"] == int(steps.max())
    assert p["uplift_first_time"] == pytest.approx(first.min())
    # -1.5 g sin: below -g for (pi - 2 asin(1 / 1.5)) / (2 pi) of a 0.5 s cycle, ~0.13 s
    assert 0.08 < p["uplift_longest"] < 0.2


def test_a_run_without_uplift_reports_none(plan_file):
    p = peaks(structures.run(plan_file, _pair(0.3)))
    assert p["uplift_bearings"] == 0 and p["uplift_steps"] == 0
    assert p["uplift_first_time"] is None and p["uplift_longest"] == 0.0


def _files(folder: Path, vertical_g: float) -> list[str]:
    pair = _pair(vertical_g)
    names = []
    for role in ("x", "y", "z"):
        path = folder / f"{role}.txt"
        motion = getattr(pair, role)
        np.savetxt(path, np.column_stack([motion.time, motion.acceleration]))
        names.append(str(path))
    return names


def test_dcfpb_run_prints_one_uplift_warning_and_the_json_keys(plan_file, tmp_path, capsys):
    x, y, z = _files(tmp_path, 1.5)
    args = ["run", str(plan_file), "--record", x, "--record-y", y, "--record-z", z, "--units",
            "m/s^2"]
    with pytest.warns(UpliftWarning) as caught:
        assert main([*args, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["success"] and out["uplift_bearings"] == 4 and out["uplift_steps"] > 10
    assert out["uplift_longest"] > 0.08 and out["uplift_first_time"] > 0.0
    assert "peak_isolator_displacement" in out  # the old keys stay
    assert len(caught) == 1
    message = str(caught[0].message)
    for text in ("4 of 4 bearing positions lifted off", "no friction and no restoring force",
                 "first at t = ", "longest ", "uplift_steps"):
        assert text in message, (text, message)


def test_dcfpb_run_without_uplift_warns_of_none(plan_file, tmp_path, capsys):
    x, y, z = _files(tmp_path, 0.3)
    import warnings

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert main(["run", str(plan_file), "--record", x, "--record-y", y, "--record-z", z,
                     "--units", "m/s^2", "--json"]) == 0
    assert not [w for w in caught if issubclass(w.category, UpliftWarning)]
    assert json.loads(capsys.readouterr().out)["uplift_bearings"] == 0
