"""``dcfpb compare-opensees`` and ``compare-opensees-bearing``: JSON keys, plots, clear errors."""

from __future__ import annotations

import json
from pathlib import Path

from dcfpb.cli import main

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"


def test_compare_opensees_json(ops, capsys):
    assert main(["compare-opensees", str(EXAMPLE), "--record", str(RECORD), "--duration", "8",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) == {"ours", "opensees", "difference", "wall_time_ratio"}
    for key in ("peak_isolator_displacement", "peak_base_shear", "nrmse_isolator_displacement",
                "nrmse_base_shear"):
        assert abs(out["difference"][key]) < 0.01
    assert out["opensees"]["element"] == "singleFPBearing Coulomb"
    assert out["ours"]["steps"] == out["opensees"]["steps"] == 1600
    assert out["wall_time_ratio"] > 0.0


def test_compare_opensees_plots(ops, tmp_path):
    plots = tmp_path / "plots"
    assert main(["compare-opensees", str(EXAMPLE), "--record", str(RECORD), "--duration", "2",
                 "--json", "--plot", str(plots)]) == 0
    assert {p.name for p in plots.iterdir()} >= {"isolator_hysteresis.png",
                                                  "response_histories.png"}


def test_compare_opensees_table(ops, capsys):
    assert main(["compare-opensees", str(EXAMPLE), "--record", str(RECORD), "--duration", "4",
                 "--model", "velocity", "--pendulum", "spring", "--integrator", "hht"]) == 0
    text = capsys.readouterr().out
    assert "flatSliderBearing + linear spring W/R VelDependent" in text
    assert "NRMSE" in text and "ratio ours/OpenSees" in text and "HHT" in text


def test_compare_opensees_bearing_json(ops, capsys):
    assert main(["compare-opensees-bearing", "--model", "ptv", "--cycles", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(out["difference"]["peak_force"]) < 0.01
    assert abs(out["difference"]["max_temperature"]) < 10.0
    assert main(["compare-opensees-bearing", "--cycles", "1"]) == 0
    assert "peak force" in capsys.readouterr().out


def test_missing_openseespy_is_a_clear_error(monkeypatch, capsys):
    import structures.opensees.building

    def unavailable():
        raise ImportError("openseespy is needed for the OpenSees comparison: pip install ...")

    monkeypatch.setattr(structures.opensees.building, "import_opensees", unavailable)
    assert main(["compare-opensees", str(EXAMPLE), "--record", str(RECORD), "--duration",
                 "1"]) == 2
    assert "openseespy is needed" in capsys.readouterr().err


def test_bad_scale_is_a_clear_error(capsys):
    assert main(["compare-opensees", str(EXAMPLE), "--record", str(RECORD), "--scale",
                 "0"]) == 2
    assert "scale" in capsys.readouterr().err
