"""The figures of building runs: hysteresis, temperature, roof acceleration, storey drift,
response histories, and (with floor spectra) the spectra and the effect of isolation."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.plotting.base import PNG_OPTIONS, colour, draw, margins, pyplot
from dcfpb.plotting.spectra import plot_floor_spectra, plot_isolation_effect


def plot_runs(results: dict[str, Any], directory: str | Path, *, title: str = "",
              fixed_base: Any = None, processes: int = 1) -> list[Path]:
    """Figures comparing building runs (one dataset per friction model or program).

    Writes ``isolator_hysteresis.png``, ``temperature.png``, ``roof_acceleration.png``,
    ``storey_drift.png`` and ``response_histories.png`` to ``directory``; when the runs carry
    floor spectra (:func:`structures.floor_spectra.with_floor_spectra`), ``floor_spectra.png``;
    and with a ``fixed_base`` run, ``isolation_effect.png`` (see :mod:`dcfpb.plotting.spectra`).

    Parameters
    ----------
    results : dict of str to xarray.Dataset
        Output of :func:`structures.analysis.run`, keyed by a label.
    directory : str or Path
        Folder for the PNG files (created if missing).
    title : str
        Figure title.
    fixed_base : xarray.Dataset, optional
        :func:`structures.fixed_base.run_fixed_base` of the same superstructure, with floor
        spectra: drawn beside the isolated runs' floor spectra, and as their reference.
    processes : int
        2: a forked copy of this process draws about half of the figures meanwhile
        (:func:`dcfpb.plotting.base.draw`); the same files either way.

    Returns
    -------
    list of Path
        The files written, in the order above.
    """
    import numpy as np

    plt = pyplot()
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)

    def save(fig, name):
        if title:
            fig.suptitle(title)
        path = directory / name
        fig.savefig(path, dpi=120, **PNG_OPTIONS)
        plt.close(fig)
        return path

    def hysteresis():
        fig, ax = plt.subplots(figsize=(6.5, 5))
        margins(fig)
        for i, (label, r) in enumerate(results.items()):
            ax.plot(1e3 * r["isolator_displacement"], r["isolator_force"] / 1e3, lw=0.7,
                    color=colour(label, i), label=label)
        ax.set_xlabel("isolator displacement [mm]")
        ax.set_ylabel("isolator force, all bearings [kN]")
        ax.set_title("isolator hysteresis")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper left")  # a fixed place: "best" searches every point of every line
        return save(fig, "isolator_hysteresis.png")

    def temperature():
        fig, ax = plt.subplots(figsize=(8, 4))
        margins(fig, left=0.75)
        for i, (label, r) in enumerate(results.items()):
            ax.plot(r["time"], r["temperature"], lw=0.8, color=colour(label, i), label=label)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("contact temperature [degC]")
        ax.set_title("temperature of the sliding surface (contact area)")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right")
        return save(fig, "temperature.png")

    def roof_acceleration():
        fig, axes = plt.subplots(len(results), 1, figsize=(9, 1.2 + 1.9 * len(results)),
                                 sharex=True, sharey=True, squeeze=False)
        margins(fig, left=0.75, hspace=0.12)
        for i, (ax, (label, r)) in enumerate(zip(axes[:, 0], results.items(), strict=True)):
            ax.plot(r["time"], r["ground_acceleration"], lw=0.5, color="0.65", label="ground")
            ax.plot(r["time"], r["absolute_acceleration"].isel(floor=-1), lw=0.6,
                    color=colour(label, i), label=f"roof, {label}")
            ax.set_ylabel("[m/s$^2$]")
            ax.grid(alpha=0.3)
            ax.legend(loc="upper right", ncol=2, fontsize=8)
        axes[0, 0].set_title("roof absolute acceleration against the ground acceleration")
        axes[-1, 0].set_xlabel("time [s]")
        return save(fig, "roof_acceleration.png")

    def storey_drift():
        first = next(iter(results.values()))
        fig, ax = plt.subplots(figsize=(5, 5.5))
        margins(fig, left=0.7)
        for i, (label, r) in enumerate(results.items()):
            drift = np.abs(r["storey_drift"]).max("time")
            ax.plot(1e3 * drift, r["storey"], marker="o", color=colour(label, i), label=label)
        ax.set_xlabel("peak storey drift [mm]")
        ax.set_ylabel("storey")
        ax.set_yticks(first["storey"].values)
        ax.set_xlim(left=0.0)
        ax.set_title("storey drift profile")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right")
        return save(fig, "storey_drift.png")

    def response_histories():
        fig, axes = plt.subplots(3, 1, figsize=(9, 7), sharex=True)
        margins(fig, left=0.9, top=0.6, hspace=0.1)
        for i, (label, r) in enumerate(results.items()):
            c = colour(label, i)
            axes[0].plot(r["time"], 1e3 * r["isolator_displacement"], lw=0.7, color=c,
                         label=label)
            axes[1].plot(r["time"], r["base_shear"] / 1e3, lw=0.7, color=c)
            axes[2].plot(r["time"], r["mu"], lw=0.5, color=c)
        axes[0].set_ylabel("isolator disp. [mm]")
        axes[1].set_ylabel("base shear [kN]")
        axes[2].set_ylabel("friction coeff. [-]")
        axes[2].set_xlabel("time [s]")
        axes[0].legend(ncol=3, fontsize=8, loc="upper right")
        for ax in axes:
            ax.grid(alpha=0.3)
        return save(fig, "response_histories.png")

    def floor_spectra():
        panels = ({"fixed base": fixed_base} if fixed_base is not None else {}) | results
        return plot_floor_spectra(panels, directory / "floor_spectra.png", title=title)

    def isolation_effect():
        colours = {label: colour(label, i) for i, label in enumerate(results)}
        return plot_isolation_effect(results, fixed_base, directory / "isolation_effect.png",
                                     colours=colours, title=title)

    # each figure, its file and its share of the drawing time (measured for the demo's runs)
    figures = [(hysteresis, "isolator_hysteresis.png", 2), (temperature, "temperature.png", 1.5),
               (roof_acceleration, "roof_acceleration.png", 3),
               (storey_drift, "storey_drift.png", 1),
               (response_histories, "response_histories.png", 3.5)]
    if all("floor_spectrum" in r for r in results.values()):
        figures.append((floor_spectra, "floor_spectra.png", 3))
    if fixed_base is not None:
        figures.append((isolation_effect, "isolation_effect.png", 6))
    return draw([(directory / name, function, weight) for function, name, weight in figures],
                processes=processes)
