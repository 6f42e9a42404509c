"""Target spectra and amplitude scaling of a ground-motion suite (ASCE 7-16 for isolation).

`scale_suite` scales each record, or each pair (every component alike), so that the suite's mean
spectrum (of pairs: RotD100 by default) is nowhere below the target over the period range:
ASCE 7-16 Section 17.3.3 over `isolated_period_range`; Section 16.2.3.1 (fixed-base structures)
is ``fraction=0.9`` over its own range.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError, InputWarning
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_array, check_choice, check_int, check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.pairs.rotd import rotd_spectra
from groundmotions.records import GroundMotion
from groundmotions.spectra import spectrum

__all__ = [
    "MAX_SCALE_FACTOR",
    "MAX_TARGET_SA",
    "MEASURES",
    "ScalingReport",
    "TargetSpectrum",
    "asce7_design_spectrum",
    "check_target_sa",
    "isolated_period_range",
    "scale_suite",
    "scaling_grid",
    "suite_factors",
    "suite_spectra",
]

Motion = GroundMotion | GroundMotionPair

MEASURES: dict[type, tuple[str, ...]] = {
    GroundMotion: ("sa",),
    GroundMotionPair: ("rotd100", "rotd50"),
}
"""The spectral measures of a record and of a pair (`suite_spectra`), the default first."""

_LABELS = {"sa": "spectrum", "rotd100": "RotD100 spectrum", "rotd50": "RotD50 spectrum"}

MCE_FACTOR = 1.5
"""MCE_R over design spectral ordinates, ASCE 7-16 Section 11.4.7 [-]."""

MAX_TARGET_SA = 10.0
"""Largest spectral acceleration a target may hold [g]: the strongest recorded spectra peak
near 5 g; a table above 10 g is almost surely in %g or cm/s^2."""
MAX_SPECTRAL_PARAMETER = 5.0
"""Largest S_DS or S_D1 of `asce7_design_spectrum` [g] (the MCE_R spectrum is 1.5 times it, so
it stays below :data:`MAX_TARGET_SA`); ASCE 7-16 maps reach about 3 g."""
MAX_SCALE_FACTOR = 100.0
"""Largest factor `scale_suite` gives a record or pair [-]: beyond it the target and the
records are in different units (a target in %g gives factors near 100 times the right ones)."""
WARN_SCALE_FACTOR = 10.0
"""A factor above this [-] is given with an :class:`InputWarning`: ASCE 7-16 17.3.3 suites are
usually scaled by 0.5 to 4, and a larger factor distorts the record's other intensities."""


def check_target_sa(sa: Any, where: str, unit: str = "m/s^2") -> None:
    """Refuse a target spectrum above :data:`MAX_TARGET_SA`.

    Parameters
    ----------
    sa : array_like
        Spectral accelerations of the target, in ``unit`` ("m/s^2" or "g").
    where : str
        The flag, file or parameter the values come from, for the message.
    unit : {"m/s^2", "g"}
        The unit of ``sa``.

    Raises
    ------
    InputError
        Naming ``where``, the first offending index and value, the limit and the likely unit.
    """
    to_g = 1.0 if unit == "g" else 1.0 / STANDARD_GRAVITY
    values = np.atleast_1d(np.asarray(sa, dtype=float))
    high = np.flatnonzero(values * to_g > MAX_TARGET_SA)
    if high.size:
        i = int(high[0])
        limit = MAX_TARGET_SA / to_g
        raise InputError(
            f"{where}: a target spectral acceleration must be at most {limit:g} {unit} "
            f"({MAX_TARGET_SA:g} g). Got {values[i]:g} {unit} ({values[i] * to_g:g} g) at index "
            f"{i} instead: the values look like %g or cm/s^2; give Sa in {unit}"
            + (" (1.5 for 1.5 g)." if unit == "g" else "."))


