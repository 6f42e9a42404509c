"""Frictional heating over a whole plate: the precise model's monitor points on a grid.

The precise model (:class:`~isolator.heating.MonitorLine`, Fig. 3a) reads the contact
temperature as the mean over the points of a line along the sliding direction inside the square
of equal area (half side a = sqrt(pi) r / 2, Eq. 5). For a slider moving anywhere on the plate
this module puts the points on a grid (m s, n s) in a frame (e1, e2) fixed to the plate: a point
with |x - p1| <= a and |y - p2| <= a in that frame takes the flux and holds the line's
sum-of-exponentials history (Eq. 4); the contact temperature is the mean over those points.

By default (``orientation=None``) e1 points along the slider's position at the first commit that
heats the plate (along the velocity if the slider is then at the centre, else along x) and stays
there, so a history in one direction gives the line at any angle; a fixed orientation may be
given. Only points ever heated are stored, so the cost grows with the area swept; a stored point
is decayed exactly, exp(-s_k elapsed), when the slider comes back.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import CapacityExceeded
from dcfpb.common.validation import check_real
from isolator.compiled.kernels import heated_window, ptv_friction
from isolator.heating import MonitorLine, SumOfExponentials, ThermalProperties, cached_step_factors

_INITIAL_CAPACITY = 256  # stored points before the first growth of the arrays


@dataclass(frozen=True)
class MonitorGrid:
    """The precise model's monitor points over the plate: a square grid of ``spacing`` [m] (the
    paper's 5 mm), its first axis at ``orientation`` [deg] counter-clockwise from x (None:
    following the motion), over a square of half side ``half_length`` [m] (None: as the line)."""

    spacing: float = 0.005
    orientation: float | None = None
    half_length: float | None = None

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_real(self.spacing, "spacing", owner, low=1e-5, high=0.1)
        if self.orientation is not None:
            check_real(self.orientation, "orientation", owner, low=-360.0, high=360.0)
        if self.half_length is not None:
            check_real(self.half_length, "half_length", owner, low=0.0, low_open=True, high=100.0)

    @classmethod
    def from_line(cls, line: MonitorLine, orientation: float | None = None) -> MonitorGrid:
        """The grid of a precise model's monitor line (same spacing and extent)."""
        return cls(line.spacing, orientation, line.half_length)

    def axis(self, contact_radius: float, travel: float) -> np.ndarray:
        """Point coordinates along either axis [m]: those of the line."""
        return MonitorLine(self.spacing, self.half_length).points(contact_radius, travel)


def plate_frame(position: np.ndarray, hint: np.ndarray | None = None,
                orientation: float | None = None) -> np.ndarray:
    """The grid's axes as the rows (e1, e2) of a 2x2 rotation [-]: e1 at ``orientation`` [deg]
    from x when given, else along the slider centre ``position`` on the plate [m] when it is not
    0, else along ``hint`` (its velocity), else along x."""
    if orientation is not None:
        angle = math.radians(orientation)
        e1 = np.array([math.cos(angle), math.sin(angle)])
    else:
        e1 = np.array([1.0, 0.0])
        for direction in (position, hint):
            if direction is not None and math.hypot(direction[0], direction[1]) > 0.0:
                e1 = np.asarray(direction, dtype=float) / math.hypot(direction[0], direction[1])
                break
    return np.array([[e1[0], e1[1]], [-e1[1], e1[0]]])


class GridTrial(NamedTuple):
    """The contact terms of a trial slider position on the grid: ``rise``, the mean of
    sum_k w_k exp(-s_k dt) G_jk [W s^0.5 / m^2] over the points under the slider; ``window``,
    their index ranges ``[i_lo, i_hi) x [k_lo, k_hi)``; ``axes``, the window's frame (2, 2)."""

    rise: float
    window: tuple[int, int, int, int]
    axes: np.ndarray

    @property
    def points(self) -> int:
        """Number of grid points under the slider."""
        i_lo, i_hi, k_lo, k_hi = self.window
        return max(i_hi - i_lo, 0) * max(k_hi - k_lo, 0)


