"""The two-stage decision of the diagnosis and its verdict (criteria: :mod:`.selection`).

1. **Kinematics** (``backlash``, ``lag``), judged on every sample since they act at the
   reversals (``kinematic_*`` thresholds): a play of at least ``backlash_min`` or a channel
   offset of at least ``lag_min_samples``, beyond what the baseline's transition and lag
   absorb. When none is named but stage 2 names a friction law, they are looked for again
   beside it (an asymmetry can hide a play).
2. **The friction law** (effects on mu and on the force), judged on the sliding phase, outside
   the transition window (:mod:`.transition`), with the kinematics of stage 1 applied and the
   channel timing refitted. Effects join by forward selection (a pair when no single one
   qualifies); a second one must earn its keep, by the stricter ``second_*`` thresholds,
   over the first in its flexible monotone form when that fits better (:mod:`.flexible`).
   Effects fitted at a bound of a parameter are not named, nor effects that together close
   less than ``name_min`` of the excess.

When neither stage names anything on its own (a play can hide a friction law and the law the
play), each kinematic candidate that closes its share on every sample but misses the z
threshold is tried *provisionally*: the friction law is selected with it applied, and the play
or lag is judged again beside the law so found; both are named only if both earn their keep
(the play beside the law by the ``kinematic_*`` thresholds, or the pair as one by
``kinematic_z`` over the baseline with the play still closing ``kinematic_explained`` of what
the law leaves, as stage 2 judges a pair). When still no friction law is named (a play named
alone, or nothing), the kinematic effect (the one named, else each of a nameable size that
improves on the baseline at all: a heating can hide most of a play) and each effect on mu or
the force are fitted *jointly on every sample* and judged together
(:meth:`Problem._joint_pair`, the rule of two directions too,
:func:`~isolator.diagnosis.selection.joint_pair_earns`): the pair is named when it earns its
keep over the baseline by the ``kinematic_*`` thresholds and each member earns its keep
against the other held out (``z_min``, ``practical_gain``, closing ``name_min`` of what the
other leaves).

A lag is named only as a channel can have it: the force recorded *after* the displacement
(a force leading the displacement is a speed effect's phase, not a channel), by at most
``LAG_PLAUSIBLE_MAX`` seconds, and the same in every test of the campaign (a lag fitted test by
test that differs by more than ``LAG_SPREAD`` samples, as a speed effect's apparent lag
changes with the period and the amplitude, is not a channel lag).

The verdict: ``["none"]`` when nothing is named, the sliding-phase gap is within the noise or
practically negligible, the residual inside the transition windows is not far above the noise
there (:attr:`Problem.transition_gap`) and no nuisance of the baseline sits at the edge of its
range (u_y at the top of its grid: a play or a soft transition it may be standing in for);
the named effects, then ``"unexplained"`` when a real gap remains in the sliding phase (or the
u_y finding); ``["unexplained"]`` when a real gap remains that no candidate closes.
``Selection.findings`` says where such a gap lies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from itertools import combinations

import numpy as np

from isolator.diagnosis.baseline import RIGID_PLASTIC_LIMIT, YIELD_DISPLACEMENT_MAX
from isolator.diagnosis.effects import Context, Effect
from isolator.diagnosis.features import Features, return_map, with_baseline
from isolator.diagnosis.fitting import Fit, HoldOut, Model, fit, kinematic_change
from isolator.diagnosis.flexible import FINE_KNOTS, KNOTS, direction, flexible
from isolator.diagnosis.implied import ImpliedHeat, temperature_slope
from isolator.diagnosis.selection import (
    MAX_EFFECTS,
    MAX_KINEMATIC,
    SCREENED,
    Assessment,
    Selection,
    Stage,
    Workspace,
    assess,
    improvement,
    joint_pair_earns,
    material,
    on_samples,
    qualifies,
    untestable,
    verdict_of,
)
from isolator.diagnosis.thresholds import Thresholds
from isolator.diagnosis.transition import TIMING, in_transition, window_statistics

LAG_PLAUSIBLE_MAX = 0.1  # [s] the largest lag a laboratory channel can plausibly have
LAG_SPREAD = 1.0  # [samples] per-test lags of one channel agree within this (or 20 %)
IMPLIED_HEAT = "implied heat"  # the baseline's own heat with the named laws' mu (never named)
IMPLIED_REFITS = 8  # the chosen model's refits with the implied heat, at most
IMPLIED_TOLERANCE = 1e-4  # [-] ... until its log temperature factor moves less than this


def lag_reason(samples: float, sample_interval: float, per_test: np.ndarray,
               th: Thresholds) -> str | None:
    """Why a fitted lag of ``samples`` [samples] at ``sample_interval`` [s] is not a channel's,
    or None when it can be (the module docstring): ``per_test`` holds the lag fitted test by
    test [samples] (empty when not computed; needed only past the first two checks)."""
    if samples < th.lag_min_samples:
        return ("the force leads the displacement: a speed effect's phase, not a channel"
                if samples <= -th.lag_min_samples else "smaller than a lag can be named")
    seconds = samples * sample_interval
    if seconds > LAG_PLAUSIBLE_MAX:
        return (f"a lag of {1e3 * seconds:.1f} ms fits, beyond what a laboratory channel "
                f"plausibly has ({1e3 * LAG_PLAUSIBLE_MAX:.0f} ms): not named as a lag (a speed "
                "effect or the rig's dynamics look like one)")
    if per_test.size >= 2 and np.ptp(per_test) > max(LAG_SPREAD, 0.2 * abs(samples)):
        return ("the lag fitted test by test varies ("
                + ", ".join(f"{x:+.1f}" for x in per_test)
                + " samples): not one channel lag for the campaign (a speed effect looks like "
                "a lag that changes with the period and the amplitude)")
    return None


def grid_minima(grid: np.ndarray, sse: np.ndarray, step: float) -> np.ndarray:
    """The minimum of each column of ``sse`` (costs on the uniform ``grid`` of spacing
    ``step``, one row a grid point), refined by a parabola through its neighbours (by at
    most one step) [units of ``grid``]; at an end of the grid, that end."""
    best = []
    for k in range(sse.shape[1]):
        j = int(np.argmin(sse[:, k]))
        if 0 < j < grid.size - 1:
            y0, y1, y2 = sse[j - 1, k], sse[j, k], sse[j + 1, k]
            curve = y0 - 2.0 * y1 + y2
            shift = 0.5 * (y0 - y2) / curve if curve > 0.0 else 0.0
            best.append(grid[j] + step * float(np.clip(shift, -1.0, 1.0)))
        else:
            best.append(float(grid[j]))
    return np.array(best)


class Problem:
    """What every decision on one campaign shares (features, folds, the candidates' fits,
    cached), so that :meth:`select` repeats cheaply with other thresholds or effects withheld.

    Parameters
    ----------
    features, context : Features, Context
        The calibrated baseline's features (weights set) and the campaign's constants (with
        its :class:`~isolator.diagnosis.fitting.Kinematics`).
    effects : tuple of Effect
        The candidates.
    thresholds : Thresholds
        Used for the candidates' own ``earns_keep`` flags (the decisions take their own).
    edges : dict, optional
        The baseline's nuisance parameters fitted at an edge of their range
        (:func:`isolator.diagnosis.baseline.nuisance_edges`), e.g.
        ``{"yield_displacement": "top"}``.
    implied : callable, optional
        For a baseline that heats, the change of its log temperature factor at every sample
        when its friction power is multiplied by a factor on mu
        (:func:`isolator.diagnosis.implied.implied_heat`); a second effect on mu must earn its
        keep over the named law with that heat too (:meth:`_implied_reference`).
    """

    def __init__(self, features: Features, context: Context, effects: tuple[Effect, ...],
                 thresholds: Thresholds, edges: dict[str, str] | None = None,
                 implied: ImpliedHeat | None = None) -> None:
        self.features = features
        self.context = context
        self.effects = effects
        self.thresholds = thresholds
        self.edges = dict(edges or {})
        self.implied = implied
        self.window = in_transition(features, context.yield_displacement)
        self.all = Workspace(features, HoldOut.of(features), context)
        self.all_baseline = assess(self.all, Model(), None, [np.array([1.0])])
        self.kinematic = {e.name: self._assess_kinematic(e) for e in effects
                          if e.acts_on == "kinematics"}
        self._stages: dict[tuple[str, ...], Stage] = {}

    # -- stage 1 -----------------------------------------------------------------------------

    def _assess_kinematic(self, effect: Effect) -> Assessment:
        model = Model((effect,))
        reason = effect.untestable(self.context)
        if reason is not None:
            return untestable(model, reason)
        return assess(self.all, model, self.all_baseline, thresholds=self.thresholds)

    def _kinematic_size_ok(self, a: Assessment, th: Thresholds) -> bool:
        for effect, part in zip(a.model.effects, a.model.slices(), strict=True):
            values = effect.physical_parameters(a.fit.theta[part], a.fit.stderr[part],
                                                self.context)
            if effect.name == "lag" and not self._lag_plausible(
                    values["lag_samples"][0], a, th):
                return False
            if effect.name == "backlash" and values["width"][0] < th.backlash_min:
                return False
        return True

    def _lag_plausible(self, samples: float, a: Assessment, th: Thresholds) -> bool:
        """Whether a fitted lag of ``samples`` can be a channel's (:func:`lag_reason`)."""
        per_test = (self.lag_per_test(a) if samples >= th.lag_min_samples
                    and samples * self.context.sample_interval <= LAG_PLAUSIBLE_MAX
                    else np.zeros(0))
        return lag_reason(samples, self.context.sample_interval, per_test, th) is None

    def lag_per_test(self, a: Assessment) -> np.ndarray:
        """The lag [samples] that fits each test best, the other parameters of the model ``a``
        (which holds ``lag``) held: a grid of half samples around the campaign's lag, refined
        by a parabola."""
        key = ("lag_per_test", *a.model.names, *map(float, a.fit.theta))
        if key in self.all.cache:
            return self.all.cache[key]
        names = a.model.names
        i = next(sl for n, sl in zip(names, a.model.slices(), strict=True) if n == "lag").start
        f, w = self.features, self.features.weight
        grid = a.fit.theta[i] + np.arange(-6.0, 6.5, 0.5)
        tests = np.unique(f.test)
        sse = np.empty((grid.size, tests.size))
        for g, value in enumerate(grid):
            theta = np.array(a.fit.theta, dtype=float)
            theta[i] = value
            r = w * (f.force - a.model.force(theta, f, self.context)) ** 2
            sse[g] = [float(r[f.test == k].sum()) for k in tests]
        out = grid_minima(grid, sse, 0.5)
        self.all.cache[key] = out
        return out

    # -- the transition window ---------------------------------------------------------------

    def window_statistics(self, prediction: np.ndarray) -> tuple[float, float]:
        """(mean squared residual over the noise variance inside the transition windows [-],
        the excess above noise there as an RMS over the whole test, over the RMS force [-])
        of a ``prediction`` at every sample."""
        f, w = self.features, self.window
        if not w.any():
            return 1.0, 0.0
        return window_statistics((f.force[w] - prediction[w]) ** 2, f.noise_variance[w], len(f),
                                 np.mean(f.force**2))

    def transition_gap(self, prediction: np.ndarray, th: Thresholds) -> bool:
        """Whether the residual of ``prediction`` inside the transition windows is far above
        the noise there (``transition_score``) and material over the whole test
        (``transition_practical``)."""
        score, excess = self.window_statistics(prediction)
        return score >= th.transition_score and excess >= th.transition_practical

    def full_force(self, chosen: Assessment) -> np.ndarray:
        """The force of ``chosen`` (fitted on the sliding phase) at every sample [N]."""
        key = ("full", *chosen.model.names, *map(float, chosen.fit.theta))
        if key not in self.all.cache:
            self.all.cache[key] = chosen.model.force(chosen.fit.theta, self.features,
                                                     self.context)
        return self.all.cache[key]

    def window_after(self, chosen: Assessment) -> tuple[float, float]:
        """:meth:`window_statistics` of ``chosen`` with the transition's u_y refitted to it (a
        nuisance calibrated without the named effects can be biased by them, as an effect at
        low speed softens the reversals): the least excess over u_y from a quarter to three
        times the baseline's (kinematic effects keep their own u_y)."""
        key = ("window_after", *chosen.model.names, *map(float, chosen.fit.theta))
        if key in self.all.cache:
            return self.all.cache[key]
        best = self.window_statistics(self.full_force(chosen))
        if not any(e.acts_on == "kinematics" for e in chosen.model.effects):
            u_y = self.context.yield_displacement
            for factor in (0.25, 0.5, 0.7, 1.4, 2.0, 3.0):
                u = min(max(u_y * factor, RIGID_PLASTIC_LIMIT), YIELD_DISPLACEMENT_MAX)
                moved = with_baseline(self.features, z=return_map(self.features, u))
                stats = self.window_statistics(
                    chosen.model.force(chosen.fit.theta, moved, self.context))
                if stats[1] < best[1]:
                    best = stats
        self.all.cache[key] = best
        return best

    def _provisional(self, exclude: tuple[str, ...], th: Thresholds) -> list[Assessment]:
        """Kinematic candidates that close their share on every sample and are of a
        plausible size, but miss the z threshold (a friction law may be hiding them)."""
        out = []
        for name, a in self.kinematic.items():
            if name in exclude or a.untestable is not None or not a.z_score > 0.0:
                continue
            if (a.explained >= th.kinematic_explained and self._kinematic_size_ok(a, th)
                    and plausible(a)):
                out.append(a)
        return sorted(out, key=lambda a: a.weighted)

    def _assessed(self, kind: str, effects: tuple[Effect, ...]) -> Assessment:
        """A model of ``effects`` alone assessed on every sample, kept in the cache under
        ``kind`` (``"law"`` or ``"kinematic"``) and the effects' names."""
        key = (kind, *(e.name for e in effects))
        if key not in self.all.cache:
            self.all.cache[key] = assess(self.all, Model(effects), None)
        return self.all.cache[key]

    def _jointly(self, candidate: Assessment, law: tuple[Effect, ...],
                 th: Thresholds) -> Assessment | None:
        """``candidate`` (one kinematic effect) when, as a pair with the friction-law effects
        ``law``, it earns its keep over the baseline on every sample by ``kinematic_z`` (a pair
        is judged as one, as in stage 2) and, beside the law, still closes its share
        (``kinematic_explained``) by a practical force (``kinematic_practical``)."""
        current = self._assessed("law", law)
        judged = self._extended(self.all, current, (candidate,))
        z, _ = improvement(self.all, self.all_baseline, judged)
        _, beside = improvement(self.all, current, judged)
        size = self.all.gain_rms(current.prediction, judged.prediction)
        if (z >= th.kinematic_z and beside >= th.kinematic_explained
                and size >= th.kinematic_practical and self._kinematic_size_ok(judged, th)
                and plausible(judged, len(current.model.effects))):
            return candidate
        return None

    def _joint_pair(self, kinematic: Assessment | None, exclude: tuple[str, ...],
                    th: Thresholds) -> tuple[Assessment, str] | None:
        """(the kinematic effect alone, the friction-law effect's name) of the best pair of a
        kinematic effect and one effect on mu or the force, fitted jointly on every sample,
        that :func:`~isolator.diagnosis.selection.joint_pair_earns` (over the baseline, over
        the kinematic effect alone and over the law alone, held out), when no friction law
        is named and a real gap remains on every sample; the kinematic effect is the one
        named, else each that improves on the baseline held out (z > 0), of a nameable size,
        within its range: a friction law can hide most of a play, so its own z and share
        need not reach their bars; the pair's rule judges. None when no pair does."""
        if kinematic is not None:
            if len(kinematic.model.effects) != 1:
                return None
            tried = [kinematic]
        else:
            tried = [a for n, a in self.kinematic.items()
                     if n not in exclude and a.untestable is None and a.z_score > 0.0
                     and self._kinematic_size_ok(a, th) and plausible(a)]
        plain = self.stage(None)
        best = None
        for alone in tried:
            left = alone.prediction
            if not material(self.all.score(left), self.all.excess_rms(left),
                            th.practical_remain, th):
                continue
            for name, single in plain.singles.items():
                if name in exclude or single.untestable is not None:
                    continue
                law_alone = self._assessed("law", (single.model.effects[-1],))
                pair = self._extended(self.all, law_alone, (alone,))
                scores = []
                for reference in (self.all_baseline, alone, law_alone):
                    z, gain = improvement(self.all, reference, pair)
                    scores.append((z, gain, self.all.gain_rms(reference.prediction,
                                                              pair.prediction)))
                if not (joint_pair_earns(*scores, th) and plausible(pair)
                        and self._kinematic_size_ok(pair, th)):
                    continue
                if best is None or pair.weighted < best[0].weighted:
                    best = (pair, alone, name)
        return None if best is None else (best[1], best[2])

    def _stage_one(self, exclude: tuple[str, ...], th: Thresholds,
                   law: tuple[Effect, ...] = ()) -> Assessment | None:
        """The kinematic effects that earn their keep on every sample, over the baseline
        extended by the friction-law effects ``law`` (named in a first pass of stage 2)."""
        pool = [a for n, a in self.kinematic.items()
                if n not in exclude and a.untestable is None]
        current = self.all_baseline
        if law:
            current = self._assessed("law", law)
        first = len(law)
        while len(current.model.effects) - first < MAX_KINEMATIC:
            options = []
            for a in pool:
                if a.model.names[0] in current.model.names:
                    continue
                judged = (a if not current.model.effects
                          else self._extended(self.all, current, (a,)))
                if (qualifies(self.all, current, judged, th.kinematic_z,
                              th.kinematic_explained, th.kinematic_practical)
                        and self._kinematic_size_ok(judged, th)
                        and plausible(judged, len(current.model.effects))):
                    options.append(judged)
            if not options:
                break
            current = min(options, key=lambda a: a.weighted)
        if len(current.model.effects) == first:
            return None
        if first:  # the kinematic effects alone, fitted on every sample
            kinematic = tuple(e for e in current.model.effects[first:])
            names = tuple(e.name for e in kinematic)
            if len(names) == 1:
                return self.kinematic[names[0]]
            return self._assessed("kinematic", kinematic)
        return current

    # -- stage 2 -----------------------------------------------------------------------------

    def stage(self, kinematic: Assessment | None) -> Stage:
        """The sliding-phase stage with the kinematic effects of ``kinematic`` applied."""
        key = () if kinematic is None else kinematic.model.names
        if key in self._stages:
            return self._stages[key]
        f = self.features
        plain_window = in_transition(f, self.context.yield_displacement)
        keep = ~plain_window
        base_model = Model()
        start = [np.array([1.0])]
        if kinematic is not None:
            base_model = kinematic.model
            start = [kinematic.fit.theta]
            change = kinematic_change(zip(base_model.effects, base_model.slices(), strict=True),
                                      kinematic.fit.theta, self.context)
            _, _, engaged = self.context.kinematics.recompute(**change)
            u_y = change["yield_displacement"] or self.context.yield_displacement
            keep &= ~in_transition(f, max(u_y, self.context.yield_displacement),
                                   change["half_width"])
            keep &= engaged[f.sample] > 0.5
        sliding = f.take(np.flatnonzero(keep))
        work = Workspace(sliding, HoldOut.of(sliding), self.context)
        # the kinematic effects' parameters stay at their fit on every sample; the channel
        # timing is refitted with every model (a nuisance, never named)
        frozen = _frozen(base_model, start[0]) if kinematic is not None else base_model
        if not math.isinf(self.context.effective_radius):
            frozen = Model((*frozen.effects, TIMING))
        baseline = assess(work, frozen, None, [frozen.initial()])
        plain = on_samples(self.all_baseline.prediction, f.sample, sliding.sample)
        singles: dict[str, Assessment] = {}
        for effect in self.effects:
            if effect.acts_on == "kinematics":
                continue
            model = Model((*frozen.effects, effect))
            reason = effect.untestable(self.context)
            singles[effect.name] = (
                untestable(model, reason) if reason is not None
                else assess(work, model, baseline, thresholds=self.thresholds))
        stage = Stage(work, baseline, plain, singles)
        self._stages[key] = stage
        return stage

    def _pass(self, kinematic: Assessment | None, exclude: tuple[str, ...], th: Thresholds,
              retry: bool = True):
        """Stage 2 over ``kinematic``, and, when it names a friction law and no kinematic
        effect is named yet, stage 1 again beside that law (``retry``)."""
        for _ in range(2):
            stage = self.stage(kinematic)
            testable, noise_like = _screened(stage, exclude, th)
            current, named, form = stage.baseline, [], {}
            if not noise_like:
                current, named, form = self._forward(stage, testable, th)
            if not retry or kinematic is not None or not named:
                break
            law = tuple(e for e in current.model.effects
                        if e.name in named and e.acts_on != "kinematics")
            again = self._stage_one(exclude, th, _own_forms(law, stage.singles))
            if again is None:
                break
            kinematic = again
        return kinematic, stage, testable, noise_like, current, named, form

    def select(self, exclude: tuple[str, ...] = (),
               thresholds: Thresholds | None = None) -> Selection:
        """The decision with ``exclude`` withheld, under ``thresholds`` (default: the problem's)."""
        th = thresholds or self.thresholds
        exclude = tuple(exclude)
        kinematic = self._stage_one(exclude, th)
        kinematic, stage, testable, noise_like, current, named, form = self._pass(
            kinematic, exclude, th)
        if kinematic is None:
            # a play and a friction law hiding each other: the law found with the play
            # applied provisionally, then the play judged again beside that law
            for candidate in self._provisional(exclude, th):
                _, st, _, _, law_model, law_named, _ = self._pass(candidate, exclude, th,
                                                                  retry=False)
                excess = st.baseline.weighted - st.work.weighted_noise
                closed = ((st.baseline.weighted - law_model.weighted) / excess
                          if excess > 0.0 else 0.0)
                if closed < th.name_min:  # no nameable law hid it
                    continue
                law = tuple(e for e in law_model.model.effects
                            if e.name in law_named and e.acts_on not in ("kinematics",))
                law = tuple(e for e in law if e.name != "timing")
                if not law:
                    continue
                st = self.stage(candidate)
                again = self._stage_one(exclude, th, _own_forms(law, st.singles))
                if again is None:
                    again = self._jointly(candidate, _own_forms(law, st.singles), th)
                if again is None:
                    continue
                kinematic = again
                kinematic, stage, testable, noise_like, current, named, form = self._pass(
                    kinematic, exclude, th, retry=False)
                break
        joint = None
        if not named:
            # a play and a friction law fitted jointly on every sample and judged together
            # (neither reaching its own bar alone or beside the other)
            joint = self._joint_pair(kinematic, exclude, th)
        if joint is not None:
            kinematic, law_name = joint
            stage = self.stage(kinematic)
            testable, noise_like = _screened(stage, exclude, th)
            named = [law_name]
            current, form = self._reported_form(stage.work, stage.singles[law_name],
                                                len(stage.baseline.model.effects), th)
        work, base = stage.work, stage.baseline
        excess = base.weighted - work.weighted_noise
        explained = (base.weighted - current.weighted) / excess if excess > 0.0 else 0.0
        left = work.excess_rms(current.prediction)
        real_gap = material(current.score, left, th.practical_remain, th)
        kin_names = [] if kinematic is None else list(kinematic.model.names)
        if named and explained < th.name_min and joint is None:  # stand-ins, not named
            named, real_gap, current, form, explained = [], True, base, {}, 0.0
        carried = (self.carried(work, current, len(base.model.effects)) if named
                   else None)
        if carried is not None and carried[1].fits:
            # the baseline's own heat follows the named laws' friction power: the model
            # reported carries it (the names were decided without it)
            current = carried[0]
            explained = ((base.weighted - current.weighted) / excess if excess > 0.0
                         else 0.0)
            left = work.excess_rms(current.prediction)
            real_gap = material(current.score, left, th.practical_remain, th)
        findings: list[str] = []
        if real_gap and not noise_like:
            findings.append("sliding")
        chosen = current if (named or kin_names) else None
        # the materiality rule covers the whole test: the transition windows too
        # (once effects are named, what the windows still hold is reported beside the verdict,
        # ``transition.after_named`` in the JSON, not in it: a law fitted on the sliding phase
        # extrapolates to the low speeds of the reversals, see docs/diagnosis.md)
        if chosen is None and self.transition_gap(self.all_baseline.prediction, th):
            findings.append("transition")
        if self.edges.get("yield_displacement") == "top" and "backlash" not in kin_names:
            findings.append("yield_displacement at the top of its range")
        real_gap = (real_gap if named or kin_names else False) or bool(findings)
        verdict = verdict_of(kin_names + named, real_gap)
        order = [n for n in verdict if n not in ("unexplained", "none")]
        rest = sorted((a for a in [*self.kinematic.values(), *testable]
                       if a.untestable is None and a.model.names[-1] not in order),
                      key=lambda a: work.nrmse(_prediction_on_samples(a, self.features, work)))
        order += [a.model.names[-1] for a in rest if a.model.names[-1] not in exclude]
        order += [n for n, a in {**self.kinematic, **stage.singles}.items()
                  if a.untestable is not None and n not in exclude and n not in order]
        return Selection(stage, kinematic, {n: a for n, a in self.kinematic.items()
                                            if n not in exclude},
                         chosen, verdict, explained, real_gap, order, form, th,
                         _all=self.features.sample, findings=tuple(findings),
                         implied=None if carried is None else carried[1])

    def _forward(self, stage: Stage, testable: list[Assessment],
                 th: Thresholds) -> tuple[Assessment, list[str], dict[str, str]]:
        """Forward selection on the sliding phase (see the module docstring)."""
        work, current = stage.work, stage.baseline
        frozen = len(current.model.effects)
        named: list[str] = []
        while len(named) < MAX_EFFECTS:
            free = [a for a in testable if a.model.names[-1] not in named]
            if not named:
                step = self._best(work, current, [(a,) for a in free], th.z_min,
                                  th.explained_min, th.practical_gain)
                if step is None:
                    step = self._best(work, current, list(combinations(free, 2)), th.z_min,
                                      th.explained_min, th.practical_gain)
            else:
                reference = self._flexible_reference(work, current, frozen)
                step = self._best(work, reference, [(a,) for a in free], th.second_z,
                                  th.second_explained, th.practical_gain,
                                  also=self._implied_reference(work, current, frozen))
            if step is None:
                break
            current = step
            named = list(current.model.names[frozen:])
        form = {}
        if named:
            current, form = self._reported_form(work, current, frozen, th)
        return current, named, form

    def _flexible_reference(self, work: Workspace, current: Assessment,
                            frozen: int, knot_count: int = KNOTS) -> Assessment:
        """``current`` with its friction-law effects on mu in flexible form (``knot_count``
        knots), if that is better on held-out data."""
        effects = list(current.model.effects)
        theta = current.fit.theta
        changed = False
        for i, (effect, part) in enumerate(zip(effects, current.model.slices(), strict=True)):
            if i < frozen or effect.acts_on != "mu" or effect.variable is None:
                continue
            if effect.name == "asymmetry":
                continue
            up = direction(effect, theta[part], work.features, work.context)
            effects[i] = flexible(effect, self.features, self.context, up, knot_count)
            changed = True
        if not changed:
            return current
        model = Model(tuple(effects))
        key = ("flexible", knot_count, *model.names)
        if key not in work.cache:
            work.cache[key] = assess(work, model, None)
        candidate = work.cache[key]
        return candidate if candidate.weighted < current.weighted else current

    def _reported_form(self, work: Workspace, current: Assessment, frozen: int,
                       th: Thresholds) -> tuple[Assessment, dict[str, str]]:
        # the named law's shape: its own (paper) form, the flexible form that judges a second
        # effect, or a finer one, whichever predicts the held-out samples best
        flex = min((self._flexible_reference(work, current, frozen, knot_count)
                    for knot_count in (KNOTS, FINE_KNOTS)), key=lambda a: a.weighted)
        form = {e.name: "paper" for e in current.model.effects[frozen:] if e.acts_on == "mu"}
        if flex is current:
            return current, form
        excess = current.weighted - work.weighted_noise
        if excess > 0.0 and (current.weighted - flex.weighted) / excess >= th.flexible_margin:
            for e in flex.model.effects[frozen:]:
                if e.acts_on == "mu" and e.name != "asymmetry":
                    form[e.name] = "flexible"
            return flex, form
        return current, form

    def _best(self, work: Workspace, current: Assessment,
              additions: list[tuple[Assessment, ...]], z_min: float, explained_min: float,
              practical: float, also: Assessment | None = None) -> Assessment | None:
        """The best qualifying extension of ``current`` (screened in-sample), qualifying over
        ``also`` too when given (the named law with the heat it implies)."""
        fitted = [self._extended_fit(work, current, add) for add in additions]
        fitted.sort(key=lambda item: item[1].sse)
        options = []
        for model, full in fitted[:SCREENED]:
            judged = self._judged(work, model, full)
            if (qualifies(work, current, judged, z_min, explained_min, practical)
                    and (also is None
                         or qualifies(work, also, judged, z_min, explained_min, practical))
                    and plausible(judged, len(current.model.effects))):
                options.append(judged)
        return min(options, key=lambda a: a.weighted) if options else None

    def _heat_parts(self, model: Model, frozen: int) -> list[tuple[Effect, slice]]:
        """(effect, parameter slice) of the laws on mu of ``model`` from position ``frozen``
        on whose friction power a heating baseline's temperature follows (``heating`` and the
        implied heat itself left out)."""
        return [(e, part) for i, (e, part) in enumerate(zip(model.effects, model.slices(),
                                                            strict=True))
                if i >= frozen and e.acts_on == "mu" and e.factor is not None
                and e.name not in ("heating", IMPLIED_HEAT)]

    def _implied_log(self, parts: list[tuple[Effect, slice]], theta: np.ndarray) -> np.ndarray:
        """The change of the baseline's log temperature factor at every sample [-] when its
        mu is the model's (mu's scale ``theta[0]`` times the laws ``parts`` at ``theta``)."""
        m = np.full(len(self.features), float(theta[0]))  # mu's scale
        for effect, part in parts:
            m = m * effect.factor(theta[part], self.features, self.context)
        return self.implied(m)

    def _implied_reference(self, work: Workspace, current: Assessment,
                           frozen: int) -> Assessment | None:
        """``current`` with the heat its named laws on mu imply for a baseline that heats
        (:mod:`isolator.diagnosis.implied`: the baseline's temperature factor recomputed with
        the named laws' friction power, held fixed; the other parameters refitted), judged
        held out; None when the baseline does not heat or no law on mu other than
        ``heating`` is named. A second effect on mu must earn its keep over it too: what a
        baseline's heat computed with the wrong mu leaves is not a second effect."""
        if self.implied is None:
            return None
        parts = self._heat_parts(current.model, frozen)
        if not parts:
            return None
        key = ("implied", *current.model.names, *map(float, current.fit.theta))
        if key not in work.cache:
            effect = _heat_effect(self._implied_log(parts, current.fit.theta),
                                  self.features.sample, "the baseline's heat with the named "
                                  "law's mu")
            model = Model((*current.model.effects, effect))
            work.cache[key] = assess(work, model, None, [np.array(current.fit.theta)])
        return work.cache[key]

    def carried(self, work: Workspace, current: Assessment,
                frozen: int) -> tuple[Assessment, ImpliedFit] | None:
        """``current`` (the chosen model, its named laws from position ``frozen`` on) carrying
        the heat its laws on mu imply for a baseline that heats: the baseline's own
        temperature computed with the chosen model's friction power, never an effect of its
        own. The laws are refitted *with* that heat to consistency (the heat from the
        parameters, the parameters refitted with the heat held, until the log temperature
        factor moves less than ``IMPLIED_TOLERANCE``, at most ``IMPLIED_REFITS`` refits), on
        all samples of ``work`` and in every fold (each fold's heat from its own parameters,
        so the held-out prediction stays held out). None when the baseline does not heat or
        no law on mu other than ``heating`` is named."""
        if self.implied is None or current.fit is None:
            return None
        parts = self._heat_parts(current.model, frozen)
        if not parts:
            return None
        key = ("carried", *current.model.names, *map(float, current.fit.theta))
        if key in work.cache:
            return work.cache[key]
        samples, context = self.features.sample, work.context
        law = current.model
        low, high = law.bounds()

        def consistent(train: Features, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray,
                                                                     int]:
            log = self._implied_log(parts, theta)
            refits, last = 0, None
            while refits < IMPLIED_REFITS:
                model = Model((*law.effects, _heat_effect(log, samples)))
                new_theta = fit(model, train, context, [theta]).theta
                refits += 1
                new = self._implied_log(parts, new_theta)
                moved = float(np.max(np.abs(new - log)))
                if moved < IMPLIED_TOLERANCE:
                    theta, log = new_theta, new
                    break
                ratio = moved / last if last else 0.0
                if 0.0 < ratio < 0.9:
                    # the refits converge geometrically (a higher friction heats more, which
                    # the scale of mu answers): jump to the limit of the sequence
                    new_theta = np.clip(new_theta + ratio / (1.0 - ratio) * (new_theta - theta),
                                        low, high)
                    new = self._implied_log(parts, new_theta)
                    last = None
                else:
                    last = moved
                theta, log = new_theta, new
            return theta, log, refits

        theta, log, refits = consistent(work.features, np.array(current.fit.theta, float))
        model = Model((*law.effects, _heat_effect(log, samples)))
        full = fit(model, work.features, context, [theta], uncertainty=True)
        full = replace(full, theta=theta)  # the parameters the heat is consistent with
        prediction = np.empty(len(work.features))
        folds = work.holdout
        for (_, te), train, held in zip(folds.folds, folds.training, folds.held_out,
                                        strict=True):
            own = fit(law, train, context, [np.array(current.fit.theta, float)]).theta
            own, own_log, _ = consistent(train, own)
            prediction[te] = Model((*law.effects, _heat_effect(own_log, samples))).force(
                own, held, context)
        judged = work.judge(model, full, prediction)
        info = ImpliedFit(tuple(e.name for e, _ in parts), refits, log, judged, current)
        work.cache[key] = (judged, info)
        return work.cache[key]

    def _extended(self, work: Workspace, current: Assessment,
                  additions: tuple[Assessment, ...]) -> Assessment:
        model, full = self._extended_fit(work, current, additions)
        return self._judged(work, model, full)

    def _extended_fit(self, work: Workspace, current: Assessment,
                      additions: tuple[Assessment, ...]) -> tuple[Model, Fit]:
        """``current`` extended by the last effect of each of ``additions``, fitted on all
        samples of ``work``."""
        own = [a.model.effects[-1] for a in additions]
        if len(own) == 1 and additions[0].model.effects[:-1] == current.model.effects:
            return additions[0].model, additions[0].fit
        model = Model(current.model.effects + tuple(own))
        key = ("fit", *model.names, *(e.description for e in model.effects))
        if key not in work.cache:
            own_theta = [a.fit.theta[a.model.slices()[-1]] for a in additions]
            scales = [current.fit.theta[0], *(a.fit.theta[0] for a in additions)]
            starts = [np.concatenate([[scale], current.fit.theta[1:], *own_theta])
                      for scale in scales]
            work.cache[key] = fit(model, work.features, work.context, starts, uncertainty=True)
        return model, work.cache[key]

    def _judged(self, work: Workspace, model: Model, full: Fit) -> Assessment:
        key = ("judged", *model.names, *(e.description for e in model.effects))
        if key not in work.cache:
            prediction, _ = work.holdout.predict(model, work.context, start=full.theta)
            work.cache[key] = work.judge(model, full, prediction)
        return work.cache[key]


