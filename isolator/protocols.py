"""Imposed displacement histories for a virtual bearing test machine (:class:`ImposedHistory`),
up to the ASCE/SEI 7-16 Section 17.8.2.2 prototype sequence.

``dt`` is the largest time step allowed: a block of duration D is cut into ``ceil(D / dt)``
equal steps so that its last sample falls on its end. Blocks are joined at a shared sample
(:func:`concatenate`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_array, check_choice, check_instance, check_int, check_real
from isolator.limits import DEFAULT_MAX_STEPS, history_steps

WIND_PEAK_VELOCITY = 0.015
"""Peak velocity of the paper's wind-load test T02 [m/s] (about 15 mm/s)."""

STEPS_PER_PERIOD_MIN = 20
"""Fewest time steps a period of a sine or an orbit: ``dt`` at most period / 20."""

_ROUNDING = 1e-9  # relative slack when deciding how many steps of dt fill a duration


@dataclass(frozen=True, eq=False)
class LabelledBlocks:
    """What an imposed history in one direction (:class:`ImposedHistory`) and an orbit in two
    (:class:`isolator.orbits.Orbit`) share: the strictly increasing sample ``time`` (n,) [s],
    the imposed ``displacement`` [m] and its analytic ``velocity`` [m/s], (n,) in one direction
    and (n, 2) in two (``_DIMENSION``; read-only copies), a ``name`` and the labelled blocks
    ``segments`` ``(label, start, stop)``, both end samples included."""

    time: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    name: str
    segments: tuple[tuple[str, int, int], ...] = ()
    _DIMENSION: ClassVar[int] = 1

    def __post_init__(self) -> None:
        owner = type(self).__name__
        n = check_array(self.time, "time", owner, min_length=2, increasing=True).size
        for name in ("time", "displacement", "velocity"):
            if name == "time" or self._DIMENSION == 1:
                arr = check_array(getattr(self, name), name, owner, min_length=2,
                                  length_of=("time", n))
            else:
                arr = check_array(getattr(self, name), name, owner, ndim=2, min_length=2)
                if arr.shape != (n, 2):
                    raise InputError(f"The {name!r} parameter of {owner} must have the shape "
                                     f"({n}, 2). Got {arr.shape} instead.")
            arr = arr.copy()
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        check_instance(self.name, "name", owner, str, "a str")
        self._set_segments(owner)

    def _set_segments(self, owner: str) -> None:
        """Check ``segments`` against the samples and store them as (str, int, int)."""
        segments = tuple(tuple(s) for s in self.segments)
        for seg in segments:
            label, *bounds = seg if len(seg) == 3 else (None, 0, 0)
            if not (
                isinstance(label, str)
                and all(isinstance(i, int | np.integer) for i in bounds)
                and 0 <= bounds[0] < bounds[1] <= self.time.size
            ):
                raise InputError(
                    f"The 'segments' parameter of {owner} must hold (label, start, stop) with "
                    f"0 <= start < stop <= {self.time.size}. Got {seg!r} instead."
                )
        object.__setattr__(
            self, "segments", tuple((str(s[0]), int(s[1]), int(s[2])) for s in segments)
        )

    def __len__(self) -> int:
        return int(self.time.size)

    def segment_slices(self, label: str) -> list[slice]:
        """Slices of every block labelled ``label`` (both end samples included)."""
        return [slice(start, stop) for lab, start, stop in self.segments if lab == label]


@dataclass(frozen=True, eq=False)
class ImposedHistory(LabelledBlocks):
    """A displacement history imposed on a bearing, with its exact velocity (read-only arrays).

    Parameters
    ----------
    time, displacement, velocity : array_like
        Strictly increasing sample times [s], and the imposed displacement [m] and analytic
        velocity [m/s] at each.
    name : str
        What the history is, e.g. ``"sine"`` or ``"ASCE 7-16 prototype sequence"``.
    segments : tuple of (str, int, int)
        Labelled blocks ``(label, start, stop)``: ``displacement[start:stop]`` is the whole
        block, both end samples included; consecutive blocks share their joining sample.
    """

    @property
    def duration(self) -> float:
        """Time from the first to the last sample [s]."""
        return float(self.time[-1] - self.time[0])


