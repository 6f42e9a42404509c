"""What every record reader needs from a file: its lines, its numbers, the units its header
states (:func:`record_units`) and the plausibility of what was read (:func:`check_plausible`).

The units of a record, in this order of authority:

1. a *statement* in the header: ``UNITS OF G``, ``The units are (g)``, ``units=cm/sec/sec``,
   ``Units: gal``. Statements that disagree, name a velocity or a length, or name an unknown
   unit are refused (the last unless the caller gives the units);
2. otherwise a *mention* of an acceleration unit anywhere in the header: ``Acceleration in g``,
   ``(g)``, ``[m/s^2]``, ``CM/SEC/SEC`` (mentions that disagree are refused);
3. the units given by the caller (``units=``, ``--units``), which must agree with the header's;
4. otherwise :data:`groundmotions.units.DEFAULT_UNITS` (g, the PEER AT2 convention).
"""

from __future__ import annotations

import re
from bisect import bisect_left
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import InputError
from dcfpb.common.files import available_memory
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_real
from groundmotions.records import RecordFormatError
from groundmotions.units import (
    DEFAULT_UNITS,
    DT_LIMITS_S,
    MAX_DURATION_S,
    PGA_LIMITS_G,
    TO_M_PER_S2,
    TYPICAL_PGA_G,
    UNIT_NAMES,
    UNSTATED_MAX_PGA_G,
    check_units,
    describe_units,
    likely_units,
    parse_units,
    quantity_of,
)

__all__ = ["RecordUnits", "agreeing_step", "check_finite", "check_plausible",
           "check_record_plausible", "check_step", "first_non_number", "line_of_value",
           "read_lines", "record_units", "timing_problem"]

_OTHER_QUANTITY = re.compile(r"\b(VELOCITY|DISPLACEMENT)\s+TIME\s+(HISTORY|SERIES)", re.IGNORECASE)
_STATEMENT = re.compile(
    r"\bunits?\s*(?:(?:used\s+)?in\s+(?:the|this)\s+(?:file|record|data)(?:\s+(?:are|is)|\s*:)"
    r"|of|are|is|in|=|:)\s*(?:of\s+)?[(\[]?\s*"
    r"(?P<unit>[^\s,;()\[\]]+(?:\s*[*.·]?\s*s\s*\^?\s*-\s*2)?)",
    re.IGNORECASE,
)
_BRACKETED = re.compile(r"[(\[]\s*([^()\[\]]{1,24}?)\s*[)\]]")
_AFTER_IN = re.compile(r"\bin\s+([^\s,;()\[\]]+)", re.IGNORECASE)
_COMPOUND = re.compile(r"(?<![\w/^*])[a-z]+\s*/\s*(?:s|sec)\s*(?:/\s*(?:s|sec)|(?:\^|\*\*)?\s*2|²)"
                       r"(?![\w/^*])", re.IGNORECASE)
_AROUND_OPERATORS = re.compile(r"\s*([/^*·])\s*")
_KNOWN = ", ".join(UNIT_NAMES)


class RecordUnits(NamedTuple):
    """The units of a record's values and where they come from."""

    name: str
    """Canonical unit (a key of :data:`groundmotions.units.TO_M_PER_S2`)."""
    factor: float
    """Factor to [m/s^2]."""
    source: str
    """``"header"``, ``"given"`` or ``"default"``."""
    line: int | None
    """Line of the header that states the units (None when not from the header)."""
    written: str
    """The units as written in the header (or as given)."""


MAX_RECORD_BYTES = 256 * 2**20
"""Largest record file read [bytes]: some 16 million values, far past the longest records and
the 2,000,000 steps a run takes unless told otherwise; a larger file is refused before it is
read (a file that is not a record, or one gone wrong)."""

READ_MEMORY_FACTOR = 12
"""Memory the reading of a text file takes per byte of it (bytes, text, lines, numbers)."""


