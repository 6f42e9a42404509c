"""The outside panel's label rule: each effect's share of the clean force, and the design
record stored with the labels.

An effect is labelled when its own contribution to the clean force, the truth with it less the
truth without it (everything else equal, no noise), has an RMS of at least 3 % of the RMS
force over the campaign (``design.contribution``). Physics the truth has but the label and the
told baseline do not contributes at most 1 % (``design.unlabelled``). The share left after
refitting the friction level of the truth without the effect (what a calibrated mu could
absorb) is stored too (``design.contribution_refit``).
"""

from __future__ import annotations

import math

import numpy as np

from validation.diagnosis.outside.cases import (
    AXIAL_NOISE,
    LABEL_MIN,
    SLIDER,
    UNLABELLED_MAX,
    VELOCITY_NOISE,
    Case,
    axial_load,
    rest_before,
)
from validation.diagnosis.outside.sources import (
    SOURCE_FUNCTIONS,
    independent,
    independent_truth_bearing,
)

# --- contributions ---------------------------------------------------------------------------


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


def _concat(runs: list[dict], key: str) -> np.ndarray:
    return np.concatenate([r[key] for r in runs])


def _refit_share(force: np.ndarray, other: np.ndarray, restoring: np.ndarray) -> float:
    """RMS of ``force`` less the truth without the effect whose friction part is rescaled by
    least squares (what a calibrated friction level absorbs), over RMS(force)."""
    part = other - restoring
    target = force - restoring
    scale = float(np.dot(part, target) / np.dot(part, part)) if np.any(part) else 0.0
    return _rms(target - scale * part) / _rms(force)


def contributions(case: Case, clean: list[dict]) -> dict:
    """Each labelled effect's share (raw and after a refit) and the unlabelled shares."""
    run = SOURCE_FUNCTIONS[case.source]
    force = _concat(clean, "force")
    total = _rms(force)
    raw, refit = {}, {}
    for effect in case.effects:
        other = run(case, set(case.effects) - {effect})
        raw[effect] = _rms(force - _concat(other, "force")) / total
        refit[effect] = _refit_share(force, _concat(other, "force"), _concat(other, "restoring"))
    unlabelled = {}
    for name in {n for c in clean for n in c.get("unlabelled", {})}:
        unlabelled[name] = _rms(np.concatenate([c["unlabelled"][name] for c in clean])) / total
    if case.source == "independent" and case.baseline == "precise":
        unlabelled.update(_precise_difference(case))
    return {"contribution": raw, "contribution_refit": refit, "unlabelled": unlabelled}


def _precise_difference(case: Case) -> dict:
    """The independent precise model against the package's on the same tests (cold starts,
    all of the truth's effects on): physics the two differ in is left unlabelled. Also the
    share of the heat carried over the rests (physics of the told precise model)."""
    from isolator.bearing import DCFPBearing
    from isolator.friction import PTVFriction
    from isolator.heating import MonitorLine, ThermalProperties
    from isolator.testrig import run_test

    mine = independent(case, set(case.effects), cold=True)
    truth = independent_truth_bearing(case, set(case.effects))
    deps = tuple(name for name, on in (("pressure", truth.pressure), ("velocity", truth.velocity),
                                       ("temperature", truth.temperature)) if on)
    u_y = truth.yield_displacement
    diffs = []
    for s, out in zip(case.tests, mine, strict=True):
        friction = PTVFriction(truth.mu0, dependencies=deps,
                               heating=MonitorLine() if "temperature" in deps else None,
                               thermal=ThermalProperties(initial_temperature=s.temperature))
        bearing = DCFPBearing(case.radius, SLIDER, axial_load(case, s), friction,
                              yield_displacement=u_y)
        theirs = run_test(bearing, out["time"], out["displacement"], out["velocity"]).force
        diffs.append(out["force"] - theirs)
    total = _rms(_concat(mine, "force"))
    carried = _concat(independent(case, set(case.effects)), "force") - _concat(mine, "force")
    return {"independent precise vs package precise (cold starts)":
            _rms(np.concatenate(diffs)) / total,
            "heat carried over the rests (part of the told precise model)":
            _rms(carried) / total}


def design_record(case: Case, shares: dict) -> dict:
    """The ``design`` stored with a case's labels: its tests, nuisance, told baseline, truth
    parameters, the ``shares`` of :func:`contributions` and whether the label rule holds."""
    base = case.spec.get("base", {})
    transition = base.get("transition", "elastic-plastic")
    if case.source != "independent":
        transition = "elastic-plastic"
    u_y = None if transition == "rigid-plastic" else base.get(
        "yield_displacement", case.spec.get("u_y", 5.0e-4))
    return {
        "pair": case.pair,
        "tests": [{"amplitude": s.amplitude, "period": s.period, "cycles": s.cycles,
                   "pressure_N_mm2": s.pressure, "axial_variation": s.varying,
                   "rest_before": rest_before(case, k), "initial_temperature": s.temperature}
                  for k, s in enumerate(case.tests)],
        "amplitudes": [s.amplitude for s in case.tests],
        "dt": case.dt, "samples": case.samples,
        "noise": {"force_fraction_of_mu0_W": case.noise, "kind": case.noise_kind,
                  "rho": case.rho, "displacement_m": case.displacement_noise,
                  "velocity_m_s": VELOCITY_NOISE if case.velocity_column else None,
                  "axial_relative": AXIAL_NOISE if case.axial_column else None},
        "lag_samples": case.lag_samples,
        "transition": transition, "yield_displacement": u_y,
        "velocity_column": case.velocity_column, "axial_column": case.axial_column,
        "baseline": case.baseline, "without": list(case.without),
        "told_radius": case.radius, "weight": case.weight, "mu0": case.mu0,
        "truth_parameters": _jsonable(case.spec),
        **shares,
        "label_rule_met": (all(v >= LABEL_MIN for v in shares["contribution"].values())
                           and all(v <= UNLABELLED_MAX for k, v in shares["unlabelled"].items()
                                   if not k.startswith("heat carried"))),
    }


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
