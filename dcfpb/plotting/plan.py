"""The figures only a building in plan has: the bearings' orbits coloured by their contact
temperature, the force orbits and the temperature field left on a plate. Each function takes
the Datasets of :func:`structures.analysis.run` in plan keyed by a label (one per friction
model, say) and writes one PNG beside those of :func:`dcfpb.plotting.building.plot_runs`."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.plotting.base import PNG_OPTIONS, colour, corner_bearing, finish, margins, pyplot

__all__ = ["plot_bearing_orbits", "plot_force_orbits", "plot_plate_temperature"]




def _capacity_circle(ax, result) -> None:
    import numpy as np

    capacity = 1e3 * float(result.attrs["displacement_capacity"])
    angle = np.linspace(0.0, 2.0 * np.pi, 181)
    ax.plot(capacity * np.cos(angle), capacity * np.sin(angle), color="0.6", lw=0.8, ls="--",
            label="displacement capacity")


def plot_bearing_orbits(results: dict[str, Any], directory: Path, title: str = "") -> Path:
    """``bearing_orbits.png``: the orbit of the corner bearing of each run, coloured by its
    contact temperature (by time when no run heats), with the displacement capacity."""
    import numpy as np
    from matplotlib.collections import LineCollection

    plt = pyplot()
    runs = list(results.items())
    fig, axes = plt.subplots(1, len(runs), figsize=(4.2 * len(runs) + 1.0, 4.6), squeeze=False)
    margins(fig, left=0.8, right=1.1, bottom=0.6, top=0.95, wspace=0.35)
    temperatures = np.concatenate([r["temperature"].values.ravel() for _, r in runs])
    low, high = float(np.nanmin(temperatures)), float(np.nanmax(temperatures))
    by_time = high - low < 0.5  # no heating (constant friction): colour by time instead
    if by_time:
        low, high = 0.0, max(float(r["time"][-1]) for _, r in runs)
    norm = plt.Normalize(low, max(high, low + 1.0))
    lines = None
    for ax, (label, r) in zip(axes[0], runs, strict=True):
        b = corner_bearing(r)
        xy = 1e3 * r["bearing_displacement"].values[:, b, :]
        segments = np.stack([xy[:-1], xy[1:]], axis=1)
        lines = LineCollection(segments, cmap="inferno", norm=norm, linewidths=1.0)
        lines.set_array(r["time"].values[1:] if by_time else r["temperature"].values[1:, b])
        ax.add_collection(lines)
        _capacity_circle(ax, r)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_xlabel("bearing displacement x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_title(f"{label}: bearing {b} at ({float(r['bearing_x'][b]):g}, "
                     f"{float(r['bearing_y'][b]):g}) m", fontsize=9)
        ax.grid(alpha=0.3)
    colourbar = fig.colorbar(lines, ax=list(axes[0]), fraction=0.04, pad=0.02)
    colourbar.set_label("time [s] (no heating)" if by_time else "contact temperature [degC]")
    return finish(fig, directory / "bearing_orbits.png", title=title, **PNG_OPTIONS)


def plot_force_orbits(results: dict[str, Any], directory: Path, title: str = "") -> Path:
    """``force_orbits.png``: the base shear (the sum of the bearings' forces) in plan, and the
    corner bearing's force against its displacement along x and y."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.4))
    margins(fig, left=0.8, bottom=0.6, top=0.95, wspace=0.35)
    for i, (label, r) in enumerate(results.items()):
        shear = r["base_shear"].values / 1e3
        axes[0].plot(shear[:, 0], shear[:, 1], lw=0.7, color=colour(label, i), label=label)
        b = corner_bearing(r)
        u = 1e3 * r["bearing_displacement"].values[:, b, :]
        f = r["bearing_force"].values[:, b, :] / 1e3
        for axis, ax in enumerate(axes[1:]):
            ax.plot(u[:, axis], f[:, axis], lw=0.7, color=colour(label, i), label=label)
    axes[0].set_aspect("equal", adjustable="datalim")
    axes[0].set_xlabel("base shear x [kN]")
    axes[0].set_ylabel("base shear y [kN]")
    axes[0].set_title("base shear orbit")
    for axis, ax in zip("xy", axes[1:], strict=True):
        ax.set_xlabel(f"corner bearing displacement {axis} [mm]")
        ax.set_ylabel(f"force {axis} [kN]")
        ax.set_title(f"corner bearing, {axis}")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper left", fontsize=8)
    return finish(fig, directory / "force_orbits.png", title=title, **PNG_OPTIONS)


def plot_plate_temperature(results: dict[str, Any], directory: Path,
                           title: str = "") -> Path | None:
    """``plate_temperature.png``: the temperature field left on the corner bearing's plate at
    the end of each run that holds one (the precise model's ``plate_temperature`` at the monitor
    points ``plate_point_x``, ``plate_point_y``), with the bearing's orbit on the plate (the
    slider's centre moves by half the bearing displacement). None when no run holds a field
    (a run that failed at its first step has no monitor point yet: it is left out)."""
    import numpy as np

    runs = [(label, r) for label, r in results.items() if "plate_temperature" in r
            and np.isfinite(r["plate_temperature"].values).any()]
    if not runs:
        return None
    plt = pyplot()
    fig, axes = plt.subplots(1, len(runs), figsize=(4.4 * len(runs) + 1.0, 4.6),
                             squeeze=False)
    margins(fig, left=0.8, right=1.1, bottom=0.6, top=0.95, wspace=0.35)
    fields = [r["plate_temperature"].values for _, r in runs]
    high = max(float(np.nanmax(f)) for f in fields)
    low = min(float(np.nanmin(f)) for f in fields)
    image = None
    for ax, (label, r) in zip(axes[0], runs, strict=True):
        b = corner_bearing(r)
        x = 1e3 * r["plate_point_x"].values[b]
        y = 1e3 * r["plate_point_y"].values[b]
        t = r["plate_temperature"].values[b]
        kept = np.isfinite(t)
        image = ax.scatter(x[kept], y[kept], c=t[kept], s=2.0, marker="s", cmap="inferno",
                           vmin=low, vmax=max(high, low + 1.0), linewidths=0)
        orbit = 0.5e3 * r["bearing_displacement"].values[:, b, :]
        ax.plot(orbit[:, 0], orbit[:, 1], color="tab:cyan", lw=0.5, alpha=0.7,
                label="slider centre")
        ax.set_aspect("equal")
        ax.set_xlabel("plate x [mm]")
        ax.set_ylabel("plate y [mm]")
        ax.set_title(f"{label}: bearing {b}, t = {float(r['time'][-1]):.3g} s", fontsize=9)
        ax.legend(loc="upper left", fontsize=7)
    colourbar = fig.colorbar(image, ax=list(axes[0]), fraction=0.04, pad=0.02)
    colourbar.set_label("plate temperature at the end [degC]")
    return finish(fig, directory / "plate_temperature.png", title=title, **PNG_OPTIONS)
