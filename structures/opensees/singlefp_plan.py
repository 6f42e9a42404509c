"""Our building in plan with singleFPBearing 3D's normal force, to attribute the differences.

singleFPBearing (3D, ``SingleFPSimple3d.cpp``) does not slide under the load it is given: it
iterates its normal force ``N = P + F_X u_X / R_x + F_Y u_Y / R_y`` (``P`` the axial load,
``R_x = sqrt(R^2 - u_Y^2)``, ``R_y = sqrt(R^2 - u_X^2)``; see
:mod:`structures.opensees.bearing3d`). Our bearing takes ``N = P``. The lift, about
``(|u| / R)(|u| / R + mu)``, is most of the gap between the two runs of the building
(:mod:`structures.opensees.comparison3d`); :class:`SingleFPNormalForce` gives each of our
bearings that same ``N`` at every trial, solved by fixed-point iteration on the element (the
map contracts by about ``|u| / R (|u| / R + mu)``), so that what then remains of the gap is
the rest: the crossed radii of its restoring law and its return map with a fixed k0.

This is a diagnostic twin, not our model: the tangent leaves out ``dN / du`` (Newton still
converges, on the exact residual), overturning is not modelled, and the friction must not
depend on the load beyond ``mu N`` (Coulomb).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from groundmotions.pairs import GroundMotionPair
from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction
from structures.analysis import resampled_record
from structures.integrators import HHT, Newmark, as_method
from structures.model import RestoringForce
from structures.spatial.analysis import spatial_history
from structures.spatial.building import SpatialBuilding
from structures.spatial.isolated import SpatialIsolatedBuilding
from structures.spatial.results import spatial_dataset

__all__ = ["SingleFPNormalForce", "run_spatial_singlefp_normal"]

_TOLERANCE = 1e-13  # change of N between fixed-point iterations, relative to the load
_ITERATIONS = 50


class SingleFPNormalForce(SpatialIsolatedBuilding):
    """:class:`SpatialIsolatedBuilding` whose bearings see singleFPBearing 3D's normal force.

    Parameters
    ----------
    building : SpatialBuilding
        The building and its plan.
    bearing : DCFPBearing
        Coulomb friction, finite radius, linear law.
    vertical : GroundMotion, optional
        As :class:`SpatialIsolatedBuilding`.

    Raises
    ------
    ValueError
        For a friction other than ConstantFriction or an infinite radius.
    """

    def __init__(self, building: SpatialBuilding, bearing: DCFPBearing, *,
                 vertical=None) -> None:
        if not isinstance(bearing.friction, ConstantFriction) or not np.isfinite(
                bearing.effective_radius):
            raise ValueError("The bearing of SingleFPNormalForce must have a ConstantFriction "
                             f"and a finite radius. Got {bearing!r} instead.")
        super().__init__(building, bearing, overturning=False, vertical=vertical)
        self._radius = float(bearing.effective_radius)

    def _lever(self, u: np.ndarray) -> np.ndarray:
        """``(u_X / R_x, u_Y / R_y)`` with the crossed radii [-]."""
        return u / np.sqrt(self._radius**2 - u[::-1] ** 2)

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        """Storey forces plus the bearings' forces at singleFPBearing's normal force."""
        force = self.superstructure_stiffness @ u
        stiffness = np.array(self.superstructure_stiffness)
        damping = np.zeros_like(stiffness)
        loads = self.axial_loads(u, v, time)
        ub, vb = u[:3], v[:3]
        for element, t, load in zip(self.elements, self.transformations, loads, strict=True):
            ui, vi = t @ ub, t @ vb
            lever = self._lever(ui)
            normal = load
            for _ in range(_ITERATIONS):
                trial = element.set_trial(ui, vi, time, axial_load=normal)
                updated = load + float(trial.force @ lever)
                if abs(updated - normal) <= _TOLERANCE * abs(load):
                    break
                normal = updated
            force[:3] += t.T @ trial.force
            stiffness[:3, :3] += t.T @ trial.stiffness @ t
            damping[:3, :3] += t.T @ trial.damping @ t
        return RestoringForce(force, stiffness, damping)


def run_spatial_singlefp_normal(building: SpatialBuilding, bearing: DCFPBearing,
                                motion: GroundMotionPair,
                                integrator: str | Newmark | HHT = "newmark", *,
                                dt: float | None = None, tolerance: float = 1e-8,
                                max_subdivisions: int = 6):
    """:func:`structures.spatial.analysis.run_spatial` (no overturning) on
    :class:`SingleFPNormalForce`: the Dataset of a run in plan, ``engine`` attribute
    ``"reference, singleFPBearing N"``.

    Parameters
    ----------
    building, bearing, motion, integrator, dt, tolerance, max_subdivisions
        As :func:`~structures.spatial.analysis.run_spatial` (the bearing takes its gravity
        share).
    """
    model = SingleFPNormalForce(building, dataclasses.replace(bearing, axial_load=None),
                                vertical=motion.z)
    x, step = resampled_record(motion.x, dt)
    y, _ = resampled_record(motion.y, step)
    acceleration = np.column_stack([x, y])
    result, record, restoring, wall = spatial_history(
        model, acceleration, step, as_method(integrator), tolerance=tolerance,
        max_subdivisions=max_subdivisions)
    attrs = {"newton_iterations": int(result.iterations.sum()),
             "subdivisions": int(result.subdivisions.sum()), "wall_time": wall,
             "engine": "reference, singleFPBearing N"}
    return spatial_dataset(model, motion, step, acceleration[:result.time.size], result,
                           record, restoring, attrs=attrs)
