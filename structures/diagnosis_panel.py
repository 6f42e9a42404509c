"""The validation panel of the diagnosis: cases made by truths it is not told about.

:func:`write_panel` writes every case of :data:`CASES` to ``folder/case_NN/`` as the CSV files
of a test campaign (``test_01.csv`` ...) and a ``bearing.json`` with what a user would type on
the command line (effective radius, slider diameter, axial load when there is no column,
baseline model); the labels, the true effects and the truth's description, go to
``folder/labels.json`` apart from the data, and only :func:`score_panel` reads them. The case
names and files say nothing about the truth.

Designs follow the paper's test campaigns, shortened for a CI budget (dt = 0.01 s, a few
cycles): sine tests at several amplitudes and velocities (one many-cycle test), a wind-speed
test (15 mm/s), tests at several pressures, tests with an axial load that varies in time, and
two-test campaigns (held out by alternate cycles). Noise: white, 1 % of the nominal friction
force on the force (0.5-1.5 % in some cases), 0.05 mm on the displacement, 2 mm/s on a
measured velocity (left out in some cases, then the diagnosis derives it), 0.5 % on a
measured axial force.

This module lives in ``structures`` because its OpenSees truths do; ``isolator`` never
imports it.
"""

from __future__ import annotations

import json
import math
import time as _time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from isolator.bearing import DCFPBearing
from isolator.factors import KumarFactors
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import MonitorLine
from isolator.protocols import sine, wind_cycles
from structures.diagnosis_truths import (
    Breakaway,
    Wear,
    element_truth,
    measured,
    opensees_truth,
)

SLIDER_DIAMETER = 0.3  # [m]
EFFECTIVE_RADIUS = 4.5  # [m] what the diagnosis is told
PRESSURE = 60.0e6  # [Pa]
AREA = math.pi * (0.5 * SLIDER_DIAMETER) ** 2
AXIAL_LOAD = PRESSURE * AREA  # [N] 4.24 MN
MU_CONSTANT = 0.041  # the paper's mu_0 for a 300 mm slider
DT = 0.01  # [s]
DISPLACEMENT_NOISE = 5.0e-5  # [m]
VELOCITY_NOISE = 2.0e-3  # [m/s]
AXIAL_NOISE = 0.005  # [-]

# (amplitude [m], period [s], cycles, pressure [Pa], axial variation [-]) per test; a period
# of 0 is a wind test at 15 mm/s.
CAMPAIGNS: dict[str, tuple[tuple[float, float, int, float, float], ...]] = {
    "sine set": ((0.1, 2.5, 3, PRESSURE, 0.0), (0.2, 2.5, 3, PRESSURE, 0.0),
                 (0.3, 3.0, 3, PRESSURE, 0.0), (0.15, 2.5, 8, PRESSURE, 0.0)),
    "velocity set": ((0.2, 2.5, 3, PRESSURE, 0.0), (0.2, 8.0, 2, PRESSURE, 0.0),
                     (0.05, 4.0, 3, PRESSURE, 0.0), (0.02, 0.0, 2, PRESSURE, 0.0)),
    "pressure set": ((0.15, 2.5, 3, 40e6, 0.0), (0.15, 2.5, 3, 80e6, 0.0),
                     (0.15, 2.5, 3, 20e6, 0.0), (0.15, 2.5, 3, 60e6, 0.0)),
    "varying axial load": ((0.15, 2.5, 3, PRESSURE, 0.35), (0.25, 3.0, 3, PRESSURE, 0.35),
                           (0.1, 2.5, 4, PRESSURE, 0.35)),
    "pair": ((0.2, 2.5, 4, PRESSURE, 0.0), (0.1, 2.5, 4, PRESSURE, 0.0)),
}


@dataclass(frozen=True)
class PanelCase:
    """One case: a truth, a campaign design and the baseline the user asks about.

    Attributes
    ----------
    effects : tuple of str
        The effects the truth has and the baseline lacks (the label; empty: none).
    truth : str
        What the truth is (kept with the labels).
    campaign : str
        Key of :data:`CAMPAIGNS`.
    friction : str
        ``"constant"``, ``"ptv:<dependency>,..."`` (our PTV model, paper factors, heated on
        the precise model's monitor line when temperature acts), ``"kumar:temperature"``.
    element : str or None
        OpenSees element (``"ptv"``, ``"velocity"``, ``"coulomb"``), None for ours.
    baseline, without : str, tuple of str
        The baseline the diagnosis is asked about.
    true_radius : float
        The truth's effective radius [m] (the diagnosis is told EFFECTIVE_RADIUS).
    breakaway, wear : bool
        Add the truths' breakaway or wear physics.
    force_noise : float
        Force noise over the nominal friction force [-].
    velocity_column : bool
        Whether the files have a measured velocity.
    """

    effects: tuple[str, ...]
    truth: str
    campaign: str
    friction: str = "constant"
    element: str | None = None
    baseline: str = "constant"
    without: tuple[str, ...] = ()
    true_radius: float = EFFECTIVE_RADIUS
    breakaway: bool = False
    wear: bool = False
    force_noise: float = 0.01
    velocity_column: bool = True


