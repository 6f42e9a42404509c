"""What the compiled engine sees of a model: :class:`EngineView`, and :func:`engine_view` of an
isolated building.

The engine (:mod:`structures.compiled.engine`) reads a model through this small record only:
the building's matrices, how the ground moves it, where its bearings are and how they are
loaded, and the bearing with its reference elements (whose friction and heating objects
:mod:`isolator.compiled.packing` packs). A building in one direction is the special case of
one DOF per level, one bearing row at (0, 0) standing for its ``n_bearings`` identical
bearings, no overturning.
"""

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
        Mass [kg, kg m^2], superstructure damping [N s/m ...] and superstructure stiffness
        (without the isolators) [N/m ...] on the levels' DOFs, the base slab's first.
    influence : ndarray, shape (n, c)
        Influence of the c horizontal ground components [-] (c = 1: x only).
    level_dofs : int
        DOFs per level: 1 (x) or 3 (x, y and the rotation theta about the plan's origin).
    positions : ndarray, shape (n_b, 2)
        Plan position of each bearing row [m].
    multiplicity : ndarray, shape (n_b,)
        Identical bearings each row stands for [-]: its force and tangent count that many
        times on the base slab.
    gravity : ndarray, shape (n_b,)
        Axial load of one bearing of each row at rest [N].
    overturning : ndarray, shape (n_b, n)
        Axial load per unit storey force ``K u + C v`` [-, 1/m] (zeros without overturning).
    load_du, load_dv : ndarray, shape (n_b, n)
        d N / d u [N/m] and d N / d v [N s/m] of the axial loads.
    with_overturning : bool
        Whether the overturning acts on the axial loads.
    vertical : GroundMotion or None
        Vertical ground acceleration [m/s^2], positive up (``time`` and ``acceleration``),
        scaling the gravity loads by 1 + a_z / g; None for none.
    bearing : DCFPBearing
        The bearing of every row.
    elements : tuple
        The model's reference elements at rest, one per row (``BearingElement`` moving along x
        or in two directions).
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
    """The :class:`EngineView` of an :class:`~structures.isolated_building.IsolatedShearBuilding`
    (a fresh model: its bearings at rest)."""
    n = model.mass_matrix.shape[0]
    influence = np.asarray(model.influence, dtype=float).reshape(n, -1)
    return EngineView(
        model.mass_matrix, model.damping_matrix, model.superstructure_stiffness, influence,
        model.level_dofs, np.asarray(model.positions, dtype=float),
        model.multiplicity.astype(float), np.asarray(model.gravity_loads, dtype=float),
        model.overturning_matrix, model.load_du, model.load_dv, model.overturning,
        model.vertical, model.bearing, tuple(model.elements))
