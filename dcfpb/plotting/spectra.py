"""Figures of floor response spectra and of what the isolation buys against a fixed base.

Both take the Datasets of :func:`structures.analysis.run` and
:func:`structures.fixed_base.run_fixed_base` with
:func:`structures.floor_spectra.with_floor_spectra` applied.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.plotting.base import PNG_OPTIONS, finish, pyplot

FIXED_BASE_COLOUR = "0.25"
PERIOD_TICKS = (0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0)  # [s], labelled as plain numbers
GROUND_STYLE = {"color": "black", "lw": 1.4, "ls": "--"}


def _period_axis(ax) -> None:
    """A logarithmic period axis with plain labels at ``PERIOD_TICKS`` and no minor ticks
    (a log axis's default minor ticks and mathtext labels are slow to draw)."""
    from matplotlib.ticker import FixedLocator, FormatStrFormatter, NullLocator

    ax.set_xscale("log")
    ax.xaxis.set_major_locator(FixedLocator(PERIOD_TICKS))
    ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.set_xlabel("period [s]")


def plot_floor_spectra(results: dict[str, Any], path: str | Path, *, title: str = "") -> Path:
    """Floor response spectra (Sa of each floor's absolute acceleration) beside the ground's,
    one panel per run and direction (a row per direction), sharing the Sa axis, written to the PNG
    file ``path`` under ``title``.

    ``results`` are runs keyed by a label, with ``floor_spectrum`` (floor, direction, period) and
    ``ground_spectrum`` (direction, period).
    """
    import numpy as np

    plt = pyplot()
    n = len(results)
    directions = [str(d) for d in next(iter(results.values()))["direction"].values]
    width = max(3.3 * n + 1.0, 6.0)
    height = 4.2 + 3.4 * (len(directions) - 1)
    fig, axes = plt.subplots(len(directions), n, figsize=(width, height), sharey=True,
                             squeeze=False)
    fig.subplots_adjust(left=0.75 / width, right=1.0 - 0.1 / width, bottom=0.55 / height,
                        top=1.0 - 0.85 / height, wspace=0.08, hspace=0.3)
    for axis, row in enumerate(axes):
        for ax, (label, r) in zip(row, results.items(), strict=True):
            period = r["period"].values
            shown = period > 0.0
            floors = r["floor"].values
            colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.9, floors.size))
            ax.plot(period[shown], r["ground_spectrum"].values[axis, shown], label="ground",
                    **GROUND_STYLE)
            spectra = r["floor_spectrum"].values[:, axis]
            for floor, colour in zip(floors, colours, strict=True):
                name = "base" if floor == 0 else (
                    "roof" if floor == floors[-1] else f"floor {floor}")
                ax.plot(period[shown], spectra[floor, shown], color=colour, lw=1.0, label=name)
            _period_axis(ax)
            ax.set_title(label if len(directions) == 1 else f"{label}, {directions[axis]}",
                         fontsize=10)
            ax.grid(alpha=0.3)
            ax.set_ylim(bottom=0.0)
        row[0].set_ylabel("Sa [m/s$^2$]")
    axes[0, -1].legend(fontsize=7, loc="upper right")
    first = next(iter(results.values()))
    damping = 100 * first.attrs.get("spectrum_damping", 0.05)
    fig.suptitle((f"{title}\n" if title else "")
                 + f"floor response spectra, {damping:g} % damping (floor 0 = base)")
    return finish(fig, path, dpi=110, **PNG_OPTIONS)


def plot_isolation_effect(results: dict[str, Any], fixed_base: Any, path: str | Path, *,
                          colours: dict[str, str], title: str = "") -> Path:
    """What the isolation buys, written to the PNG file ``path`` under ``title``: the isolated
    peaks as ratios to the fixed base's, the peak profiles up the height and the roof's spectrum
    (in plan, x solid and y dashed, the ratios per direction).

    ``results`` are the isolated runs keyed by friction model, ``fixed_base`` the same
    superstructure on a fixed base, all with floor spectra; ``colours`` gives each run's colour.
    """
    import numpy as np

    from structures.fixed_base import ratios_to_fixed_base

    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.2))
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.07, top=0.90, wspace=0.25, hspace=0.32)
    (ax_ratio, ax_drift), (ax_acc, ax_sa) = axes
    directions = [str(d) for d in fixed_base["direction"].values]
    styles = {"x": "-", "y": "--"}
    ratios = {name: ratios_to_fixed_base(r, fixed_base) for name, r in results.items()}
    keys = list(next(iter(ratios.values())))
    short = {"peak_storey_drift": "storey drift", "peak_storey_shear": "storey shear",
             "peak_roof_acceleration": "roof acc.", "peak_base_shear": "base shear"}
    labels = [short[k.removesuffix("_x").removesuffix("_y")].replace(" ", "\n")
              + f", {k[-1]}" if len(directions) == 2 else short[k] for k in keys]
    width = 0.8 / max(len(results), 1)
    for i, (name, ratio) in enumerate(ratios.items()):
        x = np.arange(len(keys)) + (i - 0.5 * (len(results) - 1)) * width
        bars = ax_ratio.bar(x, [ratio[k] for k in keys], width, color=colours[name], label=name)
        ax_ratio.bar_label(bars, fmt="%.2f", fontsize=7 if len(keys) < 5 else 5)
    ax_ratio.axhline(1.0, color=FIXED_BASE_COLOUR, lw=1.0, ls="--", label="fixed base = 1")
    ax_ratio.set_xticks(np.arange(len(keys)), labels, fontsize=10 if len(keys) < 5 else 8)
    ax_ratio.set_ylabel("isolated peak / fixed-base peak [-]")
    ax_ratio.set_title("peaks as ratios to the fixed base")
    ax_ratio.legend(fontsize=8, loc="upper right")
    ax_ratio.grid(alpha=0.3, axis="y")

    everything = {"fixed base": fixed_base, **results}
    colour_of = {"fixed base": FIXED_BASE_COLOUR, **colours}
    for name, r in everything.items():
        drift = 1e3 * np.abs(r["storey_drift"].values).max(axis=0)
        peak = np.abs(r["absolute_acceleration"].values).max(axis=0)
        shown = r["period"].values > 0.0
        for axis, direction in enumerate(directions):
            named = name if len(directions) == 1 else f"{name}, {direction}"
            style = {"color": colour_of[name], "ls": styles[direction]}
            ax_drift.plot(drift[:, axis], r["storey"], marker="o", label=named, **style)
            ax_acc.plot(peak[:, axis], r["floor"], marker="o", label=named, **style)
            ax_sa.plot(r["period"].values[shown], r["floor_spectrum"].values[-1, axis, shown],
                       label=f"roof, {named}", **style)
    shown = fixed_base["period"].values > 0.0
    for axis, direction in enumerate(directions):
        ax_sa.plot(fixed_base["period"].values[shown],
                   fixed_base["ground_spectrum"].values[axis, shown],
                   label="ground" if len(directions) == 1 else f"ground, {direction}",
                   **GROUND_STYLE | {"ls": "--" if axis == 0 else ":"})
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
        ax.legend(fontsize=7 if len(directions) == 1 else 6, loc=place)
    if title:
        fig.suptitle(title)
    return finish(fig, path, dpi=110, **PNG_OPTIONS)
