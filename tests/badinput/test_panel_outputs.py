"""The outputs' share of the bad-input panel (issue 22, point 1): one CLI call (or one API call)
per case, each asserting the exit status (2 bad input, 1 run failure) or the exception class,
that the message names the flag and the file concerned, and that no input file and no earlier
output in ``tmp_path`` changed (every file hashed before and after). Inputs are copies in
``tmp_path``; nothing under ../shared is used.
"""

from __future__ import annotations

import errno
import hashlib
import os
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest

from dcfpb.cli import main

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
PLAN_EXAMPLE = REPO / "examples" / "five_storey_plan.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
TEST_CSV = "time,displacement,force\n0,0,0\n0.01,0.001,10\n"
PROTOCOL = ["protocol", "--cycles", "1", "--model", "constant", "--dt", "0.01"]


class Files:
    """The inputs of a case, copied into ``tmp_path``."""

    def __init__(self, root: Path) -> None:
        self.root = root
        self.building = self._copy(EXAMPLE, "building.toml")
        self.plan = self._copy(PLAN_EXAMPLE, "plan.toml")
        self.record = self._copy(RECORD, "record.at2")
        self.record_y = self._copy(RECORD, "record_y.at2")
        self.record_z = self._copy(RECORD, "record_z.at2")

    def _copy(self, source: Path, name: str) -> Path:
        target = self.root / name
        shutil.copy(source, target)
        return target

    def folder(self, name: str, **files: str | Path) -> Path:
        """A folder holding ``files`` (name: text, or a file to copy)."""
        folder = self.root / name
        folder.mkdir(exist_ok=True)
        for file, content in files.items():
            if isinstance(content, Path):
                shutil.copy(content, folder / file)
            else:
                (folder / file).write_text(content)
        return folder

    def old(self, name: str) -> Path:
        """An earlier output."""
        path = self.root / name
        path.write_text("an earlier output\n")
        return path

    def run(self, *extra: object) -> list[str]:
        return ["run", str(self.building), "--record", str(self.record), *map(str, extra)]


def _link(f: Files, kind: str) -> Path:
    link = f.root / f"{kind}.nc"
    (os.link if kind == "hardlink" else os.symlink)(f.record, link)
    return link


def _suite(f: Files, *extra: object) -> list[str]:
    return ["suite", str(f.building), "--models", "constant", "--no-progress",
            *map(str, extra)]


def _diagnose(*files: object) -> list[str]:
    return ["diagnose", *map(str, files), "--model", "constant", "--effective-radius", "4.5",
            "--slider-diameter", "0.3"]


def _failing_csv(self, path) -> None:
    with open(path, "w") as handle:
        handle.write("time,displacement\n0,")
    raise OSError(errno.ENOSPC, "No space left on device")


