"""Plausibility of a bearing test's physical levels: catch unit mistakes before any fitting.

A test in the wrong units still reads and can be fitted, and the verdict would be on
nonsense: time in ms makes every velocity 1000 times too small, force in kN the friction
coefficient, and a wrong R_eff or axial load turns the pendulum force into an "unmodelled
stiffness" or a force that pushes along the motion. So each test's implied levels must pass:

1. the force varies (a constant column is a dead channel);
2. the sample interval and the peak |du/dt| are a bearing test's
   (:data:`MAX_SAMPLE_INTERVAL`, :data:`VELOCITY_RANGE`);
3. in the sliding phase the force follows the direction of motion (a friction loop standing
   out of the scatter) and resists it (the sign convention);
4. the friction coefficient F / N lies in :data:`MU_RANGE`;
5. the slope of force against displacement is N / R_eff within :data:`STIFFNESS_FACTOR`
   (not for R_eff = inf: a friction damper's loops tilt too).

F (the loop's half-height) and the slope k are least-squares fits of
force = k u + F sign(v) + c, F on the sliding samples and k on the middle of the loop; they
do not depend on the R_eff and axial load told, so a force in kN (both off by 1000) is told
apart from a wrong R_eff (only the slope off). Plain arrays only, no project imports, so the
input layer can use it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

MU_RANGE = (0.003, 0.8)
"""Allowed friction coefficient implied by the loop, F / N [-].

Sliding bearings span about 0.005 (lubricated PTFE) to 0.15 (dry composites; breakaway up to
0.3), friction dampers 0.5-0.6; the validation panels show 0.021-0.080 and the real
friction-damper data 0.011-0.127. The bounds are only 270 apart, so a factor of 1000 (kN for
N) takes any coefficient inside them outside.
"""
VELOCITY_RANGE = (1.0e-3, 5.0)
"""Allowed peak |du/dt| of a test [m/s]: below is a creep test (time in ms puts a 0.05-1 m/s
test at 0.05-1 mm/s); the fastest rigs reach about 2 m/s (displacement in mm makes a 5 mm/s
test 5 m/s)."""
MAX_SAMPLE_INTERVAL = 0.1
"""Largest median sample interval [s] (10 Hz): the diagnosis resolves the force within a few
mm of each reversal, its thresholds come from 100-500 Hz records, and time in ms makes any
record sampled below 10 kHz show 0.1 s or more."""
STIFFNESS_FACTOR = 3.0
"""Largest factor between the loops' slope and N / R_eff [-]: another radius than the one
told (the ``stiffness`` effect; 0.81-1.25 in the validation panels) and a spherical surface
stay well inside it; beyond it is a wrong R_eff or axial load."""
VISIBLE_FRACTION = 0.5
"""The slope is judged only where |k - N / R_eff| times the stroke exceeds this fraction of
the loop's half-height F [-]: a mismatch the loop shows, not one lost in a short stroke."""
MIN_SLOPE_STROKE = 0.01
"""Smallest stroke [m] on which the slope is judged: the middle of the loop must be past the
pre-sliding transition after each reversal (u_y up to 2 mm, about twice that to cross)."""
SLIDING_FRACTION = 0.2
"""Samples with |v| above this fraction of the peak velocity are taken as sliding [-]."""
MIN_LOOP_CONTRAST = 0.15
"""The loop's half-height must exceed this multiple of the fit's residual RMS [-]: noise
alone gives about 1 / sqrt(samples), under 0.05; the validation panels show 2.4-42, the real
friction-damper data (a play, poorly fitted by sign(v)) 0.41-2.4."""
_UNIT = 1000.0  # the factor of the unit mistakes named (ms, mm, kN)


@dataclass(frozen=True)
class Levels:
    """The physical levels a test implies (SI units).

    Parameters
    ----------
    sample_interval, peak_velocity : float
        Median sample interval [s]; peak |du/dt| [m/s].
    friction_force : float
        Half-height of the sliding-phase loop, F [N] (negative: the force aids the motion).
    slope : float
        Slope of force against displacement in the middle of the loop, k [N/m]; NaN for a
        stroke or a history too short to tell.
    scatter : float
        RMS of the sliding-phase force about the fit [N].
    axial_load, stroke : float
        Mean axial load [N]; 99th percentile of |u| [m].
    force_range, first_force : float
        Peak-to-peak force [N] (zero: a dead channel) and its first value [N].
    """

    sample_interval: float
    peak_velocity: float
    friction_force: float
    slope: float
    scatter: float
    axial_load: float
    stroke: float
    force_range: float
    first_force: float

    @property
    def mu(self) -> float:
        """Implied friction coefficient F / N [-]."""
        return self.friction_force / self.axial_load