def _screened(stage: Stage, exclude: tuple[str, ...],
              th: Thresholds) -> tuple[list[Assessment], bool]:
    """The testable single effects of ``stage`` not in ``exclude``, the weakest first, and
    whether its baseline leaves only noise (no material excess under ``th.practical_none``)."""
    work, base = stage.work, stage.baseline
    testable = sorted((a for n, a in stage.singles.items()
                       if n not in exclude and a.untestable is None), key=lambda a: a.weighted)
    return testable, not material(base.score, work.excess_rms(base.prediction),
                                  th.practical_none, th)


def _own_forms(law: tuple[Effect, ...], singles: dict[str, Assessment]) -> tuple[Effect, ...]:
    """The library's own (paper) form of each effect of ``law``."""
    return tuple(singles[e.name].model.effects[-1] if e.name in singles else e for e in law)


def plausible(a: Assessment, first: int = 0) -> bool:
    """Whether none of the effects from position ``first`` on sits at a bound of a parameter
    (see :class:`isolator.diagnosis.effects.Parameter`)."""
    for effect, part in list(zip(a.model.effects, a.model.slices(), strict=True))[first:]:
        for parameter, value in zip(effect.parameters, a.fit.theta[part], strict=True):
            if parameter.at_bound(float(value)):
                return False
    return True