Case = tuple[Callable[[Files], list[str]], int, tuple[str, ...]]
CASES: dict[str, Case] = {
    # an output that is one of the command's inputs (with --overwrite too)
    "outputs-overwrite-input-record": (
        lambda f: f.run("--output", f.record), 2, ("--output", "record.at2", "the record")),
    "outputs-overwrite-input-record-with-flag": (
        lambda f: f.run("--output", f.record, "--overwrite"), 2,
        ("--output", "record.at2", "destroy")),
    "outputs-overwrite-input-building": (
        lambda f: f.run("--output", f.building), 2,
        ("--output", "building.toml", "the building file")),
    "outputs-overwrite-input-record-y": (
        lambda f: ["run", str(f.plan), "--record", str(f.record), "--record-y",
                   str(f.record_y), "--output", str(f.record_y)], 2,
        ("--output", "record_y.at2", "--record-y")),
    "outputs-overwrite-input-record-z": (
        lambda f: ["run", str(f.plan), "--record", str(f.record), "--record-y",
                   str(f.record_y), "--record-z", str(f.record_z), "--output",
                   str(f.record_z)], 2, ("--output", "record_z.at2", "--record-z")),
    "outputs-overwrite-input-hardlink": (
        lambda f: f.run("--output", _link(f, "hardlink"), "--overwrite"), 2,
        ("--output", "hardlink.nc", "record.at2")),
    "outputs-overwrite-input-symlink": (
        lambda f: f.run("--output", _link(f, "symlink"), "--overwrite"), 2,
        ("--output", "symlink.nc", "record.at2")),
    "outputs-overwrite-input-run-plot-folder": (
        lambda f: ["run", str(f.building), "--record",
                   str(f.folder("plots", **{"temperature.png": RECORD}) / "temperature.png"),
                   "--plot", str(f.root / "plots"), "--overwrite"], 2,
        ("--plot", "temperature.png", "the record")),
    "outputs-overwrite-input-opensees-plot-folder": (
        lambda f: ["compare-opensees",
                   str(f.folder("cmp", **{"isolator_hysteresis.png": EXAMPLE})
                       / "isolator_hysteresis.png"), "--record", str(f.record), "--plot",
                   str(f.root / "cmp")], 2,
        ("--plot", "isolator_hysteresis.png", "the building file")),
    "outputs-overwrite-input-spectrum-plot": (
        lambda f: ["spectrum", str(f.record), "--plot", str(f.record), "--overwrite"], 2,
        ("--plot", "record.at2", "the record")),
    "outputs-overwrite-input-suite-records-manifest": (
        lambda f: _suite(f, "--records", f.folder("out", **{"peaks.csv": "record.at2\n"})
                         / "peaks.csv", "--out", f.root / "out", "--overwrite"), 2,
        ("--out", "peaks.csv", "--records")),
    "outputs-overwrite-input-suite-pairs-manifest": (
        lambda f: ["suite", str(f.plan), "--models", "constant", "--pairs",
                   str(f.folder("out", **{"summary.csv": "name,x,y\n"}) / "summary.csv"),
                   "--out", str(f.root / "out"), "--overwrite"], 2,
        ("--out", "summary.csv", "--pairs")),
    "outputs-overwrite-input-suite-target": (
        lambda f: _suite(f, "--records", f.record.parent, "--target",
                         f.folder("out", **{"failures.json": "0.1,1\n1,0.5\n"})
                         / "failures.json", "--out", f.root / "out"), 2,
        ("--out", "failures.json", "--target")),
    "outputs-overwrite-input-suite-building": (
        lambda f: ["suite", str(f.folder("out", **{"suite.log": EXAMPLE}) / "suite.log"),
                   "--records", str(f.record.parent), "--out", str(f.root / "out")], 2,
        ("--out", "suite.log", "the building file")),
    "outputs-overwrite-input-diagnose-test-file": (
        lambda f: [*_diagnose(f.folder("report", **{"summary.md": TEST_CSV}) / "summary.md"),
                   "--report", str(f.root / "report"), "--overwrite"], 2,
        ("--report", "summary.md", "the test file")),
    "outputs-overwrite-input-diagnose-manifest": (
        lambda f: ["diagnose", "--model", "constant", "--manifest",
                   str(f.folder("report", **{"diagnosis.json": "file\n"}) / "diagnosis.json"),
                   "--report", str(f.root / "report"), "--overwrite"], 2,
        ("--report", "diagnosis.json", "the manifest")),
    # an earlier output, without --overwrite
    "outputs-exists-run-output": (
        lambda f: f.run("--output", f.old("run.nc")), 2, ("--output", "run.nc", "--overwrite")),
    "outputs-exists-protocol-output": (
        lambda f: [*PROTOCOL, "--output", str(f.old("history.csv"))], 2,
        ("--output", "history.csv", "--overwrite")),
    "outputs-exists-protocol-plot": (
        lambda f: [*PROTOCOL, "--plot", str(f.old("loop.png"))], 2,
        ("--plot", "loop.png", "--overwrite")),
    "outputs-exists-spectrum-plot": (
        lambda f: ["spectrum", str(f.record), "--plot", str(f.old("sa.pdf"))], 2,
        ("--plot", "sa.pdf", "--overwrite")),
    "outputs-exists-run-plot-folder": (
        lambda f: f.run("--plot", f.folder("plots", **{"floor_spectra.png": "old"})), 2,
        ("--plot", "floor_spectra.png", "--overwrite")),
    "outputs-exists-demo-plot-folder": (
        lambda f: ["demo", "--plot", str(f.folder("demo", **{"temperature.png": "old"}))], 2,
        ("--plot", "temperature.png", "--overwrite")),
    "outputs-exists-demo-plan-plot-folder": (
        lambda f: ["demo", "--plan", "--plot",
                   str(f.folder("demo", **{"bearing_orbits.png": "old"}))], 2,
        ("--plot", "bearing_orbits.png", "--overwrite")),
    "outputs-exists-opensees-plot-folder": (
        lambda f: ["compare-opensees", str(f.building), "--record", str(f.record), "--plot",
                   str(f.folder("cmp", **{"roof_acceleration.png": "old"}))], 2,
        ("--plot", "roof_acceleration.png", "--overwrite")),
    "outputs-exists-diagnose-report-folder": (
        lambda f: [*_diagnose(f.folder("tests", **{"a.csv": TEST_CSV}) / "a.csv"), "--report",
                   str(f.folder("report", **{"summary.md": "old"}))], 2,
        ("--report", "summary.md", "--overwrite")),
    "outputs-exists-suite-out-not-a-suite": (
        lambda f: _suite(f, "--records", f.record.parent, "--out",
                         f.folder("out", **{"peaks.csv": "old"})), 2,
        ("--out", "peaks.csv", "--overwrite", "resumed")),
    # the format follows the suffix
    "outputs-format-run-csv": (
        lambda f: f.run("--output", f.root / "run.csv"), 2, ("--output", "run.csv", ".nc")),
    "outputs-format-run-no-suffix": (
        lambda f: f.run("--output", f.root / "run"), 2, ("--output", "no suffix", ".nc")),
    "outputs-format-run-png": (
        lambda f: f.run("--output", f.root / "run.png"), 2, ("--output", "run.png", ".nc")),
    "outputs-format-run-pair-csv": (
        lambda f: ["run", str(f.plan), "--record", str(f.record), "--record-y",
                   str(f.record_y), "--output", str(f.root / "pair.csv")], 2,
        ("--output", "pair.csv", ".nc (netCDF)")),
    "outputs-format-protocol-nc": (
        lambda f: [*PROTOCOL, "--output", str(f.root / "h.nc")], 2,
        ("--output", "h.nc", ".csv (CSV)")),
    "outputs-format-protocol-no-suffix": (
        lambda f: [*PROTOCOL, "--output", str(f.root / "history")], 2,
        ("--output", "history", ".csv")),
    "outputs-format-protocol-plot-csv": (
        lambda f: [*PROTOCOL, "--plot", str(f.root / "loop.csv")], 2,
        ("--plot", "loop.csv", "cannot be written as .csv")),
    "outputs-format-spectrum-plot-nc": (
        lambda f: ["spectrum", str(f.record), "--plot", str(f.root / "sa.nc")], 2,
        ("--plot", "sa.nc", "png")),
    # a write that fails midway: a run failure, the earlier output whole
    "outputs-write-fails-protocol-output": (
        lambda f: [*PROTOCOL, "--output", str(f.old("history.csv")), "--overwrite"], 1,
        ("--output", "history.csv", "No space left")),
}


