"""One bearing in OpenSees 3D under an imposed orbit in the horizontal plane.

:func:`run_opensees_orbit` is the OpenSees twin of
:func:`isolator.testrig.run_test`:
it builds one 3D element (``ndm 3``, ``ndf 6``, two coincident nodes) from a
:class:`~isolator.bearing.DCFPBearing`, loads it with the bearing's constant axial load, drives
the top node's X and Y through the orbit and returns an
:class:`~isolator.testrig.BearingTestResult`. Elements:

``"coulomb"``
    ``singleFPBearing`` (3D, ``SingleFPSimple3d``) with ``frictionModel Coulomb`` for a
    :class:`ConstantFriction` and the linear law; ``flatSliderBearing`` (3D) for a flat slider.
``"ptv"``
    ``FPBearingPTV`` for a :class:`PTVFriction` with Kumar's factors shaped as it models one
    (:func:`~structures.opensees.equivalents.fpbearingptv_equivalent`).

Driving is that of :func:`structures.opensees.bearing.run_opensees_test` on two DOFs: each of
X and Y follows its own ``imposedMotion`` (displacement, velocity and acceleration as ``Path``
series), so the element sees the imposed velocity exactly; Newmark 1/2, 1/4, transient. The
element's local x is global Z (axial, free, stiff elastic material under the load), local y is
global X and local z global Y (basic shear ub1 = u_X, ub2 = u_Y); rotations are fixed.

Conventions read in ``SingleFPSimple3d.cpp`` and ``FPBearingPTV.cpp`` (``update()``):

- Both run one coupled return map on the two shear components: a trial force
  ``q* = k0 (u - u_p)`` per axis, ``k0_i = kInit - N / R_i``; if ``|q*| > mu N`` it is
  projected on the circle of radius mu N (radial return). With k0 = mu N / u_y this is our
  :func:`~isolator.bearing.isotropic_return_map`, except that k0 is fixed by kInit
  while
  ours, mu N z with z moving by du / u_y, follows N and mu; and k0_x != k0_y off the axes.
- singleFPBearing: ``R_x = sqrt(R^2 - u_Y^2)``, ``R_y = sqrt(R^2 - u_X^2)``; restoring force
  ``(N u_X / R_x, N u_Y / R_y)`` (:func:`singlefp3d_restoring`; in 1D our linear law N u / R);
  normal force ``N = W + q_X u_X / R_x + q_Y u_Y / R_y`` iterated in the element
  (:func:`singlefp3d_normal_force` gives our element the same); speed
  ``sqrt((v_X u_X / R_x + v_Y u_Y / R_y)^2 + |v|^2)`` (no effect with Coulomb).
- FPBearingPTV: the radii swapped, ``R_x = sqrt(R^2 - u_X^2)``, ``R_y = sqrt(R^2 - u_Y^2)``,
  so its restoring force ``(N u_X / sqrt(R^2 - u_X^2), N u_Y / sqrt(R^2 - u_Y^2))``
  (:func:`fpbearingptv_restoring`) is the 1D spherical law on each axis, not ours
  ``N u / sqrt(R^2 - |u|^2)``; N = W; the speed as above with its radii. Its heating is the 1D
  one (:mod:`structures.opensees.bearing`): one centre point heated while the resultant
  ``|u| < r sqrt(22/28)``, flux with the previous step's mu, temperature by a rectangle rule.

openseespy keeps one global model: every call wipes it before and after.
"""

from __future__ import annotations

import math
import time as _time

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.validation import check_choice
from isolator.bearing import DCFPBearing
from isolator.orbits import Orbit
from isolator.testrig import BearingTestResult
from isolator.friction import ConstantFriction
from structures.opensees.bearing import imposed_analysis, record_steps
from structures.opensees.equivalents import (
    ELEMENT_ITERATIONS,
    ELEMENT_TOLERANCE,
    FPBEARINGPTV_AMBIENT,
    add_fpbearingptv,
    constant_axial_load,
    warn_if_steps_vary,
)
from structures.opensees.equivalents3d import (
    check_orbit,
    fpbearingptv_restoring,
    singlefp3d_normal_force,
    singlefp3d_restoring,
)
from structures.opensees.runtime import import_opensees

__all__ = [
    "ELEMENTS_3D",
    "fpbearingptv_restoring",
    "opensees_orbit",
    "run_opensees_orbit",
    "singlefp3d_normal_force",
    "singlefp3d_restoring",
]