def _labelled(history: ImposedHistory, label: str) -> ImposedHistory:
    return ImposedHistory(
        history.time, history.displacement, history.velocity, label, ((label, 0, len(history)),)
    )


def sine(
    amplitude: float, period: float, cycles: int, dt: float, *, start_time: float = 0.0,
    max_steps: int = DEFAULT_MAX_STEPS,
) -> ImposedHistory:
    """Fully reversed sine cycles ``u = A sin(2 pi (t - t0) / T)``, one segment ``"sine"``,
    starting and ending at exactly 0 m: ``amplitude`` A > 0 [m], ``period`` T > 0 [s],
    ``cycles`` >= 1, ``dt`` the largest time step in (0, T/20] [s], ``start_time`` t0 [s] and
    ``max_steps`` checked before any array is made (:mod:`isolator.limits`).
    """
    owner = "sine"
    amplitude = check_real(amplitude, "amplitude", owner, low=0.0, low_open=True)
    period = check_real(period, "period", owner, low=0.0, low_open=True)
    cycles = check_int(cycles, "cycles", owner, low=1)
    dt = check_real(dt, "dt", owner, low=0.0, low_open=True, high=period / STEPS_PER_PERIOD_MIN)
    start_time = check_real(start_time, "start_time", owner)
    n = history_steps(cycles * period, dt, max_steps=max_steps)
    k = np.arange(n + 1)
    # Phase as an exact fraction of a cycle (integer arithmetic), so that whole cycles end on 0.
    phase = 2.0 * np.pi * ((k * cycles) % n) / n
    time = start_time + cycles * period * k / n
    displacement = amplitude * np.sin(phase)
    displacement[0] = displacement[-1] = 0.0
    velocity = amplitude * (2.0 * np.pi / period) * np.cos(phase)
    return ImposedHistory(time, displacement, velocity, "sine", (("sine", 0, n + 1),))


def wind_cycles(
    amplitude: float,
    peak_velocity: float = WIND_PEAK_VELOCITY,
    cycles: int = 20,
    dt: float | None = None,
) -> ImposedHistory:
    """Slow sine cycles standing for a wind load (the paper's test T02), labelled ``"wind"``.

    ``amplitude`` A > 0 [m] and ``peak_velocity`` v_peak > 0 [m/s] give the period
    T = 2 pi A / v_peak; ``cycles`` >= 1; ``dt`` the largest time step in (0, T/20] [s]
    (None: T/100).
    """
    owner = "wind_cycles"
    amplitude = check_real(amplitude, "amplitude", owner, low=0.0, low_open=True)
    peak_velocity = check_real(peak_velocity, "peak_velocity", owner, low=0.0, low_open=True)
    period = 2.0 * np.pi * amplitude / peak_velocity
    if dt is None:
        dt = period / 100.0
    dt = check_real(dt, "dt", owner, low=0.0, low_open=True, high=period / STEPS_PER_PERIOD_MIN)
    return _labelled(sine(amplitude, period, cycles, dt), "wind")


def wind_displacement_from_force(
    wind_force: float, axial_load: float, effective_radius: float, friction_coefficient: float
) -> float:
    """Displacement [m] at which a pendulum bearing resists the wind design force: u solving
    ``N u / R + mu N = F_w`` (the sliding branch of the bilinear loop, Fig. 7), or 0 when
    ``F_w <= mu N`` (no sliding), for a ``wind_force`` F_w >= 0 [N], an ``axial_load`` N > 0 [N],
    a finite ``effective_radius`` R > 0 [m] and a ``friction_coefficient`` mu in [0, 1] [-]."""
    owner = "wind_displacement_from_force"
    wind_force = check_real(wind_force, "wind_force", owner, low=0.0)
    axial_load = check_real(axial_load, "axial_load", owner, low=0.0, low_open=True)
    radius = check_real(effective_radius, "effective_radius", owner, low=0.0, low_open=True)
    mu = check_real(friction_coefficient, "friction_coefficient", owner, low=0.0, high=1.0)
    return max(0.0, radius * (wind_force - mu * axial_load) / axial_load)


