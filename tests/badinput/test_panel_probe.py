"""The bad-input panel, part 6 (issue 22): the cases the independent probe of the merged issue
found still wrong (each fixed with it), and a few it checked beside them.

Each case is one call of the command line (``dcfpb.cli.main`` in-process) on copies in
``tmp_path`` beside an earlier output, and asserts (a) the exit status, (b) that the message
names the flag, key or file concerned (and no internal function or class where a flag was
given), and (c) that no input and no earlier output changed (every file hashed before and
after). Ids start with the kind of the case: ``outputs``, ``units`` (records, units, steps,
plausibility), ``channels`` (diagnose), ``resources``, ``contract`` (exit statuses and the
flag, key or file named), ``plans``.
"""

from __future__ import annotations

import gzip
import hashlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
PLAN = REPO / "examples" / "five_storey_plan.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"

N = 4.24e6  # [N] axial load of the bearing tests
DIAGNOSE = ("--model", "constant", "--effective-radius", "4.5", "--slider-diameter", "0.3")


def _digest(path: Path) -> str:
    """The file's hash; for a sparse file of gigabytes its size and modification time (the
    hole would take a minute to hash)."""
    status = path.stat()
    if status.st_size > 2**26:
        return f"{status.st_size}:{status.st_mtime_ns}"
    return hashlib.sha256(path.read_bytes()).hexdigest()


@dataclass
class Inputs:
    """The copies a case works on, in its own folder, and an earlier output beside them."""

    folder: Path
    building: Path
    plan: Path
    record: Path
    records: Path
    test: Path
    earlier: Path

    def snapshot(self) -> dict[str, str]:
        return {str(p.relative_to(self.folder)): _digest(p)
                for p in sorted(self.folder.rglob("*")) if p.is_file()}

    def edited(self, source: Path, name: str, old: str, new: str) -> str:
        """A copy of ``source`` with the line starting with ``old`` replaced by ``new``."""
        lines = source.read_text().splitlines()
        index = next(k for k, line in enumerate(lines) if line.startswith(old))
        lines[index] = new
        path = self.folder / name
        path.write_text("\n".join(lines) + "\n")
        return str(path)

    def text(self, name: str, content: str) -> str:
        (self.folder / name).write_text(content)
        return str(self.folder / name)


def _test_file(path: Path) -> None:
    """A pendulum bearing test at 100 Hz [s, m, N, m/s]."""
    t = np.arange(0.0, 5.0, 0.01)
    u = 0.1 * np.sin(2.0 * np.pi * t / 2.5)
    v = 0.1 * 2.0 * np.pi / 2.5 * np.cos(2.0 * np.pi * t / 2.5)
    f = N * u / 4.5 + 0.04 * N * np.tanh(v / 0.01)
    np.savetxt(path, np.column_stack([t, u, f, v]), delimiter=",",
               header="time,displacement,force,velocity", comments="", fmt="%.10g")


@pytest.fixture
def inputs(tmp_path, tmp_path_factory, monkeypatch) -> Inputs:
    monkeypatch.setenv("DCFPB_LOG_DIR", str(tmp_path_factory.mktemp("logs")))
    records = tmp_path / "records"
    records.mkdir()
    record = records / RECORD.name
    record.write_bytes(RECORD.read_bytes())
    building = tmp_path / EXAMPLE.name
    building.write_bytes(EXAMPLE.read_bytes())
    plan = tmp_path / PLAN.name
    plan.write_bytes(PLAN.read_bytes())
    test = tmp_path / "test1.csv"
    _test_file(test)
    out = tmp_path / "out"
    out.mkdir()
    earlier = out / "peaks.csv"
    earlier.write_text("run_id,peak\nearlier,1.0\n")
    return Inputs(tmp_path, building, plan, record, records, test, earlier)


def _one_column(i: Inputs) -> str:
    values = "\n".join(line for row in RECORD.read_text().splitlines()[4:]
                       for line in row.split())
    return i.text("one.txt", values + "\n")


def _sparse_record(i: Inputs) -> str:
    """A record file of 8 GB: El Centro's text, the rest a hole (no disk used)."""
    path = i.folder / "huge.at2"
    path.write_bytes(RECORD.read_bytes())
    with path.open("r+b") as handle:
        handle.truncate(8 * 10**9)
    return str(path)


