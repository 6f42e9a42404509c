"""The native time-history analysis repeated in OpenSees, returned in the same form.

:func:`run_opensees` builds the building and its isolation level in openseespy from the very
objects :func:`structures.analysis.run` takes (:mod:`structures.opensees.model` describes the
model), drives it with the same ground-acceleration samples and the same integrator, and
returns an ``xarray.Dataset`` with the variables, dimensions and attributes of
:func:`~structures.analysis.run`, the energy balance computed from the recorded histories with
our matrices by :func:`structures.energy.energy_balance`.

Conventions (read in ``SRC/analysis/integrator`` and ``SRC/domain/pattern`` of OpenSees):

- Ground motion: ``timeSeries Path -dt dt -values ...`` of the samples the native run uses
  (resampled the same way) in m/s^2 and ``pattern UniformExcitation 2 1 -accel``; OpenSees
  then solves for the motion relative to the ground, as we do, and absolute accelerations are
  the relative ones plus the ground's.
- Initial state: our integrator starts from the acceleration in equilibrium with the first
  sample, ``a_0 = -r a_g(0)``; OpenSees's Newmark and HHT start from the nodes' committed
  accelerations, so they are set to that (``setNodeAccel ... -commit``).
- ``Newmark(gamma, beta)`` is ``integrator Newmark gamma beta``. ``HHT(alpha)`` with our
  alpha in [-1/3, 0] is ``integrator HHT (1 + alpha)``: OpenSees's alpha in [2/3, 1] weights
  the new step (``gamma = 3/2 - alpha_OS``, ``beta = (2 - alpha_OS)^2 / 4`` give ours). For a
  linear model both are the same method; for the isolator they differ in one respect:
  OpenSees evaluates the element at the weighted state ``u_(n + alpha_OS)``, ours weights the
  forces, ``(1 + alpha) f(u_(n+1)) - alpha f(u_n)``.
- Solution: Newton with ``NormDispIncr`` (``tolerance`` in m); a step that fails is retried as
  two halves, recursively up to ``max_subdivisions`` times, as our integrator does.

The run is recorded after each full step (nodal displacement, velocity and acceleration, the
bearing state of :class:`~structures.opensees.model.BearingRecord`).
"""

from __future__ import annotations

import time as _time

import numpy as np

from dcfpb.common.validation import check_int, check_real
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from structures.analysis import resampled_record
from structures.integrators import HHT, METHODS, Newmark
from structures.isolated_building import IsolatedShearBuilding
from structures.opensees.model import BearingRecord, build_model, element_kind
from structures.opensees.runtime import import_opensees
from structures.results import response_dataset
from structures.shear_building import ShearBuilding

__all__ = ["halving_step", "opensees_integrator", "run_opensees", "transient_analysis"]


def opensees_integrator(method: str | Newmark | HHT) -> tuple:
    """Arguments of OpenSees's ``integrator`` command for one of our methods.

    Parameters
    ----------
    method : {"newmark", "hht"} or Newmark or HHT
        As :func:`structures.integrators.integrate`.

    Returns
    -------
    tuple
        ``("Newmark", gamma, beta)`` or ``("HHT", 1 + alpha)``.
    """
    if isinstance(method, str):
        method = METHODS[method]() if method in METHODS else method
    if isinstance(method, HHT):
        return ("HHT", 1.0 + method.alpha)
    if isinstance(method, Newmark):
        return ("Newmark", method.gamma, method.beta)
    raise TypeError(f"The 'integrator' parameter of run_opensees must be one of {tuple(METHODS)} "
                    f"or a Newmark or HHT instance. Got {method!r} instead.")


