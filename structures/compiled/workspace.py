"""The layout of the compiled engine's arrays and its five argument groups.

:func:`structures.compiled.integrator.integrate` takes the building, the record, the constants,
the carried state and the outputs as five NamedTuples (:class:`Model`, :class:`Motion`,
:class:`Settings`, :class:`State`, :class:`Outputs`; numba types them as tuples, so the
compiled function sees named fields at no cost per step), and indexes its arrays by the names
defined here; :func:`new_workspace` allocates the work arrays in Python so that the compiled
loop allocates nothing. The adapter :mod:`structures.compiled.engine` packs and reads the same
names.
"""

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

# Layout of the ``info`` array filled by the engine: status, the last committed step and, on
# failure, where and why; the bearing whose trial failed, its trial displacement (x, y) [m]
# and the frame of that trial.
STATUS, LAST_STEP, FAIL_TIME, FAIL_SUBSTEP, FAIL_DEPTH, FAIL_ITERATIONS, FAIL_RESIDUAL = range(7)
FAIL_REFERENCE, FAIL_VALUE, FAIL_BEARING, FAIL_UX, FAIL_UY, FAIL_E1X, FAIL_E1Y = range(7, 14)
INFO_SIZE = 14

# The work arrays of ``workspace`` (see :func:`new_workspace`), in this order.
COMMITTED, TRIAL, STACK_START, STACK_END, STACK_DEPTH, DOFS, TANGENT = range(7)
LAPACK_WORK, PIVOTS, MASS_INFLUENCE, TOP_STIFFNESS, TOP_DAMPING, MOTION = range(7, 13)
INVERSES, INVERSE_STEPS, UPDATE, GROUND = range(13, 17)


class Model(NamedTuple):
    """The building, on the levels' DOFs, base slab first (1 per level: x; 3: x, y, theta).

    Attributes
    ----------
    mass, damping, stiffness : ndarray, shape (n, n)
        Mass [kg, kg m^2], superstructure damping and stiffness (no isolators) [N/m ...].
    influence : ndarray, shape (n, c)
        Influence of the c horizontal ground components [-].
    overturning : ndarray, shape (n_b, n)
        Axial load of each bearing per unit storey force [-, 1/m] (zeros without).
    load_du, load_dv : ndarray, shape (n_b, n)
        d N / d u [N/m] and d N / d v [N s/m] (``overturning @ K``, ``overturning @ C``).
    vertical_time, vertical_acceleration : ndarray, shape (m,)
        The vertical record [s], [m/s^2] (positive up; any two points without a vertical).
    """

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
    """The constants of the run.

    Attributes
    ----------
    method : ndarray, shape (6,)
        gamma, beta, alpha [-], tolerance [-], max_iterations, max_subdivisions (indexed by
        ``GAMMA`` ... ``MAX_SUBDIVISIONS``).
    parameters : ndarray, shape (n_b, PARAMETERS_SIZE)
        One row per bearing (:mod:`isolator.compiled.element`), SI units.
    ptv : ndarray, shape (n_b, PTV_PARAMETERS)
        The friction constants per bearing (:func:`isolator.compiled.layout.pack_ptv`).
    flags : ndarray, shape (FLAGS_SIZE,)
        ``LEVEL_DOFS``, ``OVERTURNING``, ``VERTICAL``.
    """

    method: np.ndarray
    parameters: np.ndarray
    ptv: np.ndarray
    flags: np.ndarray


class State(NamedTuple):
    """What the engine carries from step to step and from call to call (changed in place):
    ``heat`` (:class:`isolator.compiled.plate.PlateHeat`) and ``workspace``
    (:func:`new_workspace`)."""

    heat: PlateHeat
    workspace: tuple


class Outputs(NamedTuple):
    """What the engine fills for the steps it takes.

    Attributes
    ----------
    displacement, velocity, acceleration : ndarray, shape (nt, n)
        Relative response [m, rad], [m/s, rad/s], [m/s^2, rad/s^2].
    record : ndarray, shape (nt, n_b, RECORD_SIZE)
        Each bearing's committed state (columns of
        :data:`isolator.compiled.element.RECORD_FIELDS`), one bearing of its row.
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
    """The engine's work arrays for ``n`` DOFs, ``components`` ground components,
    ``n_bearings`` bearing rows and ``max_subdivisions`` halvings, indexed by ``COMMITTED`` ...
    ``GROUND``.

    Allocated here, in Python, so that the compiled loop allocates nothing: the bearings'
    committed and trial states (n_b, STATE_SIZE), the halving stack, the ``dofs`` rows, the
    Newton matrix and LAPACK's work (n, n) and pivots (int32), M r (n, c), the rows of the base
    slab's DOFs (3, n) the bearings add to the tangent in stiffness and damping, each row's
    trial motion and axial load (n_b, MOTION_SIZE), ``A^-1`` per halving depth
    (depth + 1, n, n) with the step it was formed for (-1: none yet), the Woodbury update's
    work (3, n) and the ground rows (4, c).
    """
    depths = max_subdivisions + 2
    return (np.zeros((n_bearings, STATE_SIZE)), np.zeros((n_bearings, STATE_SIZE)),
            np.zeros(depths), np.zeros(depths), np.zeros(depths, dtype=np.int64),
            np.zeros((DOF_ROWS, n)), np.zeros((n, n)), np.zeros((n, n)),
            np.zeros(n, dtype=np.int32), np.zeros((n, components)), np.zeros((3, n)),
            np.zeros((3, n)), np.zeros((n_bearings, MOTION_SIZE)), np.zeros((depths, n, n)),
            np.full(depths, -1.0), np.zeros((3, n)), np.zeros((4, components)))
