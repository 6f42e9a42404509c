"""The ``dcfpb protocol`` command: JSON keys, CSV and PNG outputs, errors, numba fallback."""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from dcfpb.cli import main

REPO = Path(__file__).resolve().parents[2]
ARGS = ["protocol", "--slider-diameter", "0.3", "--pressure", "60e6", "--effective-radius",
        "4.5", "--amplitude", "0.3", "--period", "4.26", "--cycles", "2", "--dt", "0.01"]


def _json(capsys, *extra):
    assert main([*ARGS, *extra, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_has_the_documented_keys(capsys):
    out = _json(capsys, "--model", "precise")
    assert out["model"] == "precise"
    assert out["max_temperature"] > 50.0
    assert [c["cycle"] for c in out["cycles"]] == [1, 2]
    for key in ("Fmax", "Fmin", "Kru", "Krl", "EDC", "Keff", "beta_eff"):
        assert all(isinstance(c[key], float) for c in out["cycles"]), key


def test_constant_model_options_reach_the_model(capsys):
    default = _json(capsys, "--model", "constant")
    doubled = _json(capsys, "--model", "constant", "--mu0", "0.082")
    assert doubled["cycles"][1]["EDC"] == pytest.approx(2 * default["cycles"][1]["EDC"],
                                                        rel=5e-3)
    assert default["max_temperature"] == 20.0


def test_refinement_and_axial_load_options(capsys):
    lam = _json(capsys, "--model", "simplified", "--refinement", "0.886")
    half = _json(capsys, "--model", "simplified")
    assert lam["max_temperature"] > half["max_temperature"]
    without_pressure = [a for a in ARGS if a not in ("--pressure", "60e6")]
    assert main([*without_pressure, "--model", "constant", "--axial-load", "2e6", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["axial_load"] == 2e6


def test_csv_and_plot_outputs(tmp_path, capsys):
    csv_path, png_path = tmp_path / "h.csv", tmp_path / "h.png"
    assert main([*ARGS, "--model", "simplified", "--output", str(csv_path), "--plot",
                 str(png_path)]) == 0
    capsys.readouterr()
    with csv_path.open() as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["time", "displacement", "velocity", "force", "mu", "temperature"]
    assert len(rows) == 1 + 2 * 426 + 1
    assert png_path.stat().st_size > 10_000


def test_bad_value_is_a_clear_error_with_exit_status_2(capsys):
    assert main([*ARGS[:-2], "--dt", "-0.01"]) == 2
    err = capsys.readouterr().err
    assert "'--dt'" in err and "-0.01" in err  # the flag, by its name
    assert main([*ARGS, "--mu0", "2"]) == 2
    assert "'--mu0'" in capsys.readouterr().err


def test_pure_python_fallback_gives_the_compiled_answer(capsys):
    """The kernels run as plain Python with DCFPB_DISABLE_NUMBA=1, with the same result."""
    compiled = _json(capsys, "--model", "precise")
    env = {**os.environ, "DCFPB_DISABLE_NUMBA": "1", "PYTHONPATH": str(REPO)}
    run = subprocess.run([sys.executable, "-m", "dcfpb.cli", *ARGS, "--model", "precise",
                          "--json"], capture_output=True, text=True, env=env, check=True)
    fallback = json.loads(run.stdout)
    for a, b in zip(compiled["cycles"], fallback["cycles"], strict=True):
        for key in ("Fmax", "Fmin", "EDC", "Keff"):
            # numba's exp and numpy's may differ in the last bit; over 400 steps that stays
            # far below 1e-10
            assert a[key] == pytest.approx(b[key], rel=1e-10)
    check = subprocess.run([sys.executable, "-c", "import isolator.compiled.kernels as k; "
                            "print(k.COMPILED)"], capture_output=True, text=True, env=env)
    assert check.stdout.strip() == "False"
