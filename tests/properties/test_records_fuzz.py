"""Fuzzing the record readers (hypothesis): whatever a file holds, reading it either gives a
`GroundMotion` or raises the project's own `InputError`, never another exception.

Four kinds of input: random bytes; random header lines around a valid PEER record; random
numeric garbage (huge, tiny, non-finite, mis-counted values and NPTS/DT lines); random one- and
two-column text records with random ``dt`` and ``units`` arguments. A loaded record is also
checked to be what the reader promises: finite, at least 2 samples, PGA, dt and duration within
the plausible ranges.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dcfpb.common.errors import InputError
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.readers import read_peer_at2, read_record, read_text_record
from groundmotions.records import GroundMotion
from groundmotions.units import DT_LIMITS_S, MAX_DURATION_S, PGA_LIMITS_G, UNIT_NAMES

fuzz = settings(max_examples=250, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture])

PEER_LINES = [
    "PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.",
    "CHALFANT VALLEY 07/21/86 14:42, BENTON, 360 (CDMG STATION 54100)",
    "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz LP=33.0 Hz",
    "NPTS=    12, DT= .01000 SEC",
    "   .1E-01  -.2E-01   .3E-01   .4E-01   .5E-01",
    "  -.6E-01   .7E-01  -.8E-01   .9E-01   .1E+00",
    "  -.1E-01   .2E-01",
]
WORDS = ["NPTS", "NPTS=", "DT=", "DT", ",", "=", "SEC", "UNITS", "OF", "ARE", "IN", "G", "GAL",
         "CM/S/S", "M/S/S", "IN/S/S", "cm/s", "furlong", "(g)", "[m/s^2]", "VELOCITY",
         "TIME HISTORY", "*** End Data ***", "#", "%", ";", "\t", "\r", "\r\n", "\x00", "é",
         "\ufeff", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf", "0", "-0.0", "1", "2",
         "99999999999999999999999", "1" * 5000, "0.02", "-0.02", "1e400", "0x1p3", "1_0",
         "٣", "½", "1,5", ".", "E", "e-3", "+", "-"]
_counter = itertools.count()


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("fuzz")


def _file(folder: Path, data: bytes, suffix: str) -> Path:
    path = folder / f"f{next(_counter)}{suffix}"
    path.write_bytes(data)
    return path


def _loads_or_input_error(read, *args, **kwargs) -> GroundMotion | None:
    """Call the reader; a GroundMotion must be sound, any error must be an InputError."""
    try:
        motion = read(*args, **kwargs)
    except InputError:
        return None
    assert isinstance(motion, GroundMotion)
    assert motion.npts >= 2 and motion.dt > 0 and np.all(np.isfinite(motion.acceleration))
    low, high = PGA_LIMITS_G
    assert low * (1 - 1e-12) <= motion.pga / STANDARD_GRAVITY <= high * (1 + 1e-12)
    assert DT_LIMITS_S[0] <= motion.dt <= DT_LIMITS_S[1] and motion.duration <= MAX_DURATION_S
    return motion


@fuzz
@given(data=st.binary(max_size=400), suffix=st.sampled_from([".at2", ".AT2", ".txt", ".csv"]))
def test_random_bytes(folder, data, suffix):
    path = _file(folder, data, suffix)
    _loads_or_input_error(read_record, path)
    _loads_or_input_error(read_peer_at2, path)
    _loads_or_input_error(read_text_record, path, 0.01)


@fuzz
@given(
    edits=st.lists(
        st.tuples(st.integers(0, len(PEER_LINES)), st.booleans(),
                  st.lists(st.sampled_from(WORDS) | st.text(max_size=12), max_size=6)),
        min_size=1, max_size=4),
    newline=st.sampled_from(["\n", "\r\n", "\r\r\n", "\r"]),
    units=st.none() | st.sampled_from([*UNIT_NAMES, "M/S/S", "m/s2"]),
)
def test_random_headers_around_a_valid_record(folder, edits, newline, units):
    lines = list(PEER_LINES)
    for where, replace, words in edits:
        text = " ".join(words)
        if replace and where < len(lines):
            lines[where] = text
        else:
            lines.insert(where, text)
    path = _file(folder, newline.join(lines).encode("utf-8", "surrogatepass"), ".at2")
    _loads_or_input_error(read_record, path, units=units)


moderate = st.floats(-2.0, 2.0, allow_nan=False)
numbers = st.one_of(
    moderate, moderate, moderate, moderate,  # mostly values a record may hold
    st.floats(allow_nan=True, allow_infinity=True, width=64),
    st.sampled_from([1e308, -1e308, 5e-324, 0.0, 1e-5, 1e5, 300.0]),
)
steps = st.one_of(st.sampled_from([0.01, 0.02, 0.005]), numbers)


@st.composite
def npts_and_values(draw):
    values = draw(st.lists(numbers, max_size=30))
    npts = draw(st.one_of(st.just(len(values)), st.just(len(values)), st.integers(-3, 30),
                          st.sampled_from([10**9, 10**18, 10**40])))
    return npts, values


@fuzz
@given(
    counted=npts_and_values(),
    dt=st.one_of(steps.map(repr), st.sampled_from(["", "abc", ".02", "0"])),
    per_line=st.integers(1, 8),
    form=st.sampled_from(["NPTS= {n}, DT= {dt} SEC", "{n} {dt} NPTS, DT", "NPTS={n} dt={dt},"]),
    units_line=st.sampled_from(["UNITS OF G", "UNITS OF GAL", "Acceleration in m/s/s", "",
                                "UNITS OF FURLONG", "UNITS OF CM/SEC"]),
)
def test_numeric_garbage(folder, counted, dt, per_line, form, units_line):
    npts, values = counted
    rows = [" ".join(repr(v) for v in values[i:i + per_line])
            for i in range(0, len(values), per_line)]
    text = "\n".join(["PEER", "EVENT", units_line, form.format(n=npts, dt=dt), *rows]) + "\n"
    path = _file(folder, text.encode(), ".at2")
    _loads_or_input_error(read_record, path)


@fuzz
@given(
    values=st.lists(numbers, min_size=0, max_size=40),
    columns=st.sampled_from([1, 2]),
    separator=st.sampled_from([" ", ",", ";", "\t", ", "]),
    header=st.lists(st.sampled_from(["# units: gal", "time,acc", "# acceleration [m/s^2]",
                                     "% (g)", "# units: bananas", "t [s] a [in/s/s]",
                                     "# velocity [cm/s]"]), max_size=2),
    dt=st.none() | steps,
    own_times=st.booleans(),
    units=st.none() | st.sampled_from([*UNIT_NAMES, "m/s2", "bananas"]),
)
def test_random_text_records(folder, values, columns, separator, header, dt, own_times, units):
    if columns == 2:
        times = list(reversed(values)) if own_times else [0.01 * i for i in range(len(values))]
        rows = [f"{t!r}{separator}{v!r}" for t, v in zip(times, values, strict=True)]
    else:
        rows = [repr(v) for v in values]
    path = _file(folder, "\n".join([*header, *rows]).encode(), ".txt")
    _loads_or_input_error(read_text_record, path, dt, units)
    _loads_or_input_error(read_record, path, dt=dt, units=units)
