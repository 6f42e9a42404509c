"""Measured bearing histories for the diagnosis: one record per test, checked on the way in.

A test is a CSV file (or ``.csv.gz``) with a header line and the columns ``time`` [s],
``displacement`` [m] (relative displacement of the plates), ``force`` [N] (horizontal) and
optionally ``axial_force`` [N], ``velocity`` [m/s] and ``temperature`` [degC]; other columns
are ignored. A header may state a column's unit in brackets, ``force [N]``; it must then be the
unit above, except ``velocity [mm/s]`` or ``[cm/s]`` (converted to m/s) and ``temperature [C]``
or ``[°C]``. Every problem is reported before any fitting, naming the file, the column and
the row (the first data row is row 2): a file too large to read (estimated from its size and
first lines, :func:`estimate_rows`), a column named twice, a unit stated other than the
above, a missing column, a non-numeric value or NaN, unequal lengths, time that does not
increase, a non-positive axial force, a displacement in mm, a velocity column that is not the
derivative of the displacement (:func:`velocity_ratio`), a temperature in kelvin or out of
range, and levels that betray a unit mistake or a wrong R_eff or axial load
(:func:`check_plausible`).

A test in two directions (an orbit) has the columns ``time`` [s], ``displacement_x``,
``displacement_y`` [m], ``force_x``, ``force_y`` [N] and optionally ``axial_force`` [N],
``velocity_x``, ``velocity_y`` [m/s] and ``temperature`` [degC]; it is read and checked by the
same code (:func:`read_record_2d`, a :class:`BearingRecord2D`), every message naming the axis.
A campaign holds tests of one kind only: all in one direction or all in two
(:func:`check_one_kind`, :func:`load_any_campaign`).
"""

from __future__ import annotations

import csv
import gzip
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.units import KELVIN_LOOK
from dcfpb.common.validation import check_real
from isolator.bearing import SliderContact
from isolator.characteristics import magnitude
from isolator.limits import DEFAULT_MAX_STEPS, _size, available_memory

REQUIRED_COLUMNS = ("time", "displacement", "force")
OPTIONAL_COLUMNS = ("axial_force", "velocity", "temperature")
UNITS = {"time": "s", "displacement": "m", "force": "N", "axial_force": "N",
         "velocity": "m/s", "temperature": "degC"}
AXES = ("x", "y")
REQUIRED_COLUMNS_2D = ("time", "displacement_x", "displacement_y", "force_x", "force_y")
OPTIONAL_COLUMNS_2D = ("axial_force", "velocity_x", "velocity_y", "temperature")
UNITS_2D = {"time": "s", "displacement_x": "m", "displacement_y": "m", "force_x": "N",
            "force_y": "N", "axial_force": "N", "velocity_x": "m/s", "velocity_y": "m/s",
            "temperature": "degC"}
TWO_DIRECTION_MARKERS = ("displacement_x", "displacement_y", "force_x", "force_y")
"""Columns whose presence marks a test in two directions."""
VECTORS = ("displacement", "force", "velocity")
"""Channels of a test with one column per direction: (n,) in one direction, (n, 2) in two."""
_COLUMNS = {1: (REQUIRED_COLUMNS, OPTIONAL_COLUMNS, UNITS),
            2: (REQUIRED_COLUMNS_2D, OPTIONAL_COLUMNS_2D, UNITS_2D)}
_NEEDS = {
    1: ("A test needs time [s], displacement [m] and force [N], and optionally axial_force "
        "[N], velocity [m/s], temperature [degC]."),
    2: ("A test in two directions needs time [s], displacement_x, displacement_y [m], "
        "force_x, force_y [N], and optionally axial_force [N], velocity_x, velocity_y [m/s], "
        "temperature [degC]; a test in one direction has displacement and force."),
}
MIN_SAMPLES = 20
MAX_DISPLACEMENT = 5.0  # [m] a larger relative displacement is taken for a unit mistake
_DERIVATIVE_WINDOW = 0.04  # [s] span of the smoothing derivative for a missing velocity
MAX_ROWS = DEFAULT_MAX_STEPS
"""Most data rows a test file may have unless the caller raises the limit (``max_rows``,
``--max-rows``): 2,000,000 rows, over half an hour at 1 kHz."""
VELOCITY_RATIO = (0.8, 1.25)
"""Allowed range of the robust slope of a velocity column on d(displacement)/dt."""
TEMPERATURE_RANGE = (-60.0, 400.0)  # [degC] a measured temperature outside is refused
VELOCITY_UNITS = {"m/s": 1.0, "mm/s": 1.0e-3, "cm/s": 1.0e-2}
"""Units a header may state for ``velocity`` and their factor to m/s."""
TEMPERATURE_UNITS = ("degc", "°c", "c", "deg c", "celsius")
_BYTES_PER_CELL = 80  # [bytes] a cell read as text (a Python str and its pointer)
_BYTES_PER_ROW = 120  # [bytes] the float histories a row becomes (kept and derived)
_SAMPLE_BYTES = 1 << 16  # [bytes] of the file read to estimate its rows