def implied_levels(time: np.ndarray, displacement: np.ndarray, force: np.ndarray,
                   axial_force: np.ndarray, velocity: np.ndarray) -> Levels:
    """The :class:`Levels` the numbers of one test imply if they are in s, m and N.

    Parameters
    ----------
    time, displacement, force, axial_force : numpy.ndarray
        Sample times [s], relative displacement u [m], horizontal force [N], axial load [N].
    velocity : numpy.ndarray
        du/dt derived from ``displacement`` and ``time`` [m/s] (not a measured velocity
        column, whose units are not the ones checked).
    """
    u = np.asarray(displacement, dtype=float)
    force = np.asarray(force, dtype=float)
    velocity = np.asarray(velocity, dtype=float)
    peak = float(np.max(np.abs(velocity)))
    stroke = float(np.percentile(np.abs(u), 99))
    sliding = np.abs(velocity) > SLIDING_FRACTION * peak
    if np.count_nonzero(sliding) < 4:
        sliding = np.ones(u.size, dtype=bool)
    (_, friction, _), scatter = _loop_fit(u, velocity, force, sliding)
    return Levels(float(np.median(np.diff(time))), peak, friction,
                  _middle_slope(u, velocity, force, sliding, stroke), scatter,
                  float(np.mean(axial_force)), stroke, float(np.ptp(force)), float(force[0]))


def _loop_fit(u: np.ndarray, velocity: np.ndarray, force: np.ndarray,
              chosen: np.ndarray) -> tuple[np.ndarray, float]:
    """((k [N/m], F [N], offset [N]), residual RMS [N]) of force = k u + F sign(v) + c."""
    design = np.column_stack([u[chosen], np.sign(velocity[chosen]),
                              np.ones(np.count_nonzero(chosen))])
    coef, *_ = np.linalg.lstsq(design, force[chosen], rcond=None)
    residual = force[chosen] - design @ coef
    return coef, float(np.sqrt(np.mean(residual**2)))


def _middle_slope(u: np.ndarray, velocity: np.ndarray, force: np.ndarray,
                  sliding: np.ndarray, stroke: float) -> float:
    """Slope k [N/m] of the loop's middle, where both branches slide; NaN without one.

    The crossing between branches after a reversal would read as slope, so only sliding
    samples in the middle half of the stroke, more than a quarter stroke past the last reversal,
    count, for a stroke of at least :data:`MIN_SLOPE_STROKE`.
    """
    if stroke < MIN_SLOPE_STROKE:
        return math.nan
    direction = np.sign(velocity)
    moving = np.flatnonzero(direction != 0.0)
    changes = moving[1:][np.diff(direction[moving]) != 0.0]
    last = np.zeros(u.size, dtype=int)
    last[changes] = changes
    last = np.maximum.accumulate(last)
    centre = 0.5 * (float(np.max(u)) + float(np.min(u)))
    middle = (sliding & (np.abs(u - centre) < 0.5 * stroke)
              & (np.abs(u - u[last]) > 0.25 * stroke))
    if min(np.count_nonzero(middle & (velocity > 0.0)),
           np.count_nonzero(middle & (velocity < 0.0))) < 10:
        return math.nan
    return float(_loop_fit(u, velocity, force, middle)[0][0])


def implausibility(levels: Levels, effective_radius: float, where: str,
                   load_source: str = "the axial load") -> str | None:
    """The first unit mistake the ``levels`` of one test betray, or None.

    The message names ``where`` (the file, and test of a manifest), the column or value, the
    implied level, the allowed range and the likely mistake. ``effective_radius`` is the
    R_eff told [m] (``inf``: no slope check), ``load_source`` where the axial load came from.
    """
    if levels.force_range == 0.0:
        state = ("all zero" if levels.first_force == 0.0
                 else f"constant at {levels.first_force:.6g} N")
        return (f"{where}: column 'force' is {state}; it must vary with the motion. The force "
                "channel recorded nothing (a disconnected load cell, or the wrong column?).")
    for check in (_check_time, _check_loop):
        message = check(levels, where)
        if message:
            return message
    return (_check_friction(levels, where, load_source)
            or _check_slope(levels, effective_radius, where, load_source))


