"""Tune variants of the bidirectional panel: new cases drawn at random from its declared ranges.

The panel's tune half (:mod:`validation.diagnosis.bidirectional.cases`) is 14 fixed designs;
once every tune half scores 14 of 14 it no longer shows what a different orbit, campaign or
nuisance does. :func:`draw_case` draws a new case from the ranges the panel's docstring
declares (and the tune designs use), never from the test half's designs:

- campaign: 2-3 tests in run order, rests of 300-1800 s; each test's orbit a circle (radius
  0.08-0.2 m, period 2-20 s), a figure-eight (0.08-0.2 by 0.05-0.2 m, period 2.5-10 s), a
  square (half side 0.06-0.12 m, 0.02-0.25 m/s) or an earthquake orbit (one of the shared
  pairs, peak 0.1-0.25 m); the cycles cut to about 8000 samples a test, at least one
  cycle (a slow circle at 500 Hz is longer, an earthquake orbit is its 20 s window);
- axial load: constant at 60 N/mm^2, different per test (30-90 N/mm^2), or varying in time by
  30-45 % over 1.5-2.5 s (then with an axial-force column);
- nuisance: sampling 100, 200, 250 or 500 Hz; force noise 0.5-1.2 % of mu0 W, white, AR(1)
  (rho 0.8-0.9) or band-limited; 16-bit converters or none; 2-3 spikes; a force channel stuck
  for 20 samples; a gain error of 2-3 % (either sign) on one axis's force or displacement
  channel; actuators through a second-order filter of 8-25 Hz (damping 0.4-0.7); a force
  lag of 0-1.5 samples; the transition rigid-plastic, elastic-plastic or smooth with u_y
  0.5-1 mm; a velocity column or not; gzip or not;
- effects, each drawn across what the truth supports: ``velocity`` the ``exp`` law (mu_slow /
  mu_fast 0.5-0.8, 15-50 mm/s) or the paper's Eq. 2, with a slow last test (a circle of
  period 8-20 s or a figure-eight of 8-10 s: the speed varies within it); ``pressure`` Eq. 1,
  with tests at different pressures (three, so that leave-one-test-out has two pressures
  to fit on) or a load varying in time; both together: three tests; ``heating`` Eq. 3-5;
  ``wear`` a step of 4-8 % a test or 10-25 % over the travel; ``backlash`` a play of 2-5 mm
  per axis (peak |u| kept below 0.16 m); ``lag`` 5-10 samples.

A case whose labelled effects do not all meet the panel's label rule (each one's RMS
contribution at least 3 % of the RMS force, :data:`~.cases.LABEL_MIN`) is drawn again. The
labels are written as the panel's (``effects``, ``truth``, ``source``, ``half`` = ``tune``,
``design``), with ``variant`` = True and the draw's seed, so that
``python -m validation.diagnosis.score FOLDER --half tune`` scores them; they are tune data.

    python -m validation.diagnosis.bidirectional FOLDER --variants N [--seed S]
        [--effects none|pressure,velocity|...]
"""

from __future__ import annotations

import json
import math
import time as _time
from pathlib import Path

import numpy as np

from validation.diagnosis.bidirectional.bearing import SpeedLaw, WearLaw
from validation.diagnosis.bidirectional.cases import EFFECTS, LABEL_MIN, Case, Run
from validation.diagnosis.bidirectional.orbits import PAIR_FILES
from validation.diagnosis.bidirectional.write import (
    SOURCE,
    _write_case,
    design_record,
)

__all__ = ["MAX_SAMPLES", "draw_case", "parse_effects", "write_variants"]

MAX_SAMPLES = 8000  # per test
SAMPLING = (100.0, 200.0, 250.0, 500.0)  # [Hz]
PLAY_PEAK = 0.16  # [m] peak |u| with a play (the truth's static assumption, cases.py)
_TRIES = 40


