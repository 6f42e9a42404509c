"""Write the bidirectional panel: the truth of each case, its labels, the measurement, the files.

:func:`write_panel` makes each case of :mod:`validation.diagnosis.bidirectional.cases` with the
bidirectional truth (:func:`truth`), measures the label rule's shares (:func:`contributions`),
adds the measurement chain (:func:`validation.diagnosis.bidirectional.rig.measure`) and writes
the files. The labels are stored apart from the data.

Label rule
----------
As in the one-direction outside panel: an effect is labelled when its own contribution to the
clean force, the truth with it less the truth without it (everything else equal, no noise),
has an RMS of at least 3 % of the RMS force over the campaign. In two directions the RMS is
that of the force vector's norm, sqrt(mean(F_x^2 + F_y^2)). A lag is labelled only from 5
samples up. Nuisance (the measurement chain, the actuators' dynamics, a lag of up to 1.5
samples, the transition's shape) is never labelled. The share left after a least-squares
rescale of the friction force of the truth without the effect (what a calibrated mu absorbs)
is stored as ``design.contribution_refit``.

Files (the agreed two-direction format)
---------------------------------------
``folder/case_NN/test_01.csv`` (or ``.csv.gz``) ...: a header line, then ``time`` [s],
``displacement_x``, ``displacement_y`` [m] (the actuators' relative displacement),
``force_x``, ``force_y`` [N] (the horizontal force on the bearing), and where the case has
them ``axial_force`` [N], ``velocity_x``, ``velocity_y`` [m/s].
``folder/case_NN/manifest.csv``: ``file,axial_load,initial_temperature,rest_before``, the tests
in run order (axial load empty when the file has the column, rest empty for the first test,
86400 s a night). ``folder/case_NN/bearing.json``: what a user tells the diagnosis
(``effective_radius``, ``slider_diameter``, ``baseline``, ``without``, and ``axial_load`` when
the files have no column). ``folder/labels.json``: per case ``effects``, ``truth``,
``source``, ``half``, ``design``. ``folder/panel.json``: the seed. Case numbers are a seeded
shuffle.

    python -m validation.diagnosis.bidirectional FOLDER [--seed 2026] [--half tune|test]
    python -m validation.diagnosis.bidirectional FOLDER --variants N [--seed S] [--effects E]
"""

from __future__ import annotations

import argparse
import functools
import gzip
import io
import json
import math
import time as _time
import warnings
from pathlib import Path

import numpy as np

from validation.diagnosis.bidirectional.bearing import Bearing2D
from validation.diagnosis.bidirectional.cases import (
    CASES,
    DISPLACEMENT_RANGE,
    FORCE_RANGE,
    HALVES,
    LABEL_MIN,
    LAG_LABEL_MIN,
    SLIDER,
    Case,
    Run,
    axial_load,
    check_design,
    rest_before,
)
from validation.diagnosis.bidirectional.orbits import Orbit, circular, earthquake, figure_eight
from validation.diagnosis.bidirectional.orbits import square as square_orbit
from validation.diagnosis.bidirectional.rig import Measurement, Rig, Test2D, measure, simulate

__all__ = ["COLUMNS", "contributions", "load_labels", "main", "make_tests", "truth",
           "write_panel"]

COLUMNS = ("time", "displacement_x", "displacement_y", "force_x", "force_y", "axial_force",
           "velocity_x", "velocity_y")
SOURCE = "bidirectional"
VELOCITY_NOISE = 2.0e-3  # [m/s]
AXIAL_NOISE = 0.003  # [-]


# --- a case's truth ------------------------------------------------------------------------


@functools.lru_cache(maxsize=64)
def make_orbit(spec: tuple) -> Orbit:
    """The orbit of a :class:`~validation.diagnosis.bidirectional.cases.Run`'s spec."""
    kind, *args = spec
    if kind == "circular":
        return circular(*args)
    if kind == "eight":
        return figure_eight(*args)
    if kind == "square":
        return square_orbit(*args)
    if kind == "quake":
        return earthquake(*args)
    raise ValueError(f"unknown orbit {kind!r}")


def _axial(case: Case, run: Run):
    load = axial_load(case, run)
    if not run.varying:
        return load
    return lambda t: load * (1.0 + run.varying * np.sin(2.0 * math.pi * t / run.varying_period))


