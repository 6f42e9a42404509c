"""Outputs lose nothing (issue 22, point 1): no output over an input, no overwrite without
``--overwrite``, the format follows the suffix, and every write is atomic.

- an output file, or a file a command writes into its output folder, that is one of the
  command's inputs (the record, the building file, a manifest, a test file) is refused, with or
  without ``--overwrite``, naming the flag and the input (exit status 2, before any work);
- an output file that exists, or a file a command writes into its folder that exists, is
  refused without ``--overwrite`` and replaced with it; a suite's own folder is resumed;
- ``run --output`` writes netCDF (``.nc``) and ``protocol --output`` CSV (``.csv``): any other
  suffix is refused, naming the allowed ones;
- a write that fails midway (the writer raises after part of the file, or the disk is full)
  leaves the file there before byte-identical and no temporary file behind; on the command line
  it is a run failure (exit status 1) naming the flag.
"""

from __future__ import annotations

import errno
import os
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import build_parser, main
from dcfpb.cli.outputs import (
    PLAN_FIGURES,
    REPORT_FILES,
    RUN_FIGURES,
    SUITE_FILES,
    check_suite_folder,
)
from dcfpb.common.errors import InputError
from dcfpb.common.files import atomic_output

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
PROTOCOL = ["protocol", "--cycles", "1", "--model", "constant", "--dt", "0.01"]
OLD = b"the file there before\n"


def _tree(folder: Path) -> dict[str, bytes]:
    """Every file under ``folder`` (hidden ones too) and its bytes."""
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file()}


@pytest.fixture()
def inputs(tmp_path):
    """Copies of the building file and the record in ``tmp_path``."""
    building = tmp_path / "building.toml"
    record = tmp_path / "record.at2"
    shutil.copy(EXAMPLE, building)
    shutil.copy(RECORD, record)
    return building, record


def _refused(argv: list[str], capsys, *words: str) -> str:
    build_parser()
    start = time.perf_counter()
    assert main(argv) == 2
    assert time.perf_counter() - start < 2.0  # before any work
    err = capsys.readouterr().err
    for word in words:
        assert word in err, err
    return err


# --- an output that is an input --------------------------------------------------------------

@pytest.mark.parametrize("overwrite", [[], ["--overwrite"]], ids=["plain", "with-overwrite"])
@pytest.mark.parametrize("which", ["building", "record"])
def test_run_output_over_an_input_is_refused(which, overwrite, inputs, tmp_path, capsys):
    building, record = inputs
    target = building if which == "building" else record
    before = _tree(tmp_path)
    err = _refused(["run", str(building), "--record", str(record), "--output", str(target),
                    *overwrite], capsys, "--output", str(target), "an input", "destroy")
    assert ("the building file" if which == "building" else "the record (--record)") in err
    assert _tree(tmp_path) == before


def test_an_output_linked_to_an_input_is_refused(inputs, tmp_path, capsys):
    building, record = inputs
    link = tmp_path / "link.nc"
    os.link(record, link)  # a hard link: another name of the record
    before = _tree(tmp_path)
    _refused(["run", str(building), "--record", str(record), "--output", str(link),
              "--overwrite"], capsys, "--output", "the record (--record)", str(record))
    assert _tree(tmp_path) == before


def test_spectrum_plot_over_its_record_is_refused(inputs, tmp_path, capsys):
    _, record = inputs
    before = _tree(tmp_path)
    _refused(["spectrum", str(record), "--plot", str(record), "--overwrite"], capsys,
             "--plot", "the record", "destroy")
    assert _tree(tmp_path) == before


def test_a_folder_output_that_would_write_over_an_input_is_refused(inputs, tmp_path, capsys):
    building, _ = inputs
    plots = tmp_path / "plots"
    plots.mkdir()
    record = plots / "temperature.png"  # a record under the name of a figure run writes
    shutil.copy(RECORD, record)
    before = _tree(tmp_path)
    _refused(["run", str(building), "--record", str(record), "--plot", str(plots),
              "--overwrite"], capsys, "--plot", "temperature.png", "the record (--record)")
    assert _tree(tmp_path) == before


def test_suite_out_holding_its_manifest_is_refused(inputs, tmp_path, capsys):
    building, record = inputs
    out = tmp_path / "out"
    out.mkdir()
    manifest = out / "peaks.csv"  # the suite writes its table under this name
    manifest.write_text(f"{record}\n")
    before = _tree(tmp_path)
    _refused(["suite", str(building), "--records", str(manifest), "--out", str(out),
              "--models", "constant", "--no-progress", "--overwrite"], capsys,
             "--out", "peaks.csv", "the record manifest (--records)")
    assert _tree(tmp_path) == before