class DataError(InputError):
    """A test file or array that cannot be diagnosed, with the place and the reason named."""


@dataclass(frozen=True, eq=False)
class _Histories:
    """The fields of a test record, checked by :func:`check_record` for the record's
    number of directions."""

    name: str
    time: np.ndarray
    displacement: np.ndarray
    force: np.ndarray
    axial_force: np.ndarray
    velocity: np.ndarray | None = None
    temperature: np.ndarray | None = None
    initial_temperature: float | None = None
    rest_before: float | None = None
    velocity_measured: bool = field(init=False, default=True)
    _DIRECTIONS: ClassVar[int] = 1

    def __post_init__(self) -> None:
        check_record(self, self._DIRECTIONS)

    def __len__(self) -> int:
        return int(self.time.size)

    @property
    def constant_axial_force(self) -> bool:
        """Whether the axial force is the same at every sample."""
        return bool(np.ptp(self.axial_force) == 0.0)


@dataclass(frozen=True, eq=False)
class BearingRecord(_Histories):
    """Histories of one bearing test (SI units, read-only arrays of equal length).

    Parameters
    ----------
    name : str
        Name of the test (the file name for a CSV).
    time, displacement, force, axial_force : array_like
        Strictly increasing sample times [s], relative displacement of the plates [m],
        horizontal force [N], compressive axial load [N] > 0.
    velocity : array_like or None
        Relative velocity [m/s]; None derives it (:func:`derived_velocity`).
    temperature : array_like or None
        Measured temperature [degC], if any.
    initial_temperature : float or None
        Temperature of the plates at the start of the test [degC] (a campaign manifest's);
        None: the measured temperature's first value, else 20 degC.
    rest_before : float or None
        Rest since the end of the previous test [s]; None: long enough to cool.
    """


@dataclass(frozen=True, eq=False)
class BearingRecord2D(_Histories):
    """Histories of one bearing test in two directions (SI units, read-only arrays).

    Parameters
    ----------
    name : str
        Name of the test (the file name for a CSV).
    time : array_like, shape (n,)
        Strictly increasing sample times [s].
    displacement, force : array_like, shape (n, 2)
        Relative displacement of the plates (x, y) [m] and horizontal force (x, y) [N].
    axial_force : array_like, shape (n,)
        Compressive axial load [N] > 0.
    velocity : array_like, shape (n, 2), or None
        Relative velocity (x, y) [m/s]; None derives it per axis (:func:`derived_velocity`).
    temperature : array_like, shape (n,), or None
        Measured temperature [degC], if any.
    initial_temperature, rest_before : float or None
        As for :class:`BearingRecord` [degC], [s].
    """

    _DIRECTIONS: ClassVar[int] = 2

    @property
    def dimension(self) -> int:
        """2: a test in two directions."""
        return 2

    @property
    def speed(self) -> np.ndarray:
        """The sliding speed |v| [m/s]."""
        return np.hypot(self.velocity[:, 0], self.velocity[:, 1])

    @property
    def radius(self) -> np.ndarray:
        """The distance |u| of the plates from the centred position [m]."""
        return np.hypot(self.displacement[:, 0], self.displacement[:, 1])


@dataclass(frozen=True, eq=False)
class _Tests(SliderContact):
    """The fields of a campaign, checked to hold records of its kind."""

    tests: tuple
    effective_radius: float
    slider_diameter: float
    _RECORD: ClassVar[type] = BearingRecord

    def __post_init__(self) -> None:
        """Check the fields: ``tests`` made a tuple of records of the campaign's kind, at least
        one; R_eff [m] > 0 or inf; slider diameter [m] in (0, 10]."""
        owner = type(self).__name__
        tests = tuple(self.tests)
        if not tests or not all(isinstance(t, self._RECORD) for t in tests):
            raise InputTypeError(f"The 'tests' parameter of {owner} must be one or more "
                                 f"{self._RECORD.__name__} objects. Got {self.tests!r} "
                                 "instead.")
        object.__setattr__(self, "tests", tests)
        check_real(self.effective_radius, "effective_radius", owner, low=0.0, low_open=True,
                   allow_inf=True)
        check_real(self.slider_diameter, "slider_diameter", owner, low=0.0, low_open=True,
                   high=10.0)

@dataclass(frozen=True, eq=False)
class Campaign(_Tests):
    """The tests of one bearing (:class:`BearingRecord`), at least one, in the order run (wear
    accumulates across them), with its effective radius R_eff [m] (``inf`` for a flat slider
    or a friction damper) and slider diameter [m]."""


@dataclass(frozen=True, eq=False)
class Campaign2D(_Tests):
    """The tests in two directions of one bearing (:class:`BearingRecord2D`), at least one, in
    the order run, with its effective radius R_eff [m] (``inf`` for a flat slider) and slider
    diameter [m]."""

    _RECORD: ClassVar[type] = BearingRecord2D

    @property
    def dimension(self) -> int:
        """2: tests in two directions."""
        return 2