ELEMENTS_3D = ("coulomb", "ptv")
_AXIAL_SHORTENING = 1.0e-6  # [m] shortening of the stiff axial spring under the axial load
_BOTTOM, _TOP = 1, 2  # node tags
_ORIENTATION = (0.0, 0.0, 1.0, 1.0, 0.0, 0.0)  # local x = global Z, local y = global X
_TOP_X, _TOP_Y = 6, 7  # global X and Y force of the top node in the element's force vector


def run_opensees_orbit(
    bearing: DCFPBearing,
    time: ArrayLike,
    displacement: ArrayLike,
    velocity: ArrayLike | None = None,
    *,
    element: str = "coulomb",
    name: str = "orbit",
) -> BearingTestResult:
    """Drive ``bearing`` built as an OpenSees 3D element through an imposed orbit.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing; its friction model must be one the element represents (see the module
        docstring) and its axial load constant.
    time : array_like, shape (n,)
        Strictly increasing sample times [s]; OpenSees runs from 0 (the times are shifted).
    displacement : array_like, shape (n, 2)
        Imposed relative displacement (x, y) [m], starting at (0, 0).
    velocity : array_like, shape (n, 2), optional
        Imposed velocity [m/s]; by default ``numpy.gradient`` of the displacement (as
        :func:`~isolator.testrig.run_test`). Give the analytic velocity where
        known.
    element : {"coulomb", "ptv"}
        Which OpenSees element (see the module docstring).
    name : str
        Name of the orbit, kept in the result (prefixed with the element).

    Returns
    -------
    BearingTestResult
        One row per sample; sample 0 is the initial state (zero force, the axial load, mu NaN).
        ``mu`` is the friction model's COF (``MuAdjusted`` for FPBearingPTV), ``axial_load``
        the normal force the element uses, ``friction_force`` the force less the element's own
        restoring force, ``z`` the friction force over mu N, ``temperature`` and ``heat_flux``
        FPBearingPTV's (NaN for singleFPBearing).

    Raises
    ------
    ImportError
        Without openseespy.
    ValueError, TypeError
        For a bearing or orbit the element cannot represent.
    RuntimeError
        If an OpenSees step fails.

    Warns
    -----
    UserWarning
        For ``"ptv"`` with a non-uniform time step (its heat history assumes a uniform one).
    """
    owner = "run_opensees_orbit"
    element = check_choice(element, "element", owner, ELEMENTS_3D)
    t, u, v = check_orbit(time, displacement, velocity, owner)
    weight = constant_axial_load(bearing, owner)
    warn_if_steps_vary(element, t, owner)
    build = _build_fpbearingptv if element == "ptv" else _build_singlefp
    ops = import_opensees()
    start = _time.perf_counter()
    ops.wipe()
    try:
        record = build(ops, bearing, weight)
        _impose_orbit(ops, t - t[0], u, v)
        imposed_analysis(ops)
        out = {key: np.full((t.size, 2), np.nan) for key in ("displacement", "velocity",
                                                             "force", "friction_force", "z")}
        out |= {key: np.full(t.size, np.nan) for key in ("mu", "temperature", "heat_flux",
                                                         "axial_load")}
        for key in ("force", "friction_force", "z"):
            out[key][0] = 0.0
        out["displacement"][0], out["velocity"][0], out["axial_load"][0] = u[0], v[0], weight
        if element == "ptv":
            out["temperature"][0], out["heat_flux"][0] = FPBEARINGPTV_AMBIENT, 0.0
        record_steps(ops, t, record, out, owner, element)
    finally:
        ops.wipe()
    restoring = (fpbearingptv_restoring if element == "ptv" else singlefp3d_restoring)(
        out["axial_load"], out["displacement"], bearing.effective_radius)
    out["friction_force"][1:] = out["force"][1:] - restoring[1:]
    yield_force = (out["mu"] * out["axial_load"])[1:, None]
    out["z"][1:] = np.divide(out["friction_force"][1:], yield_force,
                             out=np.zeros_like(out["friction_force"][1:]),
                             where=yield_force > 0.0)
    label = {"coulomb": "singleFPBearing 3D Coulomb", "ptv": "FPBearingPTV"}[element]
    if element == "coulomb" and math.isinf(bearing.effective_radius):
        label = "flatSliderBearing 3D Coulomb"
    return BearingTestResult(t, **out, bearing=bearing, name=f"OpenSees {label}: {name}",
                           wall_time=_time.perf_counter() - start)


def opensees_orbit(bearing: DCFPBearing, orbit: Orbit, *,
                   element: str = "coulomb") -> BearingTestResult:
    """:func:`run_opensees_orbit` on an :class:`~isolator.orbits.Orbit` (its exact
    velocity)."""
    return run_opensees_orbit(bearing, orbit.time, orbit.displacement, orbit.velocity,
                              element=element, name=orbit.name)


