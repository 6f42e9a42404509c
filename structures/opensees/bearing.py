"""One bearing in OpenSees under an imposed horizontal displacement history.

:func:`run_opensees_test` is the OpenSees twin of :func:`isolator.testrig.run_test`: it builds
one element from a :class:`~isolator.bearing.DCFPBearing` (the one source of truth), loads it
with the bearing's constant axial load, drives its top node through the history and returns a
:class:`~isolator.testrig.BearingTestResult`. Elements:

``"coulomb"``
    ``singleFPBearing`` (2D) with ``frictionModel Coulomb``, for a :class:`ConstantFriction`.
``"velocity"``
    ``singleFPBearing`` (2D) with ``frictionModel VelDependent``, for a :class:`PTVFriction`
    whose mu varies with velocity only (:func:`velocity_dependent_parameters`).
``"ptv"``
    ``FPBearingPTV`` (3D only), pressure, velocity and temperature dependent with Kumar's
    factors, for a :class:`PTVFriction` shaped as it models one (:func:`fpbearingptv_equivalent`).

A flat slider (``effective_radius = inf``) becomes ``flatSliderBearing`` for the first two.

Driving. A static analysis gives the element zero velocity (``ubdotAbs = 0``: VelDependent sits
at mu_slow, FPBearingPTV falls back to displacement differences), so the analysis is transient
(Newmark 1/2, 1/4). The top node's horizontal DOF follows ``imposedMotion`` in a
``MultipleSupport`` pattern whose ground motion holds displacement, velocity and acceleration as
``Path`` series: ``ImposedMotionSP::applyConstraint`` writes the velocity into the node and the
``Transformation`` handler the displacement, so the element sees the imposed velocity exactly,
not a Newmark difference of displacements (the trapezoidal rule would oscillate about it for
ever after a wrong start). The vertical DOF is free and massless on a stiff elastic axial
material under the constant load; all other DOFs are fixed.

Conventions read in ``SRC/element/frictionBearing/`` of OpenSees:

- ``SingleFPSimple2d.cpp``: ``kInit`` is the *total* initial stiffness, the friction part has
  ``kInit - N/R``; so ``kInit = mu N / u_y + N / R`` gives it our yield displacement u_y. The
  normal force is ``N = W + F u / R`` (``-qb(0) + qb(1)/Reff*ub(1)``, iterated inside the
  element), whatever drives the node (:func:`singlefp_normal_force`); restoring force
  ``N u / R``, friction ``mu N`` at the speed ``|v| sqrt(1 + (u/R)^2)``.
- ``VelDependent.cpp``: ``frictionModel VelDependent tag muSlow muFast transRate``,
  ``mu = muFast - (muFast - muSlow) exp(-transRate |v|)``, transRate in s/m.
- ``FPBearingPTV.cpp``: ``MuRef IsPDependent pRef IsTDependent Diffusivity Conductivity
  IsVDependent rateParameter Reff rContact kInitial matP matT matMy matMz x1 x2 x3 y1 y2 y3
  shearDist doRayleigh mass iter tol unit``. With unit 1 (N, m, s, degC) pRef is in Pa, the
  diffusivity in m^2/s, the conductivity in W/(m degC), the rate in s/m; ``mu = MuRef kp kT kv``
  (MuRef = our ``mu_t0``) with p = N / (22/7 r^2) and the speed ``|v| R / sqrt(R^2 - u^2)``.
  N = W; restoring force ``N u / sqrt(R^2 - u^2)``, friction part ``kInitial - N/sqrt(R^2-u^2)``.
  The factors of a step are frozen at its first update with an axial force (the predictor); the
  flux ``q = mu p v`` uses the previous step's mu and heats one surface while
  ``|u| < r sqrt(22/28)``; the temperature ``20 + sqrt(7 D/22)/k sum_j q_(n-j) dt / sqrt(t_j)``
  is a rectangle rule re-summed over the whole history every step, with the times
  t_j = (j+1) dt as lags (the time must start at 0) and the current dt for every interval. It
  stays 20 degC on the first two steps and whenever u is exactly 0. Responses
  ``temperature``, ``MuFactors`` (kp, kT, kv), ``MuAdjusted``, ``HeatFlux``.

openseespy keeps one global model: every call wipes it before and after.
"""

from __future__ import annotations

import math
import time as _time

import numpy as np

from dcfpb.common.validation import check_choice
from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction
from isolator.testrig import HISTORY_FIELDS, BearingTestResult, imposed_history
from structures.opensees.equivalents import (
    ELEMENT_ITERATIONS,
    ELEMENT_TOLERANCE,
    FPBEARINGPTV_AMBIENT,
    VelDependentParameters,
    add_fpbearingptv,
    constant_axial_load,
    fpbearingptv_equivalent,
    singlefp_normal_force,
    velocity_dependent_parameters,
    warn_if_steps_vary,
)
from structures.opensees.runtime import import_opensees

