"""Figures of a ground-motion suite: peak distributions per friction model (of records, or of
pairs on a building in plan), scaled spectra (of records, or the RotD100 and RotD50 of pairs).

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
_PLAN_PANELS = (  # a suite of pairs: runs in plan (structures.analysis.peaks)
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


def plot_scaled_spectra(
    motions: Sequence[GroundMotion] | Sequence[GroundMotionPair],
    target_periods: np.ndarray,
    target_sa: np.ndarray,
    path: str | Path,
    *,
    period_range: tuple[float, float] | None = None,
    damping: float = 0.05,
    title: str = "",
) -> Path:
    """Spectra of the scaled suite, their mean, and the target: each record's own spectrum, or
    each pair's RotD100 with the mean RotD50 beside (`groundmotions.suite_spectra`).

    Parameters
    ----------
    motions : sequence of GroundMotion, or sequence of GroundMotionPair
        The records or the pairs as scaled for the suite (acceleration [m/s^2]).
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
    from groundmotions.pairs import GroundMotionPair
    from groundmotions.scaling import suite_spectra

    plt = _pyplot()
    t_target = np.asarray(target_periods, dtype=float)
    pairs = bool(motions) and isinstance(motions[0], GroundMotionPair)
    noun = "pairs" if pairs else "records"
    top = max(10.0, 1.2 * float(t_target.max()))
    periods = np.geomspace(0.02, top, 100 if pairs else 160)  # RotD costs 180 directions
    fig, ax = plt.subplots(figsize=(8, 5.5), constrained_layout=True)
    spectra = suite_spectra(motions, periods, damping) if motions else {}
    for k, (measure, sa) in enumerate(spectra.items()):  # the fitted measure first
        sa = sa / STANDARD_GRAVITY
        name = "" if measure == "sa" else measure.replace("rotd", "RotD") + " "
        if k == 0:
            each = f"{name}of the scaled {noun}" if name else f"scaled {noun}"
            for i, row in enumerate(sa):
                ax.plot(periods, row, color="0.6", lw=0.6, label=each if i == 0 else None)
            ax.plot(periods, sa.mean(axis=0), color="k", lw=2.0,
                    label=f"mean {name}of {len(sa)} {noun}")
        else:
            ax.plot(periods, sa.mean(axis=0), color="k", lw=1.2, ls=":", label=f"mean {name}")
    ax.plot(t_target, np.asarray(target_sa, dtype=float), color="tab:red", lw=2.0,
            ls="--", label="target")
    if period_range is not None:
        ax.axvspan(*period_range, color="tab:orange", alpha=0.15, label="scaling period range")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("period [s]")
    ax.set_ylabel(f"pseudo-spectral acceleration ({100 * damping:g} % damping) [g]")
    ax.set_title(title or f"scaled {noun}{' (RotD100)' if pairs else ''} against the target "
                 "spectrum")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
