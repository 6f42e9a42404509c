"""The figures of a Chapter 17 design report (``dcfpb design``), each drawn from a part of a
:class:`structures.design.result.DesignResult`: the scaled RotD100 spectra of the suite with the
target and the period range, the isolator displacement per pair, bound and position against the
ELF's D_M and D_TM, the governing corner bearing's orbit coloured by its contact temperature and
its hysteresis, the storey drift ratio profiles with the limit of 17.6.4.4, and the floor
spectra of the governing run; and the virtual prototype test's loop and mu per cycle. Each
function writes one PNG (:func:`~dcfpb.plotting.base.save_figure`) and returns its path."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.plotting.base import PNG_OPTIONS, corner_bearing, margins, pyplot, save_figure

__all__ = [
    "BOUND_COLOURS",
    "plot_design_displacements",
    "plot_design_drifts",
    "plot_design_floor_spectra",
    "plot_design_hysteresis",
    "plot_design_orbit",
    "plot_design_spectra",
    "plot_prototype",
]

BOUND_COLOURS = {"upper": "tab:red", "lower": "tab:blue", "nominal": "tab:gray"}
"""The colour of each bound of the properties in every design figure."""

POSITION_MARKERS = {"+x": ">", "-x": "<", "+y": "^", "-y": "v", "nominal": "o"}
"""The marker of each position of the centre of mass."""

POSITION_STYLES = {"+x": "-", "-x": "--", "+y": "-.", "-y": ":", "nominal": "-"}
"""The line style of each position of the centre of mass."""

_DPI = 120


def _save(plt, fig, path: str | Path, title: str) -> Path:
    if title:
        fig.suptitle(title, fontsize=11, wrap=True)
    path = Path(path)
    save_figure(fig, path, dpi=_DPI, **PNG_OPTIONS)
    plt.close(fig)
    return path


def _run_label(run: Any) -> str:
    """``pair X, lower bound, position +x`` of a governing run's attributes."""
    attrs = getattr(run, "attrs", {})
    parts = []
    if attrs.get("pair"):
        parts.append(f"pair {attrs['pair']}" + (" (synthetic)" if attrs.get("synthetic") else ""))
    if attrs.get("bound"):
        parts.append(f"{attrs['bound']} bound")
    if attrs.get("position"):
        parts.append(f"mass at {attrs['position']}")
    return ", ".join(parts)


