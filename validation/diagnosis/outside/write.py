"""Write the outside panel: the measurement noise, the files and the labels.

:func:`write_panel` makes each case of :mod:`validation.diagnosis.outside.cases` with its
truth source (:mod:`validation.diagnosis.outside.sources`), adds the measurement noise
(:func:`measured`), writes the files and stores the labels with their design record
(:mod:`validation.diagnosis.outside.labels`).

Files
-----
``folder/case_NN/test_01.csv ...``: a header line, then time [s], displacement [m] (the
actuator's), force [N], and velocity [m/s] and axial_force [N] where the case has them.
``folder/case_NN/manifest.csv``: ``file,axial_load,initial_temperature,rest_before``, the tests
in run order (axial load empty when the file has the column; rest empty for the first test; a
rest of 86400 s is a night, the plates are cold). ``folder/case_NN/bearing.json``: what a user
tells the diagnosis (effective radius, ``Infinity`` for a flat slider, slider diameter,
baseline, ``without``, and the axial load when the files have no column). ``folder/labels.json``
holds the labels, ``folder/panel.json`` the seed. Case numbers are a seeded shuffle, so
neither a name nor a file tells the truth.

    python -m validation.diagnosis.outside FOLDER [--seed 2026] [--half tune|test] [--no-opensees]
"""

from __future__ import annotations

import argparse
import json
import time as _time
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np

from validation.diagnosis import independent as ind
from validation.diagnosis.outside.cases import (
    AXIAL_NOISE,
    CASES,
    HALVES,
    SLIDER,
    VELOCITY_NOISE,
    Case,
    axial_load,
    check_design,
    rest_before,
)
from validation.diagnosis.outside.labels import contributions, design_record
from validation.diagnosis.outside.sources import SOURCE_FUNCTIONS
from validation.diagnosis.tuning.write import opensees_available

__all__ = ["load_labels", "main", "measured", "opensees_available", "write_panel"]

# --- measurement and files -------------------------------------------------------------------


