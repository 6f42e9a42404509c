"""The compiled engine's five argument groups and the layout of its arrays.

:func:`structures.compiled.integrator.integrate` takes :class:`Model`, :class:`Motion`,
:class:`Settings`, :class:`State` and :class:`Outputs` (numba types them as tuples: named fields
at no cost per step) and indexes its arrays by the names defined here."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from isolator.compiled.element import MOTION_SIZE, STATE_SIZE
from isolator.compiled.plate import PlateHeat

__all__ = ["Model", "Motion", "Outputs", "Settings", "State", "new_workspace"]

# Layout of the ``method`` array.
GAMMA, BETA, ALPHA, TOLERANCE, MAX_ITERATIONS, MAX_SUBDIVISIONS = range(6)

# Layout of the ``flags`` array: the DOFs per level (1: x; 3: x, y, theta), the overturning
# of the storey forces in the axial loads (1.0/0.0), a vertical record (1.0/0.0).
LEVEL_DOFS, OVERTURNING, VERTICAL = range(3)
FLAGS_SIZE = 3

# Rows of the ``dofs`` work array: committed and trial u, v, a, p, q, the Newton work, the
# restoring force f, C v and the storey forces K u + C v of the trial.
U_C, V_C, A_C, P_C, Q_C, U, V, A, P, Q, LOAD, RESIDUAL, DU, FORCE, VISCOUS = range(15)
STOREY, DOF_ROWS = 15, 16

# Rows of the ``ground`` work array (c components each): the committed ground acceleration,
# the step's start and end, and the (sub-)step's.
GROUND_COMMITTED, GROUND_START, GROUND_END, GROUND_NOW = range(4)

# Layout of the ``info`` array: status, last committed step and, on failure, where and why
# (the bearing whose trial failed, its trial displacement (x, y) [m] and frame).
STATUS, LAST_STEP, FAIL_TIME, FAIL_SUBSTEP, FAIL_DEPTH, FAIL_ITERATIONS, FAIL_RESIDUAL = range(7)
FAIL_REFERENCE, FAIL_VALUE, FAIL_BEARING, FAIL_UX, FAIL_UY, FAIL_E1X, FAIL_E1Y = range(7, 14)
INFO_SIZE = 14

# The work arrays of ``workspace`` (see :func:`new_workspace`), in this order.
COMMITTED, TRIAL, STACK_START, STACK_END, STACK_DEPTH, DOFS, TANGENT = range(7)
LAPACK_WORK, PIVOTS, MASS_INFLUENCE, TOP_STIFFNESS, TOP_DAMPING, MOTION = range(7, 13)
INVERSES, INVERSE_STEPS, UPDATE, GROUND = range(13, 17)


class Model(NamedTuple):
    """The building: the fields of :class:`structures.compiled.view.EngineView` of the same
    names (C-ordered floats), and the vertical record ``vertical_time`` [s],
    ``vertical_acceleration`` [m/s^2], shape (m,), positive up (any two points without one)."""

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    influence: np.ndarray
    overturning: np.ndarray
    load_du: np.ndarray
    load_dv: np.ndarray
    vertical_time: np.ndarray
    vertical_acceleration: np.ndarray


class Motion(NamedTuple):
    """The horizontal record: ``ground`` (nt, c) [m/s^2] at ``time`` (nt,) [s]."""

    ground: np.ndarray
    time: np.ndarray


class Settings(NamedTuple):
    """The constants of the run: ``method`` (6,), gamma, beta, alpha, tolerance,
    max_iterations, max_subdivisions (``GAMMA`` ...); ``parameters`` and ``ptv`` of
    :class:`isolator.compiled.packing.CompiledBearings`; ``flags`` (``LEVEL_DOFS`` ...)."""

    method: np.ndarray
    parameters: np.ndarray
    ptv: np.ndarray
    flags: np.ndarray


class State(NamedTuple):
    """What the engine carries between steps and calls, changed in place: ``heat``
    (:class:`isolator.compiled.plate.PlateHeat`) and ``workspace`` (:func:`new_workspace`)."""

    heat: PlateHeat
    workspace: tuple


class Outputs(NamedTuple):
    """What the engine fills for the steps it takes.

    Attributes
    ----------
    displacement, velocity, acceleration : ndarray, shape (nt, n)
        Relative response [m, rad], [m/s, rad/s], [m/s^2, rad/s^2].
    record : ndarray, shape (nt, n_b, RECORD_SIZE)
        Each row's committed state, one bearing of it (columns:
        :data:`isolator.compiled.element.RECORD_FIELDS`).
    restoring : ndarray, shape (nt, n)
        Storey springs plus all bearings on the base slab [N, N m].
    iterations, subdivisions : ndarray of int64, shape (nt - 1,)
        Newton iterations (failed attempts included) and halvings of each step.
    info : ndarray, shape (INFO_SIZE,)
        Status, last committed step and, on failure, where and why (``STATUS`` ...).
    """

    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    record: np.ndarray
    restoring: np.ndarray
    iterations: np.ndarray
    subdivisions: np.ndarray
    info: np.ndarray


def new_workspace(n: int, components: int, n_bearings: int, max_subdivisions: int) -> tuple:
    """The engine's work arrays (indexed by ``COMMITTED`` ... ``GROUND``) for ``n`` DOFs,
    ``components`` ground components, ``n_bearings`` rows and ``max_subdivisions`` halvings,
    made in Python so that the compiled loop allocates nothing."""
    depths = max_subdivisions + 2
    return (np.zeros((n_bearings, STATE_SIZE)), np.zeros((n_bearings, STATE_SIZE)),
            np.zeros(depths), np.zeros(depths), np.zeros(depths, dtype=np.int64),
            np.zeros((DOF_ROWS, n)), np.zeros((n, n)), np.zeros((n, n)),
            np.zeros(n, dtype=np.int32), np.zeros((n, components)), np.zeros((3, n)),
            np.zeros((3, n)), np.zeros((n_bearings, MOTION_SIZE)), np.zeros((depths, n, n)),
            np.full(depths, -1.0), np.zeros((3, n)), np.zeros((4, components)))
