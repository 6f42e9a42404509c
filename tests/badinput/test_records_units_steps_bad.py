"""Issue 22, records: units, steps and counts read as written or refused, never misread.

Velocity and displacement records refused naming the .AT2 needed; mg converted; DT in
milliseconds (``DT= 20 MSEC``) and a time column in ms converted; a record in m/s^2 with no unit
statement refused; numbers beyond NPTS refused; and the same plausibility of PGA, time step and
duration for every command that reads a record (``spectrum`` as ``run``, the pair readers).
Each refusal exits with status 2 (or raises `InputError`) naming the file and the line.
"""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions import load_bundled
from groundmotions.pairs import read_pair
from groundmotions.readers import read_record

EXIT_BAD_INPUT = 2
ELCENTRO = Path(str(resources.files("groundmotions").joinpath("data", "elcentro_1940_ns.at2")))
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "five_storey.toml"
HEAD = "PEER STRONG MOTION DATABASE RECORD\nCHALFANT VALLEY 07/21/86 14:42, BENTON, 360\n"
SMALL = " .1E-01 -.2E-01 .3E-01 .4E-01\n .5E-01 -.6E-01 .7E-01 .8E-01\n"  # 8 values [g]
G_VALUES = np.array([1, -2, 3, 4, 5, -6, 7, 8]) * 0.01  # [g]


def _peer(units_line: str, npts_line: str, data: str = SMALL) -> str:
    return HEAD + units_line + "\n" + npts_line + "\n" + data


def _elcentro(units_line: str | None, to_unit: float) -> str:
    """The bundled record, its units line (line 3) replaced or removed, values in a unit of
    ``to_unit`` [m/s^2]."""
    out = []
    for number, line in enumerate(ELCENTRO.read_text().splitlines(), start=1):
        if number == 3:
            out.extend([] if units_line is None else [units_line])
        elif number <= 4:
            out.append(line)
        else:
            out.append(" ".join(repr(float(v) * STANDARD_GRAVITY / to_unit) for v in line.split()))
    return "\n".join(out) + "\n"


def _spectrum(tmp_path, capsys, name: str, content: str, *flags: str) -> tuple[int, str]:
    path = tmp_path / name
    path.write_text(content)
    status = main(["spectrum", str(path), *flags])
    return status, capsys.readouterr().err


