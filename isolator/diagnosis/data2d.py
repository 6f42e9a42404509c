"""Measured bearing tests in two directions (orbits), read and checked as in one direction.

A test in two directions is a CSV file (or ``.csv.gz``) with a header line and the columns
``time`` [s], ``displacement_x``, ``displacement_y`` [m] (relative displacement of the
plates), ``force_x``, ``force_y`` [N] (horizontal force on the bearing) and optionally
``axial_force`` [N], ``velocity_x``, ``velocity_y`` [m/s] and ``temperature`` [degC]. Units in
brackets, sizes, NaN, time order, mm, kelvin and velocity columns are checked as for a test in
one direction (:mod:`isolator.diagnosis.data`); every error names the file, the column and
the row. A campaign holds tests of one kind only: all in one direction or all in two.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from dcfpb.common.validation import check_real
from isolator.diagnosis.data import (
    MAX_DISPLACEMENT,
    MAX_ROWS,
    MIN_SAMPLES,
    VELOCITY_UNITS,
    DataError,
    _check_finite,
    _check_increasing,
    _check_kelvin,
    _check_max_rows,
    _check_temperature_range,
    _column_name,
    _header_units,
    _numeric_column,
    check_campaign,
    check_consistent_units,
    check_size,
    derived_velocity,
    set_columns,
    velocity_ratio,
)

AXES = ("x", "y")
REQUIRED_COLUMNS_2D = ("time", "displacement_x", "displacement_y", "force_x", "force_y")
OPTIONAL_COLUMNS_2D = ("axial_force", "velocity_x", "velocity_y", "temperature")
UNITS_2D = {"time": "s", "displacement_x": "m", "displacement_y": "m", "force_x": "N",
            "force_y": "N", "axial_force": "N", "velocity_x": "m/s", "velocity_y": "m/s",
            "temperature": "degC"}
TWO_DIRECTION_MARKERS = ("displacement_x", "displacement_y", "force_x", "force_y")
"""Columns whose presence marks a test in two directions."""


def header_dimension(header: Sequence[str]) -> int:
    """2 when a header (cells as written) names a column of a test in two directions, else 1."""
    names = {_column_name(cell)[0] for cell in header}
    return 2 if names & set(TWO_DIRECTION_MARKERS) else 1


def file_dimension(path: str | Path, *, max_rows: int = MAX_ROWS) -> int:
    """:func:`header_dimension` of a test file's header (its size checked first)."""
    return header_dimension(check_size(Path(path), max_rows=max_rows))