def _binary(i: Inputs) -> str:
    path = i.folder / "list.csv"
    path.write_bytes(b"\xff\xfe\x00binary\x00")
    return str(path)


def _gzip_record(i: Inputs) -> str:
    path = i.folder / "elcentro.at2.gz"
    path.write_bytes(gzip.compress(RECORD.read_bytes()))
    return str(path)


def _target(i: Inputs, last_period: float = 5.0) -> str:
    return i.text("target.csv", f"period,sa\n0.5,0.9\n1.0,0.8\n2.0,0.5\n{last_period},0.2\n")


def _suite(i: Inputs, *extra: str) -> list[str]:
    return ["suite", str(i.building), "--records", str(i.records), "--models", "constant",
            "--out", str(i.earlier.parent), "--overwrite", "--no-plots", "--no-progress",
            *extra]


def _run(i: Inputs, *extra: str) -> list[str]:
    return ["run", str(i.building), "--record", str(i.record), "--model", "constant",
            "--output", str(i.earlier.parent / "run.nc"), *extra]


def _protocol(*extra: str) -> list[str]:
    return ["protocol", "--model", "precise", "--slider-diameter", "0.3", "--pressure", "60e6",
            "--effective-radius", "4.5", "--amplitude", "0.3", "--period", "4.26", "--cycles",
            "1", *extra]


def _diagnose(i: Inputs, *extra: str, load: bool = True) -> list[str]:
    return ["diagnose", str(i.test), *DIAGNOSE, *(("--axial-load", repr(N)) if load else ()),
            *extra]


@dataclass
class Case:
    argv: Callable[[Inputs], list[str]]
    status: int
    names: tuple[str, ...]
    absent: tuple[str, ...] = ()  # words the message must not hold (an internal name)


def _case(argv: Callable[[Inputs], list[str]], status: int, *names: str,
          absent: tuple[str, ...] = ()) -> Case:
    return Case(argv, status, names, absent)