def test_diagnose_report_holding_a_test_file_is_refused(tmp_path, capsys):
    report = tmp_path / "report"
    report.mkdir()
    test = report / "summary.md"
    test.write_text("time,displacement,force\n0,0,0\n")
    before = _tree(tmp_path)
    _refused(["diagnose", str(test), "--model", "constant", "--effective-radius", "4.5",
              "--slider-diameter", "0.3", "--report", str(report), "--overwrite"], capsys,
             "--report", "summary.md", "the test file")
    assert _tree(tmp_path) == before


# --- overwriting ------------------------------------------------------------------------------

@pytest.mark.parametrize(("flag", "name", "argv"), [
    ("--output", "history.csv", PROTOCOL),
    ("--plot", "loop.png", PROTOCOL),
    ("--plot", "sa.png", ["spectrum", str(RECORD)]),
], ids=["protocol-output", "protocol-plot", "spectrum-plot"])
def test_an_existing_file_needs_overwrite(flag, name, argv, tmp_path, capsys):
    target = tmp_path / name
    target.write_bytes(OLD)
    _refused([*argv, flag, str(target)], capsys, flag, str(target), "--overwrite")
    assert target.read_bytes() == OLD
    assert main([*argv, flag, str(target), "--overwrite"]) == 0
    assert target.read_bytes() != OLD and target.stat().st_size > 100
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]  # no temporary file left


@pytest.mark.parametrize(("argv", "flag", "name"), [
    (["run", str(EXAMPLE), "--record", str(RECORD)], "--plot", "storey_drift.png"),
    (["demo"], "--plot", "isolation_effect.png"),
    (["compare-opensees", str(EXAMPLE), "--record", str(RECORD)], "--plot", "temperature.png"),
    (["diagnose", "--model", "constant", "x.csv"], "--report", "loops.png"),
], ids=["run", "demo", "compare-opensees", "diagnose"])
def test_a_folder_holding_a_file_the_command_writes_needs_overwrite(argv, flag, name, tmp_path,
                                                                    capsys):
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / name).write_bytes(OLD)
    _refused([*argv, flag, str(folder)], capsys, flag, str(folder), name, "--overwrite")
    assert _tree(tmp_path) == {f"out/{name}": OLD}


def test_run_replaces_its_outputs_with_overwrite(tmp_path, capsys):
    plots, nc = tmp_path / "plots", tmp_path / "run.nc"
    plots.mkdir()
    (plots / "storey_drift.png").write_bytes(OLD)
    nc.write_bytes(OLD)
    argv = ["run", str(EXAMPLE), "--record", str(RECORD), "--model", "constant", "--dt",
            "0.02", "--plot", str(plots), "--output", str(nc)]
    _refused(argv, capsys, "--output", str(nc), "--overwrite")
    assert main([*argv, "--overwrite"]) == 0
    assert (plots / "storey_drift.png").read_bytes() != OLD and nc.read_bytes() != OLD
    assert {p.name for p in plots.iterdir()} == set(RUN_FIGURES)  # no temporary file left


def test_a_suite_folder_resumes_and_other_folders_need_overwrite(tmp_path):
    suite = tmp_path / "suite"
    (suite / "runs").mkdir(parents=True)
    (suite / "peaks.csv").write_text("a suite's table\n")
    assert check_suite_folder(suite, "--out") == suite  # its own state: resumed
    other = tmp_path / "other"
    other.mkdir()
    (other / "summary.csv").write_text("someone else's\n")
    with pytest.raises(InputError, match=r"--out .*summary\.csv.*--overwrite.*resumed"):
        check_suite_folder(other, "--out")
    assert check_suite_folder(other, "--out", overwrite=True) == other
    with pytest.raises(InputError, match="the building file"):
        check_suite_folder(suite, "--out", overwrite=True,
                           inputs={"the building file": suite / "peaks.csv"})


# --- the format follows the suffix ----------------------------------------------------------

@pytest.mark.parametrize(("argv", "name", "allowed"), [
    (["run", str(EXAMPLE), "--record", str(RECORD)], "run.csv", ".nc (netCDF)"),
    (["run", str(EXAMPLE), "--record", str(RECORD)], "run", ".nc (netCDF)"),
    (["run", str(EXAMPLE), "--record", str(RECORD)], "run.json", ".nc (netCDF)"),
    (PROTOCOL, "history.nc", ".csv (CSV)"),
    (PROTOCOL, "history.txt", ".csv (CSV)"),
], ids=["run-csv", "run-none", "run-json", "protocol-nc", "protocol-txt"])
def test_an_output_suffix_of_another_format_is_refused(argv, name, allowed, tmp_path, capsys):
    target = tmp_path / name
    err = _refused([*argv, "--output", str(target)], capsys, "--output", str(target), allowed)
    assert (Path(name).suffix or "no suffix") in err
    assert list(tmp_path.iterdir()) == []


# --- atomic writes ----------------------------------------------------------------------------

def _partial_then_fail(path) -> None:
    with open(path, "wb") as handle:
        handle.write(b"half a file")
    raise OSError(errno.ENOSPC, "No space left on device")