def parse_effects(text: str | None) -> tuple[str, ...] | None:
    """``none`` -> (), ``pressure,velocity`` -> ("pressure", "velocity"), None -> None (each
    variant draws its effects). Unknown names raise ValueError."""
    if text is None:
        return None
    if text.strip() == "none":
        return ()
    names = tuple(sorted({t.strip() for t in text.split(",") if t.strip()}))
    unknown = set(names) - set(EFFECTS)
    if unknown:
        raise ValueError(f"--effects: unknown effect(s) {sorted(unknown)}; known: "
                         f"{', '.join(EFFECTS)} or none")
    return names


def _orbit(rng: np.random.Generator, kind: str, dt: float, slow: bool, peak: float) -> tuple:
    """One orbit spec of ``kind`` (``slow``: at the low speeds a speed effect shows at),
    within ``peak`` [m] and about :data:`MAX_SAMPLES` samples."""
    budget = MAX_SAMPLES * dt  # [s]
    if kind == "circular":
        a = rng.uniform(0.08, min(0.2, peak))
        period = rng.uniform(8.0, 20.0) if slow else rng.uniform(2.0, 4.0)
        cycles = max(1.0, min(float(rng.integers(2, 5)), budget / period - 2.0))
        return ("circular", round(a, 3), round(period, 2), cycles)
    if kind == "eight":
        ax = rng.uniform(0.08, min(0.2, peak))
        ay = rng.uniform(0.05, min(0.2, peak))
        scale = min(1.0, peak / math.hypot(ax, ay))
        period = rng.uniform(8.0, 10.0) if slow else rng.uniform(2.5, 4.0)
        cycles = max(1.0, min(float(rng.integers(2, 4)), math.floor(budget / period)))
        return ("eight", round(ax * scale, 3), round(ay * scale, 3), round(period, 2), cycles)
    if kind == "square":
        a = rng.uniform(0.06, min(0.12, peak / math.sqrt(2.0)))
        speed = rng.uniform(0.02, 0.05) if slow else rng.uniform(0.1, 0.25)
        loop = 8.0 * a / speed
        cycles = int(max(1, min(2, math.floor((budget - 2.0 * a / speed) / loop))))
        return ("square", round(a, 3), round(speed, 3), cycles)
    pair = str(rng.choice(sorted(PAIR_FILES)))
    return ("quake", pair, round(rng.uniform(0.1, min(0.25, peak)), 3))


def _orbit_name(spec: tuple) -> str:
    """A short name of an orbit spec (without making the orbit)."""
    kind, *args = spec
    if kind == "circular":
        return f"circle {args[0]:g} m T={args[1]:g} s"
    if kind == "eight":
        return f"figure-eight {args[0]:g} x {args[1]:g} m T={args[2]:g} s"
    if kind == "square":
        return f"square {args[0]:g} m at {args[1]:g} m/s"
    return f"earthquake {args[0]} peak {args[1]:g} m"


def _campaign(rng: np.random.Generator, dt: float, effects: tuple[str, ...],
              axial: str) -> tuple[Run, ...]:
    n = int(rng.integers(2, 4))
    if ("pressure" in effects and axial == "per-test") or {"pressure", "velocity"} <= set(
            effects):
        n = 3  # leave-one-test-out needs two other tests to judge a per-test law
    peak = PLAY_PEAK if "backlash" in effects else 0.25
    kinds = list(rng.choice(["circular", "eight", "square", "quake"], size=n))
    slow = np.zeros(n, bool)
    if "velocity" in effects:  # at least one test at low speed, one at high
        kinds[-1] = str(rng.choice(["circular", "eight"]))  # the speed varies within it
        slow[-1] = True
        if kinds[0] == "quake" and n == 2:
            kinds[0] = "circular"
    elif rng.random() < 0.3:
        k = int(rng.integers(n))
        if kinds[k] != "quake":
            slow[k] = True
    pressures = [60.0] * n
    if axial == "per-test":
        pressures = list(rng.permutation([30.0, 45.0, 60.0, 75.0, 90.0])[:n])
    varying = rng.uniform(0.3, 0.45) if axial == "varying" else 0.0
    period = rng.uniform(1.5, 2.5)
    runs = []
    for k in range(n):
        orbit = _orbit(rng, str(kinds[k]), dt, bool(slow[k]), peak)
        rest = None if k == 0 else float(rng.choice([300.0, 600.0, 900.0, 1200.0, 1800.0]))
        runs.append(Run(orbit, float(pressures[k]), round(float(varying), 3),
                        round(float(period), 2), rest=rest))
    return tuple(runs)


