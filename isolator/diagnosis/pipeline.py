"""The diagnosis from start to end: calibrate, locate, explain, measure the shrink.

:func:`diagnose` calibrates the baseline on all data (:mod:`.baseline`), weighs each sample
by its noise (:mod:`.noise`), decides which candidate effects (:mod:`.effects`) explain the
held-out residual (:mod:`.decision`), and measures where the gap lies and how far it shrinks
on held-out data: force NRMSE and per-cycle characteristics (:mod:`.where`), with the
confidence of each named effect (:mod:`.uncertainty`).
"""

from __future__ import annotations

import time as _time
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from isolator.diagnosis.baseline import (
    RIGID_PLASTIC_LIMIT,
    BaselineFit,
    BaselineSpec,
    calibrate,
    nuisance_edges,
)
from isolator.diagnosis.data import Campaign, Campaign2D
from isolator.diagnosis.decision import IMPLIED_HEAT, Problem
from isolator.diagnosis.effects import EFFECT_NAMES, Context, effects_named
from isolator.diagnosis.features import kinematic_features, with_baseline
from isolator.diagnosis.fitting import Kinematics
from isolator.diagnosis.implied import implied_heat
from isolator.diagnosis.noise import sample_noise_variance
from isolator.diagnosis.selection import Selection
from isolator.diagnosis.signatures import signature
from isolator.diagnosis.summary import Diagnosis
from isolator.diagnosis.thresholds import Thresholds
from isolator.diagnosis.transition import in_transition, transition_finding
from isolator.diagnosis.uncertainty import confidence, intervals
from isolator.diagnosis.where import (
    cycle_errors,
    locate,
    near_reversal_distance,
)


def diagnose(
    campaign: Campaign,
    baseline: BaselineSpec | str = "constant",
    *,
    candidates: Sequence[str] = EFFECT_NAMES,
    exclude: Sequence[str] = (),
    thresholds: Thresholds | None = None,
) -> Diagnosis:
    """Diagnose the gap between ``campaign`` and the ``baseline`` model.

    Parameters
    ----------
    campaign : Campaign or Campaign2D
        The measured tests of one bearing, in the order run; tests in two directions are
        diagnosed by :func:`isolator.diagnosis.two_directions.diagnose_2d`.
    baseline : BaselineSpec or str
        The model to diagnose; a string is a model name with all its effects.
    candidates, exclude : sequence of str
        Names of the library's effects to try, and of those withheld.
    thresholds : Thresholds, optional
        The decision thresholds (default: :func:`isolator.diagnosis.thresholds.current`).
    """
    if isinstance(campaign, Campaign2D):  # tests in two directions
        from isolator.diagnosis.two_directions import diagnose_2d

        return diagnose_2d(campaign, baseline, candidates=candidates, exclude=exclude,
                           thresholds=thresholds)
    start = _time.perf_counter()
    th = thresholds or Thresholds.load()
    spec = baseline if isinstance(baseline, BaselineSpec) else BaselineSpec(baseline)
    effects = effects_named([c for c in candidates if c not in exclude])
    features, info = kinematic_features(campaign)
    fitted = calibrate(campaign, features, spec)
    u_y = fitted.parameters["yield_displacement"]
    noise = sample_noise_variance(fitted.features, campaign, info.force_noise,
                                  info.displacement_noise, info.axial_noise, u_y,
                                  lag=fitted.lag)
    residual = fitted.features.force - fitted.features.baseline_force
    excess = max(float(np.mean(residual**2) - np.mean(noise)), 0.0)
    f = with_baseline(fitted.features, noise_variance=noise, weight=1.0 / (noise + excess))
    fitted = replace(fitted, features=f)
    # effects on the kinematics replace the baseline's transition and lag with their own,
    # so they start from the displacement as measured (smoothed), not shifted
    kinematics = Kinematics(
        tuple(f.time[f.test == k] for k in range(len(campaign.tests))),
        tuple(np.ascontiguousarray(features.displacement[features.test == k])
              for k in range(len(campaign.tests))),
        tuple(f.axial_force[f.test == k] for k in range(len(campaign.tests))),
        u_y, campaign.effective_radius, float(np.mean(f.mu_base)))
    context = Context.of(f, campaign.effective_radius, sample_interval=fitted.sample_interval,
                         yield_displacement=u_y, nominal_mu=float(np.mean(f.mu_base)),
                         tests=len(campaign.tests), channel_lag=fitted.lag,
                         kinematics=kinematics)
    problem = Problem(f, context, effects, th, nuisance_edges(fitted),
                      implied_heat(campaign, f, spec))
    selection = problem.select(tuple(exclude), th)
    return _finish(campaign, fitted, problem, selection, tuple(exclude), start,
                   uncertainty=True)


