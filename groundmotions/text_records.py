"""Reader of text records (`read_text_record`): one column (acceleration) or two (time,
acceleration). The time column is in seconds unless the header says milliseconds (``time [ms]``,
``t (msec)``, ``time in ms``); a time unit in the header that disagrees with itself is refused.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_path
from groundmotions.filetext import (
    agreeing_step,
    check_finite,
    check_plausible,
    check_record_plausible,
    check_step,
    first_non_number,
    read_lines,
    record_units,
    timing_problem,
)
from groundmotions.records import GroundMotion, PathLike, RecordFormatError
from groundmotions.units import TO_SECONDS, parse_time_unit

__all__ = ["read_text_record"]

_OWNER = "read_text_record"
_TIME_UNIT = re.compile(r"\b(?:time|t)[\s_]*(?:\[|\(|\bin\b|:|=)?[\s_]*(?P<unit>[a-z][a-z-]*)",
                        re.IGNORECASE)


def _time_unit(path: Path, header: list[tuple[int, str]]) -> tuple[str, int | None]:
    """(canonical unit of the time column, line stating it) from the header: ``"s"`` and None
    when it states none; statements that disagree are refused."""
    found = [(number, match["unit"], name) for number, line in header
             for match in _TIME_UNIT.finditer(line)
             if (name := parse_time_unit(match["unit"])) is not None]
    for number, written, name in found[1:]:
        if name != found[0][2]:
            raise RecordFormatError(
                path, number, f"the header gives the time in {found[0][1]!r} on line "
                f"{found[0][0]} and in {written!r} on this line: which is the time column in? "
                "Correct the header",
            )  # fmt: skip
    return (found[0][2], found[0][0]) if found else ("s", None)


def _read_columns(
    path: Path, lines: list[str]
) -> tuple[np.ndarray, list[int], list[tuple[int, str]]]:
    """Numeric rows of one or two columns, their line numbers, and the header lines with theirs."""
    header: list[tuple[int, str]] = []
    rows: list[list[float]] = []
    numbers: list[int] = []
    for index, line in enumerate(lines):
        text = line.strip()
        if not text or text.startswith(("#", "%")):
            if not rows and text:
                header.append((index + 1, text))
            continue
        tokens = text.replace(",", " ").replace(";", " ").split()
        try:
            row = [float(token) for token in tokens]
        except ValueError:
            if not rows:
                header.append((index + 1, text))
                continue
            raise RecordFormatError(
                path, index + 1, f"non-numeric value {first_non_number(tokens)!r} in the data"
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
    check_finite(path, table.ravel(), ends)
    return table, numbers, header


def _time_step(path: Path, times: np.ndarray, numbers: list[int], dt: float | None) -> float:
    """The step of a time column, checked to be uniform (and to agree with ``dt`` if given)."""
    span = float(times[-1]) - float(times[0])  # Python floats: inf, not an overflow warning
    step = span / (times.size - 1)
    if not (step > 0.0 and np.isfinite(step)):
        raise RecordFormatError(
            path, numbers[-1], f"the time column does not increase to a finite time "
            f"(from {times[0]:g} s to {times[-1]:g} s)",
        )  # fmt: skip
    # uniform: every time within 1 % of a step of the grid from the first to the last time
    with np.errstate(over="ignore", invalid="ignore"):
        off = np.abs(times - (times[0] + step * np.arange(times.size)))
    if not off.max() <= 0.01 * step:
        with np.errstate(over="ignore", invalid="ignore"):
            steps = np.diff(times)
            typical = float(np.median(steps))
            irregular = ~(np.abs(steps - typical) <= 0.01 * abs(typical))
        i = int(np.argmax(irregular)) + 1 if irregular.any() else int(np.argmax(off))
        raise RecordFormatError(
            path, numbers[i], f"time {times[i]:g} s follows {times[i - 1]:g} s, a step of "
            f"{float(times[i]) - float(times[i - 1]):.6g} s where the usual step is "
            f"{typical:.6g} s: the record is not uniformly sampled",
        )  # fmt: skip
    if dt is not None:
        step = agreeing_step(dt, step, _OWNER, f"the time column of {path.name} (dt = "
                             f"{step:.6g} s)")
    return step


def read_text_record(
    path: PathLike, dt: float | None = None, units: str | None = None, *,
    name: str | None = None,
) -> GroundMotion:
    """Read a one-column (acceleration) or two-column (time, acceleration) text record, columns
    separated by blanks, commas or semicolons. The header (kept in the metadata) is the leading
    non-numeric lines and lines starting with ``#`` or ``%``; it may state the units.

    Parameters
    ----------
    path : str or path-like
        The file.
    dt : float, optional
        Time step [s]: required for one column; for two it is (last - first time) / (npts - 1)
        and, if given, must agree with that to 0.1 % (and is used).
    units : str, optional
        Units of the acceleration when the header states none (`groundmotions.units.UNIT_NAMES`
        or another spelling, e.g. ``"m/s2"``); by default g. Units that disagree with the
        header's are refused.
    name : str, optional
        Name of the record; the file stem by default.

    Returns
    -------
    GroundMotion
        Acceleration [m/s^2], time re-based to start at 0.

    Raises
    ------
    RecordFormatError
        A non-numeric or non-finite value, a change in the number of columns, a time more than
        1 % of a step off the uniform grid, unknown units, or a PGA outside 1e-4 to 5 g (naming the
        units that would fit).
    InputError
        ``dt`` missing for one column or disagreeing with the time column; ``units`` not an
        acceleration unit.
    """
    path = Path(check_path(path, "path", "read_text_record"))
    table, numbers, header = _read_columns(path, read_lines(path))
    found = record_units(path, header, units, _OWNER)
    start_time = 0.0
    time_unit, time_line = ("s", None) if table.shape[1] == 1 else _time_unit(path, header)
    if table.shape[1] == 1:
        if dt is None:
            raise InputError(
                f"The 'dt' parameter of {_OWNER} must be a float in (0, inf) for the one-column "
                f"file {path.name} (--record-dt on the command line). Got None instead."
            )
        step = check_step(dt, _OWNER)
        problem = timing_problem(step, table.shape[0])
        if problem is not None:
            raise InputError(
                f"The 'dt' parameter of {_OWNER} (--record-dt on the command line) for "
                f"{path.name} must give a plausible record: {problem}. Got {dt!r} instead."
            )
    else:
        times = table[:, 0] * TO_SECONDS[time_unit] if time_unit != "s" else table[:, 0]
        start_time = float(times[0])
        step = _time_step(path, times, numbers, dt)
    values = table[:, -1]
    line_ends = [(n, i + 1) for i, n in enumerate(numbers)]
    if table.shape[1] == 1:
        check_plausible(path, values, found, line_ends)
    else:
        advice = ("if the time column is in milliseconds, say so in the header ('# time [ms]')"
                  if time_unit == "s" else f"the header gives the time in ms on line {time_line}")
        check_record_plausible(path, values, found, line_ends, step, numbers[1], advice)
    label = found.name if found.source != "given" else str(units)
    read = "g -> m/s^2" if found.name == "g" else (
        "m/s^2" if found.name == "m/s^2" else f"{found.name} -> m/s^2")
    processing = [f"read from {path.name} ({read})"]
    if time_unit != "s":
        processing.append(f"time column read in {time_unit} (header line {time_line})")
    if start_time != 0.0:
        processing.append(f"time re-based: the file starts at t = {start_time:g} s")
    metadata: dict[str, Any] = {
        "format": f"text, {table.shape[1]} column(s)",
        "source_file": path.name,
        "source_path": str(path),
        "units_in_file": label,
        "header_lines": tuple(text for _, text in header),
        "start_time": start_time,
        "time_unit_in_file": time_unit if table.shape[1] == 2 else None,
    }
    return GroundMotion(values * found.factor, step, name or path.stem, metadata,
                        tuple(processing))
