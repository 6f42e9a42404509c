"""Whether a candidate earns its keep: held-out scores, the block statistic, the criteria.

Every candidate is fitted on the training folds and judged on the held-out samples
(:mod:`isolator.diagnosis.fitting`) by two mean squares of the held-out residual:

- the *score*, standardised by the variance v measurement noise alone leaves at each sample
  (:mod:`isolator.diagnosis.noise`): about one for a model that leaves only noise;
- the *weighted* mean square, weights 1 / (v + tau^2) with tau^2 the excess variance the
  calibrated baseline leaves (a random-effects weighting, also the fits'); it ranks and
  judges the candidates.

A model extended by one or more effects earns its keep over the current one when its held-out
weighted error is lower block by block (a block is a half cycle of one test) by ``z``
standard errors of the summed block differences, it closes a share of the weighted excess the
current model leaves, and the force it changes is practically significant (an RMS of
``practical_gain`` of the RMS force). Thresholds: :mod:`.thresholds`; the stages and the
verdict: :mod:`.decision`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from isolator.diagnosis.effects import Context
from isolator.diagnosis.features import Features
from isolator.diagnosis.fitting import Fit, HoldOut, Model, fit, multistart
from isolator.diagnosis.thresholds import Thresholds

if TYPE_CHECKING:
    from isolator.diagnosis.decision import ImpliedFit

MAX_EFFECTS = 3  # effects on the friction law named at most
MAX_KINEMATIC = 2  # effects on the kinematics named at most
SCREENED = 3  # extensions judged on held-out data at each step, the best fits in-sample


@dataclass(frozen=True)
class Workspace:
    """What every fit of one campaign shares: the calibrated baseline's features (with each
    sample's noise variance and weight), the folds, the constants, and a ``cache`` of the fits
    and assessments made, by effect names."""

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

    def excess_rms(self, prediction: np.ndarray) -> float:
        """RMS force error above the noise over the RMS force, held out [-]."""
        f = self.features
        excess = float(np.mean((f.force - prediction) ** 2) - np.mean(f.noise_variance))
        return float(np.sqrt(max(excess, 0.0) / np.mean(f.force**2)))

    def gain_rms(self, current: np.ndarray, extended: np.ndarray) -> float:
        """RMS force change that ``extended`` explains over ``current``, over the RMS force
        (the square root of the drop of the held-out mean square) [-]."""
        f = self.features
        drop = float(np.mean((f.force - current) ** 2) - np.mean((f.force - extended) ** 2))
        return float(np.sqrt(max(drop, 0.0) / np.mean(f.force**2)))

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
    fit, prediction : Fit or None, ndarray or None
        The fit on all data, and the held-out force of every sample [N].
    score, weighted : float
        Held-out standardised and weighted mean squares of the residual [-] (inf when
        untestable).
    z_score, explained : float
        Against the reference: the improvement in standard errors of the summed block
        differences [-], and the share of its weighted excess above noise closed [-].
    earns_keep : bool
        Whether it qualifies against the reference (:func:`qualifies`).
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
    return block_z(reference - candidate)


def block_z(d: np.ndarray) -> float:
    """The sum of the block differences ``d`` over its standard error [-] (0 for fewer than 2
    blocks; +-inf when every block improves by the same amount)."""
    if d.size < 2:
        return 0.0
    spread = float(np.std(d, ddof=1))
    if spread == 0.0:
        return 0.0 if d.sum() == 0.0 else float(np.sign(d.sum()) * np.inf)
    return float(d.sum() / (np.sqrt(d.size) * spread))


def material(score: float, excess: float, practical: float, th: Thresholds) -> bool:
    """Whether a residual is a real gap: its mean square over the noise's [-] beyond
    1 + ``none_margin`` and its RMS above the noise, over the RMS force [-], at least
    ``practical`` (the materiality rule of the verdict, in one direction and in two)."""
    return score - 1.0 > th.none_margin and excess >= practical


def verdict_of(named: list[str], gap: bool) -> list[str]:
    """The verdict: the ``named`` effects, then ``unexplained`` when a real ``gap`` remains;
    ``["unexplained"]`` when nothing is named but a gap is real, else ``["none"]``."""
    if named:
        return [*named, *(["unexplained"] if gap else [])]
    return ["unexplained"] if gap else ["none"]


def assess(work: Workspace, model: Model, reference: Assessment | None,
           starts: list[np.ndarray] | None = None,
           thresholds: Thresholds | None = None) -> Assessment:
    """Fit ``model`` on all data and on every fold; judge it against ``reference``."""
    full = fit(model, work.features, work.context, starts or multistart(model),
               uncertainty=True)
    prediction, _ = work.holdout.predict(model, work.context, start=full.theta)
    judged = work.judge(model, full, prediction)
    if reference is None:
        return judged
    th = thresholds or Thresholds()
    z, gain = improvement(work, reference, judged)
    keeps = qualifies(work, reference, judged, th.z_min, th.explained_min, th.practical_gain)
    return replace(judged, z_score=z, explained=gain, earns_keep=keeps)


def improvement(work: Workspace, current: Assessment,
                extended: Assessment) -> tuple[float, float]:
    """(z score, share of the excess left by ``current`` that ``extended`` closes)."""
    z = paired_z(work.block_sse(current.prediction), work.block_sse(extended.prediction))
    left = current.weighted - work.weighted_noise
    return z, (current.weighted - extended.weighted) / left if left > 0.0 else 0.0


def qualifies(work: Workspace, current: Assessment, extended: Assessment, z_min: float,
              explained_min: float, practical: float) -> bool:
    """Whether ``extended`` earns its keep over ``current`` (see the module docstring)."""
    z, gain = improvement(work, current, extended)
    size = work.gain_rms(current.prediction, extended.prediction)
    return z >= z_min and gain >= explained_min and size >= practical


def joint_pair_earns(over_baseline: tuple[float, float, float],
                     over_kinematic: tuple[float, float, float],
                     over_law: tuple[float, float, float], th: Thresholds) -> bool:
    """Whether a kinematic effect and a friction-law effect, fitted jointly on every sample,
    are named together (one direction and two): the pair earns its keep over the baseline as
    stage 1 judges a kinematic effect (``kinematic_z``, ``kinematic_explained``,
    ``kinematic_practical``), and each member earns its keep against the other held out by
    ``z_min`` and ``practical_gain`` and closes ``name_min`` of what the other leaves (would be
    named beside it): the pair over the kinematic effect alone (``over_kinematic``: dropping
    the law loses materially) and over the law alone (``over_law``: dropping the play does).
    A share of ``explained_min`` is not enough: a law closing a third of what a play's model
    leaves can be standing in for the play's wrong shape.

    Each argument is (held-out z [-], share of the reference's excess closed [-], RMS force
    changed over the RMS force [-]) of the pair against that reference.
    """
    z, gain, size = over_baseline
    if not (z >= th.kinematic_z and gain >= th.kinematic_explained
            and size >= th.kinematic_practical):
        return False
    return all(z >= th.z_min and gain >= th.name_min and size >= th.practical_gain
               for z, gain, size in (over_kinematic, over_law))


def untestable(model: Model, reason: str) -> Assessment:
    """An assessment for an effect the data cannot show."""
    return Assessment(model, None, None, np.inf, np.inf, untestable=reason)


@dataclass(frozen=True)
class Stage:
    """The sliding-phase stage for one set of kinematic effects.

    Attributes
    ----------
    work, baseline : Workspace, Assessment
        The sliding samples with the kinematics applied, and the baseline with them there.
    plain : np.ndarray
        The plain baseline's held-out prediction on the same samples [N].
    singles : dict
        Each effect on mu or the force alone, by name.
    """

    work: Workspace
    baseline: Assessment
    plain: np.ndarray
    singles: dict[str, Assessment]


@dataclass(frozen=True)
class Selection:
    """The result of one decision.

    Attributes
    ----------
    stage : Stage
        The sliding-phase stage the verdict was decided on (its samples define the gap).
    kinematic, kinematic_candidates : Assessment or None, dict
        The named effects on the kinematics, and each alone, judged on every sample.
    chosen : Assessment or None
        The final model on the stage's samples (kinematics and friction-law effects).
    verdict : list of str
        See :mod:`isolator.diagnosis.decision`.
    explained, real_gap_remains : float, bool
        Share of the sliding-phase excess closed by ``chosen`` [-]; whether a real gap is left.
    ranking : list of str
        Effect names, best first: the named ones, then the others by held-out error, then the
        untestable ones.
    form : dict
        ``{effect: "paper" | "flexible"}``: the form of each named effect on mu reported.
    thresholds : Thresholds
    findings : tuple of str
        Where a real gap lies: ``"sliding"`` (the sliding phase), ``"transition"`` (the
        transition windows after the reversals, far above the noise there) and the baseline's
        nuisance parameters fitted at an edge of their range.
    implied : ImpliedFit or None
        How ``chosen`` carries the heat its named laws on mu imply for a baseline that heats
        (:meth:`isolator.diagnosis.decision.Problem.carried`), or None when it was not tried.
    """

    stage: Stage
    kinematic: Assessment | None
    kinematic_candidates: dict[str, Assessment]
    chosen: Assessment | None
    verdict: list[str]
    explained: float
    real_gap_remains: bool
    ranking: list[str]
    form: dict[str, str]
    thresholds: Thresholds

    @property
    def baseline(self) -> Assessment:
        """The plain baseline on the stage's samples (prediction: held out)."""
        b = self.stage.baseline
        return replace(b, prediction=self.stage.plain)

    @property
    def candidates(self) -> dict[str, Assessment]:
        """Every candidate, kinematic ones first (predictions on the stage's samples)."""
        idx = self.stage.work.features.sample
        out = {}
        for name, a in self.kinematic_candidates.items():
            out[name] = a if a.prediction is None else replace(
                a, prediction=on_samples(a.prediction, self._all_samples, idx))
        out.update(self.stage.singles)
        return out

    @property
    def _all_samples(self) -> np.ndarray:
        return self._all

    _all: np.ndarray = field(default=None, repr=False)
    findings: tuple[str, ...] = ()
    implied: ImpliedFit | None = None


def on_samples(prediction: np.ndarray, samples: np.ndarray, wanted: np.ndarray) -> np.ndarray:
    """The values of ``prediction`` (given at ``samples``) at the samples ``wanted``."""
    position = np.searchsorted(samples, wanted)
    return prediction[position]
