"""What the compiled engine sees of a model: :class:`EngineView`, and :func:`engine_view` of an
isolated building. A building in one direction is the special case of one DOF per level, one
bearing row at (0, 0) standing for its ``n_bearings`` identical bearings, no overturning."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

if TYPE_CHECKING:
    from structures.isolated_building import IsolatedShearBuilding

__all__ = ["EngineView", "engine_view"]


class EngineView(NamedTuple):
    """A model as the compiled engine sees it (SI units).

    Attributes
    ----------
    mass, damping, stiffness : ndarray, shape (n, n)
        Mass [kg, kg m^2], superstructure damping [N s/m ...] and stiffness (without the
        isolators) [N/m ...] on the levels' DOFs, the base slab's first.
    influence : ndarray, shape (n, c)
        Influence of the c horizontal ground components [-] (c = 1: x only).
    level_dofs : int
        DOFs per level: 1 (x) or 3 (x, y and the rotation theta about the plan's origin).
    positions, multiplicity, gravity : ndarray, shape (n_b, 2), (n_b,), (n_b,)
        Each bearing row's plan position [m], the identical bearings it stands for (its force
        and tangent count that many times) and one bearing's axial load at rest [N].
    overturning, load_du, load_dv : ndarray, shape (n_b, n)
        Axial load per unit storey force ``K u + C v`` [-, 1/m] (zeros without overturning),
        and its d N / d u [N/m] and d N / d v [N s/m].
    with_overturning : bool
        Whether the overturning acts on the axial loads.
    vertical : GroundMotion or None
        Vertical ground acceleration [m/s^2], positive up, scaling gravity by 1 + a_z / g.
    bearing, elements : DCFPBearing, tuple
        The bearing of every row; the model's reference elements at rest, one per row.
    """

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    influence: np.ndarray
    level_dofs: int
    positions: np.ndarray
    multiplicity: np.ndarray
    gravity: np.ndarray
    overturning: np.ndarray
    load_du: np.ndarray
    load_dv: np.ndarray
    with_overturning: bool
    vertical: Any
    bearing: Any
    elements: tuple


def engine_view(model: IsolatedShearBuilding) -> EngineView:
    """The :class:`EngineView` of a fresh isolated building (its bearings at rest)."""
    n = model.mass_matrix.shape[0]
    influence = np.asarray(model.influence, dtype=float).reshape(n, -1)
    return EngineView(
        model.mass_matrix, model.damping_matrix, model.superstructure_stiffness, influence,
        model.level_dofs, np.asarray(model.positions, dtype=float),
        model.multiplicity.astype(float), np.asarray(model.gravity_loads, dtype=float),
        model.overturning_matrix, model.load_du, model.load_dv, model.overturning,
        model.vertical, model.bearing, tuple(model.elements))
