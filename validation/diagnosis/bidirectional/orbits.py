"""The orbits of two-direction prototype tests: circular, figure-eight, square and earthquake.

Part of the bidirectional truth (:mod:`validation.diagnosis.bidirectional`); numpy and the
standard library only. An orbit is the actuators' commanded relative displacement (x, y) [m]
as a function of time, with its velocity, for t >= 0; it starts at rest at the origin.

- ``circular(A, T, cycles)``: u = A s(t) (sin wt, cos wt) with a one-period ramp of the
  radius at the start and the end, s(t) = (1 - cos(pi t / T)) / 2, so that the constant-speed
  circle A w lies between;
- ``figure_eight(A, B, T, cycles)``: the Lissajous orbit (A sin wt, B sin 2wt);
- ``square(A, speed, cycles)``: from the origin to (A, 0), round the square of corners
  (+-A, +-A) at a constant speed, and back to the origin;
- ``earthquake(pair, peak)``: the relative displacement of an isolation system (a linear
  oscillator of period 3 s and 15 % damping in each direction) under a horizontal pair of
  ground accelerations (a PEER AT2 pair from ``../shared/groundmotions/pairs/`` or, when
  that is absent, a synthetic pair of seeded filtered noise), scaled as a pair to the peak
  norm ``peak`` [m], cut to its strong part and tapered to start and end at rest.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

PAIRS = Path(__file__).resolve().parents[3].parent / "shared" / "groundmotions" / "pairs"
PAIR_FILES = {"CHY023": ("CHY023-N.AT2", "CHY023-W.AT2"),
              "ILA061": ("ILA061-N.AT2", "ILA061-W.AT2"),
              "TAP084": ("TAP084-N.AT2", "TAP084-W.AT2"),
              "TAP094": ("TAP094-E.AT2", "TAP094-N.AT2")}
G = 9.80665  # [m/s^2]


@dataclass(frozen=True)
class Orbit:
    """A commanded orbit: ``displacement(t)`` and ``velocity(t)`` give arrays (n, 2) [m],
    [m/s] for times t [s] in [0, duration]."""

    name: str
    duration: float
    displacement: Callable[[np.ndarray], np.ndarray]
    velocity: Callable[[np.ndarray], np.ndarray]


def _ramp(t: np.ndarray, period: float, duration: float) -> tuple[np.ndarray, np.ndarray]:
    """Envelope s(t) rising over the first period and falling over the last, and ds/dt."""
    t = np.asarray(t, dtype=float)
    s, ds = np.ones_like(t), np.zeros_like(t)
    up = t < period
    s[up] = 0.5 * (1.0 - np.cos(math.pi * t[up] / period))
    ds[up] = 0.5 * math.pi / period * np.sin(math.pi * t[up] / period)
    down = t > duration - period
    tau = duration - t[down]
    s[down] = 0.5 * (1.0 - np.cos(math.pi * tau / period))
    ds[down] = -0.5 * math.pi / period * np.sin(math.pi * tau / period)
    return s, ds


def circular(amplitude: float, period: float, cycles: float) -> Orbit:
    """A circle of radius ``amplitude`` [m] run at the period ``period`` [s] for ``cycles``
    turns at constant speed, with a one-period ramp of the radius before and after."""
    w = 2.0 * math.pi / period
    duration = (cycles + 2.0) * period

    def disp(t):
        s, _ = _ramp(t, period, duration)
        return amplitude * np.column_stack([s * np.sin(w * t), s * np.cos(w * t)])

    def vel(t):
        s, ds = _ramp(t, period, duration)
        return amplitude * np.column_stack([ds * np.sin(w * t) + s * w * np.cos(w * t),
                                            ds * np.cos(w * t) - s * w * np.sin(w * t)])

    return Orbit(f"circular A={amplitude:g} m T={period:g} s", duration, disp, vel)


def figure_eight(amplitude_x: float, amplitude_y: float, period: float, cycles: float) -> Orbit:
    """The figure-eight (A sin wt, B sin 2wt) [m] for ``cycles`` periods ``period`` [s]."""
    w = 2.0 * math.pi / period

    def disp(t):
        return np.column_stack([amplitude_x * np.sin(w * t), amplitude_y * np.sin(2 * w * t)])

    def vel(t):
        return np.column_stack([amplitude_x * w * np.cos(w * t),
                                2.0 * amplitude_y * w * np.cos(2 * w * t)])

    return Orbit(f"figure-eight {amplitude_x:g} x {amplitude_y:g} m T={period:g} s",
                 cycles * period, disp, vel)


def polyline(name: str, corners: np.ndarray, speed: float) -> Orbit:
    """An orbit through ``corners`` (m, 2) [m] at the constant ``speed`` [m/s]."""
    corners = np.asarray(corners, dtype=float)
    lengths = np.hypot(*np.diff(corners, axis=0).T)
    arrival = np.concatenate([[0.0], np.cumsum(lengths)]) / speed
    directions = np.diff(corners, axis=0) / lengths[:, None] * speed

    def disp(t):
        t = np.clip(np.asarray(t, dtype=float), 0.0, arrival[-1])
        return np.column_stack([np.interp(t, arrival, corners[:, 0]),
                                np.interp(t, arrival, corners[:, 1])])

    def vel(t):
        t = np.asarray(t, dtype=float)
        leg = np.clip(np.searchsorted(arrival, t, side="right") - 1, 0, len(lengths) - 1)
        out = directions[leg]
        out[(t < 0.0) | (t > arrival[-1])] = 0.0
        return out

    return Orbit(name, float(arrival[-1]), disp, vel)


def square(amplitude: float, speed: float, cycles: int) -> Orbit:
    """From the origin to (A, 0), ``cycles`` times round the square of corners (+-A, +-A)
    at ``speed`` [m/s], then back to the origin."""
    a = amplitude
    loop = [(a, a), (-a, a), (-a, -a), (a, -a), (a, 0.0)]
    corners = [(0.0, 0.0), (a, 0.0)] + loop * cycles + [(0.0, 0.0)]
    return polyline(f"square A={a:g} m v={speed:g} m/s", np.array(corners), speed)


# --- the earthquake orbit ------------------------------------------------------------------


def read_at2(path: str | Path) -> tuple[np.ndarray, float]:
    """A PEER AT2 record: (acceleration [g], dt [s]) (header of 4 lines, NPTS and DT on the
    fourth)."""
    lines = Path(path).read_text().splitlines()
    head = lines[3].upper().replace(",", " ").split()
    npts = int(head[head.index("NPTS=") + 1])
    dt = float(head[head.index("DT=") + 1])
    values = np.array(" ".join(lines[4:]).split(), dtype=float)[:npts]
    return values, dt


def synthetic_pair(seed: int, duration: float = 40.0, dt: float = 0.005) -> tuple[np.ndarray,
                                                                                   float]:
    """Two ground accelerations [g] of seeded white noise, band-limited to 0.2-8 Hz and
    shaped by a rise-plateau-decay envelope (when the shared pairs are absent)."""
    rng = np.random.default_rng(seed)
    n = round(duration / dt)
    t = np.arange(n) * dt
    env = np.minimum(t / 3.0, 1.0) ** 2 * np.exp(-np.maximum(t - 12.0, 0.0) / 6.0)
    freq = np.fft.rfftfreq(n, dt)
    out = []
    for _ in range(2):
        spec = np.fft.rfft(rng.standard_normal(n))
        spec[(freq < 0.2) | (freq > 8.0)] = 0.0
        out.append(np.fft.irfft(spec, n) * env)
    acc = np.column_stack(out)
    return 0.1 * acc / np.max(np.abs(acc)), dt


def ground_pair(name: str) -> tuple[np.ndarray, float, str]:
    """(acceleration (n, 2) [g], dt [s], source) of the pair ``name`` from the shared data,
    or a synthetic pair when the shared data is absent."""
    files = PAIR_FILES.get(name)
    if files and all((PAIRS / f).is_file() for f in files):
        (ax, dt), (ay, _) = (read_at2(PAIRS / f) for f in files)
        n = min(ax.size, ay.size)
        return np.column_stack([ax[:n], ay[:n]]), dt, f"PEER pair {name} ({PAIRS})"
    seed = sum(map(ord, name))
    warnings.warn(f"the shared pair {name} is absent at {PAIRS} (the shared data is looked "
                  "for beside the repository this code runs from): a synthetic stand-in pair "
                  "is written, so the panel is not the published one", stacklevel=2)
    acc, dt = synthetic_pair(seed)
    return acc, dt, f"synthetic pair (seed {seed}; shared pair {name} absent)"


def isolator_response(acc: np.ndarray, dt: float, period: float = 3.0,
                      damping: float = 0.15) -> tuple[np.ndarray, np.ndarray]:
    """Relative displacement and velocity [m, m/s] of a linear oscillator (``period``
    [s], ``damping``) in each direction under the ground accelerations ``acc`` [g]: the
    exact step of the 2x2 system (its matrix exponential, by eigen-decomposition) with the
    load held at the mean of the step's two samples."""
    w = 2.0 * math.pi / period
    a = np.array([[0.0, 1.0], [-w * w, -2.0 * damping * w]])
    vals, vecs = np.linalg.eig(a)
    expm = (vecs @ np.diag(np.exp(vals * dt)) @ np.linalg.inv(vecs)).real
    gamma = np.linalg.solve(a, expm - np.eye(2)) @ np.array([0.0, 1.0])
    p = -np.asarray(acc, dtype=float) * G
    state = np.zeros((2, 2))  # rows: x and y; columns: displacement, velocity
    disp, velo = np.zeros_like(p), np.zeros_like(p)
    for i in range(1, len(p)):
        state = state @ expm.T + np.outer(0.5 * (p[i - 1] + p[i]), gamma)
        disp[i], velo[i] = state[:, 0], state[:, 1]
    return disp, velo


