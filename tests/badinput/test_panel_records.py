"""Issue 22, bad-input panel, part 2: records, units and steps.

Each case is one command (``dcfpb.cli.main`` in-process) or one Python call on files written to
``tmp_path``. Each asserts (a) the exit status (2 bad input, 1 a run that failed) or the
exception class, (b) that the message names the file, flag or parameter concerned, and (c) that
no file present before the call (the inputs and an earlier output: a figure or a result that an
earlier run wrote) changed, and, for bad input, that nothing new was written.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.pairs import read_pair
from groundmotions.readers import read_peer_at2, read_record, read_text_record
from groundmotions.records import RecordFormatError

REPO = Path(__file__).resolve().parents[2]
BUILDING = REPO / "examples" / "five_storey.toml"
PLAN = REPO / "examples" / "five_storey_plan.toml"
ELCENTRO = Path(str(resources.files("groundmotions").joinpath("data", "elcentro_1940_ns.at2")))
HEAD = "PEER STRONG MOTION DATABASE RECORD\nCHALFANT VALLEY 07/21/86 14:42, BENTON, 360\n"
SMALL = " .1E-01 -.2E-01 .3E-01 .4E-01\n .5E-01 -.6E-01 .7E-01 .8E-01\n"
EARLIER_PNG = b"\x89PNG\r\n\x1a\n an earlier figure"
EARLIER_NC = b"CDF\x01 an earlier result"


def peer(units_line: str = "UNITS OF G", npts_line: str = "NPTS= 8, DT= .01 SEC",
         data: str = SMALL) -> str:
    return HEAD + units_line + "\n" + npts_line + "\n" + data


def elcentro(units_line: str | None, to_unit: float) -> str:
    out = []
    for number, line in enumerate(ELCENTRO.read_text().splitlines(), start=1):
        if number == 3:
            out.extend([] if units_line is None else [units_line])
        elif number <= 4:
            out.append(line)
        else:
            out.append(" ".join(repr(float(v) * STANDARD_GRAVITY / to_unit) for v in line.split()))
    return "\n".join(out) + "\n"


GOOD = peer()
DT_100 = peer(npts_line="NPTS= 8, DT= 100 SEC")
DT_1E6 = peer(npts_line="NPTS= 8, DT= 1e-6 SEC")
VELOCITY = peer("VELOCITY TIME SERIES IN UNITS OF CM/S")
TRAILING = peer(data=SMALL + "*** End Data ***\n 1 2 3 4\n")


@dataclass
class Case:
    files: dict[str, str]
    """Files written to tmp_path: name -> content."""
    call: Callable[[Path], list[str]] | Callable[[Path], object]
    """argv of ``dcfpb`` (a list) or a Python call on tmp_path."""
    expect: int | type[BaseException]
    """Exit status or exception class."""
    names: list[str]
    """Words the message must hold: the file, flag, parameter (and line)."""
    api: bool = False
    writes: bool = False
    """Whether the command may write new files (a suite's failed runs are its output)."""
    extra: dict[str, bytes] = field(default_factory=dict)


def spectrum(name: str, *flags: str) -> Callable[[Path], list[str]]:
    return lambda d: ["spectrum", str(d / name), "--plot", str(d / "earlier.png"), "--overwrite",
                      *flags]


def run(name: str, *flags: str) -> Callable[[Path], list[str]]:
    return lambda d: ["run", str(BUILDING), "--record", str(d / name), "--output",
                      str(d / "earlier.nc"), "--overwrite", *flags]


def opensees(name: str) -> Callable[[Path], list[str]]:
    return lambda d: ["compare-opensees", str(BUILDING), "--record", str(d / name)]


CASES: dict[str, Case] = {
    # the quantity and the units of the values
    "records-velocity-vt2": Case({"v.vt2": VELOCITY}, spectrum("v.vt2"), 2,
                                 ["v.vt2, line 3", "velocity record", "(.AT2)"]),
    "records-displacement-dt2": Case(
        {"d.dt2": peer("DISPLACEMENT TIME SERIES IN UNITS OF CM")}, spectrum("d.dt2"), 2,
        ["d.dt2, line 3", "displacement record", "(.AT2)"]),
    "records-velocity-unit-statement": Case(
        {"v.at2": peer("UNITS OF IN/SEC")}, spectrum("v.at2"), 2,
        ["v.at2, line 3", "'IN/SEC'", "velocity"]),
    "records-length-unit-statement": Case(
        {"l.at2": peer("UNITS OF MM")}, spectrum("l.at2"), 2, ["l.at2, line 3", "'MM'"]),
    "records-unknown-unit": Case(
        {"f.at2": peer("UNITS OF FURLONG/S/S")}, spectrum("f.at2"), 2,
        ["f.at2, line 3", "'FURLONG/S/S'", "--units"]),
    "records-si-values-without-units": Case(
        {"si.at2": elcentro(None, 1.0)}, spectrum("si.at2"), 2,
        ["si.at2, line 16", "PGA 3.13 g", "m/s^2", "--units"]),
    "records-gal-values-without-units": Case(
        {"gal.at2": elcentro(None, 0.01)}, spectrum("gal.at2"), 2,
        ["gal.at2, line 16", "PGA 313 g", "cm/s^2 (gal)", "--units"]),
    "records-units-flag-against-header": Case(
        {"g.at2": GOOD}, spectrum("g.at2", "--units", "mg"), 2,
        ["g.at2, line 3", "--units", "mg"]),
    "records-g-header-of-mg-values": Case(
        {"mg.at2": peer(data=" 10 -20 30 40\n 50 -60 70 80\n")}, spectrum("mg.at2"), 2,
        ["mg.at2, line 6", "PGA 80 g", "mg (PGA 0.08 g)", "'G' on line 3"]),
    # the time step
    "records-dt-100-s": Case({"dt.at2": DT_100}, spectrum("dt.at2"), 2,
                             ["dt.at2, line 4", "time step of 100 s", "1e-05 to 0.1 s"]),
    "records-dt-1e-6-s": Case({"dt.at2": DT_1E6}, spectrum("dt.at2"), 2,
                              ["dt.at2, line 4", "time step of 1e-06 s"]),
    "records-dt-ms-unstated": Case(
        {"ms.at2": peer(npts_line="NPTS= 8, DT= 20")}, spectrum("ms.at2"), 2,
        ["ms.at2, line 4", "in milliseconds it would be 0.02 s", "MSEC"]),
    "records-dt-in-minutes": Case(
        {"min.at2": peer(npts_line="NPTS= 8, DT= 0.5 MIN")}, spectrum("min.at2"), 2,
        ["min.at2, line 4", "'MIN'"]),
    "records-dt-in-hertz": Case(
        {"hz.at2": peer(npts_line="NPTS= 8, DT= 200 HZ")}, spectrum("hz.at2"), 2,
        ["hz.at2, line 4", "'HZ'"]),
    "records-duration-too-long": Case(
        {"long.at2": peer(npts_line="NPTS= 20000, DT= 0.1 SEC",
                          data=" .1E-01 -.2E-01 .3E-01 .4E-01\n" * 5000)},
        spectrum("long.at2"), 2, ["long.at2, line 4", "1999.9 s", "1800 s"]),
    "records-text-time-column-in-ms-unstated": Case(
        {"t.txt": "time acc\n0 0.01\n20 0.02\n40 -0.03\n"}, spectrum("t.txt"), 2,
        ["t.txt, line 3", "time step of 20 s", "'# time [ms]'"]),
    "records-text-time-units-disagree": Case(
        {"t.txt": "# time [ms]\n# t (s)\n0 0.01\n0.02 0.02\n"}, spectrum("t.txt"), 2,
        ["t.txt, line 2", "'ms' on line 1"]),
    "records-record-dt-flag-100-s": Case(
        {"one.txt": "0.01\n0.02\n-0.03\n"}, spectrum("one.txt", "--record-dt", "100"), 2,
        ["one.txt", "--record-dt", "time step of 100 s"]),
    "records-record-dt-flag-1e-6-s": Case(
        {"one.txt": "0.01\n0.02\n-0.03\n"}, spectrum("one.txt", "--dt", "1e-6"), 2,
        ["one.txt", "--record-dt", "time step of 1e-06 s"]),
    "records-dt-flag-against-peer-dt": Case(
        {"p.at2": GOOD}, spectrum("p.at2", "--dt", "0.02"), 2, ["p.at2", "--record-dt", "0.02"]),
    # the count
    "records-numbers-after-the-end-line": Case(
        {"tr.at2": TRAILING}, spectrum("tr.at2"), 2,
        ["tr.at2, line 8", "more values after the 8 values of NPTS"]),
    "records-npts-smaller-than-the-values": Case(
        {"n.at2": peer(npts_line="NPTS= 7, DT= .01")}, spectrum("n.at2"), 2,
        ["n.at2, line 6", "NPTS is 7 but value 8"]),
    "records-npts-larger-than-the-values": Case(
        {"n.at2": peer(npts_line="NPTS= 12, DT= .01")}, spectrum("n.at2"), 2,
        ["n.at2, line 6", "expected 12 values (NPTS) but the file ends after 8"]),
    "records-nan-value": Case(
        {"nan.at2": peer(data=" .1E-01 -.2E-01 .3E-01 .4E-01\n nan 0 0 0\n")},
        spectrum("nan.at2"), 2, ["nan.at2, line 6", "value 5 is nan"]),
    # the building commands refuse the same records before any work
    "run-dt-100-s": Case({"dt.at2": DT_100}, run("dt.at2"), 2, ["dt.at2, line 4", "100 s"]),
    "run-si-values-without-units": Case(
        {"si.at2": elcentro(None, 1.0)}, run("si.at2"), 2, ["si.at2, line 16", "--units"]),
    "run-velocity-record": Case({"v.vt2": VELOCITY}, run("v.vt2"), 2, ["v.vt2", "velocity"]),
    "run-pair-y-dt-1e-6-s": Case(
        {"x.at2": GOOD, "y.at2": DT_1E6},
        lambda d: ["run", str(PLAN), "--record", str(d / "x.at2"), "--record-y",
                   str(d / "y.at2"), "--output", str(d / "earlier.nc"), "--overwrite"],
        2, ["y.at2, line 4", "1e-06 s"]),
    "opensees-dt-100-s": Case({"dt.at2": DT_100}, opensees("dt.at2"), 2,
                              ["dt.at2, line 4", "100 s"]),
    "opensees-numbers-after-the-end-line": Case({"tr.at2": TRAILING}, opensees("tr.at2"), 2,
                                                ["tr.at2, line 8"]),
    "suite-record-dt-100-s-is-a-failed-run": Case(
        {"recs/dt.at2": DT_100},
        lambda d: ["suite", str(BUILDING), "--records", str(d / "recs"), "--out",
                   str(d / "out"), "--models", "constant", "--no-plots", "--no-progress"],
        1, ["dt.at2, line 4", "time step of 100 s"], writes=True),
    # the Python readers
    "api-read-record-velocity": Case(
        {"v.vt2": VELOCITY}, lambda d: read_record(d / "v.vt2"), RecordFormatError,
        ["v.vt2, line 3", "velocity"], api=True),
    "api-read-peer-dt-in-minutes": Case(
        {"m.at2": peer(npts_line="NPTS= 8, DT= 1 MINUTE")},
        lambda d: read_peer_at2(d / "m.at2"), RecordFormatError, ["m.at2, line 4", "'MINUTE'"],
        api=True),
    "api-read-text-record-dt-1e-6-s": Case(
        {"one.txt": "0.01\n0.02\n"}, lambda d: read_text_record(d / "one.txt", 1e-6), InputError,
        ["'dt' parameter of read_text_record", "one.txt"], api=True),
    "api-read-pair-x-dt-100-s": Case(
        {"x.at2": DT_100, "y.at2": GOOD}, lambda d: read_pair(d / "x.at2", d / "y.at2"),
        InputError, ["x component", "x.at2, line 4", "100 s"], api=True),
    "api-read-record-units-bananas": Case(
        {"g.at2": GOOD}, lambda d: read_record(d / "g.at2", units="bananas"), InputError,
        ["'units' parameter", "'bananas'"], api=True),
}


def _hashes(root: Path) -> dict[str, str]:
    return {str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("case_id", list(CASES), ids=list(CASES))
def test_panel_records(tmp_path, capsys, case_id):
    case = CASES[case_id]
    for name, content in case.files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(content)
    (tmp_path / "earlier.png").write_bytes(EARLIER_PNG)
    (tmp_path / "earlier.nc").write_bytes(EARLIER_NC)
    before = _hashes(tmp_path)
    if case.api:
        with pytest.raises(case.expect) as info:
            case.call(tmp_path)
        message = str(info.value)
    else:
        status = main(case.call(tmp_path))
        captured = capsys.readouterr()
        message = captured.err + captured.out
        assert status == case.expect, message
    for name in case.names:
        assert name in message, (name, message)
    after = _hashes(tmp_path)
    assert {k: after.get(k) for k in before} == before  # inputs and earlier outputs unchanged
    if not case.writes:
        assert set(after) == set(before)  # and nothing new written


def test_the_panel_has_at_least_30_cases():
    assert len(CASES) >= 30