@dataclass(frozen=True, eq=False)
class TargetSpectrum:
    """A target pseudo-acceleration spectrum given as a table.

    Parameters
    ----------
    periods : array_like
        At least 2 periods, > 0 and strictly increasing [s].
    sa : array_like
        Pseudo-spectral acceleration at those periods, > 0 [m/s^2].
    name : str
        Label for reports and plots.
    damping : float
        Damping ratio of the spectrum, in [0, 1) [-].
    """

    periods: np.ndarray
    sa: np.ndarray
    name: str = "target"
    damping: float = 0.05

    def __post_init__(self) -> None:
        owner = "TargetSpectrum"
        periods = check_array(self.periods, "periods", owner, low=0.0, low_open=True,
                              min_length=2).copy()
        sa = check_array(self.sa, "sa", owner, low=0.0, low_open=True).copy()
        if sa.shape != periods.shape:
            raise InputError(f"The 'sa' parameter of {owner} must have one value per period "
                             f"({periods.size}). Got {sa.size} instead.")
        steps = np.diff(periods)
        if (steps <= 0.0).any():
            i = int(np.argmax(steps <= 0.0)) + 1
            here, before = float(periods[i]), float(periods[i - 1])
            raise InputError(f"The 'periods' parameter of {owner} must be strictly increasing. "
                             f"Got {here!r} after {before!r} at index {i} instead.")
        damping = check_real(self.damping, "damping", owner, low=0.0, high=1.0, high_open=True)
        check_target_sa(sa, f"The 'sa' parameter of {owner} ({self.name})")
        periods.flags.writeable = False
        sa.flags.writeable = False
        object.__setattr__(self, "periods", periods)
        object.__setattr__(self, "sa", sa)
        object.__setattr__(self, "damping", damping)

    def sa_at(self, periods: Any) -> np.ndarray:
        """Pseudo-spectral acceleration [m/s^2] at ``periods`` [s], interpolated in
        log(T)-log(Sa); ``ValueError`` for a period outside the table."""
        t = check_array(np.atleast_1d(np.asarray(periods, dtype=float)), "periods",
                        f"TargetSpectrum.sa_at ({self.name})", low=self.periods[0],
                        high=self.periods[-1])
        return np.exp(np.interp(np.log(t), np.log(self.periods), np.log(self.sa)))


def asce7_design_spectrum(
    S_DS: float,
    S_D1: float,
    T_L: float,
    periods: Any = None,
    *,
    level: str = "design",
) -> TargetSpectrum:
    """The ASCE 7-16 design (Section 11.4.6) or MCE_R (Section 11.4.7) response spectrum:
    a `TargetSpectrum` of ``sa`` [m/s^2] at 5 % damping.

    Parameters
    ----------
    S_DS, S_D1 : float
        Design spectral acceleration parameters at short periods and at 1 s, in (0, 5] [g]
        (:data:`MAX_SPECTRAL_PARAMETER`).
    T_L : float
        Long-period transition period, > T_S = S_D1 / S_DS [s].
    periods : array_like, optional
        Periods of the table, > 0 [s]; by default 300 log-spaced from 0.01 s to max(20 s, 2 T_L).
        The corner periods T_0, T_S and T_L within their range are added.
    level : {"design", "mce"}
        The design spectrum, or the MCE_R spectrum (1.5 times the design spectrum).

    Notes
    -----
    Eq. 11.4-5 to 11.4-8, with ``T_0 = 0.2 S_D1 / S_DS`` and ``T_S = S_D1 / S_DS``.
    """
    owner = "asce7_design_spectrum"
    s_ds = check_real(S_DS, "S_DS", owner, low=0.0, low_open=True, high=MAX_SPECTRAL_PARAMETER)
    s_d1 = check_real(S_D1, "S_D1", owner, low=0.0, low_open=True, high=MAX_SPECTRAL_PARAMETER)
    t_s = s_d1 / s_ds
    t_l = check_real(T_L, "T_L", owner, low=t_s, low_open=True)
    kind = check_choice(level, "level", owner, ("design", "mce"))
    t_0 = 0.2 * t_s
    if periods is None:
        periods = np.geomspace(0.01, max(20.0, 2.0 * t_l), 300)
    t = check_array(np.atleast_1d(np.asarray(periods, dtype=float)), "periods", owner,
                    low=0.0, low_open=True)
    corners = [c for c in (t_0, t_s, t_l) if t.min() < c < t.max()]
    t = np.unique(np.concatenate((t, corners)))
    sa = np.where(t < t_0, s_ds * (0.4 + 0.6 * t / t_0), s_ds)  # Eq. 11.4-5, 11.4-6
    sa = np.where(t > t_s, s_d1 / t, sa)  # Eq. 11.4-7
    sa = np.where(t > t_l, s_d1 * t_l / t**2, sa)  # Eq. 11.4-8
    factor = STANDARD_GRAVITY * (MCE_FACTOR if kind == "mce" else 1.0)
    label = "MCE_R" if kind == "mce" else "design"
    return TargetSpectrum(t, sa * factor, f"ASCE 7-16 {label} (S_DS={s_ds:g} g, "
                          f"S_D1={s_d1:g} g, T_L={t_l:g} s)", 0.05)