def make_tests(case: Case) -> list[Test2D]:
    """The campaign's tests in run order."""
    return [Test2D(make_orbit(run.orbit), case.dt, _axial(case, run), run.temperature,
                   rest_before(case, k)) for k, run in enumerate(case.tests)]


def truth(case: Case, effects: set[str]) -> list[dict]:
    """The clean channels of ``case`` with the labelled ``effects`` switched on (and the
    case's nuisance rig: its actuators and its lag of up to 1.5 samples)."""
    kwargs = {"weight": case.weight, "radius": case.radius, "slider_diameter": SLIDER,
              "mu0": case.mu0, **case.spec.get("base", {})}
    lag = case.lag_samples
    for effect in effects:
        extra = case.spec.get("effects", {}).get(effect)
        if effect == "lag":
            lag += float(extra)
        else:
            kwargs.update(extra)
    rig = Rig(lag=lag * case.dt, actuator_frequency=case.actuator[0] if case.actuator else None,
              actuator_damping=case.actuator[1] if case.actuator else 0.7)
    return simulate(Bearing2D(**kwargs), make_tests(case), rig)


# --- labels --------------------------------------------------------------------------------


def _rms(vectors: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.sum(np.square(vectors), axis=-1))))


def _concat(runs: list[dict], key: str) -> np.ndarray:
    return np.concatenate([r[key] for r in runs])


def contributions(case: Case, clean: list[dict]) -> dict:
    """Each labelled effect's share of the RMS force (raw and after a refit of the friction
    level of the truth without it)."""
    force = _concat(clean, "force")
    total = _rms(force)
    raw, refit = {}, {}
    for effect in case.effects:
        other = truth(case, set(case.effects) - {effect})
        f_other = _concat(other, "force")
        raw[effect] = _rms(force - f_other) / total
        part = f_other - _concat(other, "restoring")
        target = force - _concat(other, "restoring")
        scale = float(np.sum(part * target) / np.sum(part * part)) if np.any(part) else 0.0
        refit[effect] = _rms(target - scale * part) / total
    return {"contribution": raw, "contribution_refit": refit, "unlabelled": {}}


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if hasattr(value, "__dataclass_fields__"):
        return {"type": type(value).__name__, **{k: _jsonable(getattr(value, k))
                                                 for k in value.__dataclass_fields__}}
    if isinstance(value, float) and math.isinf(value):
        return "inf"
    return value


def design_record(case: Case, shares: dict, clean: list[dict]) -> dict:
    """The ``design`` stored with a case's labels (its tests, nuisance, truth, shares)."""
    base = case.spec.get("base", {})
    transition = base.get("transition", "elastic-plastic")
    lag_ok = "lag" not in case.effects or case.spec["effects"]["lag"] >= LAG_LABEL_MIN
    return {
        "pair": case.pair,
        "tests": [{"orbit": make_orbit(r.orbit).name, "orbit_spec": list(r.orbit),
                   "pressure_N_mm2": r.pressure, "axial_variation": r.varying,
                   "rest_before": rest_before(case, k), "initial_temperature": r.temperature,
                   "samples": int(c["time"].size),
                   "peak_displacement_m": float(np.max(np.hypot(*c["displacement"].T))),
                   "peak_speed_m_s": float(np.max(np.hypot(*c["velocity"].T))),
                   "peak_temperature_degC": float(np.max(c["temperature"]))}
                  for k, (r, c) in enumerate(zip(case.tests, clean, strict=True))],
        "dt": case.dt, "samples": int(sum(c["time"].size for c in clean)),
        "nuisance": {"force_noise_fraction_of_mu0_W": case.noise, "kind": case.noise_kind,
                     "rho": case.rho, "displacement_noise_m": case.displacement_noise,
                     "lag_samples": case.lag_samples, "actuator_hz_damping": case.actuator,
                     "quantised_16_bit": case.quantise, "spikes": case.spikes,
                     "stuck_samples": case.stuck, "gain": case.gain,
                     "velocity_m_s": VELOCITY_NOISE if case.velocity_column else None,
                     "axial_relative": AXIAL_NOISE if case.axial_column else None},
        "transition": transition,
        "yield_displacement": None if transition == "rigid-plastic" else base.get(
            "yield_displacement", 5.0e-4),
        "velocity_column": case.velocity_column, "axial_column": case.axial_column,
        "baseline": case.baseline, "without": list(case.without),
        "told_radius": case.radius, "weight": case.weight, "mu0": case.mu0,
        "truth_parameters": _jsonable(case.spec),
        **shares,
        "label_rule_met": bool(all(v >= LABEL_MIN for v in shares["contribution"].values())
                               and lag_ok),
    }


