"""Fitting a baseline extended by candidate effects, on training data, judged on held-out data.

:func:`fit` is a bounded Levenberg-Marquardt fit (:mod:`isolator.diagnosis.solver`) of a
:class:`Model`'s force residual, each sample weighted by ``Features.weight``.
:meth:`HoldOut.predict` gives every sample's force from the fit that did not see it, so every
error (RMS, per cycle) is measured on held-out data.

Standard errors come from the Jacobian at the fit on all data, (J^T J)^-1 s^2, inflated for
the serial correlation of the residual by sqrt((1 + rho) / (1 - rho)), rho its lag-one
autocorrelation (an AR(1) residual carries fewer independent samples than it has).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from dcfpb.common.errors import InputError
from isolator.diagnosis.effects import Context, Effect
from isolator.diagnosis.features import Features
from isolator.diagnosis.kinematics import hysteretic_variable, play_return_map, shifted
from isolator.diagnosis.solver import levenberg_marquardt

SCALE_BOUNDS = (0.02, 50.0)  # the baseline's scale c may change mu by this much at most
_MIN_TESTS_FOR_TEST_HOLDOUT = 3
MAX_FOLDS = 6  # more tests than this are held out in groups (test k in fold k mod 6)
MAX_FIT_SAMPLES = 20000  # longer training sets are thinned to every k-th sample for the fit


@dataclass(frozen=True, eq=False)
class Kinematics:
    """The campaign's contiguous histories, for effects that act on the kinematics.

    Attributes
    ----------
    time, displacement, axial_force : tuple of ndarray
        Per test: sample times [s], the displacement as measured (smoothed, no channel lag
        applied) [m] and the axial force [N].
    yield_displacement, effective_radius, nominal_mu : float
        The baseline's u_y [m], R_eff [m] and mean friction coefficient [-].
    """

    time: tuple[np.ndarray, ...]
    displacement: tuple[np.ndarray, ...]
    axial_force: tuple[np.ndarray, ...]
    yield_displacement: float
    effective_radius: float
    nominal_mu: float
    _memo: dict = field(default_factory=dict, compare=False, repr=False)

    def recompute(self, shift: float = 0.0, half_width: float = 0.0,
                  yield_displacement: float | None = None,
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(displacement of the bearing [m], z [-], engaged [-]) over the whole campaign for a
        further channel lag ``shift`` [s], a play of half width ``half_width`` [m] and a yield
        displacement (default: the baseline's) [m]."""
        u_y = self.yield_displacement if yield_displacement is None else yield_displacement
        key = (float(shift), float(half_width), float(u_y))
        if key in self._memo:
            return self._memo[key]
        inverse = 0.0 if math.isinf(self.effective_radius) else 1.0 / self.effective_radius
        parts = []
        for t, u in zip(self.time, self.displacement, strict=True):
            u = np.ascontiguousarray(shifted(t, u, shift)) if shift else u
            if half_width > 0.0:
                parts.append(play_return_map(u, float(half_width), u_y, inverse,
                                             max(self.nominal_mu, 1e-3)))
            else:
                parts.append((u, hysteretic_variable(u, u_y),
                              np.ones(u.size)))
        out = tuple(np.concatenate([p[i] for p in parts]) for i in range(3))
        if len(self._memo) > 8:
            self._memo.clear()
        self._memo[key] = out
        return out


def kinematic_change(parts, theta: np.ndarray, context: Context) -> dict[str, float]:
    """The summed changes of the kinematic effects among ``parts`` ((effect, slice) pairs)."""
    shift = half = 0.0
    u_y = None
    for effect, part in parts:
        if effect.kinematic is not None:
            change = effect.kinematic(theta[part], context)
            shift += change.get("shift", 0.0)
            half += change.get("half_width", 0.0)
            u_y = change.get("yield_displacement", u_y)
    return {"shift": shift, "half_width": half, "yield_displacement": u_y}