CASES: dict[str, Case] = {
    # records: the step of a record given by flag is named by that flag
    "units-run-record-dt-negative": _case(
        lambda i: _run(i, "--record-dt", "-1"), 2, "--record-dt", "(0, inf)",
        absent=("read_record",)),
    "units-run-record-dt-disagrees-with-peer-dt": _case(
        lambda i: _run(i, "--record-dt", "0.01"), 2, "--record-dt", "DT = 0.02 s",
        absent=("read_record",)),
    "units-spectrum-dt-alias-nan": _case(
        lambda i: ["spectrum", str(i.record), "--dt", "nan"], 2, "--record-dt", "nan",
        absent=("read_record",)),
    "units-spectrum-one-column-without-record-dt": _case(
        lambda i: ["spectrum", _one_column(i)], 2, "one.txt", "one-column", "--record-dt",
        absent=("read_text_record", "Got None")),
    "units-spectrum-one-column-record-dt-in-ms": _case(
        lambda i: ["spectrum", _one_column(i), "--record-dt", "20"], 2, "--record-dt",
        "one.txt", "in milliseconds it would be 0.02 s", absent=("read_text_record",)),
    "units-run-pair-one-column-without-record-dt": _case(
        lambda i: ["run", str(i.plan), "--record", _one_column(i), "--record-y",
                   _one_column(i), "--model", "constant"], 2, "one.txt", "--record-dt",
        absent=("read_text_record", "read_pair", "--resample")),
    "units-run-pair-record-dt-zero": _case(
        lambda i: ["run", str(i.plan), "--record", _one_column(i), "--record-y",
                   _one_column(i), "--record-dt", "0", "--model", "constant"], 2,
        "--record-dt", "Got 0.0", absent=("read_text_record", "read_pair")),
    "units-record-gzip-compressed": _case(
        lambda i: ["spectrum", _gzip_record(i)], 2, "elcentro.at2.gz", "gzip",
        absent=("found 0 data rows",)),
    "units-run-record-gzip-compressed": _case(
        lambda i: ["run", str(i.building), "--record", _gzip_record(i)], 2,
        "elcentro.at2.gz", "gzip"),
    "units-building-initial-temperature-in-kelvin": _case(
        lambda i: ["run", i.edited(i.building, "k.toml", "initial_temperature",
                                   "initial_temperature = 293.15"), "--record", str(i.record)],
        2, "k.toml", "[friction] 'initial_temperature'", "kelvin", "293.15"),
    "units-protocol-initial-temperature-in-kelvin": _case(
        lambda i: _protocol("--initial-temperature", "293.15"), 2, "--initial-temperature",
        "kelvin"),
    # resources: a record file is sized up before it is read
    "resources-record-of-8-gb-sparse": _case(
        lambda i: ["spectrum", _sparse_record(i)], 2, "huge.at2", "8,000.0 MB",
        "is it a record?"),
    "resources-run-record-of-8-gb-sparse": _case(
        lambda i: ["run", str(i.building), "--record", _sparse_record(i)], 2, "huge.at2",
        "MB"),
    "resources-record-is-a-device-that-never-ends": _case(
        lambda i: ["spectrum", "/dev/zero"], 2, "/dev/zero", "not a regular file"),
    "resources-building-is-a-device-that-never-ends": _case(
        lambda i: ["run", "/dev/zero", "--record", str(i.record)], 2, "/dev/zero",
        "not a regular file"),
    "resources-suite-target-is-a-device-that-never-ends": _case(
        lambda i: _suite(i, "--target", "/dev/zero"), 2, "--target /dev/zero",
        "not a regular file"),
    "resources-suite-target-of-8-gb-sparse": _case(
        lambda i: _suite(i, "--target", _sparse_record(i)), 2, "--target", "huge.at2",
        "8,000,000,000 bytes"),
    "contract-suite-target-missing": _case(
        lambda i: _suite(i, "--target", str(i.folder / "none.csv")), 2, "--target",
        "none.csv", "no such file"),
    "contract-suite-target-gzip": _case(
        lambda i: _suite(i, "--target", _gzip_record(i)), 2, "--target", "elcentro.at2.gz",
        "not a UTF-8 CSV"),
    "resources-suite-records-list-of-8-gb-sparse": _case(
        lambda i: ["suite", str(i.building), "--records", _sparse_record(i), "--out",
                   str(i.earlier.parent), "--overwrite"], 2, "huge.at2", "a list of records"),
    "resources-suite-pair-manifest-of-8-gb-sparse": _case(
        lambda i: ["suite", str(i.plan), "--pairs", _sparse_record(i), "--out",
                   str(i.earlier.parent), "--overwrite"], 2, "huge.at2", "a pair manifest"),
    "resources-diagnose-manifest-of-8-gb-sparse": _case(
        lambda i: ["diagnose", "--manifest", _sparse_record(i), *DIAGNOSE], 2, "huge.at2",
        "a campaign manifest"),
    "resources-diagnose-manifest-is-a-device": _case(
        lambda i: ["diagnose", "--manifest", "/dev/zero", *DIAGNOSE], 2, "/dev/zero",
        "not a regular file"),
    "contract-suite-records-list-not-utf8": _case(
        lambda i: ["suite", str(i.building), "--records", _binary(i), "--out",
                   str(i.earlier.parent), "--overwrite"], 2, "list.csv", "not a UTF-8",
        absent=("internal error",)),
    "contract-suite-pair-manifest-not-utf8": _case(
        lambda i: ["suite", str(i.plan), "--pairs", _binary(i), "--out",
                   str(i.earlier.parent), "--overwrite"], 2, "list.csv", "not a UTF-8",
        absent=("internal error",)),
    # the failure contract: flags named as flags, exit 2 (never 3) on a bad value
    "contract-run-scale-negative": _case(
        lambda i: _run(i, "--scale", "-1"), 2, "'--scale'", "(0, inf)"),
    "contract-spectrum-damping-nan": _case(
        lambda i: ["spectrum", str(i.record), "--damping", "nan"], 2, "'--damping'", "[0, 1)",
        absent=("response_spectrum",)),
    "contract-spectrum-damping-one": _case(
        lambda i: ["spectrum", str(i.record), "--damping", "1"], 2, "'--damping'",
        absent=("response_spectrum",)),
    "contract-spectrum-periods-negative": _case(
        lambda i: ["spectrum", str(i.record), "--periods", "1", "-1"], 2, "'--periods'",
        "-1", absent=("response_spectrum",)),
    "contract-spectrum-periods-inf": _case(
        lambda i: ["spectrum", str(i.record), "--periods", "inf"], 2, "'--periods'",
        absent=("response_spectrum",)),
    "contract-suite-period-range-one-value": _case(
        lambda i: _suite(i, "--target", _target(i), "--period-range", "1"), 2,
        "--period-range", "TMIN,TMAX"),
    "contract-suite-period-range-three-values": _case(
        lambda i: _suite(i, "--target", _target(i), "--period-range", "1,2,3"), 2,
        "--period-range"),
    "contract-suite-period-range-to-inf": _case(
        lambda i: _suite(i, "--target", _target(i), "--period-range", "1,inf"), 2,
        "--period-range"),
    "contract-suite-period-range-past-the-target": _case(
        lambda i: _suite(i, "--target", _target(i), "--period-range", "1,6"), 2,
        "--period-range 1,6", "--target", "target.csv", "0.5 to 5 s",
        absent=("scale_suite", "period_range[1]")),
    "contract-suite-default-period-range-past-the-target": _case(
        lambda i: _suite(i, "--target", _target(i, 4.0)), 2, "the default --period-range",
        "five_storey.toml", "target.csv", "0.5 to 4 s",
        absent=("scale_suite", "period_range[1]")),
    "contract-suite-duration-zero": _case(
        lambda i: _suite(i, "--duration", "0"), 2, "'--duration'", "(0, inf)",
        absent=("of Suite",)),
    "contract-suite-dt-nan": _case(
        lambda i: _suite(i, "--dt", "nan"), 2, "'--dt'", absent=("of Suite",)),
    "contract-suite-scales-negative": _case(
        lambda i: _suite(i, "--scales", "1,-2"), 2, "'--scales'", "-2.0",
        absent=("of Suite",)),
    "contract-suite-models-unknown": _case(
        lambda i: _suite(i, "--models", "constant,exact"), 2, "--models", "'exact'",
        absent=("of Suite",)),
    "contract-diagnose-effective-radius-negative": _case(
        lambda i: ["diagnose", str(i.test), "--model", "constant", "--effective-radius", "-1",
                   "--slider-diameter", "0.3", "--axial-load", repr(N)], 2,
        "'--effective-radius'", absent=("Campaign",)),
    "contract-diagnose-slider-diameter-nan": _case(
        lambda i: ["diagnose", str(i.test), "--model", "constant", "--effective-radius", "4.5",
                   "--slider-diameter", "nan", "--axial-load", repr(N)], 2,
        "'--slider-diameter'", "(0, 10]", absent=("Campaign",)),
    "contract-diagnose-axial-load-zero": _case(
        lambda i: _diagnose(i, "--axial-load", "0", load=False), 2, "'--axial-load'",
        absent=("read_record",)),
    "contract-diagnose-yield-displacement-inf": _case(
        lambda i: _diagnose(i, "--yield-displacement", "inf"), 2, "'--yield-displacement'",
        "(0, 0.1]", absent=("BaselineSpec",)),
    "contract-protocol-angle-without-orbit": _case(
        lambda i: _protocol("--angle", "30"), 2, "--angle", "--orbit",
        absent=("error: dcfpb protocol:",)),
    # diagnose: a folder where a test file belongs
    "channels-diagnose-test-file-is-a-folder": _case(
        lambda i: ["diagnose", str(i.records), *DIAGNOSE, "--axial-load", repr(N)], 2,
        "records",
        "is a folder", absent=("no such file",)),
    # diagnose: a manifest's value out of its range named with the manifest and its test
    "channels-manifest-rest-before-negative": _case(
        lambda i: ["diagnose", "--manifest", i.text(
            "m.csv", "file,axial_load,rest_before\ntest1.csv,4.24e6,-5\n"), *DIAGNOSE], 2,
        "m.csv: test 1", "'rest_before'", "-5", absent=("parameter of test",)),
    "channels-manifest-axial-load-zero": _case(
        lambda i: ["diagnose", "--manifest", i.text(
            "m.csv", "file,axial_load\ntest1.csv,0\n"), *DIAGNOSE], 2,
        "m.csv: test 1", "'axial_load'", absent=("parameter of",)),
    "channels-manifest-temperature-below-range": _case(
        lambda i: ["diagnose", "--manifest", i.text(
            "m.csv", "file,axial_load,initial_temperature\ntest1.csv,4.24e6,-300\n"),
            *DIAGNOSE], 2, "m.csv: test 1", "'initial_temperature'", "-300",
        absent=("parameter of test",)),
    # plans: the plan's own checks named by [plan] and key, not by the class Plan
    "plans-bearings-on-one-line": _case(
        lambda i: ["run", _line_plan(i), "--record", str(i.record), "--record-y",
                   str(i.record), "--model", "constant"], 2, "line.toml",
        "[plan] 'bearing_coordinates'", "one line", absent=("of Plan",)),
    "plans-protocol-amplitude-past-half-the-radius": _case(
        lambda i: _protocol("--amplitude", "5"), 2, "--amplitude 5 m",
        "0.5 x --effective-radius = 2.25 m"),
    "plans-protocol-square-orbit-corner-past-half-the-radius": _case(
        lambda i: _protocol("--amplitude", "2.2", "--orbit", "square"), 2, "--amplitude",
        "3.111 m", "--effective-radius"),
    "plans-protocol-slider-as-wide-as-the-radius": _case(
        lambda i: [*_protocol(), "--effective-radius", "0.3", "--amplitude", "0.1"], 2,
        "--slider-diameter 0.3 m", "--effective-radius 0.3 m"),
    "plans-no-dimensions-no-torsional-stiffness": _case(
        lambda i: ["run", i.edited(i.plan, "nodim.toml", "dimensions", ""), "--record",
                   str(i.record), "--record-y", str(i.record), "--model", "constant"], 2,
        "nodim.toml", "[plan] 'torsional_stiffnesses'", "'dimensions'",
        absent=("of Plan",)),
    # outputs: the probe's checks beside the fixes (an output that is an input, by another name)
    "outputs-run-output-hardlink-to-the-record": _case(
        lambda i: _run_hardlink(i), 2, "--output", "is the record", "Give another --output"),
    "outputs-run-output-dotted-path-to-the-building": _case(
        lambda i: ["run", str(i.building), "--record", str(i.record), "--model", "constant",
                   "--output", str(i.folder / "records" / ".." / i.building.name)], 2,
        "--output", "the building file"),
}


