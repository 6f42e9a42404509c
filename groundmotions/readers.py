"""Readers of ground-motion record files (the records bundled with the package: `records`).

``read_peer_at2``
    PEER .AT2 files in every header layout met so far: ``NPTS=  7996, DT= .00500 SEC``,
    ``NPTS=   1451, dt=  .02000``, ``NPTS=   7998, DT=   .0050 SEC,`` (trailing comma), the NGA
    "values first" ``7997 0.0050 NPTS, DT`` and free-text headers of any length (the NPTS/DT line
    is found by search, not by position), a trailing ``*** End Data ***`` line, and LF, CR LF,
    CR CR LF or CR line ends (line numbers in messages count each of these once).
``read_text_record``
    one column (acceleration; ``dt`` required) or two columns (time, acceleration; ``dt``
    inferred and checked to be uniform).
``read_record``
    dispatches on the extension and the content.

A file that cannot be read as written raises `RecordFormatError` naming the file and the line;
nothing is silently fixed (a missing value is never padded, an extra one never dropped).
"""

from __future__ import annotations

import math
import re
from bisect import bisect_left
from collections.abc import Iterable
from datetime import date
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.units import STANDARD_GRAVITY
from dcfpb.validation import check_choice, check_real
from groundmotions.records import GroundMotion, PathLike, RecordFormatError

__all__ = [
    "read_peer_at2",
    "read_record",
    "read_text_record",
]


# --------------------------------------------------------------------------------- file text


def _read_lines(path: Path) -> list[str]:
    """Lines of a text file without their ends; LF, CR LF, CR CR LF and CR all count once."""
    raw = path.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    if "\n" in text:
        return [line.rstrip("\r") for line in text.split("\n")]
    return text.split("\r")


def _first_non_number(tokens: Iterable[str]) -> str:
    for token in tokens:
        try:
            float(token)
        except ValueError:
            return token
    return ""


def _check_finite(path: Path, values: np.ndarray, line_ends: list[tuple[int, int]]) -> None:
    """Raise on the first NaN or infinite value, naming its line (float() accepts 'nan')."""
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        index = int(bad[0])
        line = line_ends[bisect_left([end for _, end in line_ends], index + 1)][0]
        raise RecordFormatError(path, line, f"value {index + 1} is {values[index]!r}, not finite")


# ------------------------------------------------------------------------------ PEER .AT2

_NPTS_WORD = re.compile(r"\bNPTS\b", re.IGNORECASE)
_VALUES_FIRST = re.compile(r"^\s*(\S+?)[\s,]+(\S+?)[\s,]+NPTS\s*,?\s*DT\b", re.IGNORECASE)
_NPTS_KEY = re.compile(r"\bNPTS\s*=\s*([^\s,]*)", re.IGNORECASE)
_DT_KEY = re.compile(r"\bDT\s*=\s*([^\s,]*)", re.IGNORECASE)
_OTHER_QUANTITY = re.compile(r"\b(VELOCITY|DISPLACEMENT)\s+TIME\s+(HISTORY|SERIES)", re.IGNORECASE)
_UNITS_G = re.compile(r"UNITS\s+(OF|ARE|IN)\s*\(?\s*G\b|\bIN\s+G\b|\(\s*G\s*\)", re.IGNORECASE)
_UNITS_CM = re.compile(r"\bCM\s*/\s*S(EC)?\s*(/\s*S(EC)?|\^?\s*2|\*\*\s*2)", re.IGNORECASE)
_FILTER = re.compile(r"\b(HP|LP)\s*=\s*([0-9.]+)\s*HZ", re.IGNORECASE)
_DATE = re.compile(r"(?<![\d/])(\d{1,2})/(\d{1,2})/(\d{4}|\d{2})(?![\d/])")
_TIME_OF_DAY = re.compile(r"^[\s,]*(\d{1,2}:\d{2}|\d{4})\s*,")
_AGENCY = re.compile(r"\(([^()]*)\)\s*$")


