"""The analysis of :func:`structures.analysis.run` repeated in OpenSees, returned in the same
form: the same ground-acceleration samples [m/s^2] (``UniformExcitation``; a vertical as loads
``-P_i a_z / g`` on the bearings), initial accelerations ``-R a_g(0)``, the same integrator
(:func:`opensees_integrator`), Newton with halving on failure (:func:`halving_step`). Recorded
after each full step: the levels at O and one bearing per position.
"""

from __future__ import annotations

import time as _time

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_int, check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from structures.analysis import check_motion, ground_record
from structures.integrators import HHT, METHODS, Newmark, as_method
from structures.isolated_building import IsolatedShearBuilding
from structures.opensees.elements import element_kind
from structures.opensees.model import Twin, build_model
from structures.opensees.runtime import import_opensees
from structures.results import BEARING_RECORD, response_dataset
from structures.shear_building import ShearBuilding

__all__ = ["halving_step", "opensees_integrator", "run_opensees"]

_FIRST_SERIES = 10  # time-series and pattern tags of the ground motion


def opensees_integrator(method: str | Newmark | HHT) -> tuple:
    """``("Newmark", gamma, beta)`` or ``("HHT", 1 + alpha)``: the arguments of OpenSees's
    ``integrator`` command for one of our methods (``"newmark"``, ``"hht"`` or an instance)."""
    if isinstance(method, str):
        method = METHODS[method]() if method in METHODS else method
    if isinstance(method, HHT):
        return ("HHT", 1.0 + method.alpha)
    if isinstance(method, Newmark):
        return ("Newmark", method.gamma, method.beta)
    raise InputTypeError(f"The 'integrator' parameter of run_opensees must be one of "
                         f"{tuple(METHODS)} or a Newmark or HHT instance. Got {method!r} instead.")


def halving_step(ops, dt: float, depth: int, limit: int, counts: list[int]) -> bool:
    """One step of ``dt`` [s], halved recursively on failure; counts = [iterations, halvings]."""
    if ops.analyze(1, dt) == 0:
        counts[0] += ops.testIter()
        return True
    counts[0] += ops.testIter()
    if depth >= limit:
        return False
    counts[1] += 1
    half = 0.5 * dt
    return (halving_step(ops, half, depth + 1, limit, counts)
            and halving_step(ops, half, depth + 1, limit, counts))


def run_opensees(
    building: ShearBuilding,
    bearing: DCFPBearing,
    motion: GroundMotion | GroundMotionPair,
    integrator: str | Newmark | HHT = "newmark",
    *,
    n_bearings: int | None = None,
    dt: float | None = None,
    pendulum: str = "singlefp",
    overturning: bool = True,
    tolerance: float = 1e-10,
    max_subdivisions: int = 6,
):
    """Run the time-history analysis of :func:`structures.analysis.run` in OpenSees.

    Parameters
    ----------
    building, bearing, motion, integrator, n_bearings, dt, overturning
        As :func:`structures.analysis.run`: a record for a building in one direction, a pair
        (x, y, optionally z) for a building in plan. The bearing's friction model selects the
        element (:func:`~structures.opensees.elements.element_kind`).
    pendulum : {"singlefp", "spring"}
        As :func:`~structures.opensees.elements.add_bearing`; not used for FPBearingPTV.
    tolerance, max_subdivisions
        Displacement-increment tolerance of Newton's method [m]; nested halvings of a step that
        does not converge.

    Returns the Dataset of :func:`structures.analysis.run` with the attributes ``program``,
    ``element``, ``pendulum`` (``"spherical"`` for FPBearingPTV), ``newton_iterations``,
    ``subdivisions``, ``wall_time`` [s] (model building included) and ``engine = "opensees"``;
    ``axial_load`` is the elements' normal force [N], ``heat_flux`` NaN without heating. Raises
    ImportError without openseespy; ValueError or TypeError for a model OpenSees cannot represent
    here (HHT with FPBearingPTV among them).
    """
    owner = "run_opensees"
    pair = check_motion(building, motion, owner)
    check_real(tolerance, "tolerance", owner, low=0.0, low_open=True)
    check_int(max_subdivisions, "max_subdivisions", owner, low=0)
    arguments = opensees_integrator(integrator)
    native = IsolatedShearBuilding(building, bearing, n_bearings, overturning=overturning,
                                   vertical=motion.z if pair else None)
    if arguments[0] == "HHT" and element_kind(native.bearing) == "ptv":
        raise InputError(
            f"The 'integrator' parameter of {owner} must be Newmark for FPBearingPTV: the "
            "element appends to its heat history whenever the domain time advances, and "
            "OpenSees's HHT moves it to t + alpha dt within each step, so the history gets "
            f"two uneven entries per step. Got {integrator!r} instead.")
    acceleration, step = ground_record(motion, dt)
    acceleration = acceleration.reshape(acceleration.shape[0], -1)  # (nt, directions)
    ops = import_opensees()
    ops.wipe()
    start = _time.perf_counter()
    try:
        twin = build_model(ops, native, pendulum)
        _ground_motion(ops, twin, acceleration, step, motion.z if pair else None)
        for tag in twin.nodes:  # a_0 = -R a_g(0), as our integrator starts
            for axis, value in enumerate(acceleration[0]):
                ops.setNodeAccel(tag, axis + 1, -float(value), "-commit")
        for command, *values in (("constraints", "Transformation"), ("numberer", "Plain"),
                                 ("system", "FullGeneral"), ("test", "NormDispIncr", tolerance,
                                                             50),
                                 ("algorithm", "Newton"), ("integrator", *arguments),
                                 ("analysis", "Transient")):
            getattr(ops, command)(*values)
        histories, bearings, counts, message = _integrate(ops, twin, step, acceleration.shape[0],
                                                          max_subdivisions)
        wall = _time.perf_counter() - start
        version = ops.version()
    finally:
        ops.wipe()
    u, v, a = histories
    kept = u.shape[0]
    ag = acceleration[:kept]
    influence = np.reshape(native.influence, (u.shape[1], -1))
    success = kept == acceleration.shape[0]
    return response_dataset(
        native, motion, step, ag, u, v, a + ag @ influence.T, bearings,
        integrator=repr(as_method(integrator)), success=success, message=message,
        failure="" if success else "convergence", failed_at=None if success else step * kept,
        attrs={"program": f"OpenSees {version} (openseespy)", "element": twin.element,
               "pendulum": "spherical" if "FPBearingPTV" in twin.element else pendulum,
               "newton_iterations": counts[0], "subdivisions": counts[1], "wall_time": wall,
               "compile_time": 0.0, "engine": "opensees"})