def reselect(diagnosis: Diagnosis, exclude: Sequence[str] = (),
             thresholds: Thresholds | None = None, *, uncertainty: bool = False) -> Diagnosis:
    """The same diagnosis with ``exclude`` withheld (a leave-one-effect-out check) or under
    other ``thresholds``, without refitting (confidence and intervals: only ``uncertainty``)."""
    from isolator.diagnosis.two_directions import Diagnosis2D, diagnose_2d

    if isinstance(diagnosis, Diagnosis2D):  # tests in two directions: diagnosed again
        return diagnose_2d(diagnosis.campaign, diagnosis.baseline.spec,
                           exclude=tuple(dict.fromkeys((*diagnosis.excluded, *exclude))),
                           thresholds=thresholds or diagnosis.problem.th)
    start = _time.perf_counter()
    excluded = tuple(dict.fromkeys((*diagnosis.excluded, *exclude)))
    selection = diagnosis.problem.select(excluded, thresholds or diagnosis.selection.thresholds)
    return _finish(diagnosis.campaign, diagnosis.baseline, diagnosis.problem, selection,
                   excluded, start, uncertainty=uncertainty)


def _finish(campaign: Campaign, fitted: BaselineFit, problem: Problem, selection: Selection,
            excluded: tuple[str, ...], start: float, *, uncertainty: bool) -> Diagnosis:
    everything = problem.features
    u_y = fitted.parameters["yield_displacement"]
    window = in_transition(everything, u_y)
    transition = transition_finding(everything, problem.all_baseline.prediction, window, u_y,
                                    RIGID_PLASTIC_LIMIT)
    f = selection.stage.work.features
    before = selection.baseline.prediction
    near = near_reversal_distance(f, u_y)
    where = locate(f, before, campaign, near)
    cycles_before = cycle_errors(campaign, everything, problem.all_baseline.prediction)
    chosen = selection.chosen
    cycles_after = None
    if chosen is not None:
        full = _full_prediction(problem, chosen)
        cycles_after = cycle_errors(campaign, everything, full)
    remaining, looks = None, []
    if selection.real_gap_remains:
        final = (before if chosen is None or selection.verdict == ["unexplained"]
                 else chosen.prediction)
        remaining = locate(f, final, campaign, near)
        left = (problem.all_baseline.prediction if chosen is None
                else _full_prediction(problem, chosen))
        looks = signature(everything, left, campaign, near)
    certainty, ranges = _uncertainty(problem, selection) if uncertainty else ({}, {})
    diagnosis = Diagnosis(campaign, fitted, problem, selection, where, cycles_before,
                          cycles_after, remaining, looks, excluded=excluded,
                          transition=transition, confidence=certainty, intervals=ranges)
    return replace(diagnosis, wall_time=_time.perf_counter() - start)


def _uncertainty(problem: Problem, selection: Selection) -> tuple[dict, dict]:
    """Confidence of each named effect and intervals of their parameters."""
    th = selection.thresholds
    certainty: dict[str, float] = {}
    ranges: dict[str, dict] = {}
    kinematic = selection.kinematic
    if kinematic is not None:
        for name in kinematic.model.names:
            certainty[name] = confidence(problem.all, problem.all_baseline, kinematic,
                                         th.kinematic_explained)
        ranges.update(intervals(problem.all, kinematic))
    stage, chosen = selection.stage, selection.chosen
    frozen = len(stage.baseline.model.effects)
    own = [] if chosen is None else [n for n in chosen.model.names[frozen:]
                                     if n != IMPLIED_HEAT]
    if own and [n for n in selection.verdict if n not in ("unexplained",)]:
        for name in own:
            others = [n for n in own if n != name]
            if not others:
                reference = stage.baseline
            elif len(others) == 1 and others[0] in stage.singles:
                reference = stage.singles[others[0]]
            else:
                continue
            certainty[name] = confidence(stage.work, reference, chosen,
                                         th.second_explained if others else th.explained_min)
        ranges.update({k: v for k, v in intervals(stage.work, chosen).items() if k in own})
    return certainty, ranges


def _full_prediction(problem: Problem, chosen) -> np.ndarray:
    """The chosen model's force at every sample, from its fit on the sliding phase [N]."""
    return chosen.model.force(chosen.fit.theta, problem.features, problem.context)
