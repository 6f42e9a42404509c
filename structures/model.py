"""The dynamic-model protocol between the integrators and what they integrate.

An integrator solves ``M a + C v + f(u, v) = p(t)``, ``p = -M r a_g(t)``: it asks a
:class:`DynamicModel` for its constant matrices and for ``f`` with its tangents at a trial state.
A trial is a pure function of the committed history and the trial state (Newton may call
:meth:`DynamicModel.restoring_force` as often as it likes); the history moves only on
:meth:`DynamicModel.commit`, and :meth:`DynamicModel.revert` discards every trial since.
"""

from __future__ import annotations

from typing import NamedTuple, Protocol, runtime_checkable

import numpy as np

from dcfpb.common.errors import InputError

__all__ = ["DynamicModel", "LinearModel", "RestoringForce"]


class RestoringForce(NamedTuple):
    """Restoring force ``f(u, v)`` of a model at a trial state, shape (n,) [N], with its
    consistent tangents ``stiffness`` d f / d u (n, n) [N/m] and ``damping`` d f / d v (n, n) [N
    s/m] of the velocity-dependent part of ``f`` (friction through d mu / d v; zeros without
    one). The linear viscous damping is not in here: it is :attr:`DynamicModel.damping_matrix`."""

    force: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray


@runtime_checkable
class DynamicModel(Protocol):
    """What an integrator needs from a structure, all motion relative to the ground."""

    @property
    def mass_matrix(self) -> np.ndarray:
        """Mass matrix, shape (n, n) [kg]."""
        ...

    @property
    def damping_matrix(self) -> np.ndarray:
        """Linear viscous damping matrix, shape (n, n) [N s/m]."""
        ...

    @property
    def influence(self) -> np.ndarray:
        """Ground-motion influence ``r``: shape (n,) for one component [-], or (n, k) for a
        ground acceleration of k components (one column each, e.g. x and y)."""
        ...

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        """Restoring force and tangents at the trial displacement ``u`` [m] and velocity ``v``
        [m/s], shape (n,), at the trial ``time`` [s] (the end of the (sub-)step solved)."""
        ...

    def commit(self) -> None:
        """Accept the last trial as converged (the history moves on)."""
        ...

    def revert(self) -> None:
        """Discard every trial since the last commit."""
        ...


class ConstantMatrices:
    """The constant part of a :class:`DynamicModel` for a class that holds it as ``_mass``,
    ``_damping`` and ``_influence``."""

    _mass: np.ndarray
    _damping: np.ndarray
    _influence: np.ndarray

    @property
    def mass_matrix(self) -> np.ndarray:
        """Mass matrix, shape (n, n) [kg; kg m, kg m^2 with rotations]."""
        return self._mass

    @property
    def damping_matrix(self) -> np.ndarray:
        """Viscous damping matrix, shape (n, n) [N s/m; N s, N m s with rotations]."""
        return self._damping

    @property
    def influence(self) -> np.ndarray:
        """Ground-motion influence, shape (n,) or (n, k) for k components [-]."""
        return self._influence


def _square(matrix: object, name: str, n: int | None) -> np.ndarray:
    arr = np.array(matrix, dtype=float)
    if arr.ndim != 2 or arr.shape[0] != arr.shape[1] or (n is not None and arr.shape[0] != n):
        size = "n" if n is None else str(n)
        raise InputError(
            f"The {name!r} parameter of LinearModel must be a ({size}, {size}) array of floats. "
            f"Got shape {arr.shape} instead."
        )
    if not np.all(np.isfinite(arr)):
        raise InputError(
            f"The {name!r} parameter of LinearModel must hold finite floats. Got {arr!r} instead."
        )
    arr.setflags(write=False)
    return arr


class LinearModel(ConstantMatrices):
    """A linear model ``M a + C v + K u = -M r a_g``: the :class:`DynamicModel` with no history
    (the fixed-base building, the tests).

    Parameters
    ----------
    mass, damping, stiffness : array_like
        Mass [kg] (symmetric positive definite), viscous damping [N s/m] and stiffness [N/m]
        matrices, shape (n, n).
    influence : array_like
        Ground-motion influence ``r``, shape (n,) or (n, k) for k components [-].

    Raises
    ------
    ValueError
        For a shape that disagrees, a value not finite or a mass matrix not symmetric positive
        definite.
    """

    def __init__(self, mass: object, damping: object, stiffness: object, influence: object) -> None:
        self._mass = _square(mass, "mass", None)
        n = self._mass.shape[0]
        if not np.allclose(self._mass, self._mass.T) or np.any(np.linalg.eigvalsh(self._mass) <= 0):
            raise InputError(
                "The 'mass' parameter of LinearModel must be a symmetric positive definite "
                f"matrix. Got {self._mass!r} instead."
            )
        self._damping = _square(damping, "damping", n)
        self._stiffness = _square(stiffness, "stiffness", n)
        r = np.array(influence, dtype=float)
        if r.shape[:1] != (n,) or r.ndim > 2 or not np.all(np.isfinite(r)):
            raise InputError(
                f"The 'influence' parameter of LinearModel must be a finite ({n},) array (or "
                f"({n}, k) for k ground-motion components). Got {r!r} instead."
            )
        r.setflags(write=False)
        self._influence = r
        self._no_velocity_tangent = np.zeros((n, n))
        self._no_velocity_tangent.setflags(write=False)

    @property
    def stiffness_matrix(self) -> np.ndarray:
        """Stiffness matrix, shape (n, n) [N/m]."""
        return self._stiffness

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        """Return ``K u`` with tangents ``K`` and zero (``f`` does not depend on ``v``)."""
        return RestoringForce(self._stiffness @ u, self._stiffness, self._no_velocity_tangent)

    def commit(self) -> None:
        """Nothing to commit: a linear model has no history."""

    def revert(self) -> None:
        """Nothing to revert: a linear model has no history."""