# name: (content, flags, words stderr must hold besides the file name)
REFUSED: dict[str, tuple[str, list[str], list[str]]] = {
    "velocity.vt2": (_peer("VELOCITY TIME SERIES IN UNITS OF CM/S", "NPTS= 8, DT= .01 SEC"), [],
                     ["line 3", "velocity record", "acceleration record (.AT2)"]),
    "displacement.dt2": (_peer("DISPLACEMENT TIME SERIES IN UNITS OF CM", "NPTS= 8, DT= .01"), [],
                         ["line 3", "displacement record", "acceleration record (.AT2)"]),
    "velocity_unit_only.at2": (_peer("UNITS OF IN/SEC", "NPTS= 8, DT= .01"), [],
                               ["line 3", "'IN/SEC'", "velocity", "(.AT2)"]),
    "displacement_unit_only.at2": (_peer("UNITS OF MM", "NPTS= 8, DT= .01"), [],
                                   ["line 3", "'MM'", "displacement", "(.AT2)"]),
    "si_unstated.at2": (_elcentro(None, 1.0), [],
                        ["line 16", "PGA 3.13 g", "read as g, the default", "above 2 g",
                         "m/s^2 (PGA 0.319 g)", "--units"]),
    "dt_100s.at2": (_peer("UNITS OF G", "NPTS= 8, DT= 100 SEC"), [],
                    ["line 4", "time step of 100 s", "1e-05 to 0.1 s", "MSEC"]),
    "dt_1e-6s.at2": (_peer("UNITS OF G", "NPTS= 8, DT= 1e-6 SEC"), [],
                     ["line 4", "time step of 1e-06 s", "1e-05 to 0.1 s"]),
    "dt_minutes.at2": (_peer("UNITS OF G", "NPTS= 8, DT= 0.5 MIN"), [],
                       ["line 4", "'MIN'", "SEC", "MSEC"]),
    "dt_hertz.at2": (_peer("UNITS OF G", "NPTS= 8, DT= 200 HZ"), [], ["line 4", "'HZ'"]),
    "ms_dt_unstated.at2": (_peer("UNITS OF G", "NPTS= 8, DT= 20"), [],
                           ["line 4", "time step of 20 s", "in milliseconds it would be 0.02 s",
                            "'DT= 20 MSEC'"]),
    "too_long.at2": (_peer("UNITS OF G", "NPTS= 20000, DT= 0.1 SEC",
                           " .1E-01 -.2E-01 .3E-01 .4E-01\n" * 5000), [],
                     ["line 4", "20000 samples at 0.1 s last 1999.9 s", "1800 s"]),
    "trailing_numbers.at2": (_peer("UNITS OF G", "NPTS= 8, DT= .01", SMALL + "END\n 1 2 3 4\n"),
                             [], ["line 8", "more values after the 8 values of NPTS",
                                  "'END' on line 7"]),
    "npts_too_small.at2": (_peer("UNITS OF G", "NPTS= 6, DT= .01"), [],
                           ["line 6", "NPTS is 6 but value 7 is on this line"]),
    "npts_too_large.at2": (_peer("UNITS OF G", "NPTS= 9, DT= .01"), [],
                           ["line 6", "expected 9 values (NPTS) but the file ends after 8"]),
    "time_ms_unstated.txt": ("time acc\n0 0.01\n20 0.02\n40 -0.03\n60 0.01\n", [],
                             ["line 3", "time step of 20 s", "milliseconds", "'# time [ms]'"]),
    "time_units_disagree.txt": ("# time [ms]\n# t (s), acceleration (g)\n0 0.01\n0.02 0.02\n",
                                [], ["line 2", "'ms' on line 1", "'s'"]),
    "record_dt_100.txt": ("0.01\n0.02\n-0.03\n", ["--dt", "100"],
                          ["--record-dt", "time step of 100 s"]),
}


@pytest.mark.parametrize("name", sorted(REFUSED))
def test_refused_by_spectrum_with_exit_2_naming_the_file(tmp_path, capsys, name):
    content, flags, words = REFUSED[name]
    status, err = _spectrum(tmp_path, capsys, name, content, *flags)
    assert status == EXIT_BAD_INPUT, err
    assert err.startswith("dcfpb spectrum: error: ") and name in err, err
    for word in words:
        assert word in err, (word, err)


@pytest.mark.parametrize("name", ["dt_100s.at2", "dt_1e-6s.at2", "si_unstated.at2"])
def test_run_refuses_the_same_records_before_any_work(tmp_path, capsys, name):
    content, _, words = REFUSED[name]
    path = tmp_path / name
    path.write_text(content)
    out = tmp_path / "out.nc"
    status = main(["run", str(EXAMPLE), "--record", str(path), "--output", str(out)])
    err = capsys.readouterr().err
    assert status == EXIT_BAD_INPUT, err
    assert err.startswith("dcfpb run: error: ") and name in err
    for word in words:
        assert word in err, (word, err)
    assert not out.exists()


def test_pair_readers_apply_the_same_limits(tmp_path):
    good = tmp_path / "y.at2"
    good.write_text(_peer("UNITS OF G", "NPTS= 8, DT= .01"))
    bad = tmp_path / "x.at2"
    bad.write_text(REFUSED["dt_100s.at2"][0])
    with pytest.raises(InputError, match=r"x component .*x.at2, line 4: a time step of 100 s"):
        read_pair(bad, good)


# --------------------------------------------------------------------- read and converted