def check_record(record, dimension: int) -> None:
    """Check a test record's histories (in its ``__post_init__``) and give them to it as
    read-only float arrays: ``time``, ``axial_force`` and ``temperature`` of shape (n,),
    ``displacement``, ``force`` and ``velocity`` (n,) in one direction and (n, 2) in two
    (``dimension``); a missing velocity is derived (``velocity_measured`` False). And its
    conditions: ``initial_temperature`` [degC] in [-50, 300], ``rest_before`` [s] >= 0."""
    where = f"test {record.name!r}"
    checked = {}
    for column in ("time", "displacement", "force", "axial_force", "velocity", "temperature"):
        values = getattr(record, column)
        if values is None:
            continue
        arr = np.array(values, dtype=float)
        if dimension == 1 or column == "time":
            if arr.ndim != 1:
                raise DataError(f"{where}: column {column!r} must be 1-d. Got shape {arr.shape}.")
        else:
            shape = (checked["time"].size, 2) if column in VECTORS else checked["time"].shape
            if arr.shape != shape:
                raise DataError(f"{where}: {column!r} must have the shape {shape} (one row per "
                                f"time). Got {arr.shape}.")
        checked[column] = arr
    n = checked["time"].size
    for column, arr in checked.items():
        if arr.shape[0] != n:
            raise DataError(f"{where}: column {column!r} has {arr.size} values but 'time' "
                            f"has {n}; all columns must have the same length.")
        _check_finite(arr, column, where, first_row=0)
    if n < MIN_SAMPLES:
        raise DataError(f"{where}: needs at least {MIN_SAMPLES} samples. Got {n}.")
    _check_increasing(checked["time"], where, first_row=0)
    _check_values(checked, where, first_row=0)
    if "velocity" not in checked:
        u = checked["displacement"]
        checked["velocity"] = (derived_velocity(checked["time"], u) if u.ndim == 1 else
                               np.column_stack([derived_velocity(checked["time"], u[:, j])
                                                for j in range(u.shape[1])]))
        object.__setattr__(record, "velocity_measured", False)
    for column, arr in checked.items():
        arr.setflags(write=False)
        object.__setattr__(record, column, arr)
    if record.initial_temperature is not None:
        check_real(record.initial_temperature, "initial_temperature", where, low=-50.0,
                   high=300.0)
    if record.rest_before is not None:
        check_real(record.rest_before, "rest_before", where, low=0.0)


def derived_velocity(time: np.ndarray, displacement: np.ndarray) -> np.ndarray:
    """Velocity [m/s] from a displacement history [m] sampled at ``time`` [s].

    Uniform steps: the first derivative of a local quadratic least-squares fit over about
    40 ms (Savitzky-Golay), which keeps displacement noise from dominating slow motion;
    uneven steps: ``numpy.gradient``.
    """
    steps = np.diff(time)
    if np.ptp(steps) > 1e-6 * steps.mean() or time.size < 7:
        return np.gradient(displacement, time)
    from scipy.signal import savgol_filter

    window = max(5, 2 * round(0.5 * _DERIVATIVE_WINDOW / steps.mean()) + 1)
    window = min(window, time.size - (1 - time.size % 2))
    return savgol_filter(displacement, window, 2, deriv=1, delta=float(steps.mean()),
                         mode="interp")


def read_record(path: str | Path, *, axial_load: float | None = None,
                initial_temperature: float | None = None,
                rest_before: float | None = None, max_rows: int = MAX_ROWS) -> BearingRecord:
    """Read one test from a CSV file (columns: see the module docstring).

    Parameters
    ----------
    path : str or Path
        CSV file, optionally gzipped.
    axial_load : float, optional
        Constant axial load [N] for a file without an ``axial_force`` column (only then).
    initial_temperature, rest_before : float, optional
        See :class:`BearingRecord` (a campaign manifest gives them).
    max_rows : int, optional
        Most data rows the file may have, estimated before it is read (:func:`estimate_rows`);
        a file past it, or one that would not fit in the memory available, is refused.

    Raises
    ------
    DataError
        Naming the file, the column and the row of the first problem.
    """
    columns = read_columns(path, 1, axial_load=axial_load, caller="read_record",
                           max_rows=max_rows)
    return BearingRecord(_test_name(path), **columns,
                         initial_temperature=initial_temperature, rest_before=rest_before)


def read_record_2d(path: str | Path, *, axial_load: float | None = None,
                   initial_temperature: float | None = None,
                   rest_before: float | None = None,
                   max_rows: int = MAX_ROWS) -> BearingRecord2D:
    """Read one test in two directions from a CSV file (columns: the module docstring).

    ``axial_load`` [N] serves a file without an ``axial_force`` column (only then);
    ``initial_temperature``, ``rest_before`` and ``max_rows`` as for :func:`read_record`.

    Raises
    ------
    DataError
        Naming the file, the column and the row of the first problem.
    """
    columns = read_columns(path, 2, axial_load=axial_load, caller="read_record_2d",
                           max_rows=max_rows)
    return BearingRecord2D(_test_name(path), **columns,
                           initial_temperature=initial_temperature, rest_before=rest_before)