def hold(duration: float, dt: float) -> ImposedHistory:
    """The bearing held at zero displacement for ``duration`` [s], labelled ``"rest"``."""
    owner = "hold"
    duration = check_real(duration, "duration", owner, low=0.0, low_open=True)
    dt = check_real(dt, "dt", owner, low=0.0, low_open=True)
    n = history_steps(duration, dt)
    time = duration * np.arange(n + 1) / n
    zeros = np.zeros(n + 1)
    return ImposedHistory(time, zeros, zeros, "rest", (("rest", 0, n + 1),))


def concatenate(*histories: ImposedHistory, name: str | None = None) -> ImposedHistory:
    """Join histories end to start into one, named ``name`` (None: their names joined by
    ``" + "``); segments keep their labels. Each history is shifted in time so that its first
    sample is the previous one's last, the two becoming one sample; the displacement must be
    continuous there (to 1e-9 of the largest), the velocity takes the mean of the two sides.
    """
    owner = "concatenate"
    if not histories or not all(isinstance(h, ImposedHistory) for h in histories):
        kinds = [type(h).__name__ for h in histories]
        raise InputTypeError(
            f"The 'histories' parameter of {owner} must be one or more ImposedHistory objects. "
            f"Got {kinds} instead."
        )
    scale = max(float(np.max(np.abs(h.displacement))) for h in histories)
    first = histories[0]
    time, disp, vel = [first.time], [first.displacement], [first.velocity.copy()]
    segments, offset = list(first.segments), len(first) - 1
    for i, h in enumerate(histories[1:], start=1):
        t_end, u_end = time[-1][-1], disp[-1][-1]
        if abs(h.displacement[0] - u_end) > 1e-9 * scale:
            raise InputError(
                f"The 'histories' parameter of {owner} must be continuous in displacement. "
                f"Got a jump from {u_end!r} to {h.displacement[0]!r} m at history {i} instead."
            )
        vel[-1][-1] = 0.5 * (vel[-1][-1] + h.velocity[0])  # midpoint of the jump
        time.append(h.time[1:] - h.time[0] + t_end)
        disp.append(h.displacement[1:])
        vel.append(h.velocity[1:].copy())
        segments.extend((lab, start + offset, stop + offset) for lab, start, stop in h.segments)
        offset += len(h) - 1
    if name is None:
        name = " + ".join(h.name for h in histories)
    return ImposedHistory(
        np.concatenate(time), np.concatenate(disp), np.concatenate(vel), name, tuple(segments)
    )


def long_duration_cycles(
    S_M1: float | None, S_MS: float | None, B_M: float | None, owner: str = "long_duration_cycles"
) -> int:
    """Cycles of ASCE 7-16 17.8.2.2 item 4: ``30 S_M1 / (S_MS B_M)`` rounded up, but not less
    than 10 (10 when all three are None), for the MCE_R spectral response accelerations at 1 s
    and at short periods ``S_M1``, ``S_MS`` > 0 [g] and the damping coefficient at D_M ``B_M`` in
    [0.8, 2.0] [-] (Table 17.7-1)."""
    missing = [k for k, v in {"S_M1": S_M1, "S_MS": S_MS, "B_M": B_M}.items() if v is None]
    if len(missing) == 3:
        return 10
    if missing:
        raise InputError(
            f"The {missing[0]!r} parameter of {owner} must be a float when any of S_M1, S_MS, "
            f"B_M is given. Got None instead."
        )
    s1 = check_real(S_M1, "S_M1", owner, low=0.0, low_open=True)
    ss = check_real(S_MS, "S_MS", owner, low=0.0, low_open=True)
    bm = check_real(B_M, "B_M", owner, low=0.8, high=2.0)
    return max(10, math.ceil(30.0 * s1 / (ss * bm) - _ROUNDING))