CASES: tuple[PanelCase, ...] = (
    PanelCase(("heating",), "precise model, temperature dependence only", "sine set",
              "ptv:temperature"),
    PanelCase(("velocity",), "PTV model, velocity dependence only (Eq. 2)", "velocity set",
              "ptv:velocity", velocity_column=False),
    PanelCase(("pressure",), "PTV model, pressure dependence only (Eq. 1)", "pressure set",
              "ptv:pressure"),
    PanelCase(("breakaway",), "constant friction with a 35 % breakaway peak fading "
              "quadratically over 10 mm", "sine set", breakaway=True),
    PanelCase(("wear",), "constant friction falling 20 % over the campaign as S^0.6",
              "sine set", wear=True, force_noise=0.005),
    PanelCase(("stiffness",), "constant friction, true R_eff 3.6 m (told 4.5 m)", "sine set",
              true_radius=3.6, force_noise=0.015),
    PanelCase(("heating",), "OpenSees FPBearingPTV, temperature dependence only (Kumar)",
              "pair", "kumar:temperature", element="ptv"),
    PanelCase(("velocity",), "OpenSees singleFPBearing, VelDependent (Eq. 2 mapped)",
              "velocity set", "ptv:velocity", element="velocity"),
    PanelCase(("pressure",), "PTV model, pressure dependence only, axial load varying in time",
              "varying axial load", "ptv:pressure"),
    PanelCase(("heating",), "full precise model", "sine set", "ptv:pressure,velocity,temperature",
              baseline="precise", without=("heating",)),
    PanelCase(("velocity",), "full precise model", "velocity set",
              "ptv:pressure,velocity,temperature", baseline="precise", without=("velocity",)),
    PanelCase(("heating", "velocity"), "precise model, temperature and velocity dependence",
              "velocity set", "ptv:velocity,temperature"),
    PanelCase(("pressure", "heating"), "precise model, pressure and temperature dependence, "
              "axial load varying in time", "varying axial load", "ptv:pressure,temperature"),
    PanelCase((), "constant friction", "sine set"),
    PanelCase((), "full precise model", "sine set", "ptv:pressure,velocity,temperature",
              baseline="precise"),
    PanelCase((), "constant friction, axial load varying in time", "varying axial load",
              velocity_column=False),
    PanelCase((), "OpenSees singleFPBearing, Coulomb friction", "pair", element="coulomb",
              force_noise=0.015),
)


def _friction(spec: str) -> ConstantFriction | PTVFriction:
    if spec == "constant":
        return ConstantFriction(MU_CONSTANT)
    family, _, names = spec.partition(":")
    dependencies = tuple(names.split(","))
    heating = MonitorLine() if "temperature" in dependencies else None
    if family == "kumar":
        return PTVFriction(0.075, heating=heating, factors=KumarFactors(),
                           dependencies=dependencies)
    return PTVFriction(0.075, heating=heating, dependencies=dependencies)


def _history(amplitude: float, period: float, cycles: int):
    if period == 0.0:
        return wind_cycles(amplitude, cycles=cycles, dt=DT)
    return sine(amplitude, period, cycles, DT)


def _tests(case: PanelCase, rng: np.random.Generator) -> list[dict[str, np.ndarray]]:
    """The measured columns of every test of a case."""
    design = CAMPAIGNS[case.campaign]
    histories = [_history(a, p, c) for a, p, c, _, _ in design]
    total = sum(float(np.sum(np.abs(np.diff(h.displacement)))) for h in histories)
    wear = Wear(campaign_travel=total) if case.wear else None
    breakaway = Breakaway() if case.breakaway else None
    friction = _friction(case.friction)
    tests, travel = [], 0.0
    for (_, _, _, pressure, variation), history in zip(design, histories, strict=True):
        load = pressure * AREA
        bearing = DCFPBearing(case.true_radius, SLIDER_DIAMETER, load, friction)
        if case.element == "ptv":
            from structures.opensees_bearing import fpbearingptv_equivalent

            bearing = replace(fpbearingptv_equivalent(replace(
                bearing, effective_radius=case.true_radius)), restoring="spherical")
        if case.element is not None:
            truth = opensees_truth(bearing, history, case.element)
        else:
            axial = None
            if variation:
                t = history.time
                axial = load * (1.0 + variation * np.sin(2.0 * np.pi * t / 1.7 + len(tests)))
            truth = element_truth(bearing, history, axial_load=axial, breakaway=breakaway,
                                  wear=wear, travel_before=travel)
        travel += float(np.sum(np.abs(np.diff(history.displacement))))
        varying = bool(variation) or any(a[3] != PRESSURE for a in design)
        tests.append(measured(
            truth, rng, force_noise=case.force_noise * MU_CONSTANT * AXIAL_LOAD,
            displacement_noise=DISPLACEMENT_NOISE,
            velocity_noise=VELOCITY_NOISE if case.velocity_column else None,
            axial_noise=AXIAL_NOISE if varying else None))
    return tests


