"""What an imposed displacement history alone decides: return-map variable, reversals, travel.

For a displacement-driven bearing the return map's z depends only on u(t) and the yield
displacement u_y, never on mu, so any friction model's force is F = N u / R_eff + mu(t) N z(t)
and a friction model is a modulation of mu(t). Pure functions on arrays.
"""

from __future__ import annotations

import numpy as np

from isolator.compiled.kernels import jit

_MAD_TO_STD = 1.4826  # standard deviation of a normal variable over its median |deviation|
_DIFFERENCE_VARIANCE = {1: 2.0, 2: 6.0, 3: 20.0, 4: 70.0}  # var(k-th difference) / var(noise)


@jit
def hysteretic_variable(displacement, yield_displacement):
    """z of the return map, z_i = clip(z_(i-1) + (u_i - u_(i-1)) / u_y, -1, 1), z_0 = 0 [-].

    The same update as :class:`isolator.bearing.BearingElement` (which starts at u = 0).
    """
    n = displacement.size
    z = np.empty(n)
    zi = 0.0
    z[0] = 0.0
    for i in range(1, n):
        zi += (displacement[i] - displacement[i - 1]) / yield_displacement
        if zi > 1.0:
            zi = 1.0
        elif zi < -1.0:
            zi = -1.0
        z[i] = zi
    return z


@jit
def _turning_points(u, threshold):
    n = u.size
    turns = np.empty(n, dtype=np.int64)
    turns[0] = 0
    count = 1
    hi = 0
    lo = 0
    direction = 0
    for i in range(1, n):
        if u[i] > u[hi]:
            hi = i
        if u[i] < u[lo]:
            lo = i
        if direction == 0:
            if u[i] - u[0] > threshold:
                direction = 1
                lo = i
            elif u[0] - u[i] > threshold:
                direction = -1
                hi = i
        elif direction == 1:
            if u[hi] - u[i] > threshold:
                turns[count] = hi
                count += 1
                direction = -1
                lo = hi
                for j in range(hi, i + 1):
                    if u[j] < u[lo]:
                        lo = j
                hi = i
        else:
            if u[i] - u[lo] > threshold:
                turns[count] = lo
                count += 1
                direction = 1
                hi = lo
                for j in range(lo, i + 1):
                    if u[j] > u[hi]:
                        hi = j
                lo = i
    return turns[:count]


def turning_points(displacement: np.ndarray, threshold: float) -> np.ndarray:
    """Indices where the motion reverses, the start (index 0) included.

    A reversal lies at the extreme of ``displacement`` [m] since the last one, confirmed once
    the motion has come back from it by more than ``threshold`` [m] (a few times the noise).
    """
    return _turning_points(np.ascontiguousarray(displacement, dtype=float), float(threshold))


def reversal_travel(
    displacement: np.ndarray, turns: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Travel since the last reversal, accumulated travel and half-cycle number per sample,
    measured between the turning points ``turns`` so that noise does not accumulate.

    Returns
    -------
    since_reversal : ndarray
        |u - u(last reversal)| [m]; the start counts as a reversal (motion from rest).
    accumulated : ndarray
        Total travel from the start [m].
    half_cycle : ndarray of int
        Number of reversals before the sample (0 before the first one).
    """
    u = np.asarray(displacement, dtype=float)
    segment = np.searchsorted(turns, np.arange(u.size), side="right") - 1
    anchor = u[turns][segment]
    since = np.abs(u - anchor)
    legs = np.abs(np.diff(u[turns]))
    before = np.concatenate([[0.0], np.cumsum(legs)])
    return since, before[segment] + since, segment.astype(np.int64)


def noise_std(signal: np.ndarray, order: int = 3) -> float:
    """Standard deviation of white noise on a smooth signal [units of the signal].

    From the median absolute ``order``-th difference: a smooth signal hardly contributes to
    a high-order difference, white noise contributes C(2k, k) times its variance, and the
    median ignores the few kinks (reversals) of a hysteresis loop.
    """
    x = np.asarray(signal, dtype=float)
    if x.size <= order + 2:
        return 0.0
    d = np.diff(x, n=order)
    mad = float(np.median(np.abs(d - np.median(d))))
    return _MAD_TO_STD * mad / float(np.sqrt(_DIFFERENCE_VARIANCE[order]))


@jit
def play_return_map(displacement, half_width, yield_displacement, inverse_radius, nominal_mu):
    """An elastic-plastic bearing behind a play of half width h: (u_b, z, engaged) per sample.

    The load path is a gap of width 2 h [m] in series with the return map's pre-sliding
    spring. A displacement increment against the force first unloads the spring (z towards 0
    over u_y [m]), then crosses the gap with no force transmitted (``engaged`` = 0, the bearing
    standing still), then loads the spring the other way. u_b is the actuator's displacement
    less the position in the gap, which starts in the middle. ``inverse_radius`` and
    ``nominal_mu`` are unused, kept for the callers' signature (the pendulum force too is
    transmitted only with the gap closed).
    """
    n = displacement.size
    ub = np.empty(n)
    z = np.empty(n)
    engaged = np.empty(n)
    zi = 0.0
    p = 0.0
    ub[0] = displacement[0]
    z[0] = 0.0
    engaged[0] = 1.0
    for i in range(1, n):
        r = displacement[i] - displacement[i - 1]
        if zi * r < 0.0:  # unload the spring towards zero force
            dz = r / yield_displacement
            if abs(dz) <= abs(zi):
                zi += dz
                r = 0.0
            else:
                r += zi * yield_displacement
                zi = 0.0
        crossing = False
        if r != 0.0 and zi == 0.0:  # cross the gap
            target = half_width if r > 0.0 else -half_width
            distance = target - p
            if abs(r) < abs(distance):
                p += r
                r = 0.0
                crossing = True
            else:
                p = target
                r -= distance
        if r != 0.0:  # load the spring the other way, sliding at |z| = 1
            zi += r / yield_displacement
            if zi > 1.0:
                zi = 1.0
            elif zi < -1.0:
                zi = -1.0
        ub[i] = displacement[i] - p
        z[i] = zi
        engaged[i] = 0.0 if crossing else 1.0
    return ub, z, engaged


def shifted(time: np.ndarray, values: np.ndarray, shift: float) -> np.ndarray:
    """``values`` at ``time - shift`` by cubic interpolation, held at the ends [units].

    A force channel that lags the displacement channel by ``shift`` [s] belongs to the
    displacement ``shifted(time, u, shift)``.
    """
    if shift == 0.0:
        return np.asarray(values, dtype=float)
    from scipy.interpolate import CubicSpline

    target = np.clip(time - shift, time[0], time[-1])
    return CubicSpline(time, values)(target)