def _log_ticks(axis) -> None:
    """Plain numbers at 1, 2, 5 times the powers of ten of a log axis; no minor labels."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())


def plot_design_spectra(spectra: Any, path: str | Path, *, title: str = "") -> Path:
    """The RotD100 of each scaled pair (synthetic ones dashed), their average and the MCE_R
    target [g] against the period [s], the period range of 17.3.3 shaded and the 90 % of the
    target the average must reach over it drawn (``spectra``: a
    :class:`~structures.design.result.ScaledSpectra`)."""
    import numpy as np

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8.0, 5.0))
    margins(fig, left=0.8, right=2.6, bottom=0.6, top=0.6 if title else 0.3)
    periods = np.asarray(spectra.periods, dtype=float)
    for i, (name, sa) in enumerate(spectra.pairs.items()):
        synthetic = name.startswith("synthetic")
        ax.plot(periods, sa, lw=0.8, color=f"C{i % 10}", ls="--" if synthetic else "-",
                alpha=0.8, label=name)
    ax.plot(periods, spectra.average, lw=2.2, color="black", label="average")
    ax.plot(periods, spectra.target, lw=2.0, color="tab:red", label="MCE$_R$ target")
    ax.plot(periods, 0.9 * np.asarray(spectra.target), lw=1.0, color="tab:red", ls=":",
            label="90 % of target")
    low, high = spectra.period_range
    ax.axvspan(low, high, color="0.85", zorder=0,
               label=f"period range {low:.2f}-{high:.2f} s")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(periods[periods > 0].min(), periods.max())
    _log_ticks(ax.xaxis)
    _log_ticks(ax.yaxis)
    ax.set_xlabel("period [s]")
    ax.set_ylabel("pseudo-acceleration RotD100 [g]")
    ax.grid(which="both", alpha=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False)
    return _save(plt, fig, path, title)


def plot_design_displacements(peaks: Any, elf: Any, path: str | Path, *,
                              column: str = "isolator_displacement",
                              capacity: float | None = None, title: str = "") -> Path:
    """The isolator displacement of every run [mm] by pair, one panel per bound, a marker per
    position of the centre of mass (ringed where the run stopped at the bearings' capacity);
    the average over the pairs of each position as a line across; the ELF's D_M and largest
    D_TM of that bound and the displacement ``capacity`` [m] as horizontal lines (``peaks``:
    the design's peaks table; ``elf``: its :class:`~structures.design.elf.ELFResult`)."""
    import numpy as np

    plt = pyplot()
    bounds = [b for b in ("upper", "lower") if b in set(peaks["bound"])]
    fig, axes = plt.subplots(1, len(bounds), figsize=(6.0 * len(bounds) + 1.6, 4.8),
                             squeeze=False, sharey=True)
    margins(fig, left=0.8, right=0.2, bottom=0.95, top=0.6 if title else 0.35, wspace=0.08)
    pairs = list(dict.fromkeys(peaks["pair"]))
    x_of = {name: i for i, name in enumerate(pairs)}
    positions = list(dict.fromkeys(peaks["position"]))
    width = 0.6
    highest = 0.0
    for ax, bound in zip(axes[0], bounds, strict=True):
        group = peaks[peaks["bound"] == bound]
        for k, position in enumerate(positions):
            rows = group[group["position"] == position]
            offset = (k - (len(positions) - 1) / 2) * width / max(len(positions), 1)
            x = np.array([x_of[p] for p in rows["pair"]], dtype=float) + offset
            values = 1e3 * rows[column].to_numpy(dtype=float)
            if values.size and np.isfinite(values).any():
                highest = max(highest, float(np.nanmax(values)))
            ax.plot(x, values, ls="none", marker=POSITION_MARKERS.get(position, "o"),
                    color=BOUND_COLOURS.get(bound, "k"), ms=6, alpha=0.85,
                    label=f"mass at {position}")
            if "failure" in rows:
                stopped = (rows["failure"] == "capacity").to_numpy()
                if stopped.any():
                    ax.plot(x[stopped], values[stopped], ls="none", marker="o", ms=11,
                            mfc="none", mec="black", mew=1.0,
                            label="stopped at capacity" if not any(
                                h.get_label() == "stopped at capacity" for h in ax.lines)
                            else None)
            if values.size:
                mean = float(np.nanmean(values))
                ax.plot([-0.5, len(pairs) - 0.5], [mean, mean], lw=0.8,
                        color=BOUND_COLOURS.get(bound, "k"),
                        ls=POSITION_STYLES.get(position, "-"), alpha=0.6,
                        label="average over pairs (style: position)" if k == 0 else None)
        result = elf.bounds[bound]
        d_tm = max(d.D_TM for d in result.directions.values())
        highest = max(highest, 1e3 * d_tm)
        ax.axhline(1e3 * result.D_M, color="black", lw=1.6, ls="--",
                   label=f"ELF D_M = {1e3 * result.D_M:.0f} mm")
        ax.axhline(1e3 * d_tm, color="black", lw=1.6, ls="-",
                   label=f"ELF D_TM = {1e3 * d_tm:.0f} mm")
        if capacity:
            ax.axhline(1e3 * capacity, color="0.45", lw=2.2, ls="-", alpha=0.6,
                       label=f"capacity {1e3 * capacity:.0f} mm")
            highest = max(highest, 1e3 * capacity)
        ax.set_xticks(range(len(pairs)))
        ax.set_xticklabels(pairs, rotation=35, ha="right", fontsize=8)
        ax.set_xlim(-0.6, len(pairs) - 0.4)
        ax.set_title(f"{bound} bound (lambda = {result.lambda_:g})", fontsize=10,
                     color=BOUND_COLOURS.get(bound, "k"))
        ax.grid(axis="y", alpha=0.3)
        ax.legend(loc="lower right", fontsize=7, ncol=2, framealpha=0.9)
    axes[0][0].set_ylim(0.0, 1.06 * highest if highest > 0 else 1.0)
    axes[0][0].set_ylabel("isolator displacement, largest bearing [mm]")
    return _save(plt, fig, path, title)


def plot_design_orbit(run: Any, path: str | Path, *, D_M: float | None = None,
                      D_TM: float | None = None, bound: str = "lower",
                      title: str = "") -> Path:
    """The orbit of the governing run's corner bearing [mm] coloured by its contact temperature
    (by time when the friction model does not heat), with the displacement capacity and the
    ELF's D_M and D_TM [m] of ``bound`` as circles."""
    import numpy as np
    from matplotlib.collections import LineCollection

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.6, 5.6))
    margins(fig, left=0.9, right=1.3, bottom=0.6, top=0.75 if title else 0.45)
    b = corner_bearing(run)
    xy = 1e3 * run["bearing_displacement"].values[:, b, :]
    temperature = run["temperature"].values[:, b] if "temperature" in run else None
    by_time = temperature is None or float(np.nanmax(temperature) - np.nanmin(temperature)) < 0.5
    colours = run["time"].values if by_time else temperature
    norm = plt.Normalize(float(np.nanmin(colours)), max(float(np.nanmax(colours)),
                                                        float(np.nanmin(colours)) + 1.0))
    segments = np.stack([xy[:-1], xy[1:]], axis=1)
    lines = LineCollection(segments, cmap="inferno", norm=norm, linewidths=1.1)
    lines.set_array(colours[1:])
    ax.add_collection(lines)
    angle = np.linspace(0.0, 2.0 * np.pi, 241)
    circles = [("displacement capacity", run.attrs.get("displacement_capacity"), "0.5", "-")]
    circles += [(f"ELF D_M ({bound} bound)", D_M, "tab:blue", "--"),
                (f"ELF D_TM ({bound} bound)", D_TM, "tab:green", ":")]
    for label, radius, colour, style in circles:
        if radius:
            r = 1e3 * float(radius)
            ax.plot(r * np.cos(angle), r * np.sin(angle), color=colour, ls=style, lw=1.0,
                    label=f"{label} {r:.0f} mm")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("bearing displacement x [mm]")
    ax.set_ylabel("bearing displacement y [mm]")
    where = f"bearing {b} at ({float(run['bearing_x'][b]):g}, {float(run['bearing_y'][b]):g}) m"
    ax.set_title(f"{_run_label(run)}\n{where}", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=7, framealpha=0.9)
    colourbar = fig.colorbar(lines, ax=ax, fraction=0.05, pad=0.03)
    colourbar.set_label("time [s] (no heating)" if by_time else "contact temperature [degC]")
    return _save(plt, fig, path, title)