def _find_npts_dt(path: Path, lines: list[str]) -> tuple[int, int, float]:
    """Return (index of the NPTS/DT line, npts, dt [s]), searching from the top."""
    for index, line in enumerate(lines):
        tokens = line.split()
        if tokens and not _first_non_number(tokens):
            raise RecordFormatError(path, index + 1, "numbers begin before any NPTS/DT line")
        if not _NPTS_WORD.search(line):
            continue
        match = _VALUES_FIRST.match(line)
        if match:
            npts_text, dt_text = match.groups()
        else:
            npts_match, dt_match = _NPTS_KEY.search(line), _DT_KEY.search(line)
            if npts_match is None:
                raise RecordFormatError(path, index + 1, f"cannot read NPTS from {line.strip()!r}")
            if dt_match is None:
                raise RecordFormatError(path, index + 1, f"no DT on the NPTS line {line.strip()!r}")
            npts_text, dt_text = npts_match.group(1), dt_match.group(1)
        try:
            npts, dt = int(npts_text), float(dt_text)
        except ValueError:
            raise RecordFormatError(
                path, index + 1, f"cannot read NPTS={npts_text!r}, DT={dt_text!r} as numbers"
            ) from None
        if npts < 2 or not (math.isfinite(dt) and dt > 0.0):
            raise RecordFormatError(
                path, index + 1, f"NPTS must be >= 2 and DT > 0; got NPTS={npts}, DT={dt!r}"
            )
        return index, npts, dt
    raise RecordFormatError(path, len(lines), "no NPTS/DT line found in the whole file")


def _read_values(
    path: Path, lines: list[str], start: int, npts: int
) -> tuple[np.ndarray, list[str]]:
    """Read exactly ``npts`` numbers row by row from ``lines[start:]``; return them and the
    non-numeric trailer (e.g. ``*** End Data ***``) that may follow them."""
    values: list[float] = []
    line_ends: list[tuple[int, int]] = []
    trailer: list[str] = []
    for index in range(start, len(lines)):
        tokens = lines[index].split()
        if not tokens:
            continue
        try:
            row = [float(token) for token in tokens]
        except ValueError:
            if len(values) == npts:
                trailer = [line.strip() for line in lines[index:] if line.strip()]
                break
            raise RecordFormatError(
                path,
                index + 1,
                f"expected {npts} values (NPTS) but found non-numeric text "
                f"{_first_non_number(tokens)!r} after {len(values)} values",
            ) from None
        if len(values) + len(row) > npts:
            raise RecordFormatError(
                path, index + 1, f"NPTS is {npts} but value {npts + 1} is on this line"
            )
        values.extend(row)
        line_ends.append((index + 1, len(values)))
    if len(values) < npts:
        last = line_ends[-1][0] if line_ends else start
        raise RecordFormatError(
            path, last, f"expected {npts} values (NPTS) but the file ends after {len(values)}"
        )
    array = np.array(values)
    _check_finite(path, array, line_ends)
    return array, trailer


def _parse_peer_line2(line: str) -> dict[str, str | None]:
    """EVENT [,] MM/DD/YY [,] [HH:MM|HHMM,] STATION, COMPONENT [(AGENCY ...)] -> fields."""
    match = _DATE.search(line)
    if match is None or "," not in line[match.end() :]:
        return {}
    month, day, year = (int(g) for g in match.groups())
    if year < 100:  # two-digit years: 30-99 -> 19xx, 00-29 -> 20xx
        year += 1900 if year >= 30 else 2000
    try:
        iso = date(year, month, day).isoformat()
    except ValueError:
        iso = None
    rest = line[match.end() :]
    time_match = _TIME_OF_DAY.match(rest)
    if time_match:
        rest = rest[time_match.end() :]
    station, comma, tail = rest.strip(" ,").rpartition(",")
    agency_match = _AGENCY.search(tail)
    component = tail[: agency_match.start()] if agency_match else tail
    return {
        "event": line[: match.start()].strip(" ,") or None,
        "date": iso,
        "date_as_written": match.group(0),
        "time": time_match.group(1) if time_match else None,
        "station": station.strip() if comma else component.strip(),
        "component": component.strip() if comma else None,
        "agency": agency_match.group(1).strip() if agency_match else None,
    }


def _peer_units(path: Path, header: list[str]) -> tuple[str, float]:
    """Units of the values as the header states them, and the factor to m/s^2."""
    for number, line in enumerate(header, start=1):
        other = _OTHER_QUANTITY.search(line)
        if other:
            raise RecordFormatError(
                path, number, f"this is a {other.group(1).lower()} record, not an acceleration"
            )
    text = "\n".join(header)
    if _UNITS_CM.search(text):
        return "cm/s^2", 0.01
    if _UNITS_G.search(text):
        return "g", STANDARD_GRAVITY
    return "g (not stated; the PEER AT2 convention)", STANDARD_GRAVITY


