"""The layout of the compiled engine's arrays and its five argument groups.

:func:`structures.compiled.integrator.integrate_building` takes the building, the record, the
constants, the carried state and the outputs as five NamedTuples (:class:`Model`,
:class:`Motion`, :class:`Settings`, :class:`State`, :class:`Outputs`; numba types them as
tuples, so the compiled function sees named fields at no cost per step), and indexes its
arrays by the names defined here; :func:`new_workspace` allocates the work arrays in Python so
that the compiled loop allocates nothing. The adapter :mod:`structures.compiled.engine` packs
and reads the same names.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from isolator.compiled.bearing import STATE_SIZE

__all__ = ["Model", "Motion", "Outputs", "Settings", "State", "new_workspace"]

# Layout of the ``method`` array.
GAMMA, BETA, ALPHA, TOLERANCE, MAX_ITERATIONS, MAX_SUBDIVISIONS = range(6)

# Rows of the ``dofs`` work array: committed and trial u, v, a, p, q, then the Newton work.
U_C, V_C, A_C, P_C, Q_C, U, V, A, P, Q, LOAD, RESIDUAL, DU = range(13)
DOF_ROWS = 13

# Layout of the ``info`` array filled by the engine.
STATUS, LAST_STEP, FAIL_TIME, FAIL_SUBSTEP, FAIL_DEPTH, FAIL_ITERATIONS, FAIL_RESIDUAL = range(7)
FAIL_REFERENCE, FAIL_VALUE = 7, 8
INFO_SIZE = 9

# The work arrays of ``workspace`` (see :func:`new_workspace`), in this order.
COMMITTED, TRIAL, INVERSES, INVERSE_STEPS, STACK_START, STACK_END, STACK_DEPTH = range(7)
DOFS, MATRIX, LAPACK_WORK, PIVOTS, MASS_INFLUENCE = range(7, 12)


class Model(NamedTuple):
    """The building, on ``[u_b, u_1..]`` (the isolators come on top of ``stiffness`` on DOF 0).

    Attributes
    ----------
    mass, damping, stiffness : ndarray, shape (n, n)
        Mass [kg], superstructure damping [N s/m] and superstructure stiffness [N/m].
    influence : ndarray, shape (n,)
        Ground-motion influence vector [-].
    """

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    influence: np.ndarray


class Motion(NamedTuple):
    """The record.

    Attributes
    ----------
    ground : ndarray, shape (nt,)
        Ground acceleration at ``time`` [m/s^2].
    time : ndarray, shape (nt,)
        Times of the record, from 0 [s].
    """

    ground: np.ndarray
    time: np.ndarray


class Settings(NamedTuple):
    """The constants of the run: the integration method and the bearing.

    Attributes
    ----------
    method : ndarray, shape (6,)
        gamma, beta, alpha [-], tolerance [-], max_iterations, max_subdivisions (indexed by
        ``GAMMA`` ... ``MAX_SUBDIVISIONS``).
    bearing : ndarray, shape (BEARING_PARAMETERS,)
        One bearing and the number of them (the index names of
        :mod:`isolator.compiled.bearing`); SI units.
    ptv : ndarray, shape (PTV_PARAMETERS,)
        The friction constants (:func:`isolator.compiled.layout.pack_ptv`); also read by the
        friction model without heating.
    """

    method: np.ndarray
    bearing: np.ndarray
    ptv: np.ndarray


class State(NamedTuple):
    """What the engine carries from step to step and from one call to the next; zero at the
    start, changed in place.

    Attributes
    ----------
    heating : tuple of ndarray
        The heat history (:func:`isolator.compiled.bearing.new_heating`).
    workspace : tuple of ndarray
        The work arrays (:func:`new_workspace`): the bearing's committed and trial states, the
        Newton rows, the inverses, ...
    """

    heating: tuple
    workspace: tuple


class Outputs(NamedTuple):
    """What the engine fills for the steps it takes.

    Attributes
    ----------
    displacement, velocity, acceleration : ndarray, shape (nt, n)
        Relative response [m], [m/s], [m/s^2].
    record : ndarray, shape (7, nt)
        The bearing's committed state, rows as ``BEARING_FIELDS`` (SI units).
    restoring : ndarray, shape (nt, n)
        Total restoring force K u + isolators [N].
    iterations, subdivisions : ndarray of int64, shape (nt - 1,)
        Newton iterations (failed attempts included) and halvings of each step.
    info : ndarray, shape (INFO_SIZE,)
        Status, last committed step and, on failure, where and why (``STATUS`` ...
        ``FAIL_VALUE``).
    """

    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    record: np.ndarray
    restoring: np.ndarray
    iterations: np.ndarray
    subdivisions: np.ndarray
    info: np.ndarray


def new_workspace(n: int, max_subdivisions: int) -> tuple[np.ndarray, ...]:
    """The engine's work arrays for ``n`` DOFs and ``max_subdivisions`` halvings.

    Allocated here, in Python, so that the compiled loop allocates nothing (each array
    constructor it used was one more function for numba to compile on a cold cache).

    Returns
    -------
    tuple of ndarray
        Indexed by ``COMMITTED`` ... ``MASS_INFLUENCE``: the committed and trial bearing
        states (``STATE_SIZE``), ``A^-1`` per halving depth (depth + 1, n, n) and the step it
        was formed for (-1: none yet), the halving stack (start, end, depth), the ``dofs`` rows
        (``DOF_ROWS``, n), the effective matrix (n, n), LAPACK's work (n, n) and pivots
        (int32), and ``M r`` (n,).
    """
    depths = max_subdivisions + 1
    return (np.zeros(STATE_SIZE), np.zeros(STATE_SIZE), np.zeros((depths, n, n)),
            np.full(depths, -1.0), np.zeros(depths + 1), np.zeros(depths + 1),
            np.zeros(depths + 1, dtype=np.int64), np.zeros((DOF_ROWS, n)), np.zeros((n, n)),
            np.zeros((n, n)), np.zeros(n, dtype=np.int32), np.zeros(n))
