"""The diagnosis's validation panel: 42 cases from three truth sources, labels kept apart.

Each *scenario* (a set of true effects) is made twice, once for each half: the **tune** half
is the only one the thresholds are chosen on (``tune.py``), the **test** half is the one
the scores are reported on (``score.py``). The two cases of a pair differ in their truth
source and in nuisance: amplitude (0.05-0.4 m), sampling (100-500 Hz), white or coloured
noise (0.3-1.5 % of the nominal friction force), a channel lag of up to 1.5 samples, the
pre-sliding transition (rigid-plastic, elastic-plastic 0.1-2 mm, smooth Bouc-Wen), campaigns
of one to four files, a velocity and an axial-force column or not.

The records and the truth sources are in :mod:`validation.diagnosis.cases_sources` (their
names are importable from here too); this module holds the case list and writes the panel.

Truth sources:

- ``independent``: :mod:`validation.diagnosis.plain_truths` (numpy only, written from
  the paper and physics; shares no code with the package);
- ``opensees``: OpenSees singleFPBearing (Coulomb, VelDependent) and FPBearingPTV through
  :func:`structures.opensees.bearing.run_opensees_test`;
- ``package``: our own element (:func:`structures.diagnosis.truths.element_truth`).

Label rule: an effect is labelled when its own contribution to the clean force (the truth
with it less the truth without it) has an RMS of at least 3 % of the RMS force; physics left
unlabelled contributes at most 1 % (both are computed and stored with the labels, in
``design``). A channel lag of up to 1.5 samples and the transition's shape are nuisance,
never labelled.

Written to ``folder/case_NN/``: ``test_01.csv`` ... (time, displacement, force, and velocity,
axial_force where the case has them), ``manifest.csv`` (the files in run order with the
axial load where there is no column, the initial temperature and the rest before each test)
and ``bearing.json`` (what a user would type: effective radius, slider diameter, baseline,
``without``, axial load). ``folder/labels.json`` holds the labels; ``folder/panel.json`` the
seed. Case numbers are shuffled so that neither the number nor the files tell the truth.

    python -m validation.diagnosis.cases FOLDER [--seed 2026] [--half tune|test]
"""

from __future__ import annotations

import argparse
import json
import math
import time as _time
from pathlib import Path

import numpy as np

from validation.diagnosis import plain_truths as ind
from validation.diagnosis.cases_sources import (
    AREA,
    LABEL_MIN,
    MU0,
    RADIUS,
    SLIDER,
    SOURCES,
    UNLABELLED_MAX,
    Case,
    Test,
    W,
    independent,
    opensees,
    package,
)

__all__ = [
    "AREA",
    "BIG",
    "CASES",
    "DAMPER",
    "EXP_VELOCITY",
    "HEAT_SET",
    "LABEL_MIN",
    "MU0",
    "ONE",
    "PAIR",
    "PRESSURE_SET",
    "RADIUS",
    "SINE_SET",
    "SLIDER",
    "SOURCES",
    "UNLABELLED_MAX",
    "VARYING",
    "VARYING_STRONG",
    "VELOCITY_SET",
    "WEAR_SET",
    "Case",
    "Test",
    "W",
    "contributions",
    "independent",
    "main",
    "measured",
    "opensees",
    "opensees_available",
    "package",
    "write_panel",
]


# --- the cases ------------------------------------------------------------------------------

SINE_SET = (Test(0.1, 2.5, 3), Test(0.2, 3.0, 3), Test(0.3, 3.0, 3), Test(0.15, 2.5, 6))
VELOCITY_SET = (Test(0.2, 2.5, 3), Test(0.2, 8.0, 2), Test(0.05, 4.0, 3), Test(0.02, 8.0, 2))
PRESSURE_SET = (Test(0.15, 2.5, 3, 40 / 60), Test(0.15, 2.5, 3, 80 / 60),
                Test(0.15, 2.5, 3, 20 / 60), Test(0.15, 2.5, 3, 1.0))
VARYING = (Test(0.15, 2.5, 3, 1.0, 0.35), Test(0.25, 3.0, 3, 1.0, 0.35),
           Test(0.1, 2.5, 4, 1.0, 0.35))
VARYING_STRONG = (Test(0.1, 2.5, 3, 1.0, 0.5), Test(0.15, 3.0, 3, 1.0, 0.5),
                  Test(0.08, 2.5, 4, 1.0, 0.5))
