"""Bad output paths and a locked suite folder: refused before any work (issue 12, point 5).

Every command checks its output paths first (:mod:`dcfpb.cli.outputs`): a file where a
folder is asked and the reverse, a path under a file, a folder nothing can be written in
(/proc and /sys refuse even root), a name longer than the file system allows, a figure in a
format matplotlib does not write, an empty path. Each case runs through the CLI entry point
and must exit with status 2 in well under a second (no analysis started), naming the flag
and the path. A suite folder locked by a running suite is refused the same way, naming the
folder and the holder; bad values of the new suite flags too. The positive control: a path
whose folders do not exist yet is accepted, and the folders are made.
"""

from __future__ import annotations

import json
import os
import socket
import time
from datetime import UTC, datetime
from pathlib import Path

import pytest

from dcfpb.cli import build_parser, main

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
EXIT_BAD_INPUT = 2
LONG = "n" * 300  # longer than any file system's 255 bytes


@pytest.fixture()
def places(tmp_path):
    """A file and a folder that exist, in a fresh folder."""
    (tmp_path / "a_file.txt").write_text("not a folder\n")
    (tmp_path / "a_folder").mkdir()
    return tmp_path


def _commands(p: Path) -> list[tuple[str, list[str], str, str]]:
    """(case, argv, flag, path named) for every command and kind of bad path."""
    run = ["run", str(EXAMPLE), "--record", str(RECORD)]
    protocol = ["protocol", "--cycles", "1"]
    suite = ["suite", str(EXAMPLE), "--records", str(RECORD.parent), "--models", "constant",
             "--duration", "4", "--no-progress"]
    diagnose = ["diagnose", "--model", "constant", str(p / "test.csv")]
    opensees = ["compare-opensees", str(EXAMPLE), "--record", str(RECORD)]
    spectrum = ["spectrum", str(RECORD)]
    return [
        ("run --output is a folder", [*run, "--output", str(p / "a_folder")], "--output",
         str(p / "a_folder")),
        ("run --output under a file", [*run, "--output", str(p / "a_file.txt" / "r.nc")],
         "--output", str(p / "a_file.txt")),
        ("run --output in /proc", [*run, "--output", "/proc/dcfpb-test/r.nc"], "--output",
         "/proc/dcfpb-test/r.nc"),
        ("run --output name too long", [*run, "--output", str(p / f"{LONG}.nc")], "--output",
         "longer than the file system allows"),
        ("run --output empty", [*run, "--output", ""], "--output", "empty path"),
        ("run --plot is a file", [*run, "--plot", str(p / "a_file.txt")], "--plot",
         str(p / "a_file.txt")),
        ("demo --plot is a file", ["demo", "--plot", str(p / "a_file.txt")], "--plot",
         str(p / "a_file.txt")),
        ("demo --plot in /sys", ["demo", "--plot", "/sys/dcfpb-plots"], "--plot",
         "/sys/dcfpb-plots"),
        ("diagnose --report under a file",
         [*diagnose, "--report", str(p / "a_file.txt" / "report")], "--report",
         str(p / "a_file.txt")),
        ("compare-opensees --plot is a file", [*opensees, "--plot", str(p / "a_file.txt")],
         "--plot", str(p / "a_file.txt")),
        ("protocol --output is a folder", [*protocol, "--output", str(p / "a_folder")],
         "--output", str(p / "a_folder")),
        ("protocol --plot not a figure format", [*protocol, "--plot", str(p / "loop.xyz")],
         "--plot", "cannot be written as .xyz"),
        ("spectrum --plot under a file",
         [*spectrum, "--plot", str(p / "a_file.txt" / "sa.png")], "--plot",
         str(p / "a_file.txt")),
        ("spectrum --plot name too long", [*spectrum, "--plot", str(p / f"{LONG}.png")],
         "--plot", "longer than the file system allows"),
        ("suite --out is a file", [*suite, "--out", str(p / "a_file.txt")], "--out",
         str(p / "a_file.txt")),
        ("suite --out in /proc", [*suite, "--out", "/proc/dcfpb-suite"], "--out",
         "/proc/dcfpb-suite"),
    ]


CASES = [case[0] for case in _commands(Path("/x"))]


@pytest.mark.parametrize("case", CASES)
def test_bad_output_path_is_refused_at_once(case, places, capsys):
    _, argv, flag, named = next(c for c in _commands(places) if c[0] == case)
    build_parser()  # the commands' modules imported: what is timed is the command's own work
    start = time.perf_counter()
    assert main(argv) == EXIT_BAD_INPUT
    elapsed = time.perf_counter() - start
    err = capsys.readouterr().err
    assert f"error: {flag} " in err, err
    assert named in err, err
    assert elapsed < 1.0, f"{case}: {elapsed:.2f} s"
    assert sorted(p.name for p in places.iterdir()) == ["a_file.txt", "a_folder"]


def _lock(folder: Path, pid: int, host: str | None = None) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / ".suite.lock"
    path.write_text(json.dumps({
        "pid": pid, "host": host or socket.gethostname(), "process_started": None,
        "started": datetime(2031, 5, 4, 3, 2, 1, tzinfo=UTC).isoformat(),
        "command": "dcfpb suite ...", "token": "theirs"}))
    return path


@pytest.mark.parametrize("host", [None, "another-machine"], ids=["this-host", "other-host"])
def test_a_locked_suite_folder_is_refused_naming_the_holder(host, tmp_path, capsys):
    out = tmp_path / "out"
    lock = _lock(out, os.getpid(), host)  # a live holder (this process), or one elsewhere
    before = lock.read_bytes()
    start = time.perf_counter()
    assert main(["suite", str(EXAMPLE), "--records", str(RECORD.parent), "--models",
                 "constant", "--duration", "4", "--no-progress", "--out", str(out)]) == 2
    assert time.perf_counter() - start < 1.0
    err = capsys.readouterr().err
    assert str(out) in err and f"pid {os.getpid()}" in err
    assert (host or socket.gethostname()) in err and "2031-05-04T03:02:01" in err
    assert "--wait-lock" in err
    assert lock.read_bytes() == before and sorted(p.name for p in out.iterdir()) == [
        ".suite.lock"]  # nothing touched


@pytest.mark.parametrize(("flag", "value", "message"), [
    ("--run-timeout", "0", "'--run-timeout'"),
    ("--run-timeout", "-5", "'--run-timeout'"),
    ("--wait-lock", "-1", "'--wait-lock'"),
])
def test_bad_suite_flags_are_refused(flag, value, message, tmp_path, capsys):
    assert main(["suite", str(EXAMPLE), "--records", str(RECORD.parent), "--models", "constant",
                 "--out", str(tmp_path / "out"), flag, value]) == EXIT_BAD_INPUT
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_missing_folders_of_an_output_file_are_made(tmp_path, capsys):
    """The positive control: folders that do not exist yet are fine (and made for a file,
    whose writer would not make them)."""
    plot = tmp_path / "new" / "deeper" / "loop.png"
    csv = tmp_path / "other" / "history.csv"
    assert main(["protocol", "--cycles", "1", "--model", "constant", "--dt", "0.01",
                 "--output", str(csv), "--plot", str(plot)]) == 0
    assert plot.stat().st_size > 0 and csv.stat().st_size > 0
