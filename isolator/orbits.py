"""Imposed orbits of a bearing test in two directions (:class:`Orbit`): circle, figure-eight,
square, and the sine along a line at an angle.

Every orbit starts at rest at the plate centre, with a ``"lead-in"`` block and then one block
per turn; ``angle`` [deg] rotates it counter-clockwise about the centre. ``dt`` is the largest
time step allowed: a period is cut into equal steps, their number a multiple of 4 (circle,
figure-eight) or 8 (square) so that the lead-in and every corner fall on a sample. Where the
velocity jumps, the sample takes the velocity of the block that ends there (the test rig moves
each step with the velocity of its end sample).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from dcfpb.common.validation import check_choice, check_int, check_real
from isolator.limits import DEFAULT_MAX_STEPS, HISTORY_FIELDS, check_steps
from isolator.protocols import STEPS_PER_PERIOD_MIN, LabelledBlocks, sine

ORBITS = ("circle", "figure8", "square", "line")
"""Names of the orbits :func:`orbit` makes."""


@dataclass(frozen=True, eq=False)
class Orbit(LabelledBlocks):
    """A 2D displacement history imposed on a bearing, with its exact velocity (read-only): the
    strictly increasing sample ``time`` (n,) [s], the relative ``displacement`` (x, y) (n, 2) [m]
    and the analytic ``velocity`` (n, 2) [m/s] at each, a ``name`` (e.g. ``"circle"``) and the
    labelled blocks ``segments`` ``(label, start, stop)``, both end samples included."""

    _DIMENSION: ClassVar[int] = 2

    @property
    def path_length(self) -> float:
        """Length of the polyline through the samples [m]."""
        return float(np.sum(np.hypot(*np.diff(self.displacement, axis=0).T)))


def rotation(angle: float) -> np.ndarray:
    """The 2x2 counter-clockwise rotation by ``angle`` [deg]."""
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    return np.array([[c, -s], [s, c]])


def _check(owner: str, size: float, size_name: str, period: float, cycles: int, dt: float,
           angle: float) -> tuple[float, float, int, float, float]:
    size = check_real(size, size_name, owner, low=0.0, low_open=True, high=10.0)
    period = check_real(period, "period", owner, low=0.0, low_open=True)
    cycles = check_int(cycles, "cycles", owner, low=1)
    dt = check_real(dt, "dt", owner, low=0.0, low_open=True,
                    high=period / STEPS_PER_PERIOD_MIN)
    angle = check_real(angle, "angle", owner, low=-360.0, high=360.0)
    return size, period, cycles, dt, angle


def _per_period(owner: str, period: float, cycles: int, dt: float, multiple: int,
                max_steps: int, lead_in: float = 0.0) -> int:
    """Equal steps per period, no longer than ``dt`` and a multiple of ``multiple``, after
    checking the whole orbit's length (:func:`isolator.limits.check_steps`)."""
    n = multiple * max(1, math.ceil(period / (multiple * dt) - 1e-9))
    total = round(n * (cycles + lead_in))
    check_steps(total, what=f"The orbit of {owner}", duration=period * (cycles + lead_in),
                dt=period / n, bytes_per_step=8 * (HISTORY_FIELDS + 8), max_steps=max_steps,
                raise_with=f"the max_steps argument of isolator.orbits.{owner}")
    return n


def _finish(name: str, time: np.ndarray, u: np.ndarray, v: np.ndarray, angle: float,
            segments: tuple[tuple[str, int, int], ...]) -> Orbit:
    turn = rotation(angle)
    return Orbit(time, u @ turn.T, v @ turn.T, name, segments)


def circle(radius: float, period: float, cycles: int, dt: float, *, angle: float = 0.0,
           max_steps: int = DEFAULT_MAX_STEPS) -> Orbit:
    """A circle of ``radius`` R [m] about the centre at constant speed 2 pi R / T: a lead-in of a
    quarter period along x to (R, 0), then ``cycles`` counter-clockwise turns of ``period`` T [s],
    in steps no longer than ``dt`` [s] (at most T / 20)."""
    owner = "circle"
    radius, period, cycles, dt, angle = _check(owner, radius, "radius", period, cycles, dt,
                                               angle)
    n = _per_period(owner, period, cycles, dt, 4, max_steps, lead_in=0.25)
    quarter = n // 4
    k = np.arange(quarter + n * cycles + 1)
    time = period * k / n
    omega = 2.0 * np.pi / period
    u, v = np.zeros((k.size, 2)), np.zeros((k.size, 2))
    lead = k <= quarter
    u[lead, 0] = radius * np.sin(np.pi / 2 * k[lead] / quarter)
    v[lead, 0] = radius * omega * np.cos(np.pi / 2 * k[lead] / quarter)
    v[quarter, 0] = 0.0  # exactly at rest at the end of the lead-in
    turn = ~lead
    phase = 2.0 * np.pi * ((k[turn] - quarter) % n) / n  # exact fractions of a turn
    u[turn] = radius * np.column_stack([np.cos(phase), np.sin(phase)])
    v[turn] = radius * omega * np.column_stack([-np.sin(phase), np.cos(phase)])
    segments = (("lead-in", 0, quarter + 1),
                *(("circle", quarter + j * n, quarter + (j + 1) * n + 1) for j in range(cycles)))
    return _finish(owner, time, u, v, angle, segments)