HEAT_SET = (Test(0.2, 3.0, 4), Test(0.3, 3.0, 3, rest=600.0), Test(0.15, 2.5, 5, rest=600.0))
PAIR = (Test(0.25, 3.0, 3), Test(0.15, 2.5, 3))
ONE = (Test(0.25, 3.0, 3),)
DAMPER = (Test(0.025, 2.0, 4), Test(0.035, 4.0, 3))
BIG = (Test(0.4, 4.0, 3), Test(0.3, 3.5, 3))
WEAR_SET = (Test(0.2, 3.0, 3), Test(0.2, 3.0, 3, rest=1800.0), Test(0.15, 2.5, 3, rest=1800.0),
            Test(0.25, 3.0, 3, rest=1800.0))

EXP_VELOCITY = ("exponential", 0.45, 0.03)
CASES: tuple[Case, ...] = (
    # --- no unmodelled effect (12) ---
    Case((), "tune", "package", "constant friction, elastic-plastic u_y 0.5 mm", SINE_SET,
         package),
    Case((), "test", "package", "constant friction, u_y 0.5 mm, coloured noise, lag 0.7 "
         "samples, 200 Hz", PAIR, package, dt=0.005, noise=0.005, colour=0.9, lag_samples=0.7),
    Case((), "tune", "independent", "rigid-plastic constant friction (the paper's form)", ONE,
         independent, options={"transition": "rigid-plastic"}),
    Case((), "test", "independent", "rigid-plastic constant friction, 500 Hz, 1.5 % noise",
         (Test(0.2, 3.0, 2),), independent, dt=0.002, noise=0.015,
         options={"transition": "rigid-plastic"}),
    Case((), "tune", "opensees", "OpenSees singleFPBearing Coulomb", PAIR, opensees,
         options={"element": "coulomb"}),
    Case((), "test", "opensees", "OpenSees singleFPBearing Coulomb, 200 Hz, lag 1 sample",
         (Test(0.2, 3.0, 3), Test(0.1, 2.5, 3), Test(0.3, 3.0, 2)), opensees, dt=0.005,
         noise=0.008, lag_samples=1.0, options={"element": "coulomb"}),
    Case((), "tune", "independent", "smooth (Bouc-Wen) transition u_y 1 mm, lag 1.2 samples, "
         "coloured noise", PAIR, independent, colour=0.8, lag_samples=1.2,
         options={"transition": "smooth", "u_y": 1e-3}),
    Case((), "test", "independent", "elastic-plastic u_y 1.5 mm, lag 1.5 samples, 0.3 % "
         "noise, no velocity column", (Test(0.05, 2.0, 4), Test(0.1, 2.5, 3)), independent,
         noise=0.003, lag_samples=1.5, velocity_column=False, options={"u_y": 1.5e-3}),
    Case((), "tune", "package", "full precise model, told precise", SINE_SET, package,
         baseline="precise", options={"base_dependencies": ("pressure", "velocity",
                                                            "temperature")}),
    Case((), "test", "package", "full precise model, told precise, 2 tests, 0.5 % noise",
         PAIR, package, noise=0.005, baseline="precise",
         options={"base_dependencies": ("pressure", "velocity", "temperature")}),
    Case((), "tune", "independent", "constant friction, axial load varying in time", VARYING,
         independent, axial_column=True, velocity_column=False),
    Case((), "test", "package", "constant friction, axial load varying in time, u_y 0.2 mm",
         VARYING[:2], package, axial_column=True, options={"u_y": 2e-4}),
    # --- one effect (22) ---
    Case(("heating",), "tune", "independent", "temperature dependence (Eq. 3-5), rests of 600 s",
         HEAT_SET, independent, options={}),
    Case(("heating",), "test", "opensees", "OpenSees FPBearingPTV, temperature (Kumar)", PAIR,
         opensees, options={"element": "ptv"}),
    Case(("velocity",), "tune", "independent", "velocity: mu_slow/mu_fast 0.55, v_c 30 mm/s",
         VELOCITY_SET, independent, velocity_column=False,
         options={"velocity": EXP_VELOCITY}),
    Case(("velocity",), "test", "opensees", "OpenSees singleFPBearing VelDependent (Eq. 2)",
         VELOCITY_SET, opensees, options={"element": "velocity"}),
    Case(("pressure",), "tune", "independent", "pressure (Eq. 1), one load per test",
         PRESSURE_SET, independent, options={}),
    Case(("pressure",), "test", "package", "pressure (Eq. 1), axial load varying in time",
         VARYING, package, axial_column=True, options={}),
    Case(("breakaway",), "tune", "independent", "breakaway 40 % fading linearly over 8 mm",
         SINE_SET[:3], independent, options={"breakaway": (0.4, 0.008)}),
    Case(("breakaway",), "test", "package", "breakaway 35 % fading quadratically over 10 mm",
         PAIR, package, noise=0.006),
    Case(("wear",), "tune", "independent", "friction drops 8 % from test to test", WEAR_SET,
         independent, noise=0.005, options={"wear_drop": -0.08}),
    Case(("wear",), "test", "package", "friction falls 20 % over the campaign as S^0.6",
         SINE_SET, package, noise=0.005),
    Case(("stiffness",), "tune", "independent", "true R_eff 3.6 m, told 4.5 m", SINE_SET[:3],
         independent, options={"true_radius": 3.6}),
    Case(("stiffness",), "test", "opensees", "OpenSees Coulomb, true R_eff 3.6 m, told 4.5",
         PAIR, opensees, options={"element": "coulomb", "true_radius": 3.6}),
    Case(("asymmetry",), "tune", "independent", "mu(+)/mu(-) = 1.35", PAIR, independent,
         options={"direction": 0.15}),
    Case(("asymmetry",), "test", "independent", "mu(+)/mu(-) = 0.79, smooth transition",
         SINE_SET[:2], independent, options={"direction": -0.12, "transition": "smooth",
                                             "u_y": 6e-4}),
    Case(("backlash",), "tune", "independent", "4 mm play, flat slider (R = inf)", DAMPER,
         independent, dt=0.004, radius=math.inf, options={"backlash": 0.004, "u_y": 2e-4}),
    Case(("backlash",), "test", "independent", "3 mm play on a pendulum, 200 Hz",
         (Test(0.05, 2.0, 3), Test(0.1, 2.5, 3)), independent, dt=0.005,
         options={"backlash": 0.003, "u_y": 3e-4}),
    Case(("geometry",), "tune", "independent", "spherical surface, R 1.2 m, 0.4 m", BIG,
         independent, radius=1.2, options={}),
    Case(("geometry",), "test", "independent", "spherical surface, R 1.2 m, rigid-plastic",
         (Test(0.35, 3.5, 3),), independent, radius=1.2, noise=0.006,
         options={"transition": "rigid-plastic"}),
    Case(("lag",), "tune", "independent", "force channel 5 samples late (50 ms)", PAIR,
         independent, lag_samples=5.0),
    Case(("lag",), "test", "package", "force channel 8 samples late at 200 Hz (40 ms)",
         PAIR, package, dt=0.005, lag_samples=8.0),
    Case(("heating",), "tune", "package", "full precise model, told precise without heating",
         SINE_SET, package, baseline="precise", without=("heating",),
         options={"base_dependencies": ("pressure", "velocity")}),
    Case(("heating",), "test", "package", "full precise model, told precise without heating,"
         " 2 tests", PAIR, package, baseline="precise", without=("heating",), noise=0.006,
         options={"base_dependencies": ("pressure", "velocity")}),
    # --- two effects (8) ---
    Case(("heating", "velocity"), "tune", "independent", "temperature and velocity (Eq. 2-5)",
         VELOCITY_SET[:3], independent, options={"velocity": ("paper",)}),
    Case(("heating", "velocity"), "test", "package", "precise model: temperature and velocity",
         VELOCITY_SET, package),
    Case(("pressure", "heating"), "tune", "independent", "pressure and temperature, axial "
         "load varying in time by 50 %", VARYING_STRONG, independent, axial_column=True),
    Case(("pressure", "heating"), "test", "package", "pressure and temperature, axial load "
         "varying in time by 50 %", VARYING_STRONG, package, axial_column=True),
    Case(("backlash", "asymmetry"), "tune", "independent", "3 mm play and mu(+)/mu(-) = 0.7 "
         "(a friction damper)", DAMPER, independent, dt=0.004, radius=math.inf,
         options={"backlash": 0.003, "direction": -0.18, "u_y": 2e-4}),
    Case(("backlash", "asymmetry"), "test", "independent", "4 mm play and mu(+)/mu(-) = 1.4 "
         "on a pendulum", (Test(0.08, 2.5, 3), Test(0.12, 3.0, 3)), independent, dt=0.005,
         options={"backlash": 0.004, "direction": 0.17, "u_y": 3e-4}),
    Case(("wear", "breakaway"), "tune", "independent", "drop of 8 % per test and a 40 % "
         "breakaway over 8 mm", WEAR_SET, independent, noise=0.006,
         options={"wear_drop": -0.08, "breakaway": (0.4, 0.008)}),
    Case(("wear", "breakaway"), "test", "package", "wear S^0.6 (-20 %) and breakaway 35 %",
         SINE_SET, package, noise=0.006),
)


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
    parser = argparse.ArgumentParser(description="Write the diagnosis's validation panel.")
    parser.add_argument("folder")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--half", choices=("tune", "test"))
    args = parser.parse_args(argv)
    write_panel(args.folder, seed=args.seed, half=args.half, progress=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