@pytest.mark.parametrize("case", list(CASES), ids=list(CASES))
def test_panel_outputs(case, tmp_path, capsys, monkeypatch):
    if case == "outputs-write-fails-protocol-output":
        from isolator.testrig import BearingTestResult

        monkeypatch.setattr(BearingTestResult, "to_csv", _failing_csv)
    argv_of, status, words = CASES[case]
    argv = argv_of(Files(tmp_path))
    before = _hashes(tmp_path)
    assert main(argv) == status
    err = capsys.readouterr().err
    assert err.startswith(f"dcfpb {argv[0]}: "), err
    for word in words:
        assert word in err, f"{word!r} not in {err!r}"
    assert _hashes(tmp_path) == before  # no input, no earlier output changed; nothing new


def _hashes(root: Path) -> dict[str, str]:
    """Every file and link under ``root`` and the hash of its bytes (or where it points)."""
    found = {}
    for path in sorted(root.rglob("*")):
        if path.is_symlink():
            found[str(path.relative_to(root))] = "-> " + os.readlink(path)
        elif path.is_file():
            found[str(path.relative_to(root))] = hashlib.sha256(path.read_bytes()).hexdigest()
        else:
            found[str(path.relative_to(root))] = "folder"
    return found


def test_panel_api_suite_folder_over_an_input(tmp_path):
    """The API of the suite folder check: an input among the suite's files is an InputError
    naming the flag, the file and the input, with ``overwrite`` too."""
    from dcfpb.cli.outputs import check_suite_folder
    from dcfpb.common.errors import InputError

    out = tmp_path / "out"
    (out / "runs").mkdir(parents=True)
    (out / "summary.csv").write_text("period,sa\n")
    before = _hashes(tmp_path)
    with pytest.raises(InputError, match=r"--out .*summary\.csv.*the target spectrum"):
        check_suite_folder(out, "--out", overwrite=True,
                           inputs={"the target spectrum": out / "summary.csv"})
    assert _hashes(tmp_path) == before


def test_panel_api_netcdf_write_fails(tmp_path, monkeypatch):
    """The API writer of a result: a failing write raises its OSError, the earlier file
    whole."""
    import numpy as np
    import xarray as xr

    from structures.results import write_netcdf

    target = tmp_path / "result.nc"
    target.write_text("an earlier output\n")
    before = _hashes(tmp_path)
    monkeypatch.setattr(xr.Dataset, "to_netcdf", _failing_csv)
    with pytest.raises(OSError, match="No space left"):
        write_netcdf(xr.Dataset({"a": ("t", np.zeros(2))}), target)
    assert _hashes(tmp_path) == before
