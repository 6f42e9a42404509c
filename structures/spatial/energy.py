"""Energy balance of a committed history of a building in plan (``structures.energy`` in 3D).

With relative displacements ``u`` and a ground acceleration of k components ``a_g`` (an
influence ``R`` of shape (n, k)), by the trapezoidal rule over each step (exact for Newmark's
average acceleration, where the balance then closes to the solver's tolerance)::

    input    E_I = sum du . (p_n + p_n+1) / 2,   p = -M R a_g
    kinetic  E_K = v . M v / 2                   (relative velocity)
    damping  E_D = sum du . C (v_n + v_n+1) / 2
    strain   E_S = sum du . (f_n + f_n+1) / 2 minus the friction: storeys and pendulums
    friction E_F = sum over bearings of sum du_i . (F_f,i,n + F_f,i,n+1) / 2
    error    = E_I - (E_K + E_D + E_S + E_F)

``du_i`` is the displacement increment of bearing ``i`` and ``F_f,i`` its friction force
(x, y), so the friction work is counted where it is done, torsion included.
"""

from __future__ import annotations

import numpy as np

from structures.energy import EnergyBalance, trapezoid_work

__all__ = ["spatial_energy_balance"]


def spatial_energy_balance(
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
    displacement, velocity : numpy.ndarray
        Response relative to the ground, shape (nt, n) [m, rad], [m/s, rad/s].
    ground_acceleration : numpy.ndarray
        Shape (nt, k) [m/s^2].
    mass, damping : numpy.ndarray
        Shape (n, n) [kg ...], [N s/m ...].
    influence : numpy.ndarray
        ``R``, shape (n, k) [-].
    restoring_force : numpy.ndarray
        Total restoring force ``f(u, v)`` (storeys and bearings), shape (nt, n) [N, N m].
    bearing_displacement, friction_force : numpy.ndarray
        Each bearing's displacement [m] and friction force [N], shape (nt, n_b, 2).

    Returns
    -------
    structures.energy.EnergyBalance
        The cumulative energies [J] and the closure error.
    """
    load = -(ground_acceleration @ (mass @ influence).T)
    energy_input = trapezoid_work(load, displacement)
    kinetic = 0.5 * np.sum((velocity @ mass.T) * velocity, axis=1)  # v . M v per step
    damping_work = trapezoid_work(velocity @ damping.T, displacement)
    friction = trapezoid_work(friction_force, bearing_displacement)
    strain = trapezoid_work(restoring_force, displacement) - friction
    error = energy_input - (kinetic + damping_work + strain + friction)
    return EnergyBalance(energy_input, kinetic, damping_work, strain, friction, error)
