"""Readers and the GroundMotion object: every shared file, every header variant, every bad file."""

from __future__ import annotations

import csv
import hashlib
import pickle
from importlib import resources

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.bundled import bundled_names, load_bundled
from groundmotions.readers import read_peer_at2, read_record, read_text_record
from groundmotions.records import GroundMotion, RecordFormatError

PEER_HEADER = (
    "PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.\n"
    "CHALFANT VALLEY 07/21/86 14:42, BENTON, 360 (CDMG STATION 54100)\n"
    "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz LP=33.0 Hz\n"
)


def _manifest(shared_dir):
    with open(shared_dir / "groundmotions" / "manifest.csv", newline="") as f:
        return list(csv.DictReader(f))


def _decimals(text: str) -> int:
    return len(text.partition(".")[2])


# ------------------------------------------------------------------------- the shared suite


@pytest.mark.shared
def test_every_suite_file_matches_the_manifest(shared_dir):
    """60 files: value count, dt, PGA to the printed precision, time of the peak."""
    rows = _manifest(shared_dir)
    assert len(rows) == 60
    for row in rows:
        motion = read_peer_at2(shared_dir / "groundmotions" / row["file"])
        where = row["file"]
        assert motion.npts == int(row["npts"]) == int(row["n_values"]), where
        assert motion.dt == pytest.approx(float(row["dt_s"]), rel=1e-12), where
        pga_g = motion.pga / STANDARD_GRAVITY
        assert abs(pga_g - float(row["pga_g"])) <= 0.5 * 10.0 ** -_decimals(row["pga_g"]), where
        t_peak = motion.time[np.argmax(np.abs(motion.acceleration))]
        assert abs(t_peak - float(row["t_pga_s"])) <= 0.5 * 10.0 ** -_decimals(row["t_pga_s"])
        assert motion.metadata["npts_dt_line"] == row["npts_dt_line"], where
        assert motion.processing == (f"read from {row['file']} (g -> m/s^2)",)


@pytest.mark.shared
def test_peer_line_2_and_3_fields_match_the_manifest(shared_dir):
    """Event, date, time, station, component, agency, filter corners (the 59 PEER files)."""
    for row in _manifest(shared_dir):
        if row["file"] == "elCentro.AT2":  # free-text header: the manifest was filled by hand
            continue
        meta = read_peer_at2(shared_dir / "groundmotions" / row["file"]).metadata
        got = [meta[k] or "" for k in ("event", "date", "time", "station", "component", "agency")]
        want = [row[k] for k in ("event", "date", "time_hhmm", "station", "component", "agency")]
        assert got == want, row["file"]
        assert meta["date"].startswith(row["year"])
        assert meta["highpass_hz"] == float(row["hp_hz"]), row["file"]
        assert meta["lowpass_hz"] == float(row["lp_hz"]), row["file"]


@pytest.mark.shared
def test_station_with_parentheses_keeps_them(shared_dir):
    meta = read_peer_at2(shared_dir / "groundmotions" / "ANLA196.AT2").metadata
    assert meta["station"] == "ANL-767 REACTOR PLANT (BASEMENT)"
    assert meta["component"] == "196"
    assert meta["agency"] is None


@pytest.mark.shared
@pytest.mark.parametrize(
    ("file", "npts", "dt", "npts_line", "trailer"),
    [
        ("EXAMPLES_ExampleScripts_ARL360.at2", 2000, 0.02, 4, ()),
        ("EXAMPLES_verification_elCentro.at2", 1559, 0.02, 7, ("*** End Data ***",)),
        ("Workshops_OpenSeesDays_Steel2dModels_Oak_2_50_5_FN.AT2", 7997, 0.005, 7, ()),
    ],
)
def test_header_variants_read(shared_dir, file, npts, dt, npts_line, trailer):
    motion = read_peer_at2(shared_dir / "groundmotions" / "variants" / file)
    assert motion.npts == npts
    assert motion.dt == dt
    assert motion.metadata["npts_dt_line_number"] == npts_line
    assert motion.metadata["trailer_lines"] == trailer
    assert motion.metadata["units_in_file"] == "g"
    assert not any("\r" in line for line in motion.metadata["header_lines"])