def _parse_peer(path: Path, lines: list[str], name: str | None) -> GroundMotion:
    index, npts, dt = _find_npts_dt(path, lines)
    header = [line.rstrip() for line in lines[: index + 1]]
    values, trailer = _read_values(path, lines, index + 1, npts)
    units, factor = _peer_units(path, header)
    metadata: dict[str, Any] = {
        "event": None, "date": None, "time": None, "station": None, "component": None,
        "agency": None, "description": header[0].strip() if index > 0 else None,
    }  # fmt: skip
    if index == 3:  # a PEER 4-line header: line 2 holds event, date, station, component
        metadata.update(_parse_peer_line2(header[1]))
    for key, value in _FILTER.findall("\n".join(header)):
        metadata["highpass_hz" if key.upper() == "HP" else "lowpass_hz"] = float(value)
    metadata.update(
        format="PEER AT2",
        source_file=path.name,
        source_path=str(path),
        units_in_file=units,
        header_lines=tuple(header),
        npts_dt_line=header[index].strip(),
        npts_dt_line_number=index + 1,
        trailer_lines=tuple(trailer),
    )
    step = f"read from {path.name} ({units.split()[0]} -> m/s^2)"
    return GroundMotion(values * factor, dt, name or path.stem, metadata, (step,))


def read_peer_at2(path: PathLike, *, name: str | None = None) -> GroundMotion:
    """Read a PEER .AT2 acceleration record.

    Parameters
    ----------
    path : str or path-like
        The file.
    name : str, optional
        Name of the record; the file stem by default.

    Returns
    -------
    GroundMotion
        Acceleration converted from the file's units (g, or cm/s^2 when the header says so)
        to [m/s^2] with ``dcfpb.units.STANDARD_GRAVITY``.

    Raises
    ------
    RecordFormatError
        No NPTS/DT line, a missing DT, a value count that disagrees with NPTS, a non-numeric,
        NaN or infinite value, or a velocity/displacement file; the message names the file and
        the line.

    Notes
    -----
    Event, date, time, station, component and agency are parsed from line 2 when the header has
    the PEER 4-line layout; the station and component are split at the last comma and only a
    trailing parenthesised group is the agency (station names may hold parentheses).
    """
    path = Path(path)
    return _parse_peer(path, _read_lines(path), name)


# ----------------------------------------------------------------------------- text records


def _read_columns(path: Path, lines: list[str]) -> tuple[np.ndarray, list[int], list[str]]:
    """Numeric rows of one or two columns (whitespace, comma or semicolon separated)."""
    header: list[str] = []
    rows: list[list[float]] = []
    numbers: list[int] = []
    for index, line in enumerate(lines):
        text = line.strip()
        if not text or text.startswith(("#", "%")):
            if not rows and text:
                header.append(text)
            continue
        tokens = text.replace(",", " ").replace(";", " ").split()
        try:
            row = [float(token) for token in tokens]
        except ValueError:
            if not rows:
                header.append(text)
                continue
            raise RecordFormatError(
                path, index + 1, f"non-numeric value {_first_non_number(tokens)!r} in the data"
            ) from None
        if not rows and len(row) not in (1, 2):
            raise RecordFormatError(
                path, index + 1, f"expected 1 or 2 columns (acceleration or time, acceleration) "
                f"but found {len(row)}; PEER files with several values a row need read_peer_at2",
            )  # fmt: skip
        if rows and len(row) != len(rows[0]):
            raise RecordFormatError(
                path, index + 1, f"expected {len(rows[0])} column(s) as on line {numbers[0]} "
                f"but found {len(row)}",
            )  # fmt: skip
        rows.append(row)
        numbers.append(index + 1)
    if len(rows) < 2:
        raise RecordFormatError(path, len(lines), f"found {len(rows)} data rows; at least 2 needed")
    table = np.array(rows)
    ends = [(number, (i + 1) * table.shape[1]) for i, number in enumerate(numbers)]
    _check_finite(path, table.ravel(), ends)
    return table, numbers, header


