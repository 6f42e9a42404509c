"""``dcfpb run --record X --record-y Y``: a building file with a [plan] table under a pair; the
peaks in plan (structures.analysis.peaks of a run in plan) against the Dataset; the figures;
clear errors."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import structures
from dcfpb.cli import main
from dcfpb.common.errors import InputWarning
from groundmotions.synthetic import synthetic_pair
from structures.analysis import peaks

PLAN_PEAK_KEYS = (
    "peak_isolator_displacement", "peak_centre_displacement", "corner_bearing",
    "peak_base_shear", "peak_roof_acceleration_x", "peak_roof_acceleration_y",
    "peak_storey_drift_x", "peak_storey_drift_y", "peak_base_rotation", "max_temperature",
    "energy_balance_error", "steps", "wall_time", "peaks_up_to_failure", "failed_at",
    "failure",
)
"""The keys of the peaks of a run in plan (:func:`structures.analysis.peaks`)."""

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"

PLAN_FILE = """
name = "three storeys"
[building]
floor_masses = [400e3, 400e3, 400e3]
fixed_base_period = 0.5
base_mass = 500e3
[bearing]
effective_radius = 2.5
slider_diameter = 0.3
[friction]
model = "simplified"
[analysis]
dt = 0.01
[plan]
bearing_coordinates = [[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0]]
eccentricity = [1.2, 0.5]
dimensions = [12.0, 10.0]
storey_heights = 3.5
"""


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("pair")
    pair = synthetic_pair("kanai-tajimi", 11, duration=4.0, dt=0.01, target_pga=4.0,
                          ground_frequency=8.0, ground_damping=0.6)
    paths = {"plan": folder / "plan.toml"}
    paths["plan"].write_text(PLAN_FILE, encoding="utf-8")
    for role, motion in (("x", pair.x), ("y", pair.y)):
        paths[role] = folder / f"{role}.txt"
        np.savetxt(paths[role], np.column_stack([motion.time, motion.acceleration]))
    paths["coarse"] = folder / "coarse.txt"  # the y component at twice the step
    np.savetxt(paths["coarse"], np.column_stack([pair.y.time[::2], pair.y.acceleration[::2]]))
    return paths


def _args(files, *extra):
    return ["run", str(files["plan"]), "--record", str(files["x"]), "--record-y",
            str(files["y"]), "--units", "m/s^2", *extra]


def test_a_pair_runs_the_plan_and_prints_its_peaks(files, capsys, tmp_path):
    plots = tmp_path / "plots"
    assert main(_args(files, "--json", "--plot", str(plots))) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(PLAN_PEAK_KEYS) <= set(out) and out["success"]
    assert set(out["ratios_to_fixed_base"]) >= {"peak_storey_drift_x", "peak_storey_drift_y"}
    from groundmotions.pairs import read_pair

    pair = read_pair(files["x"], files["y"], units="m/s^2")
    direct = peaks(structures.run(files["plan"], pair))
    for key in ("peak_isolator_displacement", "peak_base_shear", "peak_roof_acceleration_y",
                "max_temperature"):
        assert out[key] == direct[key]  # the command line is the library's one path
    assert out["energy_balance_error"] < 1e-6
    written = {p.name for p in plots.iterdir()}
    # the figures of every building run (a panel or a line style per direction), with the
    # floor spectra and the fixed-base comparison, and the figures of a building in plan
    assert written == {"isolator_hysteresis.png", "temperature.png", "roof_acceleration.png",
                       "storey_drift.png", "response_histories.png", "floor_spectra.png",
                       "isolation_effect.png", "bearing_orbits.png", "force_orbits.png"}
    assert all((plots / name).stat().st_size > 10_000 for name in written)


def test_the_peaks_in_plan_hold_to_the_histories(files):
    from groundmotions.pairs import read_pair

    result = structures.run(files["plan"], read_pair(files["x"], files["y"], units="m/s^2"))
    p = peaks(result)
    assert tuple(p) == (*PLAN_PEAK_KEYS, "uplift_bearings", "uplift_steps", "uplift_first_time",
                        "uplift_longest")  # the lift-off keys last (no vertical: none)
    assert p["uplift_bearings"] == 0
    reach = np.hypot(*np.moveaxis(result["bearing_displacement"].values, -1, 0))
    assert p["peak_isolator_displacement"] == reach.max()
    assert p["corner_bearing"] == int(np.argmax(reach.max(axis=0)))
    # the reference point is the bearings' centroid: its displacement is their mean, so no
    # bearing's peak is below it, and with e = (1.2, 0.5) m the base turns
    assert p["peak_centre_displacement"] <= p["peak_isolator_displacement"]
    assert p["peak_base_rotation"] > 0.0
    forces = result["bearing_force"].values.sum(axis=1)
    assert p["peak_base_shear"] == pytest.approx(np.hypot(*forces.T).max(), rel=1e-12)
    roof = result["absolute_acceleration"].isel(floor=-1).values
    assert p["peak_roof_acceleration_x"] == np.abs(roof[:, 0]).max()
    assert p["max_temperature"] > 25.0  # the simplified model heats the plates


def test_a_plan_file_under_one_record_warns_that_it_runs_in_one_direction(files, capsys):
    with pytest.warns(InputWarning, match="runs under one record.*give a pair of records"):
        assert main(["run", str(files["plan"]), "--record", str(files["x"]), "--units",
                     "m/s^2", "--model", "constant"]) == 0


@pytest.mark.parametrize(("extra", "message"), [
    (["--record-z", "z.txt"], "--record-z needs --record-y"),
])
def test_a_vertical_needs_a_pair(files, capsys, extra, message):
    assert main(["run", str(files["plan"]), "--record", str(files["x"]), *extra]) == 2
    assert message in capsys.readouterr().err


def test_a_pair_needs_a_plan(files, capsys):
    assert main(["run", str(EXAMPLE), "--record", str(files["x"]), "--record-y",
                 str(files["y"]), "--units", "m/s^2"]) == 2
    err = capsys.readouterr().err
    assert "[plan] table" in err and "five_storey.toml" in err


def test_components_of_other_steps_are_refused_unless_resampled(files, capsys):
    args = ["run", str(files["plan"]), "--record", str(files["x"]), "--record-y",
            str(files["coarse"]), "--units", "m/s^2", "--json"]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "dt = 0.01 s" in err and "dt = 0.02 s" in err and "--resample" in err
    assert main([*args, "--resample", "--truncate"]) == 0


def test_the_precise_model_leaves_its_plate_field_in_the_dataset(files, tmp_path):
    from dcfpb.plotting import plot_runs
    from groundmotions.pairs import read_pair

    pair = read_pair(files["x"], files["y"], units="m/s^2")
    result = structures.run(files["plan"], pair, model="precise")
    field = result["plate_temperature"].values
    assert field.shape[0] == 4 and np.isfinite(field).sum(axis=1).min() > 1000
    # cold outside the region the slider crossed, hot inside it
    assert np.nanmin(field) == pytest.approx(20.0, abs=0.5)
    assert 40.0 < np.nanmax(field) < result["temperature"].values.max() + 30.0
    assert "plate_temperature" not in structures.run(files["plan"], pair, model="simplified")
    written = plot_runs({"precise": result}, tmp_path)
    assert tmp_path / "plate_temperature.png" in written
