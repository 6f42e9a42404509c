"""Bad test files for ``dcfpb diagnose``: each error names the file, the column and the row."""

from __future__ import annotations

import gzip
import json
import math

import numpy as np
import pytest

import dcfpb.cli
from isolator.diagnosis import (
    BaselineSpec,
    BearingRecord,
    Campaign,
    DataError,
    load_campaign,
    read_record,
)

N = 4.24e6


def _rows(n: int = 60) -> dict[str, np.ndarray]:
    t = np.linspace(0.0, 2.0, n)
    u = 0.1 * np.sin(2.0 * np.pi * t)
    return {"time": t, "displacement": u, "force": 0.04 * N * np.sign(np.cos(2 * np.pi * t))}


def _write(path, columns: dict[str, np.ndarray], *, header: str | None = None) -> None:
    lines = [header or ",".join(columns)]
    lines += [",".join(f"{v:.10g}" for v in row) for row in zip(*columns.values(), strict=True)]
    path.write_text("\n".join(lines) + "\n")


@pytest.fixture
def good(tmp_path):
    path = tmp_path / "test_01.csv"
    _write(path, _rows())
    return path


def test_a_good_file_reads_and_derives_the_velocity(good):
    record = read_record(good, axial_load=N)
    assert record.name == "test_01" and len(record) == 60
    assert not record.velocity_measured
    expected = 0.2 * np.pi * np.cos(2.0 * np.pi * record.time)
    assert np.max(np.abs(record.velocity - expected)[5:-5]) < 0.03 * 0.2 * np.pi
    assert np.all(record.axial_force == N)


def test_a_gzipped_file_with_all_columns_reads(tmp_path):
    rows = _rows()
    velocity = 0.2 * np.pi * np.cos(2.0 * np.pi * rows["time"])  # d(displacement)/dt
    columns = rows | {"axial_force": np.full(60, N), "velocity": velocity,
                         "temperature": np.full(60, 20.0)}
    plain = tmp_path / "plain.csv"
    _write(plain, columns)
    path = tmp_path / "test.csv.gz"
    path.write_bytes(gzip.compress(plain.read_bytes()))
    record = read_record(path)
    assert record.name == "test" and record.velocity_measured
    assert record.temperature is not None and record.constant_axial_force


def test_missing_columns_are_named(tmp_path):
    path = tmp_path / "bad.csv"
    rows = _rows()
    del rows["force"]
    _write(path, rows)
    with pytest.raises(DataError, match=r"bad\.csv: missing column\(s\) \['force'\]"):
        read_record(path, axial_load=N)


def test_time_that_does_not_increase_names_the_row(tmp_path):
    rows = _rows()
    rows["time"][10] = rows["time"][9]
    path = tmp_path / "bad.csv"
    _write(path, rows)
    with pytest.raises(DataError, match="'time' must be strictly increasing; row 12"):
        read_record(path, axial_load=N)


def test_nan_values_are_counted_and_located(tmp_path):
    rows = _rows()
    rows["force"][[4, 7]] = np.nan
    path = tmp_path / "bad.csv"
    _write(path, rows)
    with pytest.raises(DataError, match=r"column 'force' has 2 NaN or empty value\(s\), the "
                                        "first at row 6"):
        read_record(path, axial_load=N)


def test_a_short_column_is_a_length_mismatch(tmp_path):
    rows = _rows()
    path = tmp_path / "bad.csv"
    lines = ["time,displacement,force"]
    lines += [f"{t},{u},{f}" for t, u, f in zip(rows["time"], rows["displacement"],
                                                 rows["force"], strict=True)]
    lines[-5:] = [line.rsplit(",", 1)[0] + "," for line in lines[-5:]]  # force missing
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataError, match="column 'force' has 55 values but the file has 60 rows"):
        read_record(path, axial_load=N)


def test_non_numeric_values_are_named(tmp_path):
    path = tmp_path / "bad.csv"
    _write(path, _rows())
    text = path.read_text().splitlines()
    text[3] = text[3].replace(text[3].split(",")[1], "abc")
    path.write_text("\n".join(text) + "\n")
    with pytest.raises(DataError, match="column 'displacement' has a non-numeric value 'abc' "
                                        "at row 4"):
        read_record(path, axial_load=N)