__all__ = [
    "ELEMENTS",
    "FPBEARINGPTV_AMBIENT",
    "VelDependentParameters",
    "fpbearingptv_equivalent",
    "run_opensees_test",
    "singlefp_normal_force",
    "velocity_dependent_parameters",
]

ELEMENTS = ("coulomb", "velocity", "ptv")
_AXIAL_SHORTENING = 1.0e-6  # [m] shortening of the stiff axial spring under the axial load
_BOTTOM, _TOP = 1, 2  # node tags


def run_opensees_test(
    bearing: DCFPBearing,
    time: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray | None = None,
    *,
    element: str = "coulomb",
    name: str = "imposed history",
) -> BearingTestResult:
    """Drive ``bearing`` built as an OpenSees element through an imposed history.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing; its friction model must be one the element represents (see the module
        docstring) and its axial load constant.
    time : array_like
        Strictly increasing sample times [s]; OpenSees runs from 0 (the times are shifted).
    displacement : array_like
        Imposed horizontal displacement [m], starting at 0 (the element starts at rest).
    velocity : array_like, optional
        Imposed velocity [m/s]; by default ``numpy.gradient`` of the displacement (as
        :func:`~isolator.testrig.run_test`). Give the analytic velocity where it is known.
    element : {"coulomb", "velocity", "ptv"}
        Which OpenSees element (see the module docstring).
    name : str
        Name of the history, kept in the result (prefixed with the element).

    Returns
    -------
    BearingTestResult
        One value per sample. Sample 0 is the initial state (zero force, the axial load, mu
        NaN). ``mu`` is the friction model's COF (``MuAdjusted`` for FPBearingPTV),
        ``axial_load`` the normal force the element uses (W + F u/R for singleFPBearing),
        ``friction_force`` the force less the element's restoring force, ``temperature`` and
        ``heat_flux`` FPBearingPTV's (NaN for the other elements).

    Raises
    ------
    ImportError
        Without openseespy.
    ValueError, TypeError
        For a bearing or history the element cannot represent.
    RuntimeError
        If an OpenSees step fails.

    Warns
    -----
    UserWarning
        For ``"ptv"`` with a non-uniform time step (see the module docstring).
    """
    owner = "run_opensees_test"
    element = check_choice(element, "element", owner, ELEMENTS)
    t, u, v = _history(time, displacement, velocity, owner)
    weight = constant_axial_load(bearing, owner)
    warn_if_steps_vary(element, t, owner)
    build = _build_fpbearingptv if element == "ptv" else _build_singlefp
    ops = import_opensees()
    start = _time.perf_counter()
    ops.wipe()
    try:
        record = build(ops, bearing, element, weight)
        _impose(ops, t - t[0], u, v, dof=1)
        imposed_analysis(ops)
        out = {n: np.full(t.size, np.nan) for n in HISTORY_FIELDS}
        out["force"][0] = out["friction_force"][0] = 0.0
        out["displacement"][0], out["velocity"][0], out["axial_load"][0] = u[0], v[0], weight
        if element == "ptv":
            out["temperature"][0], out["heat_flux"][0] = FPBEARINGPTV_AMBIENT, 0.0
        record_steps(ops, t, record, out, owner, element)
    finally:
        ops.wipe()
    out["time"] = t
    label = {"coulomb": "singleFPBearing Coulomb", "velocity": "singleFPBearing VelDependent",
             "ptv": "FPBearingPTV"}[element]
    return BearingTestResult(**out, bearing=bearing, name=f"OpenSees {label}: {name}",
                             wall_time=_time.perf_counter() - start)


def imposed_analysis(ops) -> None:
    """The transient analysis of a test with imposed displacements (planar or 3D): Newmark
    (1/2, 1/4), Newton on the displacement increment to 1e-12 in at most 25 iterations."""
    ops.constraints("Transformation")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", 1.0e-12, 25)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def record_steps(ops, t: np.ndarray, record, out: dict, owner: str, element: str) -> None:
    """Analyse one step per interval of the times ``t`` [s], writing what ``record(ops)``
    returns into row k of ``out``; RuntimeError naming the step where OpenSees fails."""
    for k, dt in enumerate(np.diff(t), start=1):
        if ops.analyze(1, float(dt)) != 0:
            raise RuntimeError(f"OpenSees failed at step {k} (t = {t[k] - t[0]:g} s) of "
                               f"{owner} with element {element!r}.")
        for field, value in record(ops).items():
            out[field][k] = value


def _history(time, displacement, velocity, owner):
    t, u, v = imposed_history(time, displacement, velocity, owner)
    if u[0] != 0.0:
        raise ValueError(f"The 'displacement' parameter of {owner} must start at 0 (the "
                         f"element starts at rest). Got {u[0]!r} instead.")
    return t, u, v