# --- files -----------------------------------------------------------------------------------


def chain(case: Case) -> Measurement:
    """The case's measurement chain."""
    return Measurement(
        force_noise=case.noise * case.mu0 * case.weight, kind=case.noise_kind, rho=case.rho,
        displacement_noise=case.displacement_noise,
        velocity_noise=VELOCITY_NOISE if case.velocity_column else None,
        axial_noise=AXIAL_NOISE if case.axial_column else None,
        force_range=FORCE_RANGE if case.quantise else None,
        displacement_range=DISPLACEMENT_RANGE if case.quantise else None,
        spikes=case.spikes, stuck=case.stuck, gain=case.gain)


def write_table(path: Path, columns: dict[str, np.ndarray]) -> None:
    """A CSV (gzip-compressed when ``path`` ends in ``.gz``) with a header line."""
    names = [c for c in COLUMNS if c in columns]
    buffer = io.StringIO()
    np.savetxt(buffer, np.column_stack([columns[c] for c in names]), delimiter=",",
               header=",".join(names), comments="", fmt="%.10g")
    text = buffer.getvalue()
    if path.suffix == ".gz":
        path.write_bytes(gzip.compress(text.encode(), mtime=0))
    else:
        path.write_text(text)


def _write_case(case: Case, out: Path, rng: np.random.Generator) -> tuple[dict, list[dict]]:
    clean = truth(case, set(case.effects))
    shares = contributions(case, clean)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    measurement = chain(case)
    for k, (run, data) in enumerate(zip(case.tests, clean, strict=True), start=1):
        columns = measure(data, measurement, rng)
        name = f"test_{k:02d}.csv" + (".gz" if case.gzip else "")
        write_table(out / name, columns)
        load = "" if case.axial_column else f"{axial_load(case, run):.6f}"
        rest = rest_before(case, k - 1)
        rows.append(f"{name},{load},{run.temperature:g},{'' if rest is None else f'{rest:g}'}")
    (out / "manifest.csv").write_text(
        "file,axial_load,initial_temperature,rest_before\n" + "\n".join(rows) + "\n")
    told = {"effective_radius": case.radius, "slider_diameter": SLIDER,
            "baseline": case.baseline, "without": list(case.without)}
    if not case.axial_column:
        told["axial_load"] = axial_load(case, case.tests[0])
    (out / "bearing.json").write_text(json.dumps(told, indent=2) + "\n")
    return shares, clean


