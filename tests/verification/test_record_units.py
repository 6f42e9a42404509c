"""Record units: copies of the bundled El Centro record in gal, m/s^2, mm/s^2, in/s^2, ft/s^2
read back to the g original; unknown units refused; the PGA plausibility check both ways;
text records and the command line with ``--units``."""

from __future__ import annotations

import argparse
import json
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.bundled import load_bundled
from groundmotions.readers import read_peer_at2, read_record, read_text_record
from groundmotions.records import RecordFormatError
from groundmotions.units import TO_M_PER_S2, UNIT_NAMES, likely_units, parse_units

ELCENTRO = Path(str(resources.files("groundmotions").joinpath("data", "elcentro_1940_ns.at2")))
UNITS_LINE = "The units are (g)"  # line 3 of the bundled file


def _copy(tmp_path: Path, name: str, units_line: str | None, to_unit: float) -> Path:
    """The bundled record with its values in another unit (``to_unit`` [m/s^2] each) and line 3
    replaced by ``units_line`` (None: removed, the header then states no units)."""
    lines = ELCENTRO.read_text().splitlines()
    assert lines[2] == UNITS_LINE
    out = []
    for number, line in enumerate(lines, start=1):
        if number == 3:
            if units_line is not None:
                out.append(units_line)
        elif number <= 4 or not line.strip() or not line.split()[0][-1].isdigit():
            out.append(line)
        else:
            out.append(" ".join(repr(float(v) * STANDARD_GRAVITY / to_unit) for v in line.split()))
    path = tmp_path / name
    path.write_text("\n".join(out) + "\n")
    return path


def test_the_unit_table():
    assert TO_M_PER_S2 == {"g": 9.80665, "mg": 0.00980665, "cm/s^2": 0.01, "m/s^2": 1.0,
                           "mm/s^2": 0.001, "in/s^2": 0.0254, "ft/s^2": 0.3048}
    assert UNIT_NAMES == ("g", "mg", "gal", "cm/s^2", "m/s^2", "mm/s^2", "in/s^2", "ft/s^2")
    from dcfpb.cli.run import RECORD_UNITS

    assert RECORD_UNITS == UNIT_NAMES  # the --units choices, written out in the CLI


@pytest.mark.parametrize(
    ("written", "name"),
    [("g", "g"), ("G", "g"), ("(g)", "g"), ("GAL", "cm/s^2"), ("gals", "cm/s^2"),
     ("CM/S/S", "cm/s^2"), ("CM/SEC/SEC", "cm/s^2"), ("cm/s2", "cm/s^2"), ("cm/s**2", "cm/s^2"),
     ("CM/SEC**2", "cm/s^2"), ("cm/s²", "cm/s^2"), ("cm s^-2", "cm/s^2"),
     ("M/S/S", "m/s^2"), ("M/SEC/SEC", "m/s^2"), ("m/s2", "m/s^2"), ("m/s^2", "m/s^2"),
     ("MM/S/S", "mm/s^2"), ("mm/sec2", "mm/s^2"), ("IN/S/S", "in/s^2"),
     ("IN/SEC/SEC", "in/s^2"), ("in/s2", "in/s^2"), ("inch/sec^2", "in/s^2"),
     ("FT/S/S", "ft/s^2"), ("feet/sec/sec", "ft/s^2"),
     ("cm/s", None), ("m", None), ("km/s/s", None), ("furlong", None)],
)
def test_spellings(written, name):
    assert parse_units(written) == name


# ------------------------------------------------------------- the El Centro copies, read back


@pytest.mark.parametrize(
    ("units_line", "to_unit"),
    [
        ("ACCELERATION TIME HISTORY IN UNITS OF GAL", 0.01),
        ("ACCELERATION TIME HISTORY IN UNITS OF CM/SEC/SEC", 0.01),
        ("units=cm/sec2 (04)", 0.01),
        ("ACCELERATION TIME HISTORY IN UNITS OF M/S/S", 1.0),
        ("Acceleration [m/s^2]", 1.0),
        ("The units are (MM/S/S)", 0.001),
        ("ACCELERATION TIME HISTORY IN UNITS OF IN/S/S", 0.0254),
        ("Units: in/sec/sec", 0.0254),
        ("Acceleration in ft/s2", 0.3048),
        ("UNITS IN THE FILE ARE G", STANDARD_GRAVITY),
        ("Units used in this record are cm/s/s", 0.01),
        ("units in the data: m/s^2", 1.0),
    ],
)
def test_copies_in_other_units_read_as_the_g_original(tmp_path, units_line, to_unit):
    original = load_bundled("elcentro")
    motion = read_peer_at2(_copy(tmp_path, "copy.at2", units_line, to_unit))
    assert motion.pga == pytest.approx(original.pga, rel=1e-9)
    np.testing.assert_allclose(motion.acceleration, original.acceleration, rtol=1e-9, atol=0)
    assert motion.metadata["units_in_file"] == parse_units(
        {STANDARD_GRAVITY: "g", 0.01: "gal", 1.0: "m/s^2", 0.001: "mm/s^2", 0.0254: "in/s^2",
         0.3048: "ft/s^2"}[to_unit])