def read_text_record(
    path: PathLike, dt: float | None = None, units: str = "g", *, name: str | None = None
) -> GroundMotion:
    """Read a one-column (acceleration) or two-column (time, acceleration) text record.

    Leading non-numeric lines and lines starting with ``#`` or ``%`` are kept as the header;
    columns may be separated by blanks, commas or semicolons.

    Parameters
    ----------
    path : str or path-like
        The file.
    dt : float, optional
        Time step [s]. Required for one column; for two columns it is inferred from the time
        column (first to last time over npts - 1) and, if given, must agree with it to 0.1 %.
    units : {"g", "m/s2"}
        Units of the acceleration column.
    name : str, optional
        Name of the record; the file stem by default.

    Returns
    -------
    GroundMotion
        Acceleration [m/s^2], time re-based to start at 0.

    Raises
    ------
    RecordFormatError
        A non-numeric, NaN or infinite value, a change in the number of columns, or a time
        column that is not uniform (a sample more than 1 % of a step off the uniform grid).
    ValueError
        ``dt`` missing for one column, or disagreeing with the time column.
    """
    owner = "read_text_record"
    units = check_choice(units, "units", owner, ("g", "m/s2"))
    path = Path(path)
    table, numbers, header = _read_columns(path, _read_lines(path))
    processing = [f"read from {path.name} ({'g -> m/s^2' if units == 'g' else 'm/s^2'})"]
    start_time = 0.0
    if table.shape[1] == 1:
        if dt is None:
            raise ValueError(
                f"The 'dt' parameter of {owner} must be a float in (0, inf) for the one-column "
                f"file {path.name}. Got None instead."
            )
        step = check_real(dt, "dt", owner, low=0.0, low_open=True)
    else:
        times = table[:, 0]
        start_time = float(times[0])
        step = (times[-1] - times[0]) / (times.size - 1)
        if not step > 0.0:
            raise RecordFormatError(path, numbers[-1], "the time column does not increase")
        # Uniform if every time lies within 1 % of a step of the grid from the first to the
        # last time (robust to times printed with few digits: rounding does not accumulate).
        off = np.abs(times - (times[0] + step * np.arange(times.size)))
        if off.max() > 0.01 * step:
            steps = np.diff(times)
            typical = float(np.median(steps))
            irregular = np.abs(steps - typical) > 0.01 * typical
            i = int(np.argmax(irregular)) + 1 if irregular.any() else int(np.argmax(off))
            raise RecordFormatError(
                path, numbers[i], f"time {times[i]:g} s follows {times[i - 1]:g} s, a step of "
                f"{times[i] - times[i - 1]:.6g} s where the usual step is {typical:.6g} s: "
                "the record is not uniformly sampled",
            )  # fmt: skip
        if dt is not None:
            given = check_real(dt, "dt", owner, low=0.0, low_open=True)
            if abs(given - step) > 1e-3 * step:
                raise ValueError(
                    f"The 'dt' parameter of {owner} must agree with the time column of "
                    f"{path.name} (dt = {step:.6g} s). Got {dt!r} instead."
                )
            step = given
        if start_time != 0.0:
            processing.append(f"time re-based: the file starts at t = {start_time:g} s")
    factor = STANDARD_GRAVITY if units == "g" else 1.0
    metadata: dict[str, Any] = {
        "format": f"text, {table.shape[1]} column(s)",
        "source_file": path.name,
        "source_path": str(path),
        "units_in_file": units,
        "header_lines": tuple(header),
        "start_time": start_time,
    }
    return GroundMotion(table[:, -1] * factor, step, name or path.stem, metadata, tuple(processing))


def read_record(path: PathLike, **kwargs: Any) -> GroundMotion:
    """Read a record, choosing the reader from the extension and the content.

    A ``.at2`` file, or any file with an NPTS line before its first row of numbers, goes to
    `read_peer_at2`; anything else to `read_text_record` (keywords are passed on).
    """
    path = Path(path)
    if path.suffix.lower() == ".at2" or _npts_before_numbers(_read_lines(path)):
        return read_peer_at2(path, **kwargs)
    return read_text_record(path, **kwargs)


def _npts_before_numbers(lines: list[str]) -> bool:
    for line in lines:
        if _NPTS_WORD.search(line):
            return True
        tokens = line.split()
        if tokens and not _first_non_number(tokens):
            return False
    return False
