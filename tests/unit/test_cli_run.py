"""``dcfpb run`` and ``dcfpb demo``: JSON keys, netCDF, plots, and clear errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from dcfpb.cli import main

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"


def test_example_shipped_in_the_package_is_the_documented_one():
    assert (REPO / "dcfpb" / "data" / "five_storey.toml").read_bytes() == EXAMPLE.read_bytes()


def test_run_json_keys_and_values(capsys):
    assert main(["run", str(EXAMPLE), "--record", str(RECORD), "--model", "constant",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("peak_isolator_displacement", "peak_base_shear", "peak_roof_acceleration",
                "energy_balance_error", "steps", "wall_time"):
        assert key in out
    assert 0.02 < out["peak_isolator_displacement"] < 0.3
    assert out["steps"] == 6232  # 31.16 s of record at the file's dt = 0.005 s
    assert out["energy_balance_error"] < 1e-9


def test_run_scale_hht_output_and_plots(tmp_path, capsys):
    nc, plots = tmp_path / "run.nc", tmp_path / "plots"
    assert main(["run", str(EXAMPLE), "--record", str(RECORD), "--model", "simplified",
                 "--scale", "1.5", "--integrator", "hht", "--alpha", "-0.1", "--dt", "0.01",
                 "--output", str(nc), "--plot", str(plots)]) == 0
    text = capsys.readouterr().out
    assert "simplified" in text and "HHT" in text
    import xarray as xr

    with xr.open_dataset(nc) as ds:
        assert ds.sizes["floor"] == 6 and ds.sizes["storey"] == 5
        assert ds.attrs["friction_model"] == "simplified"
        assert "scaled by 1.5" in ds.attrs["record_processing"]
    assert {p.name for p in plots.iterdir()} >= {"isolator_hysteresis.png", "temperature.png",
                                                  "roof_acceleration.png", "storey_drift.png"}


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--record", "missing.at2"], "missing.at2"),
        (["--record", str(RECORD), "--dt", "0.05"], "'dt'"),
        (["--record", str(RECORD), "--integrator", "hht", "--alpha", "0.5"], "'alpha'"),
        (["--record", str(RECORD), "--scale", "-1"], "scale"),
    ],
)
def test_run_errors_are_clear(args, message, capsys):
    assert main(["run", str(EXAMPLE), *args]) == 2
    assert message in capsys.readouterr().err


def test_bad_building_file_names_the_key(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(EXAMPLE.read_text().replace("slider_diameter", "slider_diametre"))
    assert main(["run", str(bad), "--record", str(RECORD)]) == 2
    assert "slider_diametre" in capsys.readouterr().err


def test_demo_runs_and_writes_its_plots(tmp_path, capsys):
    assert main(["demo", "--plot", str(tmp_path / "demo")]) == 0
    out = capsys.readouterr().out
    for model in ("precise", "simplified", "constant"):
        assert model in out
    assert len(list((tmp_path / "demo").glob("*.png"))) == 5
