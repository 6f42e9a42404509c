"""The analysis of the building in plan repeated in OpenSees, returned in the same form.

:func:`run_opensees_3d` builds the building in plan on its bearings in openseespy
(:mod:`structures.opensees.model3d` describes the model) from the very objects
:func:`structures.spatial.analysis.run_spatial` takes, drives it with the same ground
acceleration samples and the same integrator, and returns the ``xarray.Dataset`` of
:func:`structures.spatial.results.spatial_dataset` (levels at the centre of stiffness, every
bearing, the energy balance computed from the recorded histories with our matrices).

Conventions (those of the planar twin, :mod:`structures.opensees.building`):

- Ground motion: the x and y samples on the analysis step (resampled as ours) as two
  ``timeSeries Path`` and ``pattern UniformExcitation`` in directions 1 and 2; only the
  masters carry mass, so the load is ``-m a_g`` at each centre of mass, ours ``-M R a_g``.
  A vertical component is a quasi-static load on each bearing (``-N_i a_z / g``, its samples
  at the record's own times, linear between them and held after the end, as ours).
- Initial state: ``a_0 = -R a_g(0)`` on every node (``setNodeAccel ... -commit``).
- ``Newmark(gamma, beta)`` and ``HHT(alpha)`` as :func:`~structures.opensees.building.
  opensees_integrator`; Newton with ``NormDispIncr``; the ``Transformation`` constraint
  handler (the rigid diaphragms); a step that fails is retried as two halves, recursively.

The run is recorded after each full step: the levels' centre-of-stiffness nodes (X, Y and the
rotation about Z: our degrees of freedom) and each bearing (force, normal force, mu).
"""

from __future__ import annotations

import dataclasses
import math
import time as _time

import numpy as np

from dcfpb.common.errors import InputTypeError
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_int, check_real
from groundmotions.pairs import GroundMotionPair
from isolator.bearing import DCFPBearing
from structures.analysis import resampled_record
from structures.integrators import HHT, IntegrationResult, Newmark, as_method
from structures.opensees.building import halving_step, opensees_integrator, transient_analysis
from structures.opensees.equivalents3d import singlefp3d_restoring
from structures.opensees.model3d import SpatialModel, build_model_3d
from structures.opensees.runtime import import_opensees
from structures.spatial.building import SpatialBuilding
from structures.spatial.isolated import SpatialIsolatedBuilding
from structures.spatial.results import spatial_dataset

__all__ = ["run_opensees_3d"]

_LEVEL_DOFS = (1, 2, 6)  # X, Y and the rotation about Z: our (u_x, u_y, theta)
_FIRST_SERIES = 10  # time-series and pattern tags of the ground motion


def _ground_motion(ops, model: SpatialModel, acceleration: np.ndarray, step: float,
                   pair: GroundMotionPair) -> None:
    """Uniform excitation in X and Y; the vertical as quasi-static loads on the bearings."""
    for axis in (0, 1):
        tag = _FIRST_SERIES + axis
        ops.timeSeries("Path", tag, "-dt", step, "-values", *acceleration[:, axis].tolist(),
                       "-useLast")  # the summed steps may pass the last sample by round-off
        ops.pattern("UniformExcitation", tag, axis + 1, "-accel", tag)
    if pair.z is not None:
        tag = _FIRST_SERIES + 2
        ops.timeSeries("Path", tag, "-time", *pair.z.time.tolist(), "-values",
                       *(pair.z.acceleration / STANDARD_GRAVITY).tolist(), "-useLast")
        ops.pattern("Plain", tag, tag)
        for node, share in zip(model.tops, model.shares, strict=True):
            ops.load(node, 0.0, 0.0, -float(share), 0.0, 0.0, 0.0)