def isolated_period_range(
    lower_bound_period: float, upper_bound_period: float
) -> tuple[float, float]:
    """The ASCE 7-16 Section 17.3.3 scaling period range of an isolated structure,
    ``(0.75 lower_bound_period, 1.25 upper_bound_period)`` [s], from the effective period T_M
    [s] with the upper-bound isolator properties (> 0) and with the lower-bound ones (not
    shorter)."""
    owner = "isolated_period_range"
    lower = check_real(lower_bound_period, "lower_bound_period", owner, low=0.0, low_open=True)
    upper = check_real(upper_bound_period, "upper_bound_period", owner, low=lower)
    return 0.75 * lower, 1.25 * upper


@dataclass(frozen=True, eq=False)
class ScalingReport:
    """What `scale_suite` did.

    Attributes
    ----------
    names : tuple of str
        Names of the records or pairs, in the order given.
    individual_factors : numpy.ndarray
        Step 1: each one's factor matching its ``measure`` to the target on average over the range
        (geometric mean of target / measure) [-].
    common_factor : float
        Step 2: the one factor applied to all so that the mean touches the target [-].
    scale_factors : numpy.ndarray
        The factors applied, ``common_factor * individual_factors`` [-].
    periods, target_sa : numpy.ndarray
        The period grid [s] and ``fraction`` times the target on it [m/s^2].
    spectra : dict of str to numpy.ndarray
        The spectral measures of the scaled suite on the grid (`suite_spectra`), each of shape
        (len(names), len(periods)) [m/s^2].
    ratio : numpy.ndarray
        ``mean_sa / target_sa`` on the grid [-].
    min_ratio, tightest_period : float
        The minimum of ``ratio`` (1 to round-off with ``method="mean"``, >= 1 with
        ``"individual"``) [-] and the grid period where it occurs [s].
    motions : tuple of GroundMotion or of GroundMotionPair
        The scaled records or pairs.
    period_range, damping, fraction, method, measure, target_name
        As `scale_suite` took them (``period_range`` [s], ``damping`` and ``fraction`` [-]):
        ``measure`` is the key of ``spectra`` fitted, ``target_name`` the target's name.
    """

    names: tuple[str, ...]
    individual_factors: np.ndarray
    common_factor: float
    scale_factors: np.ndarray
    periods: np.ndarray
    target_sa: np.ndarray
    spectra: dict[str, np.ndarray]
    ratio: np.ndarray
    min_ratio: float
    tightest_period: float
    motions: tuple[Motion, ...] = field(repr=False)
    period_range: tuple[float, float] = (0.0, 0.0)
    damping: float = 0.05
    fraction: float = 1.0
    method: str = "mean"
    measure: str = "sa"
    target_name: str = ""

    @property
    def mean_spectra(self) -> dict[str, np.ndarray]:
        """The mean over the suite of each of ``spectra`` [m/s^2]."""
        return {name: sa.mean(axis=0) for name, sa in self.spectra.items()}

    @property
    def mean_sa(self) -> np.ndarray:
        """The mean over the suite of the scaled ``measure`` [m/s^2]."""
        return self.spectra[self.measure].mean(axis=0)

    def to_frame(self) -> Any:
        """One row per record (index ``record``) or pair (index ``pair``): the individual,
        common and final factors and the PGA [m/s^2] of the scaled record (``scaled_pga``) or of the
        pair's x and y (``scaled_pga_x``, ``scaled_pga_y``); the summary (min ratio, tightest period
        ...) in ``attrs``."""
        import pandas as pd

        pairs = isinstance(self.motions[0], GroundMotionPair)
        if pairs:
            pga = {f"scaled_pga_{c}": [getattr(p, c).pga for p in self.motions] for c in "xy"}
        else:
            pga = {"scaled_pga": [m.pga for m in self.motions]}
        frame = pd.DataFrame(
            {
                "individual_factor": self.individual_factors,
                "common_factor": self.common_factor,
                "scale_factor": self.scale_factors,
                **pga,
            },
            index=pd.Index(self.names, name="pair" if pairs else "record"),
        )
        frame.attrs.update(min_ratio=self.min_ratio, tightest_period=self.tightest_period,
                           period_range=self.period_range, damping=self.damping,
                           fraction=self.fraction, method=self.method, measure=self.measure,
                           target=self.target_name)
        return frame

    def spectrum_frame(self) -> Any:
        """One row per period [s]: ``target_sa``, the mean of each spectral measure (``mean_sa``;
        ``mean_rotd100``, ``mean_rotd50`` of pairs) [m/s^2] and ``ratio`` [-]."""
        import pandas as pd

        means = {f"mean_{name}": sa for name, sa in self.mean_spectra.items()}
        return pd.DataFrame({"target_sa": self.target_sa, **means, "ratio": self.ratio},
                            index=pd.Index(self.periods, name="period"))


