"""A shear building on DCFPB isolators as a dynamic model (the integrators' protocol).

Degrees of freedom ``[u_b, u_1, ..., u_n]``: the base slab and the floors, relative to the
ground. The superstructure is linear (storey springs and dampers acting on the drifts); the
isolation level is ``n_bearings`` identical bearings that share the building's weight, reached
only through the element contract ``set_trial / commit / revert``. No damping acts on the
isolation level.
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from dcfpb.common.errors import InputWarning
from dcfpb.common.validation import check_int
from isolator.bearing import AxialLoadHistory, BearingElement, DCFPBearing
from structures.model import RestoringForce
from structures.shear_building import ShearBuilding


def _warn_if_replaced(given: object, load: float, n_bearings: int) -> None:
    """Say so when the building replaces an axial load the bearing was given."""
    if given is None:
        return
    if isinstance(given, AxialLoadHistory) or abs(float(given) - load) > 1e-9 * load:
        warnings.warn(
            f"The bearing's 'axial_load' ({given!r}) is replaced by the building's weight "
            f"shared by its {n_bearings} bearing(s), W / n = {load:.6g} N; describe the "
            "bearing with axial_load=None.", InputWarning, stacklevel=3)


class IsolatedShearBuilding:
    """Building + isolators implementing :class:`~structures.model.DynamicModel`.

    Parameters
    ----------
    building : ShearBuilding
        Floor masses, storey stiffnesses, base slab mass and superstructure damping.
    bearing : DCFPBearing
        One bearing of the isolation level, best described without an axial load
        (``axial_load=None``): its load is the building's weight shared equally by the
        bearings, W / n_bearings. A load given on the bearing that differs from it is replaced,
        with an :class:`~dcfpb.common.errors.InputWarning`.
    n_bearings : int
        Number of identical bearings under the base slab.
    """

    def __init__(self, building: ShearBuilding, bearing: DCFPBearing, n_bearings: int = 1):
        if not isinstance(building, ShearBuilding):
            raise TypeError(f"The 'building' parameter of {type(self).__name__} must be a "
                            f"ShearBuilding. Got {building!r} instead.")
        if not isinstance(bearing, DCFPBearing):
            raise TypeError(f"The 'bearing' parameter of {type(self).__name__} must be a "
                            f"DCFPBearing. Got {bearing!r} instead.")
        self.n_bearings = check_int(n_bearings, "n_bearings", type(self).__name__, low=1)
        self.building = building
        load = building.weight / self.n_bearings
        _warn_if_replaced(bearing.axial_load, load, self.n_bearings)
        self.bearing = dataclasses.replace(bearing, axial_load=load)
        self.element: BearingElement = self.bearing.element()
        self._mass = building.isolated_mass_matrix
        self._damping = building.isolated_damping_matrix
        self._stiffness = np.array(building.isolated_stiffness_matrix)
        self._influence = building.isolated_influence
        self._zeros = np.zeros_like(self._stiffness)

    @property
    def mass_matrix(self) -> np.ndarray:
        """Mass matrix on ``[u_b, u_1..u_n]`` [kg]."""
        return self._mass

    @property
    def damping_matrix(self) -> np.ndarray:
        """Superstructure damping on the drifts only [N s/m]."""
        return self._damping

    @property
    def influence(self) -> np.ndarray:
        """Ground-motion influence vector (ones) [-]."""
        return self._influence

    @property
    def superstructure_stiffness(self) -> np.ndarray:
        """Storey stiffness matrix on ``[u_b, u_1..u_n]`` without the isolators [N/m]."""
        return self._stiffness

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        """Storey spring forces plus the isolators' force on the base slab, and the tangent."""
        trial = self.element.set_trial(float(u[0]), float(v[0]), time)
        force = self._stiffness @ u
        force[0] += self.n_bearings * trial.force
        stiffness = self._stiffness.copy()
        stiffness[0, 0] += self.n_bearings * trial.stiffness
        damping = self._zeros.copy()
        damping[0, 0] = self.n_bearings * trial.damping
        return RestoringForce(force, stiffness, damping)

    def commit(self) -> None:
        """Accept the last trial of the isolators."""
        self.element.commit()

    def revert(self) -> None:
        """Return the isolators to their last committed state."""
        self.element.revert()

    def isolated_period(self) -> float:
        """Period of the rigid building on the pendulum stiffness, 2 pi sqrt(R_eff / g) [s]."""
        k = self.n_bearings * self.bearing.pendulum_stiffness
        return float(2 * np.pi * np.sqrt(self.building.total_mass / k)) if k > 0 else np.inf
