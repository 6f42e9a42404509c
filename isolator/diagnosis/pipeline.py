"""The diagnosis from start to end: calibrate, locate, explain, measure the shrink.

:func:`diagnose` runs the steps on a :class:`~isolator.diagnosis.data.Campaign`:

1. calibrate the baseline's own parameters on all data (:mod:`.baseline`);
2. judge the baseline on held-out data and locate its residual (:mod:`.where`);
3. fit every candidate effect of the library (:mod:`.effects`) on training folds, judge it on
   held-out data, combine the leaders, decide (:mod:`.selection`);
4. measure the gap before and after on held-out data: force NRMSE and the per-cycle
   characteristics (:mod:`.where`).

:func:`reselect` repeats step 3's decision with effects withheld from the library (a
leave-one-effect-out check) without refitting the others.
"""

from __future__ import annotations

import time as _time
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from isolator.diagnosis.baseline import BaselineFit, BaselineSpec, calibrate
from isolator.diagnosis.data import Campaign
from isolator.diagnosis.effects import EFFECT_NAMES, Context, effects_named
from isolator.diagnosis.features import kinematic_features, with_baseline
from isolator.diagnosis.fitting import HoldOut, Model
from isolator.diagnosis.noise import sample_noise_variance
from isolator.diagnosis.selection import (
    Assessment,
    Selection,
    Workspace,
    assess,
    select,
    untestable,
)
from isolator.diagnosis.signatures import signature
from isolator.diagnosis.where import (
    CycleErrors,
    Where,
    cycle_errors,
    locate,
    near_reversal_distance,
)


@dataclass(frozen=True)
class Diagnosis:
    """Everything the diagnosis found; :meth:`to_json` gives the documented summary.

    Attributes
    ----------
    campaign : Campaign
        The data.
    baseline : BaselineFit
        The calibrated baseline.
    work : Workspace
        Features, folds, constants and noise shared by every fit.
    selection : Selection
        Candidates, chosen effects and verdict.
    where : Where
        Where the baseline's held-out residual lies.
    cycles_before, cycles_after : CycleErrors
        Per-cycle characteristic errors of the baseline and of the chosen effects (held out).
    remaining : Where or None
        Where the residual left after the chosen effects lies, when a real gap remains.
    looks_like : list of str
        What the remaining gap looks like, when a real gap remains.
    wall_time : float
        Seconds the diagnosis took.
    """

    campaign: Campaign
    baseline: BaselineFit
    work: Workspace
    selection: Selection
    where: Where
    cycles_before: CycleErrors
    cycles_after: CycleErrors | None
    remaining: Where | None
    looks_like: list[str]
    wall_time: float = 0.0
    excluded: tuple[str, ...] = field(default=())

    @property
    def verdict(self) -> list[str]:
        """The verdict (see :mod:`isolator.diagnosis.selection`)."""
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
        """The summary as plain JSON types (see :mod:`isolator.diagnosis.summary`)."""
        from isolator.diagnosis.summary import summary

        return summary(self)


def diagnose(
    campaign: Campaign,
    baseline: BaselineSpec | str = "constant",
    *,
    candidates: Sequence[str] = EFFECT_NAMES,
    exclude: Sequence[str] = (),
) -> Diagnosis:
    """Diagnose the gap between ``campaign`` and the ``baseline`` model.

    Parameters
    ----------
    campaign : Campaign
        The measured tests of one bearing, in the order run.
    baseline : BaselineSpec or str
        The model to diagnose; a string is a model name with all its effects.
    candidates : sequence of str
        Names of the library's effects to try.
    exclude : sequence of str
        Effects withheld from the library.

    Returns
    -------
    Diagnosis
    """
    start = _time.perf_counter()
    spec = baseline if isinstance(baseline, BaselineSpec) else BaselineSpec(baseline)
    effects = effects_named([c for c in candidates if c not in exclude])
    features, info = kinematic_features(campaign)
    fitted = calibrate(campaign, features, spec)
    noise = sample_noise_variance(fitted.features, campaign, info.force_noise,
                                  info.displacement_noise, info.axial_noise,
                                  fitted.parameters["yield_displacement"])
    residual = fitted.features.force - fitted.features.baseline_force
    excess = max(float(np.mean(residual**2) - np.mean(noise)), 0.0)
    f = with_baseline(fitted.features, noise_variance=noise, weight=1.0 / (noise + excess))
    fitted = replace(fitted, features=f)
    context = Context.of(f, campaign.effective_radius)
    work = Workspace(f, HoldOut.of(f), context)
    base = assess(work, Model(), None, [np.array([1.0])])
    singles: dict[str, Assessment] = {}
    for effect in effects:
        model = Model((effect,))
        reason = effect.untestable(context)
        singles[effect.name] = (untestable(model, reason) if reason is not None
                                else assess(work, model, base))
    selection = select(work, base, singles)
    return _finish(campaign, fitted, work, selection, tuple(exclude), start)


def reselect(diagnosis: Diagnosis, exclude: Sequence[str]) -> Diagnosis:
    """The same diagnosis with the effects ``exclude`` withheld from the library."""
    start = _time.perf_counter()
    sel = diagnosis.selection
    selection = select(diagnosis.work, sel.baseline, sel.candidates, tuple(exclude))
    excluded = tuple(dict.fromkeys((*diagnosis.excluded, *exclude)))
    return _finish(diagnosis.campaign, diagnosis.baseline, diagnosis.work, selection, excluded,
                   start)


def _finish(campaign: Campaign, fitted: BaselineFit, work: Workspace, selection: Selection,
            excluded: tuple[str, ...], start: float) -> Diagnosis:
    f = work.features
    before = selection.baseline.prediction
    near = near_reversal_distance(f, fitted.parameters["yield_displacement"])
    where = locate(f, before, campaign, near)
    cycles_before = cycle_errors(campaign, f, before)
    chosen = selection.chosen
    after = None if chosen is None else chosen.prediction
    cycles_after = None if after is None else cycle_errors(campaign, f, after)
    remaining, looks = None, []
    if selection.real_gap_remains:
        final = before if after is None or selection.verdict == ["unexplained"] else after
        remaining = locate(f, final, campaign, near)
        looks = signature(f, final, campaign, near)
    diagnosis = Diagnosis(campaign, fitted, work, selection, where, cycles_before, cycles_after,
                          remaining, looks, excluded=excluded)
    return replace(diagnosis, wall_time=_time.perf_counter() - start)
