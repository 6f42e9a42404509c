"""Record processing: integration, baseline correction, filtering, resampling, Arias intensity
and significant durations. The functions are pure: each returns a new record whose
``processing`` ends with what was done. A record is a piecewise-linear acceleration [m/s^2]
between samples, and the integrals here are exact for it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Protocol

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_int, check_real

__all__ = [
    "arias_intensity",
    "baseline_corrected",
    "filtered",
    "resampled",
    "significant_duration",
    "velocity_and_displacement",
    "zero_residuals",
]

ANTI_ALIAS_FRACTION = 0.8
"""Corner of the anti-alias low-pass as a fraction of the new Nyquist frequency [-]."""

ANTI_ALIAS_ORDER = 8
"""Butterworth order of the anti-alias low-pass (doubled by the forward-backward pass) [-]."""


_MOTION_FIELDS = ("acceleration", "dt", "name", "metadata", "processing")


class GroundMotion(Protocol):
    """What the processing reads of a record (`groundmotions.records.GroundMotion`): the
    acceleration [m/s^2] every ``dt`` [s], name, metadata and processing steps, and a constructor
    taking them in that order."""

    acceleration: np.ndarray
    dt: float
    name: str
    metadata: Mapping
    processing: tuple[str, ...]

    def __init__(self, acceleration: np.ndarray, dt: float, name: str, metadata: dict,
                 processing: tuple[str, ...]) -> None: ...

    @property
    def time(self) -> np.ndarray: ...

    @property
    def npts(self) -> int: ...

    @property
    def duration(self) -> float: ...


def _new(motion: GroundMotion, acceleration: np.ndarray, dt: float, step: str) -> GroundMotion:
    return type(motion)(
        acceleration, dt, motion.name, dict(motion.metadata), (*motion.processing, step)
    )


def _check_motion(motion: object, owner: str) -> GroundMotion:
    if not all(hasattr(motion, name) for name in _MOTION_FIELDS):
        raise InputTypeError(
            f"The 'motion' parameter of {owner} must be a GroundMotion. Got {motion!r} instead."
        )
    return motion


def velocity_and_displacement(
    acceleration: np.ndarray, dt: float
) -> tuple[np.ndarray, np.ndarray]:
    """Ground velocity [m/s] and displacement [m] from rest of ``acceleration`` [m/s^2] sampled
    every ``dt`` [s], exact for an acceleration linear between samples."""
    owner = "velocity_and_displacement"
    try:
        a = np.asarray(acceleration, dtype=float)
    except (TypeError, ValueError):
        raise InputTypeError(f"The 'acceleration' parameter of {owner} must be an array of "
                             f"floats [m/s^2]. Got {acceleration!r:.80} instead.") from None
    dt = check_real(dt, "dt", owner, low=0.0, low_open=True)
    velocity = np.concatenate(([0.0], np.cumsum(0.5 * dt * (a[1:] + a[:-1]))))
    increments = dt * velocity[:-1] + dt * dt * (a[:-1] / 3.0 + a[1:] / 6.0)
    return velocity, np.concatenate(([0.0], np.cumsum(increments)))


def baseline_corrected(motion: GroundMotion, order: int = 1) -> GroundMotion:
    """Remove the least-squares polynomial of degree ``order`` in time from the acceleration;
    ``order`` in [0, 10] and below the number of samples (0 removes the mean, 1 a linear drift).
    """
    owner = "baseline_corrected"
    motion = _check_motion(motion, owner)
    degree = check_int(order, "order", owner, low=0, high=min(10, motion.npts - 1))
    t = motion.time
    fit = np.polynomial.Legendre.fit(t, motion.acceleration, degree)
    corrected = motion.acceleration - fit(t)
    return _new(motion, corrected, motion.dt,
                f"baseline corrected: least-squares polynomial of degree {degree} removed")


def zero_residuals(motion: GroundMotion, order: int = 3) -> GroundMotion:
    """Correct the acceleration so that the final ground velocity and displacement are zero.

    Subtracts ``P''(t)``, P a polynomial of degree ``order`` (3 to 10) in t / T (T the duration)
    with P(0) = P'(0) = 0, so the record still starts from rest; P is the least-squares fit to
    the displacement history under the two end constraints (order 3: a straight-line correction
    acceleration; higher orders also remove more long-period drift).
    """
    owner = "zero_residuals"
    motion = _check_motion(motion, owner)
    degree = check_int(order, "order", owner, low=3, high=10)
    tau = motion.time / motion.duration
    # P_j = tau^2 L_j(2 tau - 1) (shifted Legendre L_j): a well-conditioned basis of the
    # polynomials of degree <= order with P(0) = P'(0) = 0; columns d^2 P_j / dt^2 [1/s^2].
    square = np.polynomial.Polynomial([0.0, 0.0, 1.0])
    basis_acc = np.column_stack([
        (square * np.polynomial.Legendre.basis(j, domain=[0.0, 1.0]).convert(
            kind=np.polynomial.Polynomial)).deriv(2)(tau)
        for j in range(degree - 1)
    ]) / motion.duration**2
    vel, disp = velocity_and_displacement(motion.acceleration, motion.dt)
    basis = [velocity_and_displacement(column, motion.dt) for column in basis_acc.T]
    basis_disp = np.column_stack([d for _, d in basis])
    constraints = np.array([[v[-1] for v, _ in basis], [d[-1] for _, d in basis]])
    m = basis_acc.shape[1]
    kkt = np.zeros((m + 2, m + 2))
    kkt[:m, :m] = basis_disp.T @ basis_disp
    kkt[:m, m:] = constraints.T
    kkt[m:, :m] = constraints
    rhs = np.concatenate((basis_disp.T @ disp, [vel[-1], disp[-1]]))
    coefficients = np.linalg.lstsq(kkt, rhs, rcond=None)[0][:m]
    corrected = motion.acceleration - basis_acc @ coefficients
    return _new(motion, corrected, motion.dt,
                f"zero residuals: displacement polynomial of degree {degree} removed (final "
                f"velocity {vel[-1]:.4g} m/s and displacement {disp[-1]:.4g} m set to 0)")


def _butterworth_sos(
    dt: float, low: float | None, high: float | None, order: int, owner: str
) -> tuple[np.ndarray, str]:
    from scipy import signal

    nyquist = 0.5 / dt
    if low is None and high is None:
        raise InputError(f"The 'low' and 'high' parameters of {owner} cannot both be None: "
                         "give a high-pass corner (low), a low-pass corner (high) or both.")
    f_low = None if low is None else check_real(
        low, "low", owner, low=0.0, high=nyquist, low_open=True, high_open=True)
    f_high = None if high is None else check_real(
        high, "high", owner, low=0.0 if f_low is None else f_low, high=nyquist, low_open=True,
        high_open=True)
    if f_low is not None and f_high is not None:
        corners, kind, text = [f_low, f_high], "bandpass", f"band-pass {f_low:g}-{f_high:g} Hz"
    elif f_low is not None:
        corners, kind, text = f_low, "highpass", f"high-pass {f_low:g} Hz"
    else:
        corners, kind, text = f_high, "lowpass", f"low-pass {f_high:g} Hz"
    sos = signal.butter(order, corners, btype=kind, fs=1.0 / dt, output="sos")
    return sos, text


def _sosfiltfilt(sos: np.ndarray, x: np.ndarray, owner: str) -> np.ndarray:
    from scipy import signal

    padlen = 3 * (2 * len(sos) + 1 - min((sos[:, 2] == 0).sum(), (sos[:, 5] == 0).sum()))
    if x.size <= padlen:
        raise InputError(f"The 'motion' parameter of {owner} must have more than {padlen} "
                         f"samples for this filter order. Got {x.size} instead.")
    return signal.sosfiltfilt(sos, x)


def filtered(
    motion: GroundMotion, low: float | None = None, high: float | None = None, order: int = 4
) -> GroundMotion:
    """Zero-phase Butterworth filter: high-pass (``low``), low-pass (``high``) or band-pass (both).

    Corners in Hz, 0 < low < high < Nyquist = 1 / (2 dt); ``order`` in [1, 10]. The filter runs
    forward and backward (``scipy.signal.sosfiltfilt``): gain 1/2 (-6 dB) at a corner; the
    result has the record's dt and length.
    """
    owner = "filtered"
    motion = _check_motion(motion, owner)
    n = check_int(order, "order", owner, low=1, high=10)
    sos, text = _butterworth_sos(motion.dt, low, high, n, owner)
    result = _sosfiltfilt(sos, motion.acceleration, owner)
    return _new(motion, result, motion.dt,
                f"filtered: zero-phase Butterworth {text}, order {n} (forward-backward)")


def _positions(npts_new: int, ratio: float, npts_old: int) -> tuple[np.ndarray, np.ndarray]:
    """Left indices and fractions of the new sample times on the old grid (ratio = new / old
    dt); a position within 1e-9 of an old sample is put on it, which keeps that sample bit for bit.
    """
    position = np.arange(npts_new) * ratio
    nearest = np.rint(position)
    on_node = np.abs(position - nearest) < 1e-9
    position[on_node] = nearest[on_node]
    position = np.clip(position, 0.0, npts_old - 1.0)
    index = np.minimum(np.floor(position).astype(int), npts_old - 2)
    return index, position - index


def resampled(motion: GroundMotion, dt: float, *, anti_alias: bool = True) -> GroundMotion:
    """The record at the time step ``dt`` [s], in (0, duration], sampled at every
    ``k dt <= duration``.

    Finer: linear interpolation, exact for the piecewise-linear record. Coarser: with
    ``anti_alias``, a zero-phase Butterworth low-pass (:data:`ANTI_ALIAS_ORDER`, corner at
    :data:`ANTI_ALIAS_FRACTION` of the new Nyquist frequency), then decimation (integer ratio) or
    linear interpolation; without it the record is sampled at the new times.
    """
    owner = "resampled"
    motion = _check_motion(motion, owner)
    # (a round-off margin: a record resampled finer may be a hair shorter than a coarse step)
    step = check_real(dt, "dt", owner, low=0.0, high=motion.duration * (1.0 + 1e-9),
                      low_open=True)
    ratio = step / motion.dt
    acc, how = motion.acceleration, "linear interpolation"
    if ratio > 1.0 + 1e-12 and anti_alias:
        corner = ANTI_ALIAS_FRACTION * 0.5 / step
        sos, _ = _butterworth_sos(motion.dt, None, corner, ANTI_ALIAS_ORDER, owner)
        acc = _sosfiltfilt(sos, acc, owner)
        how = f"anti-alias low-pass {corner:.4g} Hz (order {ANTI_ALIAS_ORDER}, zero phase), "
        how += "decimation" if abs(ratio - round(ratio)) < 1e-9 else "linear interpolation"
    npts = math.floor(motion.duration / step + 1e-9) + 1
    index, fraction = _positions(npts, ratio, motion.npts)
    values = acc[index] * (1.0 - fraction) + acc[index + 1] * fraction
    return _new(motion, values, step,
                f"resampled from dt = {motion.dt:g} s to {step:g} s ({how}, {npts} samples)")


def arias_intensity(motion: GroundMotion) -> tuple[np.ndarray, np.ndarray]:
    """Cumulative Arias intensity ``I_A(t) = pi / (2 g) * integral_0^t a^2 dt``, exact for the
    piecewise-linear record.

    Returns
    -------
    times : numpy.ndarray
        Sample times [s].
    cumulative : numpy.ndarray
        I_A at those times [m/s]; the last value is the record's Arias intensity.
    """
    motion = _check_motion(motion, "arias_intensity")
    a = motion.acceleration
    steps = motion.dt / 3.0 * (a[:-1] ** 2 + a[:-1] * a[1:] + a[1:] ** 2)
    cumulative = np.concatenate(([0.0], np.cumsum(steps))) * (np.pi / (2.0 * STANDARD_GRAVITY))
    return motion.time, cumulative


def significant_duration(motion: GroundMotion, start: float = 0.05, stop: float = 0.95) -> float:
    """Time [s] for the Arias intensity to grow from ``start`` to ``stop`` of its total.

    ``0 <= start < stop <= 1`` [-]: (0.05, 0.75) gives D5-75, (0.05, 0.95) D5-95. The record must
    have a non-zero Arias intensity; crossing times are interpolated linearly between samples.
    """
    owner = "significant_duration"
    motion = _check_motion(motion, owner)
    lo = check_real(start, "start", owner, low=0.0, high=1.0, high_open=True)
    hi = check_real(stop, "stop", owner, low=lo, high=1.0, low_open=True)
    times, cumulative = arias_intensity(motion)
    total = cumulative[-1]
    if not total > 0.0:
        raise InputError(f"The 'motion' parameter of {owner} must have a non-zero Arias "
                         f"intensity. Got {motion!r} (all zero) instead.")
    fraction = cumulative / total
    t_start, t_stop = _crossing(times, fraction, lo), _crossing(times, fraction, hi)
    return t_stop - t_start


def _crossing(times: np.ndarray, fraction: np.ndarray, level: float) -> float:
    """First time at which the non-decreasing ``fraction`` reaches ``level``."""
    i = int(np.searchsorted(fraction, level, side="left"))
    if i == 0:
        return float(times[0])
    f0, f1 = fraction[i - 1], fraction[i]
    return float(times[i - 1] + (times[i] - times[i - 1]) * (level - f0) / (f1 - f0))