def earthquake(pair: str, peak: float, window: float = 20.0, taper: float = 2.0) -> Orbit:
    """The bearing orbit of the pair ``pair`` scaled to the peak norm ``peak`` [m]: the
    ``window`` [s] around the largest response, tapered over ``taper`` [s] at each end (a
    cosine taper of the displacement, so the orbit starts and ends at rest)."""
    acc, dt, source = ground_pair(pair)
    disp, velo = isolator_response(acc, dt)
    norm = np.hypot(disp[:, 0], disp[:, 1])
    centre = int(np.argmax(norm))
    n = round(window / dt)
    start = int(np.clip(centre - n // 3, 0, max(len(norm) - n, 0)))
    disp, velo = disp[start:start + n + 1], velo[start:start + n + 1]
    t = np.arange(len(disp)) * dt
    s, ds = _ramp(t, taper, t[-1])
    disp0 = disp[0]
    disp = disp - disp0  # from the origin: the window starts where the bearing is
    u = disp * s[:, None]
    v = velo * s[:, None] + disp * ds[:, None]
    scale = peak / np.max(np.hypot(u[:, 0], u[:, 1]))
    u, v = u * scale, v * scale

    def disp_f(tt):
        tt = np.clip(np.asarray(tt, dtype=float), 0.0, t[-1])
        return np.column_stack([np.interp(tt, t, u[:, 0]), np.interp(tt, t, u[:, 1])])

    def vel_f(tt):
        tt = np.clip(np.asarray(tt, dtype=float), 0.0, t[-1])
        return np.column_stack([np.interp(tt, t, v[:, 0]), np.interp(tt, t, v[:, 1])])

    return Orbit(f"earthquake {pair} peak {peak:g} m ({source})", float(t[-1]), disp_f, vel_f)
