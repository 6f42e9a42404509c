"""Figures of a ground-motion suite: peak distributions per friction model (of records, or of
pairs on a building in plan) and scaled spectra (of records, or the RotD100 and RotD50 of
pairs)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.plotting.base import finish
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
    """Box plots of the peak responses per friction model, each run drawn as a point, written
    to the PNG file ``path`` under ``title``.

    ``peaks`` is the peaks table of a suite (``SuiteResult.peaks``), failed runs left out; a suite
    of pairs (columns ``peak_roof_acceleration_x`` and ``_y``) gets the corner bearing's resultant
    displacement, the resultant base shear and the roof acceleration per direction. ``seed`` seeds
    the horizontal jitter of the points, so the figure is reproducible.
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
    return finish(fig, path)


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
    """Spectra of the scaled suite, their mean and the target, written to the PNG file ``path``
    under ``title``: each record's own spectrum, or each pair's RotD100 with the mean RotD50
    beside (`groundmotions.suite_spectra`).

    ``motions`` are the records or pairs as scaled for the suite [m/s^2]; the target is given by
    ``target_periods`` [s] and ``target_sa`` [g]; ``period_range`` [s], the scaling's, is shaded;
    ``damping`` [-] is the spectra's damping ratio.
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
    return finish(fig, path)
