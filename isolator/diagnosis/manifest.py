"""A campaign manifest: the tests of one bearing in run order, with their conditions.

A CSV manifest has a header line and one row per test, in the order the tests were run:

``file``
    The test's CSV file, relative to the manifest (required).
``axial_load``
    Constant axial load of the test [N] for a file without an ``axial_force`` column (with
    the column, a value disagreeing with it by more than 2 % is an error).
``initial_temperature``
    Temperature of the plates at the start of the test [degC]; 250-400 is taken for kelvin
    and refused.
``rest_before``
    Rest since the end of the previous test [s]; empty: long enough to cool down.

A TOML manifest has a ``[[test]]`` table per test (same keys) and may give the bearing's
``effective_radius`` [m] and ``slider_diameter`` [m] at the top.

On the command line (``must_agree`` of :func:`load_manifest`), a value given both in the
manifest and as a flag (``--effective-radius``, ``--slider-diameter``, ``--axial-load``) must be
the same in both; a disagreement is refused naming both sources and values, and an
``--axial-load`` that no test uses (every test has an ``axial_force`` column) is warned about
(:class:`~dcfpb.common.errors.InputWarning`). In Python the arguments are defaults: the
radius and diameter arguments replace the TOML values, ``axial_load`` serves the rows without
one.
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np

from dcfpb.common.errors import InputError, InputWarning
from dcfpb.common.units import KELVIN_LOOK
from isolator.diagnosis.data import (
    MAX_ROWS,
    Campaign,
    Campaign2D,
    DataError,
    _column_name,
    check_consistent_units,
    check_one_kind,
    check_plausible,
    check_size,
    estimate_rows,
    file_dimension,
    read_record,
    read_record_2d,
)

COLUMNS = ("file", "axial_load", "initial_temperature", "rest_before")
_AXIAL_TOLERANCE = 0.02


MAX_MANIFEST_BYTES = 10 * 2**20
"""Largest campaign manifest read [bytes] (some hundred thousand tests)."""


def read_manifest(path: str | Path) -> tuple[list[dict], dict]:
    """The rows of a manifest (one dict per test) and its top-level bearing values."""
    path = Path(path)
    if not path.is_file():
        raise DataError(f"{path}: not a regular file (a folder, a device or a pipe); give the "
                        "manifest file." if path.exists() else f"{path}: no such manifest file.")
    if path.stat().st_size > MAX_MANIFEST_BYTES:
        raise DataError(f"{path}: {path.stat().st_size:,} bytes, more than the "
                        f"{MAX_MANIFEST_BYTES:,} of a campaign manifest; is it one?")
    if path.suffix.lower() == ".toml":
        import tomllib

        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
            raise DataError(f"{path}: not a readable TOML manifest ({error}).") from error
        rows = data.pop("test", None)
        if not isinstance(rows, list) or not rows:
            raise DataError(f"{path}: a TOML manifest needs one [[test]] table per test.")
        top = {k: data[k] for k in ("effective_radius", "slider_diameter") if k in data}
        unknown = sorted(set(data) - set(top))
        if unknown:
            raise DataError(f"{path}: unknown key(s) {unknown}; allowed: effective_radius, "
                            "slider_diameter and [[test]] tables.")
    else:
        import csv

        try:
            with path.open(newline="", encoding="utf-8") as handle:
                rows = list(csv.DictReader(handle))
        except UnicodeDecodeError as error:
            raise DataError(f"{path}: not a UTF-8 CSV manifest ({error}).") from error
        top = {}
        if not rows or "file" not in rows[0]:
            raise DataError(f"{path}: a CSV manifest needs a header with a 'file' column and "
                            "one row per test.")
    out = []
    for number, row in enumerate(rows, start=1):
        where = f"{path}: test {number}"
        if not isinstance(row, dict):
            raise DataError(f"{where}: must be a table of {COLUMNS}.")
        unknown = sorted(set(row) - set(COLUMNS))
        if unknown:
            raise DataError(f"{where}: unknown column(s) {unknown}; allowed: {list(COLUMNS)}.")
        entry = {"file": str(row.get("file") or "").strip()}
        if not entry["file"]:
            raise DataError(f"{where}: 'file' is empty.")
        for key in COLUMNS[1:]:
            entry[key] = _number(row.get(key), key, where)
        for key, low, unit in (("axial_load", 0.0, "N"), ("rest_before", None, "s")):
            value = entry[key]
            if value is not None and (value < 0.0 or value == low):
                bound = "above 0" if low is not None else "at least 0"
                raise DataError(f"{where}: '{key}' must be {bound} {unit}. Got {value!r}.")
        start = entry["initial_temperature"]
        if start is not None and KELVIN_LOOK[0] <= start <= KELVIN_LOOK[1]:
            raise DataError(f"{where}: 'initial_temperature' is {start!r}, which looks like "
                            "kelvin (plates at 250 degC or more before a test are implausible); "
                            "give it in degC (subtract 273.15).")
        out.append(entry)
    return out, top


def _number(value, key: str, where: str) -> float | None:
    if value is None or (isinstance(value, str) and not value.strip()):
        return None
    if isinstance(value, bool):
        raise DataError(f"{where}: '{key}' must be a number. Got {value!r}.")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise DataError(f"{where}: '{key}' must be a number. Got {value!r}.") from None
    if not math.isfinite(number):
        raise DataError(f"{where}: '{key}' must be finite. Got {value!r}.")
    return number


def load_manifest(
    path: str | Path,
    *,
    effective_radius: float | None = None,
    slider_diameter: float | None = None,
    axial_load: float | None = None,
    max_rows: int = MAX_ROWS,
    must_agree: bool = False,
    argument_names: dict[str, str] | None = None,
) -> Campaign:
    """The campaign a manifest lists.

    ``effective_radius`` [m] and ``slider_diameter`` [m] come from the arguments, else from a
    TOML manifest; ``axial_load`` [N] applies to the tests whose row gives none and whose file
    has no ``axial_force`` column. With ``must_agree`` (the command line's rule), a value given
    both in the manifest and as an argument must be the same in both, and an ``axial_load``
    that no test uses is warned about. ``max_rows``: see
    :func:`~isolator.diagnosis.data.read_record`; ``argument_names`` names each argument in
    messages (default: the argument's name; the command line gives its flags).

    Raises
    ------
    DataError
        Naming the manifest, the test and the problem: a missing file, a value disagreeing
        with an argument, a load disagreeing with the file's column, mixed units, implausible
        levels (:func:`~isolator.diagnosis.data.check_plausible`).
    """
    path = Path(path)
    names = {key: key for key in ("effective_radius", "slider_diameter", "axial_load")}
    names.update(argument_names or {})
    rows, top = read_manifest(path)
    for key, given in (("effective_radius", effective_radius),
                       ("slider_diameter", slider_diameter)):
        if must_agree and given is not None and key in top:
            _same(top[key], given, f"{path}: '{key}'", names[key], "m")
    if must_agree and axial_load is not None:
        for number, row in enumerate(rows, start=1):
            if row["axial_load"] is not None:
                _same(row["axial_load"], axial_load,
                      f"{path}: test {number} ({row['file']}): 'axial_load'",
                      names["axial_load"], "N")
    radius = effective_radius if effective_radius is not None else top.get("effective_radius")
    diameter = slider_diameter if slider_diameter is not None else top.get("slider_diameter")
    if radius is None or diameter is None:
        raise DataError(f"{path}: give the effective radius and the slider diameter (on the "
                        "command line, or in a TOML manifest).")
    tests, places, sources = [], [], []
    for number, row in enumerate(rows, start=1):
        file = (path.parent / row["file"]).resolve()
        where = f"{path}: test {number} ({row['file']})"
        places.append(where)
        if not file.is_file():
            raise DataError(f"{where}: the file does not exist ({file}).")
        try:
            check_size(file, max_rows=max_rows)
        except DataError as error:
            raise DataError(f"{where}: {error}") from None
    files = [(path.parent / row["file"]).resolve() for row in rows]
    two = check_one_kind(files, max_rows=max_rows, where=places) == 2
    used_flag = False
    for number, row in enumerate(rows, start=1):
        file = (path.parent / row["file"]).resolve()
        where = places[number - 1]
        load = row["axial_load"] if row["axial_load"] is not None else axial_load
        has_column = _has_axial_column(file)
        used_flag = used_flag or not has_column  # applied, or equal to the manifest's
        sources.append("column 'axial_force'" if has_column else
                       "the manifest's axial_load" if row["axial_load"] is not None else
                       "the axial load given")
        if has_column and row["axial_load"] is not None:
            record = _read(where, file, initial_temperature=row["initial_temperature"],
                           rest_before=row["rest_before"], max_rows=max_rows)
            mean = float(np.mean(record.axial_force))
            if abs(mean - row["axial_load"]) > _AXIAL_TOLERANCE * abs(mean):
                raise DataError(f"{where}: the manifest's axial_load {row['axial_load']:.6g} N "
                                f"disagrees with the file's axial_force column (mean "
                                f"{mean:.6g} N); give one of the two.")
        else:
            if not has_column and load is None:
                raise DataError(f"{where}: no axial_force column and no axial_load in the "
                                "manifest or on the command line.")
            record = _read(where, file, axial_load=None if has_column else load,
                           initial_temperature=row["initial_temperature"],
                           rest_before=row["rest_before"], max_rows=max_rows)
        tests.append(record)
    if must_agree and axial_load is not None and not used_flag:
        warnings.warn(f"{names['axial_load']} {axial_load!r} N has no effect: every test of "
                      f"{path} has an axial_force column, which gives its axial load.",
                      InputWarning, stacklevel=2)
    check_consistent_units(tests, places)
    if two:  # tests in two directions
        return Campaign2D(tuple(tests), float(radius), float(diameter))
    campaign = Campaign(tuple(tests), float(radius), float(diameter))
    check_plausible(campaign, places, sources)
    return campaign


def _read(where: str, file: Path, **options):
    """:func:`read_record` (or :func:`read_record_2d` for a test in
    two directions) of a manifest's test; its errors name the manifest and the test."""
    try:
        if file_dimension(file, max_rows=options.get("max_rows", MAX_ROWS)) == 2:
            return read_record_2d(file, **options)
        return read_record(file, **options)
    except InputError as error:  # DataError, or a value of the manifest out of its range
        text = re.sub(r"The '(\w+)' parameter of test '[^']*'", r"'\1'", str(error))
        raise DataError(f"{where}: {text}") from None


def _same(manifest: float, given: float, where: str, source: str, unit: str) -> None:
    """Refuse a manifest value that differs from the one given as an argument."""
    if not math.isclose(float(manifest), float(given), rel_tol=1e-9, abs_tol=0.0):
        raise DataError(f"{where} is {float(manifest)!r} {unit} but {source} gives "
                        f"{float(given)!r} {unit}; give one value, or the same in both.")


def _has_axial_column(file: Path) -> bool:
    """Whether a test file's header (read by :func:`estimate_rows`) names an ``axial_force``
    column."""
    return "axial_force" in {_column_name(c)[0] for c in estimate_rows(file)[1]}
