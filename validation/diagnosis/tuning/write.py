"""Write the tuning panel: the label rule, the measurement noise, the files and the labels.

:func:`write_panel` makes each case of :mod:`validation.diagnosis.tuning.cases` with its
truth source (:mod:`validation.diagnosis.tuning.sources`), measures each labelled effect's
share of the clean force (:func:`contributions`), adds the measurement noise
(:func:`measured`) and writes ``folder/case_NN/`` (``test_01.csv`` ..., ``manifest.csv``,
``bearing.json``), ``folder/labels.json`` and ``folder/panel.json`` (the seed). Case numbers
are a seeded shuffle.

    python -m validation.diagnosis.tuning FOLDER [--seed 2026] [--half tune|test]
"""

from __future__ import annotations

import argparse
import json
import time as _time
from pathlib import Path

import numpy as np

from validation.diagnosis.tuning import truths as ind
from validation.diagnosis.tuning.cases import CASES
from validation.diagnosis.tuning.sources import MU0, SLIDER, SOURCES, Case, W

__all__ = ["contributions", "main", "measured", "opensees_available", "write_panel"]


# --- writing --------------------------------------------------------------------------------


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


def contributions(case: Case, clean: list[dict]) -> dict[str, float]:
    """Each labelled effect's share of the clean force: RMS(with - without) / RMS(with)."""
    force = np.concatenate([c["force"] for c in clean])
    out = {}
    for effect in case.effects:
        without = SOURCES[case.source](case, set(case.effects) - {effect})
        other = np.concatenate([c["force"] for c in without])
        out[effect] = _rms(force - other) / _rms(force)
    return out


def measured(case: Case, clean: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """The columns a test machine writes: the clean histories plus measurement noise."""
    n = clean["time"].size
    sigma = case.noise * MU0 * W
    out = {"time": clean["time"],
           "displacement": clean["displacement"] + rng.normal(0.0, case.displacement_noise, n),
           "force": clean["force"] + ind.noise(rng, n, sigma, case.colour)}
    if case.velocity_column:
        out["velocity"] = clean["velocity"] + rng.normal(0.0, 2.0e-3, n)
    if case.axial_column:
        out["axial_force"] = clean["axial_force"] * (1.0 + rng.normal(0.0, 0.005, n))
    if case.drift:  # a ramp from -drift to +drift plus half a sine (instrument nuisance)
        x = np.linspace(0.0, 1.0, n)
        phase = float(rng.uniform(0.0, 2.0 * np.pi))
        size = case.drift * MU0 * W
        out["force"] = out["force"] + size * (2.0 * x - 1.0 + np.sin(np.pi * x + phase))
    return out


def opensees_available() -> bool:
    """Whether openseespy can be imported (its cases are left out otherwise)."""
    try:
        from structures.opensees.runtime import import_opensees

        import_opensees()
    except ImportError:
        return False
    return True


def write_panel(folder: str | Path, *, seed: int = 2026, half: str | None = None,
                opensees: bool | None = None, progress: bool = False) -> Path:
    """Write the cases (of one ``half``, or all) and the labels; returns the labels file."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    if opensees is None:
        opensees = opensees_available()
    order = np.random.default_rng(seed).permutation(len(CASES))
    labels = {}
    for index in order:
        case = CASES[index]
        number = int(np.flatnonzero(order == index)[0]) + 1
        if (half is not None and case.half != half) or (case.source == "opensees"
                                                        and not opensees):
            continue
        start = _time.perf_counter()
        name = f"case_{number:02d}"
        rng = np.random.default_rng([seed, int(index)])
        clean = SOURCES[case.source](case, set(case.effects))
        shares = contributions(case, clean)
        out = folder / name
        out.mkdir(exist_ok=True)
        rows = []
        for k, (test, data) in enumerate(zip(case.tests, clean, strict=True), start=1):
            columns = measured(case, data, rng)
            file = f"test_{k:02d}.csv"
            np.savetxt(out / file, np.column_stack(list(columns.values())), delimiter=",",
                       header=",".join(columns), comments="", fmt="%.10g")
            load = "" if case.axial_column else repr(test.load * W)
            rest = "" if test.rest is None else repr(test.rest)
            rows.append(f"{file},{load},20.0,{rest}")
        (out / "manifest.csv").write_text(
            "file,axial_load,initial_temperature,rest_before\n" + "\n".join(rows) + "\n")
        told = {"effective_radius": case.radius, "slider_diameter": SLIDER,
                "baseline": case.baseline, "without": list(case.without)}
        (out / "bearing.json").write_text(json.dumps(told, indent=2))
        labels[name] = {
            "effects": list(case.effects), "truth": case.truth, "source": case.source,
            "half": case.half, "baseline": case.baseline, "without": list(case.without),
            "design": {"tests": len(case.tests), "dt": case.dt, "noise": case.noise,
                       "colour": case.colour, "lag_samples": case.lag_samples,
                       "amplitudes": [t.amplitude for t in case.tests],
                       "velocity_column": case.velocity_column,
                       "axial_column": case.axial_column,
                       "transition": case.options.get("transition", "elastic-plastic"),
                       "contribution": shares}}
        if progress:
            print(f"{name}: {case.half:4s} {case.source:11s} {','.join(case.effects) or 'none':20s}"
                  f" {shares} ({_time.perf_counter() - start:.1f} s)", flush=True)
    path = folder / "labels.json"
    path.write_text(json.dumps(dict(sorted(labels.items())), indent=2))
    (folder / "panel.json").write_text(json.dumps({"seed": seed, "cases": len(labels),
                                                   "half": half or "all"}, indent=2))
    return path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m validation.diagnosis.tuning",
                                     description="Write the tuning panel of the diagnosis.")
    parser.add_argument("folder")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--half", choices=("tune", "test"))
    args = parser.parse_args(argv)
    write_panel(args.folder, seed=args.seed, half=args.half, progress=True)
    return 0

