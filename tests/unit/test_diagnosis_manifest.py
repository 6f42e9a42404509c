"""Campaign manifests: the tests in run order with their axial load, initial temperature and
rest; every bad manifest is an error that names the manifest, the test and the problem."""

from __future__ import annotations

import json

import numpy as np
import pytest

import dcfpb.cli
from isolator.diagnosis import DataError
from isolator.diagnosis.features import kinematic_features, measured_temperature_rise
from isolator.diagnosis.manifest import load_manifest
from isolator.heating import MonitorLine, ThermalProperties

N = 4.24e6


def _write_test(path, amplitude=0.1, scale=1.0, axial=None, dt=0.01, time_scale=1.0):
    t = np.arange(0.0, 5.0, dt)
    u = amplitude * np.sin(2.0 * np.pi * t / 2.5)
    v = amplitude * 2.0 * np.pi / 2.5 * np.cos(2.0 * np.pi * t / 2.5)
    f = N * u / 4.5 + 0.05 * N * np.tanh(v / 0.01)
    columns = {"time": t * time_scale, "displacement": u * scale, "force": f,
               "velocity": v * scale / time_scale}  # the velocity channel in the same units
    if axial is not None:
        columns["axial_force"] = np.full(t.size, axial)
    np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",",
               header=",".join(columns), comments="", fmt="%.10g")


@pytest.fixture
def folder(tmp_path):
    _write_test(tmp_path / "a.csv", 0.1)
    _write_test(tmp_path / "b.csv", 0.2)
    _write_test(tmp_path / "c.csv", 0.15, axial=2.0 * N)
    return tmp_path


def test_csv_manifest_gives_each_test_its_conditions(folder):
    (folder / "m.csv").write_text("file,axial_load,initial_temperature,rest_before\n"
                                  f"a.csv,{N},20,\nb.csv,{0.5 * N},25,60\nc.csv,,30,3600\n")
    campaign = load_manifest(folder / "m.csv", effective_radius=4.5, slider_diameter=0.3)
    a, b, c = campaign.tests
    assert [t.name for t in campaign.tests] == ["a", "b", "c"]
    assert a.axial_force[0] == N and b.axial_force[0] == 0.5 * N and c.axial_force[0] == 2 * N
    assert (a.rest_before, b.rest_before, c.rest_before) == (None, 60.0, 3600.0)
    assert (a.initial_temperature, c.initial_temperature) == (20.0, 30.0)


def test_toml_manifest_may_give_the_bearing(folder):
    (folder / "m.toml").write_text('effective_radius = 4.5\nslider_diameter = 0.3\n'
                                   f'[[test]]\nfile = "a.csv"\naxial_load = {N}\n'
                                   f'[[test]]\nfile = "b.csv"\naxial_load = {N}\n'
                                   'rest_before = 10.0\n')
    campaign = load_manifest(folder / "m.toml")
    assert campaign.effective_radius == 4.5 and len(campaign.tests) == 2


def test_heat_is_carried_over_a_short_rest_and_forgotten_after_a_long_one(folder):
    def rise(rest):
        (folder / "m.csv").write_text(f"file,axial_load,rest_before\na.csv,{N},\n"
                                      f"b.csv,{N},{rest}\n")
        campaign = load_manifest(folder / "m.csv", effective_radius=4.5, slider_diameter=0.3)
        features, _ = kinematic_features(campaign)
        r = measured_temperature_rise(features, campaign, MonitorLine(), ThermalProperties())
        return r[features.test == 1]

    short, long_rest = rise(1.0), rise(1.0e5)
    assert long_rest[0] == 0.0
    assert short[0] > 1.0  # the plate is still warm from the first test
    assert np.all(short >= long_rest - 1e-9)


@pytest.mark.parametrize("text, message", [
    ("file,axial_load\nmissing.csv,4e6\n", "does not exist"),
    ("file,axial_load\nc.csv,1e6\n", "disagrees with the file's axial_force"),
    ("file,load\na.csv,4e6\n", "unknown column"),
    ("file,axial_load\na.csv,heavy\n", "'axial_load' must be a number"),
    ("file,axial_load\na.csv,\n", "no axial_force column and no axial_load"),
    ("name\na.csv\n", "needs a header with a 'file' column"),
])
def test_bad_manifests_name_the_problem(folder, text, message):
    (folder / "m.csv").write_text(text)
    with pytest.raises(DataError, match=message):
        load_manifest(folder / "m.csv", effective_radius=4.5, slider_diameter=0.3)


def test_a_campaign_mixing_units_is_refused(folder):
    _write_test(folder / "mm.csv", 0.004, scale=1000.0)  # 4 mm written in mm: "4 m"
    _write_test(folder / "ms.csv", 0.1, time_scale=1000.0)  # time in ms
    (folder / "m.csv").write_text(f"file,axial_load\na.csv,{N}\nb.csv,{N}\nms.csv,{N}\n")
    with pytest.raises(DataError, match=r"time step .* mixes units"):
        load_manifest(folder / "m.csv", effective_radius=4.5, slider_diameter=0.3)
    (folder / "m.csv").write_text(f"file,axial_load\na.csv,{N}\na.csv,{N}\nmm.csv,{N}\n")
    with pytest.raises(DataError, match=r"peak displacement .* mixes units"):
        load_manifest(folder / "m.csv", effective_radius=4.5, slider_diameter=0.3)


def test_cli_reads_a_manifest_and_refuses_a_missing_file(folder, capsys):
    (folder / "m.csv").write_text(f"file,axial_load\na.csv,{N}\nb.csv,{N}\n")
    assert dcfpb.cli.main(["diagnose", "--manifest", str(folder / "m.csv"), "--model",
                           "constant", "--effective-radius", "4.5", "--slider-diameter", "0.3",
                           "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["tests"] == 2 and {"transition", "lag"} <= set(out)
    (folder / "m.csv").write_text(f"file,axial_load\na.csv,{N}\ngone.csv,{N}\n")
    assert dcfpb.cli.main(["diagnose", "--manifest", str(folder / "m.csv"), "--model",
                           "constant", "--effective-radius", "4.5",
                           "--slider-diameter", "0.3"]) == 2
    assert "gone.csv" in capsys.readouterr().err
