"""A readable report of a diagnosis: a markdown summary, the JSON summary and plots.

:func:`write_report` writes ``summary.md`` (the data, the baseline, the gap and where it lies,
every candidate, the verdict, the shrink with the fitted parameters, what remains
unexplained), ``diagnosis.json`` (:meth:`isolator.diagnosis.Diagnosis.to_json`) and the plots
``loops.png``, ``residual_breakdown.png``, ``candidates.png``, ``cycle_errors.png`` and
``residual_history.png``; of tests in two directions, ``diagnosis.json``, ``summary.md`` (the
printed summary), ``loops.png`` (force against displacement along x and along y) and
``candidates.png``. matplotlib is imported by the plotting functions only.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from dcfpb.common.files import atomic_output
from isolator.diagnosis.summary import Diagnosis, effect_parameters
from isolator.diagnosis.where import DIMENSIONS

_MAX_LOOPS = 9


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _write_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (a failed write leaves an earlier file whole)."""
    with atomic_output(path) as temporary:
        temporary.write_text(text)


def _save(fig, path: Path) -> None:
    """Save a PNG figure atomically."""
    with atomic_output(path) as temporary:
        fig.savefig(temporary, format="png", dpi=110)


def write_report(diagnosis: Diagnosis, folder: str | Path, text: str = "") -> list[Path]:
    """Write the summary, the JSON and the plots of ``diagnosis`` to ``folder``; return the
    paths written. ``text`` is the printed summary, the Markdown of a diagnosis of tests in
    two directions (:class:`~isolator.diagnosis.two_directions.Diagnosis2D`)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    summary = diagnosis.to_json()
    if summary.get("dimension") == 2:
        return _write_report_2d(diagnosis, summary, folder, text)
    written = [folder / "diagnosis.json"]
    _write_text(written[0], json.dumps(summary, indent=2))
    written += [_loops(diagnosis, folder / "loops.png"),
                _breakdown(diagnosis, folder / "residual_breakdown.png"),
                _candidates(diagnosis, summary, folder / "candidates.png"),
                _cycle_errors(diagnosis, folder / "cycle_errors.png"),
                _history(diagnosis, folder / "residual_history.png")]
    md = folder / "summary.md"
    _write_text(md, markdown(diagnosis, summary, [p.name for p in written[1:]]))
    return [md, *written]


def _write_report_2d(diagnosis, summary: dict, folder: Path, text: str) -> list[Path]:
    """The report of tests in two directions (:func:`write_report`)."""
    paths = [folder / "summary.md", folder / "diagnosis.json", folder / "loops.png",
             folder / "candidates.png"]
    _write_text(paths[1], json.dumps(summary, indent=2))
    plt = _pyplot()
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
    _save(fig, paths[2])
    plt.close(fig)
    _candidates(diagnosis, summary, paths[3])
    _write_text(paths[0], "# Diagnosis of tests in two directions\n\n```\n" + text
                + "\n```\n\n![loops](loops.png)\n\n![candidates](candidates.png)\n")
    return paths


def _predictions(d: Diagnosis) -> dict[str, np.ndarray]:
    """Force at every sample: the baseline held out, and the chosen model as fitted."""
    from isolator.diagnosis.pipeline import _full_prediction

    out = {f"baseline ({d.baseline.spec.label}, held out)":
           d.problem.all_baseline.prediction}
    chosen = d.selection.chosen
    if chosen is not None:
        names = [n for n in d.verdict if n != "unexplained"] or ["the effects tried"]
        out["with " + " + ".join(names) + " (fitted)"] = _full_prediction(d.problem, chosen)
    return out


def _loops(d: Diagnosis, path: Path) -> Path:
    plt = _pyplot()
    f = d.problem.features
    tests = d.campaign.tests[:_MAX_LOOPS]
    cols = min(3, len(tests))
    rows = -(-len(tests) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.6 * cols, 3.6 * rows), squeeze=False,
                             constrained_layout=True)
    for k, (ax, rec) in enumerate(zip(axes.flat, tests, strict=False)):
        idx = f.test == k
        ax.plot(1e3 * f.displacement[idx], 1e-3 * f.force[idx], lw=0.6, color="black",
                label="measured")
        for (label, pred), colour in zip(_predictions(d).items(), ("tab:blue", "tab:red"),
                                         strict=False):
            ax.plot(1e3 * f.displacement[idx], 1e-3 * pred[idx], lw=0.7, color=colour,
                    label=label)
        ax.set_title(rec.name, fontsize=8)
        ax.set_xlabel("displacement [mm]")
        ax.set_ylabel("force [kN]")
        ax.grid(alpha=0.3)
    for ax in axes.flat[len(tests):]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=7)
    _save(fig, path)
    plt.close(fig)
    return path


def _breakdown(d: Diagnosis, path: Path) -> Path:
    plt = _pyplot()
    dims = [dim for dim in DIMENSIONS if len(d.where.breakdowns.get(dim, [])) > 1]
    fig, axes = plt.subplots(len(dims), 1, figsize=(9, 2.2 * len(dims)), squeeze=False,
                             constrained_layout=True)
    for ax, dim in zip(axes[:, 0], dims, strict=True):
        bands = d.where.breakdowns[dim]
        x = np.arange(len(bands))
        ax.bar(x - 0.2, [100 * b.energy_share for b in bands], 0.4, label="residual energy")
        ax.bar(x + 0.2, [100 * b.sample_share for b in bands], 0.4, label="samples",
               color="tab:gray")
        ax.set_xticks(x, [b.label for b in bands], fontsize=7, rotation=15)
        ax.set_ylabel(f"by {dim} [%]", fontsize=8)
        ax.grid(alpha=0.3, axis="y")
    axes[0, 0].legend(fontsize=7)
    axes[0, 0].set_title(d.where.statement, fontsize=8)
    _save(fig, path)
    plt.close(fig)
    return path


def _candidates(d: Diagnosis, summary: dict, path: Path) -> Path:
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(8, 3.6), constrained_layout=True)
    rows = [e for e in summary["effects"] if e.get("gap_after") is not None]
    names = [e["name"] for e in rows]
    colours = ["tab:red" if e["role"].startswith(("selected", "named")) else
               "tab:orange" if e.get("earns_keep") else "tab:gray" for e in rows]
    ax.bar(names, [e["gap_after"] for e in rows], color=colours)
    ax.axhline(summary["gap"]["value"], color="tab:blue", lw=1.2, label="baseline")
    ax.axhline(summary["gap"]["noise"], color="black", ls="--", lw=1.0, label="noise")
    if summary["chosen"]:
        ax.axhline(summary["chosen"]["gap_after"], color="tab:red", ls=":", lw=1.2,
                   label="chosen: " + " + ".join(summary["chosen"]["names"]))
    ax.set_ylabel("held-out force NRMSE [-]")
    ax.set_title("verdict: " + ", ".join(summary["verdict"]), fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, axis="y")
    _save(fig, path)
    plt.close(fig)
    return path


def _cycle_errors(d: Diagnosis, path: Path) -> Path:
    plt = _pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.4), constrained_layout=True)
    sets = [("baseline", d.cycles_before)]
    if d.cycles_after is not None:
        names = [n for n in d.verdict if n != "unexplained"] or ["the effects tried"]
        sets.append(("with " + " + ".join(names), d.cycles_after))
    for ax, quantity in zip(axes, ("EDC", "Keff"), strict=True):
        for label, errors in sets:
            values = [100 * r[f"{quantity}_error"] for r in errors.rows]
            ax.plot(np.arange(1, len(values) + 1), values, "o-", ms=3, lw=0.8, label=label)
        ax.axhline(0.0, color="black", lw=0.6)
        ax.set_xlabel("cycle (all tests in order)")
        ax.set_ylabel(f"{quantity} error, held out [%]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    _save(fig, path)
    plt.close(fig)
    return path


def _history(d: Diagnosis, path: Path) -> Path:
    plt = _pyplot()
    f = d.problem.features
    fig, ax = plt.subplots(figsize=(11, 3.4), constrained_layout=True)
    sample = np.arange(len(f))
    for label, pred in _predictions(d).items():
        ax.plot(sample, 1e-3 * (f.force - pred), lw=0.4, label=label)
    for k in range(1, len(d.campaign.tests)):
        ax.axvline(int(np.argmax(f.test == k)), color="gray", lw=0.5)
    ax.set_xlabel("sample (tests one after the other)")
    ax.set_ylabel("measured - predicted [kN]")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    _save(fig, path)
    plt.close(fig)
    return path


def _value(value, stderr: float | None, unit: str) -> str:
    if isinstance(value, list | tuple):  # a flexible form's curve
        return "[" + ", ".join(f"{x:.3g}" for x in value) + "]"
    unit = "" if unit == "-" else f" {unit}"
    if stderr is None or not np.isfinite(stderr) or stderr == 0.0:
        return f"{value:.4g}{unit}"
    return f"{value:.4g} ± {stderr:.2g}{unit}"


def markdown(d: Diagnosis, summary: dict, figures: list[str]) -> str:
    """The markdown summary (see the module docstring)."""
    gap = summary["gap"]
    lines = [
        "# Sim-to-real gap diagnosis", "",
        f"**Verdict: {', '.join(summary['verdict'])}**", "",
        "## Data and baseline", "",
        f"- {summary['tests']} test(s), {summary['samples']} samples; effective radius "
        f"{d.campaign.effective_radius:g} m, slider diameter {d.campaign.slider_diameter:g} m.",
        f"- Baseline: `{summary['baseline']['model']}`, calibrated on all data: "
        + ", ".join(f"{k} = {v:.4g}" for k, v in summary["baseline"]["parameters"].items())
        + ".",
        f"- Held out: {gap['holdout']}. Every error below is on held-out data.", "",
        "## The gap and where it lies", "",
        f"- Force NRMSE of the calibrated baseline: **{gap['value']:.4f}** "
        f"(measurement noise alone: {gap['noise']:.4f}).",
    ]
    cycles = gap.get("cycles") or {}
    if cycles.get("cycles"):
        lines.append("- Per-cycle RMS relative errors over " f"{cycles['cycles']} cycles: "
                     + ", ".join(f"{q} {100 * cycles[f'{q}_rms_error']:.1f} %"
                                 for q in ("EDC", "Keff", "beta_eff", "Fmax", "Fmin")
                                 if cycles.get(f"{q}_rms_error") is not None) + ".")
    lines.append(f"- Judged on the {gap['phase']}; over all samples the baseline's NRMSE is "
                 f"{gap['all_samples']:.4f}.")
    if summary.get("transition"):
        lines.append(f"- {summary['transition']['statement']}")
    lag = summary["lag"]
    lines.append(f"- Channel lag (force behind displacement): {1e3 * lag['seconds']:.3g} ms "
                 f"({lag['samples']:.2f} samples){' - named as an effect' if lag['named'] else ''}"
                 ".")
    lines += [f"- {summary['where']['statement']}", "", "## Candidate effects (best first)", "",
              "| effect | held-out NRMSE | shrink | z | closes | role | parameters |",
              "| --- | --- | --- | --- | --- | --- | --- |"]
    for e in summary["effects"]:
        if e.get("gap_after") is None:
            lines.append(f"| {e['name']} | - | - | - | - | {e['role']} | |")
            continue
        params = "; ".join(f"{k} = {_value(v, e['stderr'][k], e['units'][k])}"
                           for k, v in e["parameters"].items())
        lines.append(f"| {e['name']} | {e['gap_after']:.4f} | {100 * e['shrink']:.0f} % | "
                     f"{e['held_out_z']:.1f} | {100 * e['explained_excess']:.0f} % | "
                     f"{e['role']} | {params} |")
    chosen = summary["chosen"]
    if chosen is not None and summary["verdict"] != ["unexplained"]:
        lines += ["", "## How far it shrinks", "",
                  f"With {' + '.join(chosen['names'])}: force NRMSE {chosen['gap_before']:.4f}"
                  f" -> **{chosen['gap_after']:.4f}** (shrink {100 * chosen['shrink']:.0f} %);"
                  f" it closes {100 * chosen['explained_excess']:.0f} % of the gap above the "
                  "noise."]
        for q in ("EDC", "Keff"):
            a, b = chosen[f"{q}_rms_error_before"], chosen[f"{q}_rms_error_after"]
            if a is not None and b is not None:
                lines.append(f"- {q} per-cycle RMS error: {100 * a:.1f} % -> {100 * b:.1f} %.")
        heat = chosen.get("baseline_heat")
        if heat and heat["follows_named_laws"]:
            lines.append(f"- {heat['statement']} Without it the NRMSE after would be "
                         f"{heat['gap_after_without']:.4f} (shrink "
                         f"{100 * heat['shrink_without']:.0f} %).")
        elif heat and heat["laws"]:
            lines.append(f"- {heat['statement']}")
        lines += ["", "Fitted parameters (standard errors from the Jacobian, inflated for "
                  "serial correlation):", ""]
        for effect, params in effect_parameters(d, d.selection.chosen).items():
            lines.append(f"- {effect}: " + "; ".join(
                f"{k} = {_value(*v)}" for k, v in params.items()))
        if chosen.get("form"):
            flexible = [k for k, v in chosen["form"].items() if v == "flexible"]
            lines.append("- Form reported: " + ", ".join(
                f"{k} {v}" for k, v in chosen["form"].items()) + "." + (
                f" For {', '.join(flexible)} the paper's form does not fit; the fitted monotone "
                "curve is given instead." if flexible else ""))
        for effect, value in chosen.get("confidence", {}).items():
            if value is not None:
                lines.append(f"- Confidence in {effect}: {100 * value:.0f} % of block "
                             "resamples keep it.")
        for effect, ranges in chosen.get("intervals", {}).items():
            lines.append(f"- {effect}, 5-95 % bootstrap intervals: " + "; ".join(
                f"{k} in [{lo:.4g}, {hi:.4g}]" for k, (lo, hi) in ranges.items()))
    if summary["unexplained"]:
        lines += ["", "## What remains unexplained", "",
                  f"- {summary['unexplained']['statement']}"]
        lines += [f"- It looks like {text}." for text in summary["unexplained"]["looks_like"]]
    if summary["excluded"]:
        lines += ["", f"Effects withheld from the library: {', '.join(summary['excluded'])}."]
    lines += ["", "## Figures", ""] + [f"![{name}]({name})" for name in figures]
    return "\n".join(lines) + "\n"
