"""The optional channels and the size of a test file for ``dcfpb diagnose`` (issue 22, part 3).

A velocity column is checked against d(displacement)/dt (a robust slope over the moving
samples, allowed 0.8-1.25): mm/s or cm/s read as m/s, a reversed sign or a channel that is not
the velocity of the displacement is refused naming the column, the file, the ratio found and
the likely cause; a unit stated in the header (``velocity [mm/s]``) is converted. A
temperature column that looks like kelvin (all of it within 250-400) or is stated in kelvin is
refused, and so is one outside -60-400 degC. A column named twice (letter case, spaces and a
stated unit aside) is refused naming the file and the column. A manifest value that disagrees
with the flag of the same name is refused naming both; equal values pass. A test file is
sized before it is read: past ``--max-rows`` (default 2,000,000) or past the memory
available it is refused within a second, naming the file, the rows estimated and the memory.
The positive controls: consistent channels read, stated units convert, equal values agree,
and the real friction-damper data (velocity column in m/s, ratio 0.998-1.001) still reads.
"""

from __future__ import annotations

import gzip
import math
import re
import time
import warnings

import numpy as np
import pytest

import isolator.diagnosis.data as data
from dcfpb.cli import main
from dcfpb.common.errors import InputWarning
from isolator.diagnosis import BearingRecord, DataError, load_campaign, read_record
from isolator.diagnosis.data import estimate_rows, velocity_ratio
from isolator.diagnosis.manifest import load_manifest

N = 4.24e6  # [N]
R_EFF = 4.5  # [m]
DIAMETER = 0.3  # [m]


