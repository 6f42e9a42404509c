"""Figures of floor response spectra and of what the isolation buys against a fixed base.

:func:`plot_floor_spectra` draws the 5 %-damped spectra of every floor beside the ground's, one
panel per run; :func:`plot_isolation_effect` draws the isolated peaks as ratios to the fixed
base, the peak profiles up the height and the roof's spectrum. Both take the Datasets of
:func:`structures.analysis.run` and :func:`structures.fixed_base.run_fixed_base` with
:func:`structures.floor_spectra.with_floor_spectra` applied. matplotlib is imported inside each
function (:func:`dcfpb.plotting.base.pyplot`, Agg backend).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.plotting.base import PNG_OPTIONS, pyplot

FIXED_BASE_COLOUR = "0.25"
PERIOD_TICKS = (0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0)  # [s], labelled as plain numbers
GROUND_STYLE = {"color": "black", "lw": 1.4, "ls": "--"}


def _period_axis(ax) -> None:
    """A logarithmic period axis with plain labels at ``PERIOD_TICKS`` and no minor ticks
    (a log axis's default minor ticks and mathtext labels take most of a figure's time)."""
    from matplotlib.ticker import FixedLocator, FormatStrFormatter, NullLocator

    ax.set_xscale("log")
    ax.xaxis.set_major_locator(FixedLocator(PERIOD_TICKS))
    ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.set_xlabel("period [s]")


def plot_floor_spectra(results: dict[str, Any], path: str | Path, *, title: str = "") -> Path:
    """Floor response spectra (Sa of each floor's absolute acceleration) and the ground's.

    Parameters
    ----------
    results : dict of str to xarray.Dataset
        Runs with ``floor_spectrum`` and ``ground_spectrum``, keyed by a label (one panel
        each, sharing the Sa axis).
    path : str or Path
        PNG file to write.
    title : str
        Figure title.
    """
    import numpy as np

    plt = pyplot()
    n = len(results)
    width = max(3.3 * n + 1.0, 6.0)
    fig, axes = plt.subplots(1, n, figsize=(width, 4.2), sharey=True, squeeze=False)
    fig.subplots_adjust(left=0.75 / width, right=1.0 - 0.1 / width, bottom=0.13, top=0.80,
                        wspace=0.08)
    for ax, (label, r) in zip(axes[0], results.items(), strict=True):
        period = r["period"].values
        shown = period > 0.0
        floors = r["floor"].values
        colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.9, floors.size))
        ax.plot(period[shown], r["ground_spectrum"].values[shown], label="ground", **GROUND_STYLE)
        for floor, colour in zip(floors, colours, strict=True):
            name = "base" if floor == 0 else ("roof" if floor == floors[-1] else f"floor {floor}")
            ax.plot(period[shown], r["floor_spectrum"].sel(floor=floor).values[shown],
                    color=colour, lw=1.0, label=name)
        _period_axis(ax)
        ax.set_title(label, fontsize=10)
        ax.grid(alpha=0.3)
        ax.set_ylim(bottom=0.0)
    axes[0, 0].set_ylabel("Sa [m/s$^2$]")
    axes[0, -1].legend(fontsize=7, loc="upper right")
    first = next(iter(results.values()))
    damping = 100 * first.attrs.get("spectrum_damping", 0.05)
    fig.suptitle((f"{title}\n" if title else "")
                 + f"floor response spectra, {damping:g} % damping (floor 0 = base)")
    path = Path(path)
    fig.savefig(path, dpi=110, **PNG_OPTIONS)
    plt.close(fig)
    return path


def plot_isolation_effect(results: dict[str, Any], fixed_base: Any, path: str | Path, *,
                          colours: dict[str, str], title: str = "") -> Path:
    """What the isolation buys: isolated peaks over the fixed base's, profiles and roof spectra.

    Parameters
    ----------
    results : dict of str to xarray.Dataset
        Isolated runs (with floor spectra), keyed by their friction model.
    fixed_base : xarray.Dataset
        The same superstructure on a fixed base (with floor spectra).
    path : str or Path
        PNG file to write.
    colours : dict of str to str
        Colour of each run's label.
    title : str
        Figure title.
    """
    import numpy as np

    from structures.fixed_base import PEAK_NAMES, ratios_to_fixed_base

    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.2))
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.07, top=0.90, wspace=0.25, hspace=0.32)
    (ax_ratio, ax_drift), (ax_acc, ax_sa) = axes
    labels = ("storey drift", "storey shear", "roof acc.", "base shear")
    width = 0.8 / max(len(results), 1)
    for i, (name, r) in enumerate(results.items()):
        ratios = ratios_to_fixed_base(r, fixed_base)
        x = np.arange(len(PEAK_NAMES)) + (i - 0.5 * (len(results) - 1)) * width
        bars = ax_ratio.bar(x, [ratios[k] for k in PEAK_NAMES], width, color=colours[name],
                            label=name)
        ax_ratio.bar_label(bars, fmt="%.2f", fontsize=7)
    ax_ratio.axhline(1.0, color=FIXED_BASE_COLOUR, lw=1.0, ls="--", label="fixed base = 1")
    ax_ratio.set_xticks(np.arange(len(PEAK_NAMES)), labels)
    ax_ratio.set_ylabel("isolated peak / fixed-base peak [-]")
    ax_ratio.set_title("peaks as ratios to the fixed base")
    ax_ratio.legend(fontsize=8, loc="upper right")
    ax_ratio.grid(alpha=0.3, axis="y")

    everything = {"fixed base": fixed_base, **results}
    colour_of = {"fixed base": FIXED_BASE_COLOUR, **colours}
    for name, r in everything.items():
        drift = 1e3 * np.abs(r["storey_drift"]).max("time")
        ax_drift.plot(drift, r["storey"], marker="o", color=colour_of[name], label=name)
        peak = np.abs(r["absolute_acceleration"]).max("time")
        ax_acc.plot(peak, r["floor"], marker="o", color=colour_of[name], label=name)
        shown = r["period"].values > 0.0
        ax_sa.plot(r["period"].values[shown],
                   r["floor_spectrum"].isel(floor=-1).values[shown], color=colour_of[name],
                   label=f"roof, {name}")
    ground = fixed_base["ground_spectrum"]
    shown = fixed_base["period"].values > 0.0
    ax_sa.plot(fixed_base["period"].values[shown], ground.values[shown], label="ground",
               **GROUND_STYLE)
    pga = float(np.abs(fixed_base["ground_acceleration"]).max())
    ax_acc.axvline(pga, **GROUND_STYLE, label=f"PGA {pga / STANDARD_GRAVITY:.2f} g")
    ax_drift.set_xlim(left=0.0)
    ax_drift.set_xlabel("peak storey drift [mm]")
    ax_drift.set_ylabel("storey")
    ax_drift.set_yticks(fixed_base["storey"].values)
    ax_drift.set_title("storey drift profile")
    ax_acc.set_xlabel("peak absolute acceleration [m/s$^2$]")
    ax_acc.set_ylabel("floor (0 = base)")
    ax_acc.set_yticks(fixed_base["floor"].values)
    ax_acc.set_xlim(left=0.0)
    ax_acc.set_title("peak floor acceleration")
    _period_axis(ax_sa)
    ax_sa.set_ylabel("Sa [m/s$^2$]")
    ax_sa.set_ylim(bottom=0.0)
    ax_sa.set_title(f"roof response spectrum, {100 * fixed_base.attrs['spectrum_damping']:g} %")
    for ax, place in ((ax_drift, "upper right"), (ax_acc, "lower right"), (ax_sa, "upper right")):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc=place)
    if title:
        fig.suptitle(title)
    path = Path(path)
    fig.savefig(path, dpi=110, **PNG_OPTIONS)
    plt.close(fig)
    return path