def _base_model(ops, weight: float) -> None:
    """Two coincident nodes in 3D, the top one free in X, Y, Z; stiff elastic materials."""
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(_BOTTOM, 0.0, 0.0, 0.0)
    ops.node(_TOP, 0.0, 0.0, 0.0)  # zero length: the orientation vectors hold
    ops.fix(_BOTTOM, 1, 1, 1, 1, 1, 1)
    ops.fix(_TOP, 0, 0, 0, 1, 1, 1)
    ops.uniaxialMaterial("Elastic", 1, weight / _AXIAL_SHORTENING)
    ops.uniaxialMaterial("Elastic", 2, weight / _AXIAL_SHORTENING)


def _axial_load(ops, weight: float) -> None:
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(_TOP, 0.0, 0.0, -weight, 0.0, 0.0, 0.0)


def _build_singlefp(ops, bearing: DCFPBearing, weight: float):
    """singleFPBearing (flatSliderBearing if R is infinite) in 3D; return the recorder."""
    owner = "run_opensees_orbit"
    friction = bearing.friction
    if not isinstance(friction, ConstantFriction):
        raise ValueError(f"Element 'coulomb' of {owner} needs a ConstantFriction. "
                         f"Got {friction!r} instead.")
    if bearing.restoring != "linear":
        raise ValueError(f"Element 'coulomb' of {owner} has the linear restoring law N u / R "
                         f"along each axis. Got a bearing with {bearing.restoring!r} instead.")
    radius = bearing.effective_radius
    flat = math.isinf(radius)
    mu = friction.mu
    _base_model(ops, weight)
    ops.frictionModel("Coulomb", 1, mu)
    k_initial = mu * weight / bearing.yield_displacement + (0.0 if flat else weight / radius)
    materials = ("-P", 1, "-T", 2, "-My", 2, "-Mz", 2, "-orient", *_ORIENTATION,
                 "-iter", ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * weight)
    if flat:
        ops.element("flatSliderBearing", 1, _BOTTOM, _TOP, 1, k_initial, *materials)
    else:
        ops.element("singleFPBearing", 1, _BOTTOM, _TOP, 1, radius, k_initial, *materials)
    _axial_load(ops, weight)

    def record(ops) -> dict[str, object]:
        force = ops.eleResponse(1, "force")
        return {"displacement": (ops.nodeDisp(_TOP, 1), ops.nodeDisp(_TOP, 2)),
                "velocity": (ops.nodeVel(_TOP, 1), ops.nodeVel(_TOP, 2)),
                "force": (force[_TOP_X], force[_TOP_Y]),
                "axial_load": ops.eleResponse(1, "frictionModel", "normalForce")[0],
                "mu": ops.eleResponse(1, "frictionModel", "COF")[0]}

    return record


def _build_fpbearingptv(ops, bearing: DCFPBearing, weight: float):
    """FPBearingPTV in 3D; return the recorder."""
    _base_model(ops, weight)
    add_fpbearingptv(ops, _BOTTOM, _TOP, bearing, weight, "run_opensees_orbit")
    _axial_load(ops, weight)

    def record(ops) -> dict[str, object]:
        force = ops.eleResponse(1, "force")
        return {"displacement": (ops.nodeDisp(_TOP, 1), ops.nodeDisp(_TOP, 2)),
                "velocity": (ops.nodeVel(_TOP, 1), ops.nodeVel(_TOP, 2)),
                "force": (force[_TOP_X], force[_TOP_Y]),
                "axial_load": -ops.eleResponse(1, "basicForce")[0],
                "mu": ops.eleResponse(1, "MuAdjusted")[0],
                "temperature": ops.eleResponse(1, "temperature")[0],
                "heat_flux": ops.eleResponse(1, "HeatFlux")[0]}

    return record


def _impose_orbit(ops, time: np.ndarray, displacement: np.ndarray,
                  velocity: np.ndarray) -> None:
    """Drive X and Y of the top node through the orbit (exact velocity, see the module doc)."""
    acceleration = np.gradient(velocity, time, axis=0)  # only completes the ground motion
    ops.pattern("MultipleSupport", 2)
    for axis in (0, 1):
        tags = [10 * (axis + 1) + k for k in range(3)]
        for tag, values in zip(tags, (displacement, velocity, acceleration), strict=True):
            ops.timeSeries("Path", tag, "-time", *time.tolist(), "-values",
                           *values[:, axis].tolist(), "-useLast")
        ops.groundMotion(axis + 1, "Plain", "-disp", tags[0], "-vel", tags[1],
                         "-accel", tags[2])
        ops.imposedMotion(_TOP, axis + 1, axis + 1)
