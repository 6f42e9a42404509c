"""A shear building on DCFPB isolators, in one direction or in plan, as a
:class:`~structures.model.DynamicModel` on the degrees of freedom of
:class:`~structures.shear_building.ShearBuilding`.

Each bearing position holds a multiplicity and a :class:`~isolator.bearing.BearingElement`,
used only through ``set_trial / commit / revert``: in one direction one group of ``n_bearings``
identical bearings moving with the base slab along x; in plan one bearing at each ``(x_i, y_i)``,
displaced by ``u_i = T_i q_b`` (:func:`structures.plan.bearing_transformation`) and acting on
the base slab as ``T_i^T F_i``, tangent ``T_i^T K_i T_i``. The isolation level has no viscous
damping; P-delta effects are not modelled. The axial load of one bearing at each position, at
every trial (:meth:`IsolatedShearBuilding.axial_loads`), is::

    N_i = N_i,gravity (1 + a_z(t) / g) + G_i1 sum_j H_j F_x,j + G_i2 sum_j H_j F_y,j

with the weight shares ``N_i,gravity`` (W / n in one direction,
:func:`structures.plan.gravity_shares` in plan), the vertical ground acceleration ``a_z``
[m/s^2], positive up, and, in plan with overturning, the storey forces on each floor
``F_j = (K_s u + C v)_j`` [N] at its height ``H_j`` [m], shared by ``G``
(:func:`structures.plan.axial_distribution`). The tangent includes ``F_i / N_i`` times
``dN_i / du`` and ``dN_i / dv`` (the PTV models' pressure dependence of mu left out). A bearing
whose load is not positive lifts off: no force, no heat, no redistribution.
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from dcfpb.common.errors import InputError, InputWarning
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_instance, check_int
from groundmotions.records import GroundMotion
from isolator.bearing import BearingElement, BearingState, DCFPBearing
from structures.model import ConstantMatrices, RestoringForce
from structures.plan import bearing_transformation
from structures.shear_building import ShearBuilding

__all__ = ["IsolatedShearBuilding"]


class IsolatedShearBuilding(ConstantMatrices):
    """Building + isolators implementing :class:`~structures.model.DynamicModel` (the
    superstructure's damping acts on the drifts only; the influence is (n_dof, 2) in plan).

    Parameters
    ----------
    building : ShearBuilding
        The superstructure and base slab, with its plan for a building in plan.
    bearing : DCFPBearing
        The bearing of every position, best given with ``axial_load=None``: each takes its
        share of the weight (a load given is replaced, with an
        :class:`~dcfpb.common.errors.InputWarning`).
    n_bearings : int, optional
        Identical bearings under the base slab in one direction (default 1). In plan, one per
        bearing position: leave it out or give that number.
    overturning : bool
        In plan, add the overturning moment of the floors' inertia forces to the axial loads
        (needs the plan's ``storey_heights``). Default True; no effect in one direction.
    vertical : GroundMotion, optional
        Vertical ground acceleration [m/s^2], positive up, from ``t = 0`` (linear between its
        samples, held after its end).
    grid_orientation : float, optional
        The precise model's monitor grid orientation in plan [deg] (None: follows the motion).
    """

    def __init__(self, building: ShearBuilding, bearing: DCFPBearing,
                 n_bearings: int | None = None, *, overturning: bool = True,
                 vertical: GroundMotion | None = None,
                 grid_orientation: float | None = None) -> None:
        owner = type(self).__name__
        check_instance(building, "building", owner, ShearBuilding, "a ShearBuilding")
        check_instance(bearing, "bearing", owner, DCFPBearing, "a DCFPBearing")
        check_instance(vertical, "vertical", owner, GroundMotion | None,
                       "a GroundMotion or None")
        self.building = building
        self.level_dofs = building.level_dofs
        positions = building.bearing_positions
        if building.plan is None:
            count = 1 if n_bearings is None else check_int(n_bearings, "n_bearings", owner,
                                                             low=1)
            self.multiplicity = np.array([count])
        else:
            if n_bearings is not None and n_bearings != len(positions):
                raise InputError(f"The 'n_bearings' parameter of {owner} must be the number "
                                 f"of bearing positions of the plan ({len(positions)}) or None. "
                                 f"Got {n_bearings!r} instead.")
            self.multiplicity = np.ones(len(positions), dtype=int)
        self.n_bearings = int(self.multiplicity.sum())
        self._count = float(self.multiplicity[0])  # the one group's, in one direction
        self.gravity_loads = building.gravity_shares / self.multiplicity  # one bearing's [N]
        _warn_if_replaced(bearing.axial_load, self.gravity_loads, stacklevel=3)
        self.bearing = dataclasses.replace(bearing, axial_load=None)
        self.bearings = tuple(dataclasses.replace(bearing, axial_load=float(load))
                              for load in self.gravity_loads)
        self.elements = tuple(BearingElement(b, len(building.directions), grid_orientation)
                              for b in self.bearings)
        self.transformations = tuple(bearing_transformation(x, y) for x, y in positions)
        self.overturning = bool(overturning) and building.plan is not None
        self.vertical = vertical
        self._mass = building.isolated_mass_matrix
        self._damping = building.isolated_damping_matrix
        self._stiffness = np.array(building.isolated_stiffness_matrix)
        self._influence = building.isolated_influence
        n = building.n_dof
        self._overturning = np.zeros((len(positions), n))
        if self.overturning:
            heights = building.plan.floor_heights(building.n_storeys)
            levels = np.arange(1, building.n_storeys + 1)
            arm_x, arm_y = np.zeros(n), np.zeros(n)
            arm_x[3 * levels], arm_y[3 * levels + 1] = heights, heights
            g = building.axial_distribution
            self._overturning = np.outer(g[:, 1], arm_x) + np.outer(g[:, 2], arm_y)
        self._load_du = self._overturning @ self._stiffness  # dN / du [N/m]
        self._load_dv = self._overturning @ self._damping  # dN / dv [N s/m]

    @property
    def positions(self) -> np.ndarray:
        """Where the bearing positions stand, shape (n_b, 2) [m]."""
        return self.building.bearing_positions

    @property
    def superstructure_stiffness(self) -> np.ndarray:
        """Storey stiffness matrix without the isolators [N/m, ...]."""
        return self._stiffness

    @property
    def overturning_matrix(self) -> np.ndarray:
        """``G H``, the axial loads per storey force ``K_s u + C v``, (n_b, n_dof) [-, 1/m]."""
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
        """Vertical ground acceleration [m/s^2] at each of ``times`` [s], shape of ``times``."""
        times = np.asarray(times, dtype=float)
        if self.vertical is None:
            return np.zeros_like(times)
        return np.interp(times, self.vertical.time, self.vertical.acceleration)

    def axial_loads(self, u: np.ndarray, v: np.ndarray, time: float) -> np.ndarray:
        """Axial load of one bearing at each position at a trial state, (n_b,) [N]; <= 0: uplift."""
        if self.vertical is None and not self.overturning:
            return self.gravity_loads
        loads = self.gravity_loads * (1.0 + self.vertical_acceleration(time) / STANDARD_GRAVITY)
        if self.overturning:
            loads = loads + self._overturning @ (self._stiffness @ u + self._damping @ v)
        return loads

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        """Storey forces plus the bearings' forces on the base slab, and the tangents."""
        force = self._stiffness @ u
        stiffness = self._stiffness.copy()
        damping = np.zeros(stiffness.shape)
        loads = self.axial_loads(u, v, time)
        if self.level_dofs == 1:  # one group along x on the base slab's one DOF
            (element,), count = self.elements, self._count
            trial = element.set_trial(float(u[0]), float(v[0]), time, axial_load=float(loads[0]))
            force[0] += count * trial.force
            stiffness[0, 0] += count * trial.stiffness
            damping[0, 0] = count * trial.damping
            return RestoringForce(force, stiffness, damping)
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
        """The committed state of one bearing at each position."""
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


def _warn_if_replaced(given: object, loads: np.ndarray, *, stacklevel: int) -> None:
    """Say so when the building replaces an axial load the bearing was given."""
    if given is None:
        return
    if isinstance(given, float | int) and np.all(np.abs(loads - float(given)) <= 1e-9 * loads):
        return
    share = (f"W / n = {loads[0]:.6g} N" if loads.size == 1
             else f"{loads.min():.6g} to {loads.max():.6g} N")
    warnings.warn(
        f"The bearing's 'axial_load' ({given!r}) is replaced by the building's weight shared by "
        f"its bearings ({share}); describe the bearing with axial_load=None.", InputWarning,
        stacklevel=stacklevel + 1)