@dataclass(frozen=True)
class Model:
    """The calibrated baseline with ``effects`` acting on its kinematics, mu or force.

    The parameter vector is the baseline's scale c of mu, then each effect's parameters.
    """

    effects: tuple[Effect, ...] = ()

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the effects."""
        return tuple(e.name for e in self.effects)

    @property
    def label(self) -> str:
        """``"baseline"`` or the effects joined with ``+``."""
        return "+".join(self.names) or "baseline"

    @property
    def size(self) -> int:
        """Number of fitted parameters, the baseline's scale included."""
        return 1 + sum(len(e.parameters) for e in self.effects)

    def slices(self) -> list[slice]:
        """Where each effect's parameters sit in the parameter vector."""
        out, start = [], 1
        for e in self.effects:
            out.append(slice(start, start + len(e.parameters)))
            start += len(e.parameters)
        return out

    def initial(self) -> np.ndarray:
        """Start values."""
        return np.array([1.0, *(p.initial for e in self.effects for p in e.parameters)])

    @property
    def acts_on_kinematics(self) -> bool:
        """Whether an effect of the model changes the kinematics."""
        return any(e.acts_on == "kinematics" for e in self.effects)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper bounds."""
        low = [SCALE_BOUNDS[0], *(p.low for e in self.effects for p in e.parameters)]
        high = [SCALE_BOUNDS[1], *(p.high for e in self.effects for p in e.parameters)]
        return np.array(low), np.array(high)

    def force(self, theta: np.ndarray, f: Features, context: Context) -> np.ndarray:
        """Predicted force at every sample of ``f`` [N]."""
        parts = list(zip(self.effects, self.slices(), strict=True))
        engaged = None
        if self.acts_on_kinematics:
            u, z, engaged = context.kinematics.recompute(**kinematic_change(parts, theta,
                                                                            context))
            u, z, engaged = u[f.sample], z[f.sample], engaged[f.sample]
            radius = context.effective_radius
            pendulum = np.zeros(u.size) if math.isinf(radius) else f.axial_force * u / radius
            f = replace(f, displacement=u, z=z, pendulum=pendulum)
        mu = theta[0] * f.mu_base
        extra = 0.0
        for effect, part in parts:
            if effect.factor is not None:
                mu = mu * effect.factor(theta[part], f, context)
            if effect.extra is not None:
                extra = extra + effect.extra(theta[part], f, context)
        friction = mu * f.axial_force * f.z
        force = f.pendulum + friction
        for effect, part in parts:
            if effect.transform is not None:
                force = effect.transform(theta[part], f, context, f.pendulum, friction)
        force = force + extra
        return force if engaged is None else force * engaged


@dataclass(frozen=True)
class Fit:
    """A least-squares fit.

    Attributes
    ----------
    theta, stderr : ndarray
        Parameters on their fitting scale and their standard errors (NaN where not
        identifiable).
    sse, samples : float, int
        Weighted sum of squared force residuals [-] over the training samples, and their
        number.
    """

    theta: np.ndarray
    stderr: np.ndarray
    sse: float
    samples: int


def _clip_start(theta: np.ndarray, model: Model) -> np.ndarray:
    low, high = model.bounds()
    span = high - low
    return np.clip(theta, low + 1e-6 * span, high - 1e-6 * span)


def fit(
    model: Model,
    f: Features,
    context: Context,
    starts: Sequence[np.ndarray] | None = None,
    *,
    uncertainty: bool = False,
) -> Fit:
    """Least-squares fit of ``model`` to the samples ``f`` (best of the ``starts``).

    A training set longer than ``MAX_FIT_SAMPLES`` is thinned to every k-th sample (a
    campaign sampled at hundreds of hertz has far more samples per cycle than its few
    parameters need); predictions and errors always use every sample.
    """
    stride = -(-len(f) // MAX_FIT_SAMPLES)
    if stride > 1:
        f = f.take(np.arange(0, len(f), stride))
    weight = np.sqrt(f.weight)
    low, high = model.bounds()

    def residual(theta: np.ndarray) -> np.ndarray:
        return (model.force(theta, f, context) - f.force) * weight

    best = None
    starts = [_clip_start(np.asarray(s, float), model) for s in (starts or [model.initial()])]
    for start in [*starts, *_scanned(model, residual, starts)]:
        result = levenberg_marquardt(residual, start, low, high)
        if best is None or result.cost < best.cost:
            best = result
    stderr = np.full(model.size, np.nan)
    if uncertainty:
        stderr = _standard_errors(best.jacobian, best.residual, f)
    return Fit(best.x, stderr, best.cost, len(f))


SCAN_COARSE = 4  # a scanned parameter's coarse grid: this many of its steps


def _scanned(model: Model, residual, starts: list[np.ndarray]) -> list[np.ndarray]:
    """Further starts: each of ``starts`` with each parameter that has a ``scan`` step set to
    the best point of a grid over its range (the others held), where that beats the start;
    a parameter whose effect moves in whole samples has a zero finite-difference gradient,
    so the least-squares search cannot move it (:class:`~isolator.diagnosis.effects.Parameter`)."""
    low, high = model.bounds()
    scanned = [(i, p.scan) for i, p in enumerate(
        (p for e in model.effects for p in e.parameters), start=1) if p.scan > 0.0]
    def cost(theta: np.ndarray, i: int, value: float) -> float:
        theta = theta.copy()
        theta[i] = value
        return float(np.sum(residual(theta) ** 2))

    out: list[np.ndarray] = []
    for start in starts:
        for i, step in scanned:
            # a coarse grid of SCAN_COARSE steps over the range, then the step around its best
            coarse = np.arange(low[i], high[i] + 0.5 * step, SCAN_COARSE * step)
            best = coarse[int(np.argmin([cost(start, i, v) for v in coarse]))]
            fine = np.clip(best + step * np.arange(-SCAN_COARSE + 1, SCAN_COARSE), low[i], high[i])
            costs = [cost(start, i, v) for v in fine]
            j = int(np.argmin(costs))
            if costs[j] < float(np.sum(residual(start) ** 2)):
                theta = start.copy()
                theta[i] = fine[j]
                theta = _clip_start(theta, model)
                if not any(np.array_equal(theta, o) for o in out):
                    out.append(theta)
    return out


def _standard_errors(jac: np.ndarray, res: np.ndarray, f: Features) -> np.ndarray:
    n, p = jac.shape
    if n <= p:
        return np.full(p, np.nan)
    variance = float(np.einsum("i,i->", res, res)) / (n - p)
    covariance = np.linalg.pinv(np.einsum("ij,ik->jk", jac, jac)) * variance
    same_test = f.test[1:] == f.test[:-1]
    a, b = res[1:][same_test], res[:-1][same_test]
    norm = float(np.sqrt(np.einsum("i,i->", a, a) * np.einsum("i,i->", b, b)))
    rho = float(np.einsum("i,i->", a, b)) / norm if a.size > 2 and norm > 0.0 else 0.0
    rho = min(max(rho, 0.0), 0.99)
    inflation = np.sqrt((1.0 + rho) / (1.0 - rho))
    return np.sqrt(np.maximum(np.diag(covariance), 0.0)) * inflation


def multistart(model: Model) -> list[np.ndarray]:
    """Start values: the initial guess and, for each log parameter, both ends of its range."""
    starts = [model.initial()]
    position = 1
    for effect in model.effects:
        for parameter in effect.parameters:
            values = list(parameter.starts)
            if parameter.log and not values:
                values = [parameter.low + frac * (parameter.high - parameter.low)
                          for frac in (0.2, 0.8)]
            for value in values:
                start = model.initial()
                start[position] = value
                starts.append(start)
            position += 1
    return starts


@dataclass(frozen=True)
class HoldOut:
    """The folds of a campaign and their features.

    Attributes
    ----------
    scheme : str
        ``"leave-one-test-out"``, ``"tests held out in N groups"`` or ``"alternate cycles"``.
    folds : tuple of (ndarray, ndarray)
        (training indices, held-out indices) of each fold.
    training, held_out : tuple of Features
        The training and the held-out features of each fold.
    """

    scheme: str
    folds: tuple[tuple[np.ndarray, np.ndarray], ...]
    training: tuple[Features, ...]
    held_out: tuple[Features, ...]

    @classmethod
    def of(cls, features: Features) -> HoldOut:
        """Leave-one-test-out with three or more tests (beyond ``MAX_FOLDS`` tests, test k
        in group k mod ``MAX_FOLDS``), else odd against even cycles of every test."""
        tests = np.unique(features.test)
        if tests.size >= _MIN_TESTS_FOR_TEST_HOLDOUT:
            groups = min(tests.size, MAX_FOLDS)
            scheme = ("leave-one-test-out" if groups == tests.size
                      else f"tests held out in {groups} groups")
            masks = [features.test % groups == g for g in range(groups)]
        else:
            scheme = "alternate cycles"
            masks = [features.cycle % 2 == parity for parity in (1, 0)]
        if any(not m.any() or m.all() for m in masks):
            raise InputError("The campaign needs at least two cycles (or three tests) so that "
                             "part of it can be held out.")
        folds = tuple((np.flatnonzero(~m), np.flatnonzero(m)) for m in masks)
        return cls(scheme, folds, tuple(features.take(tr) for tr, _ in folds),
                   tuple(features.take(te) for _, te in folds))

    def predict(self, model: Model, context: Context,
                start: np.ndarray | None = None) -> tuple[np.ndarray, list[np.ndarray]]:
        """Held-out force of every sample [N] and the parameters of each fold."""
        n = sum(te.size for _, te in self.folds)
        prediction = np.empty(n)
        thetas = []
        for (_, te), train, held in zip(self.folds, self.training, self.held_out, strict=True):
            starts = [start] if start is not None else multistart(model)
            result = fit(model, train, context, starts)
            prediction[te] = model.force(result.theta, held, context)
            thetas.append(result.theta)
        return prediction, thetas
