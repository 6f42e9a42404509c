"""The report of a diagnosis in two directions (``dcfpb diagnose --report`` on orbits):
``diagnosis.json``, ``summary.md`` and ``loops.png`` (the force against the displacement
along x and along y, measured, baseline held out and the chosen model as fitted)."""

from __future__ import annotations

import json
from pathlib import Path


def write_report_2d(diagnosis, folder: str | Path, text: str) -> list[Path]:
    """Write the JSON summary, ``text`` (the printed summary) as Markdown and the loops of
    ``diagnosis`` (a :class:`~isolator.diagnosis.two_directions.Diagnosis2D`) to
    ``folder``; return the paths written."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    summary = diagnosis.to_json()
    paths = [folder / "summary.md", folder / "diagnosis.json", folder / "loops.png"]
    paths[1].write_text(json.dumps(summary, indent=2))
    d = diagnosis.data
    fig, axes = plt.subplots(2, len(d.campaign.tests), figsize=(4 * len(d.campaign.tests), 7),
                             squeeze=False)
    for k, rec in enumerate(d.campaign.tests):
        idx = d.test == k
        for j, axis in enumerate(("x", "y")):
            ax = axes[j, k]
            u = 1e3 * rec.displacement[:, j]
            ax.plot(u, 1e-3 * rec.force[:, j], lw=0.8, color="0.3", label="measured")
            ax.plot(u, 1e-3 * diagnosis.base_all.prediction[idx, j], lw=0.8,
                    label="baseline (held out)")
            if diagnosis.chosen is not None:
                ax.plot(u, 1e-3 * diagnosis.chosen.full[idx, j], lw=0.8, ls="--",
                        label="with " + " + ".join(diagnosis.chosen.model.names))
            ax.set_xlabel(f"displacement {axis} [mm]")
            ax.set_ylabel(f"force {axis} [kN]")
            ax.set_title(f"{rec.name}: {axis}", fontsize=9)
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(paths[2], dpi=110)
    plt.close(fig)
    paths[0].write_text("# Diagnosis of tests in two directions\n\n```\n" + text + "\n```\n\n"
                        "![loops](loops.png)\n")
    return paths