def plot_design_hysteresis(run: Any, path: str | Path, *, title: str = "") -> Path:
    """The governing run's corner bearing: its force against its displacement along x and y
    [kN, mm], the loop coloured by time."""
    import numpy as np
    from matplotlib.collections import LineCollection

    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.6), sharey=True)
    margins(fig, left=0.9, right=1.2, bottom=0.6, top=0.75 if title else 0.45, wspace=0.08)
    b = corner_bearing(run)
    u = 1e3 * run["bearing_displacement"].values[:, b, :]
    f = run["bearing_force"].values[:, b, :] / 1e3
    time = run["time"].values
    norm = plt.Normalize(float(time[0]), float(time[-1]))
    lines = None
    for axis, ax in enumerate(axes):
        segments = np.stack([np.column_stack([u[:-1, axis], f[:-1, axis]]),
                             np.column_stack([u[1:, axis], f[1:, axis]])], axis=1)
        lines = LineCollection(segments, cmap="viridis", norm=norm, linewidths=0.9)
        lines.set_array(time[1:])
        ax.add_collection(lines)
        ax.autoscale_view()
        name = "xy"[axis]
        ax.set_xlabel(f"displacement {name} [mm]")
        ax.set_title(f"along {name}", fontsize=10)
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.axvline(0.0, color="0.6", lw=0.6)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("bearing force [kN]")
    colourbar = fig.colorbar(lines, ax=list(axes), fraction=0.04, pad=0.02)
    colourbar.set_label("time [s]")
    where = (f"bearing {b} at ({float(run['bearing_x'][b]):g}, "
             f"{float(run['bearing_y'][b]):g}) m")
    fig.text(0.5, 0.985, f"corner {where}; {_run_label(run)}", ha="center", va="top",
             fontsize=9)
    return _save(plt, fig, path, title)


