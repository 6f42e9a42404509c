"""Frictional heating of a sliding surface: a semi-infinite solid under a moving heat source.

The temperature rise [degC] at a point of the surface under a heat flux history q(t) [W/m^2] is
(Eq. 4)

    dT(t) = c * integral_0^t q(t - tau) / sqrt(tau) dtau,    c = sqrt(D) / (k sqrt(pi)),

k the thermal conductivity, D the diffusivity. A point takes the flux while within
sqrt(pi) r / 2 of the slider centre (Eq. 5), or within lambda r for the centre point (Eq. 6).

The flux is piecewise constant over the time steps: the newest interval is integrated exactly,
2 c q_n sqrt(dt_n), the older history by a sum of exponentials 1/sqrt(tau) ~ sum_k w_k
exp(-s_k tau) with an exact one-step recursion, O(1) per step and point (Jiang, Zhang, Zhang &
Zhang 2017, Commun. Comput. Phys. 21; Beylkin & Monzon 2005). A trial never changes the state, a
commit adds one interval, an uncommitted trial is dropped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from dcfpb.common.errors import CapacityExceeded, InputError
from dcfpb.common.validation import check_real
from isolator.compiled.kernels import (
    advance_states,
    contact_history,
    heated_window,
    jit,
    ptv_trial,
)


@dataclass(frozen=True)
class ThermalProperties:
    """Thermal properties of the sliding plate, taken as a semi-infinite solid.

    Parameters
    ----------
    conductivity : float
        Thermal conductivity k [W/(m degC)]; default 16 (0.016 W/(mm degC), JSME data book).
    diffusivity : float
        Thermal diffusivity D [m^2/s]; default 4.07e-6 (4.07 mm^2/s).
    initial_temperature : float
        Temperature T0 of the surface before any sliding [degC]; default 20.
    """

    conductivity: float = 16.0
    diffusivity: float = 4.07e-6
    initial_temperature: float = 20.0

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_real(self.conductivity, "conductivity", owner, low=0.0, low_open=True)
        check_real(self.diffusivity, "diffusivity", owner, low=0.0, low_open=True)
        check_real(self.initial_temperature, "initial_temperature", owner, low=-273.15, high=1000.0)

    @property
    def flux_coefficient(self) -> float:
        """c = sqrt(D) / (k sqrt(pi)) of Eq. 4 [degC m^2 / (W s^0.5)]."""
        return float(np.sqrt(self.diffusivity) / (self.conductivity * np.sqrt(np.pi)))


@dataclass(frozen=True)
class SumOfExponentials:
    """1/sqrt(tau) ~ sum_k weights_k exp(-rates_k tau) [s^-0.5]: decay rates s_k [1/s] and
    non-negative weights w_k [s^-0.5], within the relative ``tolerance`` [-] (checked on a dense
    grid) for lags from ``min_lag`` to ``max_lag`` [s]."""

    rates: np.ndarray = field(repr=False)
    weights: np.ndarray = field(repr=False)
    min_lag: float
    max_lag: float
    tolerance: float

    def __call__(self, lag: np.ndarray) -> np.ndarray:
        """The approximation of 1/sqrt(lag) [s^-0.5] at ``lag`` [s]."""
        lag = np.asarray(lag, dtype=float)
        return np.exp(-np.multiply.outer(lag, self.rates)) @ self.weights


@lru_cache(maxsize=8)
def sum_of_exponentials(
    min_lag: float = 1.0e-6, max_lag: float = 1.0e4, tolerance: float = 1.0e-7
) -> SumOfExponentials:
    """The sum of exponentials within the relative ``tolerance`` [-] of 1/sqrt(tau) for lags from
    ``min_lag`` to ``max_lag`` [s]: geometric rates, weights by non-negative least squares, terms
    added until the tolerance is met (about 50 for the default ten decades).

    Raises
    ------
    ValueError
        For a bad range or tolerance, or when 200 terms do not reach it.
    """
    from scipy.optimize import nnls  # here: a process that only compiles never pays for it

    owner = "sum_of_exponentials"
    check_real(min_lag, "min_lag", owner, low=1e-12, high=1.0)
    check_real(max_lag, "max_lag", owner, low=10.0 * min_lag, high=1e12)
    check_real(tolerance, "tolerance", owner, low=1e-13, high=1e-2)
    decades = np.log10(max_lag / min_lag)
    check_grid = np.geomspace(min_lag, max_lag, int(2000 * decades))
    n_terms = int(np.ceil(4.0 * decades))
    while n_terms <= 200:
        rates = np.geomspace(0.1 / max_lag, 10.0 / min_lag, n_terms)
        fit_grid = np.geomspace(min_lag, max_lag, 20 * n_terms)
        design = np.exp(-np.outer(fit_grid, rates)) * np.sqrt(fit_grid)[:, None]
        weights, _ = nnls(design, np.ones_like(fit_grid), maxiter=50 * n_terms)
        approx = np.exp(-np.outer(check_grid, rates)) @ weights
        error = float(np.max(np.abs(approx * np.sqrt(check_grid) - 1.0)))
        if error <= tolerance:
            keep = weights > 0.0
            return SumOfExponentials(
                rates[keep].copy(), weights[keep].copy(), min_lag, max_lag, error
            )
        n_terms += 4
    raise InputError(
        f"sum_of_exponentials could not reach a relative error of {tolerance:g} on "
        f"[{min_lag:g}, {max_lag:g}] s with 200 terms; widen the tolerance."
    )


@dataclass(frozen=True)
class MonitorLine:
    """The precise model's monitor points: a line through the plate centre along the sliding
    direction (Fig. 3a), a point every ``spacing`` [m] (the paper's 5 mm), out to ``half_length``
    [m] from the centre (None: the slider's path at the displacement capacity). The contact
    temperature is the mean over the points within sqrt(pi) r / 2 of the slider centre (Eq. 5).
    """

    spacing: float = 0.005
    half_length: float | None = None

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_real(self.spacing, "spacing", owner, low=1e-5, high=0.1)
        if self.half_length is not None:
            check_real(self.half_length, "half_length", owner, low=0.0, low_open=True, high=100.0)

    def points(self, contact_radius: float, travel: float) -> np.ndarray:
        """Point positions on the plate [m] covering a slider path of +-``travel`` [m]."""
        half = self.half_length
        if half is None:
            half = travel + 0.5 * np.sqrt(np.pi) * contact_radius + self.spacing
        n_half = int(np.ceil(half / self.spacing - 1e-9))
        return self.spacing * np.arange(-n_half, n_half + 1, dtype=float)

    def flux_half_width(self, contact_radius: float) -> float:
        """Half side of the square of equal area, sqrt(pi) r / 2 (Eq. 5) [m]."""
        return float(0.5 * np.sqrt(np.pi) * contact_radius)

    average_over_contact = True


@dataclass(frozen=True)
class CentrePoint:
    """The simplified model's single monitor point at the plate centre (Fig. 3b, 3c), heated
    while the slider centre is within lambda r of it (Eq. 6), lambda the ``refinement`` [-]: 0.5
    the paper's refined model, sqrt(pi)/2 = 0.886 Kumar's unrefined centre point."""

    refinement: float = 0.5

    def __post_init__(self) -> None:
        check_real(self.refinement, "refinement", type(self).__name__, low=0.0, low_open=True,
                   high=2.0)

    def points(self, contact_radius: float, travel: float) -> np.ndarray:
        """The single point at the plate centre [m]."""
        return np.zeros(1)

    def flux_half_width(self, contact_radius: float) -> float:
        """lambda r (Eq. 6) [m]."""
        return float(self.refinement * contact_radius)

    average_over_contact = False


HeatingLayout = MonitorLine | CentrePoint


_FACTOR_CACHE_SIZE = 16  # distinct step sizes whose factors are kept


@jit
def step_factors(rates, weights, coefficient, dt, step, weighted_decay):
    """Fill ``step`` (2, K) with exp(-s_k dt) and (1 - exp(-s_k dt)) / s_k, and
    ``weighted_decay`` (K,) with w_k exp(-s_k dt); return 2 c sqrt(dt) [degC m^2 / W]."""
    for k in range(rates.shape[0]):
        decay = np.exp(-rates[k] * dt)
        step[0, k] = decay
        step[1, k] = (1.0 - decay) / rates[k]
        weighted_decay[k] = weights[k] * decay
    return 2.0 * coefficient * np.sqrt(dt)


def cached_step_factors(cache: dict, kernel: SumOfExponentials, coefficient: float,
                        dt: float) -> tuple[np.ndarray, np.ndarray, float]:
    """The :func:`step_factors` of a step ``dt`` [s] for the flux coefficient ``coefficient``
    c: exp(-s_k dt) and (1 - exp(-s_k dt)) / s_k stacked (2, K), w_k exp(-s_k dt) (K,) and
    2 c sqrt(dt) [degC m^2 / W], computed exactly for each distinct dt and kept in ``cache`` for
    the last few. Raises InputError for a step shorter than the kernel's ``min_lag``."""
    entry = cache.get(dt)
    if entry is None:
        if dt < kernel.min_lag:
            raise InputError(
                f"The time step {dt:g} s is shorter than the heating kernel's min_lag "
                f"{kernel.min_lag:g} s; build the kernel with a smaller min_lag."
            )
        size = kernel.rates.size
        step, weighted = np.empty((2, size)), np.empty(size)
        newest = step_factors(kernel.rates, kernel.weights, coefficient, dt, step, weighted)
        if len(cache) >= _FACTOR_CACHE_SIZE:
            cache.pop(next(iter(cache)))  # the oldest entry
        entry = cache[dt] = (step, weighted, float(newest))
    return entry


class SurfaceHeating:
    """Temperature of one sliding surface under a moving slider, with trial / commit: the
    monitor points of ``layout`` for a slider of ``contact_radius`` r [m] whose centre moves up to
    ``travel`` [m] from the plate centre, the plate's ``thermal`` properties and ``kernel``."""

    def __init__(
        self,
        layout: HeatingLayout,
        contact_radius: float,
        travel: float,
        thermal: ThermalProperties,
        kernel: SumOfExponentials,
    ) -> None:
        self.layout = layout
        self.thermal = thermal
        self.kernel = kernel
        self.points = layout.points(contact_radius, travel)
        self.flux_half_width = layout.flux_half_width(contact_radius)
        self.average_over_contact = layout.average_over_contact
        self.first_point = float(self.points[0])
        self.spacing = float(self.points[1] - self.points[0]) if self.points.size > 1 else 1.0
        self.n_points = int(self.points.size)
        self.coefficient = thermal.flux_coefficient
        self.states = np.zeros((self.points.size, kernel.rates.size))
        self._touched = (self.points.size, 0)  # [lo, hi) of points ever heated
        self.prepared_step = -1.0
        self._factor_cache: dict[float, tuple[np.ndarray, np.ndarray, float]] = {}
        self._step = np.empty((2, kernel.rates.size))
        self.weighted_decay = np.empty(kernel.rates.size)
        self.newest_coefficient = 0.0
        self._staged = (0, 0)  # the points the last friction trial heats

    def prepare(self, dt: float) -> None:
        """Make the step factors of the step ``dt`` [s] current (:func:`cached_step_factors`)."""
        self.prepared_step = dt
        self._step, self.weighted_decay, self.newest_coefficient = cached_step_factors(
            self._factor_cache, self.kernel, self.coefficient, dt)

    def window(self, position: float) -> tuple[int, int]:
        """Index range ``[lo, hi)`` of the points within the flux half width of ``position``."""
        lo, hi, inside = heated_window(position, self.first_point, self.spacing, self.n_points,
                                       self.flux_half_width, self.average_over_contact)
        if not inside:
            raise CapacityExceeded(
                f"The slider centre at {position:.4f} m has left the monitor line "
                f"(+-{self.points[-1]:.4f} m): the displacement exceeds the bearing's "
                "displacement_capacity; give a larger capacity or MonitorLine.half_length."
            )
        return lo, hi

    def trial(self, position: float, dt: float) -> tuple[float, float, tuple[int, int]]:
        """Contact temperature terms for the slider centre at ``position`` [m] on this plate after
        a trial step ``dt`` [s] since the last commit.

        Returns
        -------
        base_temperature : float
            T0 plus the history part of the contact temperature (all committed flux) [degC].
        newest_coefficient : float
            d T / d q_n [degC m^2 / W]: 2 c sqrt(dt) when points take the flux, else 0.
        heated : (int, int)
            Index range of the points that take the newest flux.
        """
        self.prepare(dt)
        heated = self.window(position)
        if self.average_over_contact:
            lo, hi = heated
        else:
            lo, hi = 0, 1
        rise = contact_history(self.states, self.weighted_decay, lo, hi)
        base = self.thermal.initial_temperature + self.coefficient * rise
        newest = self.newest_coefficient if heated[1] > heated[0] else 0.0
        return base, newest, heated

    def commit(self, dt: float, heated: tuple[int, int], flux: float) -> None:
        """Add one interval of constant ``flux`` [W/m^2] on the ``heated`` points."""
        if dt != self.prepared_step:
            self.prepare(dt)
        self._touched = advance_states(self.states, self._step, *self._touched, *heated, flux)

    def constants(self) -> dict[str, float]:
        """The layout's constants of :func:`~isolator.compiled.layout.pack_ptv`."""
        return {"first_point": self.first_point, "spacing": self.spacing,
                "n_points": self.n_points, "flux_half_width": self.flux_half_width,
                "average_over_contact": self.average_over_contact,
                "flux_coefficient": self.coefficient}

    def friction_trial(self, position: tuple[float, float], velocity: tuple[float, float],
                       pressure: float, speed: float, dt: float,
                       parameters: np.ndarray) -> tuple[float, float, float, float]:
        """Eq. 7 solved with this surface's contact temperature for the slider centre at
        ``position`` (x, y) [m] on the plate after ``dt`` [s]: ``(mu, d mu / d|v| [s/m],
        temperature [degC], flux [W/m^2])`` (:func:`~isolator.compiled.kernels.ptv_trial` on the
        packed ``parameters``); ``velocity`` is not used. The heated points are kept for
        :meth:`commit_trial`.

        Raises
        ------
        dcfpb.common.errors.CapacityExceeded
            When the slider has left the monitor line.
        """
        x, y = position
        coordinate = x if self.average_over_contact or y == 0.0 else math.hypot(x, y)
        if dt != self.prepared_step:
            self.prepare(dt)
        mu, dmu_dspeed, temperature, flux, lo, hi, inside = ptv_trial(
            self.states, self.weighted_decay, parameters, coordinate, self.newest_coefficient,
            pressure, speed)
        if not inside:
            self.window(coordinate)  # raises with the full message
        self._staged = (lo, hi)
        return mu, dmu_dspeed, temperature, flux

    def commit_trial(self, dt: float, flux: float) -> None:
        """:meth:`commit` one interval ``dt`` [s] of ``flux`` [W/m^2] on the points of the last
        :meth:`friction_trial`."""
        self.commit(dt, self._staged, flux)

    def temperature_field(self) -> tuple[np.ndarray, np.ndarray] | None:
        """Positions (m, 2) [m] on the plate of the monitor line's points ever heated and their
        temperatures (m,) [degC] after the last commit; None for the centre point."""
        if not self.average_over_contact:
            return None
        lo, hi = self._touched
        points = self.points[lo:hi]
        return np.column_stack([points, np.zeros_like(points)]), self.profile()[lo:hi]

    def profile(self, dt: float = 0.0) -> np.ndarray:
        """Temperature at every monitor point ``dt`` after the last commit [degC]."""
        weighted = self.kernel.weights * np.exp(-self.kernel.rates * max(dt, 0.0))
        return self.thermal.initial_temperature + self.coefficient * (self.states @ weighted)

    def snapshot(self) -> tuple[np.ndarray, tuple[int, int]]:
        """A copy of the committed state (for tests and checkpoints)."""
        return self.states.copy(), self._touched


def exact_rise(
    times: np.ndarray, fluxes: np.ndarray, at: float, thermal: ThermalProperties
) -> float:
    """Exact Eq. 4 for a piecewise-constant flux, the tests' reference [degC]: ``fluxes`` (n,)
    [W/m^2] on the intervals between ``times`` t_0 < ... < t_n (n + 1,) [s], evaluated at
    ``at`` >= t_n [s]."""
    times = np.asarray(times, dtype=float)
    start = np.sqrt(np.maximum(at - times[:-1], 0.0))
    stop = np.sqrt(np.maximum(at - times[1:], 0.0))
    return float(2.0 * thermal.flux_coefficient * np.sum(np.asarray(fluxes) * (start - stop)))