@dataclass(frozen=True, eq=False)
class BearingRecord2D:
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
        Relative velocity (x, y) [m/s]; None derives it per axis
        (:func:`~isolator.diagnosis.data.derived_velocity`).
    temperature : array_like, shape (n,), or None
        Measured temperature [degC], if any.
    initial_temperature, rest_before : float or None
        As for :class:`~isolator.diagnosis.data.BearingRecord` [degC], [s].
    """

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

    def __post_init__(self) -> None:
        where = f"test {self.name!r}"
        time = np.array(self.time, dtype=float)
        if time.ndim != 1:
            raise DataError(f"{where}: 'time' must be 1-d. Got shape {time.shape}.")
        n = time.size
        shapes = {"displacement": (n, 2), "force": (n, 2), "velocity": (n, 2),
                  "axial_force": (n,), "temperature": (n,)}
        checked = {"time": time}
        for name, shape in shapes.items():
            values = getattr(self, name)
            if values is None:
                continue
            arr = np.array(values, dtype=float)
            if arr.shape != shape:
                raise DataError(f"{where}: {name!r} must have the shape {shape} (one row per "
                                f"time). Got {arr.shape}.")
            checked[name] = arr
        for name, arr in checked.items():
            _check_finite(arr.reshape(n, -1).max(axis=1) if arr.ndim == 2 else arr, name,
                          where, first_row=0)
        if n < MIN_SAMPLES:
            raise DataError(f"{where}: needs at least {MIN_SAMPLES} samples. Got {n}.")
        _check_increasing(time, where, first_row=0)
        _check_values_2d(checked, where, first_row=0)
        if "velocity" not in checked:
            checked["velocity"] = np.column_stack(
                [derived_velocity(time, checked["displacement"][:, j]) for j in range(2)])
            object.__setattr__(self, "velocity_measured", False)
        set_columns(self, checked, where)

    def __len__(self) -> int:
        return int(self.time.size)

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
class Campaign2D:
    """The tests in two directions of one bearing, at least one, in the order run, with its
    effective radius R_eff [m] (``inf`` for a flat slider) and slider diameter [m]."""

    tests: tuple[BearingRecord2D, ...]
    effective_radius: float
    slider_diameter: float

    def __post_init__(self) -> None:
        check_campaign(self, BearingRecord2D)

    @property
    def dimension(self) -> int:
        """2: tests in two directions."""
        return 2

    @property
    def contact_radius(self) -> float:
        """Contact radius r = half the slider diameter [m]."""
        return 0.5 * self.slider_diameter

    @property
    def contact_area(self) -> float:
        """Contact area pi r^2 [m^2]."""
        return math.pi * self.contact_radius**2


def read_record_2d(path: str | Path, *, axial_load: float | None = None,
                   initial_temperature: float | None = None,
                   rest_before: float | None = None,
                   max_rows: int = MAX_ROWS) -> BearingRecord2D:
    """Read one test in two directions from a CSV file (columns: the module docstring).

    ``axial_load`` [N] serves a file without an ``axial_force`` column (only then);
    ``initial_temperature``, ``rest_before`` and ``max_rows`` as for
    :func:`~isolator.diagnosis.data.read_record`.

    Raises
    ------
    DataError
        Naming the file, the column and the row of the first problem.
    """
    import pandas as pd

    path = Path(path)
    if not path.is_file():
        raise DataError(f"{path}: no such file.")
    header = check_size(path, max_rows=max_rows)
    units = _header_units(header, path, UNITS_2D)
    try:
        frame = pd.read_csv(path, dtype=str, keep_default_na=False, skipinitialspace=True)
    except (pd.errors.ParserError, UnicodeDecodeError, pd.errors.EmptyDataError) as error:
        raise DataError(f"{path}: not a readable CSV file with a header line ({error}).") \
            from error
    if not isinstance(frame.index, pd.RangeIndex) or len(frame.columns) != len(header):
        raise DataError(f"{path}: the data rows do not have the header line's {len(header)} "
                        f"column(s) ({', '.join(header)}); name every column in the header.")
    frame.columns = [_column_name(c)[0] for c in header]
    missing = [c for c in REQUIRED_COLUMNS_2D if c not in frame.columns]
    if missing:
        raise DataError(
            f"{path}: missing column(s) {missing}; found {list(frame.columns)}. A test in two "
            "directions needs time [s], displacement_x, displacement_y [m], force_x, force_y "
            "[N], and optionally axial_force [N], velocity_x, velocity_y [m/s], temperature "
            "[degC]; a test in one direction has displacement and force.")
    if ("velocity_x" in frame.columns) != ("velocity_y" in frame.columns):
        raise DataError(f"{path}: give both velocity_x and velocity_y, or neither (the "
                        "velocity is then derived from the displacement).")
    if "axial_force" in frame.columns and axial_load is not None:
        raise DataError(f"{path}: has an 'axial_force' column and an axial load "
                        f"{axial_load!r} N was given as well; give one of the two.")
    if "axial_force" not in frame.columns and axial_load is None:
        raise DataError(f"{path}: no 'axial_force' column; give the constant axial load "
                        "[N] (--axial-load).")
    columns = {c: _numeric_column(frame[c].to_numpy(), c, path)
               for c in (*REQUIRED_COLUMNS_2D, *OPTIONAL_COLUMNS_2D) if c in frame.columns}
    n = len(frame)
    for column, arr in columns.items():
        _check_finite(arr, column, str(path), first_row=2, total=n)
    for column in ("velocity_x", "velocity_y"):
        if column in columns and units.get(column):
            columns[column] = columns[column] * VELOCITY_UNITS[units[column]]
    if n < MIN_SAMPLES:
        raise DataError(f"{path}: needs at least {MIN_SAMPLES} data rows. Got {n}.")
    _check_increasing(columns["time"], str(path), first_row=2)
    if "axial_force" not in columns:
        check_real(axial_load, "axial_load", "read_record_2d", low=0.0, low_open=True)
        columns["axial_force"] = np.full(n, float(axial_load))
    values = {
        "time": columns["time"],
        "displacement": np.column_stack([columns["displacement_x"], columns["displacement_y"]]),
        "force": np.column_stack([columns["force_x"], columns["force_y"]]),
        "axial_force": columns["axial_force"],
    }
    if "velocity_x" in columns:
        values["velocity"] = np.column_stack([columns["velocity_x"], columns["velocity_y"]])
    if "temperature" in columns:
        values["temperature"] = columns["temperature"]
    _check_values_2d(values, str(path), first_row=2)
    if "temperature" in values and not units.get("temperature"):
        _check_kelvin(values["temperature"], str(path))
    return BearingRecord2D(path.name.removesuffix(".gz").removesuffix(".csv"), **values,
                           initial_temperature=initial_temperature, rest_before=rest_before)


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
    if isinstance(paths, str | Path) or not paths:
        raise DataError("load_campaign_2d needs a list of one or more CSV files.")
    _check_max_rows(max_rows)
    check_one_kind(paths, max_rows=max_rows)
    tests = tuple(read_record_2d(p, axial_load=axial_load, max_rows=max_rows) for p in paths)
    check_consistent_units(tests, [str(p) for p in paths])
    return Campaign2D(tests, effective_radius, slider_diameter)


def load_any_campaign(
    paths: Sequence[str | Path],
    *,
    effective_radius: float,
    slider_diameter: float,
    axial_load: float | None = None,
    max_rows: int = MAX_ROWS,
):
    """The campaign of ``paths``, tests in one direction
    (:func:`~isolator.diagnosis.data.load_campaign`) or in two (:func:`load_campaign_2d`),
    told apart by their headers; a campaign mixing the two kinds is refused."""
    from isolator.diagnosis.data import load_campaign

    if isinstance(paths, str | Path) or not paths:
        raise DataError("load_any_campaign needs a list of one or more CSV files.")
    options = {"effective_radius": effective_radius, "slider_diameter": slider_diameter,
               "axial_load": axial_load, "max_rows": max_rows}
    if all(Path(p).is_file() for p in paths) and check_one_kind(paths, max_rows=max_rows) == 2:
        return load_campaign_2d(paths, **options)
    return load_campaign(paths, **options)


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


def _check_values_2d(values: dict[str, np.ndarray], where: str, *, first_row: int) -> None:
    axial = values.get("axial_force")
    if axial is not None and np.any(axial <= 0.0):
        i = int(np.argmax(axial <= 0.0))
        raise DataError(f"{where}: 'axial_force' must be positive (compression) [N]; row "
                        f"{i + first_row} has {float(axial[i])!r}.")
    u = values["displacement"]
    for j, axis in enumerate(AXES):
        peak = float(np.max(np.abs(u[:, j])))
        if peak > MAX_DISPLACEMENT:
            raise DataError(f"{where}: 'displacement_{axis}' reaches {peak:g}; it must be in "
                            f"metres (at most {MAX_DISPLACEMENT:g} m). Was it written in "
                            "millimetres?")
    if np.ptp(u[:, 0]) == 0.0 and np.ptp(u[:, 1]) == 0.0:
        raise DataError(f"{where}: 'displacement_x' and 'displacement_y' never change; there "
                        "is nothing to diagnose.")
    _check_temperature_range(values.get("temperature"), where, first_row=first_row)
    velocity = values.get("velocity")
    if velocity is None:
        return
    for j, axis in enumerate(AXES):
        if np.ptp(u[:, j]) == 0.0:
            continue
        ratio = velocity_ratio(values["time"], u[:, j], velocity[:, j])
        if ratio is not None and not 0.8 <= ratio <= 1.25:
            raise DataError(f"{where}: column 'velocity_{axis}' is {ratio:.3g} times "
                            f"d(displacement_{axis})/dt (a robust fit over the moving samples; "
                            "allowed 0.8-1.25); check its units (m/s, or state "
                            f"'velocity_{axis} [mm/s]'), its sign and that it is this "
                            "displacement's velocity, or leave it out.")