def _ground_motion(ops, twin: Twin, acceleration: np.ndarray, step: float,
                   vertical: GroundMotion | None) -> None:
    """Uniform excitation per direction; the vertical as quasi-static loads on the bearings."""
    for axis in range(acceleration.shape[1]):
        tag = _FIRST_SERIES + axis
        ops.timeSeries("Path", tag, "-dt", step, "-values", *acceleration[:, axis].tolist(),
                       "-useLast")  # the summed steps may pass the last sample by round-off
        ops.pattern("UniformExcitation", tag, axis + 1, "-accel", tag)
    if vertical is not None:
        tag = _FIRST_SERIES + 2
        ops.timeSeries("Path", tag, "-time", *vertical.time.tolist(), "-values",
                       *(vertical.acceleration / STANDARD_GRAVITY).tolist(), "-useLast")
        ops.pattern("Plain", tag, tag)
        for node, load in zip(twin.tops, twin.loads, strict=True):
            ops.load(node, 0.0, 0.0, -float(load), 0.0, 0.0, 0.0)


def _integrate(ops, twin: Twin, step: float, nt: int, max_subdivisions: int):
    """The step loop: (u, v, a) on our degrees of freedom (3, kept, n_dof), the bearings'
    records (:data:`~structures.results.BEARING_RECORD`), counts and the message."""
    dofs = [(tag, dof) for tag in twin.levels for dof in twin.dofs]
    histories = np.zeros((3, nt, len(dofs)))
    histories[2, 0] = [ops.nodeAccel(tag, dof) for tag, dof in dofs]
    record = {name: np.zeros((nt, *np.shape(value))) for name, value in twin.initial.items()}
    for name, value in twin.initial.items():
        record[name][0] = value
    counts = [0, 0]
    message = "The integration reached the end of the record."
    kept = nt
    for k in range(1, nt):
        if not halving_step(ops, step, 0, max_subdivisions, counts):
            message = (f"Step {k}: OpenSees did not converge in the step to t = {k * step:.6g} s "
                       f"after {max_subdivisions} halvings.")
            kept = k
            break
        histories[:, k] = [[ops.nodeDisp(tag, dof) for tag, dof in dofs],
                           [ops.nodeVel(tag, dof) for tag, dof in dofs],
                           [ops.nodeAccel(tag, dof) for tag, dof in dofs]]
        for name, value in twin.read(ops).items():
            record[name][k] = value
    return (histories[:, :kept], {name: record[name][:kept] for name in BEARING_RECORD},
            counts, message)