def scaling_grid(target: object, period_range: object, n_periods: object, owner: str,
                 ) -> tuple[TargetSpectrum, np.ndarray, tuple[float, float]]:
    """The target, the period grid and the range a suite is scaled on, checked for ``owner``:
    ``target`` (or the one made of a (periods [s], sa [m/s^2]) pair), ``n_periods`` log-spaced
    periods from T_min to T_max (one when they are equal) [s], and (T_min, T_max) [s] within the
    target's periods."""
    if isinstance(target, tuple) and len(target) == 2:
        target = TargetSpectrum(*target)
    if not isinstance(target, TargetSpectrum):
        raise InputTypeError(f"The 'target' parameter of {owner} must be a TargetSpectrum or a "
                             f"(periods, sa) pair. Got {target!r} instead.")
    try:
        t_min, t_max = (float(t) for t in period_range)
    except (TypeError, ValueError):
        raise InputTypeError(f"The 'period_range' parameter of {owner} must be a pair of "
                             f"floats (T_min, T_max). Got {period_range!r} instead.") from None
    t_min = check_real(t_min, "period_range[0]", owner, low=target.periods[0],
                       high=target.periods[-1])
    t_max = check_real(t_max, "period_range[1]", owner, low=t_min, high=target.periods[-1])
    n = check_int(n_periods, "n_periods", owner, low=2, high=1000) if t_max > t_min else 1
    return target, np.geomspace(t_min, t_max, n), (t_min, t_max)


def suite_factors(spectra: np.ndarray, target_sa: np.ndarray, method: str,
                  ) -> tuple[np.ndarray, float, np.ndarray]:
    """The two steps of `scale_suite` on ``spectra`` of shape (records, periods): the step-1
    factors [-], the step-2 common factor [-] (1 for ``"individual"``) and each record's scale
    factor [-]."""
    individual = np.exp(np.mean(np.log(target_sa / spectra), axis=1))
    scaled = individual[:, None] * spectra
    if method == "mean":
        common = 1.0 / float(np.min(scaled.mean(axis=0) / target_sa))
        return individual, common, common * individual
    return individual, 1.0, individual / np.min(scaled / target_sa, axis=1)


