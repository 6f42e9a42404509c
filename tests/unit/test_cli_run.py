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
    # the five plots of the three models, then the floor spectra and the fixed-base ratios
    assert {p.name for p in (tmp_path / "demo").glob("*.png")} == {
        "isolator_hysteresis.png", "temperature.png", "roof_acceleration.png",
        "storey_drift.png", "response_histories.png", "floor_spectra.png",
        "isolation_effect.png"}


def test_demo_table_has_the_fixed_base_and_the_ratios(tmp_path, capsys):
    assert main(["demo", "--plot", str(tmp_path / "demo")]) == 0
    lines = capsys.readouterr().out.splitlines()
    fixed = next(line for line in lines if line.startswith("fixed base"))
    assert float(fixed.split()[4]) > 10.0  # roof acceleration [m/s2]: about 4.5 x the PGA
    header = lines.index("isolated / fixed base (below 1: the isolation reduces it)")
    assert lines[header + 1].split() == ["model", "drift", "storey", "shear", "roof", "acc",
                                         "base", "shear"]
    for model, line in zip(("precise", "simplified", "constant"), lines[header + 2:header + 5],
                           strict=True):
        name, *ratios = line.split()
        assert name == model and len(ratios) == 4
        assert all(0.0 < float(r) < 0.5 for r in ratios)


def test_run_output_carries_the_floor_spectra(tmp_path, capsys):
    nc = tmp_path / "run.nc"
    assert main(["run", str(EXAMPLE), "--record", str(RECORD), "--model", "constant",
                 "--output", str(nc)]) == 0
    import xarray as xr

    with xr.open_dataset(nc) as ds:
        assert ds["floor_spectrum"].dims == ("floor", "direction", "period")
        assert ds["ground_spectrum"].dims == ("direction", "period")
        assert list(ds["direction"].values) == ["x"]
        assert ds["period"].values[0] == 0.0 and ds.attrs["spectrum_damping"] == 0.05


def test_own_commands_do_not_import_the_others(monkeypatch):
    """``dcfpb run`` and ``demo`` parse without importing the other commands' modules."""
    import sys

    from dcfpb.cli import COMMAND_MODULES, build_parser

    parser = build_parser(modules=False)
    choices = parser._subparsers._group_actions[0].choices
    assert set(choices) == {"protocol", "run", "demo"}
    assert set(build_parser()._subparsers._group_actions[0].choices) > set(choices)
    monkeypatch.setitem(sys.modules, "dcfpb.cli.diagnose", None)  # importing it would fail
    args = ["run", str(EXAMPLE), "--record", "missing.at2"]
    assert main(args) == 2  # parsed and run (the record is missing), diagnose never imported
    assert COMMAND_MODULES[-1] == "dcfpb.cli.diagnose"