def check_record_file(path: Path) -> None:
    """Refuse, before reading it, a device or pipe (which may never end), a record
    file past :data:`MAX_RECORD_BYTES` or the memory available, or one that is gzip-compressed
    (its bytes are no text)."""
    if path.exists() and not path.is_file() and not path.is_dir():  # a folder: OSError
        raise InputError(f"{path}: not a regular file (a device or a pipe, which may never "
                         "end); give the record file itself.")
    size = path.stat().st_size
    limit = MAX_RECORD_BYTES
    memory = available_memory()
    if memory is not None:
        limit = min(limit, memory // READ_MEMORY_FACTOR)
    if size > limit:
        raise InputError(
            f"{path}: {size / 1e6:,.1f} MB, more than the {limit / 1e6:,.0f} MB a ground-motion "
            f"record file may have here (at most {MAX_RECORD_BYTES / 1e6:,.0f} MB, some 16 "
            "million values, and what the memory available can read); is it a record? Cut it "
            "to the part to analyse.")
    with path.open("rb") as handle:
        if handle.read(2) == b"\x1f\x8b":
            raise InputError(f"{path}: is gzip-compressed, not a text record; decompress it "
                             "first (gunzip) and give the text file.")


def read_lines(path: Path) -> list[str]:
    """Lines of a text file (UTF-8, else Latin-1) without their ends; LF, CR LF, CR CR LF
    and CR each count once. A file too large to be a record, or gzip-compressed, is refused
    first (:func:`check_record_file`)."""
    check_record_file(path)
    raw = path.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    if "\n" in text:
        return [line.rstrip("\r") for line in text.split("\n")]
    return text.split("\r")


def first_non_number(tokens: Iterable[str]) -> str:
    """The first token that ``float`` cannot read ("" when there is none)."""
    for token in tokens:
        try:
            float(token)
        except ValueError:
            return token
    return ""


def line_of_value(line_ends: Sequence[tuple[int, int]], index: int) -> int:
    """Line number of value ``index`` (0-based), from ``(line number, values so far)`` pairs."""
    return line_ends[bisect_left([end for _, end in line_ends], index + 1)][0]


def check_finite(path: Path, values: np.ndarray, line_ends: Sequence[tuple[int, int]]) -> None:
    """Raise on the first NaN or infinite value, naming its line (``float`` reads 'nan')."""
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        index = int(bad[0])
        raise RecordFormatError(path, line_of_value(line_ends, index),
                                f"value {index + 1} is {float(values[index])!r}, not finite")


def check_step(dt: object, owner: str) -> float:
    """A time step given by the caller [s], > 0 and finite, else `InputError` (`InputTypeError`
    for one that is not a number)."""
    return check_real(dt, "dt", owner, low=0.0, low_open=True)


def agreeing_step(dt: object, step: float, owner: str, source: str) -> float:
    """A time step given by the caller [s] (:func:`check_step`) that must agree to 0.1 % with
    the file's ``step`` [s], which ``source`` names ("the DT of X.AT2 (DT = 0.01 s)")."""
    given = check_step(dt, owner)
    if abs(given - step) > 1e-3 * step:
        raise InputError(f"The 'dt' parameter of {owner} must agree with {source}. Got {dt!r} "
                         "instead.")
    return given


def _squeezed(line: str) -> str:
    """The line without blanks around ``/``, ``^``, ``*`` and ``·`` (``cm / s^2`` -> ``cm/s^2``)."""
    return _AROUND_OPERATORS.sub(r"\1", line)


def _statements(header: Sequence[tuple[int, str]]) -> list[tuple[int, str]]:
    found = []
    for number, line in header:
        for match in _STATEMENT.finditer(_squeezed(line)):
            written = match["unit"].strip().rstrip(".:")
            if re.search(r"[a-zA-Z]", written):  # "unit 5", "units: 12" are not units
                found.append((number, written))
    return found


def _mentions(header: Sequence[tuple[int, str]]) -> list[tuple[int, str, str]]:
    found = []
    for number, text in header:
        line = _squeezed(text)
        candidates = [m.group(1) for m in _BRACKETED.finditer(line)]
        candidates += [m.group(1) for m in _AFTER_IN.finditer(line)]
        candidates += [m.group(0) for m in _COMPOUND.finditer(line)]
        for written in candidates:
            name = parse_units(written)
            if name is not None:
                found.append((number, written.strip(), name))
    return found


def _not_acceleration(quantity: str) -> str:
    """The reason a velocity or displacement record is refused, and what to read instead."""
    return (f"this is a {quantity} record, not an acceleration: the readers take acceleration "
            "records only (PEER .AT2, not .VT2 or .DT2); read the acceleration record (.AT2) "
            "of the same component")


def _from_header(path: Path, header: Sequence[tuple[int, str]],
                 given: str | None) -> tuple[str, int, str] | None:
    """(canonical unit, line, as written) stated or mentioned by the header, or None."""
    for number, line in header:
        other = _OTHER_QUANTITY.search(line)
        if other:
            raise RecordFormatError(path, number, _not_acceleration(other.group(1).lower()))
    known: list[tuple[int, str, str]] = []
    for number, written in _statements(header):
        quantity = quantity_of(written)
        if quantity is None:
            if given is None:
                raise RecordFormatError(
                    path, number, f"the header states units {written!r}, which the readers do "
                    f"not know; known units: {_KNOWN} (with spellings such as CM/SEC/SEC, "
                    "M/S/S or IN/S/S); correct the header or declare the units (--units)",
                )  # fmt: skip
            continue
        if quantity[0] != "acceleration":
            raise RecordFormatError(
                path, number, f"the header states units {written!r}, a {quantity[0]} "
                f"({quantity[1]}): {_not_acceleration(quantity[0])}",
            )  # fmt: skip
        known.append((number, written, quantity[1]))
    kind = "states"
    if not known:
        known, kind = _mentions(header), "mentions"
    for number, written, name in known[1:]:
        if name != known[0][2]:
            first_line, first_written, _ = known[0]
            raise RecordFormatError(
                path, number, f"the header {kind} units {first_written!r} on line {first_line} "
                f"and {written!r} on this line: which are the values in? Correct the header",
            )  # fmt: skip
    return (known[0][2], known[0][0], known[0][1]) if known else None


def record_units(path: Path, header: Sequence[tuple[int, str]], given: object,
                 owner: str) -> RecordUnits:
    """The units of a record's values, by the order of authority of the module docstring, from
    the ``header`` lines with their numbers and the caller's units ``given`` (any spelling
    :func:`groundmotions.units.parse_units` reads, or None); messages name ``path`` and ``owner``.

    Raises
    ------
    RecordFormatError
        A velocity or displacement record, unknown units, statements that disagree, or given
        units that disagree with the header's.
    InputError
        ``given`` is not an acceleration unit.
    """
    name = None if given is None else check_units(given, owner)
    stated = _from_header(path, header, name)
    if stated is not None:
        unit, line, written = stated
        if name is not None and name != unit:
            raise RecordFormatError(
                path, line, f"the header says the values are in {written!r} "
                f"({describe_units(unit)}) but the units given (--units / units=) are "
                f"{describe_units(name)}; correct the header or leave the units out",
            )  # fmt: skip
        return RecordUnits(unit, TO_M_PER_S2[unit], "header", line, written)
    if name is not None:
        return RecordUnits(name, TO_M_PER_S2[name], "given", None, str(given))
    return RecordUnits(DEFAULT_UNITS, TO_M_PER_S2[DEFAULT_UNITS], "default", None, "")


def check_plausible(path: Path, values: np.ndarray, units: RecordUnits,
                    line_ends: Sequence[tuple[int, int]]) -> None:
    """Refuse a record whose PGA lies outside :data:`groundmotions.units.PGA_LIMITS_G` (above
    :data:`groundmotions.units.UNSTATED_MAX_PGA_G` for units taken as g by default), for the
    ``values`` as written in the file in ``units``, and ``line_ends`` the ``(line number, values
    so far)`` pairs; the `RecordFormatError` names the line of the peak, the PGA, the range and
    the units that would bring it into :data:`groundmotions.units.TYPICAL_PGA_G`."""
    index = int(np.argmax(np.abs(values)))
    peak = float(abs(values[index]))
    pga = peak * (units.factor / STANDARD_GRAVITY)  # never overflows: factor / g <= 1
    low, high = PGA_LIMITS_G
    # read as g with no unit statement: values in m/s^2 would read as 2 to 10 g
    unstated = units.source == "default" and UNSTATED_MAX_PGA_G < pga <= high
    if low <= pga <= (UNSTATED_MAX_PGA_G if unstated else high):
        return
    candidates = likely_units(peak, units.name)
    if candidates:
        look = " or ".join(f"{describe_units(name)} (PGA {g:.3g} g)" for name, g in candidates)
        if "cm/s^2" in dict(candidates) and units.name != "mg":  # mg is 2 % off gal
            look += f" or mg (PGA {peak * TO_M_PER_S2['mg'] / STANDARD_GRAVITY:.3g} g)"
        look = f"the values look like {look}"
    else:
        look = f"no known unit brings it into {TYPICAL_PGA_G[0]:g}-{TYPICAL_PGA_G[1]:g} g"
    if not candidates:
        advice = "check the values"
    elif units.source == "header":
        advice = (f"the header says {units.written!r} on line {units.line}; correct the header")
    elif units.source == "given":
        advice = f"check the units given (--units / units=): {describe_units(units.name)}"
    else:
        advice = "declare the units in the header (e.g. 'UNITS OF CM/S/S') or with --units"
    if unstated:
        raise RecordFormatError(
            path, line_of_value(line_ends, index),
            f"PGA {pga:.3g} g (value {values[index]:.6g} read as g, the default: the file "
            f"states no units) is above {UNSTATED_MAX_PGA_G:g} g, the most a record whose units "
            f"are not stated may have: {look}; {advice} ('UNITS OF G' or --units g if it is in "
            "g indeed)",
        )  # fmt: skip
    raise RecordFormatError(
        path, line_of_value(line_ends, index),
        f"PGA {pga:.3g} g (value {values[index]:.6g} read as {describe_units(units.name)}) is "
        f"outside the plausible range {low:g} to {high:g} g: {look}; {advice}",
    )


def timing_problem(dt: float, npts: int) -> str | None:
    """Why a record of ``npts`` samples at the step ``dt`` [s] is implausible, or None: a step
    outside :data:`groundmotions.units.DT_LIMITS_S` or a duration ``(npts - 1) * dt`` beyond
    :data:`groundmotions.units.MAX_DURATION_S`. The limits of every command that reads a record
    (``run``, ``spectrum``, ``suite``, ``compare-opensees`` and the pair readers)."""
    low, high = DT_LIMITS_S
    if not low <= dt <= high:
        reason = (f"a time step of {dt:.6g} s is outside the plausible range {low:g} to {high:g} s "
                  "of a ground-motion record")
        if low <= dt * 1e-3 <= high:
            reason += f" (in milliseconds it would be {dt * 1e-3:.6g} s)"
        return reason
    duration = (npts - 1) * dt
    if duration > MAX_DURATION_S:
        return (f"{npts} samples at {dt:.6g} s last {duration:.6g} s, longer than the plausible "
                f"{MAX_DURATION_S:g} s of a ground-motion record")
    return None


def check_record_plausible(path: Path, values: np.ndarray, units: RecordUnits,
                           line_ends: Sequence[tuple[int, int]], dt: float, dt_line: int,
                           dt_advice: str) -> None:
    """The plausibility of a record read from a file, the one check of every reader: its PGA
    (:func:`check_plausible`), then its time step ``dt`` [s] and duration
    (:func:`timing_problem`); the `RecordFormatError` of the latter names ``dt_line`` (where
    the step is written) and, for a step too long, ends with ``dt_advice`` (how to state the
    step in milliseconds)."""
    check_plausible(path, values, units, line_ends)
    problem = timing_problem(dt, values.size)
    if problem is not None:
        advice = dt_advice if dt > DT_LIMITS_S[1] else "check the time step and the count"
        raise RecordFormatError(path, dt_line, f"{problem}; {advice}")