def suite_spectra(motions: Sequence[Motion], periods: np.ndarray, damping: float = 0.05,
                  *, angle_step: float = 1.0) -> dict[str, np.ndarray]:
    """The spectral measures of a suite, each of shape (len(motions), len(periods)) [m/s^2].

    Records give ``{"sa": ...}``, each its own pseudo-acceleration spectrum
    (`groundmotions.spectrum`); pairs give ``{"rotd100": ..., "rotd50": ...}`` of their horizontals
    (`groundmotions.rotd_spectra`, directions ``angle_step`` [deg] apart). ``periods`` [s] and
    ``damping`` [-] as those take them; ``motions`` are all records or all pairs (:data:`MEASURES`).
    """
    motions, _ = _suite(motions, "suite_spectra")
    if isinstance(motions[0], GroundMotionPair):
        rotd = [rotd_spectra(p, periods, damping, (50, 100), angle_step=angle_step)
                for p in motions]
        return {"rotd100": np.array([s.rotd100 for s in rotd]),
                "rotd50": np.array([s.rotd50 for s in rotd])}
    return {"sa": np.array([spectrum(m, periods, damping).sa for m in motions])}


def _check_factors(suite: Sequence[Motion], factors: np.ndarray, target: TargetSpectrum,
                   owner: str, limit: float = MAX_SCALE_FACTOR) -> None:
    """Refuse a factor above ``limit``, warn of one above :data:`WARN_SCALE_FACTOR`, naming the
    record or pair and its factor."""
    order = np.argsort(factors)[::-1]
    worst = int(order[0])
    largest = float(factors[worst])
    hint = (f"the target {target.name!r} (peak Sa {target.sa.max() / STANDARD_GRAVITY:.3g} g) and "
            f"the records' spectra are likely in different units (a target in %g or cm/s^2, a "
            f"record in cm/s^2 read as m/s^2)")
    if largest > limit:
        raise InputError(f"{owner}: the scale factor of {suite[worst].name!r} would be "
                         f"{largest:.4g}, above the limit of {limit:g} ('max_factor'): {hint}.")
    if largest > WARN_SCALE_FACTOR:
        many = int((factors > WARN_SCALE_FACTOR).sum())
        warnings.warn(f"{owner}: {many} scale factor(s) above {WARN_SCALE_FACTOR:g}, the largest "
                      f"{largest:.4g} for {suite[worst].name!r}; check the units if that is "
                      f"not meant ({hint}).", InputWarning, stacklevel=3)


def _suite(motions: Any, owner: str) -> tuple[tuple[Motion, ...], type]:
    """The records or the pairs of a suite and their kind (a key of :data:`MEASURES`)."""
    if isinstance(motions, str | bytes) or not hasattr(motions, "__iter__"):
        raise InputTypeError(f"The 'motions' parameter of {owner} must be a non-empty sequence "
                             f"of GroundMotion or of GroundMotionPair. Got {motions!r:.80} "
                             "instead.")
    suite = tuple(motions)
    for kind in MEASURES:
        if suite and all(isinstance(m, kind) for m in suite):
            return suite, kind
    raise InputTypeError(f"The 'motions' parameter of {owner} must be a non-empty sequence of "
                         f"GroundMotion or of GroundMotionPair. Got {motions!r} instead.")