def _test_name(path: str | Path) -> str:
    return Path(path).name.removesuffix(".gz").removesuffix(".csv")


def read_columns(path: str | Path, dimension: int, *, axial_load: float | None,
                 caller: str, max_rows: int = MAX_ROWS) -> dict[str, np.ndarray]:
    """The checked histories of a test file in one direction or two (``dimension``), SI units,
    keyed as the fields of :class:`BearingRecord`: ``displacement``, ``force`` and
    ``velocity`` (if measured) (n,) in one direction, (n, 2) in two; ``axial_force`` [N] from
    its column or the constant ``axial_load``; ``caller`` is named for a bad ``axial_load``.

    Raises
    ------
    DataError
        Naming the file, the column and the row of the first problem.
    """
    import pandas as pd

    path = Path(path)
    if path.is_dir():
        raise DataError(f"{path}: is a folder, not a test file; give the CSV file.")
    if path.exists() and not path.is_file():
        raise DataError(f"{path}: not a regular file (a device or a pipe); give the CSV file.")
    if not path.is_file():
        raise DataError(f"{path}: no such file.")
    required, optional, known = _COLUMNS[dimension]
    header = check_size(path, max_rows=max_rows)
    units = _header_units(header, path, known)
    try:
        frame = pd.read_csv(path, dtype=str, keep_default_na=False, skipinitialspace=True)
    except (pd.errors.ParserError, UnicodeDecodeError, pd.errors.EmptyDataError) as error:
        raise DataError(f"{path}: not a readable CSV file with a header line ({error}).") \
            from error
    if not isinstance(frame.index, pd.RangeIndex):  # pandas took the first field for an index
        raise DataError(f"{path}: the data rows have one field more than the header line's "
                        f"{len(header)} column(s) ({', '.join(header)}); the columns would be "
                        "read shifted. Name every column in the header.")
    if len(frame.columns) != len(header):
        raise DataError(f"{path}: the header line has {len(header)} column(s) but the CSV "
                        f"reader found {len(frame.columns)}; check the header line.")
    frame.columns = [_column_name(c)[0] for c in header]
    missing = [c for c in required if c not in frame.columns]
    if dimension == 1 and missing and {"displacement_x", "force_x"} <= set(frame.columns):
        raise DataError(f"{path}: a test in two directions (columns displacement_x, "
                        "displacement_y, force_x, force_y); read it with "
                        "isolator.diagnosis.data.read_record_2d (isolator.diagnosis."
                        "load_campaign, load_manifest and dcfpb diagnose read such tests "
                        "themselves).")
    if missing:
        raise DataError(f"{path}: missing column(s) {missing}; found {list(frame.columns)}. "
                        f"{_NEEDS[dimension]}")
    if dimension == 2 and ("velocity_x" in frame.columns) != ("velocity_y" in frame.columns):
        raise DataError(f"{path}: give both velocity_x and velocity_y, or neither (the "
                        "velocity is then derived from the displacement).")
    if "axial_force" in frame.columns and axial_load is not None:
        raise DataError(f"{path}: has an 'axial_force' column and an axial load "
                        f"{axial_load!r} N was given as well; give one of the two.")
    if "axial_force" not in frame.columns and axial_load is None:
        raise DataError(f"{path}: no 'axial_force' column; give the constant axial load "
                        "[N] (--axial-load).")
    columns = {c: _numeric_column(frame[c].to_numpy(), c, path)
               for c in (*required, *optional) if c in frame.columns}
    n = len(frame)
    for column, arr in columns.items():
        _check_finite(arr, column, str(path), first_row=2, total=n)
    for column, unit in units.items():
        if column.startswith("velocity") and unit:
            columns[column] = columns[column] * VELOCITY_UNITS[unit]
    if n < MIN_SAMPLES:
        raise DataError(f"{path}: needs at least {MIN_SAMPLES} data rows. Got {n}.")
    _check_increasing(columns["time"], str(path), first_row=2)
    if "axial_force" not in columns:
        check_real(axial_load, "axial_load", caller, low=0.0, low_open=True)
        columns["axial_force"] = np.full(n, float(axial_load))
    if dimension == 2:  # one (n, 2) array a channel
        for channel in VECTORS:
            if f"{channel}_x" in columns:
                columns[channel] = np.column_stack([columns.pop(f"{channel}_{axis}")
                                                    for axis in AXES])
    _check_values(columns, str(path), first_row=2)
    if "temperature" in columns and not units.get("temperature"):
        _check_kelvin(columns["temperature"], str(path))
    return columns


def load_campaign(
    paths: Sequence[str | Path],
    *,
    effective_radius: float,
    slider_diameter: float,
    axial_load: float | None = None,
    max_rows: int = MAX_ROWS,
) -> Campaign:
    """Read the tests of a campaign, in the order run (``axial_load``, ``max_rows``: see
    :func:`read_record`), and check them (:func:`check_consistent_units`,
    :func:`check_plausible`). Tests in two directions: :func:`load_campaign_2d` (or
    :func:`load_any_campaign`)."""
    tests, places = _read_tests(paths, 1, "load_campaign", axial_load=axial_load,
                                max_rows=max_rows)
    campaign = Campaign(tests, effective_radius, slider_diameter)
    source = "column 'axial_force'" if axial_load is None else "the axial load given"
    check_plausible(campaign, places, [source] * len(tests))
    return campaign