def asce7_prototype_sequence(
    maximum_displacement: float,
    total_maximum_displacement: float,
    period: float,
    dt: float,
    *,
    wind_displacement: float,
    wind_peak_velocity: float = WIND_PEAK_VELOCITY,
    S_M1: float | None = None,
    S_MS: float | None = None,
    B_M: float | None = None,
    rest: float = 0.0,
    item2: str = "a",
) -> ImposedHistory:
    """The cyclic prototype-test sequence of ASCE 7-16 Section 17.8.2.2 as one history.

    The clauses (17.8.2.2, paraphrased; to be checked against the standard's text):

    1. Twenty fully reversed cycles at the wind design force, imposed as cycles of amplitude
       ``wind_displacement`` (:func:`wind_displacement_from_force`) at ``wind_peak_velocity``
       (the paper's T02: about 15 mm/s); omitted for a wind displacement of 0.
    2. (a) Three fully reversed cycles at each of 0.25, 0.5, 0.67 and 1.0 D_M; or (b) one
       continuous cycle at each of 1.0, 0.67, 0.5, 0.25 D_M, then at each of 0.25, 0.5, 0.67,
       1.0 D_M, a rest permitted between the two.
    3. Three fully reversed cycles at the total maximum displacement D_TM.
    4. ``30 S_M1 / (S_MS B_M)``, but not less than 10, cycles at 0.75 D_TM
       (:func:`long_duration_cycles`).

    All but the wind block run at the effective period T_M (17.8.2.3; the paper's 4.26 s). Not
    implemented: the extra vertical-load cases of item 2, splitting item 4 into segments.

    Parameters
    ----------
    maximum_displacement, total_maximum_displacement : float
        D_M > 0 and D_TM >= D_M [m].
    period : float
        Effective period T_M of every block but the wind block [s].
    dt : float
        Largest time step [s], at most 1/20 of the period and of the wind period.
    wind_displacement, wind_peak_velocity : float
        Amplitude >= 0 [m] and peak velocity > 0 [m/s] of the wind cycles.
    S_M1, S_MS, B_M : float or None
        Set the number of item-4 cycles; all None gives 10.
    rest : float
        Time held at zero displacement between blocks [s] (not inside the continuous sequences of
        item 2b).
    item2 : {"a", "b"}
        Which option of item 2.

    Returns
    -------
    ImposedHistory
        Blocks labelled ``"wind"``, ``"0.25 D_M"``, ``"0.5 D_M"``, ``"0.67 D_M"``, ``"1.0 D_M"``,
        ``"D_TM"``, ``"0.75 D_TM"`` and ``"rest"``, each starting and ending at zero
        displacement; the velocity jumps where the amplitude changes.
    """
    owner = "asce7_prototype_sequence"
    d_m = check_real(maximum_displacement, "maximum_displacement", owner, low=0.0, low_open=True)
    d_tm = check_real(total_maximum_displacement, "total_maximum_displacement", owner, low=d_m)
    period = check_real(period, "period", owner, low=0.0, low_open=True)
    d_w = check_real(wind_displacement, "wind_displacement", owner, low=0.0)
    v_w = check_real(wind_peak_velocity, "wind_peak_velocity", owner, low=0.0, low_open=True)
    n_long = long_duration_cycles(S_M1, S_MS, B_M, owner)
    rest_time = check_real(rest, "rest", owner, low=0.0)
    item2 = check_choice(item2, "item2", owner, ("a", "b"))
    shortest = period if d_w == 0.0 else min(period, 2.0 * np.pi * d_w / v_w)
    dt = check_real(dt, "dt", owner, low=0.0, low_open=True, high=shortest / STEPS_PER_PERIOD_MIN)

    def block(amplitude: float, label: str, cycles: int) -> ImposedHistory:
        return _labelled(sine(amplitude, period, cycles, dt), label)

    multiples = [(f * d_m, f"{f} D_M") for f in (0.25, 0.5, 0.67, 1.0)]  # item 2
    groups: list[list[ImposedHistory]] = []  # blocks inside a group are joined without rest
    if d_w > 0.0:
        groups.append([wind_cycles(d_w, v_w, 20, dt)])
    if item2 == "a":
        groups.extend([block(f, label, 3)] for f, label in multiples)
    else:
        groups.append([block(f, label, 1) for f, label in reversed(multiples)])
        groups.append([block(f, label, 1) for f, label in multiples])
    groups.append([block(d_tm, "D_TM", 3)])
    groups.append([block(0.75 * d_tm, "0.75 D_TM", n_long)])
    parts: list[ImposedHistory] = []
    for i, group in enumerate(groups):
        if i > 0 and rest_time > 0.0:
            parts.append(hold(rest_time, dt))
        parts.extend(group)
    return concatenate(*parts, name="ASCE 7-16 prototype sequence")
