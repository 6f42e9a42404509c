"""Energy balance of a time-history run, in the relative frame of the ground.

Every term is a work integral taken over the displacement increments of each step with the
trapezoid rule, which is exactly the identity the average-acceleration Newmark method satisfies:
for gamma = 1/2, beta = 1/4 the balance closes to round-off (for linear, nonlinear and
hysteretic restoring forces alike). For HHT-alpha the closure error is the method's numerical
dissipation.

    input   E_I = sum du . (p_n + p_n+1) / 2,          p = -M r a_g
    kinetic E_K = v . M v / 2                            (relative velocity)
    damping E_D = sum du . C (v_n + v_n+1) / 2
    strain  E_S = sum du . (f_n + f_n+1) / 2 minus friction: storey springs + pendulum
    friction E_F = sum du_b . (F_f,n + F_f,n+1) / 2 x n_bearings
    error = E_I - (E_K + E_D + E_S + E_F)
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class EnergyBalance(NamedTuple):
    """Cumulative energies at every step [J] and the closure error."""

    input: np.ndarray
    kinetic: np.ndarray
    damping: np.ndarray
    strain: np.ndarray
    friction: np.ndarray
    error: np.ndarray

    @property
    def relative_error(self) -> float:
        """max |error| / max |input| over the run [-]."""
        scale = float(np.max(np.abs(self.input)))
        return float(np.max(np.abs(self.error)) / scale) if scale > 0 else 0.0


def trapezoid_work(force: np.ndarray, displacement: np.ndarray) -> np.ndarray:
    """Cumulative sum over the steps of du . (f_n + f_n+1) / 2 [J], for arrays of shape
    (nt,) or (nt, ...) (the dot product over every axis but the first)."""
    du = np.diff(displacement, axis=0)
    mean = 0.5 * (force[1:] + force[:-1])
    step = (du * mean).reshape(du.shape[0], -1).sum(axis=1)
    return np.concatenate([[0.0], np.cumsum(step)])


def energy_balance(
    displacement: np.ndarray,
    velocity: np.ndarray,
    ground_acceleration: np.ndarray,
    mass: np.ndarray,
    damping: np.ndarray,
    influence: np.ndarray,
    restoring_force: np.ndarray,
    friction_force: np.ndarray,
    friction_dof: int = 0,
) -> EnergyBalance:
    """Energy balance of a committed history.

    Parameters
    ----------
    displacement, velocity : ndarray, shape (nt, n)
        Response relative to the ground [m], [m/s].
    ground_acceleration : ndarray, shape (nt,)
        [m/s^2].
    mass, damping : ndarray, shape (n, n)
        [kg], [N s/m].
    influence : ndarray, shape (n,)
        Influence vector r [-].
    restoring_force : ndarray, shape (nt, n)
        Total restoring force f(u, v) at each step (springs and isolators) [N].
    friction_force : ndarray, shape (nt,)
        Friction part of the isolators' force on ``friction_dof`` (all bearings) [N].
    friction_dof : int
        Degree of freedom of the isolators.
    """
    load = -np.outer(ground_acceleration, mass @ influence)
    energy_input = trapezoid_work(load, displacement)
    kinetic = 0.5 * np.einsum("ti,ij,tj->t", velocity, mass, velocity)
    damping_work = trapezoid_work(velocity @ damping.T, displacement)
    restoring = trapezoid_work(restoring_force, displacement)
    friction = trapezoid_work(friction_force, displacement[:, friction_dof])
    strain = restoring - friction
    error = energy_input - (kinetic + damping_work + strain + friction)
    return EnergyBalance(energy_input, kinetic, damping_work, strain, friction, error)