def _effect_spec(rng: np.random.Generator, effect: str) -> object:
    if effect == "velocity":
        if rng.random() < 0.35:
            return {"speed": SpeedLaw("paper")}
        return {"speed": SpeedLaw("exp", ratio=round(rng.uniform(0.5, 0.8), 3),
                                  speed=round(rng.uniform(0.015, 0.05), 4))}
    if effect == "pressure":
        return {"pressure": True}
    if effect == "heating":
        return {"heating": True}
    if effect == "wear":
        if rng.random() < 0.5:
            return {"wear": WearLaw("step", round(rng.uniform(0.04, 0.08), 3))}
        return {"wear": WearLaw("travel", round(rng.uniform(0.1, 0.25), 3),
                                round(rng.uniform(8.0, 15.0), 1))}
    if effect == "backlash":
        return {"play": (round(rng.uniform(0.002, 0.005), 4),
                         round(rng.uniform(0.002, 0.005), 4))}
    if effect == "lag":
        return float(rng.integers(5, 11))
    raise ValueError(f"unknown effect {effect!r}")


def _draw_effects(rng: np.random.Generator) -> tuple[str, ...]:
    options = [(), (), ("velocity",), ("pressure",), ("heating",), ("wear",), ("backlash",),
               ("lag",), ("pressure", "velocity"), ("backlash", "heating")]
    return tuple(options[int(rng.integers(len(options)))])


def draw_case(rng: np.random.Generator, effects: tuple[str, ...] | None = None,
              name: str = "V") -> Case:
    """One tune-variant :class:`~.cases.Case` drawn from the panel's declared ranges (module
    docstring), with ``effects`` (None: drawn too). The label rule is not checked here
    (:func:`write_variants` draws again until it holds)."""
    if effects is None:
        effects = _draw_effects(rng)
    effects = tuple(sorted(effects))
    dt = 1.0 / float(rng.choice(SAMPLING))
    axial = str(rng.choice(["constant", "per-test", "varying"], p=[0.5, 0.3, 0.2]))
    if "pressure" in effects and axial == "constant":
        axial = str(rng.choice(["per-test", "varying"], p=[0.6, 0.4]))
    tests = _campaign(rng, dt, effects, axial)
    transition = str(rng.choice(["rigid-plastic", "elastic-plastic", "smooth"]))
    base: dict = {"transition": transition}
    if transition != "rigid-plastic":
        base["yield_displacement"] = round(float(rng.uniform(5.0e-4, 1.0e-3)), 6)
    spec = {"base": base, "effects": {e: _effect_spec(rng, e) for e in effects}}
    kind = str(rng.choice(["white", "ar1", "band"]))
    gain = None
    if rng.random() < 0.35:
        channel = str(rng.choice(["force_x", "force_y", "displacement_x", "displacement_y"]))
        gain = (channel, round(float(rng.choice([-1.0, 1.0]) * rng.uniform(0.02, 0.03)), 4))
    actuator = None
    if rng.random() < 0.4:
        actuator = (round(float(rng.uniform(8.0, 25.0)), 1),
                    round(float(rng.uniform(0.4, 0.7)), 2))
    nuisance = {
        "noise": round(float(rng.uniform(0.005, 0.012)), 4), "noise_kind": kind,
        "rho": round(float(rng.uniform(0.8, 0.9)), 3) if kind == "ar1" else 0.0,
        "lag_samples": round(float(rng.uniform(0.0, 1.5)), 2) if rng.random() < 0.6 else 0.0,
        "actuator": actuator, "quantise": bool(rng.random() < 0.35),
        "spikes": int(rng.integers(2, 4)) if rng.random() < 0.25 else 0,
        "stuck": 20 if rng.random() < 0.15 else 0, "gain": gain,
        "velocity_column": bool(rng.random() < 0.2),
        "axial_column": axial == "varying" or bool(rng.random() < 0.3),
        "gzip": bool(rng.random() < 0.2)}
    words = [", ".join(effects) or "no effect", transition,
             " / ".join(_orbit_name(r.orbit) for r in tests),
             f"{1.0 / dt:g} Hz", f"{kind} noise {100 * nuisance['noise']:.2g} %"]
    if gain:
        words.append(f"gain {gain[1]:+.3f} on {gain[0]}")
    if actuator:
        words.append(f"actuators {actuator[0]:g} Hz")
    if nuisance["lag_samples"]:
        words.append(f"lag {nuisance['lag_samples']:g} samples")
    if axial != "constant":
        words.append(f"axial load {axial}")
    return Case(name, effects, "tune", "tune variant: " + "; ".join(words), tests, spec, dt=dt,
                **nuisance)