def test_the_g_and_cm_paths_keep_their_digits(tmp_path):
    """g: values x 9.80665; cm/s^2: values x 0.01, bit for bit as before the unit table."""
    raw = np.array([float(v) for line in ELCENTRO.read_text().splitlines()[4:]
                    for v in line.split()])
    motion = load_bundled("elcentro")
    np.testing.assert_array_equal(motion.acceleration, raw * STANDARD_GRAVITY)
    assert motion.processing == ("read from elcentro_1940_ns.at2 (g -> m/s^2)",)
    path = tmp_path / "cm.at2"
    path.write_text(ELCENTRO.read_text().replace(UNITS_LINE, "UNITS OF CM/S/S").replace(
        "0.0", "9.0"))  # values of 9 to 20 cm/s^2 (plausible)
    cm = read_peer_at2(path)
    values = np.array([float(v) for line in path.read_text().splitlines()[4:]
                       for v in line.split()])
    np.testing.assert_array_equal(cm.acceleration, values * 0.01)


def test_no_units_in_the_header_is_g_as_before(tmp_path):
    motion = read_peer_at2(_copy(tmp_path, "none.at2", None, STANDARD_GRAVITY))
    assert motion.metadata["units_in_file"] == "g (not stated; the PEER AT2 convention)"
    np.testing.assert_allclose(motion.acceleration, load_bundled().acceleration, rtol=1e-15)
    given = read_peer_at2(_copy(tmp_path, "none_gal.at2", None, 0.01), units="gal")
    np.testing.assert_allclose(given.acceleration, load_bundled().acceleration, rtol=1e-9)
    assert given.metadata["units_in_file"] == "cm/s^2 (given by the caller)"


# ------------------------------------------------------------------------- refused units


@pytest.mark.parametrize(
    ("units_line", "words"),
    [
        ("ACCELERATION TIME HISTORY IN UNITS OF FURLONG/S/S", ["'FURLONG/S/S'", "known units: g, "
                                                                "mg, gal, cm/s^2, m/s^2, mm/s^2"]),
        ("units: km/s/s", ["'km/s/s'", "do not know"]),
        ("VELOCITY IN UNITS OF CM/S", ["'CM/S'", "velocity"]),
        ("DISPLACEMENT IN UNITS OF CM", ["'CM'", "displacement"]),
    ],
)
def test_unknown_and_other_quantities_refused(tmp_path, units_line, words):
    path = _copy(tmp_path, "odd.at2", units_line, STANDARD_GRAVITY)
    with pytest.raises(RecordFormatError) as info:
        read_record(path)
    message = str(info.value)
    assert message.startswith("odd.at2, line 3: ")
    for word in words:
        assert word in message


def test_units_given_decide_when_the_header_is_unknown_but_not_against_it(tmp_path):
    odd = _copy(tmp_path, "odd.at2", "UNITS OF FURLONG", 0.01)
    np.testing.assert_allclose(read_record(odd, units="gal").acceleration,
                               load_bundled().acceleration, rtol=1e-9)
    g = _copy(tmp_path, "g.at2", "UNITS OF G", STANDARD_GRAVITY)
    with pytest.raises(RecordFormatError, match=r"g.at2, line 3: the header says .*'G'.*\(gal\)"):
        read_record(g, units="gal")
    assert read_record(g, units="g").pga == pytest.approx(load_bundled().pga, rel=1e-12)
    with pytest.raises(InputError, match=r"'units' parameter of read_peer_at2 .*'bananas'"):
        read_record(g, units="bananas")


def test_header_statements_that_disagree_are_refused(tmp_path):
    path = _copy(tmp_path, "two.at2", "UNITS OF G", STANDARD_GRAVITY)
    path.write_text(path.read_text().replace("(Peknold Version)", "(units: gal)"))
    with pytest.raises(RecordFormatError, match=r"two.at2, line 3: .*'gal' on line 1 and 'G'"):
        read_record(path)


# ----------------------------------------------------------------------------- plausibility


def test_gal_values_without_units_name_gal(tmp_path):
    path = _copy(tmp_path, "gal_unstated.at2", None, 0.01)
    with pytest.raises(RecordFormatError) as info:
        read_record(path)
    message = str(info.value)
    assert message.startswith("gal_unstated.at2, line 16: PGA 313 g")  # the peak's line
    assert "outside the plausible range 0.0001 to 5 g" in message
    assert "the values look like cm/s^2 (gal) (PGA 0.319 g)" in message
    assert "declare the units in the header" in message and "--units" in message