def plot_design_drifts(averages: Any, heights: Any, limit: float, path: str | Path, *,
                       elf: Any = None, title: str = "") -> Path:
    """The storey drift ratio [%] of each storey, averaged over the pairs, one line per bound
    (colour) and position (style), one panel per direction, with the limit of 17.6.4.4
    (``limit``, a ratio) and, where ``elf`` is given, the ELF's drift ratios of each bound
    (thin grey). ``averages``: the design's averages (columns ``drift_ratio_x_1`` ...);
    ``heights``: the storey heights [m]."""
    import numpy as np

    plt = pyplot()
    directions = [d for d in ("x", "y") if f"drift_ratio_{d}_1" in averages.columns]
    fig, axes = plt.subplots(1, max(len(directions), 1), figsize=(5.0 * len(directions) + 1.8,
                                                                  4.8), squeeze=False,
                             sharey=True)
    margins(fig, left=0.8, right=2.0, bottom=0.6, top=0.6 if title else 0.35, wspace=0.08)
    heights = np.asarray(heights, dtype=float)
    storeys = np.arange(1, heights.size + 1)
    largest = 0.0
    for ax, direction in zip(axes[0], directions, strict=False):
        for _, row in averages.iterrows():
            columns = [f"drift_ratio_{direction}_{k}" for k in storeys]
            if not all(c in row for c in columns):
                continue
            values = 100.0 * np.array([row[c] for c in columns], dtype=float)
            if np.isfinite(values).any():
                largest = max(largest, float(np.nanmax(values)))
            ax.plot(values, storeys, marker="o", ms=3, lw=1.2,
                    color=BOUND_COLOURS.get(row["bound"], "k"),
                    ls=POSITION_STYLES.get(row["position"], "-"),
                    label=f"{row['bound']}, mass at {row['position']}")
        if elf is not None:
            for bound, result in elf.bounds.items():
                if direction in result.directions:
                    largest = max(largest, 100.0 * float(
                        np.max(result.directions[direction].drift_ratio)))
                    ax.plot(100.0 * np.asarray(result.directions[direction].drift_ratio),
                            storeys, color=BOUND_COLOURS.get(bound, "0.5"), alpha=0.45,
                            lw=0.9, ls=(0, (1, 1)), marker="s", ms=3,
                            label=f"ELF, {bound} bound (17.5.6)")
        ax.axvline(100.0 * limit, color="black", lw=1.8, ls="--",
                   label=f"limit {100.0 * limit:g} % (17.6.4.4)")
    off_scale = largest > 0 and 100.0 * limit > 3.0 * largest
    for ax in axes[0][:len(directions)]:
        if off_scale:  # the limit far beyond the data: the profiles shown, the limit named
            ax.set_xlim(0.0, 1.25 * largest)
        else:
            ax.set_xlim(left=0.0)
    for ax, direction in zip(axes[0], directions, strict=False):
        ax.set_xlabel(f"storey drift ratio {direction} [%]")
        ax.set_title(f"direction {direction}", fontsize=10)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("storey")
    axes[0][0].set_yticks(storeys)
    handles, labels = axes[0][0].get_legend_handles_labels()
    seen = dict(zip(labels, handles, strict=True))
    if off_scale:
        name = f"limit {100.0 * limit:g} % (17.6.4.4)"
        seen[f"{name}:\noff the scale, {100.0 * limit / largest:.0f} x the largest"] = \
            seen.pop(name)
    fig.legend(seen.values(), seen.keys(), loc="center right", fontsize=7, frameon=False)
    return _save(plt, fig, path, title)