def figure_eight(amplitude: float, period: float, cycles: int, dt: float, *,
                 ratio: float = 0.5, angle: float = 0.0,
                 max_steps: int = DEFAULT_MAX_STEPS) -> Orbit:
    """A figure-eight (lemniscate of Gerono), x = A sin(w t), y = ratio A sin(2 w t), of
    ``amplitude`` A [m], ``ratio`` [-] and w = 2 pi / ``period`` [s], each cycle from and to the
    centre, in steps no longer than ``dt`` [s]."""
    owner = "figure_eight"
    amplitude, period, cycles, dt, angle = _check(owner, amplitude, "amplitude", period,
                                                  cycles, dt, angle)
    ratio = check_real(ratio, "ratio", owner, low=0.0, low_open=True, high=10.0)
    n = _per_period(owner, period, cycles, dt, 4, max_steps)
    k = np.arange(n * cycles + 1)
    time = period * k / n
    omega = 2.0 * np.pi / period
    phase = 2.0 * np.pi * (k % n) / n
    double = 2.0 * np.pi * ((2 * k) % n) / n
    u = amplitude * np.column_stack([np.sin(phase), ratio * np.sin(double)])
    v = amplitude * omega * np.column_stack([np.cos(phase), 2.0 * ratio * np.cos(double)])
    segments = tuple(("figure8", j * n, (j + 1) * n + 1) for j in range(cycles))
    return _finish(owner, time, u, v, angle, segments)


_SQUARE_LEGS = ((0.0, 1.0), (-1.0, 0.0), (0.0, -1.0), (1.0, 0.0), (0.0, 1.0))
_SQUARE_STEPS = (1, 2, 2, 2, 1)  # eighths of a turn per leg, from (a, 0) back to (a, 0)


def square(half_side: float, period: float, cycles: int, dt: float, *, angle: float = 0.0,
           max_steps: int = DEFAULT_MAX_STEPS) -> Orbit:
    """A square of half side ``half_side`` a [m] about the centre at constant speed 8 a / T: a
    lead-in along x to (a, 0) (T / 8), then ``cycles`` counter-clockwise turns through the
    corners (a, a), (-a, a), (-a, -a), (a, -a)."""
    owner = "square"
    a, period, cycles, dt, angle = _check(owner, half_side, "half_side", period, cycles, dt,
                                          angle)
    n = _per_period(owner, period, cycles, dt, 8, max_steps, lead_in=0.125)
    eighth = n // 8
    speed = 8.0 * a / period
    u, v = [np.zeros((1, 2))], [np.zeros((1, 2))]
    legs = [((1.0, 0.0), 1)] + [leg for _ in range(cycles)
                                for leg in zip(_SQUARE_LEGS, _SQUARE_STEPS, strict=True)]
    start = np.zeros(2)
    for direction, eighths in legs:
        steps = eighths * eighth
        fraction = np.arange(1, steps + 1) / steps
        along = np.asarray(direction)
        u.append(start + np.outer(fraction * eighths * a, along))
        v.append(np.tile(speed * along, (steps, 1)))
        start = start + eighths * a * along
    u, v = np.vstack(u), np.vstack(v)
    u[np.abs(u) < 1e-15 * a] = 0.0  # exact centre lines
    time = period * np.arange(u.shape[0]) / n
    segments = (("lead-in", 0, eighth + 1),
                *(("square", eighth + j * n, eighth + (j + 1) * n + 1) for j in range(cycles)))
    return _finish(owner, time, u, v, angle, segments)


def line(amplitude: float, period: float, cycles: int, dt: float, *, angle: float = 0.0,
         max_steps: int = DEFAULT_MAX_STEPS) -> Orbit:
    """The sine of :func:`isolator.protocols.sine` along the direction ``angle`` [deg], on the
    same samples; each cycle is a block ``"line"`` when the cycles end on samples, else the whole
    history is one block."""
    owner = "line"
    _check(owner, amplitude, "amplitude", period, cycles, dt, angle)
    history = sine(amplitude, period, cycles, dt, max_steps=max_steps)
    direction = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    steps = len(history) - 1
    if steps % cycles == 0:
        each = steps // cycles
        segments = tuple((owner, j * each, (j + 1) * each + 1) for j in range(cycles))
    else:
        segments = ((owner, 0, steps + 1),)
    return Orbit(history.time, np.outer(history.displacement, direction),
                 np.outer(history.velocity, direction), owner, segments)


def orbit(kind: str, amplitude: float, period: float, cycles: int, dt: float, *,
          angle: float = 0.0, max_steps: int = DEFAULT_MAX_STEPS) -> Orbit:
    """The orbit called ``kind`` (one of :data:`ORBITS`) of size ``amplitude`` [m]: the
    circle's radius, the figure-eight's and the line's amplitude, the square's half side."""
    kind = check_choice(kind, "kind", "orbit", ORBITS)
    check_real(amplitude, "amplitude", "orbit", low=0.0, low_open=True)
    make = {"circle": circle, "figure8": figure_eight, "square": square, "line": line}[kind]
    return make(amplitude, period, cycles, dt, angle=angle, max_steps=max_steps)
