"""The figure of a bearing test: hysteresis loop and temperature history."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.plotting.base import PNG_OPTIONS, pyplot


def plot_bearing_test(result: Any, path: str | Path, *, title: str = "") -> Path:
    """Hysteresis loop (force against displacement) and temperature history of a bearing test.

    Parameters
    ----------
    result : BearingTestResult
        Output of :func:`isolator.testrig.run_test`.
    path : str or Path
        PNG file to write.
    title : str
        Figure title.
    """
    plt = pyplot()
    fig, (ax_loop, ax_temp) = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    ax_loop.plot(result.displacement * 1e3, result.force / 1e3, lw=0.8)
    ax_loop.set_xlabel("displacement [mm]")
    ax_loop.set_ylabel("horizontal force [kN]")
    ax_loop.set_title("hysteresis loop")
    ax_loop.grid(alpha=0.3)
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
    path = Path(path)
    fig.savefig(path, dpi=120, **PNG_OPTIONS)
    plt.close(fig)
    return path
