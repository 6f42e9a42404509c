"""The pre-sliding branch: how u_y and the superstructure damping move the roof acceleration.

Reproduces ``docs/presliding_study.md`` and ``docs/presliding_study.png``:

    python docs/presliding_study.py            # about 20 s with a warm numba cache

The demo building (``examples/five_storey.toml``) under the bundled El Centro 1940 N-S record,
with the yield displacement u_y of the bearings' elastic-plastic friction branch at 0.1, 0.2,
0.5, 1 and 2 mm and the superstructure's Rayleigh damping at 1, 2 and 5 % (modes 1 and 2),
for the precise and the constant friction models (the simplified model follows the precise one
within 1 %). Each configuration is compared with the same superstructure on a fixed base with
the same damping (:mod:`structures.fixed_base`), and the precise model at 2 % is run again at
dt = 0.001 s to show the time step is not what moves the numbers. Prints the Markdown tables
of the document.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from groundmotions.bundled import load_bundled
from structures.analysis import run
from structures.config import load_config
from structures.fixed_base import run_fixed_base, superstructure_peaks
from structures.floor_spectra import with_floor_spectra, with_floor_spectra_all
from structures.shear_building import RayleighDamping, ShearBuilding

HERE = Path(__file__).resolve().parent
YIELD_DISPLACEMENTS = (0.1e-3, 0.2e-3, 0.5e-3, 1.0e-3, 2.0e-3)  # u_y [m]
DAMPING_RATIOS = (0.01, 0.02, 0.05)  # superstructure, Rayleigh on modes 1 and 2 [-]
MODELS = ("precise", "constant")
STYLE = {"precise": "-", "constant": "--"}
DAMPING_COLOURS = {0.01: "tab:red", 0.02: "tab:purple", 0.05: "tab:blue"}


def building_with_damping(building: ShearBuilding, ratio: float) -> ShearBuilding:
    """The same superstructure with Rayleigh damping ``ratio`` on modes 1 and 2."""
    return ShearBuilding(building.floor_masses, building.storey_stiffnesses, building.base_mass,
                         RayleighDamping((ratio, ratio), (1, 2)))


def study():
    """Every run of the study: {(model, ratio, u_y, dt): Dataset}, and the fixed bases."""
    config = load_config(HERE.parent / "examples" / "five_storey.toml")
    motion = load_bundled("elcentro")
    runs, fixed = {}, {}
    for ratio in DAMPING_RATIOS:
        building = building_with_damping(config.building, ratio)
        fixed[ratio] = with_floor_spectra(run_fixed_base(building, motion, dt=config.dt), motion)
        for model in MODELS:
            for uy in YIELD_DISPLACEMENTS:
                bearing = dataclasses.replace(config.bearing(model), yield_displacement=uy)
                steps = (config.dt, 0.001) if (model, ratio) == ("precise", 0.02) else (
                    config.dt,)
                for dt in steps:
                    runs[model, ratio, uy, dt] = run(building, bearing, motion,
                                                     config.integrator,
                                                     n_bearings=config.n_bearings, dt=dt)
    return config, motion, with_floor_spectra_all(runs, motion), fixed


def tables(config, motion, runs, fixed) -> str:
    """The Markdown tables of the study."""
    pga = motion.pga
    lines = ["| model | damping | u_y [mm] | roof acc. [m/s^2] | roof / PGA | roof / fixed base "
             "| storey drift / fixed | base shear [kN] | isolator disp. [mm] |",
             "|---|---|---|---|---|---|---|---|---|"]
    for (model, ratio, uy, dt), result in runs.items():
        if dt != config.dt:
            continue
        p, f = superstructure_peaks(result), superstructure_peaks(fixed[ratio])
        roof = p["peak_roof_acceleration"]
        lines.append(
            f"| {model} | {100 * ratio:g} % | {1e3 * uy:g} | {roof:.2f} | {roof / pga:.2f} | "
            f"{roof / f['peak_roof_acceleration']:.3f} | "
            f"{p['peak_storey_drift'] / f['peak_storey_drift']:.3f} | "
            f"{p['peak_base_shear'] / 1e3:.0f} | "
            f"{1e3 * float(np.abs(result['isolator_displacement']).max()):.1f} |")
    lines += ["", "| u_y [mm] | roof acc., dt = 0.005 s | roof acc., dt = 0.001 s | change |",
              "|---|---|---|---|"]
    for uy in YIELD_DISPLACEMENTS:
        coarse = superstructure_peaks(runs["precise", 0.02, uy, config.dt])
        fine = superstructure_peaks(runs["precise", 0.02, uy, 0.001])
        a, b = coarse["peak_roof_acceleration"], fine["peak_roof_acceleration"]
        lines.append(f"| {1e3 * uy:g} | {a:.3f} | {b:.3f} | {100 * (b / a - 1):+.1f} % |")
    lines += ["", "| damping | fixed base roof acc. [m/s^2] | roof / PGA |", "|---|---|---|"]
    for ratio, result in fixed.items():
        roof = superstructure_peaks(result)["peak_roof_acceleration"]
        lines.append(f"| {100 * ratio:g} % | {roof:.2f} | {roof / pga:.2f} |")
    return "\n".join(lines)


def figure(config, motion, runs, fixed, path: Path) -> Path:
    """The study's figure: peaks against u_y, and roof spectra against u_y and damping."""
    from dcfpb.plotting.base import pyplot

    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.4))
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.07, top=0.90, wspace=0.24, hspace=0.34)
    (ax_roof, ax_ratio), (ax_uy, ax_xi) = axes
    uy_mm = 1e3 * np.asarray(YIELD_DISPLACEMENTS)
    for ratio in DAMPING_RATIOS:
        for model in MODELS:
            peaks = [superstructure_peaks(runs[model, ratio, uy, config.dt])
                     for uy in YIELD_DISPLACEMENTS]
            roof = np.array([p["peak_roof_acceleration"] for p in peaks])
            fixed_roof = superstructure_peaks(fixed[ratio])["peak_roof_acceleration"]
            label = f"{model}, {100 * ratio:g} %"
            ax_roof.plot(uy_mm, roof, STYLE[model], marker="o", color=DAMPING_COLOURS[ratio],
                         label=label)
            ax_ratio.plot(uy_mm, roof / fixed_roof, STYLE[model], marker="o",
                          color=DAMPING_COLOURS[ratio], label=label)
    ax_roof.axhline(motion.pga, color="black", lw=1.2, ls=":", label="PGA")
    ax_roof.set_title("peak roof acceleration")
    ax_roof.set_ylabel("[m/s$^2$]")
    ax_ratio.set_title("peak roof acceleration / fixed base (same damping)")
    ax_ratio.set_ylabel("[-]")
    ax_ratio.set_ylim(0.0, 0.4)
    for ax in (ax_roof, ax_ratio):
        ax.set_xscale("log")
        ax.set_xticks(uy_mm, [f"{u:g}" for u in uy_mm])
        ax.set_xlabel("yield displacement u$_y$ [mm]")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7, ncol=2)
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.9, len(YIELD_DISPLACEMENTS)))
    ground = fixed[0.02]
    shown = ground["period"].values > 0.0
    period = ground["period"].values[shown]
    for uy, colour in zip(YIELD_DISPLACEMENTS, colours, strict=True):
        roof = runs["precise", 0.02, uy, config.dt]["floor_spectrum"].isel(floor=-1)
        ax_uy.plot(period, roof.values[shown], color=colour, label=f"u$_y$ = {1e3 * uy:g} mm")
    for ratio in DAMPING_RATIOS:
        roof = runs["precise", ratio, 0.5e-3, config.dt]["floor_spectrum"].isel(floor=-1)
        ax_xi.plot(period, roof.values[shown], color=DAMPING_COLOURS[ratio],
                   label=f"damping {100 * ratio:g} %")
    for ax, title in ((ax_uy, "roof spectrum, precise, damping 2 %"),
                      (ax_xi, "roof spectrum, precise, u$_y$ = 0.5 mm")):
        ax.plot(period, ground["ground_spectrum"].values[shown], color="black", ls="--",
                label="ground")
        for mode, t in enumerate(ground.attrs["fixed_base_periods"][:3], start=1):
            ax.axvline(t, color="0.6", lw=0.8, ls=":")
            ax.text(t, 0.98, f" T{mode}", transform=ax.get_xaxis_transform(), fontsize=7,
                    va="top", color="0.4")
        ax.set_xscale("log")
        ax.set_xlabel("period [s] (dotted: fixed-base modes)")
        ax.set_ylabel("Sa, 5 % [m/s$^2$]")
        ax.set_ylim(bottom=0.0)
        ax.set_title(title)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.suptitle(f"{config.name} under {motion.name}: the pre-sliding branch u$_y$ and the "
                 "superstructure damping")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


if __name__ == "__main__":
    config, motion, runs, fixed = study()
    print(tables(config, motion, runs, fixed))
    print(figure(config, motion, runs, fixed, HERE / "presliding_study.png"))