def write_variant(folder: str | Path, number: int, *, seed: int,
                  effects: tuple[str, ...] | None = None) -> tuple[dict, Path]:
    """Write the tune variant numbered ``number`` of ``seed`` alone (the case
    :func:`write_variants` writes as ``case_NN`` among others) to ``folder``; return its
    labels and its case folder."""
    labels = json.loads(write_variants(folder, 1, seed=seed, effects=effects,
                                       first=number).read_text())
    name = f"case_{number:02d}"
    return labels[name], Path(folder) / name


def write_variants(folder: str | Path, count: int, *, seed: int = 1,
                   effects: tuple[str, ...] | None = None, first: int = 1,
                   progress: bool = False) -> Path:
    """Write ``count`` tune variants to ``folder`` as ``case_NN`` (from ``first``) with their
    labels (merged into an existing ``labels.json``); return the labels file.

    Parameters
    ----------
    folder : str or Path
        Where to write (created).
    count : int
        Number of variants.
    seed : int
        Seed of the draws and of the measurement noise (the variant written as case number
        m draws from ``default_rng([seed, m - 1])``, so one variant can be written again
        alone with ``first`` = m).
    effects : tuple of str or None
        The labelled effects of every variant (``()``: no effect; None: drawn per variant).
    first : int
        Number of the first case folder.
    progress : bool
        Print a line per case.
    """
    if count < 1:
        raise ValueError("count must be at least 1")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "labels.json"
    labels = json.loads(path.read_text()) if path.is_file() else {}
    start_all = _time.perf_counter()
    for k in range(count):
        index = first - 1 + k
        rng = np.random.default_rng([seed, index])
        name = f"case_{first + k:02d}"
        start = _time.perf_counter()
        for attempt in range(_TRIES):
            case = draw_case(rng, effects, name=f"V{seed}-{index}")
            for old in (folder / name).glob("test_*"):
                old.unlink()
            shares, clean = _write_case(case, folder / name, np.random.default_rng(
                [seed, index, attempt]))
            if all(v >= LABEL_MIN for v in shares["contribution"].values()):
                break
        else:
            raise RuntimeError(f"{name}: no draw in {_TRIES} met the label rule for {effects}")
        design = design_record(case, shares, clean)
        labels[name] = {"effects": sorted(case.effects), "truth": case.truth, "source": SOURCE,
                        "half": "tune", "variant": True, "variant_seed": [seed, index],
                        "draws": attempt + 1, "design": design}
        if progress:
            pct = ", ".join(f"{e} {100 * v:.1f}%" for e, v in shares["contribution"].items())
            print(f"{name} {','.join(case.effects) or 'none':18s} {pct} "
                  f"({_time.perf_counter() - start:.1f} s) {case.truth}", flush=True)
    path.write_text(json.dumps(dict(sorted(labels.items())), indent=1) + "\n")
    (folder / "panel.json").write_text(json.dumps({
        "panel": "bidirectional", "variants": True, "seed": seed, "cases": len(labels),
        "half": "tune", "effects": "drawn" if effects is None else (list(effects) or "none"),
        "seconds": round(_time.perf_counter() - start_all, 1)}, indent=2) + "\n")
    return path
