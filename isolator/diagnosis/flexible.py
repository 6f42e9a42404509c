"""Flexible monotone forms of the effects on mu: shapes that do not leak.

An effect's own form (the paper's alpha(v), an exponential wear law) need not be the truth's
shape, and what a wrong shape leaves can make another candidate seem to earn its keep. So
each effect on mu also has a flexible monotone form in its own variable x:

    m(x) = exp(sum_k c_k h_k(x)),   h_k(x) = clip((x - x_k) / (x_(k+1) - x_k), 0, 1),

with knots x_k at quantiles of x (for wear also at the start of every test after the first:
a drop from test to test) and all c_k of the sign of the effect's own fit, so m is monotone
and positive. A second effect is named only if it earns its keep over the first in this form
(:mod:`isolator.diagnosis.decision`). A named law is reported in its paper form, this form or
a finer one (``FINE_KNOTS``), whichever predicts the held-out samples best.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from dcfpb.common.errors import InputError
from isolator.diagnosis.effects import Context, Effect, Parameter

KNOTS = 6  # knot positions (quantiles of the variable): five ramps
FINE_KNOTS = 11  # the finer form a named law may also be reported in: ten ramps
_MAX_STEP = 4.0  # |c_k| bound: a factor of e^4 per ramp at most


def knots(x: np.ndarray, extra: np.ndarray | None = None, count: int = KNOTS) -> np.ndarray:
    """Knot positions: ``count`` quantiles of ``x`` and the ``extra`` positions, distinct,
    sorted."""
    q = np.quantile(x, np.linspace(0.0, 1.0, count))
    if extra is not None and extra.size:
        q = np.concatenate([q, extra, extra + 1e-9 * max(float(np.ptp(x)), 1e-12)])
    q = np.unique(q)
    keep = np.concatenate([[True], np.diff(q) > 1e-12 * max(float(np.ptp(q)), 1e-300)])
    return q[keep]


def ramps(x: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """The basis h_k(x), one column per interval between knots [-]."""
    lo, hi = positions[:-1], positions[1:]
    return np.clip((x[:, None] - lo) / (hi - lo), 0.0, 1.0)


def flexible(effect: Effect, features, context: Context, increasing: bool,
             knot_count: int = KNOTS) -> Effect:
    """``effect`` (on mu, with a ``variable``) in its flexible monotone form, rising with its
    variable if ``increasing``, with ``knot_count`` knots at quantiles of the variable over
    ``features``."""
    if effect.acts_on != "mu" or effect.variable is None:
        raise InputError(f"Effect {effect.name!r} has no flexible form (it must act on mu "
                         "and name its variable).")
    x = effect.variable(features, context)
    extra = None
    if effect.name == "wear":
        starts = [features.campaign_travel[features.test == k].min()
                  for k in np.unique(features.test)[1:]]
        extra = np.asarray(starts, dtype=float)
    positions = knots(x, extra, knot_count)
    count = max(positions.size - 1, 1)
    if positions.size < 2:
        positions = np.array([x.min(), x.min() + 1.0])
    low, high = (0.0, _MAX_STEP) if increasing else (-_MAX_STEP, 0.0)
    start = 0.05 if increasing else -0.05
    variable = effect.variable

    def factor(theta, f, c):
        return np.exp(ramps(variable(f, c), positions) @ theta)

    parameters = tuple(Parameter(f"c{k + 1}", start, low, high, edge_ok=True)
                       for k in range(count))
    return replace(effect, description=f"{effect.description} (flexible monotone form)",
                   parameters=parameters, factor=factor, reading=_curve_reading(positions))


def _curve_reading(positions: np.ndarray):
    def reading(theta, stderr, c):
        m = np.exp(np.concatenate([[0.0], np.cumsum(theta)]))
        return {"curve_variable": (positions.tolist(), 0.0, "variable"),
                "curve_factor": ((m / m[0]).tolist(), 0.0, "-")}
    return reading


def direction(effect: Effect, theta: np.ndarray, features, context: Context) -> bool:
    """Whether the fitted ``effect`` (own form, parameters ``theta``) rises with its variable."""
    m = effect.factor(theta, features, context)
    x = effect.variable(features, context)
    if np.ptp(x) == 0.0 or np.ptp(m) == 0.0:
        return True
    return bool(np.corrcoef(x, m)[0, 1] >= 0.0)