def _prediction_on_samples(a: Assessment, features: Features, work: Workspace) -> np.ndarray:
    if a.prediction.size == len(work.features):
        return a.prediction
    return on_samples(a.prediction, features.sample, work.features.sample)


def _frozen(model: Model, theta: np.ndarray) -> Model:
    """``model`` with its effects' parameters held at ``theta`` (only the scale is free)."""
    effects = []
    for effect, part in zip(model.effects, model.slices(), strict=True):
        fixed = np.array(theta[part], dtype=float)
        effects.append(replace(
            effect, parameters=(),
            kinematic=(None if effect.kinematic is None
                       else (lambda _t, c, e=effect, v=fixed: e.kinematic(v, c))),
            factor=(None if effect.factor is None
                    else (lambda _t, f, c, e=effect, v=fixed: e.factor(v, f, c))),
            extra=(None if effect.extra is None
                   else (lambda _t, f, c, e=effect, v=fixed: e.extra(v, f, c)))))
    return Model(tuple(effects))


@dataclass(frozen=True, eq=False)
class ImpliedFit:
    """How the chosen model carries the heat its laws on mu imply (:meth:`Problem.carried`).

    Attributes
    ----------
    laws : tuple of str
        The named laws on mu whose friction power the baseline's temperature follows.
    refits : int
        Refits of the laws with the heat until it was consistent with their parameters.
    log_change : ndarray
        The change of the baseline's log temperature factor at every sample [-].
    carrying, without : Assessment
        The chosen model carrying the implied heat, and without it (the laws as named,
        fitted on their own), both judged held out.
    """

    laws: tuple[str, ...]
    refits: int
    log_change: np.ndarray
    carrying: Assessment
    without: Assessment

    @property
    def fits(self) -> bool:
        """Whether the model carrying the heat fits at least as well held out (weighted mean
        square) as without it, so that the chosen model carries it: a baseline whose heat
        is off in another way (a campaign's heat carried over its rests, which it starts
        cold) can fit worse with the named law's friction power."""
        return self.carrying.weighted <= self.without.weighted

    @property
    def temperature_change(self) -> np.ndarray:
        """The change of the baseline's contact temperature at every sample [degC]."""
        return self.log_change / temperature_slope()


def _heat_effect(log_change: np.ndarray, samples: np.ndarray,
                 description: str = "the baseline's own heat with the named laws' mu"
                 ) -> Effect:
    """The baseline's temperature factor changed by ``exp(log_change)`` (given at every one of
    ``samples``), as an effect without parameters on mu."""
    return Effect(IMPLIED_HEAT, description,
                  "the baseline's own temperature factor, its heat input computed with the named "
                  "law's friction power", (), "mu",
                  factor=lambda _t, f, _c: np.exp(on_samples(log_change, samples, f.sample)))
