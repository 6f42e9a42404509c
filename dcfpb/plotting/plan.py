"""The figures of runs of a building in plan under a pair of records: the bearings' orbits
coloured by their contact temperature, the force orbits, the temperature field left on a plate,
and the roof and drift responses per direction.

Each function takes the Datasets of :func:`structures.spatial.analysis.run_spatial` keyed by
a label (one per friction model, say) and writes one PNG.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.plotting.base import PNG_OPTIONS, colour, draw, margins, pyplot

__all__ = ["plot_plan_runs"]


def corner_bearing(result: Any) -> int:
    """The bearing that moved farthest (largest resultant displacement): the corner bearing
    that torsion loads most."""
    import numpy as np

    reach = np.hypot(*np.moveaxis(result["bearing_displacement"].values, -1, 0))
    return int(np.argmax(reach.max(axis=0)))


def _save(plt, fig, directory: Path, name: str, title: str) -> Path:
    if title:
        fig.suptitle(title, fontsize=12 if fig.get_figwidth() > 7.0 else 9, wrap=True)
    path = directory / name
    fig.savefig(path, dpi=120, **PNG_OPTIONS)
    plt.close(fig)
    return path


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
    return _save(plt, fig, directory, "bearing_orbits.png", title)


def plot_force_orbits(results: dict[str, Any], directory: Path, title: str = "") -> Path:
    """``force_orbits.png``: the base shear (the sum of the bearings' forces) in the plane,
    and the corner bearing's force against its displacement along x and y."""
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
    return _save(plt, fig, directory, "force_orbits.png", title)


def plot_plate_temperature(results: dict[str, Any], directory: Path,
                           title: str = "") -> Path | None:
    """``plate_temperature.png``: the temperature field left on the corner bearing's plate at
    the end of each run that holds one (``plate_temperature`` on the monitor points under
    ``plate_point_x``, ``plate_point_y``; the precise model), with the bearing's orbit on
    the plate (the slider's centre moves by half the bearing displacement). None when no
    run holds a field."""
    import numpy as np

    runs = [(label, r) for label, r in results.items() if "plate_temperature" in r]
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
    return _save(plt, fig, directory, "plate_temperature.png", title)


def plot_plan_responses(results: dict[str, Any], directory: Path, title: str = "") -> Path:
    """``plan_responses.png``: the roof's absolute acceleration along x and y, the base
    rotation, and the envelope of the storey drift per direction."""
    import numpy as np

    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(11, 7))
    margins(fig, left=0.85, bottom=0.6, top=0.9, hspace=0.4, wspace=0.3)
    for i, (label, r) in enumerate(results.items()):
        c = colour(label, i)
        roof = r["absolute_acceleration"].isel(floor=-1).values
        for axis in range(2):
            axes[0, axis].plot(r["time"], roof[:, axis], lw=0.6, color=c, label=label)
        axes[1, 0].plot(r["time"], 1e3 * r["rotation"].isel(floor=0).values, lw=0.6,
                        color=c, label=label)
        drift = 1e3 * np.abs(r["storey_drift"].values).max(axis=0)  # (storey, direction)
        storeys = r["storey"].values
        axes[1, 1].plot(drift[:, 0], storeys, "o-", color=c, label=f"{label}, x")
        axes[1, 1].plot(drift[:, 1], storeys, "s--", color=c, label=f"{label}, y")
    for axis, name in enumerate("xy"):
        axes[0, axis].set_title(f"roof absolute acceleration, {name}")
        axes[0, axis].set_xlabel("time [s]")
        axes[0, axis].set_ylabel("[m/s^2]")
    axes[1, 0].set_title("rotation of the base slab")
    axes[1, 0].set_xlabel("time [s]")
    axes[1, 0].set_ylabel("[mrad]")
    axes[1, 1].set_title("peak storey drift")
    axes[1, 1].set_xlabel("drift [mm]")
    axes[1, 1].set_ylabel("storey")
    axes[1, 1].yaxis.get_major_locator().set_params(integer=True)
    for ax in axes.ravel():
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="upper right", fontsize=8)
    axes[1, 1].legend(loc="upper right", fontsize=7)
    return _save(plt, fig, directory, "plan_responses.png", title)


def plot_plan_runs(results: dict[str, Any], directory: str | Path, *, title: str = "",
                   processes: int = 1) -> list[Path]:
    """Figures of runs of a building in plan.

    Writes ``bearing_orbits.png``, ``force_orbits.png``, ``plan_responses.png`` and, when a
    run holds the plate's temperature field, ``plate_temperature.png`` to ``directory``.

    Parameters
    ----------
    results : dict of str to xarray.Dataset
        Output of :func:`structures.spatial.analysis.run_spatial`, keyed by a label.
    directory : str or Path
        Folder for the PNG files (created if missing).
    title : str
        Figure title.
    processes : int
        2: a forked copy of this process draws part of the figures
        (:func:`dcfpb.plotting.base.draw`).

    Returns
    -------
    list of Path
        The files written.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    figures = [
        (directory / "bearing_orbits.png",
         lambda: plot_bearing_orbits(results, directory, title), 1.0),
        (directory / "force_orbits.png",
         lambda: plot_force_orbits(results, directory, title), 1.0),
        (directory / "plan_responses.png",
         lambda: plot_plan_responses(results, directory, title), 1.5),
    ]
    if any("plate_temperature" in r for r in results.values()):
        figures.append((directory / "plate_temperature.png",
                        lambda: plot_plate_temperature(results, directory, title), 1.0))
    return draw(figures, processes=processes)
