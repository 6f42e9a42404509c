"""Reader of PEER .AT2 acceleration records (`read_peer_at2`).

The NPTS/DT line is found after a free-text header of any length, as ``NPTS=  7996, DT= .00500
SEC`` (any case, with or without unit or trailing comma) or the NGA ``7997 0.0050 NPTS, DT``.
DT is in seconds unless its unit says milliseconds (``DT= 20 MSEC``, ``DT=20ms``); another unit
after DT (``MIN``, ``HZ`` ...) is refused. A trailing ``*** End Data ***`` line is allowed; numbers
after the NPTS values (after such a line or not) are refused, never dropped.
"""

from __future__ import annotations

import math
import re
from datetime import date
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.common.validation import check_path
from groundmotions.filetext import (
    RecordUnits,
    check_finite,
    check_record_plausible,
    first_non_number,
    read_lines,
    record_units,
)
from groundmotions.records import GroundMotion, PathLike, RecordFormatError
from groundmotions.units import TO_SECONDS, parse_time_unit

__all__ = ["read_peer_at2"]

_NPTS_WORD = re.compile(r"\bNPTS\b", re.IGNORECASE)
_VALUES_FIRST = re.compile(r"^\s*([^\s,]+)[\s,]+([^\s,]+)[\s,]+NPTS\s*,?\s*DT\b", re.IGNORECASE)
_NPTS_KEY = re.compile(r"\bNPTS\s*=\s*([^\s,]*)", re.IGNORECASE)
_DT_KEY = re.compile(r"\bDT\s*=\s*([^\s,]*)(?:[\s,]*(?P<unit>[a-zA-Z][a-zA-Z-]*)\b)?",
                     re.IGNORECASE)
_ATTACHED_UNIT = re.compile(r"^([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)([a-zA-Z][a-zA-Z-]*)$")
_NOT_A_STEP_UNIT = re.compile(r"^(?:min|mins|minutes?|h|hrs?|hours?|us|usec|microsec\w*|ns|"
                              r"hz|khz|sps|samples?)$", re.IGNORECASE)
_FILTER = re.compile(r"\b(HP|LP)\s*=\s*([0-9.]+)\s*HZ", re.IGNORECASE)
_DATE = re.compile(r"(?<![\d/])(\d{1,2})/(\d{1,2})/(\d{4}|\d{2})(?![\d/])")
_TIME_OF_DAY = re.compile(r"^[\s,]*(\d{1,2}:\d{2}|\d{4})\s*,")
_AGENCY = re.compile(r"\(([^()]*)\)\s*$")


def has_npts_line(lines: list[str]) -> bool:
    """Whether an NPTS line precedes the first row of numbers (a PEER file, any extension)."""
    for line in lines:
        if _NPTS_WORD.search(line):
            return True
        tokens = line.split()
        if tokens and not first_non_number(tokens):
            return False
    return False


def _step_unit(path: Path, number: int, dt_text: str, unit: str | None) -> tuple[str, str]:
    """(DT's number as written, its canonical time unit) from the text after ``DT=`` and the
    word after it: seconds unless the unit says milliseconds."""
    attached = _ATTACHED_UNIT.match(dt_text)
    if attached:
        dt_text, unit = attached.groups()
    if unit is None:
        return dt_text, "s"
    name = parse_time_unit(unit)
    if name is not None:
        return dt_text, name
    if _NOT_A_STEP_UNIT.match(unit):
        raise RecordFormatError(
            path, number, f"DT is given in {unit!r}, not a time step unit the readers take: "
            f"write DT in seconds (SEC) or milliseconds (MSEC); got DT= {dt_text} {unit}",
        )  # fmt: skip
    return dt_text, "s"  # another key follows (HP=, NPTS=): DT in seconds, the PEER default


def _find_npts_dt(path: Path, lines: list[str]) -> tuple[int, int, float, str]:
    """Return (index of the NPTS/DT line, npts, dt [s], DT's unit in the file), searching from
    the top."""
    for index, line in enumerate(lines):
        tokens = line.split()
        if tokens and not first_non_number(tokens):
            raise RecordFormatError(path, index + 1, "numbers begin before any NPTS/DT line")
        if not _NPTS_WORD.search(line):
            continue
        match = _VALUES_FIRST.match(line)
        unit = "s"
        if match:
            npts_text, dt_text = match.groups()
        else:
            npts_match, dt_match = _NPTS_KEY.search(line), _DT_KEY.search(line)
            if npts_match is None:
                raise RecordFormatError(path, index + 1, f"cannot read NPTS from {line.strip()!r}")
            if dt_match is None:
                raise RecordFormatError(path, index + 1, f"no DT on the NPTS line {line.strip()!r}")
            npts_text = npts_match.group(1)
            dt_text, unit = _step_unit(path, index + 1, dt_match.group(1), dt_match["unit"])
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
        return index, npts, dt * TO_SECONDS[unit], unit
    raise RecordFormatError(path, len(lines), "no NPTS/DT line found in the whole file")


