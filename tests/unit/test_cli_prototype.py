"""``dcfpb prototype``: the virtual prototype test of 17.8 on the command line: the per-cycle
table, CSV and JSON output, the figure, the flags' errors (exit status 2 naming the flag) and
``--overwrite``."""

from __future__ import annotations

import csv
import json

import pytest

from dcfpb.cli import main
from tests.unit.design_result_helper import BUILDING

GIVEN = ["--model", "constant", "--displacements", "0.2,0.25", "--period", "3.0"]


def test_the_table_from_the_elf(capsys):
    from dcfpb.common.errors import InputWarning

    with pytest.warns(InputWarning, match="17.2.8.4"):  # lambda inside 1.8 / 0.6
        status = main(["prototype", str(BUILDING), "--model", "constant", "--site", "1.5,0.6",
                       "--lambda", "1.5,0.8", "--lambda-test", "1.2,0.85"])
    out = capsys.readouterr().out
    assert status == 0
    assert out.startswith("D_M, D_TM, T_M from ELF, lower bound (lambda 0.8)")
    assert "Q_d [kN]" in out and "mu/nom" in out
    for block in ("0.25 D_M", "0.5 D_M", "0.67 D_M", "1.0 D_M", "D_TM", "0.75 D_TM"):
        assert f"\n{block} " in out
    assert "lambda_test,max" in out
    assert "within the assumed 1.2 / 0.85 (--lambda-test)" in out


def test_csv_json_and_the_figure(tmp_path, capsys):
    table = tmp_path / "cycles.csv"
    status = main(["prototype", str(BUILDING), *GIVEN, "--output", str(table),
                   "--plot", str(tmp_path / "plots")])
    assert status == 0
    out = capsys.readouterr().out
    assert "D_M, D_TM, T_M from given" in out
    with open(table, newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0][:6] == ["block", "cycle", "D [m]", "EDC [J]", "Q_d [N]", "mu [-]"]
    assert len(rows) == 1 + 4 * 3 + 3 + 10
    d, edc, q_d = (float(x) for x in rows[1][2:5])
    assert q_d == pytest.approx(edc / (4 * d))
    figure = tmp_path / "plots" / "prototype_hysteresis.png"
    assert figure.read_bytes()[:4] == b"\x89PNG"
    document = tmp_path / "cycles.json"
    assert main(["prototype", str(BUILDING), *GIVEN, "--output", str(document)]) == 0
    data = json.loads(document.read_text())
    assert data["D_M"] == {"value": 0.2, "unit": "m"}
    assert len(data["cycles"]) == len(rows) - 1
    assert data["inputs"]["source"] == "given"
    # existing outputs are refused without --overwrite
    assert main(["prototype", str(BUILDING), *GIVEN, "--output", str(table)]) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert main(["prototype", str(BUILDING), *GIVEN, "--plot", str(tmp_path / "plots")]) == 2
    assert main(["prototype", str(BUILDING), *GIVEN, "--output", str(table),
                 "--overwrite"]) == 0


def test_json_on_stdout(capsys):
    assert main(["prototype", str(BUILDING), *GIVEN, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["lambda_test_max"]["value"] >= 1.0 >= data["lambda_test_min"]["value"]


@pytest.mark.parametrize(("flags", "named"), [
    (["--model", "constant"], "--site"),
    (["--displacements", "0.2,0.25"], "--period"),
    (["--displacements", "0.3,0.2", "--period", "3"], "--displacements"),
    (["--displacements", "0.2,0.9", "--period", "3"], "displacement capacity"),
    (["--model", "constant", "--site", "1.5,0.6", "--lambda", "1.8,0.6"], "capacity"),
    (["--site", "1.5,0.6", "--lambda", "0.5,0.6"], "--lambda"),
    (["--site", "1.5,0.6", "--lambda-test", "0.9,0.8"], "--lambda-test"),
    (["--site", "1.5,0.6", "--output", "x.txt"], "--output"),
    (["--site", "1.5"], "--site"),
])
def test_bad_flags_exit_2_naming_the_flag(capsys, flags, named):
    assert main(["prototype", str(BUILDING), *flags]) == 2
    assert named in capsys.readouterr().err


def test_the_building_files_design_table_gives_the_elf(tmp_path, capsys):
    from dcfpb.common.errors import InputWarning

    building = tmp_path / "with_design.toml"
    building.write_text(BUILDING.read_text() + "\n[design]\nae_max = 1.2\nae_min = 0.9\n"
                        "test_max = 1.2\ntest_min = 0.85\nS_MS = 1.5\nS_M1 = 0.6\n")
    with pytest.warns(InputWarning):  # the parts assemble to within 1.8 / 0.6
        assert main(["prototype", str(building), "--model", "constant"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("D_M, D_TM, T_M from ELF, lower bound (lambda 0.")