def measured(case: Case, clean: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """The columns a test machine writes: the clean channels plus measurement noise."""
    n = clean["time"].size
    out = {"time": clean["time"],
           "displacement": clean["displacement"] + rng.normal(0.0, case.displacement_noise, n),
           "force": clean["force"] + ind.noise(rng, n, case.noise * case.mu0 * case.weight,
                                               case.noise_kind, case.rho)}
    if case.velocity_column:
        out["velocity"] = clean["velocity"] + rng.normal(0.0, VELOCITY_NOISE, n)
    if case.axial_column:
        out["axial_force"] = clean["axial_force"] * (1.0 + rng.normal(0.0, AXIAL_NOISE, n))
    if case.drift:
        out["force"] = out["force"] + drift(n, case.drift * case.mu0 * case.weight,
                                            float(rng.uniform(0.0, 2.0 * np.pi)))
    return out


def drift(n: int, size: float, phase: float) -> np.ndarray:
    """A slow drift of a channel's zero over ``n`` samples: a ramp from -size to +size plus
    half a sine of amplitude ``size`` started at ``phase`` [rad] (in the channel's unit)."""
    x = np.linspace(0.0, 1.0, n)
    return size * (2.0 * x - 1.0) + size * np.sin(np.pi * x + phase)


def _write_case(case: Case, out: Path, rng: np.random.Generator) -> dict:
    """Write one case's files; return its contributions."""
    clean = SOURCE_FUNCTIONS[case.source](case, set(case.effects))
    shares = contributions(case, clean)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for k, (sine, data) in enumerate(zip(case.tests, clean, strict=True), start=1):
        columns = measured(case, data, rng)
        name = f"test_{k:02d}.csv"
        np.savetxt(out / name, np.column_stack(list(columns.values())), delimiter=",",
                   header=",".join(columns), comments="", fmt="%.10g")
        load = "" if case.axial_column else f"{axial_load(case, sine):.6f}"
        rest = rest_before(case, k - 1)
        rows.append(f"{name},{load},{sine.temperature:g},{'' if rest is None else f'{rest:g}'}")
    (out / "manifest.csv").write_text(
        "file,axial_load,initial_temperature,rest_before\n" + "\n".join(rows) + "\n")
    told = {"effective_radius": case.radius, "slider_diameter": SLIDER,
            "baseline": case.baseline, "without": list(case.without)}
    if not case.axial_column:
        told["axial_load"] = axial_load(case, case.tests[0])
    (out / "bearing.json").write_text(json.dumps(told, indent=2) + "\n")
    return shares


def write_panel(folder: str | Path, *, seed: int = 2026, opensees: bool | None = None,
                half: str | None = None, progress: bool = False,
                pairs: tuple[str, ...] | None = None, cases: tuple[Case, ...] | None = None,
                noise_offset: int = 0, variant: Callable[[Case], str] | None = None,
                panel_info: dict | None = None) -> Path:
    """Write the panel to ``folder`` (see the module docstring); return the labels file.

    Parameters
    ----------
    folder : str or Path
        Where to write (created; existing case folders are overwritten).
    seed : int
        Seed of the case numbering and of the measurement noise.
    opensees : bool or None
        Include the cases made by OpenSees; None: when openseespy can be imported.
    half : {"tune", "test"} or None
        Write one half only (None: both).
    progress : bool
        Print a line per case.
    pairs : tuple of str or None
        Write these scenario pairs only (``("P25", "P31")``; None: all). The case numbers and
        each case's noise stay those of the whole panel.
    cases : tuple of Case or None
        The cases to write (None: the panel's :data:`~.cases.CASES`, checked as tune/test
        pairs; e.g. the tune variants of :mod:`validation.diagnosis.variants_1d`, not
        checked).
    noise_offset : int
        Added to each case's index in the seed of its noise (``[seed, noise_offset +
        index]``), so that cases written apart from the panel draw noise of their own.
    variant : callable or None
        ``case -> text`` stored as the case's ``design["variant"]`` (what a tune variant is).
    panel_info : dict or None
        Keys to store in ``panel.json`` instead of ``half`` and ``opensees``.
    """
    if cases is None:
        check_design()
        cases = CASES
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    if opensees is None:
        opensees = opensees_available()
    order = np.random.default_rng(seed).permutation(len(cases))
    labels, start_all = {}, _time.perf_counter()
    for number, index in enumerate(order, start=1):
        case = cases[int(index)]
        if (case.source == "opensees" and not opensees) or (half and case.half != half):
            continue
        if pairs is not None and case.pair not in pairs:
            continue
        start = _time.perf_counter()
        name = f"case_{number:02d}"
        rng = np.random.default_rng([seed, noise_offset + int(index)])
        shares = _write_case(case, folder / name, rng)
        design = design_record(case, shares)
        if variant is not None:
            design["variant"] = variant(case)
        if not design["label_rule_met"]:
            warnings.warn(f"{name} ({case.pair} {case.half}) breaks the label rule: {shares}",
                          stacklevel=2)
        labels[name] = {"effects": list(case.effects), "truth": case.truth,
                        "source": case.source, "half": case.half, "design": design}
        if progress:
            pct = ", ".join(f"{k} {100 * v:.1f}%" for k, v in shares["contribution"].items())
            print(f"{name} {case.pair} {case.half:4s} {case.source:11s} "
                  f"{','.join(case.effects) or 'none':18s} {pct} "
                  f"({_time.perf_counter() - start:.1f} s)", flush=True)
    path = folder / "labels.json"
    path.write_text(json.dumps(dict(sorted(labels.items())), indent=1) + "\n")
    info = panel_info or {"half": half or "all", "opensees": bool(opensees)}
    (folder / "panel.json").write_text(json.dumps({
        "seed": seed, "cases": len(labels), **info,
        "seconds": round(_time.perf_counter() - start_all, 1)}, indent=2) + "\n")
    return path


def load_labels(folder: str | Path) -> dict:
    """The labels of a panel written by :func:`write_panel` (read them after diagnosing)."""
    return json.loads((Path(folder) / "labels.json").read_text())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m validation.diagnosis.outside",
                                     description="Write the outside panel of the diagnosis.")
    parser.add_argument("folder")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--half", choices=HALVES)
    parser.add_argument("--no-opensees", action="store_true")
    parser.add_argument("--pairs", help="comma-separated scenario pairs to write (P25,P31)")
    args = parser.parse_args(argv)
    pairs = None if not args.pairs else tuple(p.strip() for p in args.pairs.split(","))
    write_panel(args.folder, seed=args.seed, half=args.half,
                opensees=False if args.no_opensees else None, progress=True, pairs=pairs)
    return 0