def write_panel(folder: str | Path, *, seed: int = 2026, half: str | None = None,
                pairs: tuple[str, ...] | None = None, progress: bool = False,
                cases: tuple[Case, ...] | None = None) -> Path:
    """Write the bidirectional panel to ``folder``; return the labels file.

    Parameters
    ----------
    folder : str or Path
        Where to write (created; existing case folders are overwritten).
    seed : int
        Seed of the case numbering and of the measurement noise.
    half : {"tune", "test"} or None
        Write one half only (None: both).
    pairs : tuple of str or None
        Write these scenario pairs only (e.g. ``("B01", "B10")``; None: all).
    progress : bool
        Print a line per case.
    cases : tuple of Case or None
        The cases to write (None: the panel's :data:`~.cases.CASES`, checked as tune/test
        pairs; e.g. the tune variants of :data:`~.play_variants.PLAY_VARIANTS`, not checked).
    """
    if cases is None:
        check_design()
        cases = CASES
    if half is not None and half not in HALVES:
        raise ValueError(f"half must be one of {HALVES}, not {half!r}")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    order = np.random.default_rng(seed).permutation(len(cases))
    labels, start_all = {}, _time.perf_counter()
    for number, index in enumerate(order, start=1):
        case = cases[int(index)]
        if (half and case.half != half) or (pairs and case.pair not in pairs):
            continue
        start = _time.perf_counter()
        name = f"case_{number:02d}"
        shares, clean = _write_case(case, folder / name, np.random.default_rng([seed,
                                                                                 int(index)]))
        design = design_record(case, shares, clean)
        if not design["label_rule_met"]:
            warnings.warn(f"{name} ({case.pair} {case.half}) breaks the label rule: {shares}",
                          stacklevel=2)
        labels[name] = {"effects": sorted(case.effects), "truth": case.truth,
                        "source": SOURCE, "half": case.half, "design": design}
        if progress:
            pct = ", ".join(f"{k} {100 * v:.1f}%" for k, v in shares["contribution"].items())
            print(f"{name} {case.pair} {case.half:4s} {','.join(case.effects) or 'none':18s} "
                  f"{pct} ({_time.perf_counter() - start:.1f} s)", flush=True)
    path = folder / "labels.json"
    path.write_text(json.dumps(dict(sorted(labels.items())), indent=1) + "\n")
    (folder / "panel.json").write_text(json.dumps({
        "panel": "bidirectional", "seed": seed, "cases": len(labels), "half": half or "all",
        "pairs": list(pairs) if pairs else "all",
        "cases_of": "panel" if cases is CASES else "variants",
        "seconds": round(_time.perf_counter() - start_all, 1)}, indent=2) + "\n")
    return path


def load_labels(folder: str | Path) -> dict:
    """The labels of a panel written by :func:`write_panel` (read them after diagnosing)."""
    return json.loads((Path(folder) / "labels.json").read_text())


def main(argv: list[str] | None = None) -> int:
    """``python -m validation.diagnosis.bidirectional``: write the panel or run the checks."""
    parser = argparse.ArgumentParser(prog="python -m validation.diagnosis.bidirectional",
                                     description="Write the bidirectional panel of the "
                                                 "diagnosis, or run its truth's self-checks.")
    parser.add_argument("folder", nargs="?")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--half", choices=HALVES)
    parser.add_argument("--pairs", nargs="+", help="scenario pairs to write (e.g. B01 B10)")
    parser.add_argument("--checks", action="store_true", help="run the self-checks")
    parser.add_argument("--variants", type=int, metavar="N",
                        help="write N tune variants drawn from the panel's declared ranges "
                             "instead of the panel (validation.diagnosis.bidirectional.variants)")
    parser.add_argument("--effects", help="the variants' labelled effects: none, or a comma-"
                        "separated set (pressure,velocity); default: drawn per variant")
    parser.add_argument("--first", type=int, default=1,
                        help="number of the variants' first case folder (default 1)")
    parser.add_argument("--play-variants", action="store_true",
                        help="write the tune variants of the plays (unequal per axis, "
                             "validation.diagnosis.bidirectional.play_variants) instead of the "
                             "panel; all labelled tune")
    args = parser.parse_args(argv)
    if args.checks or args.folder is None:
        from validation.diagnosis.bidirectional.checks import TOLERANCES, checks

        errors = checks()
        failed = [k for k, v in errors.items() if not v <= TOLERANCES[k]]
        if failed:
            print("FAILED: " + ", ".join(failed))
            return 1
        if args.folder is None:
            return 0
    if args.variants is not None:
        from validation.diagnosis.bidirectional.variants import parse_effects, write_variants

        if args.half == "test" or args.pairs:
            parser.error("--variants writes tune variants only (no --half test, no --pairs)")
        try:
            effects = parse_effects(args.effects)
        except ValueError as error:
            parser.error(str(error))
        write_variants(args.folder, args.variants, seed=args.seed, effects=effects,
                       first=args.first, progress=True)
        return 0
    if args.effects is not None:
        parser.error("--effects goes with --variants")
    variants = None
    if args.play_variants:
        from validation.diagnosis.bidirectional.play_variants import PLAY_VARIANTS

        variants = PLAY_VARIANTS
    write_panel(args.folder, seed=args.seed, half=args.half,
                pairs=tuple(args.pairs) if args.pairs else None, progress=True,
                cases=variants)
    return 0