def _friction_model(ops, bearing: DCFPBearing, element: str, weight: float) -> float:
    """Define friction model 1 for singleFPBearing; return the mu that sets kInit."""
    friction, owner = bearing.friction, "run_opensees_test"
    if element == "coulomb":
        if not isinstance(friction, ConstantFriction):
            raise ValueError(f"Element 'coulomb' of {owner} needs a ConstantFriction. "
                             f"Got {friction!r} instead.")
        ops.frictionModel("Coulomb", 1, friction.mu)
        return friction.mu
    parameters = velocity_dependent_parameters(friction, weight / bearing.contact_area)
    ops.frictionModel("VelDependent", 1, *parameters)
    return parameters.mu_fast


def _build_singlefp(ops, bearing: DCFPBearing, element: str, weight: float):
    """singleFPBearing (flatSliderBearing if R is infinite) in 2D; return the recorder."""
    if bearing.restoring != "linear":
        raise ValueError(f"Element {element!r} of run_opensees_test has the linear restoring "
                         f"law N u / R. Got a bearing with {bearing.restoring!r} instead.")
    radius = bearing.effective_radius
    flat = math.isinf(radius)
    mu = _friction_model(ops, bearing, element, weight)
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(_BOTTOM, 0.0, 0.0)
    ops.node(_TOP, 0.0, 1.0)  # vertical: local x up, local y = -global X (signs cancel)
    ops.fix(_BOTTOM, 1, 1, 1)
    ops.fix(_TOP, 0, 0, 1)
    ops.uniaxialMaterial("Elastic", 1, weight / _AXIAL_SHORTENING)
    ops.uniaxialMaterial("Elastic", 2, weight / _AXIAL_SHORTENING)
    pendulum = 0.0 if flat else weight / radius
    k_initial = mu * weight / bearing.yield_displacement + pendulum
    if flat:
        ops.element("flatSliderBearing", 1, _BOTTOM, _TOP, 1, k_initial, "-P", 1, "-Mz", 2,
                    "-iter", ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * weight)
    else:
        ops.element("singleFPBearing", 1, _BOTTOM, _TOP, 1, radius, k_initial,
                    "-P", 1, "-Mz", 2, "-iter", ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * weight)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(_TOP, 0.0, -weight, 0.0)

    def record(ops) -> dict[str, float]:
        force = ops.eleResponse(1, "force")[3]
        normal = ops.eleResponse(1, "frictionModel", "normalForce")[0]
        u = ops.nodeDisp(_TOP, 1)
        restoring = 0.0 if flat else normal * u / radius
        return {"displacement": u, "velocity": ops.nodeVel(_TOP, 1), "force": force,
                "friction_force": force - restoring, "axial_load": normal,
                "mu": ops.eleResponse(1, "frictionModel", "COF")[0]}

    return record


def _build_fpbearingptv(ops, bearing: DCFPBearing, element: str, weight: float):
    """FPBearingPTV in 3D (x vertical, y = global X); return the recorder."""
    radius = bearing.effective_radius
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(_BOTTOM, 0.0, 0.0, 0.0)
    ops.node(_TOP, 0.0, 0.0, 0.0)  # zero length: the orientation vectors below hold
    ops.fix(_BOTTOM, 1, 1, 1, 1, 1, 1)
    ops.fix(_TOP, 0, 1, 0, 1, 1, 1)
    ops.uniaxialMaterial("Elastic", 1, weight / _AXIAL_SHORTENING)
    ops.uniaxialMaterial("Elastic", 2, weight / _AXIAL_SHORTENING)
    add_fpbearingptv(ops, _BOTTOM, _TOP, bearing, weight, "run_opensees_test")
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(_TOP, 0.0, 0.0, -weight, 0.0, 0.0, 0.0)

    def record(ops) -> dict[str, float]:
        force = ops.eleResponse(1, "force")[6]
        normal = -ops.eleResponse(1, "basicForce")[0]
        u = ops.nodeDisp(_TOP, 1)
        restoring = normal * u / math.sqrt(radius**2 - u * u)
        return {"displacement": u, "velocity": ops.nodeVel(_TOP, 1), "force": force,
                "friction_force": force - restoring, "axial_load": normal,
                "mu": ops.eleResponse(1, "MuAdjusted")[0],
                "temperature": ops.eleResponse(1, "temperature")[0],
                "heat_flux": ops.eleResponse(1, "HeatFlux")[0]}

    return record


def _impose(ops, time: np.ndarray, displacement: np.ndarray, velocity: np.ndarray,
            dof: int) -> None:
    """Drive ``dof`` of the top node through the history (exact velocity, see module doc)."""
    acceleration = np.gradient(velocity, time)  # only completes the ground motion: no mass
    for tag, values in ((2, displacement), (3, velocity), (4, acceleration)):
        ops.timeSeries("Path", tag, "-time", *time.tolist(), "-values", *values.tolist(),
                       "-useLast")  # rounding of the summed steps must not fall off the end
    ops.pattern("MultipleSupport", 2)
    ops.groundMotion(1, "Plain", "-disp", 2, "-vel", 3, "-accel", 4)
    ops.imposedMotion(_TOP, dof, 1)
