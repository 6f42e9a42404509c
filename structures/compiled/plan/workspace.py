"""The layout of the plan engine's arrays and its five argument groups.

:func:`structures.compiled.plan.integrator.integrate_plan` takes the building, the records,
the constants, the carried state and the outputs as five NamedTuples (numba types them as
tuples), as the planar engine does (:mod:`structures.compiled.workspace`, whose method layout
``GAMMA`` ... ``MAX_SUBDIVISIONS`` and first ``info`` fields it shares); :func:`new_plan_workspace`
allocates the work arrays in Python so that the compiled loop allocates nothing.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from isolator.compiled.bidirectional.bearing import PLATE_STATE_SIZE

__all__ = ["PlanModel", "PlanMotion", "PlanOutputs", "PlanSettings", "PlanState",
           "new_plan_workspace"]

# Rows of the ``dofs`` work array: committed and trial u, v, a, p, q, the Newton work, the
# restoring force f, C v and the storey forces K u + C v of the trial.
U_C, V_C, A_C, P_C, Q_C, U, V, A, P, Q, LOAD, RESIDUAL, DU, FORCE, VISCOUS = range(15)
STOREY, DOF_ROWS = 15, 16

# ``info`` beyond the planar engine's first nine fields (STATUS ... FAIL_VALUE): the bearing
# whose trial failed, its trial displacement (x, y) [m] and the grid frame of that trial.
FAIL_BEARING, FAIL_UX, FAIL_UY, FAIL_E1X, FAIL_E1Y = range(9, 14)
PLAN_INFO_SIZE = 14

# ``flags``: overturning in the axial loads (1.0/0.0), a vertical record (1.0/0.0).
OVERTURNING, VERTICAL = range(2)

# The work arrays of ``workspace`` (see :func:`new_plan_workspace`), in this order.
COMMITTED, TRIAL, STACK_START, STACK_END, STACK_DEPTH, DOFS, TANGENT = range(7)
LAPACK_WORK, PIVOTS, MASS_INFLUENCE, TOP_STIFFNESS, TOP_DAMPING, LOADS = range(7, 13)
INVERSES, INVERSE_STEPS, UPDATE = range(13, 16)


class PlanModel(NamedTuple):
    """The building in plan, on the levels' (u_x, u_y, theta), base slab first.

    Attributes
    ----------
    mass, damping, stiffness : ndarray, shape (n, n)
        Mass [kg, kg m^2], superstructure damping and stiffness (no isolators) [N/m ...].
    influence : ndarray, shape (n, 2)
        Influence of the (x, y) ground acceleration [-].
    overturning : ndarray, shape (n_b, n)
        Axial load of each bearing per unit storey force (``G`` times the floor heights) [-, 1/m].
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


class PlanMotion(NamedTuple):
    """The horizontal records: ``ground`` (nt, 2) [m/s^2] at ``time`` (nt,) [s]."""

    ground: np.ndarray
    time: np.ndarray


class PlanSettings(NamedTuple):
    """The constants of the run.

    Attributes
    ----------
    method : ndarray, shape (6,)
        As the planar engine's (``structures.compiled.workspace.GAMMA`` ...).
    bearings : ndarray, shape (n_b, PLATE_PARAMETERS)
        One row per bearing (:mod:`isolator.compiled.bidirectional.bearing`), SI units.
    ptv : ndarray, shape (PTV_PARAMETERS,)
        The friction constants (:func:`isolator.compiled.layout.pack_ptv`).
    flags : ndarray, shape (2,)
        ``OVERTURNING``, ``VERTICAL``.
    """

    method: np.ndarray
    bearings: np.ndarray
    ptv: np.ndarray
    flags: np.ndarray


class PlanState(NamedTuple):
    """What the engine carries from step to step and from call to call (changed in place):
    ``heat`` (:func:`isolator.compiled.bidirectional.bearing.new_plate_heating`) and ``workspace``
    (:func:`new_plan_workspace`)."""

    heat: tuple
    workspace: tuple


class PlanOutputs(NamedTuple):
    """What the engine fills for the steps it takes.

    Attributes
    ----------
    displacement, velocity, acceleration : ndarray, shape (nt, n)
        Relative response [m, rad], [m/s, rad/s], [m/s^2, rad/s^2].
    record : ndarray, shape (nt, n_b, PLATE_STATE_SIZE)
        Each bearing's committed state (:mod:`isolator.compiled.bidirectional.bearing` columns).
    restoring : ndarray, shape (nt, n)
        Storey springs plus all bearings on the base slab [N, N m].
    iterations, subdivisions : ndarray of int64, shape (nt - 1,)
        Newton iterations (failed attempts included) and halvings of each step.
    info : ndarray, shape (PLAN_INFO_SIZE,)
        Status, last committed step and, on failure, where and why.
    """

    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    record: np.ndarray
    restoring: np.ndarray
    iterations: np.ndarray
    subdivisions: np.ndarray
    info: np.ndarray


def new_plan_workspace(n: int, n_bearings: int, max_subdivisions: int) -> tuple:
    """The engine's work arrays for ``n`` DOFs, ``n_bearings`` bearings and
    ``max_subdivisions`` halvings, indexed by ``COMMITTED`` ... ``LOADS``: the bearings'
    committed and trial states (n_b, PLATE_STATE_SIZE), the halving stack, the ``dofs`` rows,
    the Newton matrix and LAPACK's work (n, n) and pivots (int32), M r (n, 2), the tangent's
    rows of the base slab (3, n) the bearings add in stiffness and damping, the trial's axial
    loads, ``A^-1`` per halving depth (depth + 1, n, n) with the step it was formed for (-1:
    none yet), and the Woodbury update's work (3, n)."""
    depths = max_subdivisions + 2
    return (np.zeros((n_bearings, PLATE_STATE_SIZE)), np.zeros((n_bearings, PLATE_STATE_SIZE)),
            np.zeros(depths), np.zeros(depths), np.zeros(depths, dtype=np.int64),
            np.zeros((DOF_ROWS, n)), np.zeros((n, n)), np.zeros((n, n)),
            np.zeros(n, dtype=np.int32), np.zeros((n, 2)), np.zeros((3, n)), np.zeros((3, n)),
            np.zeros(n_bearings), np.zeros((depths, n, n)), np.full(depths, -1.0),
            np.zeros((3, n)))