def _check_time(levels: Levels, where: str) -> str | None:
    dt, peak = levels.sample_interval, levels.peak_velocity
    low, high = VELOCITY_RANGE
    if dt > MAX_SAMPLE_INTERVAL:
        return (f"{where}: time looks like milliseconds: column 'time' has a sample interval "
                f"of {dt:.4g} s ({1.0 / dt:.3g} Hz); allowed: at most {MAX_SAMPLE_INTERVAL:g} s "
                f"(peak velocity |du/dt| {peak:.3g} m/s). If time is in ms, divide "
                "it by 1000.")
    if peak < low:
        return (f"{where}: time looks like milliseconds: the peak velocity |du/dt| of columns "
                f"'displacement' and 'time' is {peak:.3g} m/s, outside the {low:g}-{high:g} "
                f"m/s of a bearing test (sample interval {dt:.4g} s). If time is in ms, "
                "divide it by 1000.")
    if peak > high:
        return (f"{where}: displacement looks like mm: the peak velocity |du/dt| of columns "
                f"'displacement' and 'time' is {peak:.3g} m/s, outside the {low:g}-{high:g} "
                f"m/s of a bearing test (stroke {levels.stroke:.4g}). If displacement is in "
                "mm, divide it by 1000.")
    return None


def _check_loop(levels: Levels, where: str) -> str | None:
    f, scatter = levels.friction_force, levels.scatter
    if abs(f) < MIN_LOOP_CONTRAST * scatter:
        return (f"{where}: column 'force' shows no friction loop: its sliding-phase level "
                f"(loop half-height) is {f:.4g} N against a scatter of {scatter:.4g} N, "
                f"below the {MIN_LOOP_CONTRAST:g} x scatter allowed; the force does not "
                "follow the direction of motion (a dead or wrong force channel, or a stroke "
                f"of {levels.stroke:.3g} m too small for the bearing to slide?).")
    if f < 0.0:
        return (f"{where}: column 'force' looks sign-reversed: in the sliding phase it pushes "
                f"along the motion (loop half-height {f:.4g} N, mu = {levels.mu:.3g}, "
                "allowed: positive); the force must resist the imposed displacement. "
                "Multiply it by -1.")
    return None


def _check_friction(levels: Levels, where: str, load_source: str) -> str | None:
    mu, (low, high) = levels.mu, MU_RANGE
    if low <= mu <= high:
        return None
    text = (f"{where}: the friction coefficient implied by column 'force' (loop half-height "
            f"{levels.friction_force:.4g} N) over {load_source} ({levels.axial_load:.6g} N) "
            f"is {mu:.3g}, outside the {low:g}-{high:g} of a sliding bearing: ")
    if mu < low:
        hint = ("force looks like kN: multiply it by 1000 (or the axial load is 1000 times "
                "too large)" if low <= _UNIT * mu <= high else
                "the force is far too small for the axial load; check the units of both")
    else:
        hint = (f"{load_source} looks like kN: give it in N (multiply it by 1000)"
                if low <= mu / _UNIT <= high else
                "the force is far too large for the axial load; check the units of both")
    return text + hint + "."


def _check_slope(levels: Levels, effective_radius: float, where: str,
                 load_source: str) -> str | None:
    n, k, stroke = levels.axial_load, levels.slope, levels.stroke
    if math.isnan(k):
        return None
    if math.isinf(effective_radius):
        # no bound for R_eff = inf: a friction damper's loops tilt as steeply as a pendulum's
        # (the real damper data: apparent radii of 0.06-0.7 m), so a forgotten R_eff cannot
        # be told; the diagnosis names it ``stiffness`` with the apparent R_eff
        return None
    expected = n / effective_radius
    ratio = k / expected
    visible = abs(k - expected) * stroke > VISIBLE_FRACTION * levels.friction_force
    if not visible or 1.0 / STIFFNESS_FACTOR <= ratio <= STIFFNESS_FACTOR:
        return None
    text = (f"the loops' slope of force against displacement is {k:.4g} N/m, "
            f"{ratio:.3g} times the pendulum's N / R_eff = {expected:.4g} N/m (R_eff = "
            f"{effective_radius:g} m, {load_source} {n:.6g} N; allowed: a factor of "
            f"{STIFFNESS_FACTOR:g} either way)")
    if 1.0 / (STIFFNESS_FACTOR * _UNIT) <= ratio <= STIFFNESS_FACTOR / _UNIT:
        return (f"{where}: displacement looks like mm: {text}; if displacement is in mm, "
                "divide it by 1000.")
    implied = (f"; the slope implies R_eff = {n / k:.3g} m at that load, or an axial load of "
               f"{k * effective_radius:.4g} N at that R_eff" if k > 0.0 else
               "; the force falls as the displacement grows")
    return (f"{where}: R_eff or the axial load looks wrong: {text}{implied}. The diagnosis "
            "would blame it on an effect or on the sign convention of 'force'.")