def plot_design_floor_spectra(run: Any, path: str | Path, *, title: str = "") -> Path | None:
    """The governing run's floor spectra (``floor_spectrum``, pseudo-acceleration [g] against
    period [s]) of every floor, one panel per direction, with the ground's; None when the run
    holds none."""
    from dcfpb.common.units import STANDARD_GRAVITY

    if run is None or "floor_spectrum" not in run:
        return None
    plt = pyplot()
    directions = [str(d) for d in run["direction"].values]
    fig, axes = plt.subplots(1, len(directions), figsize=(5.2 * len(directions) + 1.6, 4.6),
                             squeeze=False, sharey=True)
    margins(fig, left=0.8, right=1.7, bottom=0.6, top=0.75 if title else 0.5, wspace=0.08)
    periods = run["period"].values
    shown = periods > 0
    spectra = run["floor_spectrum"].values / STANDARD_GRAVITY
    floors = run["floor"].values
    cmap = plt.get_cmap("viridis")
    for axis, (ax, direction) in enumerate(zip(axes[0], directions, strict=True)):
        if "ground_spectrum" in run:
            ground = run["ground_spectrum"].values[axis] / STANDARD_GRAVITY
            ax.plot(periods[shown], ground[shown], color="black", lw=1.4, ls="--",
                    label="ground")
        for k, floor in enumerate(floors):
            name = "base slab" if int(floor) == 0 else f"floor {int(floor)}"
            ax.plot(periods[shown], spectra[k, axis, shown], lw=1.1,
                    color=cmap(k / max(len(floors) - 1, 1)), label=name)
        ax.set_xscale("log")
        _log_ticks(ax.xaxis)
        ax.set_xlabel("period [s]")
        ax.set_title(f"direction {direction}", fontsize=10)
        ax.grid(which="both", alpha=0.3)
    damping = run.attrs.get("spectrum_damping", 0.05)
    axes[0][0].set_ylabel(f"pseudo-acceleration [g], {100 * float(damping):g} % damping")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=8, frameon=False)
    fig.text(0.5, 0.985, _run_label(run), ha="center", va="top", fontsize=9)
    return _save(plt, fig, path, title)


def plot_prototype(result: Any, path: str | Path, *, title: str = "") -> Path:
    """The virtual prototype test (:class:`structures.design.PrototypeResult`): the hysteresis
    loop [kN, mm] coloured by block of the sequence, and mu of every cycle with the nominal mu
    (the mean at D_M) and the cycle's peak contact temperature."""
    import numpy as np

    plt = pyplot()
    fig, (ax_loop, ax_mu) = plt.subplots(1, 2, figsize=(12.0, 4.8))
    margins(fig, left=0.85, right=0.9, bottom=0.6, top=0.85, wspace=0.3)
    test = result.test
    u = 1e3 * np.asarray(test.displacement, dtype=float)
    f = np.asarray(test.force, dtype=float) / 1e3
    if u.ndim > 1:
        u, f = u[:, 0], f[:, 0]
    ax_loop.plot(u, f, lw=0.7, color="tab:blue")
    ax_loop.set_xlabel("displacement [mm]")
    ax_loop.set_ylabel("horizontal force [kN]")
    ax_loop.set_title("hysteresis, the whole sequence", fontsize=10)
    ax_loop.grid(alpha=0.3)
    blocks = list(dict.fromkeys(c.block for c in result.cycles))
    index = np.arange(1, len(result.cycles) + 1)
    mu = np.array([c.mu for c in result.cycles])
    for k, block in enumerate(blocks):
        chosen = np.array([c.block == block for c in result.cycles])
        ax_mu.plot(index[chosen], mu[chosen], "o", color=f"C{k}", ms=5, label=block)
    ax_mu.axhline(result.nominal_mu, color="black", ls="--", lw=1.0,
                  label=f"nominal mu {result.nominal_mu:.4f} (mean at D_M)")
    ax_mu.set_xlabel("cycle of the sequence")
    ax_mu.set_ylabel("mu = EDC / (4 W D) [-]")
    ax_mu.set_title(f"lambda_test,max {result.lambda_test_max:.3f}, lambda_test,min "
                    f"{result.lambda_test_min:.3f}", fontsize=10)
    ax_mu.grid(alpha=0.3)
    twin = ax_mu.twinx()
    twin.plot(index, [c.peak_temperature for c in result.cycles], color="tab:red", lw=0.9,
              alpha=0.6, label="peak temperature")
    twin.set_ylabel("peak contact temperature [degC]", color="tab:red")
    handles, labels = ax_mu.get_legend_handles_labels()
    more, extra = twin.get_legend_handles_labels()
    ax_mu.legend(handles + more, labels + extra, loc="upper right", fontsize=7, ncol=2)
    title = title or (f"virtual prototype test (ASCE/SEI 7-16 17.8.2.2)\nD_M = "
                      f"{1e3 * result.D_M:.0f} mm, D_TM = {1e3 * result.D_TM:.0f} mm, T_M = "
                      f"{result.T_M:.3g} s, W = {result.W / 1e3:.4g} kN")
    return _save(plt, fig, path, title)