def test_a_failing_protocol_write_leaves_the_old_file(tmp_path, monkeypatch, capsys):
    from isolator.testrig import BearingTestResult

    target = tmp_path / "history.csv"
    target.write_bytes(OLD)
    monkeypatch.setattr(BearingTestResult, "to_csv", lambda self, path: _partial_then_fail(path))
    assert main([*PROTOCOL, "--output", str(target), "--overwrite"]) == 1
    err = capsys.readouterr().err
    assert "run failed: --output" in err and str(target) in err and "No space" in err
    assert _tree(tmp_path) == {"history.csv": OLD}


def test_a_failing_netcdf_write_leaves_the_old_file(tmp_path, monkeypatch):
    import xarray as xr

    from structures.results import write_netcdf

    target = tmp_path / "run.nc"
    target.write_bytes(OLD)
    monkeypatch.setattr(xr.Dataset, "to_netcdf", lambda self, path: _partial_then_fail(path))
    with pytest.raises(OSError, match="No space"):
        write_netcdf(xr.Dataset({"a": ("t", np.arange(3.0))}), target)
    assert _tree(tmp_path) == {"run.nc": OLD}


def test_a_failing_figure_write_leaves_the_old_file(tmp_path, monkeypatch):
    from dcfpb.plotting.base import pyplot, save_figure

    plt = pyplot()
    fig = plt.figure()
    target = tmp_path / "figure.png"
    target.write_bytes(OLD)
    monkeypatch.setattr(fig, "savefig", lambda path, **_: _partial_then_fail(path))
    with pytest.raises(OSError, match="No space"):
        save_figure(fig, target)
    plt.close(fig)
    assert _tree(tmp_path) == {"figure.png": OLD}


def test_atomic_output_replaces_only_on_success(tmp_path):
    target = tmp_path / "table.json"
    target.write_bytes(OLD)
    target.chmod(0o640)
    with pytest.raises(KeyboardInterrupt), atomic_output(target) as temporary:
        temporary.write_text("{\"half\": ")
        raise KeyboardInterrupt  # interrupted midway
    assert _tree(tmp_path) == {"table.json": OLD}
    with atomic_output(target) as temporary:
        temporary.write_text("{}")
    assert _tree(tmp_path) == {"table.json": b"{}"}
    assert target.stat().st_mode & 0o777 == 0o640  # the mode of the file before is kept


def test_the_suites_store_writes_through_the_one_helper(tmp_path, monkeypatch):
    from structures.suites import store

    target = tmp_path / "peaks.csv"
    target.write_bytes(OLD)

    def failing_open(path, mode="r", *args, **kwargs):
        handle = open(path, mode, *args, **kwargs)  # noqa: SIM115
        handle.write(b"half")
        handle.close()
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(store, "open", failing_open, raising=False)
    with pytest.raises(OSError, match="No space"):
        store.atomic_write(target, b"a new table\n")
    assert _tree(tmp_path) == {"peaks.csv": OLD}


# --- a full disk -------------------------------------------------------------------------------

@pytest.fixture()
def small_disk(tmp_path):
    """A 256 kB tmpfs mounted in ``tmp_path`` (root and a working ``mount`` only)."""
    if os.name != "posix" or os.geteuid() != 0 or shutil.which("mount") is None:
        pytest.skip("a tmpfs needs root and mount(8) on this platform")
    disk = tmp_path / "disk"
    disk.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(disk)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {done.stderr.strip()}")
    try:
        yield disk
    finally:
        subprocess.run(["umount", str(disk)], check=False)


def test_a_full_disk_leaves_the_old_file(small_disk, capsys):
    target = small_disk / "history.csv"
    target.write_bytes(OLD)
    filler = small_disk / "filler"
    free = shutil.disk_usage(small_disk).free
    filler.write_bytes(b"x" * max(free - 16 * 1024, 0))  # 16 kB left: the history is larger
    before = _tree(small_disk)
    assert main(["protocol", "--cycles", "3", "--model", "constant", "--output", str(target),
                 "--overwrite"]) == 1
    err = capsys.readouterr().err
    assert "--output" in err and str(target) in err and "No space left" in err
    assert _tree(small_disk) == before


# --- the lists of files a command writes match its writers ------------------------------------

def test_the_declared_file_lists_match_the_writers():
    import re

    def names(*files: str) -> set[str]:
        return {m for f in files for m in re.findall(r'"([a-z_]+\.(?:png|md|json))"',
                                                     (REPO / f).read_text())}

    assert names("dcfpb/plotting/building.py", "dcfpb/plotting/plan.py") == set(PLAN_FIGURES)
    assert set(RUN_FIGURES) < set(PLAN_FIGURES)
    assert names("isolator/diagnosis/report.py") == set(REPORT_FILES)
    assert {"peaks.csv", "failures.json"} <= set(SUITE_FILES)
