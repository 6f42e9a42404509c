"""Bad command-line flags and runs past their limits: refused before any work.

``dcfpb run --dt 0`` used to fall back to the file's step (``args.dt or config.dt``),
``dcfpb protocol --period 0`` ended in a ZeroDivisionError, ``--cycles 100000`` ran without
bound and a record with DT = 100 s asked for 31 million steps and 20 GB (now refused by the
record reader as implausible; the step and memory limits are checked with a tiny --dt). Each
case runs through the CLI entry point and must exit with status 2, stderr naming the flag (or,
for a run past its limit, the steps, the duration and dt they come from and ``--max-steps``)
and what is allowed.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from dcfpb.cli import main
from isolator.limits import available_memory

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
EXIT_BAD_INPUT = 2


def _refused(argv: list[str], capsys, *expected: str) -> str:
    assert main(argv) == EXIT_BAD_INPUT
    captured = capsys.readouterr()
    assert captured.out == ""
    err = captured.err
    assert err.startswith(f"dcfpb {argv[0]}: error: ") and err.count("\n") == 1, err
    for text in expected:
        assert text in err, (text, err)
    return err


RUN = ["run", str(EXAMPLE), "--record", str(RECORD)]

RUN_CASES = {
    "dt 0": (["--dt", "0"], ("'--dt'", "(0, 1]", "Got 0.0")),
    "dt negative": (["--dt", "-0.005"], ("'--dt'", "(0, 1]", "Got -0.005")),
    "dt nan": (["--dt", "nan"], ("'--dt'", "(0, 1]", "Got nan")),
    "dt above the record's": (["--dt", "0.05"], ("'dt'", "(0, 0.02]", "Got 0.05")),
    "alpha under newmark": (["--integrator", "newmark", "--alpha", "-0.1"],
                            ("--alpha applies to --integrator hht only",)),
    "alpha out of range": (["--integrator", "hht", "--alpha", "0.5"],
                           ("'alpha'", "[-0.333333, 0]", "Got 0.5")),
    "max-steps 0": (["--max-steps", "0"], ("'--max-steps'", "[1, inf)", "Got 0")),
    "max-steps below the run": (["--max-steps", "1000"],
                                ("6,232 steps (31.16 s at dt = 0.005 s)",
                                 "past the limit of 1,000 steps",
                                 "raise the limit with --max-steps (at least 6,232)")),
    "scale 0": (["--scale", "0"], ("'--scale'", "(0, inf)", "Got 0.0")),
}


@pytest.mark.parametrize("case", RUN_CASES, ids=list(RUN_CASES))
def test_run_flag_is_refused_by_name_and_range(case, capsys):
    flags, expected = RUN_CASES[case]
    _refused([*RUN, *flags], capsys, *expected)


def _record_with_dt(tmp_path: Path, dt: str) -> Path:
    """El Centro with its header's time step (the DT statement and its mention) changed."""
    text = RECORD.read_text()
    text = text.replace("DT= .02000 SEC", f"DT= {dt} SEC").replace("spacing of 0.02 sec",
                                                                    f"spacing of {dt} sec")
    path = tmp_path / "elcentro_dt.at2"
    path.write_text(text)
    return path


def test_record_with_dt_100s_is_refused_at_once_by_its_reader(tmp_path, capsys):
    # since issue 22 the reader refuses DT = 100 s as implausible before the step count
    record = _record_with_dt(tmp_path, "100.0")
    start = time.perf_counter()
    err = _refused(["run", str(EXAMPLE), "--record", str(record)], capsys,
                   "elcentro_dt.at2, line 4", "time step of 100 s", "1e-05 to 0.1 s")
    assert time.perf_counter() - start < 5.0, err


def test_run_past_max_steps_is_refused_at_once_with_its_step_count(capsys):
    start = time.perf_counter()
    err = _refused([*RUN, "--dt", "1e-5"], capsys,
                   "3,116,000 steps (31.16 s at dt = 1e-05 s)",
                   "past the limit of 2,000,000 steps", "GB",
                   "DT in its header", "--max-steps")
    assert time.perf_counter() - start < 5.0, err