def _check_trailer(path: Path, lines: list[str], start: int, npts: int) -> None:
    """Refuse numbers in the text after the ``npts`` values (from ``lines[start]``): they would
    be values beyond NPTS, silently dropped."""
    for index in range(start + 1, len(lines)):
        tokens = lines[index].split()
        if tokens and not first_non_number(tokens):
            raise RecordFormatError(
                path, index + 1, f"more values after the {npts} values of NPTS and the text "
                f"{lines[start].strip()[:40]!r} on line {start + 1}: correct NPTS or remove "
                "the extra values",
            )  # fmt: skip


def _read_values(
    path: Path, lines: list[str], start: int, npts: int
) -> tuple[np.ndarray, list[tuple[int, int]], list[str]]:
    """Exactly ``npts`` numbers read row by row from ``lines[start:]`` (nothing of size ``npts``
    allocated before), their ``(line number, values so far)`` pairs and the non-numeric trailer."""
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
                _check_trailer(path, lines, index, npts)
                break
            raise RecordFormatError(
                path,
                index + 1,
                f"expected {npts} values (NPTS) but found non-numeric text "
                f"{first_non_number(tokens)!r} after {len(values)} values",
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
    check_finite(path, array, line_ends)
    return array, line_ends, trailer


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


def _units_label(units: RecordUnits) -> str:
    """``units_in_file`` of the metadata: the unit, and where it came from unless the header."""
    if units.source == "default":
        return "g (not stated; the PEER AT2 convention)"
    return units.name if units.source == "header" else f"{units.name} (given by the caller)"


def parse_peer(path: Path, lines: list[str], name: str | None = None,
               units: str | None = None) -> GroundMotion:
    """The record of a PEER file already split into lines (see `read_peer_at2`)."""
    index, npts, dt, dt_unit = _find_npts_dt(path, lines)
    header = [line.rstrip() for line in lines[: index + 1]]
    found = record_units(path, list(enumerate(header, start=1)), units, "read_peer_at2")
    values, line_ends, trailer = _read_values(path, lines, index + 1, npts)
    advice = ("if DT is in milliseconds, say so on its line ('DT= 20 MSEC')" if dt_unit == "s"
              else "check DT and NPTS")
    check_record_plausible(path, values, found, line_ends, dt, index + 1, advice)
    label = _units_label(found)
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
        units_in_file=label,
        header_lines=tuple(header),
        npts_dt_line=header[index].strip(),
        npts_dt_line_number=index + 1,
        dt_unit_in_file=dt_unit,
        trailer_lines=tuple(trailer),
    )
    steps = [f"read from {path.name} ({label.split()[0]} -> m/s^2)"]
    if dt_unit != "s":
        steps.append(f"DT read in {dt_unit}: {dt:g} s")
    return GroundMotion(values * found.factor, dt, name or path.stem, metadata, tuple(steps))


def read_peer_at2(
    path: PathLike, *, name: str | None = None, units: str | None = None
) -> GroundMotion:
    """Read a PEER .AT2 acceleration record (with the PEER 4-line header, event, date, time,
    station, component and agency go to the metadata from line 2).

    Parameters
    ----------
    path : str or path-like
        The file.
    name : str, optional
        Name of the record; the file stem by default.
    units : str, optional
        Units of the values when the header states none (`groundmotions.units.UNIT_NAMES` or
        another spelling, e.g. ``"CM/S/S"``); by default g, the PEER convention. Units that
        disagree with the header's are refused.

    Returns
    -------
    GroundMotion
        Acceleration [m/s^2] (`groundmotions.units.TO_M_PER_S2`).

    Raises
    ------
    RecordFormatError
        Naming the file and the line: no NPTS/DT line or no DT, a value count other than NPTS, a
        non-numeric or non-finite value, a velocity or displacement file, unknown units, or a PGA
        outside 1e-4 to 5 g (naming the units that would fit).
    InputError
        ``units`` is not an acceleration unit.
    """
    path = Path(check_path(path, "path", "read_peer_at2"))
    return parse_peer(path, read_lines(path), name, units)