def transient_analysis(ops, integrator: tuple, tolerance: float,
                       constraints: str = "Plain") -> None:
    """Set up the transient analysis of a twin: ``constraints`` handler, plain numbering, a
    full system, Newton on ``NormDispIncr`` to ``tolerance`` [m] in 50 iterations, the
    ``integrator`` of :func:`opensees_integrator`."""
    ops.constraints(constraints)
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", tolerance, 50)
    ops.algorithm("Newton")
    ops.integrator(*integrator)
    ops.analysis("Transient")


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
    motion: GroundMotion,
    integrator: str | Newmark | HHT = "newmark",
    *,
    n_bearings: int = 1,
    dt: float | None = None,
    pendulum: str = "singlefp",
    tolerance: float = 1e-10,
    max_subdivisions: int = 6,
):
    """Run the time-history analysis of :func:`structures.analysis.run` in OpenSees.

    Parameters
    ----------
    building, bearing, motion, integrator, n_bearings, dt
        As :func:`structures.analysis.run`. The bearing's friction model selects the element
        (:func:`~structures.opensees.model.element_kind`).
    pendulum : {"singlefp", "spring"}
        singleFPBearing (N = W + F u / R) or flatSliderBearing plus a linear spring (N = W,
        our law); see :mod:`structures.opensees.model`. Ignored for FPBearingPTV.
    tolerance : float
        Displacement-increment tolerance of Newton's method [m].
    max_subdivisions : int
        Nested halvings of a step that does not converge.

    Returns
    -------
    xarray.Dataset
        As :func:`structures.analysis.run`, with the attributes ``program``, ``element`` and
        ``pendulum`` besides; ``heat_flux`` is NaN for elements without heating.

    Raises
    ------
    ImportError
        Without openseespy.
    ValueError, TypeError
        For a bearing or method OpenSees cannot represent here (HHT with FPBearingPTV
        among them: on the example its temperature peak falls from 119 to 111 degC).
    """
    owner = "run_opensees"
    n_bearings = check_int(n_bearings, "n_bearings", owner, low=1)
    check_real(tolerance, "tolerance", owner, low=0.0, low_open=True)
    check_int(max_subdivisions, "max_subdivisions", owner, low=0)
    arguments = opensees_integrator(integrator)
    method = integrator if not isinstance(integrator, str) else METHODS[integrator]()
    native = IsolatedShearBuilding(building, bearing, n_bearings)  # our matrices, W / n
    if arguments[0] == "HHT" and element_kind(native.bearing) == "ptv":
        raise ValueError(
            f"The 'integrator' parameter of {owner} must be Newmark for FPBearingPTV: the "
            "element appends to its heat history whenever the domain time advances, and "
            "OpenSees's HHT moves it to t + alpha dt within each step, so the history gets "
            f"two uneven entries per step. Got {integrator!r} instead."
        )
    acceleration, step = resampled_record(motion, dt)
    ops = import_opensees()
    ops.wipe()
    start = _time.perf_counter()
    try:
        model = build_model(ops, building, native.bearing, n_bearings, pendulum)
        ops.timeSeries("Path", 2, "-dt", step, "-values", *acceleration.tolist(),
                       "-useLast")  # the summed steps may pass the last sample by round-off
        ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
        for tag in model.nodes:  # a_0 = -r a_g(0), as our integrator starts
            ops.setNodeAccel(tag, 1, -float(acceleration[0]), "-commit")
        transient_analysis(ops, arguments, tolerance)
        histories, records, counts, message = _integrate(ops, model, step, acceleration.size,
                                                         max_subdivisions)
        wall = _time.perf_counter() - start
        version = ops.version()
    finally:
        ops.wipe()
    kept = records.shape[0]
    u, v, a = histories
    ag = acceleration[:kept]
    bearing = {name: records[:, i] for i, name in enumerate(BearingRecord._fields)}
    return response_dataset(
        native, motion, step, ag, u, v, a + ag[:, None], bearing, integrator=repr(method),
        success=kept == acceleration.size, message=message,
        attrs={"program": f"OpenSees {version} (openseespy)", "element": model.element,
               "pendulum": pendulum if "FPBearingPTV" not in model.element else "spherical",
               "newton_iterations": counts[0], "subdivisions": counts[1], "wall_time": wall,
               "compile_time": 0.0},  # nothing to compile: the attrs of analysis.run
    )


def _integrate(ops, model, step: float, nt: int, max_subdivisions: int):
    """The step loop: (u, v, a) histories (3, nt, m), bearing records (kept, 6), counts."""
    m = len(model.nodes)
    histories = np.zeros((3, nt, m))
    for i, tag in enumerate(model.nodes):
        histories[2, 0, i] = ops.nodeAccel(tag, 1)
    records = [model.initial]
    counts = [0, 0]
    message = "The integration reached the end of the record."
    for k in range(1, nt):
        if not halving_step(ops, step, 0, max_subdivisions, counts):
            message = (f"Step {k}: OpenSees did not converge in the step to t = {k * step:.6g} s "
                       f"after {max_subdivisions} halvings.")
            break
        for i, tag in enumerate(model.nodes):
            histories[:, k, i] = (ops.nodeDisp(tag, 1), ops.nodeVel(tag, 1),
                                  ops.nodeAccel(tag, 1))
        records.append(model.record(ops))
    table = np.array(records, dtype=float)
    return histories[:, : table.shape[0]], table, counts, message