def opensees_available() -> bool:
    """Whether openseespy can be imported (its cases are left out otherwise)."""
    try:
        from structures.opensees_runtime import import_opensees

        import_opensees()
    except ImportError:
        return False
    return True


def write_panel(folder: str | Path, *, seed: int = 2024,
                cases: tuple[PanelCase, ...] = CASES, opensees: bool | None = None) -> Path:
    """Write every case's data to ``folder/case_NN/`` and the labels to ``folder/labels.json``.

    Parameters
    ----------
    folder : str or Path
        Where to write.
    seed : int
        Seed of the measurement noise (each case draws from ``(seed, case number)``).
    cases : tuple of PanelCase
        The cases (default :data:`CASES`).
    opensees : bool or None
        Whether to include the cases made by OpenSees; None includes them when openseespy
        can be imported.

    Returns
    -------
    Path
        The labels file.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    if opensees is None:
        opensees = opensees_available()
    if not opensees:
        cases = tuple(c for c in cases if c.element is None)
    labels = {}
    for number, case in enumerate(cases, start=1):
        name = f"case_{number:02d}"
        rng = np.random.default_rng([seed, number])
        out = folder / name
        out.mkdir(exist_ok=True)
        tests = _tests(case, rng)
        for k, columns in enumerate(tests, start=1):
            header = ",".join(columns)
            np.savetxt(out / f"test_{k:02d}.csv", np.column_stack(list(columns.values())),
                       delimiter=",", header=header, comments="", fmt="%.10g")
        bearing = {"effective_radius": EFFECTIVE_RADIUS, "slider_diameter": SLIDER_DIAMETER,
                   "baseline": case.baseline, "without": list(case.without)}
        if "axial_force" not in tests[0]:
            bearing["axial_load"] = AXIAL_LOAD
        (out / "bearing.json").write_text(json.dumps(bearing, indent=2))
        labels[name] = {"effects": list(case.effects), "truth": case.truth,
                        "campaign": case.campaign,
                        "opensees": case.element, "baseline": case.baseline,
                        "without": list(case.without)}
    path = folder / "labels.json"
    path.write_text(json.dumps(labels, indent=2))
    return path


def load_case(folder: str | Path):
    """(campaign, baseline spec) of one case folder, from its data and bearing.json only."""
    from isolator.diagnosis import BaselineSpec, load_campaign

    folder = Path(folder)
    info = json.loads((folder / "bearing.json").read_text())
    campaign = load_campaign(sorted(folder.glob("test_*.csv")),
                             effective_radius=info["effective_radius"],
                             slider_diameter=info["slider_diameter"],
                             axial_load=info.get("axial_load"))
    return campaign, BaselineSpec(info["baseline"], tuple(info["without"]))


def score_panel(folder: str | Path, *, leave_one_out: bool = True) -> list[dict]:
    """Diagnose every case, then read the labels and score (one dict per case).

    Each dict has the case, its true effects, the verdict, the ranking, the rank (from 1) of
    each true effect, the held-out gap before and after and the shrink of the chosen effects,
    and with ``leave_one_out`` the verdict with each true effect withheld from the library.
    """
    from isolator.diagnosis import diagnose, reselect

    folder = Path(folder)
    results = {}
    for case_dir in sorted(p for p in folder.iterdir() if p.is_dir()):
        start = _time.perf_counter()
        campaign, spec = load_case(case_dir)
        results[case_dir.name] = (diagnose(campaign, spec), _time.perf_counter() - start)
    labels = json.loads((folder / "labels.json").read_text())  # read only after diagnosing
    scores = []
    for name, (d, wall) in results.items():
        truth = labels[name]["effects"]
        summary = d.to_json()
        ranking = [e["name"] for e in summary["effects"]]
        chosen = summary["chosen"]
        row = {"case": name, "truth": labels[name]["truth"], "effects": truth,
               "baseline": d.baseline.spec.label, "verdict": d.verdict, "ranking": ranking,
               "rank": {e: ranking.index(e) + 1 for e in truth},
               "gap_before": d.gap_before, "gap_after": d.gap_after,
               "noise": d.noise_nrmse, "shrink": chosen["shrink"] if chosen else 0.0,
               "wall_time": wall, "loo": []}
        if leave_one_out:
            for effect in truth:
                loo = reselect(d, (effect,))
                loo_chosen = loo.to_json()["chosen"]
                row["loo"].append({"withheld": effect, "verdict": loo.verdict,
                                   "shrink": loo_chosen["shrink"] if loo_chosen else 0.0})
        scores.append(row)
    return scores