def run_opensees_3d(
    building: SpatialBuilding,
    bearing: DCFPBearing,
    motion: GroundMotionPair,
    integrator: str | Newmark | HHT = "newmark",
    *,
    dt: float | None = None,
    pendulum: str = "singlefp",
    tolerance: float = 1e-10,
    max_subdivisions: int = 6,
):
    """Run the analysis of :func:`structures.spatial.analysis.run_spatial` in OpenSees.

    Parameters
    ----------
    building : SpatialBuilding
        The building and its plan (Rayleigh damping).
    bearing : DCFPBearing
        The bearing of every position: Coulomb friction, linear law; each carries its
        gravity share (a load given on the bearing is ignored).
    motion : GroundMotionPair
        Ground acceleration x, y and optionally z (positive up) [m/s^2].
    integrator : {"newmark", "hht"} or Newmark or HHT
        As :func:`~structures.spatial.analysis.run_spatial`.
    dt : float, optional
        Analysis step [s], as :func:`~structures.spatial.analysis.run_spatial`.
    pendulum : {"singlefp", "spring"}
        singleFPBearing 3D, or flatSliderBearing 3D plus linear springs N_i / R (our law);
        see :mod:`structures.opensees.model3d`.
    tolerance : float
        Displacement-increment tolerance of Newton's method [m].
    max_subdivisions : int
        Nested halvings of a step that does not converge.

    Returns
    -------
    xarray.Dataset
        As :func:`~structures.spatial.analysis.run_spatial` without overturning (the
        OpenSees model has none), with the attributes ``program``, ``element``,
        ``pendulum``, ``newton_iterations``, ``subdivisions`` and ``wall_time`` [s] (model
        building included).

    Raises
    ------
    ImportError
        Without openseespy.
    ValueError
        For a building or bearing the model cannot represent
        (:func:`~structures.opensees.model3d.build_model_3d`).
    """
    owner = "run_opensees_3d"
    if not isinstance(motion, GroundMotionPair):
        raise InputTypeError(f"The 'motion' parameter of {owner} must be a GroundMotionPair. "
                             f"Got {motion!r} instead.")
    check_real(tolerance, "tolerance", owner, low=0.0, low_open=True)
    check_int(max_subdivisions, "max_subdivisions", owner, low=0)
    arguments = opensees_integrator(integrator)
    method = as_method(integrator)
    native = SpatialIsolatedBuilding(building, dataclasses.replace(bearing, axial_load=None),
                                     overturning=False, vertical=motion.z)
    x, step = resampled_record(motion.x, dt)
    y, _ = resampled_record(motion.y, step)
    acceleration = np.column_stack([x, y])
    ops = import_opensees()
    ops.wipe()
    start = _time.perf_counter()
    try:
        model = build_model_3d(ops, building, native.bearing, pendulum)
        _ground_motion(ops, model, acceleration, step, motion)
        for tag in (*model.masters, *model.centres, *model.tops):
            ops.setNodeAccel(tag, 1, -float(acceleration[0, 0]), "-commit")
            ops.setNodeAccel(tag, 2, -float(acceleration[0, 1]), "-commit")
        transient_analysis(ops, arguments, tolerance, constraints="Transformation")
        histories, bearings, counts, message = _integrate(ops, model, step, x.size,
                                                          max_subdivisions, bearing)
        wall = _time.perf_counter() - start
        version = ops.version()
    finally:
        ops.wipe()
    u, v, a = histories
    kept = u.shape[0]
    ag = acceleration[:kept]
    result = IntegrationResult(
        step * np.arange(kept), u, v, a, a + ag @ native.influence.T, kept == x.size, message,
        np.zeros(max(kept - 1, 0), dtype=int), np.zeros(max(kept - 1, 0), dtype=int), method,
        "" if kept == x.size else "convergence", None if kept == x.size else step * kept)
    restoring = u @ native.superstructure_stiffness.T
    t = np.asarray(native.transformations)  # (n_b, 2, 3)
    restoring[:, :3] += np.einsum("bij,tbi->tj", t, bearings["force"])
    attrs = {"program": f"OpenSees {version} (openseespy)", "element": model.element,
             "pendulum": pendulum, "newton_iterations": counts[0], "subdivisions": counts[1],
             "wall_time": wall, "engine": "opensees"}
    return spatial_dataset(native, motion, step, ag, result, bearings, restoring, attrs=attrs)


def _integrate(ops, model: SpatialModel, step: float, nt: int, max_subdivisions: int,
               bearing: DCFPBearing):
    """The step loop: (u, v, a) on our DOFs (3, kept, n_dof), the bearings' record, counts."""
    levels = len(model.centres)
    n_b = len(model.tops)
    histories = np.zeros((3, nt, 3 * levels))
    for i, tag in enumerate(model.centres):
        for j, dof in enumerate(_LEVEL_DOFS):
            histories[2, 0, 3 * i + j] = ops.nodeAccel(tag, dof)
    record = {"displacement": np.zeros((nt, n_b, 2)), "force": np.zeros((nt, n_b, 2)),
              "friction_force": np.zeros((nt, n_b, 2)), "mu": np.zeros((nt, n_b)),
              "temperature": np.full((nt, n_b), bearing.friction.initial_temperature),
              "heat_flux": np.full((nt, n_b), math.nan), "axial_load": np.zeros((nt, n_b))}
    record["mu"][0], record["axial_load"][0] = bearing.friction.mu, model.shares
    counts = [0, 0]
    message = "The integration reached the end of the record."
    kept = nt
    for k in range(1, nt):
        if not halving_step(ops, step, 0, max_subdivisions, counts):
            message = (f"Step {k}: OpenSees did not converge in the step to t = {k * step:.6g} s "
                       f"after {max_subdivisions} halvings.")
            kept = k
            break
        for i, tag in enumerate(model.centres):
            for j, dof in enumerate(_LEVEL_DOFS):
                histories[:, k, 3 * i + j] = (ops.nodeDisp(tag, dof), ops.nodeVel(tag, dof),
                                              ops.nodeAccel(tag, dof))
        record["displacement"][k] = [(ops.nodeDisp(tag, 1), ops.nodeDisp(tag, 2))
                                     for tag in model.tops]
        force, normal, mu = model.record(ops)
        record["force"][k], record["axial_load"][k], record["mu"][k] = force, normal, mu
    record = {name: values[:kept] for name, values in record.items()}
    radius = bearing.effective_radius
    if "singleFPBearing" in model.element:  # its own law, with its normal force
        restoring = np.stack([singlefp3d_restoring(record["axial_load"][:, i],
                                                   record["displacement"][:, i], radius)
                              for i in range(n_b)], axis=1)
    elif math.isinf(radius):
        restoring = np.zeros_like(record["force"])
    else:  # flatSliderBearing + springs N_i / R
        restoring = model.shares[None, :, None] * record["displacement"] / radius
    record["friction_force"] = record["force"] - restoring
    return histories[:, :kept], record, counts, message