def test_the_axial_load_must_come_from_one_place(good, tmp_path):
    with pytest.raises(DataError, match="no 'axial_force' column"):
        read_record(good)
    path = tmp_path / "axial.csv"
    _write(path, _rows() | {"axial_force": np.full(60, N)})
    with pytest.raises(DataError, match="give one of the two"):
        read_record(path, axial_load=N)
    _write(path, _rows() | {"axial_force": np.r_[np.full(59, N), -1.0]})
    with pytest.raises(DataError, match=r"'axial_force' must be positive .* row 61"):
        read_record(path)


def test_millimetres_and_too_few_rows_are_refused(tmp_path):
    rows = _rows()
    rows["displacement"] *= 1000.0
    path = tmp_path / "mm.csv"
    _write(path, rows)
    with pytest.raises(DataError, match="Was it written in millimetres"):
        read_record(path, axial_load=N)
    _write(path, {k: v[:10] for k, v in _rows().items()})
    with pytest.raises(DataError, match="at least 20 data rows"):
        read_record(path, axial_load=N)
    with pytest.raises(DataError, match="no such file"):
        read_record(tmp_path / "absent.csv", axial_load=N)


def test_arrays_of_different_lengths_are_refused():
    rows = _rows()
    with pytest.raises(DataError, match="column 'force' has 59 values but 'time' has 60"):
        BearingRecord("t", rows["time"], rows["displacement"], rows["force"][:-1],
                      np.full(60, N))


def test_campaign_and_baseline_parameters_are_checked(good):
    record = read_record(good, axial_load=N)
    with pytest.raises(ValueError, match="'slider_diameter' parameter of Campaign"):
        Campaign((record,), 4.5, -0.3)
    assert math.isinf(Campaign((record,), math.inf, 0.3).effective_radius)
    with pytest.raises(ValueError, match="must be empty for the constant model"):
        BaselineSpec("constant", ("heating",))
    with pytest.raises(ValueError, match="'without' parameter of BaselineSpec"):
        BaselineSpec("precise", ("wear",))
    assert BaselineSpec("precise", ("heating",)).label == "precise --without heating"
    with pytest.raises(DataError, match="a list of one or more CSV files"):
        load_campaign([], effective_radius=4.5, slider_diameter=0.3)


def test_cli_reports_bad_files_with_exit_status_2(good, tmp_path, monkeypatch, capsys):
    rows = _rows()
    rows["time"][20] = np.nan
    bad = tmp_path / "bad.csv"
    _write(bad, rows)
    status = dcfpb.cli.main(["diagnose", str(good), str(bad), "--model", "constant",
                             "--effective-radius", "inf", "--slider-diameter", "0.3",
                             "--axial-load", str(N)])
    assert status == 2
    err = capsys.readouterr().err
    assert "dcfpb diagnose: error:" in err and "bad.csv" in err and "row 22" in err
    with pytest.raises(SystemExit):  # argparse: an unknown effect to remove
        dcfpb.cli.main(["diagnose", str(good), "--model", "precise", "--effective-radius",
                        "4.5", "--slider-diameter", "0.3", "--without", "wear"])
    assert "invalid choice: 'wear'" in capsys.readouterr().err


def test_cli_json_of_a_flat_slider_with_constant_friction(tmp_path, monkeypatch, capsys):
    """A noise-free constant-friction flat slider: the constant baseline leaves nothing."""
    from isolator.bearing import DCFPBearing
    from isolator.friction import ConstantFriction
    from isolator.protocols import sine
    from isolator.testrig import run_test

    bearing = DCFPBearing(math.inf, 0.3, N, ConstantFriction(0.05))
    files = []
    for k, amplitude in enumerate((0.05, 0.1)):
        h = sine(amplitude, 2.0, 3, 0.01)
        r = run_test(bearing, h.time, h.displacement, h.velocity)
        noise = np.random.default_rng(k).normal(0.0, 0.005 * 0.05 * N, r.force.size)
        path = tmp_path / f"t{k}.csv"
        _write(path, {"time": r.time, "displacement": r.displacement,
                      "force": r.force + noise})
        files.append(str(path))
    assert dcfpb.cli.main(["diagnose", *files, "--model", "constant", "--effective-radius",
                           "inf", "--slider-diameter", "0.3", "--axial-load", str(N),
                           "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["baseline"]["model"] == "constant"
    assert out["gap"]["metric"] == "force_nrmse" and out["gap"]["holdout"] == "alternate cycles"
    assert set(out) >= {"baseline", "gap", "where", "effects", "verdict"}
    assert out["verdict"] == ["none"]
    assert out["baseline"]["parameters"]["mu"] == pytest.approx(
        ConstantFriction(0.05).mu, rel=2e-3)
    for effect in out["effects"]:
        assert {"name", "role"} <= set(effect)