def load_campaign_2d(
    paths: Sequence[str | Path],
    *,
    effective_radius: float,
    slider_diameter: float,
    axial_load: float | None = None,
    max_rows: int = MAX_ROWS,
) -> Campaign2D:
    """Read the tests in two directions of a campaign, in the order run, and check that they
    are of one kind and in one set of units (:func:`check_consistent_units`)."""
    tests, _ = _read_tests(paths, 2, "load_campaign_2d", axial_load=axial_load,
                           max_rows=max_rows)
    return Campaign2D(tests, effective_radius, slider_diameter)


def _read_tests(paths: Sequence[str | Path], dimension: int, caller: str, *,
                axial_load: float | None, max_rows: int) -> tuple[tuple, list[str]]:
    """The tests of ``paths`` read in one direction or two (``dimension``), every file's
    size checked before the first is read (in two directions, their kind too:
    :func:`check_one_kind`), and their units checked to agree; and the places to name."""
    if isinstance(paths, str | Path) or not paths:
        raise DataError(f"{caller} needs a list of one or more CSV files.")
    _check_max_rows(max_rows)
    existing = [p for p in paths if Path(p).is_file()]  # a missing one: "no such file" below
    if dimension == 2 and existing:
        check_one_kind(existing, max_rows=max_rows)
    for p in existing:
        check_size(Path(p), max_rows=max_rows)
    read = read_record if dimension == 1 else read_record_2d
    tests = tuple(read(p, axial_load=axial_load, max_rows=max_rows) for p in paths)
    places = [str(p) for p in paths]
    check_consistent_units(tests, places)
    return tests, places


def load_any_campaign(
    paths: Sequence[str | Path],
    *,
    effective_radius: float,
    slider_diameter: float,
    axial_load: float | None = None,
    max_rows: int = MAX_ROWS,
) -> Campaign | Campaign2D:
    """The campaign of ``paths``, tests in one direction (:func:`load_campaign`) or in two
    (:func:`load_campaign_2d`), told apart by their headers; a campaign mixing the two kinds
    is refused."""
    if isinstance(paths, str | Path) or not paths:
        raise DataError("load_any_campaign needs a list of one or more CSV files.")
    options = {"effective_radius": effective_radius, "slider_diameter": slider_diameter,
               "axial_load": axial_load, "max_rows": max_rows}
    if all(Path(p).is_file() for p in paths) and check_one_kind(paths, max_rows=max_rows) == 2:
        return load_campaign_2d(paths, **options)
    return load_campaign(paths, **options)


def header_dimension(header: Sequence[str]) -> int:
    """2 when a header (cells as written) names a column of a test in two directions, else 1."""
    names = {_column_name(cell)[0] for cell in header}
    return 2 if names & set(TWO_DIRECTION_MARKERS) else 1


def file_dimension(path: str | Path, *, max_rows: int = MAX_ROWS) -> int:
    """:func:`header_dimension` of a test file's header (its size checked first)."""
    return header_dimension(check_size(Path(path), max_rows=max_rows))


def check_one_kind(paths: Sequence[str | Path], *, max_rows: int = MAX_ROWS,
                   where: Sequence[str] | None = None) -> int:
    """The dimension shared by every test file of ``paths`` (1 or 2); a campaign mixing tests
    in one and in two directions raises a ``DataError`` naming a file of each kind."""
    kinds = [file_dimension(p, max_rows=max_rows) for p in paths]
    if len(set(kinds)) > 1:
        names = list(where) if where else [str(p) for p in paths]
        one = names[kinds.index(1)]
        two = names[kinds.index(2)]
        raise DataError(f"the campaign mixes tests in one direction ({one}: columns "
                        f"displacement, force) and in two ({two}: columns displacement_x, "
                        "displacement_y, force_x, force_y); a campaign holds tests of one kind "
                        "only. Diagnose them as two campaigns.")
    return kinds[0]


def check_plausible(campaign: Campaign, where: Sequence[str] | None = None,
                    load_sources: Sequence[str] | None = None) -> None:
    """Refuse tests whose implied levels betray a unit mistake or a wrong R_eff or axial load
    (:mod:`isolator.diagnosis.plausibility`).

    Parameters
    ----------
    campaign : Campaign
        The tests and the effective radius R_eff [m] told.
    where, load_sources : sequence of str, optional
        Per test, the file (and manifest test) to name, default ``test 'name'``, and where
        its axial load came from, default "the axial load".

    Raises
    ------
    DataError
        Naming the test, the implied level, the allowed range and the likely mistake.
    """
    from isolator.diagnosis.plausibility import implausibility, implied_levels

    for k, test in enumerate(campaign.tests):
        levels = implied_levels(test.time, test.displacement, test.force, test.axial_force,
                                derived_velocity(test.time, test.displacement))
        message = implausibility(levels, campaign.effective_radius,
                                 where[k] if where else f"test {test.name!r}",
                                 load_sources[k] if load_sources else "the axial load")
        if message:
            raise DataError(message)


