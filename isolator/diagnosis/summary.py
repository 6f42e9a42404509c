"""What the diagnosis found (:class:`Diagnosis`) and its summary as plain JSON types, the
documented output of ``dcfpb diagnose --json``.

Keys: ``baseline`` (model and calibrated parameters), ``gap`` (``metric`` = "force_nrmse",
``value`` on held-out data, the noise on the same scale, the hold-out scheme and the per-cycle
characteristic errors), ``where`` (the statement and the breakdowns), ``effects`` (every
candidate, best first, with ``gap_after``, ``shrink`` = 1 - after / before, ``parameters``,
their ``stderr`` and ``units``, and its ``role``), ``chosen`` (the combination named in the
verdict, with the gap and the per-cycle EDC and Keff errors before and after; for a baseline
that heats, ``baseline_heat``: whether its temperature follows the named laws' friction power,
which the chosen model then carries), ``verdict`` and
``unexplained`` (where a real gap remains and what it looks like).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from isolator.diagnosis.baseline import BaselineFit, nuisance_edges
from isolator.diagnosis.data import Campaign
from isolator.diagnosis.decision import IMPLIED_HEAT, Problem
from isolator.diagnosis.selection import Assessment, Selection, Workspace
from isolator.diagnosis.transition import NUISANCE_LAG_SAMPLES, TransitionFinding
from isolator.diagnosis.where import QUANTITIES, CycleErrors, Where


def _number(x: float) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def _where(where: Where) -> dict:
    return {
        "statement": where.statement,
        "energy_share": where.energy_share,
        "sample_share": where.sample_share,
        "focus": [{"by": dim, "bands": label} for dim, label in where.focus],
        "near_reversal": where.near_reversal,
        "breakdowns": {dim: [{"band": b.label, "energy_share": b.energy_share,
                              "sample_share": b.sample_share, "rms": b.rms, "bias": b.bias}
                             for b in bands] for dim, bands in where.breakdowns.items()},
    }


def _cycles(errors: CycleErrors | None) -> dict | None:
    if errors is None:
        return None
    return {"cycles": len(errors.rows),
            **{f"{q}_rms_error": _number(errors.rms(q)) for q in QUANTITIES}}


def effect_parameters(d: Diagnosis, assessment: Assessment) -> dict[str, dict]:
    """``{effect: {parameter: (value, stderr, unit)}}`` of a fitted model, the scale first;
    kinematic effects held fixed in the sliding phase are read from their fit on all samples."""
    fit = assessment.fit
    out: dict[str, dict] = {"baseline_scale": {"scale": (float(fit.theta[0]),
                                                         float(fit.stderr[0]), "-")}}
    kinematic = d.selection.kinematic
    for effect, part in zip(assessment.model.effects, assessment.model.slices(), strict=True):
        if effect.name == IMPLIED_HEAT:  # the baseline's own heat: no parameters, not an effect
            continue
        if not effect.parameters and kinematic is not None:
            own = dict(zip(kinematic.model.names, kinematic.model.slices(), strict=True))
            k_effect = kinematic.model.effects[kinematic.model.names.index(effect.name)]
            sl = own[effect.name]
            out[effect.name] = k_effect.physical_parameters(
                kinematic.fit.theta[sl], kinematic.fit.stderr[sl], d.problem.context)
            continue
        out[effect.name] = effect.physical_parameters(fit.theta[part], fit.stderr[part],
                                                      d.problem.context)
    return out


def _role(d: Diagnosis, name: str, assessment: Assessment) -> str:
    sel = d.selection
    if assessment.untestable is not None:
        return f"untestable: {assessment.untestable}"
    in_chosen = sel.chosen is not None and name in sel.chosen.model.names
    if in_chosen and name in sel.verdict:
        named = [n for n in sel.verdict if n != "unexplained"]
        if assessment.earns_keep or len(named) == 1:
            return "selected"
        others = " + ".join(n for n in named if n != name)
        return f"selected together with {others} (alone it does not earn its keep)"
    if in_chosen or (assessment.earns_keep and sel.verdict == ["unexplained"]):
        return "partial stand-in: earns a little but leaves a real gap"
    if assessment.earns_keep:
        return "earns its keep alone, adds too little to the chosen effects"
    return "does not earn its keep on held-out data"


def baseline_heat(d: Diagnosis) -> dict | None:
    """The JSON ``chosen.baseline_heat`` entry, for a baseline that heats: whether its
    temperature follows the named laws' friction power in the chosen model (its own physics,
    never an effect), with the change of its temperature and of its temperature factor and
    the gap the chosen model would leave without it; None for a baseline that does not heat."""
    if not d.baseline.spec.heats or d.selection.chosen is None:
        return None
    info = d.selection.implied
    if info is None:
        return {"follows_named_laws": False, "laws": [],
                "statement": "No law on mu other than heating is named: the baseline's "
                             "temperature follows its own friction power."}
    before = d.gap_before
    with_heat = d.work.nrmse(info.carrying.prediction)
    without = d.work.nrmse(info.without.prediction)
    change = info.temperature_change
    factor = np.exp(info.log_change)
    laws = " and ".join(info.laws)
    size = (f"its contact temperature changes by {float(change.min()):.3g} to "
            f"{float(change.max()):.3g} degC, its temperature factor by "
            f"{float(factor.min()):.4g} to {float(factor.max()):.4g}")
    if info.fits:
        statement = (f"The baseline's temperature follows the friction power of the named "
                     f"{laws} (its heat input computed with the chosen model's mu: the "
                     f"baseline's own physics, not an effect of its own), the parameters "
                     f"refitted with that heat ({info.refits} refits): {size}.")
    else:
        statement = (f"The baseline's temperature follows its own friction power: with the "
                     f"friction power of the named {laws} ({size}, the parameters refitted "
                     f"with that heat) the chosen model fits worse held out (NRMSE "
                     f"{with_heat:.4f}), so the baseline's heat is off in another way too "
                     f"and the chosen model does not carry it.")
    return {"follows_named_laws": bool(info.fits), "laws": list(info.laws),
            "statement": statement, "refitted_with_heat": True, "refits": info.refits,
            "temperature_change": [float(change.min()), float(change.max())],
            "temperature_factor": [float(factor.min()), float(factor.max())],
            "gap_after_with": with_heat, "shrink_with": 1.0 - with_heat / before if before
            else 0.0, "gap_after_without": without,
            "shrink_without": 1.0 - without / before if before else 0.0}


def _transition(d: Diagnosis) -> dict | None:
    t = d.transition
    if t is None:
        return None
    return {"statement": t.statement(), "yield_displacement": t.yield_displacement,
            "rigid_plastic": t.rigid_plastic, "window_travel": t.window_travel,
            "window_samples": t.window_samples, "sample_share": t.sample_share,
            "energy_share": t.energy_share, "rms": t.rms, "relative_rms": t.relative_rms,
            "sliding_rms": t.sliding_rms, "score": _number(t.score), "excess": t.excess,
            "gap": "transition" in d.selection.findings, "after_named": _after_named(d)}


def _after_named(d: Diagnosis) -> dict | None:
    """What the transition windows still hold once the named effects are applied (u_y refitted
    to them): reported, not part of the verdict."""
    chosen = d.selection.chosen
    if chosen is None:
        return None
    th = d.selection.thresholds
    score, excess = d.problem.window_after(chosen)
    return {"score": _number(score), "excess": excess,
            "far_above_noise": bool(score >= th.transition_score
                                    and excess >= th.transition_practical)}


def nuisance_entry(yield_displacement: float, yield_range: tuple[float, float],
                   calibrated: bool, lag: float, sample_interval: float,
                   edges: dict[str, str], findings) -> dict:
    """The JSON ``nuisance`` entry of a diagnosis in one direction or in two: the baseline's
    u_y [m] and channel lag [s] with their ranges and whether they sit at an edge
    (``edges``, :func:`~isolator.diagnosis.baseline.edges_of`), the plausible limit of a
    channel lag [s] and the ``findings`` (where a real gap lies)."""
    from isolator.diagnosis.decision import LAG_PLAUSIBLE_MAX

    return {
        "yield_displacement": {"value": yield_displacement, "range": list(yield_range),
                               "unit": "m", "at_edge": edges.get("yield_displacement"),
                               "calibrated": calibrated},
        "lag": {"value": lag, "samples": lag / sample_interval if sample_interval else 0.0,
                "range_samples": [-NUISANCE_LAG_SAMPLES, NUISANCE_LAG_SAMPLES], "unit": "s",
                "at_edge": edges.get("lag"), "plausible_max": LAG_PLAUSIBLE_MAX},
        "findings": list(findings),
    }


def _nuisance(d: Diagnosis) -> dict:
    """The baseline's nuisance parameters with their ranges and whether they sit at an edge
    (a finding, not a calibration), and the lag candidate fitted test by test."""
    fit = d.baseline
    dt = fit.sample_interval
    out = nuisance_entry(fit.parameters["yield_displacement"], fit.yield_range,
                         fit.spec.yield_displacement is None, fit.lag, dt,
                         nuisance_edges(fit), d.selection.findings)
    lag = d.problem.kinematic.get("lag")
    if lag is not None and lag.untestable is None:
        i = lag.model.names.index("lag")
        samples = float(lag.fit.theta[lag.model.slices()[i]][0])
        per_test = None
        if abs(samples) >= d.selection.thresholds.lag_min_samples:
            per_test = [float(x) for x in d.problem.lag_per_test(lag)]
        out["lag_candidate"] = {"samples": samples, "seconds": samples * dt,
                                "per_test_samples": per_test,
                                "force_leads": samples < 0.0}
    return out


def _lag(d: Diagnosis) -> dict:
    dt = d.baseline.sample_interval
    total = d.baseline.lag
    named = d.selection.kinematic is not None and "lag" in d.selection.kinematic.model.names
    correction = 0.0
    if named:
        params = effect_parameters(d, d.selection.kinematic)["lag"]
        total = params["lag"][0]
    else:
        final = d.selection.chosen or d.selection.stage.baseline
        if "timing" in final.model.names:
            i = final.model.names.index("timing")
            correction = float(final.fit.theta[final.model.slices()[i]][0]) * dt
            total += correction
    return {"seconds": float(total), "samples": float(total / dt), "sample_interval": dt,
            "calibrated_in_baseline": float(d.baseline.lag),
            "refitted_while_sliding": correction, "named": bool(named)}


def _gap_statement(d: Diagnosis) -> str:
    """Where the real gap left lies: the sliding phase, the transition windows, or a nuisance
    of the baseline at the edge of its range."""
    parts = []
    findings = d.selection.findings
    if "sliding" in findings or not findings:
        parts.append(d.remaining.statement)
    t = d.transition
    if "transition" in findings and t is not None:
        chosen = d.selection.chosen
        score, excess = (d.problem.window_statistics(d.problem.all_baseline.prediction)
                         if chosen is None else d.problem.window_after(chosen))
        what = "the baseline" if chosen is None else "the named effects"
        parts.append(f"Inside the transition windows after the reversals "
                     f"({1e3 * t.window_travel:.3g} mm or {t.window_samples} samples, "
                     f"{100 * t.sample_share:.0f} % of the samples) the residual {what} leave "
                     f"is far above the noise ({math.sqrt(score):.3g} x its RMS there, an "
                     f"excess of {100 * excess:.2g} % of the RMS force over the whole test): a "
                     f"play, a softer or slower transition or a breakaway the candidates do not "
                     f"capture.")
    for f in findings:
        if f.startswith("yield_displacement"):
            top = d.baseline.yield_range[1]
            parts.append(f"The pre-sliding yield displacement was fitted at the top of its "
                         f"range ({1e3 * top:.3g} mm): a play or a soft transition it stands "
                         f"in for, not a calibration.")
    return " ".join(parts)


def summary(d: Diagnosis) -> dict:
    """The JSON summary of a diagnosis (see the module docstring)."""
    before = d.gap_before
    sel = d.selection
    candidates = sel.candidates
    effects = []
    for name in sel.ranking:
        a = candidates[name]
        effect = a.model.effects[-1]
        entry: dict = {"name": name, "description": effect.description,
                       "acts_on": effect.acts_on, "physical_reading": effect.physical_reading,
                       "role": _role(d, name, a)}
        if a.untestable is None:
            after = d.work.nrmse(a.prediction)
            params = effect_parameters(d, a)[name]
            entry.update({
                "gap_after": after, "shrink": 1.0 - after / before if before else 0.0,
                "parameters": {k: v[0] for k, v in params.items()},
                "stderr": {k: _number(v[1]) for k, v in params.items()},
                "units": {k: v[2] for k, v in params.items()},
                "held_out_z": _number(a.z_score), "explained_excess": _number(a.explained),
                "earns_keep": bool(a.earns_keep),
                "confidence": _number(d.confidence.get(name, float("nan"))),
                "intervals": d.intervals.get(name, {}),
            })
        else:  # untestable on these data: the same keys, with nothing measured
            entry.update({"gap_after": None, "shrink": None, "parameters": {}, "stderr": {},
                          "units": {}, "held_out_z": None, "explained_excess": None,
                          "earns_keep": False, "confidence": None, "intervals": {}})
        effects.append(entry)
    chosen = None
    if sel.chosen is not None:
        after = d.gap_after
        params = effect_parameters(d, sel.chosen)
        chosen = {
            "names": [n for n in sel.verdict if n != "unexplained"],
            "gap_before": before, "gap_after": after,
            "shrink": 1.0 - after / before if before else 0.0,
            "explained_excess": _number(sel.explained),
            "EDC_rms_error_before": _number(d.cycles_before.rms("EDC")),
            "EDC_rms_error_after": _number(d.cycles_after.rms("EDC")),
            "Keff_rms_error_before": _number(d.cycles_before.rms("Keff")),
            "Keff_rms_error_after": _number(d.cycles_after.rms("Keff")),
            "parameters": {e: {k: v[0] for k, v in p.items()} for e, p in params.items()},
            "stderr": {e: {k: _number(v[1]) for k, v in p.items()} for e, p in params.items()},
            "form": dict(sel.form),
            "confidence": {k: _number(v) for k, v in d.confidence.items()},
            "intervals": d.intervals,
        }
        heat = baseline_heat(d)
        if heat is not None:  # a baseline that heats (absent for one that does not)
            chosen["baseline_heat"] = heat
    unexplained = None
    if sel.real_gap_remains and d.remaining is not None:
        unexplained = {"statement": _gap_statement(d), "looks_like": d.looks_like,
                       "findings": list(sel.findings)}
    f = d.work.features
    return {
        "baseline": {"model": d.baseline.spec.label, "parameters": d.baseline.parameters,
                     "runs": d.baseline.iterations},
        "gap": {"metric": "force_nrmse", "value": before, "noise": d.noise_nrmse,
                "holdout": d.work.holdout.scheme, "cycles": _cycles(d.cycles_before),
                "phase": "sliding phase (outside the transition window after each reversal)",
                "samples": int(f.force.size),
                "all_samples": d.problem.all.nrmse(d.problem.all_baseline.prediction)},
        "transition": _transition(d),
        "lag": _lag(d),
        "nuisance": _nuisance(d),
        "where": _where(d.where),
        "effects": effects,
        "chosen": chosen,
        "verdict": list(sel.verdict),
        "unexplained": unexplained,
        "excluded": list(d.excluded),
        "tests": len(d.campaign.tests),
        "samples": int(f.force.size),
        "force_rms": float(np.sqrt(np.mean(f.force**2))),
        "wall_time": d.wall_time,
    }


@dataclass(frozen=True)
class Diagnosis:
    """Everything the diagnosis found; :meth:`to_json` gives the documented summary.

    Attributes
    ----------
    campaign, baseline : Campaign, BaselineFit
        The data and the calibrated baseline.
    problem : Problem
        What every decision shares (features, folds, the candidates' fits).
    selection : Selection
        Candidates, chosen effects and verdict.
    where : Where
        Where the baseline's held-out residual lies.
    cycles_before, cycles_after : CycleErrors
        Per-cycle characteristic errors of the baseline and of the chosen effects (held out).
    remaining, looks_like : Where or None, list of str
        When a real gap remains, where the residual left by the chosen effects lies and
        what it looks like.
    wall_time : float
        Time the diagnosis took [s].
    excluded : tuple of str
        Effects withheld from the library.
    transition : TransitionFinding or None
        What the baseline leaves inside the transition window after each reversal.
    confidence, intervals : dict
        ``{effect: share [-]}`` and ``{effect: {parameter: [low, high]}}`` of the named
        effects (:mod:`isolator.diagnosis.uncertainty`).
    """

    campaign: Campaign
    baseline: BaselineFit
    problem: Problem
    selection: Selection
    where: Where
    cycles_before: CycleErrors
    cycles_after: CycleErrors | None
    remaining: Where | None
    looks_like: list[str]
    wall_time: float = 0.0
    excluded: tuple[str, ...] = field(default=())
    transition: TransitionFinding | None = None
    confidence: dict[str, float] = field(default_factory=dict)
    intervals: dict[str, dict] = field(default_factory=dict)

    @property
    def work(self) -> Workspace:
        """The samples the verdict was decided on (the sliding phase) and their fits."""
        return self.selection.stage.work

    @property
    def verdict(self) -> list[str]:
        """The verdict (see :mod:`isolator.diagnosis.decision`)."""
        return self.selection.verdict

    @property
    def gap_before(self) -> float:
        """Held-out force NRMSE of the calibrated baseline [-]."""
        return self.work.nrmse(self.selection.baseline.prediction)

    @property
    def gap_after(self) -> float:
        """Held-out force NRMSE with the chosen effects (the baseline's when none) [-]."""
        chosen = self.selection.chosen
        return self.gap_before if chosen is None else self.work.nrmse(chosen.prediction)

    @property
    def noise_nrmse(self) -> float:
        """The measurement noise on the same scale as the gap [-]."""
        return self.work.noise_nrmse

    def to_json(self) -> dict:
        """The summary as plain JSON types (:func:`summary`)."""
        return summary(self)
