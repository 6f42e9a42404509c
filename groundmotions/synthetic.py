"""Synthetic ground motions: filtered white noise (Kanai-Tajimi, Clough-Penzien) with an envelope.

A record is a stationary Gaussian process of the Kanai-Tajimi (or Clough-Penzien) power spectral
density times a deterministic time envelope, its white noise from
``numpy.random.Generator(PCG64(seed))``: reproducible bit for bit from its seed (same numpy and
platform), with every parameter and the seed in its ``metadata``.

Power spectral densities are two-sided and per rad/s. With the white-noise intensity S0
[m^2/s^3 = (m/s^2)^2 / (rad/s)]

    S_KT(omega) = S0 (w_g^4 + 4 z_g^2 w_g^2 omega^2) / ((w_g^2 - omega^2)^2 + 4 z_g^2 w_g^2 omega^2)

and Clough-Penzien multiplies it by ``omega^4 / ((w_f^2 - omega^2)^2 + 4 z_f^2 w_f^2 omega^2)``.

References
----------
H. Tajimi (1960), "A statistical method of determining the maximum response of a building
structure during an earthquake", Proc. 2nd WCEE, Tokyo, 781-797.
R. W. Clough and J. Penzien, "Dynamics of Structures" (1975), Sec. 25 (the filtered spectrum).
M. Amin and A. H.-S. Ang (1968), "Nonstationary stochastic model of earthquake motions",
J. Eng. Mech. Div. ASCE 94(EM2), 559-583; P. C. Jennings, G. W. Housner and N. C. Tsai
(1968), "Simulated earthquake motions", EERL Caltech (the piecewise envelope).
G. R. Saragoni and G. C. Hart (1974), "Simulation of artificial earthquakes", Earthq. Eng.
Struct. Dyn. 2, 249-267; D. M. Boore (2003), "Simulation of ground motion using the
stochastic method", Pure Appl. Geophys. 160, 635-676 (the (epsilon, eta) parameters).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_choice, check_int, check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion

__all__ = [
    "GENERATORS",
    "PiecewiseEnvelope",
    "SaragoniHartEnvelope",
    "clough_penzien",
    "clough_penzien_psd",
    "kanai_tajimi",
    "kanai_tajimi_psd",
    "synthetic_pair",
]


@dataclass(frozen=True)
class PiecewiseEnvelope:
    """Amin-Ang / Jennings envelope: ``e(t) = (t / t1)^2`` for t < t1, ``1`` for t1 <= t <= t2,
    ``exp(-c (t - t2))`` after.

    Parameters
    ----------
    rise_time : float
        t1, end of the quadratic rise, > 0 [s].
    plateau_end : float
        t2, end of the strong phase, >= t1 [s].
    decay : float
        c, decay rate of the tail, > 0 [1/s].
    """

    rise_time: float
    plateau_end: float
    decay: float

    def __post_init__(self) -> None:
        owner = "PiecewiseEnvelope"
        t1 = check_real(self.rise_time, "rise_time", owner, low=0.0, low_open=True)
        object.__setattr__(self, "rise_time", t1)
        object.__setattr__(self, "plateau_end",
                           check_real(self.plateau_end, "plateau_end", owner, low=t1))
        object.__setattr__(self, "decay",
                           check_real(self.decay, "decay", owner, low=0.0, low_open=True))

    @classmethod
    def for_duration(cls, duration: float, rise: float = 0.1, plateau: float = 0.5,
                     end_value: float = 0.05) -> PiecewiseEnvelope:
        """The envelope used by ``envelope="jennings"``: t1 = 0.1 D, t2 = 0.5 D and a decay
        that brings e to ``end_value`` at t = D (fractions of the duration D [s])."""
        d = check_real(duration, "duration", "PiecewiseEnvelope.for_duration", low=0.0,
                       low_open=True)
        return cls(rise * d, plateau * d, math.log(1.0 / end_value) / ((1.0 - plateau) * d))

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """Envelope values [-] at times ``t`` >= 0 [s]."""
        t = np.asarray(t, dtype=float)
        rise = (t / self.rise_time) ** 2
        tail = np.exp(-self.decay * np.maximum(t - self.plateau_end, 0.0))
        return np.where(t < self.rise_time, rise, tail)


@dataclass(frozen=True)
class SaragoniHartEnvelope:
    """Saragoni-Hart envelope ``e(t) = a t^b exp(-c t)`` in Boore's (2003) parameters.

    Parameters
    ----------
    duration : float
        T_w, the window length, > 0 [s].
    peak_fraction : float
        epsilon: the envelope peaks, at 1, at ``epsilon T_w``; in (0, 1) [-].
    end_value : float
        eta: the envelope's value at T_w, in (0, 1) [-].

    Notes
    -----
    ``b = -epsilon ln(eta) / (1 + epsilon (ln(epsilon) - 1))``, ``c = b / (epsilon T_w)``,
    ``a = (e / (epsilon T_w))^b`` (Boore 2003, Eq. 9-10 with the peak normalised to 1).
    """

    duration: float
    peak_fraction: float = 0.2
    end_value: float = 0.05

    def __post_init__(self) -> None:
        owner = "SaragoniHartEnvelope"
        object.__setattr__(self, "duration", check_real(self.duration, "duration", owner,
                                                        low=0.0, low_open=True))
        for name in ("peak_fraction", "end_value"):
            value = check_real(getattr(self, name), name, owner, low=0.0, high=1.0,
                               low_open=True, high_open=True)
            object.__setattr__(self, name, value)

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """Envelope values [-] at times ``t`` >= 0 [s]."""
        eps, eta, t_peak = self.peak_fraction, self.end_value, self.peak_fraction * self.duration
        b = -eps * math.log(eta) / (1.0 + eps * (math.log(eps) - 1.0))
        x = np.maximum(np.asarray(t, dtype=float), 0.0) / t_peak  # e = (x exp(1 - x))^b
        return np.exp(b * (np.log(np.maximum(x, 1e-300)) + 1.0 - x)) * (x > 0.0)


def kanai_tajimi_psd(
    omega: Any, ground_frequency: float, ground_damping: float, intensity: float = 1.0
) -> np.ndarray:
    """Two-sided Kanai-Tajimi PSD of ground acceleration [m^2/s^3] at ``omega`` [rad/s]: soil
    filter of circular frequency ``ground_frequency`` w_g [rad/s] and damping ratio
    ``ground_damping`` z_g [-], white-noise intensity ``intensity`` S0 [m^2/s^3]."""
    return intensity * np.abs(_kanai_tajimi_filter(np.asarray(omega, dtype=float),
                                                   ground_frequency, ground_damping)) ** 2


def clough_penzien_psd(
    omega: Any, ground_frequency: float, ground_damping: float, filter_frequency: float,
    filter_damping: float, intensity: float = 1.0,
) -> np.ndarray:
    """Two-sided Clough-Penzien PSD [m^2/s^3] at ``omega`` [rad/s]: Kanai-Tajimi times the
    high-pass term with circular frequency w_f [rad/s] and damping ratio z_f [-]."""
    w = np.asarray(omega, dtype=float)
    h = _kanai_tajimi_filter(w, ground_frequency, ground_damping)
    h = h * _high_pass_filter(w, filter_frequency, filter_damping)
    return intensity * np.abs(h) ** 2


def _kanai_tajimi_filter(w: np.ndarray, wg: float, zg: float) -> np.ndarray:
    """Absolute acceleration of a ground oscillator per unit base acceleration (complex)."""
    return (wg**2 + 2j * zg * wg * w) / (wg**2 - w**2 + 2j * zg * wg * w)


def _high_pass_filter(w: np.ndarray, wf: float, zf: float) -> np.ndarray:
    """Relative acceleration of a second oscillator per unit base acceleration (complex)."""
    return -(w**2) / (wf**2 - w**2 + 2j * zf * wf * w)


def _envelope(envelope: Any, duration: float, owner: str) -> Any:
    if isinstance(envelope, PiecewiseEnvelope | SaragoniHartEnvelope):
        return envelope
    if envelope is None:
        envelope = "none"
    kind = check_choice(envelope, "envelope", owner, ("jennings", "saragoni-hart", "none"))
    if kind == "jennings":
        return PiecewiseEnvelope.for_duration(duration)
    return SaragoniHartEnvelope(duration) if kind == "saragoni-hart" else None


def _filtered_white_noise(
    model: str, duration: float, dt: float, filters: dict[str, float], intensity: float | None,
    target_pga: float | None, envelope: Any, seed: int, name: str | None,
) -> GroundMotion:
    owner = model.lower().replace("-", "_")
    d = check_real(duration, "duration", owner, low=0.0, low_open=True)
    step = check_real(dt, "dt", owner, low=0.0, high=d / 2.0, low_open=True)
    nyquist = np.pi / step  # [rad/s]
    params: dict[str, float] = {}
    for key, value in filters.items():
        if key.endswith("frequency"):
            params[key] = check_real(value, key, owner, low=0.0, high=nyquist, low_open=True,
                                     high_open=True)
        else:
            params[key] = check_real(value, key, owner, low=0.0, low_open=True)
    if (intensity is None) == (target_pga is None):
        raise InputError(f"Exactly one of the 'intensity' and 'target_pga' parameters of "
                         f"{owner} must be given. Got intensity={intensity!r}, "
                         f"target_pga={target_pga!r} instead.")
    s0 = 1.0 if intensity is None else check_real(intensity, "intensity", owner, low=0.0,
                                                  low_open=True)
    pga = None if target_pga is None else check_real(target_pga, "target_pga", owner,
                                                     low=0.0, low_open=True)
    n_seed = check_int(seed, "seed", owner, low=0)
    shape = _envelope(envelope, d, owner)

    npts = math.floor(d / step + 1e-9) + 1
    rng = np.random.Generator(np.random.PCG64(n_seed))
    noise = rng.standard_normal(npts) * math.sqrt(2.0 * np.pi * s0 / step)  # PSD S0 per rad/s
    w = 2.0 * np.pi * np.fft.rfftfreq(npts, step)
    transfer = _kanai_tajimi_filter(w, params["ground_frequency"], params["ground_damping"])
    if "filter_frequency" in params:
        transfer = transfer * _high_pass_filter(w, params["filter_frequency"],
                                                params["filter_damping"])
    acc = np.fft.irfft(np.fft.rfft(noise) * transfer, npts)
    time = np.arange(npts) * step
    if shape is not None:
        acc = acc * shape(time)
    if pga is not None:
        peak = float(np.max(np.abs(acc)))
        acc = acc * (pga / peak)
        s0 = s0 * (pga / peak) ** 2
    metadata: dict[str, Any] = {
        "generator": f"{model} filtered white noise",
        **params,
        "intensity": s0,
        "target_pga": pga,
        "envelope": {"kind": type(shape).__name__, **asdict(shape)} if shape else None,
        "seed": n_seed,
        "bit_generator": "PCG64",
        "numpy_version": np.__version__,
        "duration": d,
        "dt": step,
    }
    step_text = f"generated: {model} filtered white noise, seed {n_seed}"
    return GroundMotion(acc, step, name or f"{model} (seed {n_seed})", metadata, (step_text,))


def kanai_tajimi(
    duration: float, dt: float, *, ground_frequency: float, ground_damping: float,
    intensity: float | None = None, target_pga: float | None = None,
    envelope: Any = "jennings", seed: int, name: str | None = None,
) -> GroundMotion:
    """A Kanai-Tajimi filtered white-noise record with a time envelope.

    Parameters
    ----------
    duration, dt : float
        Record length, > 0 [s] (samples at ``k dt <= duration``), and time step, in
        (0, duration / 2] [s].
    ground_frequency, ground_damping : float
        w_g, circular frequency of the soil filter, in (0, pi / dt) [rad/s], and z_g, its damping
        ratio, > 0 [-] (e.g. 15.6 rad/s and 0.6 for firm ground).
    intensity, target_pga : float, optional
        Exactly one of: S0, the two-sided white-noise intensity [m^2/s^3]; the peak acceleration
        of the final record [m/s^2] (the equivalent S0 goes to ``metadata["intensity"]``).
    envelope : {"jennings", "saragoni-hart", "none"} or PiecewiseEnvelope or SaragoniHartEnvelope
        ``"jennings"`` is ``PiecewiseEnvelope.for_duration(duration)``, ``"saragoni-hart"``
        ``SaragoniHartEnvelope(duration)``; ``"none"`` (or None) keeps the process stationary.
    seed : int
        Seed of the PCG64 generator, >= 0.
    name : str, optional
        Record name; ``"Kanai-Tajimi (seed <seed>)"`` by default.

    Returns
    -------
    GroundMotion
        Acceleration [m/s^2]; ``metadata`` holds every parameter, the envelope and the seed.

    Notes
    -----
    The white noise is filtered in the frequency domain (a circular convolution), so the process
    is stationary from the first sample and its expected PSD is S_KT at the FFT frequencies.
    """
    return _filtered_white_noise(
        "Kanai-Tajimi", duration, dt,
        {"ground_frequency": ground_frequency, "ground_damping": ground_damping},
        intensity, target_pga, envelope, seed, name)


def clough_penzien(
    duration: float, dt: float, *, ground_frequency: float, ground_damping: float,
    filter_frequency: float, filter_damping: float, intensity: float | None = None,
    target_pga: float | None = None, envelope: Any = "jennings", seed: int,
    name: str | None = None,
) -> GroundMotion:
    """A Clough-Penzien filtered white-noise record with a time envelope.

    As `kanai_tajimi`, with the output passed through a second-order high-pass filter of circular
    frequency ``filter_frequency`` (w_f, in (0, pi / dt) [rad/s], typically about w_g / 10) and
    damping ratio ``filter_damping`` (z_f > 0 [-]).
    """
    return _filtered_white_noise(
        "Clough-Penzien", duration, dt,
        {"ground_frequency": ground_frequency, "ground_damping": ground_damping,
         "filter_frequency": filter_frequency, "filter_damping": filter_damping},
        intensity, target_pga, envelope, seed, name)


GENERATORS: dict[str, Callable[..., GroundMotion]] = {
    "kanai-tajimi": kanai_tajimi,
    "clough-penzien": clough_penzien,
}
"""The generators a pair can be drawn from, by name."""


def synthetic_pair(
    generator: str | Callable[..., GroundMotion],
    seed: int,
    *,
    duration: float,
    dt: float,
    vertical_ratio: float | None = None,
    name: str | None = None,
    **parameters: Any,
) -> GroundMotionPair:
    """A pair of independent synthetic horizontals (and optionally a vertical).

    Parameters
    ----------
    generator : {"kanai-tajimi", "clough-penzien"} or callable
        The generator, by name or as a function with the signature of `kanai_tajimi`:
        ``(duration, dt, *, seed, name, **parameters) -> GroundMotion``.
    seed : int
        Seed of the pair, >= 0: x uses ``seed``, y ``seed + 1``, z ``seed + 2`` (independent
        realisations of one process).
    duration, dt : float
        Record length, > 0 [s], and time step [s] (see the generator).
    vertical_ratio : float, optional
        Adds a vertical component: a third realisation of the same process times this ratio,
        > 0 [-] (e.g. 2/3, the classical vertical-to-horizontal ratio; with ``target_pga`` the
        vertical's PGA is ``vertical_ratio * target_pga``).
    name : str, optional
        The pair's name; ``"<generator> pair (seed <seed>)"`` by default.
    **parameters
        Keyword parameters of the generator, the same for every component (``ground_frequency``
        [rad/s], ``ground_damping`` [-], ``intensity`` [m^2/s^3] or ``target_pga`` [m/s^2],
        ``envelope`` ...).

    Returns
    -------
    GroundMotionPair
        Components named ``<name> x``, ``<name> y`` (and ``<name> z``) [m/s^2].
    """
    owner = "synthetic_pair"
    if isinstance(generator, str):
        make = GENERATORS[check_choice(generator, "generator", owner, tuple(GENERATORS))]
        label = generator
    elif callable(generator):
        make, label = generator, getattr(generator, "__name__", "synthetic")
    else:
        raise InputTypeError(f"The 'generator' parameter of {owner} must be one of "
                             f"{tuple(GENERATORS)} or a generator function. "
                             f"Got {generator!r} instead.")
    first = check_int(seed, "seed", owner, low=0)
    ratio = None if vertical_ratio is None else check_real(
        vertical_ratio, "vertical_ratio", owner, low=0.0, low_open=True)
    pair_name = name if name is not None else f"{label} pair (seed {first})"
    roles = ("x", "y") if ratio is None else ("x", "y", "z")
    motions = {role: make(duration, dt, seed=first + k, name=f"{pair_name} {role}",
                          **parameters) for k, role in enumerate(roles)}
    z = None if ratio is None else motions["z"].scaled(ratio)
    return GroundMotionPair(motions["x"], motions["y"], z, pair_name)
