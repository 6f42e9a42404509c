"""``dcfpb compare-opensees`` with a pair: the building in plan against OpenSees 3D; its JSON,
its table and its errors, each naming the flag."""

from __future__ import annotations

import json

import numpy as np
import pytest

from dcfpb.cli import main

PLAN_FILE = """
name = "three-storey in plan"
[building]
floor_masses = [400e3, 400e3, 400e3]
fixed_base_period = 0.5
base_mass = 500e3
[bearing]
effective_radius = 4.5
slider_diameter = 0.3
yield_displacement = 0.0005
displacement_capacity = 0.6
[friction]
model = "constant"
[analysis]
dt = 0.005
[plan]
bearing_coordinates = [[-9.0, -6.0], [0.0, -6.0], [9.0, -6.0], [-9.0, 6.0], [0.0, 6.0],
                       [9.0, 6.0]]
eccentricity = [0.9, 0.6]
dimensions = [18.0, 12.0]
storey_heights = 3.5
"""
ONE_DIRECTION_FILE = PLAN_FILE.split("[plan]")[0].replace("[bearing]\n", "[bearing]\ncount = 6\n")


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The building files and a 2 s synthetic pair with a vertical, as text records."""
    from groundmotions.synthetic import synthetic_pair

    folder = tmp_path_factory.mktemp("plan")
    (folder / "plan.toml").write_text(PLAN_FILE)
    (folder / "modal.toml").write_text(PLAN_FILE.replace(
        "base_mass = 500e3\n", "base_mass = 500e3\n[building.damping]\nkind = \"modal\"\n"
        "ratio = 0.05\n"))
    (folder / "one_direction.toml").write_text(ONE_DIRECTION_FILE)
    (folder / "low.toml").write_text(PLAN_FILE.replace("storey_heights = 3.5\n", ""))
    pair = synthetic_pair("kanai-tajimi", 3, duration=2.0, dt=0.005, target_pga=4.0,
                          ground_frequency=15.0, ground_damping=0.6, vertical_ratio=0.5)
    for role, motion in zip("xyz", pair, strict=True):
        np.savetxt(folder / f"{role}.txt", np.column_stack([motion.time, motion.acceleration]))
    return folder


def _args(folder, *extra: str) -> list[str]:
    return ["compare-opensees", str(folder / "plan.toml"), "--record", str(folder / "x.txt"),
            "--record-y", str(folder / "y.txt"), "--units", "m/s^2", *extra]


def test_pair_runs_the_building_in_plan_against_opensees_3d(ops, files, capsys):
    """A plan with storey heights: the overturning on both sides by default, and the corner
    bearings' axial loads compared."""
    assert main(_args(files, "--record-z", str(files / "z.txt"), "--json")) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) == {"ours", "opensees", "difference", "corner_bearing", "axial_load",
                        "wall_time_ratio"}
    assert out["opensees"]["element"] == "singleFPBearing 3D Coulomb"
    assert out["ours"]["steps"] == out["opensees"]["steps"] == 400
    assert out["ours"]["overturning"] is True and out["opensees"]["overturning"] is True
    assert sorted(out["axial_load"]["bearings"]) == [0, 2, 3, 5]
    for side in ("ours", "opensees"):
        assert all(low < share < high for low, share, high in zip(
            out["axial_load"][side]["min"], out["axial_load"]["gravity_share"],
            out["axial_load"][side]["max"], strict=True))
    for key in ("peak_isolator_displacement", "peak_base_shear"):
        assert abs(out["difference"][key]) < 0.01
    for key in ("nrmse_isolator_displacement_x", "nrmse_isolator_displacement_y"):
        assert out["difference"][key] < 0.02
    for key in ("max_axial_load", "min_axial_load", "nrmse_axial_load"):
        assert abs(out["difference"][key]) < 0.05, key
    assert out["wall_time_ratio"] > 0.0


@pytest.mark.parametrize(("building", "extra"), [("plan.toml", ("--no-overturning",)),
                                                 ("low.toml", ())])
def test_without_overturning_on_both_sides(ops, files, capsys, building, extra):
    """``--no-overturning``, or a plan without storey heights: neither side has it."""
    args = _args(files, "--duration", "0.5", "--json", *extra)
    args[1] = str(files / building)
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ours"]["overturning"] is False and out["opensees"]["overturning"] is False
    assert out["axial_load"]["ours"]["max"] == out["axial_load"]["gravity_share"]


def test_modal_damping_in_plan(ops, files, capsys):
    """Modal damping in plan is a network of dashpots too (every level with the same
    eccentricity): the spring twin is ours to round-off."""
    args = _args(files, "--pendulum", "spring", "--duration", "1", "--no-overturning", "--json")
    args[1] = str(files / "modal.toml")
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["opensees"]["element"] == "flatSliderBearing 3D Coulomb + linear springs N_i/R"
    assert out["ours"]["steps"] == out["opensees"]["steps"] == 200
    for key, value in out["difference"].items():
        assert abs(value) < 1e-7, key


def test_spring_twin_table(ops, files, capsys):
    assert main(_args(files, "--pendulum", "spring", "--duration", "1", "--no-overturning")) == 0
    text = capsys.readouterr().out
    assert "flatSliderBearing 3D Coulomb + linear springs N_i/R" in text
    assert "NRMSE x" in text and "ratio ours/OpenSees" in text
    assert "     0.000" in text  # the spring twin is ours


def test_velocity_dependent_friction_in_plan(ops, files, capsys):
    """The element follows the friction model in plan too: VelDependent on singleFPBearing 3D
    at each bearing's own pressure."""
    assert main(_args(files, "--model", "velocity", "--duration", "1", "--json")) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["opensees"]["element"] == "singleFPBearing 3D VelDependent"
    for key in ("peak_isolator_displacement", "peak_base_shear"):
        assert abs(out["difference"][key]) < 0.02


@pytest.mark.parametrize(("extra", "flag"), [
    (("--scale", "0"), "--scale"),
    (("--duration", "0"), "--duration"),
    (("--dt", "-1"), "--dt"),
])
def test_bad_flags_with_a_pair_name_the_flag(files, capsys, extra, flag):
    assert main(_args(files, *extra)) == 2
    assert flag in capsys.readouterr().err


def test_a_pair_needs_a_plan_and_z_needs_y(files, capsys):
    one_direction = ["compare-opensees", str(files / "one_direction.toml"), "--record",
                     str(files / "x.txt"), "--units", "m/s^2"]
    assert main([*one_direction, "--record-y", str(files / "y.txt")]) == 2
    assert "--record-y" in capsys.readouterr().err
    assert main([*one_direction, "--record-z", str(files / "z.txt")]) == 2
    assert "--record-z needs --record-y" in capsys.readouterr().err
    assert main([*one_direction, "--overturning"]) == 2
    assert "--overturning" in capsys.readouterr().err
    low = _args(files, "--overturning")
    low[1] = str(files / "low.toml")
    assert main(low) == 2
    assert "--overturning needs the storey heights" in capsys.readouterr().err