def _line_plan(i: Inputs) -> str:
    text = i.plan.read_text().replace(
        "bearing_coordinates = [[-10.0, -5.0], [0.0, -5.0], [10.0, -5.0],\n"
        "                       [-10.0, 5.0], [0.0, 5.0], [10.0, 5.0]]",
        "bearing_coordinates = [[-10.0, 0.0], [0.0, 0.0], [10.0, 0.0],\n"
        "                       [-5.0, 0.0], [5.0, 0.0], [7.0, 0.0]]")
    assert "[7.0, 0.0]" in text
    return i.text("line.toml", text)


def _run_hardlink(i: Inputs) -> list[str]:
    link = i.folder / "link.nc"
    link.hardlink_to(i.record)
    return ["run", str(i.building), "--record", str(i.record), "--model", "constant",
            "--output", str(link), "--overwrite"]


@pytest.mark.parametrize("case", CASES, ids=list(CASES))
def test_panel_probe(case, inputs, capsys):
    spec = CASES[case]
    argv = spec.argv(inputs)
    if "/dev/zero" in argv and not Path("/dev/zero").exists():
        pytest.skip("no /dev/zero on this platform")
    before = inputs.snapshot()  # the case's own inputs written
    status = main(argv)
    err = capsys.readouterr().err
    assert status == spec.status, err
    for name in spec.names:
        assert name in err, (name, err)
    for word in spec.absent:
        assert word not in err, (word, err)
    assert "Traceback" not in err
    assert inputs.snapshot() == before


def test_the_probe_panel_covers_its_kinds():
    kinds = {case.split("-")[0] for case in CASES}
    assert kinds == {"units", "resources", "contract", "channels", "plans", "outputs"}
