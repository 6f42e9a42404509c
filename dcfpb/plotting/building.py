"""The figures of building runs, in one direction or in plan (:func:`plot_runs`): a quantity
with a direction gets a panel, or a line style, per direction."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.plotting.base import PNG_OPTIONS, colour, corner_bearing, draw, finish, margins, pyplot
from dcfpb.plotting.plan import plot_bearing_orbits, plot_force_orbits, plot_plate_temperature
from dcfpb.plotting.spectra import plot_floor_spectra, plot_isolation_effect

DIRECTION_STYLES = {"x": "-", "y": "--"}
"""Line style of each direction where both share a panel."""


def plot_runs(results: dict[str, Any], directory: str | Path, *, title: str = "",
              fixed_base: Any = None, processes: int = 1) -> list[Path]:
    """Figures comparing building runs, one Dataset of :func:`structures.analysis.run` per
    label (friction model or program), written to ``directory`` (made if missing) under
    ``title``; returns the files written, in the order below.

    ``isolator_hysteresis.png``, ``temperature.png``, ``roof_acceleration.png``,
    ``storey_drift.png`` and ``response_histories.png``; when the runs carry floor spectra
    (:func:`structures.floor_spectra.with_floor_spectra`) ``floor_spectra.png``, and with a
    ``fixed_base`` run (:func:`structures.fixed_base.run_fixed_base` of the same superstructure,
    with floor spectra) ``isolation_effect.png`` (:mod:`dcfpb.plotting.spectra`); in plan
    ``bearing_orbits.png``, ``force_orbits.png`` and, when a run holds the plate's temperature
    field, ``plate_temperature.png`` (:mod:`dcfpb.plotting.plan`). With ``processes=2`` a forked
    copy of this process draws about half of the figures (:func:`dcfpb.plotting.base.draw`); the
    files are the same.
    """
    import numpy as np

    plt = pyplot()
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    first = next(iter(results.values()))
    directions = [str(d) for d in first["direction"].values]
    one_direction = len(directions) == 1

    def save(fig, name):
        return finish(fig, directory / name, title=title, **PNG_OPTIONS)

    def hysteresis():
        fig, axes = plt.subplots(1, len(directions), figsize=(6.5 * len(directions), 5),
                                 squeeze=False)
        margins(fig, wspace=0.3)
        for axis, (ax, name) in enumerate(zip(axes[0], directions, strict=True)):
            for i, (label, r) in enumerate(results.items()):
                ax.plot(1e3 * r["displacement"].values[:, 0, axis],
                        r["base_shear"].values[:, axis] / 1e3, lw=0.7, color=colour(label, i),
                        label=label)
            where = "" if one_direction else f", {name}"
            ax.set_xlabel(f"isolator displacement{where} [mm]")
            ax.set_ylabel(f"isolator force, all bearings{where} [kN]")
            ax.set_title("isolator hysteresis" + ("" if one_direction else " (base slab at the "
                                                                     "centre of stiffness)"))
            ax.grid(alpha=0.3)
        axes[0, 0].legend(loc="upper left")  # a fixed place: "best" searches every point
        return save(fig, "isolator_hysteresis.png")

    def temperature():
        fig, ax = plt.subplots(figsize=(8, 4))
        margins(fig, left=0.75)
        for i, (label, r) in enumerate(results.items()):
            ax.plot(r["time"], r["temperature"].values[:, corner_bearing(r)], lw=0.8,
                    color=colour(label, i), label=label)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("contact temperature [degC]")
        ax.set_title("temperature of the sliding surface (contact area)"
                     + ("" if one_direction else ", corner bearing"))
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right")
        return save(fig, "temperature.png")

    def roof_acceleration():
        fig, axes = plt.subplots(len(results), len(directions),
                                 figsize=(9 * len(directions), 1.2 + 1.9 * len(results)),
                                 sharex=True, sharey=True, squeeze=False)
        margins(fig, left=0.75, hspace=0.12)
        for i, (row, (label, r)) in enumerate(zip(axes, results.items(), strict=True)):
            for axis, ax in enumerate(row):
                ax.plot(r["time"], r["ground_acceleration"].values[:, axis], lw=0.5,
                        color="0.65", label="ground")
                ax.plot(r["time"], r["absolute_acceleration"].values[:, -1, axis], lw=0.6,
                        color=colour(label, i), label=f"roof, {label}")
                ax.set_ylabel("[m/s$^2$]")
                ax.grid(alpha=0.3)
                ax.legend(loc="upper right", ncol=2, fontsize=8)
        for axis, name in enumerate(directions):
            axes[0, axis].set_title("roof absolute acceleration against the ground acceleration"
                                    + ("" if one_direction else f", {name}"))
            axes[-1, axis].set_xlabel("time [s]")
        return save(fig, "roof_acceleration.png")

    def storey_drift():
        fig, ax = plt.subplots(figsize=(5, 5.5))
        margins(fig, left=0.7)
        for i, (label, r) in enumerate(results.items()):
            drift = 1e3 * np.abs(r["storey_drift"].values).max(axis=0)  # (storey, direction)
            for axis, name in enumerate(directions):
                ax.plot(drift[:, axis], r["storey"], marker="o", color=colour(label, i),
                        ls=DIRECTION_STYLES[name],
                        label=label if one_direction else f"{label}, {name}")
        ax.set_xlabel("peak storey drift [mm]")
        ax.set_ylabel("storey")
        ax.set_yticks(first["storey"].values)
        ax.set_xlim(left=0.0)
        ax.set_title("storey drift profile")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right", fontsize=8 if one_direction else 7)
        return save(fig, "storey_drift.png")

    def response_histories():
        rows = 3 if one_direction else 4
        fig, axes = plt.subplots(rows, 1, figsize=(9, 2.3 * rows), sharex=True)
        margins(fig, left=0.9, top=0.6, hspace=0.1)
        for i, (label, r) in enumerate(results.items()):
            c = colour(label, i)
            for axis, name in enumerate(directions):
                style = {"lw": 0.7, "color": c, "ls": DIRECTION_STYLES[name]}
                named = label if one_direction else f"{label}, {name}"
                axes[0].plot(r["time"], 1e3 * r["displacement"].values[:, 0, axis],
                             label=named, **style)
                axes[1].plot(r["time"], r["base_shear"].values[:, axis] / 1e3, **style)
            axes[2].plot(r["time"], r["mu"].values[:, corner_bearing(r)], lw=0.5, color=c)
            if not one_direction:
                axes[3].plot(r["time"], 1e3 * r["rotation"].values[:, 0], lw=0.6, color=c)
        axes[0].set_ylabel("isolator disp. [mm]")
        axes[1].set_ylabel("base shear [kN]")
        axes[2].set_ylabel("friction coeff. [-]")
        if not one_direction:
            axes[3].set_ylabel("base rotation [mrad]")
        axes[-1].set_xlabel("time [s]")
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
    if not one_direction:
        figures += [(lambda: plot_bearing_orbits(results, directory, title),
                     "bearing_orbits.png", 1.0),
                    (lambda: plot_force_orbits(results, directory, title),
                     "force_orbits.png", 1.0)]
        if any("plate_temperature" in r for r in results.values()):
            figures.append((lambda: plot_plate_temperature(results, directory, title),
                            "plate_temperature.png", 1.0))
    return draw([(directory / name, function, weight) for function, name, weight in figures],
                processes=processes)