@pytest.mark.shared
def test_cr_cr_lf_file_keeps_peer_fields(shared_dir):
    file = shared_dir / "groundmotions" / "variants" / "EXAMPLES_ExampleScripts_ARL360.at2"
    meta = read_peer_at2(file).metadata
    assert (meta["event"], meta["date"], meta["time"]) == ("NORTHRIDGE", "1994-01-17", "1231")
    assert (meta["station"], meta["component"]) == ("ARLETA", "360")


@pytest.mark.shared
def test_verification_el_centro_holds_the_suite_values(shared_dir):
    variant = read_peer_at2(
        shared_dir / "groundmotions" / "variants" / "EXAMPLES_verification_elCentro.at2"
    )
    suite = read_peer_at2(shared_dir / "groundmotions" / "elCentro.AT2")
    np.testing.assert_array_equal(variant.acceleration, suite.acceleration)


@pytest.mark.shared
def test_bundled_file_is_the_shared_el_centro_byte_for_byte(shared_dir):
    row = next(r for r in _manifest(shared_dir) if r["file"] == "elCentro.AT2")
    data = resources.files("groundmotions").joinpath("data", "elcentro_1940_ns.at2").read_bytes()
    assert hashlib.sha256(data).hexdigest() == row["sha256"]


# --------------------------------------------------------------------------- bundled records


def test_bundled_el_centro_loads_without_shared_data():
    motion = load_bundled("elcentro")
    assert bundled_names() == ("elcentro",)
    assert (motion.npts, motion.dt, motion.name) == (1559, 0.02, "El Centro 1940 N-S")
    assert motion.pga / STANDARD_GRAVITY == pytest.approx(0.31882, abs=5e-6)
    assert motion.metadata["licence"].startswith("public domain")
    with pytest.raises(ValueError, match=r"'name' parameter of load_bundled"):
        load_bundled("kobe")


# ------------------------------------------------------------------- accepted header forms


@pytest.mark.parametrize(
    "npts_line",
    [
        "NPTS=  6, DT= .01000 SEC",
        "NPTS=   6, dt=  .01000",
        "NPTS=   6, DT=   .0100 SEC,",  # NGA-West2, trailing comma
        "6 0.0100 NPTS, DT",  # NGA "values first"
        "npts = 6 , dt = 1.0E-02 sec",
    ],
)
@pytest.mark.parametrize("newline", ["\n", "\r\n", "\r\r\n", "\r"])
def test_npts_dt_forms_and_line_ends(tmp_path, npts_line, newline):
    text = PEER_HEADER + npts_line + "\n  .1E-01  -.2E-01   .3E-01\n  .4E-01   .5E-01  -.6E-01\n"
    path = tmp_path / "rec.at2"
    path.write_bytes(text.replace("\n", newline).encode())
    motion = read_peer_at2(path)
    assert motion.dt == 0.01
    np.testing.assert_allclose(
        motion.acceleration, np.array([1, -2, 3, 4, 5, -6]) * 0.01 * STANDARD_GRAVITY, rtol=1e-15
    )
    assert motion.metadata["station"] == "BENTON"


# ------------------------------------------------------------------------------- bad files