UNIT_RATIO = 30.0  # tests of one campaign whose scales differ more than this mix units


def check_consistent_units(tests: Sequence,
                           where: Sequence[str] | None = None) -> None:
    """Refuse a campaign whose tests look written in different units.

    A test whose sampling interval, peak displacement or peak force [s, m, N] (in two
    directions their magnitudes |u| and |F|) differs from the
    campaign's median by a factor above ``UNIT_RATIO`` (a unit mistake is 1000) raises a
    ``DataError`` naming it (``where``: per test; default ``test 'name'``).
    """
    if len(tests) < 2:
        return
    vector = tests[0].displacement.ndim == 2  # tests in two directions: magnitudes
    scales = {
        "time step": ([float(np.median(np.diff(t.time))) for t in tests], "s"),
        "peak displacement |u|" if vector else "peak displacement":
            ([_peak(t.displacement) for t in tests], "m"),
        "peak force |F|" if vector else "peak force": ([_peak(t.force) for t in tests], "N"),
    }
    for what, (values, unit) in scales.items():
        middle = float(np.median(values))
        for k, (test, value) in enumerate(zip(tests, values, strict=True)):
            if middle > 0.0 and value > 0.0 and max(value / middle, middle / value) > UNIT_RATIO:
                name = where[k] if where else f"test {test.name!r}"
                raise DataError(f"{name}: its {what} is {value:.4g} {unit} against "
                                f"{middle:.4g} {unit} for the campaign's median test, a factor "
                                f"of {max(value / middle, middle / value):.0f}; the campaign "
                                "mixes units (every file must be in s, m and N).")


def _numeric_column(values: np.ndarray, column: str, path: Path) -> np.ndarray:
    out = np.empty(values.size)
    for i, text in enumerate(values):
        text = text.strip()
        if text == "" or text.lower() == "nan":
            out[i] = np.nan
            continue
        try:
            out[i] = float(text)
        except ValueError:
            raise DataError(f"{path}: column {column!r} has a non-numeric value {text!r} at "
                            f"row {i + 2}.") from None
    return out


def _check_finite(arr: np.ndarray, column: str, where: str, *, first_row: int,
                  total: int | None = None) -> None:
    bad = ~np.isfinite(arr)
    if bad.ndim == 2:  # a row of a channel in two directions
        bad = bad.any(axis=1)
    if not bad.any():
        return
    first = int(np.argmax(bad))
    if total is not None and np.all(bad[first:]) and first > 0:
        raise DataError(f"{where}: column {column!r} has {first} values but the file has "
                        f"{total} rows; all columns must have the same length (row "
                        f"{first + first_row} onwards is empty).")
    kind = "NaN or empty" if np.isnan(arr[first]).any() else "infinite"
    raise DataError(f"{where}: column {column!r} has {int(bad.sum())} {kind} value(s), the "
                    f"first at row {first + first_row}.")


def _check_increasing(time: np.ndarray, where: str, *, first_row: int) -> None:
    steps = np.diff(time)
    if np.any(steps <= 0.0):
        i = int(np.argmax(steps <= 0.0)) + 1
        raise DataError(f"{where}: 'time' must be strictly increasing; row {i + first_row} has "
                        f"{float(time[i])!r} s after {float(time[i - 1])!r} s.")


def _check_values(columns: dict[str, np.ndarray], where: str, *, first_row: int) -> None:
    axial = columns.get("axial_force")
    if axial is not None and np.any(axial <= 0.0):
        i = int(np.argmax(axial <= 0.0))
        raise DataError(f"{where}: 'axial_force' must be positive (compression) [N]; row "
                        f"{i + first_row} has {float(axial[i])!r}.")
    u = _axes(columns["displacement"])
    for suffix, values in u.items():
        peak = float(np.max(np.abs(values)))
        if peak > MAX_DISPLACEMENT:
            raise DataError(f"{where}: 'displacement{suffix}' reaches {peak:g}; it must be in "
                            f"metres (at most {MAX_DISPLACEMENT:g} m). Was it written in "
                            "millimetres?")
    if all(np.ptp(values) == 0.0 for values in u.values()):
        named = " and ".join(f"'displacement{suffix}'" for suffix in u)
        raise DataError(f"{where}: {named} never change{'s' if len(u) == 1 else ''}; there "
                        "is nothing to diagnose.")
    _check_temperature_range(columns.get("temperature"), where, first_row=first_row)
    if columns.get("velocity") is None:
        return
    for (suffix, displacement), velocity in zip(u.items(),
                                                _axes(columns["velocity"]).values(),
                                                strict=True):
        if np.ptp(displacement) > 0.0:
            _check_velocity(columns["time"], displacement, velocity, where, suffix)


