"""A shear building in plan: floors that translate in x and y and turn about the vertical.

Each level (the base slab, level 0, and the floors 1..n) is a rigid diaphragm with three degrees
of freedom at the reference point ``O`` of :mod:`structures.spatial.plan` (the centre of stiffness),
relative to the ground: ``(u_x, u_y, theta)`` [m, m, rad], numbered level by level,
``[b_x, b_y, b_theta, 1_x, 1_y, 1_theta, ...]`` (:func:`dof`). Rotations are small.

Mass. A level of mass ``m`` and inertia ``J_G`` about its centre of mass ``G = O + e`` moves its
centre of mass at ``(u_x - theta e_y, u_y + theta e_x)``, so its kinetic energy is
``T = m/2 [(u_x' - theta' e_y)^2 + (u_y' + theta' e_x)^2] + J_G/2 theta'^2`` and its mass matrix
``d^2 T / dq' dq'``::

    [[ m,       0,     -m e_y            ],
     [ 0,       m,      m e_x            ],
     [-m e_y,   m e_x,  J_G + m |e|^2    ]]

The ground translates without turning, so the absolute velocity is ``q' + R g'`` with the
influence ``R`` of shape (3(n+1), 2): ones on the x and on the y degrees of freedom.

Stiffness. Storey ``s`` joins levels ``s-1`` and ``s`` with ``k_x``, ``k_y`` and ``k_theta``
acting at the centre of stiffness, uncoupled there (:meth:`Plan.stiffnesses`): along each
component the planar shear building's matrix, and ``K = T^T K_fb T`` with the drifts ``T``.

Damping of the superstructure only, as the planar building: ``C = T^T C_fb T`` on the drifts,
``C_fb`` defined on the fixed-base building in plan. Rayleigh damping takes its coefficients
``a0, a1`` from the planar building's fixed-base modes ``modes`` (the x direction: with a
symmetric plan the x response is then damped exactly as the planar building) and applies them
to the 3D matrices, ``C_fb = a0 M + a1 K``; modal damping puts its one ratio on every 3D
fixed-base mode (per-mode ratios are refused: the planar mode numbers do not name 3D modes).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from structures.shear_building import (
    ModalDamping,
    ModalProperties,
    RayleighDamping,
    ShearBuilding,
    modal_analysis,
    shear_stiffness_matrix,
)
from structures.spatial.plan import Plan, axial_distribution, gravity_shares

__all__ = [
    "COMPONENTS", "SpatialBuilding", "bearing_stiffness_matrix", "bearing_transformation", "dof",
    "level_mass_matrix",
]

COMPONENTS = ("x", "y", "theta")
"""The degrees of freedom of a level, in their order."""


def dof(level: int, component: int) -> int:
    """Index of ``component`` (0: x, 1: y, 2: theta) of ``level`` (0: base slab)."""
    return 3 * level + component


def _frozen(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


def level_mass_matrix(mass: float, inertia: float, centre: np.ndarray) -> np.ndarray:
    """Mass matrix of a rigid level at the reference point (module docstring), (3, 3).

    Parameters
    ----------
    mass : float
        [kg].
    inertia : float
        Mass moment of inertia about the level's own centre of mass [kg m^2].
    centre : numpy.ndarray
        Centre of mass ``(e_x, e_y)`` from the reference point [m].
    """
    ex, ey = float(centre[0]), float(centre[1])
    return np.array([[mass, 0.0, -mass * ey],
                     [0.0, mass, mass * ex],
                     [-mass * ey, mass * ex, inertia + mass * (ex * ex + ey * ey)]])


def _interleaved(blocks: list[np.ndarray]) -> np.ndarray:
    """One (3n, 3n) matrix from three (n, n) matrices, one per component."""
    n = blocks[0].shape[0]
    out = np.zeros((3 * n, 3 * n))
    for component, block in enumerate(blocks):
        out[component::3, component::3] = block
    return out


@dataclass(frozen=True, eq=False)
class SpatialBuilding:
    """A shear building (masses, x stiffnesses, base slab, damping) with its plan.

    Parameters
    ----------
    building : ShearBuilding
        Floor masses, storey stiffnesses along x, base slab mass and damping.
    plan : Plan
        Bearings, eccentricities, inertias, stiffnesses along y and in torsion.

    Raises
    ------
    InputError
        If the plan does not fit the building (a per-storey field of another length, an
        inertia or torsional stiffness with neither its value nor the plan's dimensions),
        if the bearings cannot carry the weight (:func:`structures.spatial.plan.gravity_shares`), or
        for per-mode modal damping ratios.
    """

    building: ShearBuilding
    plan: Plan

    def __post_init__(self) -> None:
        owner = type(self).__name__
        if not isinstance(self.building, ShearBuilding):
            raise InputTypeError(f"The 'building' parameter of {owner} must be a ShearBuilding. "
                                 f"Got {self.building!r} instead.")
        if not isinstance(self.plan, Plan):
            raise InputTypeError(f"The 'plan' parameter of {owner} must be a Plan. "
                                 f"Got {self.plan!r} instead.")
        damping = self.building.damping
        if isinstance(damping, ModalDamping) and isinstance(damping.ratio, tuple):
            raise InputError(f"The 'damping' of a {owner} must be RayleighDamping or "
                             "ModalDamping with one ratio for every mode (the planar mode "
                             f"numbers do not name the modes in plan). Got {damping!r} instead.")
        _ = self.storey_stiffnesses, self.level_inertias, self.gravity_shares  # checked now

    @property
    def n_storeys(self) -> int:
        """Number of storeys [-]."""
        return self.building.n_storeys

    @property
    def n_dof(self) -> int:
        """Degrees of freedom of the building on its isolators, 3 (n + 1) [-]."""
        return 3 * (self.n_storeys + 1)

    @cached_property
    def level_masses(self) -> np.ndarray:
        """Masses of the base slab and the floors, shape (n+1,) [kg]."""
        return _frozen(np.concatenate([[self.building.base_mass], self.building.floor_masses]))

    @cached_property
    def level_centres(self) -> np.ndarray:
        """Centres of mass of the base slab and the floors, shape (n+1, 2) [m]."""
        floors = self.plan.floor_eccentricities(self.n_storeys)
        return _frozen(np.vstack([self.plan.base_eccentricity, floors]))

    @cached_property
    def level_inertias(self) -> np.ndarray:
        """Mass moments of inertia about each level's centre of mass, (n+1,) [kg m^2]."""
        floors, base = self.plan.inertias(self.building.floor_masses, self.building.base_mass)
        return _frozen(np.concatenate([[base], floors]))

    @cached_property
    def storey_stiffnesses(self) -> np.ndarray:
        """``(k_x, k_y, k_theta)`` per storey, shape (n, 3) [N/m, N/m, N m/rad]."""
        return _frozen(self.plan.stiffnesses(self.building.storey_stiffnesses))

    @cached_property
    def gravity_shares(self) -> np.ndarray:
        """Each bearing's share of the weight, shape (n_b,) [N], summing to the weight."""
        return _frozen(gravity_shares(self.plan.bearing_coordinates, self.level_masses,
                                      self.level_centres))

    @cached_property
    def axial_distribution(self) -> np.ndarray:
        """``G`` of :func:`structures.spatial.plan.axial_distribution`, shape (n_b, 3)."""
        return _frozen(axial_distribution(self.plan.bearing_coordinates))

    @property
    def weight(self) -> float:
        """Weight carried by the isolators [N]."""
        return self.building.weight

    @property
    def total_mass(self) -> float:
        """Mass carried by the isolators [kg]."""
        return self.building.total_mass

    def _mass(self, levels: range) -> np.ndarray:
        out = np.zeros((3 * len(levels), 3 * len(levels)))
        for k, level in enumerate(levels):
            out[3 * k:3 * k + 3, 3 * k:3 * k + 3] = level_mass_matrix(
                self.level_masses[level], self.level_inertias[level], self.level_centres[level])
        return out

    @cached_property
    def fixed_base_mass_matrix(self) -> np.ndarray:
        """Mass matrix of the floors on a fixed base, shape (3n, 3n) [kg, kg m, kg m^2]."""
        return _frozen(self._mass(range(1, self.n_storeys + 1)))

    @cached_property
    def fixed_base_stiffness_matrix(self) -> np.ndarray:
        """Stiffness matrix on a fixed base, shape (3n, 3n) [N/m, N m/rad]."""
        k = self.storey_stiffnesses
        return _frozen(_interleaved([shear_stiffness_matrix(k[:, c]) for c in range(3)]))

    @cached_property
    def fixed_base_damping_matrix(self) -> np.ndarray:
        """Superstructure damping on a fixed base, shape (3n, 3n) (module docstring)."""
        mass, stiffness = self.fixed_base_mass_matrix, self.fixed_base_stiffness_matrix
        damping = self.building.damping
        if isinstance(damping, RayleighDamping):
            omega = self.building.fixed_base_modes().circular_frequencies
            i, j = damping.modes
            a0, a1 = damping.coefficients((omega[i - 1], omega[j - 1]), damping.ratios)
            return _frozen(a0 * mass + a1 * stiffness)
        return _frozen(damping.matrix(mass, stiffness))

    @cached_property
    def drift_transformation(self) -> np.ndarray:
        """``T`` with ``T q`` the drifts of every floor from the base slab, (3n, 3(n+1))."""
        n = self.n_storeys
        return _frozen(np.hstack([-np.tile(np.eye(3), (n, 1)), np.eye(3 * n)]))

    @cached_property
    def isolated_mass_matrix(self) -> np.ndarray:
        """Mass matrix on the levels' DOFs, shape (3(n+1), 3(n+1))."""
        return _frozen(self._mass(range(self.n_storeys + 1)))

    @cached_property
    def isolated_stiffness_matrix(self) -> np.ndarray:
        """Superstructure stiffness ``T^T K_fb T`` (isolators not included)."""
        t = self.drift_transformation
        return _frozen(t.T @ self.fixed_base_stiffness_matrix @ t)

    @cached_property
    def isolated_damping_matrix(self) -> np.ndarray:
        """Superstructure damping ``T^T C_fb T`` on the drifts only."""
        t = self.drift_transformation
        return _frozen(t.T @ self.fixed_base_damping_matrix @ t)

    @cached_property
    def isolated_influence(self) -> np.ndarray:
        """Influence ``R`` of the (x, y) ground acceleration, shape (3(n+1), 2) [-]."""
        r = np.zeros((self.n_dof, 2))
        r[0::3, 0] = 1.0
        r[1::3, 1] = 1.0
        return _frozen(r)

    def fixed_base_modes(self) -> ModalProperties:
        """Periods [s] and mass-normalised shapes of the fixed-base building in plan."""
        return modal_analysis(self.fixed_base_mass_matrix, self.fixed_base_stiffness_matrix)

    def isolated_modes(self, bearing_stiffnesses: np.ndarray) -> ModalProperties:
        """Periods [s] and shapes on linear isotropic bearings of the given stiffnesses.

        Parameters
        ----------
        bearing_stiffnesses : numpy.ndarray
            Lateral stiffness of each bearing, the same in x and y, shape (n_b,) [N/m]
            (e.g. ``N_i / R_eff`` for a pendulum).
        """
        stiffness = np.array(self.isolated_stiffness_matrix)
        stiffness[:3, :3] += bearing_stiffness_matrix(self.plan.bearing_coordinates,
                                                      np.asarray(bearing_stiffnesses, float))
        return modal_analysis(self.isolated_mass_matrix, stiffness)


def bearing_transformation(x: float, y: float) -> np.ndarray:
    """``T_i``: the displacement of a bearing at ``(x, y)`` [m] from the base slab's
    ``(u_x, u_y, theta)``, ``u_i = (u_x - theta y, u_y + theta x)``, shape (2, 3)."""
    return np.array([[1.0, 0.0, -y], [0.0, 1.0, x]])


def bearing_stiffness_matrix(coordinates: np.ndarray, stiffnesses: np.ndarray) -> np.ndarray:
    """``sum_i k_i T_i^T T_i`` on the base slab's DOFs for isotropic linear bearings, (3, 3)
    [N/m, N, N m/rad]."""
    out = np.zeros((3, 3))
    for (x, y), k in zip(coordinates, stiffnesses, strict=True):
        t = bearing_transformation(x, y)
        out += k * (t.T @ t)
    return out