BAD_FILES = {
    # name: (text, line named, words in the message)
    "truncated.at2": (PEER_HEADER + "NPTS=  8, DT= .01 SEC\n 1. 2. 3.\n 4. 5. 6.\n", 6,
                      "expected 8 values (NPTS) but the file ends after 6"),
    "nan.at2": (PEER_HEADER + "NPTS=  6, DT= .01 SEC\n 1. 2. 3.\n 4. NaN 6.\n", 6, "not finite"),
    "inf.at2": (PEER_HEADER + "NPTS=  6, DT= .01 SEC\n 1. 2. 3.\n 4. 5. -inf\n", 6, "not finite"),
    "no_dt.at2": (PEER_HEADER + "NPTS=  6\n 1. 2. 3.\n 4. 5. 6.\n", 4, "no DT"),
    "too_many.at2": (PEER_HEADER + "NPTS=  4, DT= .01 SEC\n 1. 2. 3.\n 4. 5. 6.\n", 6,
                     "value 5 is on this line"),
    "token.at2": (PEER_HEADER + "NPTS=  6, DT= .01 SEC\n 1. 2. 3.\n 4. 5.O 6.\n", 6, "'5.O'"),
    "early_end.at2": (PEER_HEADER + "NPTS=  9, DT= .01 SEC\n 1. 2. 3.\n 4. 5. 6.\n"
                      "*** End Data ***\n", 7, "after 6 values"),
    "no_npts.at2": (PEER_HEADER + " 1. 2. 3.\n", 4, "numbers begin before any NPTS/DT line"),
    "bad_dt.at2": (PEER_HEADER + "6 abc NPTS, DT\n 1. 2. 3.\n 4. 5. 6.\n", 4, "'abc'"),
    "zero_dt.at2": (PEER_HEADER + "NPTS=  6, DT= 0.0 SEC\n 1. 2. 3.\n 4. 5. 6.\n", 4, "DT > 0"),
    "velocity.vt2": (PEER_HEADER.replace("ACCELERATION", "VELOCITY")
                     + "NPTS=  3, DT= .01 SEC\n 1. 2. 3.\n", 3, "velocity record"),
    "crcrlf.at2": ((PEER_HEADER + "NPTS=  6, DT= .01 SEC\n 1. 2. 3.\n 4. x 6.\n")
                   .replace("\n", "\r\r\n"), 6, "'x'"),
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(BAD_FILES))
def test_bad_file_names_file_and_line(tmp_path, name):
    text, line, words = BAD_FILES[name]
    path = tmp_path / name
    path.write_bytes(text.encode())
    with pytest.raises(RecordFormatError) as info:
        read_peer_at2(path)
    message = str(info.value)
    assert message.startswith(f"{name}, line {line}: "), message
    assert words in message
    assert (info.value.file, info.value.line) == (name, line)


def test_record_format_error_is_a_value_error_and_pickles():
    error = RecordFormatError("/some/where/x.at2", 12, "bad")
    assert isinstance(error, ValueError)
    again = pickle.loads(pickle.dumps(error))
    assert (str(again), again.file, again.line) == ("x.at2, line 12: bad", "x.at2", 12)


# ----------------------------------------------------------------------------- text records


def test_one_column_text_needs_dt(tmp_path):
    path = tmp_path / "one.txt"
    path.write_text("# my record, in g\n0.0\n0.1\n-0.2\n0.05\n")
    motion = read_text_record(path, dt=0.01)
    np.testing.assert_allclose(motion.acceleration, [0, 0.1 * 9.80665, -0.2 * 9.80665, 0.4903325])
    assert motion.metadata["header_lines"] == ("# my record, in g",)
    with pytest.raises(ValueError, match=r"'dt' parameter of read_text_record .*one.txt"):
        read_text_record(path)


