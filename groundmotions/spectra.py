"""Elastic response spectra and peak ground values: pure functions on arrays.

The response of a linear oscillator, u'' + 2 zeta omega u' + omega^2 u = -a_g(t), is computed
with the exact recurrence of Nigam & Jennings (1969) for a ground acceleration linear between
samples (no step-size condition), every oscillator in one pass over the record.

References
----------
N. C. Nigam and P. C. Jennings (1969), "Calculation of response spectra from strong-motion
earthquake records", Bull. Seismol. Soc. Am. 59(2), 909-922.
A. K. Chopra, "Dynamics of Structures", Sec. 5.2 and Table 5.2.1 (the coefficients, with
m = 1, k = omega^2 and p(t) = -a_g(t)).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_array, check_real

if TYPE_CHECKING:
    from groundmotions.records import GroundMotion

__all__ = [
    "Spectrum",
    "nigam_jennings_coefficients",
    "oscillator_recurrence",
    "peak_ground_values",
    "response_spectra",
    "response_spectrum",
    "sdof_response",
    "spectrum",
]


class Spectrum(NamedTuple):
    """An elastic response spectrum.

    Attributes
    ----------
    periods : numpy.ndarray
        Oscillator periods [s].
    sd : numpy.ndarray
        Spectral displacement, max |u| of the relative displacement [m].
    sv, sa : numpy.ndarray
        Pseudo-spectral velocity omega sd [m/s] and acceleration omega^2 sd [m/s^2] (the PGA at
        period 0).
    damping : float
        Damping ratio [-].
    """

    periods: np.ndarray
    sd: np.ndarray
    sv: np.ndarray
    sa: np.ndarray
    damping: float


def _check_record(acceleration: object, dt: object, owner: str) -> tuple[np.ndarray, float]:
    acc = check_array(acceleration, "acceleration", owner, min_length=2)
    return acc, check_real(dt, "dt", owner, low=0.0, low_open=True)


def _check_periods(periods: object, owner: str, *, allow_zero: bool) -> np.ndarray:
    values = np.atleast_1d(periods) if np.ndim(periods) == 0 else periods
    return check_array(values, "periods", owner, low=0.0, low_open=not allow_zero)


def _check_damping(damping: object, owner: str, size: int | None = None) -> float | np.ndarray:
    """One damping ratio in [0, 1), or (where ``size`` is given) one per oscillator."""
    if size is None or np.ndim(damping) == 0:
        return check_real(damping, "damping", owner, low=0.0, high=1.0, high_open=True)
    ratios = check_array(damping, "damping", owner, low=0.0)
    if ratios.shape != (size,) or (ratios >= 1.0).any():
        raise InputError(
            f"The 'damping' parameter of {owner} must be a float in [0, 1) or {size} such "
            f"floats, one per period. Got {damping!r} instead."
        )
    return ratios


def nigam_jennings_coefficients(omega: np.ndarray, damping: float, dt: float) -> np.ndarray:
    """Coefficients of the exact recurrence for a piecewise-linear load, per oscillator of
    circular frequency ``omega`` > 0 [rad/s] and damping ratio ``damping`` in [0, 1) [-] (one, or
    one per frequency), over a time step ``dt`` [s].

    Returns
    -------
    numpy.ndarray, shape (2, 4, len(omega))
        ``[[A, B, C, D], [A', B', C', D']]`` such that, with p = -a_g (Chopra, Table 5.2.1),
        ``u[i+1] = A u[i] + B v[i] + C p[i] + D p[i+1]`` and
        ``v[i+1] = A' u[i] + B' v[i] + C' p[i] + D' p[i+1]``; C, D, C' and D' lose digits
        when omega dt is small (~1e-9 relative at T = 10 s with dt = 0.005 s).
    """
    owner = "nigam_jennings_coefficients"
    w = check_array(np.atleast_1d(omega), "omega", owner, low=0.0, low_open=True)
    z = _check_damping(damping, owner, w.size)
    dt = check_real(dt, "dt", owner, low=0.0, low_open=True)
    root = np.sqrt(1.0 - z * z)
    wd = w * root  # damped circular frequency [rad/s]
    e = np.exp(-z * w * dt)
    s, c = np.sin(wd * dt), np.cos(wd * dt)
    k = w * w  # stiffness per unit mass [1/s^2]
    r = z / root
    a = e * (r * s + c)
    b = e * s / wd
    cc = (
        2 * z / (w * dt) + e * (((1 - 2 * z * z) / (wd * dt) - r) * s - (1 + 2 * z / (w * dt)) * c)
    ) / k
    d = (1 - 2 * z / (w * dt) + e * ((2 * z * z - 1) / (wd * dt) * s + 2 * z / (w * dt) * c)) / k
    a1 = -e * w / root * s
    b1 = e * (c - r * s)
    c1 = (-1 / dt + e * ((w / root + z / (dt * root)) * s + c / dt)) / k
    d1 = (1 - e * (r * s + c)) / (k * dt)
    return np.array([[a, b, cc, d], [a1, b1, c1, d1]])


_CHUNK = 256  # steps whose load terms are formed at once by the recurrence


def oscillator_recurrence(
    acceleration: np.ndarray,
    dt: float,
    omega: np.ndarray,
    damping: float,
    out: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """Run the recurrence from rest over the record, all oscillators at once; return max |u|
    per oscillator [m], shape (n,), or (m, n) for m records side by side (npts, m). Given
    ``out = (u, v)`` of shape (npts, n), the histories are written into them too."""
    (a, b, c, d), (a1, b1, c1, d1) = nigam_jennings_coefficients(omega, damping, dt)
    p = -acceleration
    p = p[:, :, None] if p.ndim == 2 else p[:, None]  # (npts, [m,] 1) against (n,) oscillators
    shape = np.broadcast_shapes(p.shape[1:], omega.shape)
    u, v, peak = np.zeros(shape), np.zeros(shape), np.zeros(shape)
    u_next, v_next, work = np.empty(shape), np.empty(shape), np.empty(shape)
    steps = p.shape[0] - 1
    chunk = min(_CHUNK, max(steps, 1))
    load_u, load_v = np.empty((chunk, *shape)), np.empty((chunk, *shape))
    for first in range(0, steps, chunk):
        last = min(first + chunk, steps)
        p0, p1 = p[first:last], p[first + 1:last + 1]
        f, g = load_u[:last - first], load_v[:last - first]
        np.add(np.multiply(c, p0, out=f), d * p1, out=f)  # the load terms of a whole chunk
        np.add(np.multiply(c1, p0, out=g), d1 * p1, out=g)
        for j in range(last - first):
            # u' = (a u + b v) + (c p0 + d p1), v' = (a1 u + b1 v) + (c1 p0 + d1 p1), in place
            np.multiply(a, u, out=u_next)
            u_next += np.multiply(b, v, out=work)
            u_next += f[j]
            np.multiply(a1, u, out=v_next)
            v_next += np.multiply(b1, v, out=work)
            v_next += g[j]
            u, u_next, v, v_next = u_next, u, v_next, v
            np.maximum(peak, np.abs(u, out=work), out=peak)
            if out is not None:
                out[0][first + j + 1], out[1][first + j + 1] = u, v
    return peak


def sdof_response(
    acceleration: np.ndarray, dt: float, periods: np.ndarray,
    damping: float | np.ndarray = 0.05,
) -> tuple[np.ndarray, np.ndarray]:
    """Relative displacement [m] and velocity [m/s] histories, each of shape
    (npts, len(periods)), of linear oscillators from rest under ``acceleration`` [m/s^2] sampled
    every ``dt`` [s]; ``periods`` > 0 [s], ``damping`` in [0, 1) [-], one or one per period."""
    owner = "sdof_response"
    acc, step = _check_record(acceleration, dt, owner)
    t = _check_periods(periods, owner, allow_zero=False)
    zeta = _check_damping(damping, owner, t.size)
    u = np.zeros((acc.size, t.size))
    v = np.zeros((acc.size, t.size))
    oscillator_recurrence(acc, step, 2 * np.pi / t, zeta, out=(u, v))
    return u, v


def response_spectrum(
    acceleration: np.ndarray, dt: float, periods: np.ndarray, damping: float = 0.05
) -> Spectrum:
    """Elastic displacement, pseudo-velocity and pseudo-acceleration spectra (a `Spectrum`)
    of a record.

    Parameters
    ----------
    acceleration : array_like
        Ground acceleration samples [m/s^2], linear between samples.
    dt : float
        Time step [s].
    periods : array_like
        Oscillator periods, >= 0 [s]; at 0 (a rigid oscillator) sd = sv = 0 and sa = PGA.
    damping : float
        Damping ratio in [0, 1) [-].

    Notes
    -----
    Peaks are taken at the sample times: for periods shorter than a few dt the true peak may fall
    between samples (resample the record if that matters).
    """
    owner = "response_spectrum"
    acc, step = _check_record(acceleration, dt, owner)
    t = _check_periods(periods, owner, allow_zero=True)
    zeta = _check_damping(damping, owner)
    sd, sv, sa = _spectra(acc[:, None], step, t, zeta)
    return Spectrum(t, sd[0], sv[0], sa[0], zeta)


def _spectra(acc: np.ndarray, step: float, t: np.ndarray, zeta: float,
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """sd [m], sv [m/s], sa [m/s^2] of shape (m, len(t)) of the checked records acc (npts, m)."""
    shape = (acc.shape[1], t.size)
    sd, sv, sa = np.zeros(shape), np.zeros(shape), np.zeros(shape)
    rigid = t == 0.0
    sa[:, rigid] = np.max(np.abs(acc), axis=0)[:, None]
    if (~rigid).any():
        omega = 2 * np.pi / t[~rigid]
        sd[:, ~rigid] = oscillator_recurrence(acc, step, omega, zeta)
        sv[:, ~rigid] = omega * sd[:, ~rigid]
        sa[:, ~rigid] = omega**2 * sd[:, ~rigid]
    return sd, sv, sa


def response_spectra(
    accelerations: np.ndarray, dt: float, periods: np.ndarray, damping: float = 0.05
) -> Spectrum:
    """`response_spectrum` of m records sampled alike, ``accelerations`` of shape (npts, m)
    [m/s^2], in one pass; ``dt``, ``periods`` and ``damping`` as there. The `Spectrum`'s ``sd``
    [m], ``sv`` [m/s] and ``sa`` [m/s^2] have shape (m, len(periods)).
    """
    owner = "response_spectra"
    acc = check_array(accelerations, "accelerations", owner, ndim=2, min_length=2)
    step = check_real(dt, "dt", owner, low=0.0, low_open=True)
    t = _check_periods(periods, owner, allow_zero=True)
    zeta = _check_damping(damping, owner)
    return Spectrum(t, *_spectra(acc, step, t, zeta), zeta)


def spectrum(motion: GroundMotion, periods: np.ndarray, damping: float = 0.05) -> Spectrum:
    """`response_spectrum` of a `GroundMotion` (acceleration [m/s^2], dt [s])."""
    if not (hasattr(motion, "acceleration") and hasattr(motion, "dt")):
        raise InputTypeError(f"The 'motion' parameter of spectrum must be a GroundMotion. Got "
                             f"{motion!r:.80} instead.")
    return response_spectrum(motion.acceleration, motion.dt, periods, damping)


def peak_ground_values(acceleration: np.ndarray, dt: float) -> tuple[float, float, float]:
    """Peak ground acceleration [m/s^2], velocity [m/s] and displacement [m] of ``acceleration``
    [m/s^2] sampled every ``dt`` [s], integrated from rest by the trapezoid rule without
    baseline correction."""
    acc, step = _check_record(acceleration, dt, "peak_ground_values")
    velocity = np.concatenate(([0.0], np.cumsum(0.5 * step * (acc[1:] + acc[:-1]))))
    displacement = np.concatenate(([0.0], np.cumsum(0.5 * step * (velocity[1:] + velocity[:-1]))))
    return (
        float(np.max(np.abs(acc))),
        float(np.max(np.abs(velocity))),
        float(np.max(np.abs(displacement))),
    )