def test_record_with_dt_100s_is_refused_at_the_default_step_too(tmp_path, capsys):
    building = tmp_path / "no_dt.toml"
    building.write_text(EXAMPLE.read_text().replace("\ndt = 0.005", "\n"))
    record = _record_with_dt(tmp_path, "100.0")  # default step: 100 s in parts of 5 ms
    _refused(["run", str(building), "--record", str(record)], capsys,
             "elcentro_dt.at2, line 4", "time step of 100 s")


@pytest.mark.skipif(available_memory() is None, reason="no /proc/meminfo: no memory check")
def test_run_past_the_memory_available_is_refused_even_with_the_limit_raised(capsys):
    # 3 x 10^10 steps: no machine holds their ~21 TB, whatever --max-steps allows
    _refused([*RUN, "--dt", "1e-9", "--max-steps", str(10**13)], capsys, "more than the",
             "of memory available")


def test_compare_opensees_dt_0_is_refused(capsys):
    _refused(["compare-opensees", str(EXAMPLE), "--record", str(RECORD), "--dt", "0"], capsys,
             "'--dt'", "(0, 1]")


PROTOCOL_CASES = {
    "period 0": (["--period", "0"], ("'--period'", "(0, inf)", "Got 0.0")),
    "period negative": (["--period", "-4.26"], ("'--period'", "(0, inf)", "Got -4.26")),
    "period inf": (["--period", "inf"], ("'--period'", "(0, inf)", "Got inf")),
    "amplitude 0": (["--amplitude", "0"], ("'--amplitude'", "(0, 9.5]", "Got 0.0")),
    "amplitude negative": (["--amplitude", "-0.3"], ("'--amplitude'", "(0, 9.5]")),
    "cycles 0": (["--cycles", "0"], ("'--cycles'", "[1, inf)", "Got 0")),
    "cycles negative": (["--cycles", "-3"], ("'--cycles'", "[1, inf)", "Got -3")),
    "dt 0": (["--dt", "0"], ("'--dt'", "(0, 0.213]", "Got 0.0")),
    "dt above period/20": (["--dt", "1"], ("'--dt'", "(0, 0.213]", "Got 1.0")),
    "slider diameter 0": (["--slider-diameter", "0"], ("'--slider-diameter'", "(0, 10]")),
    "pressure negative": (["--pressure", "-1"], ("'--pressure'", "[1e+06, 2e+08]", "Pa")),
    "mu_t0 0": (["--mu-t0", "0"], ("'--mu-t0'", "(0, 1]")),
    "temperature below absolute zero": (["--initial-temperature", "-300"],
                                        ("'--initial-temperature'", "[-273.15, 1000]")),
    "max-steps 0": (["--max-steps", "0"], ("'--max-steps'", "[1, inf)")),
    "max-steps below the test": (["--max-steps", "100"],
                                 ("2,556 steps (12.78 s at dt = 0.005 s)",
                                  "past the limit of 100 steps", "--max-steps")),
}


@pytest.mark.parametrize("case", PROTOCOL_CASES, ids=list(PROTOCOL_CASES))
def test_protocol_flag_is_refused_by_name_and_range(case, capsys):
    flags, expected = PROTOCOL_CASES[case]
    _refused(["protocol", *flags], capsys, *expected)


def test_protocol_with_a_huge_cycle_count_is_refused_at_once(capsys):
    start = time.perf_counter()
    _refused(["protocol", "--cycles", "100000"], capsys,
             "The test (100000 cycles of 4.26 s) would take 85,200,000 steps",
             "(426000 s at dt = 0.005 s)", "past the limit of 2,000,000 steps",
             "Check --cycles, --period and --dt", "--max-steps (at least 85,200,000)")
    assert time.perf_counter() - start < 5.0


def test_compare_opensees_bearing_period_0_is_refused(capsys):
    _refused(["compare-opensees-bearing", "--period", "0"], capsys, "'--period'", "(0, inf)")
