"""Which candidate earns its keep: held-out errors, block statistics, combination, verdict.

Every candidate is fitted on the training folds and judged on the held-out samples (see
:mod:`isolator.diagnosis.fitting`). Two mean squares of the held-out residual are used:

- the *score*, the residual standardised by the variance v that measurement noise alone
  leaves at each sample (:mod:`isolator.diagnosis.noise`): about one for a model that leaves
  only noise, so score - 1 is the excess above the noise; it decides whether a gap is within
  the noise;
- the *weighted* mean square, with weights 1 / (v + tau^2), tau^2 the excess variance the
  calibrated baseline leaves (a random-effects weighting): noise weights when the model is
  nearly right, even weights when model error dominates, so that a quiet test does not
  outweigh a noisy one whose misfit is just as real. It ranks and judges the candidates, and
  the fits use the same weights.

A model extended by one or more effects earns its keep over the current one when its held-out
weighted error is lower block by block (a block is a half cycle of one test) by ``Z_MIN``
standard errors of the summed block differences (serial correlation within a block does not
fool this) and when it closes at least ``EXPLAINED_MIN`` of the weighted excess the current
model leaves; so an extra parameter is not rewarded for fitting noise. Effects join by
forward selection with a look-ahead of two (:func:`select`).

The verdict:

- ``["none"]`` when nothing earns its keep and the baseline's score is within
  1 + ``NONE_MARGIN``;
- the selected effects when they close at least ``NAME_MIN`` of the baseline's weighted
  excess, followed by ``"unexplained"`` when a real gap remains (a score excess above
  ``REMAINING_NOISE`` and above ``REMAINING_MAX`` of the baseline's);
- ``["unexplained"]`` otherwise: a real gap that no candidate closes (candidates that close a
  little are reported as partial stand-ins, never named in the verdict).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from itertools import combinations

import numpy as np

from isolator.diagnosis.effects import Context, Effect
from isolator.diagnosis.features import Features
from isolator.diagnosis.fitting import Fit, HoldOut, Model, fit, multistart

Z_MIN = 2.5  # improvement over the reference, in standard errors of the block differences
EXPLAINED_MIN = 0.25  # share of the excess left that an extension must close to earn its keep
NAME_MIN = 0.7  # share of the baseline's excess the selected effects must close to be named
NONE_MARGIN = 0.15  # a held-out score within 1.15 is noise
REMAINING_NOISE = 1.0  # an excess left above one noise variance ...
REMAINING_MAX = 0.05  # ... and above 5 % of the excess before is a real gap
MAX_EFFECTS = 3
SCREENED = 3  # extensions judged on held-out data at each step, the best fits in-sample


@dataclass(frozen=True)
class Workspace:
    """What every fit of one campaign shares: features, folds and constants.

    Attributes
    ----------
    features : Features
        The calibrated baseline's features (with the noise variance of each sample).
    holdout : HoldOut
        The folds.
    context : Context
        Campaign constants of the candidates.
    cache : dict
        Fits and assessments of effect combinations already made, by their names.
    """

    features: Features
    holdout: HoldOut
    context: Context
    cache: dict = field(default_factory=dict, compare=False, repr=False)

    def score(self, prediction: np.ndarray) -> float:
        """Held-out mean square of the standardised residual (1 for noise alone) [-]."""
        f = self.features
        return float(np.mean((f.force - prediction) ** 2 / f.noise_variance))

    def weighted(self, prediction: np.ndarray) -> float:
        """Held-out weighted mean square residual [-] (see the module docstring)."""
        f = self.features
        return float(np.mean(f.weight * (f.force - prediction) ** 2))

    @property
    def weighted_noise(self) -> float:
        """The weighted mean square that noise alone leaves [-]."""
        f = self.features
        return float(np.mean(f.weight * f.noise_variance))

    def block_sse(self, prediction: np.ndarray) -> np.ndarray:
        """Held-out weighted squared residual summed over each block [-]."""
        f = self.features
        return np.bincount(f.block, weights=f.weight * (f.force - prediction) ** 2)

    def judge(self, model: Model, full: Fit, prediction: np.ndarray) -> Assessment:
        """An assessment of ``model`` from its held-out prediction."""
        return Assessment(model, full, prediction, self.score(prediction),
                          self.weighted(prediction))

    def nrmse(self, prediction: np.ndarray) -> float:
        """Held-out RMS force error over the RMS force [-] (``force_nrmse``)."""
        f = self.features
        return float(np.sqrt(np.mean((f.force - prediction) ** 2) / np.mean(f.force**2)))

    @property
    def noise_nrmse(self) -> float:
        """The RMS force error noise alone leaves, over the RMS force [-]."""
        f = self.features
        return float(np.sqrt(np.mean(f.noise_variance) / np.mean(f.force**2)))


@dataclass(frozen=True)
class Assessment:
    """A model fitted on all data and judged on held-out data.

    Attributes
    ----------
    model : Model
        The baseline with its effects.
    fit : Fit or None
        The fit on all data (parameters and standard errors).
    prediction : ndarray or None
        Held-out force of every sample [N].
    score : float
        Held-out mean square standardised residual [-] (inf when untestable).
    weighted : float
        Held-out weighted mean square residual [-] (inf when untestable).
    z_score : float
        Improvement over the baseline in standard errors of the block differences.
    explained : float
        Share of the baseline's weighted excess above noise that it closes [-].
    earns_keep : bool
        Whether it qualifies against the baseline (:func:`qualifies`).
    untestable : str or None
        Why the data cannot show it (then nothing else is set).
    """

    model: Model
    fit: Fit | None
    prediction: np.ndarray | None
    score: float
    weighted: float
    z_score: float = 0.0
    explained: float = 0.0
    earns_keep: bool = False
    untestable: str | None = None


def paired_z(reference: np.ndarray, candidate: np.ndarray) -> float:
    """Summed block improvement over its standard error (0 for fewer than 2 blocks)."""
    d = reference - candidate
    if d.size < 2:
        return 0.0
    spread = float(np.std(d, ddof=1))
    if spread == 0.0:
        return 0.0 if d.sum() == 0.0 else float(np.sign(d.sum()) * np.inf)
    return float(d.sum() / (np.sqrt(d.size) * spread))


def assess(work: Workspace, model: Model, reference: Assessment | None,
           starts: list[np.ndarray] | None = None) -> Assessment:
    """Fit ``model`` on all data and on every fold; judge it against ``reference``."""
    full = fit(model, work.features, work.context, starts or multistart(model),
               uncertainty=True)
    prediction, _ = work.holdout.predict(model, work.context, start=full.theta)
    judged = work.judge(model, full, prediction)
    if reference is None:
        return judged
    z, gain = improvement(work, reference, judged)
    return replace(judged, z_score=z, explained=gain,
                   earns_keep=z >= Z_MIN and gain >= EXPLAINED_MIN)


def improvement(work: Workspace, current: Assessment,
                extended: Assessment) -> tuple[float, float]:
    """(z score, share of the excess left by ``current`` that ``extended`` closes)."""
    z = paired_z(work.block_sse(current.prediction), work.block_sse(extended.prediction))
    left = current.weighted - work.weighted_noise
    return z, (current.weighted - extended.weighted) / left if left > 0.0 else 0.0


def qualifies(work: Workspace, current: Assessment, extended: Assessment) -> bool:
    """Whether ``extended`` earns its keep over ``current`` (see the module docstring)."""
    z, gain = improvement(work, current, extended)
    return z >= Z_MIN and gain >= EXPLAINED_MIN


@dataclass(frozen=True)
class Selection:
    """The result of the selection.

    Attributes
    ----------
    baseline : Assessment
        The calibrated baseline (its scale refitted per fold).
    candidates : dict
        Assessment of each single effect, by name.
    chosen : Assessment or None
        The selected combination (None when nothing earns its keep).
    verdict : list of str
        See the module docstring.
    explained : float
        Share of the excess closed by ``chosen`` [-].
    real_gap_remains : bool
        Whether a real gap is left after ``chosen`` (or after the baseline).
    ranking : list of str
        Effect names, best first: the chosen ones in the order they joined, then the other
        testable candidates by held-out error, then the untestable ones.
    """

    baseline: Assessment
    candidates: dict[str, Assessment]
    chosen: Assessment | None
    verdict: list[str]
    explained: float
    real_gap_remains: bool
    ranking: list[str] = field(default_factory=list)


def select(work: Workspace, baseline: Assessment, candidates: dict[str, Assessment],
           exclude: tuple[str, ...] = ()) -> Selection:
    """Forward selection with a look-ahead of two, and the verdict.

    At each step every free effect is added to the current model and fitted on all data; the
    ``SCREENED`` best fits are judged on held-out data and the best one that qualifies
    (:func:`qualifies`) joins. When no single one qualifies, pairs are screened the same way
    and the best qualifying pair joins (two effects that each hide the other, like heating and
    velocity in a campaign where the fast tests are also the hot ones). The search stops when
    nothing qualifies, when what is left is within the noise, or at ``MAX_EFFECTS``.
    """
    pool = {n: a for n, a in candidates.items() if n not in exclude}
    testable = sorted((a for a in pool.values() if a.untestable is None),
                      key=lambda a: a.weighted)
    excess = baseline.weighted - work.weighted_noise
    current = baseline
    while len(current.model.effects) < MAX_EFFECTS and current.score - 1.0 > NONE_MARGIN:
        free = [a for a in testable if a.model.names[0] not in current.model.names]
        step = _best_extension(work, current, [(a,) for a in free])
        if step is None and not current.model.effects:
            step = _best_extension(work, current, list(combinations(free, 2)))
        if step is None:
            break
        current = step
    chosen = current if current.model.effects else None
    explained = (baseline.weighted - current.weighted) / excess if excess > 0.0 else 0.0
    left = current.score - 1.0
    if chosen is None:
        real_gap = left > NONE_MARGIN
    else:
        real_gap = left > max(REMAINING_NOISE, REMAINING_MAX * (baseline.score - 1.0))
    if chosen is None:
        verdict = ["unexplained"] if real_gap else ["none"]
    elif explained >= NAME_MIN:
        verdict = list(chosen.model.names) + (["unexplained"] if real_gap else [])
    else:
        verdict, real_gap = ["unexplained"], True
    order = list(chosen.model.names) if chosen is not None and verdict != ["unexplained"] else []
    order += [a.model.names[0] for a in testable if a.model.names[0] not in order]
    order += [n for n, a in pool.items() if a.untestable is not None]
    return Selection(baseline, pool, chosen, verdict, explained, real_gap, order)


def _best_extension(work: Workspace, current: Assessment,
                    additions: list[tuple[Assessment, ...]]) -> Assessment | None:
    """The best qualifying extension of ``current`` among ``additions`` (screened in-sample)."""
    fitted = [(_extended_fit(work, current, add), add) for add in additions]
    fitted.sort(key=lambda item: item[0][1].sse)
    options = []
    for (model, full), _ in fitted[:SCREENED]:
        judged = _judged(work, model, full)
        if qualifies(work, current, judged):
            options.append(judged)
    return min(options, key=lambda a: a.weighted) if options else None


def _extended_fit(work: Workspace, current: Assessment,
                  additions: tuple[Assessment, ...]) -> tuple[Model, Fit]:
    """``current`` extended by the effects of ``additions``, fitted on all data."""
    if not current.model.effects and len(additions) == 1:
        return additions[0].model, additions[0].fit
    effects: tuple[Effect, ...] = current.model.effects + tuple(
        e for a in additions for e in a.model.effects)
    model = Model(effects)
    key = ("fit", *model.names)  # the order of the effects is the order of the parameters
    if key not in work.cache:
        own = [a.fit.theta[1:] for a in additions]
        scales = [current.fit.theta[0], *(a.fit.theta[0] for a in additions)]
        starts = [np.concatenate([[scale], current.fit.theta[1:], *own]) for scale in scales]
        work.cache[key] = fit(model, work.features, work.context, starts, uncertainty=True)
    return model, work.cache[key]


def _judged(work: Workspace, model: Model, full: Fit) -> Assessment:
    """``model`` judged on held-out data (cached by its effects)."""
    key = ("judged", *model.names)
    if key not in work.cache:
        prediction, _ = work.holdout.predict(model, work.context, start=full.theta)
        work.cache[key] = work.judge(model, full, prediction)
    return work.cache[key]


def untestable(model: Model, reason: str) -> Assessment:
    """An assessment for an effect the data cannot show."""
    return Assessment(model, None, None, np.inf, np.inf, untestable=reason)

