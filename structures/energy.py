"""Energy balance of a time-history run in the relative frame of the ground, in one direction or
in plan. Each term is a trapezoidal work integral over the steps' displacement increments, the
identity average-acceleration Newmark satisfies (closure to round-off for any restoring force;
under HHT-alpha the error is the method's numerical dissipation)::

    input    E_I = sum du . (p_n + p_n+1) / 2,          p = -M R a_g
    kinetic  E_K = v . M v / 2                            (relative velocity)
    damping  E_D = sum du . C (v_n + v_n+1) / 2
    strain   E_S = sum du . (f_n + f_n+1) / 2 minus friction: storey springs + pendulums
    friction E_F = sum over the bearings of sum du_i . (F_f,i,n + F_f,i,n+1) / 2
    error = E_I - (E_K + E_D + E_S + E_F)

with ``du_i`` and ``F_f,i`` the displacement increment and friction force of bearing ``i``.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class EnergyBalance(NamedTuple):
    """Cumulative energies at every step and the closure error, shape (nt,) [J]."""

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
    step = (du * mean).reshape(du.shape[0], int(np.prod(du.shape[1:]))).sum(axis=1)
    return np.concatenate([[0.0], np.cumsum(step)])


def energy_balance(
    displacement: np.ndarray,
    velocity: np.ndarray,
    ground_acceleration: np.ndarray,
    mass: np.ndarray,
    damping: np.ndarray,
    influence: np.ndarray,
    restoring_force: np.ndarray,
    bearing_displacement: np.ndarray,
    friction_force: np.ndarray,
) -> EnergyBalance:
    """Energy balance of a committed history (module docstring).

    Parameters
    ----------
    displacement, velocity : ndarray, shape (nt, n)
        Response relative to the ground [m, rad], [m/s, rad/s].
    ground_acceleration : ndarray, shape (nt, k)
        The k components of the ground acceleration [m/s^2].
    mass, damping, influence : ndarray
        Mass [kg, kg m, kg m^2] and damping [N s/m, ...] matrices (n, n), and the influence ``R``
        (n, k) [-] of the ground acceleration.
    restoring_force : ndarray, shape (nt, n)
        Total restoring force f(u, v) at each step, storeys and bearings [N, N m].
    bearing_displacement, friction_force : ndarray, shape (nt, n_b, d)
        Displacement of each bearing position [m] and friction force of all its bearings [N].
    """
    load = -(ground_acceleration @ (mass @ influence).T)
    energy_input = trapezoid_work(load, displacement)
    kinetic = 0.5 * np.sum((velocity @ mass.T) * velocity, axis=1)  # v . M v per step
    damping_work = trapezoid_work(velocity @ damping.T, displacement)
    friction = trapezoid_work(friction_force, bearing_displacement)
    strain = trapezoid_work(restoring_force, displacement) - friction
    error = energy_input - (kinetic + damping_work + strain + friction)
    return EnergyBalance(energy_input, kinetic, damping_work, strain, friction, error)
