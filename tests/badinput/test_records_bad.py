"""Bad ground-motion records and record flags through the command line: nothing silently wrong.

Each case is a crafted file (a copy of the bundled El Centro record with one thing wrong, or a
small text record) or a bad flag, run through the CLI entry point (``dcfpb spectrum``, and
``dcfpb run`` for the building path). Each must exit with status 2 and say on stderr which file
and what in it is wrong: the unit as written, the line, the value.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import pytest

from dcfpb.cli import main
from dcfpb.common.units import STANDARD_GRAVITY

EXIT_BAD_INPUT = 2
ELCENTRO = Path(str(resources.files("groundmotions").joinpath("data", "elcentro_1940_ns.at2")))
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "five_storey.toml"
PEER_HEADER = (
    "PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.\n"
    "CHALFANT VALLEY 07/21/86 14:42, BENTON, 360 (CDMG STATION 54100)\n"
    "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz LP=33.0 Hz\n"
)
SMALL = " .1E-01 -.2E-01 .3E-01 .4E-01\n .5E-01 -.6E-01 .7E-01 .8E-01\n"  # 8 values in g


def _elcentro(units_line: str | None, to_unit: float = STANDARD_GRAVITY) -> str:
    """The bundled record, line 3 (``The units are (g)``) replaced or removed, values in a unit
    of ``to_unit`` [m/s^2]."""
    out = []
    for number, line in enumerate(ELCENTRO.read_text().splitlines(), start=1):
        if number == 3:
            out.extend([] if units_line is None else [units_line])
        elif number <= 4:
            out.append(line)
        else:
            out.append(" ".join(repr(float(v) * STANDARD_GRAVITY / to_unit) for v in line.split()))
    return "\n".join(out) + "\n"


def _text(values, times=None, header: str = "") -> str:
    rows = [repr(v) for v in values] if times is None else [
        f"{t!r} {v!r}" for t, v in zip(times, values, strict=True)]
    return header + "\n".join(rows) + "\n"


WAVE = [0.01, -0.02, 0.03, 0.05, -0.04, 0.02]  # [g]
TIMES = [0.0, 0.01, 0.02, 0.03, 0.04, 0.05]

# name: (file content, extra flags, words stderr must hold besides the file name)
CASES: dict[str, tuple[str | bytes, list[str], list[str]]] = {
    # units
    "gal_unstated.at2": (_elcentro(None, 0.01), [],
                         ["line 16", "PGA 313 g", "0.0001 to 5 g", "cm/s^2 (gal) (PGA 0.319 g)",
                          "--units"]),
    "gal_said_g.at2": (_elcentro("ACCELERATION TIME HISTORY IN UNITS OF G", 0.01), [],
                       ["line 17", "PGA 313 g", "cm/s^2 (gal)", "'G' on line 3"]),
    "g_said_mm.at2": (_elcentro("UNITS OF MM/S/S"), [],
                      ["PGA 3.25e-05 g", "look like g (PGA 0.319 g)", "'MM/S/S' on line 3"]),
    "furlongs.at2": (_elcentro("ACCELERATION TIME HISTORY IN UNITS OF FURLONG/S/S"), [],
                     ["line 3", "'FURLONG/S/S'", "known units: g, mg, gal, cm/s^2, m/s^2, mm/s^2, "
                      "in/s^2, ft/s^2"]),
    "velocity_units.at2": (_elcentro("TIME HISTORY IN UNITS OF CM/S"), [],
                           ["line 3", "'CM/S'", "velocity"]),
    "velocity.vt2": (PEER_HEADER.replace("ACCELERATION", "VELOCITY") + "NPTS= 8, DT= .01\n"
                     + SMALL, [], ["line 3", "velocity record"]),
    "two_units.at2": (_elcentro("UNITS OF G").replace("(Peknold Version)", "(units: gal)"), [],
                      ["line 3", "'gal' on line 1", "'G'"]),
    "units_flag_against_header.at2": (_elcentro("UNITS OF G"), ["--units", "gal"],
                                      ["line 3", "'G' (g)", "cm/s^2 (gal)"]),
    "zeros.at2": (PEER_HEADER + "NPTS= 4, DT= .01\n 0. 0. 0. 0.\n", [],
                  ["line 5", "PGA 0 g", "no known unit", "check the values"]),
    # counts, values, time steps
    "short.at2": (PEER_HEADER + "NPTS= 20, DT= .01 SEC\n" + SMALL, [],
                  ["line 6", "expected 20 values (NPTS) but the file ends after 8"]),
    "huge_npts.at2": (PEER_HEADER + "NPTS= 1000000000000, DT= .01\n" + SMALL, [],
                      ["line 6", "expected 1000000000000 values"]),
    "token.at2": (PEER_HEADER + "NPTS= 8, DT= .01\n .1E-01 -.2E-01 1.2.3 .4E-01\n", [],
                  ["line 5", "'1.2.3'"]),
    "nan.at2": (PEER_HEADER + "NPTS= 8, DT= .01\n .1E-01 -.2E-01 .3E-01 .4E-01\n nan 0 0 0\n",
                [], ["line 6", "value 5 is nan"]),
    "zero_dt.at2": (PEER_HEADER + "NPTS= 8, DT= 0.0 SEC\n" + SMALL, [], ["line 4", "DT=0.0"]),
    "no_dt.at2": (PEER_HEADER + "NPTS= 8\n" + SMALL, [], ["line 4", "no DT"]),
    "binary.at2": (bytes(range(256)) * 4, [], ["no NPTS/DT line"]),
    "peer_dt_flag.at2": (PEER_HEADER + "NPTS= 8, DT= .02\n" + SMALL, ["--dt", "0.01"],
                         ["--record-dt", "DT = 0.02 s", "0.01"]),
    # text records
    "one_column.txt": (_text(WAVE), [], ["one_column.txt", "one-column record", "--record-dt"]),
    "uneven.txt": (_text(WAVE, [0.0, 0.01, 0.02, 0.04, 0.05, 0.06]), [],
                   ["line 4", "not uniformly sampled", "0.04"]),
    "dt_disagrees.txt": (_text(WAVE, TIMES), ["--dt", "0.05"],
                         ["--record-dt", "must agree with the time column", "0.05"]),
    "bananas.txt": (_text(WAVE, TIMES, "# units: bananas\n"), [], ["line 1", "'bananas'"]),
    "text_gal_unstated.csv": (_text([312.0, -150.0, 20.0], header="acc\n"), ["--dt", "0.02"],
                              ["line 2", "PGA 312 g", "cm/s^2 (gal) (PGA 0.318 g)"]),
    "three_columns.txt": ("0 1 2\n0.01 1 2\n", [], ["line 1", "expected 1 or 2 columns"]),
    "empty.txt": ("", [], ["found 0 data rows"]),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_bad_record_exits_2_naming_the_file_and_the_culprit(tmp_path, capsys, name):
    content, flags, words = CASES[name]
    path = tmp_path / name
    path.write_bytes(content if isinstance(content, bytes) else content.encode())
    assert main(["spectrum", str(path), *flags]) == EXIT_BAD_INPUT
    captured = capsys.readouterr()
    assert captured.out == ""
    err = captured.err
    assert err.startswith("dcfpb spectrum: error: ")
    assert name in err, err
    for word in words:
        assert word in err, (word, err)


@pytest.mark.parametrize("name", ["gal_unstated.at2", "furlongs.at2", "one_column.txt"])
def test_bad_record_stops_dcfpb_run_before_any_work(tmp_path, capsys, name):
    content, flags, words = CASES[name]
    path = tmp_path / name
    path.write_text(content)
    flags = [f.replace("--dt", "--record-dt") for f in flags]  # run's --dt is the analysis step
    out = tmp_path / "out.nc"
    assert main(["run", str(EXAMPLE), "--record", str(path), "--output", str(out),
                 *flags]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert err.startswith("dcfpb run: error: ") and name in err
    for word in words:
        assert word in err, (word, err)
    assert not out.exists()


@pytest.mark.parametrize(("flags", "words"), [
    (["--units", "furlong/s/s"], ["--units", "invalid choice: 'furlong/s/s'", "'gal'"]),
    (["--units", "cm/s"], ["--units", "invalid choice: 'cm/s'"]),
    (["--record-dt", "abc"], ["--record-dt", "invalid float value: 'abc'"]),
])
def test_bad_record_flags_exit_2_naming_the_flag(capsys, flags, words):
    with pytest.raises(SystemExit) as info:
        main(["spectrum", str(ELCENTRO), *flags])
    assert info.value.code == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    for word in words:
        assert word in err, (word, err)


@pytest.mark.parametrize("dt", ["-0.01", "0", "nan"])
def test_bad_record_dt_value_exits_2(tmp_path, capsys, dt):
    path = tmp_path / "one_column.txt"
    path.write_text(_text(WAVE))
    assert main(["spectrum", str(path), "--dt", dt]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert "--record-dt" in err and dt in err
