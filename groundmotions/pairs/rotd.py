"""Orientation-independent response spectra of a horizontal pair: RotD50, RotD100 (Boore 2010).

The oscillator displacement along the direction theta is ``u_theta(t) = cos(theta) u_x(t) +
sin(theta) u_y(t)``, for theta = 0, step, ..., 180 - step deg. RotDnn is the nn-th percentile
over the angles of the peaks ``max_t |u_theta(t)|``: RotD100 the largest (the maximum-direction
spectrum of ASCE 7-16), RotD50 the median.

References
----------
D. M. Boore (2010), "Orientation-independent, nongeometric-mean measures of seismic intensity
from two horizontal components of motion", Bull. Seismol. Soc. Am. 100(4), 1830-1835.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_array, check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.spectra import oscillator_recurrence

__all__ = ["RotDSpectrum", "rotd_peaks", "rotd_spectra"]

_CHUNK = 4096  # samples whose projections on every angle are formed at once
_CANDIDATES = 64  # samples of largest radius that bound the smallest peak from below


class RotDSpectrum(NamedTuple):
    """RotDnn pseudo-acceleration spectra of a horizontal pair.

    Attributes
    ----------
    periods : numpy.ndarray
        Oscillator periods [s] (0: peak ground acceleration over the directions).
    percentiles : tuple of float
        The nn of each row of ``sa`` [%].
    sa : numpy.ndarray, shape (len(percentiles), len(periods))
        RotDnn pseudo-spectral acceleration, omega^2 times the percentile of the peak
        displacements over the angles [m/s^2].
    angles : numpy.ndarray
        The directions [deg], 0 to 180 excluded.
    sa_by_angle : numpy.ndarray, shape (len(periods), len(angles))
        omega^2 max_t |u_theta(t)| per period and angle [m/s^2].
    damping : float
        Damping ratio [-].
    """

    periods: np.ndarray
    percentiles: tuple[float, ...]
    sa: np.ndarray
    angles: np.ndarray
    sa_by_angle: np.ndarray
    damping: float

    def rotd(self, percentile: float) -> np.ndarray:
        """The RotD``percentile`` spectrum [m/s^2] (one of ``percentiles``)."""
        for row, p in enumerate(self.percentiles):
            if p == percentile:
                return self.sa[row]
        raise InputError(f"The 'percentile' parameter of RotDSpectrum.rotd must be one of "
                         f"{self.percentiles} (those computed). Got {percentile!r} instead.")

    @property
    def rotd50(self) -> np.ndarray:
        """RotD50, the median over the directions [m/s^2]."""
        return self.rotd(50.0)

    @property
    def rotd100(self) -> np.ndarray:
        """RotD100, the maximum direction [m/s^2]."""
        return self.rotd(100.0)

    @property
    def rotd100_angle(self) -> np.ndarray:
        """The direction of RotD100 per period [deg] (the first one on a tie)."""
        return self.angles[np.argmax(self.sa_by_angle, axis=1)]


def _projected_peaks(u_x: np.ndarray, u_y: np.ndarray, c: np.ndarray,
                     s: np.ndarray) -> np.ndarray:
    """max over samples of |c u_x + s u_y| per angle, in chunks of samples."""
    peak = np.zeros(c.size)
    for first in range(0, u_x.size, _CHUNK):
        ux, uy = u_x[first:first + _CHUNK, None], u_y[first:first + _CHUNK, None]
        np.maximum(peak, np.abs(ux * c + uy * s).max(axis=0, initial=0.0), out=peak)
    return peak


def rotd_peaks(u_x: np.ndarray, u_y: np.ndarray, angles_deg: np.ndarray) -> np.ndarray:
    """Peak over time of ``|cos(theta) u_x + sin(theta) u_y|`` for every angle and column,
    shape (n, len(angles_deg)), in the units of the histories.

    ``u_x``, ``u_y`` of shape (npts, n) are the histories of the two components (e.g. oscillator
    displacements [m], a column per period); ``angles_deg`` the directions theta [deg]. Only the
    samples whose radius can hold a peak are projected; the result is the full computation's.
    """
    theta = np.radians(np.asarray(angles_deg, dtype=float))
    c, s = np.cos(theta), np.sin(theta)
    peak = np.zeros((u_x.shape[1], theta.size))
    for j in range(u_x.shape[1]):
        ux, uy = u_x[:, j], u_y[:, j]
        radius = np.hypot(ux, uy)
        top = np.argpartition(radius, radius.size - min(_CANDIDATES, radius.size))
        top = top[radius.size - min(_CANDIDATES, radius.size):]
        bound = _projected_peaks(ux[top], uy[top], c, s).min()
        keep = radius >= bound * (1.0 - 1e-12)
        peak[j] = _projected_peaks(ux[keep], uy[keep], c, s)
    return peak


def rotd_spectra(
    pair: GroundMotionPair,
    periods: np.ndarray,
    damping: float = 0.05,
    percentiles: Sequence[float] = (50, 100),
    *,
    angle_step: float = 1.0,
) -> RotDSpectrum:
    """RotDnn pseudo-acceleration spectra (a `RotDSpectrum`) of the horizontal components of
    a pair.

    Parameters
    ----------
    pair : GroundMotionPair
        The pair; a vertical component is not used.
    periods : array_like
        Oscillator periods, >= 0 [s] (at 0 the peak ground acceleration over the directions).
    damping : float
        Damping ratio in [0, 1) [-].
    percentiles : sequence of float
        The nn of the RotDnn to report, each in [0, 100] [%], interpolated linearly between the
        sorted peaks as by ``np.percentile`` (RotD50 of 180 angles is the mean of the 90th and
        91st).
    angle_step : float
        Step of the directions [deg], in (0, 90] and dividing 180 into a whole number of steps.

    Notes
    -----
    With ``u_y = 0`` RotD100 is the x component's `groundmotions.spectrum` to the last digit.
    """
    owner = "rotd_spectra"
    if not isinstance(pair, GroundMotionPair):
        raise InputTypeError(f"The 'pair' parameter of {owner} must be a GroundMotionPair. "
                         f"Got {pair!r} instead.")
    t = check_array(np.atleast_1d(periods) if np.ndim(periods) == 0 else periods, "periods", owner,
                    low=0.0)
    zeta = check_real(damping, "damping", owner, low=0.0, high=1.0, high_open=True)
    levels = tuple(float(p) for p in check_array(np.atleast_1d(np.asarray(percentiles,
                                                                          dtype=float)),
                                                 "percentiles", owner, low=0.0, high=100.0))
    step = check_real(angle_step, "angle_step", owner, low=0.0, high=90.0, low_open=True)
    count = round(180.0 / step)
    if abs(count * step - 180.0) > 1e-9:
        raise InputError(f"The 'angle_step' parameter of {owner} must divide 180 deg into a "
                         f"whole number of steps. Got {angle_step!r} instead.")
    angles = np.arange(count) * step
    by_angle = np.zeros((t.size, count))
    rigid = t == 0.0
    ax, ay = pair.x.acceleration[:, None], pair.y.acceleration[:, None]
    if rigid.any():
        by_angle[rigid] = rotd_peaks(ax, ay, angles)[0]
    if (~rigid).any():
        omega = 2 * np.pi / t[~rigid]
        # both components in one pass of the recurrence: u[:, 0] and u[:, 1] are x and y
        u = np.zeros((pair.npts, 2, omega.size))
        oscillator_recurrence(np.column_stack((ax[:, 0], ay[:, 0])), pair.dt, omega, zeta,
                    out=(u, np.zeros_like(u)))
        by_angle[~rigid] = omega[:, None] ** 2 * rotd_peaks(u[:, 0], u[:, 1], angles)
    sa = np.array([np.max(by_angle, axis=1) if p == 100.0 else
                   np.percentile(by_angle, p, axis=1) for p in levels])
    return RotDSpectrum(t, levels, sa, angles, by_angle, zeta)
