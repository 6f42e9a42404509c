"""singleFPBearing's normal force ``N = P + F . u / R`` (``SingleFPSimple3d.cpp``, radii
crossed) given to our bearing (``N = P``), to attribute the differences: that lift is most of
the gap. :func:`singlefp_normal_force` for our test rig; :class:`SingleFPNormalForce`, run by
:func:`run_singlefp_normal`, for our building (a diagnostic twin: Coulomb friction only, the
tangent without ``dN / du``).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from dcfpb.common.errors import InputError
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from isolator.bearing import AxialLoadHistory, DCFPBearing
from isolator.testrig import imposed_history, run_test
from structures.analysis import ground_record, reference_history
from structures.integrators import HHT, Newmark, as_method
from structures.isolated_building import IsolatedShearBuilding
from structures.model import RestoringForce
from structures.opensees.elements import constant_axial_load, singlefp_restoring
from structures.results import history_dataset
from structures.shear_building import ShearBuilding

__all__ = ["SingleFPNormalForce", "run_singlefp_normal", "singlefp_normal_force"]

_TOLERANCE = 1e-13  # change of N between fixed-point iterations in a trial, relative to P
_ITERATIONS = 50


def _lever(displacement, radius: float, dimension: int) -> np.ndarray:
    """``(u_X / R_x, u_Y / R_y)`` of (..., 2) displacements [m] (``dimension`` 2), or ``u / R``."""
    u = np.asarray(displacement, dtype=float)
    if dimension == 2:
        return singlefp_restoring(np.ones(u.shape[:-1]), u, radius)
    return u / radius


def singlefp_normal_force(
    bearing: DCFPBearing,
    time: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray | None = None,
    *,
    tolerance: float = 1e-12,
    max_iterations: int = 20,
) -> AxialLoadHistory:
    """The normal force singleFPBearing uses under an imposed history, from our element, as an
    ``AxialLoadHistory`` [N] (times relative to the first): fixed-point iteration on
    :func:`~isolator.testrig.run_test`, N_0 = W, N_(k+1) = W + F_k . (u_X / R_x, u_Y / R_y),
    contracting by about |u| / R (|u| / R + mu) (0.4 % for |u| = 0.2 m, R = 4.5 m).

    Parameters
    ----------
    bearing : DCFPBearing
        A bearing with a constant axial load W [N] and a finite radius.
    time, displacement, velocity
        As :func:`~isolator.testrig.run_test`: (n,) times [s], (n,) or (n, 2) displacement
        [m] and velocity [m/s].
    tolerance, max_iterations
        Largest change of N between iterations, relative to W [-]; iterations allowed.

    Raises ValueError if the axial load is not constant or the iteration does not converge.
    """
    owner = "singlefp_normal_force"
    weight = constant_axial_load(bearing, owner)
    t, u, v = imposed_history(time, displacement, velocity, owner)
    lever = _lever(u, bearing.effective_radius, u.ndim)
    relative = t - t[0]
    normal = np.full(t.size, weight)
    change = math.inf
    for _ in range(max_iterations):
        trial = replace(bearing, axial_load=AxialLoadHistory(relative, normal))
        force = run_test(trial, t, u, v).force
        updated = weight + np.reshape(force * lever, (t.size, -1)).sum(axis=1)
        change = float(np.max(np.abs(updated - normal))) / weight
        normal = updated
        if change <= tolerance:
            return AxialLoadHistory(relative, normal)
    raise ValueError(f"{owner} did not converge in {max_iterations} iterations "
                     f"(last relative change {change:.3g}).")


class SingleFPNormalForce(IsolatedShearBuilding):
    """:class:`IsolatedShearBuilding` whose bearings see singleFPBearing's normal force (a
    fixed point per bearing at every trial). Arguments as :class:`IsolatedShearBuilding`
    (``overturning`` False by default); raises ValueError unless the friction is the constant
    model and the radius finite."""

    def __init__(self, building: ShearBuilding, bearing: DCFPBearing,
                 n_bearings: int | None = None, *, overturning: bool = False,
                 vertical: GroundMotion | None = None) -> None:
        if bearing.friction.name != "constant" or not np.isfinite(bearing.effective_radius):
            raise InputError("The bearing of SingleFPNormalForce must have a ConstantFriction "
                             f"and a finite radius. Got {bearing!r} instead.")
        super().__init__(building, bearing, n_bearings, overturning=overturning,
                         vertical=vertical)

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        """Storey forces plus the bearings' forces at singleFPBearing's normal force."""
        dofs, radius = self.level_dofs, self.bearing.effective_radius
        force = self.superstructure_stiffness @ u
        stiffness = np.array(self.superstructure_stiffness)
        damping = np.zeros_like(stiffness)
        loads = self.axial_loads(u, v, time)
        for element, t, count, load in zip(self.elements, self.transformations,
                                           self.multiplicity, loads, strict=True):
            t = t[:, :3] if dofs == 3 else t[:1, :1]  # one direction: x of the base slab
            ui, vi = t @ u[:dofs], t @ v[:dofs]
            if dofs == 1:
                ui, vi = float(ui[0]), float(vi[0])
            lever = _lever(ui, radius, 2 if dofs == 3 else 1)
            normal = load
            for _ in range(_ITERATIONS):
                trial = element.set_trial(ui, vi, time, axial_load=normal)
                updated = load + float(np.sum(trial.force * lever))
                if abs(updated - normal) <= _TOLERANCE * abs(load):
                    break
                normal = updated
            force[:dofs] += count * (t.T @ np.atleast_1d(trial.force))
            stiffness[:dofs, :dofs] += count * (t.T @ np.atleast_2d(trial.stiffness) @ t)
            damping[:dofs, :dofs] += count * (t.T @ np.atleast_2d(trial.damping) @ t)
        return RestoringForce(force, stiffness, damping)


def run_singlefp_normal(building: ShearBuilding, bearing: DCFPBearing,
                        motion: GroundMotion | GroundMotionPair,
                        integrator: str | Newmark | HHT = "newmark", *,
                        n_bearings: int | None = None, dt: float | None = None,
                        overturning: bool = False, tolerance: float = 1e-8,
                        max_subdivisions: int = 6):
    """:func:`structures.analysis.run` (reference engine) on :class:`SingleFPNormalForce`: the
    Dataset of a run, ``engine`` attribute ``"reference, singleFPBearing N"``. Arguments as
    :func:`~structures.analysis.run` (each bearing takes its gravity share); ``overturning``
    (default False): in plan, ``P`` with the overturning of the floors' inertia forces."""
    pair = isinstance(motion, GroundMotionPair)
    model = SingleFPNormalForce(building, replace(bearing, axial_load=None), n_bearings,
                                overturning=overturning, vertical=motion.z if pair else None)
    acceleration, step = ground_record(motion, dt)
    history = reference_history(model, acceleration, step, as_method(integrator),
                                tolerance=tolerance, max_subdivisions=max_subdivisions)
    return history_dataset(model, motion, step, acceleration, history,
                           engine="reference, singleFPBearing N")
