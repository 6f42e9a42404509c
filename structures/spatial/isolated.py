"""A building in plan on DCFPB isolators as a dynamic model (the integrators' protocol).

Degrees of freedom: those of :class:`~structures.spatial.building.SpatialBuilding`, the base
slab's ``(u_x, u_y, theta)`` first. Bearing ``i`` at ``(x_i, y_i)`` is a
:class:`~isolator.bearing.BearingElement` whose plates move apart by
``u_i = T_i q_b = (u_x - theta y_i, u_y + theta x_i)``; its force ``F_i`` acts on the base slab as
``T_i^T F_i`` (force x, force y, torque about O) and its 2x2 tangents as ``T_i^T K_i T_i``.
No viscous damping acts on the isolation level.

Axial loads, evaluated at every trial (:meth:`SpatialIsolatedBuilding.axial_loads`)::

    N_i = N_i,gravity (1 + a_z(t) / g) + G_i1 sum_j H_j F_x,j + G_i2 sum_j H_j F_y,j

- ``N_i,gravity``: the gravity share by the statics of the rigid base
  (:func:`structures.spatial.plan.gravity_shares`);
- ``a_z``: the vertical ground acceleration [m/s^2], positive up, when a vertical component
  is given (the building is rigid vertically, so it scales the weight and its moments alike);
- overturning: the floors' inertia forces ``F_j = -(M a_abs)_j``, which equal the storey
  forces acting on floor j, ``(K_s u + C v)_j``, at the floor's height ``H_j`` above the
  isolation level; their moments ``sum_j H_j F_j`` are shared linearly over the bearings
  (``G`` of :func:`structures.spatial.plan.axial_distribution`). The base slab's own inertia has no
  lever arm. Being a function of ``(u, v)``, the loads enter the tangent: ``dF_i / dN_i``
  times ``dN_i / du`` and ``dN_i / dv``, with ``dF_i / dN_i = F_i / N_i`` (exact for the
  constant model; the PTV models' pressure dependence of mu is left out of the tangent only,
  the residual is exact). P-delta effects are not modelled.

Uplift is the element's: a bearing whose load is not positive carries no force and makes no
heat (the loads are not redistributed to the others). With a symmetric plan, equal shares and
no overturning, a motion along x or y is the planar :class:`IsolatedShearBuilding` with
``n_bearings`` bearings.
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from dcfpb.common.errors import InputTypeError, InputWarning
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from isolator.bearing import BearingElement, BearingState
from structures.model import RestoringForce
from structures.spatial.building import SpatialBuilding, bearing_transformation, dof

__all__ = ["SpatialIsolatedBuilding"]


class SpatialIsolatedBuilding:
    """Building in plan + isolators implementing :class:`~structures.model.DynamicModel`.

    Parameters
    ----------
    building : SpatialBuilding
        The building and its plan (bearing positions, gravity shares).
    bearing : DCFPBearing
        The bearing of every position, best without an axial load (``axial_load=None``): each
        takes its gravity share (a load given on the bearing is replaced, with an
        :class:`~dcfpb.common.errors.InputWarning`).
    overturning : bool
        Add the overturning moment of the floors' inertia forces to the axial loads (needs
        the plan's ``storey_heights``). Default True.
    vertical : GroundMotion, optional
        Vertical ground acceleration [m/s^2], positive up, from ``t = 0`` (linear between its
        samples, held after its end).
    grid_orientation : float, optional
        The precise model's monitor grid orientation [deg] (None: follows the motion).
    """

    def __init__(self, building: SpatialBuilding, bearing: DCFPBearing, *,
                 overturning: bool = True, vertical: GroundMotion | None = None,
                 grid_orientation: float | None = None) -> None:
        owner = type(self).__name__
        for name, value, kind in (("building", building, SpatialBuilding),
                                  ("bearing", bearing, DCFPBearing)):
            if not isinstance(value, kind):
                raise InputTypeError(f"The {name!r} parameter of {owner} must be a "
                                     f"{kind.__name__}. Got {value!r} instead.")
        if vertical is not None and not isinstance(vertical, GroundMotion):
            raise InputTypeError(f"The 'vertical' parameter of {owner} must be a GroundMotion "
                                 f"or None. Got {vertical!r} instead.")
        self.building = building
        self.overturning = bool(overturning)
        self.vertical = vertical
        shares = building.gravity_shares
        if bearing.axial_load is not None:
            warnings.warn(
                f"The bearing's 'axial_load' ({bearing.axial_load!r}) is replaced by each "
                f"bearing's gravity share ({shares.min():.6g} to {shares.max():.6g} N); "
                "describe the bearing with axial_load=None.", InputWarning, stacklevel=2)
        self.bearing = dataclasses.replace(bearing, axial_load=None)
        self.bearings = tuple(dataclasses.replace(bearing, axial_load=float(share))
                              for share in shares)
        self.elements = tuple(BearingElement(b, 2, grid_orientation) for b in self.bearings)
        self.transformations = tuple(bearing_transformation(x, y)
                                     for x, y in building.plan.bearing_coordinates)
        self._gravity = shares
        self._mass = building.isolated_mass_matrix
        self._damping = building.isolated_damping_matrix
        self._stiffness = np.array(building.isolated_stiffness_matrix)
        self._influence = building.isolated_influence
        n = building.n_dof
        self._overturning = np.zeros((len(shares), n))
        if self.overturning:
            heights = building.plan.floor_heights(building.n_storeys)
            levels = np.arange(1, building.n_storeys + 1)
            arm_x, arm_y = np.zeros(n), np.zeros(n)
            arm_x[dof(levels, 0)], arm_y[dof(levels, 1)] = heights, heights
            g = building.axial_distribution
            self._overturning = np.outer(g[:, 1], arm_x) + np.outer(g[:, 2], arm_y)
        self._load_du = self._overturning @ self._stiffness  # dN / du [N/m]
        self._load_dv = self._overturning @ self._damping  # dN / dv [N s/m]

    @property
    def n_bearings(self) -> int:
        """Number of bearings [-]."""
        return len(self.elements)

    @property
    def mass_matrix(self) -> np.ndarray:
        """Mass matrix on the levels' ``(u_x, u_y, theta)``."""
        return self._mass

    @property
    def damping_matrix(self) -> np.ndarray:
        """Superstructure damping on the drifts only."""
        return self._damping

    @property
    def influence(self) -> np.ndarray:
        """Influence of the (x, y) ground acceleration, shape (n_dof, 2) [-]."""
        return self._influence

    @property
    def superstructure_stiffness(self) -> np.ndarray:
        """Storey stiffness matrix without the isolators."""
        return self._stiffness

    @property
    def gravity_shares(self) -> np.ndarray:
        """Each bearing's share of the weight at rest, shape (n_b,) [N]."""
        return self._gravity

    @property
    def overturning_matrix(self) -> np.ndarray:
        """``G H``: the axial loads' share of the storey forces ``K_s u + C v``, shape
        (n_b, n_dof) [m] (zeros without overturning)."""
        return self._overturning

    @property
    def load_du(self) -> np.ndarray:
        """dN / du of the axial loads through the overturning, shape (n_b, n_dof) [N/m]."""
        return self._load_du

    @property
    def load_dv(self) -> np.ndarray:
        """dN / dv of the axial loads through the overturning, shape (n_b, n_dof) [N s/m]."""
        return self._load_dv

    def vertical_acceleration(self, time: float) -> float:
        """Vertical ground acceleration at ``time`` [m/s^2] (0 without a vertical)."""
        if self.vertical is None:
            return 0.0
        return float(np.interp(time, self.vertical.time, self.vertical.acceleration))

    def vertical_accelerations(self, times: np.ndarray) -> np.ndarray:
        """Vertical ground acceleration at each of ``times`` [s], one interpolation for all
        (the values of :meth:`vertical_acceleration`), shape of ``times`` [m/s^2]."""
        times = np.asarray(times, dtype=float)
        if self.vertical is None:
            return np.zeros_like(times)
        return np.interp(times, self.vertical.time, self.vertical.acceleration)

    def axial_loads(self, u: np.ndarray, v: np.ndarray, time: float) -> np.ndarray:
        """Axial load of each bearing at a trial state (module docstring), (n_b,) [N];
        zero or negative is uplift."""
        loads = self._gravity * (1.0 + self.vertical_acceleration(time) / STANDARD_GRAVITY)
        if self.overturning:
            loads = loads + self._overturning @ (self._stiffness @ u + self._damping @ v)
        return loads

    def bearing_displacements(self, u: np.ndarray) -> np.ndarray:
        """Displacement ``(x, y)`` of each bearing, shape (n_b, 2) [m], or (nt, n_b, 2)
        for a history ``u`` of shape (nt, n_dof)."""
        t = np.asarray(self.transformations)  # (n_b, 2, 3)
        return np.einsum("bij,...j->...bi", t, np.asarray(u)[..., :3])

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        """Storey forces plus the bearings' forces on the base slab, and the tangents."""
        force = self._stiffness @ u
        stiffness = self._stiffness.copy()
        damping = np.zeros_like(stiffness)
        loads = self.axial_loads(u, v, time)
        ub, vb = u[:3], v[:3]
        for element, t, load, du, dv in zip(self.elements, self.transformations, loads,
                                            self._load_du, self._load_dv, strict=True):
            trial = element.set_trial(t @ ub, t @ vb, time, axial_load=load)
            force[:3] += t.T @ trial.force
            stiffness[:3, :3] += t.T @ trial.stiffness @ t
            damping[:3, :3] += t.T @ trial.damping @ t
            if self.overturning and load > 0.0:
                per_load = t.T @ (trial.force / load)  # d(T^T F_i) / dN_i
                stiffness[:3] += np.outer(per_load, du)
                damping[:3] += np.outer(per_load, dv)
        return RestoringForce(force, stiffness, damping)

    def committed_states(self) -> tuple[BearingState, ...]:
        """The committed state of every bearing."""
        return tuple(element.committed for element in self.elements)

    def commit(self) -> None:
        """Accept the last trial of every bearing."""
        for element in self.elements:
            element.commit()

    def revert(self) -> None:
        """Return every bearing to its last committed state."""
        for element in self.elements:
            element.revert()

    def isolated_period(self) -> float:
        """Period of the rigid building on the pendulums, 2 pi sqrt(R_eff / g) [s]."""
        stiffness = self.building.weight / self.bearing.effective_radius
        return float(2 * np.pi * np.sqrt(self.building.total_mass / stiffness)) \
            if stiffness > 0 else np.inf