def _columns(seed: int = 0, n_cycles: int = 2) -> dict[str, np.ndarray]:
    """A pendulum test [s, m, N, m/s] at 100 Hz with noise on every channel."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, 2.5 * n_cycles, 0.01)
    u = 0.1 * np.sin(2.0 * np.pi * t / 2.5)
    v = 0.1 * 2.0 * np.pi / 2.5 * np.cos(2.0 * np.pi * t / 2.5)
    f = N * u / R_EFF + 0.04 * N * np.tanh(v / 0.01)
    return {"time": t, "displacement": u + rng.normal(0.0, 2e-5, t.size),
            "force": f + rng.normal(0.0, 0.005 * 0.04 * N, t.size),
            "velocity": v + rng.normal(0.0, 2e-3, t.size)}


def _write(path, columns: dict[str, np.ndarray], header: str | None = None) -> str:
    np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",",
               header=header or ",".join(columns), comments="", fmt="%.10g")
    return str(path)


def _refused(args: list[str], capsys, *needles: str | re.Pattern) -> str:
    status = main(args)
    err = capsys.readouterr().err
    assert status == 2, err
    assert err.startswith("dcfpb diagnose: error: ") and err.count("\n") == 1, err
    for needle in needles:
        found = needle.search(err) if isinstance(needle, re.Pattern) else needle in err
        assert found, (needle, err)
    return err


def _args(*files: str, extra: tuple[str, ...] = ()) -> list[str]:
    return ["diagnose", *files, "--model", "constant", "--effective-radius", str(R_EFF),
            "--slider-diameter", str(DIAMETER), "--axial-load", repr(N), *extra]


# ---- velocity -------------------------------------------------------------------------

def test_a_consistent_velocity_column_reads(tmp_path):
    record = read_record(_write(tmp_path / "good.csv", _columns()), axial_load=N)
    assert record.velocity_measured
    ratio = velocity_ratio(record.time, record.displacement, record.velocity)
    assert ratio == pytest.approx(1.0, abs=0.02)


@pytest.mark.parametrize("factor, needles", [
    (1000.0, ("is 999 times d(displacement)/dt", "looks like mm/s:", "divide it by 1000",
              "'velocity [mm/s]'")),
    (100.0, ("is 99.9 times", "looks like cm/s:")),
    (-1.0, ("is -0.999 times", "sign-reversed", "Multiply it by -1")),
    (-1000.0, ("is -999 times", "looks like mm/s and reversed in sign")),
    (0.5, ("is 0.5 times", "check its units", "its sign convention")),
    (1.6, ("is 1.6 times", "check its units")),
])
def test_a_velocity_off_by_a_factor_or_sign_is_refused(tmp_path, capsys, factor, needles):
    columns = _columns()
    path = _write(tmp_path / "v.csv", columns | {"velocity": factor * columns["velocity"]})
    _refused(_args(path), capsys, "v.csv", "column 'velocity'", "allowed 0.8-1.25", *needles)


def test_a_velocity_channel_of_noise_only_is_refused(tmp_path, capsys):
    columns = _columns()
    noise = np.random.default_rng(5).normal(0.0, 0.2, columns["time"].size)
    path = _write(tmp_path / "v.csv", columns | {"velocity": noise})
    _refused(_args(path), capsys, "v.csv", "column 'velocity'",
             "that it is the velocity of this displacement")


def test_a_velocity_stated_in_mm_per_s_is_converted(tmp_path):
    columns = _columns()
    header = "time,displacement [m],force [N],velocity [mm/s]"
    path = _write(tmp_path / "mm_s.csv", columns | {"velocity": 1e3 * columns["velocity"]},
                  header)
    record = read_record(path, axial_load=N)
    assert np.allclose(record.velocity, columns["velocity"])


def test_a_velocity_stated_in_m_per_s_but_written_in_mm_per_s_is_refused(tmp_path, capsys):
    columns = _columns()
    path = _write(tmp_path / "v.csv", columns | {"velocity": 1e3 * columns["velocity"]},
                  "time,displacement,force,velocity [m/s]")
    _refused(_args(path), capsys, "v.csv", "column 'velocity' is 999 times")


def test_an_in_memory_record_checks_its_velocity():
    columns = _columns()
    with pytest.raises(DataError, match=r"test 'mem': column 'velocity' is 999 times"):
        BearingRecord("mem", columns["time"], columns["displacement"], columns["force"],
                      np.full(columns["time"].size, N), velocity=1e3 * columns["velocity"])


@pytest.mark.shared
def test_the_real_velocity_columns_pass(shared_dir):
    """Datasets 1-2 of the friction damper: velocity in m/s, within 0.2 % of du/dt."""
    folder = shared_dir / "realdata" / "friction-damper" / "compact"
    files = sorted(folder.glob("*.csv.gz"))
    if len(files) < 3:
        pytest.skip(f"the compact friction-damper files are absent from {folder}")
    for path in files:
        record = read_record(path, axial_load=1.0e5)
        assert record.velocity_measured
        ratio = velocity_ratio(record.time, record.displacement, record.velocity)
        assert ratio == pytest.approx(1.0, abs=0.01), path.name
        rows, header = estimate_rows(path)
        assert rows == pytest.approx(len(record), rel=0.1) and "velocity" in header


# ---- temperature ----------------------------------------------------------------------

def test_a_temperature_that_looks_like_kelvin_is_refused(tmp_path, capsys):
    columns = _columns()
    temperature = 293.15 + np.linspace(0.0, 15.0, columns["time"].size)
    path = _write(tmp_path / "k.csv", columns | {"temperature": temperature})
    _refused(_args(path), capsys, "k.csv", "column 'temperature'", "looks like kelvin",
             "between 293.15 and 308.15", "give it in degC", "'temperature [degC]'")


def test_a_temperature_stated_in_kelvin_is_refused(tmp_path, capsys):
    columns = _columns()
    temperature = 293.15 + np.linspace(0.0, 15.0, columns["time"].size)
    path = _write(tmp_path / "k.csv", columns | {"temperature": temperature},
                  "time,displacement,force,velocity,temperature [K]")
    _refused(_args(path), capsys, "k.csv", "column 'temperature' is stated in kelvin",
             "'temperature [K]'", "give it in degC")


def test_a_hot_test_stated_in_degc_reads(tmp_path):
    columns = _columns()
    temperature = np.linspace(260.0, 300.0, columns["time"].size)
    path = _write(tmp_path / "hot.csv", columns | {"temperature": temperature},
                  "time,displacement,force,velocity,temperature [degC]")
    assert read_record(path, axial_load=N).temperature[0] == pytest.approx(260.0)


@pytest.mark.parametrize("value, row", [(450.0, 12), (-80.0, 12)])
def test_a_temperature_out_of_range_is_refused(tmp_path, capsys, value, row):
    columns = _columns()
    temperature = np.full(columns["time"].size, 20.0)
    temperature[row - 2] = value
    path = _write(tmp_path / "t.csv", columns | {"temperature": temperature})
    _refused(_args(path), capsys, "t.csv", "column 'temperature' must be in degC within "
             "[-60, 400]", f"row {row} has {value!r}")


# ---- duplicate columns and stated units -------------------------------------------------

@pytest.mark.parametrize("header, named", [
    ("time,displacement,force,force", "'force' appears twice"),
    ("time,displacement,force, Force ", "'Force' appears twice"),
    ("time,displacement [m],force,displacement", "'displacement' appears twice"),
    ("time,displacement,force,velocity,VELOCITY [m/s]", "'VELOCITY' appears twice"),
])
def test_a_column_named_twice_is_refused(tmp_path, capsys, header, named):
    columns = _columns()
    width = header.count(",") + 1
    values = list(columns.values()) + [columns["force"]] * 4
    path = _write(tmp_path / "dup.csv", dict(zip(header.split(","), values[:width],
                                                 strict=True)), header)
    _refused(_args(path), capsys, "dup.csv", named, "Rename or remove one of them")


@pytest.mark.parametrize("header, named", [
    ("time,displacement,force [kN],velocity", "column 'force' is stated in 'kN'"),
    ("time [ms],displacement,force,velocity", "column 'time' is stated in 'ms'"),
    ("time,displacement (mm),force,velocity", "column 'displacement' is stated in 'mm'"),
    ("time,displacement,force,velocity [in/s]", "column 'velocity' is stated in 'in/s'"),
])
def test_a_unit_stated_other_than_the_one_read_is_refused(tmp_path, capsys, header, named):
    path = _write(tmp_path / "u.csv", _columns(), header)
    _refused(_args(path), capsys, "u.csv", named, "it must be in")


# ---- a manifest and the flags -----------------------------------------------------------

def _toml(tmp_path, **top) -> str:
    _write(tmp_path / "a.csv", _columns())
    lines = [f"{k} = {v!r}" for k, v in top.items()]
    (tmp_path / "m.toml").write_text("\n".join(lines) + f'\n[[test]]\nfile = "a.csv"\n'
                                     f"axial_load = {N!r}\n")
    return str(tmp_path / "m.toml")


@pytest.mark.parametrize("flag, key, given", [
    ("--effective-radius", "effective_radius", "3.0"),
    ("--slider-diameter", "slider_diameter", "0.25"),
    ("--axial-load", "axial_load", "2000000.0"),
])
def test_a_manifest_value_disagreeing_with_its_flag_is_refused(tmp_path, capsys, flag, key,
                                                               given):
    manifest = _toml(tmp_path, effective_radius=R_EFF, slider_diameter=DIAMETER)
    args = ["diagnose", "--manifest", manifest, "--model", "constant", flag, given]
    _refused(args, capsys, "m.toml", f"'{key}' is", f"but {flag} gives {float(given)!r}",
             "give one value, or the same in both")


def test_a_csv_manifest_axial_load_disagreeing_with_the_flag_is_refused(tmp_path, capsys):
    _write(tmp_path / "a.csv", _columns())
    (tmp_path / "m.csv").write_text(f"file,axial_load\na.csv,{N}\n")
    args = ["diagnose", "--manifest", str(tmp_path / "m.csv"), "--model", "constant",
            "--effective-radius", str(R_EFF), "--slider-diameter", str(DIAMETER),
            "--axial-load", "1e6"]
    _refused(args, capsys, "m.csv: test 1 (a.csv): 'axial_load' is 4240000.0 N",
             "but --axial-load gives 1000000.0 N")


def test_equal_values_in_the_manifest_and_the_flags_agree(tmp_path):
    manifest = _toml(tmp_path, effective_radius=R_EFF, slider_diameter=DIAMETER)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        campaign = load_manifest(manifest, effective_radius=R_EFF, slider_diameter=DIAMETER,
                                 axial_load=N, must_agree=True)
    assert campaign.effective_radius == R_EFF and campaign.tests[0].axial_force[0] == N


def test_an_axial_load_flag_no_test_uses_is_warned_about(tmp_path):
    columns = _columns() | {"axial_force": np.full(500, N)}
    _write(tmp_path / "a.csv", columns)
    (tmp_path / "m.csv").write_text("file\na.csv\n")
    with pytest.warns(InputWarning, match=r"--axial-load 1000000.0 N has no effect: every "
                      r"test of .*m\.csv has an axial_force column"):
        load_manifest(tmp_path / "m.csv", effective_radius=R_EFF, slider_diameter=DIAMETER,
                      axial_load=1.0e6, must_agree=True,
                      argument_names={"axial_load": "--axial-load"})


# ---- size -------------------------------------------------------------------------------

def _sparse(path, size: int = 10**9) -> str:
    """A CSV of ``size`` bytes that holds a header and ten rows, the rest a hole."""
    lines = ["time,displacement,force"] + [f"{0.01 * i:.2f},{1e-3 * i:.4f},{1000.0 * i:.1f}"
                                           for i in range(10)]
    path.write_text("\n".join(lines) + "\n")
    with path.open("r+b") as handle:
        handle.truncate(size)
    return str(path)


def test_a_file_of_ten_million_rows_is_refused_at_once(tmp_path, capsys):
    path = _sparse(tmp_path / "huge.csv")
    start = time.perf_counter()
    err = _refused(_args(path), capsys, "huge.csv", "1 GB", "past the limit of 2,000,000 rows",
                   "--max-rows", "of memory")
    assert time.perf_counter() - start < 5.0
    rows = int(re.search(r"about ([\d,]+) data rows", err)[1].replace(",", ""))
    assert 3e7 < rows < 1e8  # 1 GB over rows of 12-20 bytes


def test_a_large_gzipped_file_is_refused(tmp_path, capsys):
    body = b"time,displacement,force\n" + b"0.0100000,0.0010000,1000.0000\n" * 3_000_000
    path = tmp_path / "big.csv.gz"
    path.write_bytes(gzip.compress(body, compresslevel=1))
    err = _refused(_args(str(path)), capsys, "big.csv.gz", "past the limit of 2,000,000 rows")
    rows = int(re.search(r"about ([\d,]+) data rows", err)[1].replace(",", ""))
    assert rows == pytest.approx(3_000_000, rel=0.05)


def test_max_rows_is_a_limit_the_user_sets(tmp_path, capsys):
    path = _write(tmp_path / "good.csv", _columns())
    _refused(_args(path, extra=("--max-rows", "100")), capsys, "good.csv",
             "about 500 data rows", "past the limit of 100 rows", "at least 500")
    _refused(_args(path, extra=("--max-rows", "0")), capsys, "--max-rows", "Got 0")


def test_a_file_past_the_memory_available_is_refused(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(data, "available_memory", lambda: 10_000)
    path = _write(tmp_path / "good.csv", _columns())
    _refused(_args(path), capsys, "good.csv", "about 500 data rows",
             "more than the 10 kB available")


def test_every_file_of_a_campaign_is_sized_before_the_first_is_read(tmp_path, monkeypatch):
    good = _write(tmp_path / "good.csv", _columns())
    huge = _sparse(tmp_path / "huge.csv")
    read = []
    monkeypatch.setattr(data, "_numeric_column",
                        lambda *a: read.append(a[1]) or np.zeros(a[0].size))
    with pytest.raises(DataError, match=r"huge\.csv: about .* data rows"):
        load_campaign([good, huge], effective_radius=R_EFF, slider_diameter=DIAMETER,
                      axial_load=N)
    assert read == []


def test_a_manifest_names_the_test_too_large(tmp_path, capsys):
    _sparse(tmp_path / "huge.csv")
    (tmp_path / "m.csv").write_text(f"file,axial_load\nhuge.csv,{N}\n")
    args = ["diagnose", "--manifest", str(tmp_path / "m.csv"), "--model", "constant",
            "--effective-radius", str(R_EFF), "--slider-diameter", str(DIAMETER)]
    _refused(args, capsys, "m.csv: test 1 (huge.csv)", "past the limit of 2,000,000 rows")


def test_a_small_file_is_counted_exactly(tmp_path):
    path = _write(tmp_path / "good.csv", _columns())
    assert estimate_rows(path) == (500, ["time", "displacement", "force", "velocity"])
    assert math.isfinite(read_record(path, axial_load=N).time[-1])


# ---- the values a message quotes are plain numbers --------------------------------------

@pytest.mark.parametrize("column, value, needle", [
    ("time", 0.005, "row 6 has 0.005 s after 0.03 s"),
    ("axial_force", -5.0, "'axial_force' must be positive (compression) [N]; row 6 has -5.0"),
])
def test_a_message_quotes_the_value_as_written(tmp_path, capsys, column, value, needle):
    """Not numpy's repr (``np.float64(-5.0)``)."""
    columns = _columns() | {"axial_force": np.full(500, N)}
    columns[column] = columns[column].copy()
    columns[column][4] = value
    path = _write(tmp_path / "q.csv", columns)
    args = ["diagnose", path, "--model", "constant", "--effective-radius", str(R_EFF),
            "--slider-diameter", str(DIAMETER)]
    err = _refused(args, capsys, "q.csv", needle)
    assert "np.float64" not in err


def test_a_manifest_finds_an_axial_force_column_with_its_unit_stated(tmp_path):
    """``axial_force [N]`` is the axial_force column: the manifest needs no load for it."""
    columns = _columns() | {"axial_force": np.full(500, N)}
    _write(tmp_path / "a.csv", columns, "time [s],displacement [m],force [N],velocity [m/s],"
           "axial_force [N]")
    (tmp_path / "m.csv").write_text("file\na.csv\n")
    campaign = load_manifest(tmp_path / "m.csv", effective_radius=R_EFF,
                             slider_diameter=DIAMETER)
    assert campaign.tests[0].axial_force[0] == N


def test_rows_wider_than_the_header_are_refused(tmp_path, capsys):
    """pandas would take the first field for an index and read every column shifted."""
    columns = _columns()
    path = _write(tmp_path / "wide.csv", columns, "time,displacement,force")
    _refused(_args(path), capsys, "wide.csv", "one field more than the header line's 3 "
             "column(s) (time, displacement, force)", "Name every column")