def test_two_column_text_infers_dt_and_rebases_time(tmp_path):
    path = tmp_path / "two.csv"
    path.write_text("time,acc\n1.00,0.5\n1.02,-1.0\n1.04,0.25\n1.06,0.0\n")
    motion = read_text_record(path, units="m/s2")
    assert motion.dt == pytest.approx(0.02, rel=1e-12)
    np.testing.assert_array_equal(motion.acceleration, [0.5, -1.0, 0.25, 0.0])
    assert motion.metadata["start_time"] == 1.0
    assert "time re-based" in motion.processing[-1]
    with pytest.raises(ValueError, match=r"'dt' parameter of read_text_record must agree"):
        read_text_record(path, dt=0.01, units="m/s2")


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("0.00 1\n0.01 2\n0.03 3\n0.04 4\n0.05 5\n", 3, "not uniformly sampled"),
        ("0.00 1\n0.01 2\n0.02 abc\n", 3, "'abc'"),
        ("0.00 1\n0.01 2\n0.02\n", 3, "expected 2 column(s) as on line 1"),
        ("0.00 1\n0.01 nan\n", 2, "not finite"),
        ("1 2 3 4 5\n", 1, "expected 1 or 2 columns"),
    ],
)
def test_bad_text_files(tmp_path, text, line, words):
    path = tmp_path / "bad.txt"
    path.write_text(text)
    with pytest.raises(RecordFormatError) as info:
        read_text_record(path)
    assert str(info.value).startswith(f"bad.txt, line {line}: ")
    assert words in str(info.value)


def test_read_record_dispatches_on_extension_and_content(tmp_path):
    peer_text = PEER_HEADER + "NPTS=  3, DT= .01 SEC\n 1. 2. 3.\n"
    (tmp_path / "a.AT2").write_text(peer_text)
    (tmp_path / "a_peer.txt").write_text(peer_text)
    (tmp_path / "b.txt").write_text("0 1\n0.05 2\n0.1 3\n")
    assert read_record(tmp_path / "a.AT2").metadata["format"] == "PEER AT2"
    assert read_record(tmp_path / "a_peer.txt").metadata["format"] == "PEER AT2"
    motion = read_record(tmp_path / "b.txt", units="m/s2")
    assert (motion.metadata["format"], motion.dt) == ("text, 2 column(s)", 0.05)


# ---------------------------------------------------------------------------- GroundMotion


def test_ground_motion_properties_and_new_objects():
    source = np.array([0.0, 1.0, -3.0, 2.0, 0.5])
    motion = GroundMotion(source, 0.1, "m")
    source[1] = 99.0  # the record holds its own copy
    assert motion.acceleration[1] == 1.0
    with pytest.raises(ValueError):
        motion.acceleration[0] = 1.0  # read-only
    assert (motion.npts, motion.duration, motion.pga) == (5, pytest.approx(0.4), 3.0)
    np.testing.assert_allclose(motion.time, [0, 0.1, 0.2, 0.3, 0.4])

    scaled = motion.scaled(2.0).negated().truncated(0.2)
    np.testing.assert_array_equal(scaled.acceleration, [-0.0, -2.0, 6.0])
    assert scaled.processing == ("scaled by 2", "negated", "truncated to 0.2 s (3 samples)")
    assert motion.processing == ()  # the original is untouched


@pytest.mark.parametrize(
    ("kwargs", "error", "pattern"),
    [
        ({"acceleration": [0.0, 1.0], "dt": 0.0}, ValueError, r"'dt' parameter of GroundMotion"),
        ({"acceleration": [0.0, np.nan], "dt": 0.1}, ValueError, r"'acceleration' .*index 1"),
        ({"acceleration": [1.0], "dt": 0.1}, ValueError, r"at least 2 values"),
        ({"acceleration": [0.0, 1.0], "dt": 0.1, "name": 3}, TypeError, r"'name' parameter"),
        ({"acceleration": [0.0, 1.0], "dt": 0.1, "processing": "x"}, TypeError, r"'processing'"),
    ],
)
def test_ground_motion_rejects_bad_parameters(kwargs, error, pattern):
    with pytest.raises(error, match=pattern):
        GroundMotion(**kwargs)


def test_methods_reject_bad_parameters():
    motion = GroundMotion([0.0, 1.0, 2.0], 0.1)
    with pytest.raises(ValueError, match=r"'factor' parameter of GroundMotion.scaled"):
        motion.scaled(np.inf)
    with pytest.raises(ValueError, match=r"'duration' parameter of GroundMotion.truncated"):
        motion.truncated(0.05)  # would leave a single sample