def scale_suite(
    motions: Sequence[GroundMotion] | Sequence[GroundMotionPair],
    target: TargetSpectrum | tuple[Any, Any],
    period_range: tuple[float, float],
    damping: float = 0.05,
    method: str = "mean",
    *,
    measure: str | None = None,
    fraction: float = 1.0,
    n_periods: int = 60,
    angle_step: float = 1.0,
    max_factor: float | None = MAX_SCALE_FACTOR,
) -> ScalingReport:
    """Amplitude-scale a suite so that its mean spectrum envelopes the target over a period range.

    Parameters
    ----------
    motions : sequence of GroundMotion, or sequence of GroundMotionPair
        At least one record, or pair (one factor for every component of a pair).
    target : TargetSpectrum or (array_like, array_like)
        The target, or a ``(periods [s], sa [m/s^2])`` table; its periods must cover
        ``period_range``.
    period_range : (float, float)
        ``(T_min, T_max)`` with 0 < T_min <= T_max [s], e.g. `isolated_period_range`.
    damping : float
        Damping ratio of the spectra, in [0, 1) [-].
    method : {"mean", "individual"}
        ``"mean"`` (ASCE 7-16 17.3.3): the mean spectrum of the scaled suite is nowhere on the
        grid below ``fraction`` times the target; ``"individual"``: each one's own spectrum.
    measure : {"sa", "rotd100", "rotd50"}, optional
        The spectrum the factors are fitted on: ``"sa"``, a record's own (the only one of
        records); ``"rotd100"`` (the default of pairs, ASCE 7-16 17.3.3) or ``"rotd50"``, a
        pair's maximum-direction or median-direction spectrum.
    fraction : float
        The share of the target the mean must reach, in (0, 1] [-] (1 for 17.3.3).
    n_periods : int
        Number of log-spaced grid periods over the range, in [2, 1000] (1 if T_min = T_max).
    angle_step : float
        Step of the directions of a pair's RotD spectra [deg] (`rotd_spectra`).
    max_factor : float or None
        The largest scale factor accepted [-] (default :data:`MAX_SCALE_FACTOR`; one above
        :data:`WARN_SCALE_FACTOR` is given with a warning when it is at most that); None
        accepts any, without a warning (e.g. to study the scaling itself).

    Returns
    -------
    ScalingReport
        The factors, the scaled suite, its spectra and the mean-to-target ratio on the grid.

    Raises
    ------
    InputError
        For a parameter out of range, a target above :data:`MAX_TARGET_SA`, or a scale factor
        above ``max_factor`` (the record or pair and its factor named): the target and the
        records are then likely in different units.

    Warns
    -----
    InputWarning
        For a scale factor above :data:`WARN_SCALE_FACTOR` (unless ``max_factor`` is None).

    Notes
    -----
    Step 1: each record's (pair's) factor is the geometric mean over the grid of
    ``target / measure``. Step 2: one common factor ``1 / min_T(mean_i(Sa_i) / target)`` (per
    record with ``"individual"``). The criterion is checked on the grid only.
    """
    owner = "scale_suite"
    suite, kind = _suite(motions, owner)
    target, periods, (t_min, t_max) = scaling_grid(target, period_range, n_periods, owner)
    how = check_choice(method, "method", owner, ("mean", "individual"))
    fitted = check_choice(MEASURES[kind][0] if measure is None else measure, "measure", owner,
                          MEASURES[kind])
    zeta = check_real(damping, "damping", owner, low=0.0, high=1.0, high_open=True)
    share = check_real(fraction, "fraction", owner, low=0.0, high=1.0, low_open=True)
    target_sa = share * target.sa_at(periods)
    spectra = suite_spectra(suite, periods, zeta, angle_step=angle_step)
    empty = np.flatnonzero(~(spectra[fitted] > 0.0).all(axis=1))
    if empty.size:
        noun = "pairs" if kind is GroundMotionPair else "records"
        raise InputError(f"The 'motions' parameter of {owner} must hold {noun} with a non-zero "
                         f"{_LABELS[fitted]} over the range. Got {suite[empty[0]]!r} at index "
                         f"{empty[0]} instead.")
    individual, common, factors = suite_factors(spectra[fitted], target_sa, how)
    if max_factor is not None:
        limit = check_real(max_factor, "max_factor", owner, low=1.0)
        _check_factors(suite, factors, target, owner, limit)
    scaled = {name: factors[:, None] * sa for name, sa in spectra.items()}
    ratio = scaled[fitted].mean(axis=0) / target_sa
    tight = int(np.argmin(ratio))
    return ScalingReport(
        names=tuple(m.name for m in suite), individual_factors=individual,
        common_factor=common, scale_factors=factors, periods=periods, target_sa=target_sa,
        spectra=scaled, ratio=ratio, min_ratio=float(ratio[tight]),
        tightest_period=float(periods[tight]),
        motions=tuple(m.scaled(float(k)) for m, k in zip(suite, factors, strict=True)),
        period_range=(t_min, t_max), damping=zeta, fraction=share, method=how,
        measure=fitted, target_name=target.name,
    )
