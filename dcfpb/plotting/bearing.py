"""The figure of a bearing test: hysteresis loop(s) and temperature history."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.plotting.base import PNG_OPTIONS, finish, pyplot


def plot_bearing_test(result: Any, path: str | Path, *, title: str = "") -> Path:
    """Hysteresis loop (force against displacement; one per direction for an orbit) and the
    temperature history of a bearing test, written to the PNG file ``path``.

    ``result`` is the `BearingTestResult` of :func:`isolator.testrig.run_test` or of an orbit;
    ``title`` the figure's title.
    """
    plt = pyplot()
    axes_names = ("x", "y")[:result.dimension]
    fig, axes = plt.subplots(1, 1 + result.dimension, figsize=(5.5 * (1 + result.dimension), 4.2),
                             constrained_layout=True)
    for axis, (ax_loop, name) in enumerate(zip(axes[:-1], axes_names, strict=True)):
        where = "" if result.dimension == 1 else f" {name}"
        u = result.displacement if result.dimension == 1 else result.displacement[:, axis]
        f = result.force if result.dimension == 1 else result.force[:, axis]
        ax_loop.plot(u * 1e3, f / 1e3, lw=0.8)
        ax_loop.set_xlabel(f"displacement{where} [mm]")
        ax_loop.set_ylabel(f"horizontal force{where} [kN]")
        ax_loop.set_title("hysteresis loop" + ("" if result.dimension == 1 else f", {name}"))
        ax_loop.grid(alpha=0.3)
    ax_temp = axes[-1]
    ax_temp.plot(result.time, result.temperature, lw=0.9, color="tab:red")
    ax_temp.set_xlabel("time [s]")
    ax_temp.set_ylabel("contact temperature [degC]")
    ax_temp.set_title("temperature of the contact area")
    ax_temp.grid(alpha=0.3)
    ax_mu = ax_temp.twinx()
    ax_mu.plot(result.time, result.mu, lw=0.6, color="tab:gray", alpha=0.7)
    ax_mu.set_ylabel("friction coefficient [-]", color="tab:gray")
    if title:
        fig.suptitle(title)
    return finish(fig, path, **PNG_OPTIONS)
