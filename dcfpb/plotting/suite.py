"""Figures of a ground-motion suite: peak distributions per friction model (of records, or of
pairs on a building in plan), scaled spectra (of records, or the RotD100 of pairs).

matplotlib is imported inside each function (Agg backend) so the library runs without it.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.plotting.base import pyplot as _pyplot

if TYPE_CHECKING:
    import pandas as pd

    from groundmotions.pairs import GroundMotionPair
    from groundmotions.records import GroundMotion

_PANELS = (  # column, label, factor from SI to the plotted unit
    ("peak_isolator_displacement", "peak isolator displacement [mm]", 1e3),
    ("peak_base_shear", "peak base shear [kN]", 1e-3),
    ("peak_roof_acceleration", "peak roof acceleration [m/s$^2$]", 1.0),
    ("peak_storey_drift", "peak storey drift [mm]", 1e3),
)
_PLAN_PANELS = (  # the same for a suite of pairs (structures.spatial.peaks.plan_peaks)
    ("peak_isolator_displacement", "peak corner-bearing displacement [mm]", 1e3),
    ("peak_base_shear", "peak resultant base shear [kN]", 1e-3),
    ("peak_roof_acceleration_x", "peak roof acceleration x [m/s$^2$]", 1.0),
    ("peak_roof_acceleration_y", "peak roof acceleration y [m/s$^2$]", 1.0),
)


def plot_peak_distributions(peaks: pd.DataFrame, path: str | Path, *, title: str = "",
                            seed: int = 0) -> Path:
    """Box plots of the peak responses per friction model, each run drawn as a point.

    Parameters
    ----------
    peaks : pandas.DataFrame
        The peaks table of a suite (``SuiteResult.peaks``); failed runs are left out. The
        table of a suite of pairs (columns ``peak_roof_acceleration_x`` and ``_y``) gets the
        corner bearing's resultant displacement, the resultant base shear and the roof
        acceleration per direction.
    path : str or Path
        PNG file to write.
    title : str
        Figure title.
    seed : int
        Seed of the horizontal jitter of the points (the figure is reproducible).
    """
    plt = _pyplot()
    from structures.suites.summary import group_labels

    done = peaks[peaks["status"] == "done"]
    labels = np.asarray(group_labels(done, separator="\n"), dtype=object)
    groups = list(dict.fromkeys(labels))
    rng = np.random.default_rng(seed)
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), constrained_layout=True)
    panels = _PLAN_PANELS if "peak_roof_acceleration_x" in peaks.columns else _PANELS
    for ax, (column, label, factor) in zip(axes.flat, panels, strict=True):
        values = np.asarray(done[column], dtype=float)
        data = [factor * values[labels == g] for g in groups]
        if groups:
            ax.boxplot(data, tick_labels=groups, whis=(5, 95), showfliers=False)
            for i, values in enumerate(data, start=1):
                jitter = rng.uniform(-0.12, 0.12, values.size)
                ax.plot(i + jitter, values, "o", ms=3.5, alpha=0.6, color="tab:blue")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3, axis="y")
    fig.suptitle(title or f"peak responses of {len(done)} runs (whiskers: 5-95 %)")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def _finish_spectra(plt, fig, ax, target_periods: np.ndarray, target_sa: np.ndarray,
                    period_range: tuple[float, float] | None, damping: float, title: str,
                    path: str | Path) -> Path:
    """Add the target [g] and the shaded period range to spectra drawn on ``ax``, label the
    log-log axes, save the figure to ``path`` and close it."""
    ax.plot(target_periods, np.asarray(target_sa, dtype=float), color="tab:red", lw=2.0,
            ls="--", label="target")
    if period_range is not None:
        ax.axvspan(*period_range, color="tab:orange", alpha=0.15, label="scaling period range")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("period [s]")
    ax.set_ylabel(f"pseudo-spectral acceleration ({100 * damping:g} % damping) [g]")
    ax.set_title(title)
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_scaled_spectra(
    motions: Sequence[GroundMotion],
    target_periods: np.ndarray,
    target_sa: np.ndarray,
    path: str | Path,
    *,
    period_range: tuple[float, float] | None = None,
    damping: float = 0.05,
    title: str = "",
) -> Path:
    """5 %-damped spectra of the scaled records, their mean, and the target.

    Parameters
    ----------
    motions : sequence of GroundMotion
        The records as scaled for the suite (acceleration [m/s^2]).
    target_periods : array_like
        Periods of the target spectrum [s].
    target_sa : array_like
        Target pseudo-spectral acceleration [g].
    path : str or Path
        PNG file to write.
    period_range : (float, float), optional
        Period range of the scaling [s], shaded.
    damping : float
        Damping ratio of the spectra [-].
    title : str
        Figure title.
    """
    from groundmotions.spectra import spectrum

    plt = _pyplot()
    t_target = np.asarray(target_periods, dtype=float)
    top = max(10.0, 1.2 * float(t_target.max()))
    periods = np.geomspace(0.02, top, 160)
    fig, ax = plt.subplots(figsize=(8, 5.5), constrained_layout=True)
    curves = []
    for i, motion in enumerate(motions):
        sa = spectrum(motion, periods, damping).sa / STANDARD_GRAVITY
        curves.append(sa)
        ax.plot(periods, sa, color="0.6", lw=0.6, label="scaled records" if i == 0 else None)
    if curves:
        ax.plot(periods, np.mean(curves, axis=0), color="k", lw=2.0,
                label=f"mean of {len(curves)} records")
    return _finish_spectra(plt, fig, ax, t_target, target_sa, period_range, damping,
                           title or "scaled records against the target spectrum", path)


def plot_scaled_pair_spectra(
    pairs: Sequence[GroundMotionPair],
    target_periods: np.ndarray,
    target_sa: np.ndarray,
    path: str | Path,
    *,
    period_range: tuple[float, float] | None = None,
    damping: float = 0.05,
    title: str = "",
) -> Path:
    """5 %-damped RotD100 spectra of the scaled pairs, their mean and RotD50 mean, the target.

    Parameters
    ----------
    pairs : sequence of GroundMotionPair
        The pairs as scaled for the suite (acceleration [m/s^2]).
    target_periods : array_like
        Periods of the target spectrum [s].
    target_sa : array_like
        Target pseudo-spectral acceleration [g].
    path : str or Path
        PNG file to write.
    period_range : (float, float), optional
        Period range of the scaling [s], shaded.
    damping : float
        Damping ratio of the spectra [-].
    title : str
        Figure title.
    """
    from groundmotions.pairs.rotd import rotd_spectra

    plt = _pyplot()
    t_target = np.asarray(target_periods, dtype=float)
    top = max(10.0, 1.2 * float(t_target.max()))
    periods = np.geomspace(0.02, top, 100)
    fig, ax = plt.subplots(figsize=(8, 5.5), constrained_layout=True)
    rotd100, rotd50 = [], []
    for i, pair in enumerate(pairs):
        spectra = rotd_spectra(pair, periods, damping, (50, 100))
        rotd100.append(spectra.rotd100 / STANDARD_GRAVITY)
        rotd50.append(spectra.rotd50 / STANDARD_GRAVITY)
        ax.plot(periods, rotd100[-1], color="0.6", lw=0.6,
                label="RotD100 of the scaled pairs" if i == 0 else None)
    if rotd100:
        ax.plot(periods, np.mean(rotd100, axis=0), color="k", lw=2.0,
                label=f"mean RotD100 of {len(rotd100)} pairs")
        ax.plot(periods, np.mean(rotd50, axis=0), color="k", lw=1.2, ls=":",
                label="mean RotD50")
    return _finish_spectra(plt, fig, ax, t_target, target_sa, period_range, damping,
                           title or "scaled pairs (RotD100) against the target spectrum", path)