class GridHeating:
    """Temperature of one plate under a slider moving in two directions: the grid of ``layout``
    for a slider of ``contact_radius`` r [m] whose centre moves up to ``travel`` [m] from the
    plate centre, the plate's ``thermal`` properties and ``kernel``. A trial never changes the
    state; :meth:`commit` adds one interval of constant flux on the trial's window."""

    def __init__(self, layout: MonitorGrid, contact_radius: float, travel: float,
                 thermal: ThermalProperties, kernel: SumOfExponentials) -> None:
        self.layout = layout
        self.thermal = thermal
        self.kernel = kernel
        axis = layout.axis(contact_radius, travel)
        self.first_point = float(axis[0])
        self.spacing = float(layout.spacing)
        self.n_points = int(axis.size)
        self.half_length = float(axis[-1])
        self.flux_half_width = MonitorLine(layout.spacing).flux_half_width(contact_radius)
        self.coefficient = thermal.flux_coefficient
        size = kernel.rates.size
        self._states = np.zeros((_INITIAL_CAPACITY, size))
        self._stamps = np.zeros(_INITIAL_CAPACITY)
        self._grid_index = np.zeros((_INITIAL_CAPACITY, 2), dtype=np.int64)
        self._stored = 0
        self._columns: dict[int, tuple[int, np.ndarray]] = {}  # i -> (first k, storage rows)
        self._axes: np.ndarray | None = None
        self._time = 0.0  # committed time of the plate's own clock [s]
        self._factors: dict[float, tuple[np.ndarray, np.ndarray, float]] = {}
        self._staged: GridTrial | None = None  # the window of the last friction trial

    # --- geometry -------------------------------------------------------------------------

    @property
    def axes(self) -> np.ndarray | None:
        """The grid's frame (rows e1, e2), or None before any heat was committed."""
        return None if self._axes is None else self._axes.copy()

    @property
    def stored_points(self) -> int:
        """Number of points holding a history (those ever under the slider with heat)."""
        return self._stored

    def frame(self, position: np.ndarray, hint: np.ndarray | None = None) -> np.ndarray:
        """The frame a trial at ``position`` [m] uses: the fixed one, or the one it would fix."""
        if self._axes is not None:
            return self._axes
        return plate_frame(position, hint, self.layout.orientation)

    def window(self, position: np.ndarray, axes: np.ndarray) -> tuple[int, int, int, int]:
        """Index ranges of the points under a slider centred at ``position`` [m] on the plate, in
        the frame ``axes``.

        Raises
        ------
        dcfpb.common.errors.CapacityExceeded
            When the square under the slider reaches past the grid's edge.
        """
        along = float(axes[0, 0] * position[0] + axes[0, 1] * position[1])
        across = float(axes[1, 0] * position[0] + axes[1, 1] * position[1])
        i_lo, i_hi, inside_i = heated_window(along, self.first_point, self.spacing,
                                             self.n_points, self.flux_half_width, True)
        k_lo, k_hi, inside_k = heated_window(across, self.first_point, self.spacing,
                                             self.n_points, self.flux_half_width, True)
        if not (inside_i and inside_k):
            raise CapacityExceeded(
                f"The slider centre at ({position[0]:.4f}, {position[1]:.4f}) m has left the "
                f"monitor grid (+-{self.half_length:.4f} m along its axes): the displacement "
                "exceeds the bearing's displacement_capacity; give a larger capacity or "
                "MonitorLine.half_length.")
        return i_lo, i_hi, k_lo, k_hi

    # --- the step factors -----------------------------------------------------------------

    def factors(self, dt: float) -> tuple[np.ndarray, np.ndarray, float]:
        """:func:`~isolator.heating.cached_step_factors` of a step ``dt`` [s] on this plate."""
        return cached_step_factors(self._factors, self.kernel, self.coefficient, dt)

    # --- stored histories -----------------------------------------------------------------

    def _rows(self, window: tuple[int, int, int, int]) -> np.ndarray:
        """Storage rows of the stored points in ``window``."""
        i_lo, i_hi, k_lo, k_hi = window
        found = []
        for i in range(i_lo, i_hi):
            column = self._columns.get(i)
            if column is None:
                continue
            k0, rows = column
            a, b = max(k_lo - k0, 0), min(k_hi - k0, rows.size)
            if b > a:
                found.append(rows[a:b])
        if not found:
            return np.zeros(0, dtype=np.int64)
        rows = np.concatenate(found)
        return rows[rows >= 0]

    def _histories_now(self, rows: np.ndarray) -> np.ndarray:
        """Histories G_jk of ``rows`` at the committed time (a copy)."""
        histories = self._states[rows]
        elapsed = self._time - self._stamps[rows]
        stale = elapsed > 0.0
        if np.any(stale):
            histories[stale] *= np.exp(-np.multiply.outer(elapsed[stale], self.kernel.rates))
        return histories

    def _store(self, window: tuple[int, int, int, int]) -> np.ndarray:
        """Storage rows of every point of ``window``, new (zero) histories for the others."""
        i_lo, i_hi, k_lo, k_hi = window
        out = []
        for i in range(i_lo, i_hi):
            k0, rows = self._columns.get(i, (k_lo, np.zeros(0, dtype=np.int64)))
            start, stop = min(k0, k_lo), max(k0 + rows.size, k_hi)
            if start < k0 or stop > k0 + rows.size:  # widen the column's index
                wider = np.full(stop - start, -1, dtype=np.int64)
                wider[k0 - start:k0 - start + rows.size] = rows
                k0, rows = start, wider
            part = rows[k_lo - k0:k_hi - k0]
            for offset in np.flatnonzero(part < 0):
                part[offset] = self._new_point(i, k_lo + int(offset))
            self._columns[i] = (k0, rows)
            out.append(part.copy())
        return np.concatenate(out)

    def _new_point(self, i: int, k: int) -> int:
        if self._stored == self._stamps.size:
            grow = self._stamps.size
            self._states = np.vstack([self._states, np.zeros((grow, self._states.shape[1]))])
            self._stamps = np.concatenate([self._stamps, np.zeros(grow)])
            self._grid_index = np.vstack([self._grid_index, np.zeros((grow, 2), np.int64)])
        row = self._stored
        self._states[row] = 0.0
        self._stamps[row] = self._time
        self._grid_index[row] = (i, k)
        self._stored += 1
        return row

    # --- trial / commit -------------------------------------------------------------------

    def trial(self, position: np.ndarray, dt: float, hint: np.ndarray | None = None) -> GridTrial:
        """Contact terms for the slider centre at ``position`` [m] on the plate after ``dt`` [s]
        (the newest interval left to the friction solve); ``hint`` (the velocity) orients a frame
        not yet fixed while the slider is at the centre."""
        axes = self.frame(position, hint)
        window = self.window(position, axes)
        rows = self._rows(window)
        count = GridTrial(0.0, window, axes).points
        if rows.size == 0 or count == 0:
            return GridTrial(0.0, window, axes)
        _, weighted, _ = self.factors(dt)
        column_sums = self._histories_now(rows).sum(axis=0)
        return GridTrial(float(column_sums @ weighted) / count, window, axes)

    def commit(self, dt: float, trial: GridTrial, flux: float) -> None:
        """Add one interval ``dt`` [s] of constant ``flux`` [W/m^2] on the trial's window."""
        if flux != 0.0 and trial.points > 0:
            if self._axes is None:
                self._axes = np.array(trial.axes, dtype=float)
            step, _, _ = self.factors(dt)
            rows = self._store(trial.window)
            self._states[rows] = self._histories_now(rows) * step[0] + flux * step[1]
            self._stamps[rows] = self._time + dt
        self._time += dt

    def constants(self) -> dict[str, float]:
        """The grid's constants of :func:`~isolator.compiled.layout.pack_ptv`."""
        return {"first_point": self.first_point, "spacing": self.spacing,
                "n_points": self.n_points, "flux_half_width": self.flux_half_width,
                "average_over_contact": True, "flux_coefficient": self.coefficient}

    def friction_trial(self, position: tuple[float, float], velocity: tuple[float, float],
                       pressure: float, speed: float, dt: float,
                       parameters: np.ndarray) -> tuple[float, float, float, float]:
        """Eq. 7 solved with the grid's contact temperature for the slider centre at
        ``position`` (x, y) [m] on the plate after ``dt`` [s]: ``(mu, d mu / d|v| [s/m],
        temperature [degC], flux [W/m^2])``; ``velocity`` [m/s] as the :meth:`trial`'s hint. The
        window is kept for :meth:`commit_trial`."""
        grid = self.trial(np.asarray(position, dtype=float), dt,
                          hint=np.asarray(velocity, dtype=float))
        _, _, newest = self.factors(dt)
        self._staged = grid
        return ptv_friction(grid.rise, grid.points > 0, parameters, newest, pressure, speed)

    def commit_trial(self, dt: float, flux: float) -> None:
        """:meth:`commit` one interval ``dt`` [s] of ``flux`` [W/m^2] on the window of the last
        :meth:`friction_trial`."""
        self.commit(dt, self._staged, flux)

    def temperature_field(self) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`point_positions` (m, 2) [m] and :meth:`point_temperatures` (m,) [degC] of
        the stored points."""
        return self.point_positions(), self.point_temperatures()

    # --- read-outs ------------------------------------------------------------------------

    def point_indices(self) -> np.ndarray:
        """Grid indices (i, k) of the stored points, shape (m, 2); point (i, k) lies at
        (first + i s, first + k s) in the grid frame."""
        return self._grid_index[:self._stored].copy()

    def point_positions(self) -> np.ndarray:
        """Plate coordinates (x, y) of the stored points [m], shape (m, 2)."""
        local = self.first_point + self.spacing * self.point_indices().astype(float)
        axes = self._axes if self._axes is not None else np.eye(2)
        return local @ axes

    def point_temperatures(self, dt: float = 0.0) -> np.ndarray:
        """Temperature of the stored points ``dt`` [s] after the last commit [degC]; at ``dt`` = 0
        a point heated in the last step is short by the kernel's error near lag 0 (1e-4 of the
        rise for 10 ms steps)."""
        rows = np.arange(self._stored)
        weighted = self.kernel.weights * np.exp(-self.kernel.rates * max(dt, 0.0))
        rise = self._histories_now(rows) @ weighted
        return self.thermal.initial_temperature + self.coefficient * rise