@pytest.mark.parametrize(("units_line", "factor"), [
    ("ACCELERATION TIME SERIES IN UNITS OF MG", 1000.0),
    ("UNITS OF milli-g", 1000.0),
    ("UNITS OF GAL", 100.0 * STANDARD_GRAVITY),
    ("UNITS OF CM/S2", 100.0 * STANDARD_GRAVITY),
    ("UNITS OF M/S/S", STANDARD_GRAVITY),
    ("UNITS OF MM/S^2", 1000.0 * STANDARD_GRAVITY),
    ("UNITS OF IN/S/S", STANDARD_GRAVITY / 0.0254),
    ("UNITS OF FT/SEC/SEC", STANDARD_GRAVITY / 0.3048),
])
def test_accelerations_in_any_unit_are_converted(tmp_path, units_line, factor):
    data = "\n".join(" ".join(repr(float(v) * factor) for v in G_VALUES[i:i + 4]) for i in (0, 4))
    path = tmp_path / "rec.at2"
    path.write_text(_peer(units_line, "NPTS= 8, DT= .01 SEC", data + "\n"))
    np.testing.assert_allclose(read_record(path).acceleration, G_VALUES * STANDARD_GRAVITY,
                               rtol=1e-12)


def test_mg_record_through_spectrum_equals_the_g_record(tmp_path, capsys):
    mg = "\n".join(" ".join(repr(float(v) * 1e3) for v in G_VALUES[i:i + 4]) for i in (0, 4))
    outputs = []
    for name, content in (("mg.at2", _peer("UNITS OF MG", "NPTS= 8, DT= .01", mg + "\n")),
                          ("g.at2", _peer("UNITS OF G", "NPTS= 8, DT= .01"))):
        (tmp_path / name).write_text(content)
        assert main(["spectrum", str(tmp_path / name), "--json"]) == 0
        outputs.append(json.loads(capsys.readouterr().out))
    for key in ("pga", "pgv", "pgd", "arias_intensity"):
        assert outputs[0][key] == pytest.approx(outputs[1][key], rel=1e-12)


@pytest.mark.parametrize("npts_line", ["NPTS= 8, DT= 20 MSEC", "NPTS=8, DT=20msec",
                                       "NPTS= 8, DT= 20 ms", "npts = 8, dt = 20 Milliseconds",
                                       "NPTS= 8, DT= 20MSEC,"])
def test_dt_in_milliseconds_is_converted(tmp_path, npts_line):
    path = tmp_path / "ms.at2"
    path.write_text(_peer("UNITS OF G", npts_line))
    motion = read_record(path)
    assert motion.dt == pytest.approx(0.02, rel=1e-15)
    assert motion.metadata["dt_unit_in_file"] == "ms"
    assert "DT read in ms: 0.02 s" in motion.processing
    reference = tmp_path / "s.at2"
    reference.write_text(_peer("UNITS OF G", "NPTS= 8, DT= .02 SEC"))
    np.testing.assert_array_equal(motion.acceleration, read_record(reference).acceleration)


@pytest.mark.parametrize("header", ["# time [ms], acceleration [g]\n", "t(ms) a(g)\n",
                                    "% Time in msec\n", "time (milliseconds); acc (g)\n",
                                    "time_ms,acc_g\n", "Time [ms] , Acceleration [g]\n"])
def test_time_column_in_milliseconds_is_converted(tmp_path, header):
    path = tmp_path / "ms.txt"
    path.write_text(header + "0 0.01\n20 0.02\n40 -0.03\n60 0.01\n")
    motion = read_record(path)
    assert motion.dt == pytest.approx(0.02, rel=1e-12)
    assert motion.metadata["time_unit_in_file"] == "ms"
    np.testing.assert_allclose(motion.acceleration / STANDARD_GRAVITY, [0.01, 0.02, -0.03, 0.01])


def test_record_dt_out_of_range_through_the_api_names_the_parameter(tmp_path):
    path = tmp_path / "one.txt"
    path.write_text("0.01\n0.02\n-0.03\n")
    with pytest.raises(InputError, match=r"'dt' parameter of read_text_record .*one.txt.*1e-06"):
        read_record(path, dt=1e-6)


def test_the_bundled_record_and_a_units_statement_in_g_still_read(tmp_path):
    assert load_bundled().dt == 0.02
    path = tmp_path / "g.at2"
    path.write_text(_elcentro(None, 1.0))
    motion = read_record(path, units="m/s^2")  # stated by the caller: read as such
    np.testing.assert_allclose(motion.acceleration, load_bundled().acceleration, rtol=1e-12)