def test_a_header_that_says_g_of_gal_values_is_named(tmp_path):
    path = _copy(tmp_path, "wrong_header.at2", "UNITS OF G", 0.01)
    with pytest.raises(RecordFormatError, match=r"look like cm/s\^2 \(gal\).*the header says "
                                                r"'G' on line 3; correct the header"):
        read_record(path)


def test_too_small_names_the_larger_unit(tmp_path):
    path = _copy(tmp_path, "g_as_mm.at2", "UNITS OF MM/S/S", STANDARD_GRAVITY)
    with pytest.raises(RecordFormatError) as info:
        read_record(path)
    message = str(info.value)
    assert "PGA 3.25e-05 g" in message and "the values look like g (PGA 0.319 g)" in message
    assert likely_units(0.31882, "mm/s^2")[0][0] == "g"


# ---------------------------------------------------------------------------- text records


def _text_copy(tmp_path: Path, name: str, header: str, to_unit: float, columns: int) -> Path:
    acc = load_bundled().acceleration / to_unit
    rows = ([f"{0.02 * i:.2f}, {float(a)!r}" for i, a in enumerate(acc)] if columns == 2
            else [repr(float(a)) for a in acc])
    path = tmp_path / name
    path.write_text("\n".join([header, *rows]) + "\n" if header else "\n".join(rows) + "\n")
    return path


@pytest.mark.parametrize(("header", "units", "to_unit"), [
    ("# time [s], acceleration [gal]", None, 0.01),
    ("time, acc (m/s^2)", None, 1.0),
    ("# units: IN/S/S", None, 0.0254),
    ("", "mm/s^2", 0.001),
    ("", "ft/s^2", 0.3048),
    ("", "m/s2", 1.0),  # the spelling of earlier versions
])
@pytest.mark.parametrize("columns", [1, 2])
def test_text_records_in_other_units(tmp_path, header, units, to_unit, columns):
    path = _text_copy(tmp_path, "acc.txt", header, to_unit, columns)
    motion = read_text_record(path, 0.02 if columns == 1 else None, units)
    assert motion.dt == pytest.approx(0.02, rel=1e-12)
    np.testing.assert_allclose(motion.acceleration, load_bundled().acceleration, rtol=1e-9)


def test_spectrum_command_reads_text_records_with_units_and_dt(tmp_path, capsys):
    reference = load_bundled().pga
    one = _text_copy(tmp_path, "one.txt", "", 0.01, 1)
    assert main(["spectrum", str(one), "--units", "gal", "--dt", "0.02", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pga"] == pytest.approx(reference, rel=1e-9) and out["dt"] == 0.02
    two = _text_copy(tmp_path, "two.csv", "", 0.0254, 2)
    assert main(["spectrum", str(two), "--units", "in/s^2", "--record-dt", "0.02",
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["pga"] == pytest.approx(reference, rel=1e-9)


def test_run_command_reads_the_record_with_units_and_record_dt(tmp_path):
    """`dcfpb run --units --record-dt` reach the reader; --dt stays the analysis step."""
    from dcfpb.cli import build_parser
    from dcfpb.cli.run import building_run_inputs

    example = Path(__file__).resolve().parents[2] / "examples" / "five_storey.toml"
    one = _text_copy(tmp_path, "one.txt", "", 0.01, 1)
    args = build_parser().parse_args(["run", str(example), "--record", str(one), "--units", "gal",
                                      "--record-dt", "0.02", "--dt", "0.01"])
    assert isinstance(args, argparse.Namespace) and args.dt == 0.01
    _, _, motion = building_run_inputs(args, "dcfpb run")
    assert motion.dt == 0.02
    np.testing.assert_allclose(motion.acceleration, load_bundled().acceleration, rtol=1e-9)


def test_record_dt_must_agree_with_a_peer_file():
    assert read_record(ELCENTRO, dt=0.02).dt == 0.02
    with pytest.raises(InputError, match=r"'dt' parameter of read_record must agree .*0.02"):
        read_record(ELCENTRO, dt=0.01)


@pytest.mark.parametrize("units_line, to_unit", [
    ("ACCELERATION TIME HISTORY IN UNITS OF GAL", 0.01),
    ("ACCELERATION TIME HISTORY IN UNITS OF M/S/S", 1.0),
    ("ACCELERATION TIME HISTORY IN UNITS OF IN/S/S", 0.0254),
])
def test_copies_in_other_units_give_the_building_response_of_the_g_original(
        tmp_path, units_line, to_unit):
    """The tester's case: an M/S/S copy once ran 'successfully' 14.8 times too weak."""
    import structures

    example = Path(__file__).resolve().parents[2] / "examples" / "five_storey.toml"
    original = structures.run(example, ELCENTRO, model="precise")
    copy = structures.run(example, _copy(tmp_path, "copy.at2", units_line, to_unit),
                          model="precise")
    for name in ("bearing_displacement", "base_shear", "absolute_acceleration", "temperature"):
        scale = float(np.abs(original[name]).max())
        np.testing.assert_allclose(copy[name], original[name], rtol=0, atol=1e-9 * scale)
