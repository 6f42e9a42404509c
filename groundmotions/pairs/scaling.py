"""Amplitude scaling of a suite of horizontal pairs on their RotD100 spectra (ASCE 7-16).

``scale_pairs``
    one factor per pair (both horizontals and the vertical scaled alike) so that the mean
    maximum-direction (RotD100) spectrum of the scaled suite is nowhere below the target over
    the period range and touches it at its tightest period; the mean RotD50 is reported too.
``PairScalingReport``
    what it did, in the style of `groundmotions.scaling.ScalingReport`.

ASCE 7-16 Section 17.3.3 (isolated structures, three-dimensional analysis): for each pair a
maximum-direction spectrum is formed, one factor scales both components of a pair, and over
0.75 T_M (upper-bound properties) to 1.25 T_M (lower-bound properties)
(`groundmotions.isolated_period_range`) the average of the maximum-direction spectra of the
suite may not fall below the target. Section 16.2.3.1 (fixed-base structures) asks for 90 % of
the target over its own range: give ``fraction=0.9`` and that range.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_choice, check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.pairs.rotd import rotd_spectra
from groundmotions.scaling import TargetSpectrum, scaling_grid, suite_factors

__all__ = ["PairScalingReport", "scale_pairs"]


@dataclass(frozen=True, eq=False)
class PairScalingReport:
    """What `scale_pairs` did.

    Attributes
    ----------
    names : tuple of str
        Pair names, in the order given.
    individual_factors : numpy.ndarray
        Step 1: the factor matching each pair's RotD100 to the target on average over the
        range (geometric mean of target / RotD100) [-].
    common_factor : float
        Step 2: the one factor applied to all pairs so the mean RotD100 touches the target [-].
    scale_factors : numpy.ndarray
        The factors applied, ``common_factor * individual_factors`` [-].
    periods, target_sa : numpy.ndarray
        The period grid [s] and ``fraction`` times the target on it [m/s^2].
    rotd100, rotd50 : numpy.ndarray, shape (n_pairs, n_periods)
        The scaled pairs' RotD100 and RotD50 spectra on the grid [m/s^2].
    mean_rotd100, mean_rotd50 : numpy.ndarray
        Their means over the suite [m/s^2].
    ratio : numpy.ndarray
        ``mean_rotd100 / target_sa`` on the grid [-].
    min_ratio, tightest_period : float
        The minimum of ``ratio`` (1 to round-off with ``method="mean"``, >= 1 with
        ``"individual"``) [-] and the grid period where it occurs [s].
    pairs : tuple of GroundMotionPair
        The scaled pairs.
    period_range : (float, float)
        [s]. Also ``damping`` [-], ``fraction`` [-], ``method`` and ``target_name``.
    """

    names: tuple[str, ...]
    individual_factors: np.ndarray
    common_factor: float
    scale_factors: np.ndarray
    periods: np.ndarray
    target_sa: np.ndarray
    rotd100: np.ndarray
    rotd50: np.ndarray
    mean_rotd100: np.ndarray
    mean_rotd50: np.ndarray
    ratio: np.ndarray
    min_ratio: float
    tightest_period: float
    pairs: tuple[GroundMotionPair, ...] = field(repr=False)
    period_range: tuple[float, float] = (0.0, 0.0)
    damping: float = 0.05
    fraction: float = 1.0
    method: str = "mean"
    target_name: str = ""

    def to_frame(self) -> Any:
        """One row per pair (index ``pair``): the factors and the scaled PGA of x and y
        [m/s^2]; the summary (min ratio, tightest period ...) in ``attrs``."""
        import pandas as pd

        frame = pd.DataFrame(
            {
                "individual_factor": self.individual_factors,
                "common_factor": self.common_factor,
                "scale_factor": self.scale_factors,
                "scaled_pga_x": [p.x.pga for p in self.pairs],
                "scaled_pga_y": [p.y.pga for p in self.pairs],
            },
            index=pd.Index(self.names, name="pair"),
        )
        frame.attrs.update(min_ratio=self.min_ratio, tightest_period=self.tightest_period,
                           period_range=self.period_range, damping=self.damping,
                           fraction=self.fraction, method=self.method, target=self.target_name)
        return frame

    def spectrum_frame(self) -> Any:
        """One row per period [s]: ``target_sa``, ``mean_rotd100``, ``mean_rotd50`` [m/s^2]
        and ``ratio`` [-]."""
        import pandas as pd

        return pd.DataFrame({"target_sa": self.target_sa, "mean_rotd100": self.mean_rotd100,
                             "mean_rotd50": self.mean_rotd50, "ratio": self.ratio},
                            index=pd.Index(self.periods, name="period"))


def scale_pairs(
    pairs: Sequence[GroundMotionPair],
    target: TargetSpectrum | tuple[Any, Any],
    period_range: tuple[float, float],
    damping: float = 0.05,
    method: str = "mean",
    *,
    fraction: float = 1.0,
    n_periods: int = 60,
    angle_step: float = 1.0,
) -> PairScalingReport:
    """Scale a suite of pairs so its mean RotD100 spectrum envelopes the target over a range.

    Parameters
    ----------
    pairs : sequence of GroundMotionPair
        The pairs, at least one.
    target : TargetSpectrum or (array_like, array_like)
        The target, or a ``(periods [s], sa [m/s^2])`` table made into one; its periods must
        cover ``period_range``.
    period_range : (float, float)
        ``(T_min, T_max)`` with 0 < T_min <= T_max [s], e.g. `isolated_period_range`.
    damping : float
        Damping ratio of the spectra, in [0, 1) [-].
    method : {"mean", "individual"}
        ``"mean"`` (ASCE 7-16 17.3.3): the mean RotD100 of the scaled suite is not below
        ``fraction`` times the target on the grid and equals it at the tightest period.
        ``"individual"``: each pair's own RotD100 satisfies that.
    fraction : float
        The share of the target the mean must reach, in (0, 1] [-] (1 for 17.3.3).
    n_periods : int
        Number of log-spaced grid periods over the range, in [2, 1000] (1 if T_min = T_max).
    angle_step : float
        Step of the directions of the RotD spectra [deg] (see `rotd_spectra`).

    Returns
    -------
    PairScalingReport
        The factors, the scaled pairs, their RotD100 and RotD50 and the ratio on the grid.

    Notes
    -----
    The steps of `groundmotions.scale_suite` on RotD100 instead of a component's spectrum.
    A RotD spectrum scales with the pair (|k u_theta| = |k| |u_theta| at every angle), so the
    spectra are computed once, unscaled, and multiplied by the factors. The criterion is
    checked on the grid only.
    """
    owner = "scale_pairs"
    suite = tuple(pairs)
    if not suite or not all(isinstance(p, GroundMotionPair) for p in suite):
        raise InputTypeError(f"The 'pairs' parameter of {owner} must be a non-empty sequence of "
                         f"GroundMotionPair. Got {pairs!r} instead.")
    target, periods, (t_min, t_max) = scaling_grid(target, period_range, n_periods, owner)
    kind = check_choice(method, "method", owner, ("mean", "individual"))
    zeta = check_real(damping, "damping", owner, low=0.0, high=1.0, high_open=True)
    share = check_real(fraction, "fraction", owner, low=0.0, high=1.0, low_open=True)
    target_sa = share * target.sa_at(periods)
    spectra = [rotd_spectra(p, periods, zeta, (50, 100), angle_step=angle_step) for p in suite]
    rotd100 = np.array([s.rotd100 for s in spectra])
    rotd50 = np.array([s.rotd50 for s in spectra])
    empty = np.flatnonzero(~(rotd100 > 0.0).all(axis=1))
    if empty.size:
        raise InputError(f"The 'pairs' parameter of {owner} must hold pairs with a non-zero "
                         f"RotD100 spectrum over the range. Got {suite[empty[0]]!r} at index "
                         f"{empty[0]} instead.")
    individual, common, factors = suite_factors(rotd100, target_sa, kind)
    out = tuple(p.scaled(float(k)) for p, k in zip(suite, factors, strict=True))
    rotd100, rotd50 = factors[:, None] * rotd100, factors[:, None] * rotd50
    mean100 = rotd100.mean(axis=0)
    ratio = mean100 / target_sa
    tight = int(np.argmin(ratio))
    return PairScalingReport(
        names=tuple(p.name for p in suite), individual_factors=individual,
        common_factor=common, scale_factors=factors, periods=periods, target_sa=target_sa,
        rotd100=rotd100, rotd50=rotd50, mean_rotd100=mean100, mean_rotd50=rotd50.mean(axis=0),
        ratio=ratio, min_ratio=float(ratio[tight]), tightest_period=float(periods[tight]),
        pairs=out, period_range=(t_min, t_max), damping=zeta, fraction=share, method=kind,
        target_name=target.name,
    )