def _axes(values: np.ndarray) -> dict[str, np.ndarray]:
    """A channel's columns by the suffix of their names: ``{"": x}`` for (n,) values,
    ``{"_x": x, "_y": y}`` for (n, 2) values."""
    if values.ndim == 1:
        return {"": values}
    return {f"_{axis}": values[:, j] for j, axis in enumerate(AXES)}


def _check_temperature_range(temperature: np.ndarray | None, where: str, *,
                             first_row: int) -> None:
    """Refuse a temperature column [degC] outside :data:`TEMPERATURE_RANGE`, naming the row."""
    if temperature is None:
        return
    low, high = TEMPERATURE_RANGE
    bad = (temperature < low) | (temperature > high)
    if bad.any():
        i = int(np.argmax(bad))
        raise DataError(f"{where}: column 'temperature' must be in degC within "
                        f"[{low:g}, {high:g}]; row {i + first_row} has "
                        f"{float(temperature[i])!r}.")


def _check_max_rows(max_rows: int) -> None:
    if isinstance(max_rows, bool) or not isinstance(max_rows, int):
        raise InputTypeError(f"max_rows (--max-rows) must be an integer in [1, inf). Got "
                             f"{max_rows!r} of type {type(max_rows).__name__}.")
    if max_rows < 1:
        raise DataError(f"max_rows (--max-rows) must be an integer in [1, inf). Got "
                        f"{max_rows!r}.")


def estimate_rows(path: str | Path) -> tuple[int, list[str]]:
    """The data rows of a CSV file (``.gz`` too) estimated from its size and its first
    64 kB, without reading the rest, and its header's column names as written.

    A file that fits in the sample is counted exactly; otherwise the rows are the (estimated
    uncompressed) size over the mean length of the complete lines sampled.

    Raises
    ------
    DataError
        For a file that cannot be opened or decoded, naming it.
    """
    path = Path(path)
    size = path.stat().st_size
    try:
        if path.suffix == ".gz":
            with path.open("rb") as raw:
                with gzip.GzipFile(fileobj=raw) as handle:
                    sample = handle.read(_SAMPLE_BYTES)
                    whole = not handle.read(1)
                    consumed = max(raw.tell(), 1)
                raw.seek(max(size - 4, 0))
                trailer = int.from_bytes(raw.read(4), "little")  # size mod 2**32
            total = len(sample) if whole else max(trailer, int(size * len(sample) / consumed))
        else:
            with path.open("rb") as handle:
                sample = handle.read(_SAMPLE_BYTES)
            whole, total = size <= len(sample), size
    except (OSError, EOFError, gzip.BadGzipFile) as error:
        raise DataError(f"{path}: cannot be read ({error}).") from error
    lines = sample.split(b"\n")
    try:
        header = next(csv.reader([lines[0].decode("utf-8-sig").rstrip("\r")]), [])
    except UnicodeDecodeError as error:
        raise DataError(f"{path}: not a readable CSV file with a header line ({error}).") \
            from error
    if whole:
        rows = sum(1 for line in lines[1:] if line.strip())
        return rows, header
    complete = lines[1:-1]  # the last line sampled may be cut
    body = sum(len(line) + 1 for line in complete)
    mean = body / len(complete) if complete else max(len(sample) - len(lines[0]), 1)
    return math.ceil((total - len(lines[0]) - 1) / mean), header


def check_size(path: str | Path, *, max_rows: int = MAX_ROWS) -> list[str]:
    """Refuse a test file past ``max_rows`` data rows or past the memory available, from its
    size and first lines (:func:`estimate_rows`), before it is read; return its header.

    Raises
    ------
    DataError
        Naming the file, its size, the rows estimated and the memory reading would take.
    """
    _check_max_rows(max_rows)
    path = Path(path)
    rows, header = estimate_rows(path)
    need = rows * (_BYTES_PER_CELL * max(len(header), 1) + _BYTES_PER_ROW)
    source = (f"{path}: about {rows:,} data rows (estimated from its size, "
              f"{_size(path.stat().st_size)}, and its first lines)")
    if rows > max_rows:
        raise DataError(
            f"{source}, past the limit of {max_rows:,} rows; reading it would take about "
            f"{_size(need)} of memory. Is it one bearing test? To read it all the same, raise "
            f"the limit (--max-rows, or max_rows= in Python) to at least {rows:,}.")
    free = available_memory()
    if free is not None and need > free:
        raise DataError(f"{source}: reading it would take about {_size(need)} of memory, more "
                        f"than the {_size(free)} available. Decimate the test or split it.")
    return header


_UNIT = re.compile(r"^(?P<name>[^\[\(]*?)\s*(?:[\[\(](?P<unit>[^\]\)]*)[\]\)])?\s*$")


def _peak(values: np.ndarray) -> float:
    """The peak magnitude of a channel (:func:`~isolator.characteristics.magnitude`)."""
    return float(np.max(magnitude(values)))


def _column_name(text: str) -> tuple[str, str | None]:
    """A header cell's column name and the unit it states in brackets, if any."""
    match = _UNIT.match(str(text).strip())
    if match is None:
        return str(text).strip(), None
    unit = match["unit"]
    return match["name"].strip(), unit.strip() if unit is not None else None


