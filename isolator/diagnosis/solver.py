"""A small bounded Levenberg-Marquardt solver for long residual vectors and few parameters.

The diagnosis fits 1 to 8 parameters to 10^3 to 10^5 residuals, hundreds of times. The normal
equations J^T J and J^T r are formed with ``numpy.einsum`` (no BLAS threads, which slow such
tall products on a small, busy machine) and the p x p system is solved directly; bounds are
kept by projection, and the Jacobian is a forward difference.

References
----------
Marquardt D.W. (1963). An algorithm for least-squares estimation of nonlinear parameters.
J. Soc. Indust. Appl. Math. 11(2), 431-441 (diagonal scaling of the damping).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

_STEP = 1.0e-6  # relative forward-difference step
_TOLERANCE = 1.0e-8  # relative decrease of the cost, or relative step, that ends the iteration


@dataclass(frozen=True)
class Solution:
    """Result of :func:`levenberg_marquardt`.

    Attributes
    ----------
    x, cost : ndarray, float
        Parameters at the minimum found, and the sum of squared residuals there.
    residual, jacobian : ndarray
        Residual vector and forward-difference Jacobian (n x p) there.
    evaluations : int
        Residual evaluations used.
    """

    x: np.ndarray
    cost: float
    residual: np.ndarray
    jacobian: np.ndarray
    evaluations: int


def _jacobian(fun: Callable[[np.ndarray], np.ndarray], x: np.ndarray, r: np.ndarray,
              low: np.ndarray, high: np.ndarray) -> np.ndarray:
    jac = np.empty((r.size, x.size))
    for j in range(x.size):
        h = _STEP * max(abs(x[j]), 1e-3 * (high[j] - low[j]), 1e-8)
        if x[j] + h > high[j]:
            h = -h  # step inwards at the upper bound
        trial = x.copy()
        trial[j] += h
        jac[:, j] = (fun(trial) - r) / h
    return jac


def levenberg_marquardt(
    fun: Callable[[np.ndarray], np.ndarray],
    x0: np.ndarray,
    low: np.ndarray,
    high: np.ndarray,
    *,
    max_iterations: int = 60,
) -> Solution:
    """Minimise sum(fun(x)^2) for low <= x <= high.

    ``fun(x)`` is the residual vector, ``x0`` the start (projected onto the bounds), and
    ``max_iterations`` the largest number of Jacobian evaluations.
    """
    x = np.clip(np.asarray(x0, dtype=float), low, high)
    r = fun(x)
    cost = float(np.einsum("i,i->", r, r))
    evaluations = 1
    damping = 1.0e-3
    jac = _jacobian(fun, x, r, low, high)
    evaluations += x.size
    for _ in range(max_iterations):
        normal = np.einsum("ij,ik->jk", jac, jac)
        gradient = np.einsum("ij,i->j", jac, r)
        # parameters held at a bound by the gradient stay there (projected active set)
        free = ~(((x <= low) & (gradient > 0.0)) | ((x >= high) & (gradient < 0.0)))
        if not free.any():
            break
        sub = normal[np.ix_(free, free)]
        scale = np.maximum(np.diag(sub), 1e-12 * max(float(np.max(np.diag(sub))), 1e-300))
        improved = False
        while damping < 1.0e12:
            try:
                step = np.zeros_like(x)
                step[free] = np.linalg.solve(sub + damping * np.diag(scale), -gradient[free])
            except np.linalg.LinAlgError:
                damping *= 10.0
                continue
            trial = np.clip(x + step, low, high)
            r_trial = fun(trial)
            evaluations += 1
            cost_trial = float(np.einsum("i,i->", r_trial, r_trial))
            if np.isfinite(cost_trial) and cost_trial < cost:
                decrease = (cost - cost_trial) / max(cost, 1e-300)
                moved = float(np.max(np.abs(trial - x) / (np.abs(x) + 1e-3 * (high - low))))
                x, r, cost = trial, r_trial, cost_trial
                damping = max(damping / 3.0, 1.0e-9)
                improved = True
                break
            damping *= 4.0
        if not improved:
            break
        jac = _jacobian(fun, x, r, low, high)
        evaluations += x.size
        if decrease < _TOLERANCE or moved < _TOLERANCE:
            break
    return Solution(x, cost, r, jac, evaluations)