def _header_units(header: Sequence[str], path: Path,
                  known: dict[str, str] = UNITS) -> dict[str, str | None]:
    """Check a header: no column named twice (letter case and spaces aside), and a unit
    stated for a column of ``known`` (its units: :data:`UNITS`, or the two-direction table)
    must be one read here; return the units stated."""
    seen: dict[str, str] = {}
    for cell in header:
        name, _ = _column_name(cell)
        key = " ".join(name.lower().split())
        if key and key in seen:
            raise DataError(f"{path}: the column {name!r} appears twice in the header "
                            f"({seen[key]!r} and {cell.strip()!r}); which one to read is "
                            "unclear. Rename or remove one of them.")
        seen[key] = cell.strip()
    units: dict[str, str | None] = {}
    for cell in header:
        name, unit = _column_name(cell)
        if name not in known or unit is None:
            continue
        stated = unit.strip()
        if name.startswith("velocity") and stated in VELOCITY_UNITS:
            units[name] = stated
        elif name == "temperature" and stated.lower() in TEMPERATURE_UNITS:
            units[name] = "degC"
        elif name == "temperature" and stated.lower() in ("k", "kelvin"):
            raise DataError(f"{path}: column 'temperature' is stated in kelvin ({cell.strip()!r}); "
                            "give it in degC (subtract 273.15) and write 'temperature [degC]'.")
        elif stated == known[name]:
            units[name] = None
        else:
            allowed = (", ".join(VELOCITY_UNITS) if name.startswith("velocity") else
                       "degC or °C" if name == "temperature" else known[name])
            raise DataError(f"{path}: column {name!r} is stated in {stated!r} "
                            f"({cell.strip()!r}); it must be in {allowed}. Convert the column "
                            "and its header.")
    return units


def _check_kelvin(temperature: np.ndarray, where: str) -> None:
    low, high = KELVIN_LOOK
    if np.all((temperature >= low) & (temperature <= high)):
        raise DataError(
            f"{where}: column 'temperature' lies between {float(temperature.min()):.6g} and "
            f"{float(temperature.max()):.6g} throughout, which looks like kelvin (a test that "
            f"starts at {low:g} degC or more is implausible); give it in degC (subtract 273.15). "
            "If it really is in degC, say so in the header: 'temperature [degC]'.")


def velocity_ratio(time: np.ndarray, displacement: np.ndarray,
                   velocity: np.ndarray) -> float | None:
    """Robust least-squares slope of a velocity column [m/s] on the derivative of the
    displacement (:func:`derived_velocity`) over the moving samples (|du/dt| above 20 % of
    its peak), refitted without the samples whose residual exceeds five times the median
    one; None when fewer than 10 samples move. About 1 for a column in m/s with the
    displacement's sign."""
    derived = derived_velocity(time, displacement)
    peak = float(np.max(np.abs(derived)))
    moving = np.abs(derived) > 0.2 * peak
    if peak == 0.0 or np.count_nonzero(moving) < 10:
        return None
    d, v = derived[moving], velocity[moving]
    slope = float(np.dot(v, d) / np.dot(d, d))
    residual = np.abs(v - slope * d)
    keep = residual <= 5.0 * float(np.median(residual)) + 1e-300
    if np.count_nonzero(keep) >= 10:
        slope = float(np.dot(v[keep], d[keep]) / np.dot(d[keep], d[keep]))
    return slope


def _check_velocity(time: np.ndarray, displacement: np.ndarray, velocity: np.ndarray,
                    where: str, suffix: str = "") -> None:
    """Refuse a velocity column [m/s] (``velocity`` + ``suffix``, the axis's in two
    directions) whose :func:`velocity_ratio` is out of :data:`VELOCITY_RATIO`, naming the
    likely cause."""
    ratio = velocity_ratio(time, displacement, velocity)
    low, high = VELOCITY_RATIO
    if ratio is None or low <= ratio <= high:
        return
    size = abs(ratio)
    sign = " and reversed in sign (multiply it by -1)" if ratio < 0.0 else ""
    if ratio < 0.0 and low <= size <= high:
        cause = ("it looks sign-reversed: the velocity must be positive when the displacement "
                 "grows. Multiply it by -1")
    elif 300.0 <= size <= 3000.0:
        cause = (f"it looks like mm/s{sign}: divide it by 1000, or state the unit in the "
                 f"header ('velocity{suffix} [mm/s]')")
    elif 30.0 <= size <= 300.0:
        cause = (f"it looks like cm/s{sign}: divide it by 100, or state the unit in the "
                 f"header ('velocity{suffix} [cm/s]')")
    else:
        cause = (f"check its units (m/s, or state 'velocity{suffix} [mm/s]' in the header), "
                 "its sign convention (positive when the displacement grows) and that it is the "
                 "velocity of this displacement; or leave the column out and the velocity is "
                 "derived from the displacement")
    raise DataError(
        f"{where}: column 'velocity{suffix}' is {ratio:.3g} times d(displacement{suffix})/dt (a "
        f"robust fit over the moving samples; allowed {low:g}-{high:g}); {cause}.")
