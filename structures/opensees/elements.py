"""What our bearing becomes in OpenSees: the element for its friction model, its parameters and
restoring law, and the element itself between two nodes of a 3D model.

``"coulomb"`` (:class:`~isolator.friction.ConstantFriction`) is ``singleFPBearing``
(``SingleFPSimple3d.cpp``; ``flatSliderBearing`` if flat) with ``frictionModel Coulomb``,
``"velocity"`` (Eq. 7 without heating) the same with ``VelDependent``, ``"ptv"`` (Eq. 7,
Kumar's factors, :func:`fpbearingptv_equivalent`) ``FPBearingPTV``. kInit is the element's
total initial stiffness, ``mu N / u_y`` (u_y our yield displacement [m]) plus ``N / R`` for a
pendulum, with the mu at ``"rest"`` (zero speed, initial temperature, the bearing's pressure;
mu_slow for VelDependent) or the ``"reference"`` mu (mu_fast, MuRef). singleFPBearing iterates
its normal force ``N = P + F . u / R``; FPBearingPTV keeps N = P and takes the pressure
``N / (22/7 r^2)`` and the speed ``|v| R / sqrt(R^2 - u^2)``.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import replace
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_choice
from isolator.bearing import AxialLoadHistory, DCFPBearing
from isolator.heating import CentrePoint

__all__ = ["ELEMENTS", "FPBEARINGPTV_AMBIENT", "FPBEARINGPTV_REFINEMENT", "BearingElements",
           "VelDependentParameters", "add_bearing", "constant_axial_load", "element_kind",
           "fpbearingptv_equivalent", "fpbearingptv_restoring", "singlefp_restoring",
           "velocity_dependent_parameters", "warn_if_steps_vary"]

ELEMENTS = ("coulomb", "velocity", "ptv")
FPBEARINGPTV_AMBIENT = 20.0
"""Initial (ambient) temperature hard-coded in FPBearingPTV [degC]."""
FPBEARINGPTV_REFINEMENT = 0.5 * math.sqrt(np.pi)
"""FPBearingPTV heats the centre while |u| < r sqrt(pi)/2 (Kumar's unrefined centre point)."""
ELEMENT_ITERATIONS = 100
"""Element-level iterations of the friction pendulum elements (N = P + F u / R)."""
ELEMENT_TOLERANCE = 1.0e-12
"""Their force tolerance, relative to the element's axial load [-]."""
AXIAL_SHORTENING = 1.0e-6
"""Shortening of the stiff axial material under the element's axial load [m]."""
ORIENTATION = (0.0, 0.0, 1.0, 1.0, 0.0, 0.0)
"""Local x = global Z (axial), local y = global X: the basic shears are u_X and u_Y."""
KINIT = ("rest", "reference")
_TOP_X, _TOP_Y = 6, 7  # global X and Y force on the top node in the element's force vector
_FAST_SPEED = 1.0e6  # [m/s] a speed at which an exponential velocity factor has saturated
_UNIFORM_STEP = 1.0e-9  # relative spread of the steps below which they count as uniform
_LABELS = {"coulomb": "Coulomb", "velocity": "VelDependent"}


class VelDependentParameters(NamedTuple):
    """Arguments of OpenSees ``frictionModel VelDependent``: mu at zero and at large sliding
    speed [-] and the transRate of ``mu_fast - (mu_fast - mu_slow) exp(-transRate |v|)``
    [s/m]."""

    mu_slow: float
    mu_fast: float
    transition_rate: float


class BearingElements(NamedTuple):
    """The OpenSees elements of one bearing position: ``name`` (``"singleFPBearing"``,
    ``"flatSliderBearing"`` or ``"FPBearingPTV"``), ``friction`` (``"Coulomb"``,
    ``"VelDependent"``, "" for FPBearingPTV), ``spring`` (a linear spring N / R beside a flat
    slider) and ``read(ops) -> (force (2,) [N], friction_force (2,) [N], normal [N], mu [-],
    temperature [degC], heat_flux [W/m^2])`` of one bearing at the committed state (without
    FPBearingPTV: the initial temperature and NaN)."""

    name: str
    friction: str
    spring: bool
    read: Callable[[object], tuple]


def element_kind(bearing: DCFPBearing) -> str:
    """``"coulomb"``, ``"velocity"`` or ``"ptv"``: the element for the bearing's friction
    model (by its name: the constant model, Eq. 7 without heating, or with it)."""
    name = bearing.friction.name
    return "coulomb" if name == "constant" else "velocity" if name == "ptv-no-heating" else "ptv"


def velocity_dependent_parameters(friction, pressure: float) -> VelDependentParameters:
    """VelDependent parameters reproducing ``friction`` (Eq. 7) at a constant pressure [Pa]:
    ``k(v) = 1 - c exp(-a |v|)`` (c, a read off the factor set) maps ``mu = C k(v)`` to
    ``mu_fast = C``, ``mu_slow = C (1 - c)``, ``transRate = a`` [s/m], C being mu_t0 times the
    factors at ``pressure`` and the initial temperature. Raises TypeError for the constant model,
    ValueError if mu varies with a heated temperature or the velocity factor is not exponential."""
    owner = "velocity_dependent_parameters"
    if friction.name == "constant":
        raise InputTypeError(f"The 'friction' parameter of {owner} must be a PTVFriction "
                             f"(Eq. 7). Got {friction!r} instead.")
    dependencies, factors = friction.dependencies, friction.factors
    if friction.heats and "temperature" in dependencies:
        raise InputError(
            f"The 'friction' parameter of {owner} must not depend on a heated temperature "
            "(VelDependent has velocity dependence only). Got heating "
            f"{friction.heating!r} with dependencies {dependencies!r} instead.")
    scale = friction.mu_t0
    if "pressure" in dependencies:
        scale *= factors.pressure(pressure)[0]
    if "temperature" in dependencies:
        scale *= factors.temperature(friction.initial_temperature)[0]
    if "velocity" not in dependencies:
        return VelDependentParameters(scale, scale, 0.0)
    at_rest, slope = factors.velocity(0.0)
    fast = factors.velocity(_FAST_SPEED)[0]
    drop = fast - at_rest
    rate = slope / drop
    probe = 1.0 / rate
    if abs(fast - 1.0) > 1e-12 or abs(
            factors.velocity(probe)[0] - (fast - drop * math.exp(-rate * probe))) > 1e-12:
        raise InputError(f"The velocity factor of {factors!r} is not of the form "
                         f"1 - c exp(-a |v|) that {owner} maps to VelDependent.")
    return VelDependentParameters(scale * at_rest, scale * fast, rate)


def check_ptv_friction(friction, owner: str):
    """``friction`` if Eq. 7 with Kumar's factors at 20 degC (FPBearingPTV's), else ValueError."""
    if friction.name == "constant" or friction.factors.name != "kumar":
        raise InputError(f"The bearing of {owner} must have a PTVFriction with KumarFactors "
                         f"(the factors FPBearingPTV implements). Got {friction!r} instead.")
    if friction.initial_temperature != FPBEARINGPTV_AMBIENT:
        raise InputError(f"The initial temperature of the bearing of {owner} must be "
                         f"{FPBEARINGPTV_AMBIENT:g} degC (hard-coded in FPBearingPTV). Got "
                         f"{friction.initial_temperature!r} instead.")
    return friction


def fpbearingptv_equivalent(bearing: DCFPBearing) -> DCFPBearing:
    """``bearing`` shaped as FPBearingPTV models it: one sliding surface heated at its centre
    while |u| < sqrt(pi)/2 r, the spherical restoring law; friction parameters, factors,
    dependencies and thermal properties kept. Raises ValueError unless the friction is Eq. 7 with
    Kumar's factors at 20 degC."""
    check_ptv_friction(bearing.friction, "fpbearingptv_equivalent")
    friction = replace(bearing.friction, heating=CentrePoint(FPBEARINGPTV_REFINEMENT),
                       surfaces=1)
    return replace(bearing, friction=friction, restoring="spherical")


def singlefp_restoring(normal, displacement, radius: float) -> np.ndarray:
    """singleFPBearing's restoring force ``N (u_X / R_x, u_Y / R_y)`` [N], radii crossed
    (``R_x = sqrt(R^2 - u_Y^2)``), for ``displacement`` (..., 2) [m] and ``normal`` (...) [N];
    zero for an infinite ``radius`` [m]."""
    n, u = np.asarray(normal, dtype=float), np.asarray(displacement, dtype=float)
    if math.isinf(radius):
        return np.zeros_like(u)
    return n[..., None] * u / np.sqrt(radius**2 - u[..., ::-1] ** 2)


def fpbearingptv_restoring(normal, displacement, radius: float) -> np.ndarray:
    """FPBearingPTV's restoring force ``N u_i / sqrt(R^2 - u_i^2)`` on each axis [N], as
    :func:`singlefp_restoring`."""
    n, u = np.asarray(normal, dtype=float), np.asarray(displacement, dtype=float)
    return n[..., None] * u / np.sqrt(radius**2 - u**2)


def constant_axial_load(bearing: DCFPBearing, owner: str) -> float:
    """The bearing's axial load [N] if it is constant, else an error naming ``owner``."""
    if isinstance(bearing.axial_load, AxialLoadHistory) or bearing.axial_load is None:
        raise InputError(f"The 'bearing' parameter of {owner} must have a constant axial load. "
                         f"Got {bearing.axial_load!r} instead.")
    return float(bearing.axial_load)


def warn_if_steps_vary(element: str, time: np.ndarray, owner: str) -> None:
    """Warn (``UserWarning``) when ``element`` is ``"ptv"`` and the steps of ``time`` [s]
    vary: FPBearingPTV applies the current step to its whole heat history."""
    steps = np.diff(time)
    if element == "ptv" and np.ptp(steps) > _UNIFORM_STEP * np.max(steps):
        warnings.warn(f"FPBearingPTV in {owner} takes the times as heating lags and applies the "
                      "current step to its whole flux history: its temperature is only "
                      "meaningful for a uniform time step.", UserWarning, stacklevel=3)


def _mu_at_rest(friction, pressure: float) -> float:
    """Eq. 7's mu at zero speed and the initial temperature under ``pressure`` [Pa]."""
    factors, mu = friction.factors, friction.mu_t0
    for name, value in (("pressure", pressure), ("velocity", 0.0),
                        ("temperature", friction.initial_temperature)):
        if name in friction.dependencies:
            mu *= getattr(factors, name)(value)[0]
    return mu


def add_bearing(ops, tag: Callable[[], int], bottom: int, top: int, bearing: DCFPBearing,
                load: float, count: int = 1, *, kind: str, pendulum: str = "singlefp",
                kinit: str = "rest", axial_stiffness: float | None = None,
                hinged: bool = False, owner: str) -> BearingElements:
    """Add ``count`` bearings of ``bearing`` (its own axial load unused) carrying ``load``
    [N] together between the nodes ``bottom`` (fixed) and ``top`` (free vertically; rotations
    fixed, or turning with a base slab) of the 3D model in ``ops``; return their
    :class:`BearingElements`. ``tag()`` gives a new tag at each call; ``owner`` is named in errors.
    One singleFPBearing or flatSliderBearing stands for the ``count`` bearings (linear in N);
    FPBearingPTV is ``count`` parallel elements of ``load / count``. Torsion has no stiffness; the
    P-Delta moments ``N u`` go to ``bottom``.

    Parameters
    ----------
    kind : {"coulomb", "velocity", "ptv"}
        The element (module docstring).
    pendulum : {"singlefp", "spring"}
        singleFPBearing (N = P + F . u / R), or flatSliderBearing plus a linear spring N / R in X
        and Y (N = P, our law). Not used for FPBearingPTV.
    kinit : {"rest", "reference"}
        The mu that sets kInit (module docstring).
    axial_stiffness : float, optional
        Vertical stiffness of the bearings together [N/m]; default ``load / AXIAL_SHORTENING``.
    hinged : bool
        No rocking stiffness (a ``top`` turning with a base slab); default False (as axial).

    Raises ValueError for a bearing the element cannot represent.
    """
    kind = check_choice(kind, "element", owner, ELEMENTS)
    check_choice(kinit, "kinit", owner, KINIT)
    friction, radius = bearing.friction, bearing.effective_radius
    group = load / count if kind == "ptv" else load  # what one element carries
    axial, torsion = tag(), tag()
    ops.uniaxialMaterial("Elastic", axial, group / AXIAL_SHORTENING if axial_stiffness is None
                         else axial_stiffness * group / load)
    ops.uniaxialMaterial("Elastic", torsion, 0.0)
    rocking = torsion if hinged else axial
    if kind == "ptv":
        return _fpbearingptv(ops, tag, bottom, top, bearing, group, count, kinit, owner,
                             (axial, torsion, rocking))
    if bearing.restoring != "linear":
        raise InputError(f"Element {kind!r} of {owner} has the linear restoring law N u / R. "
                         f"Got a bearing with {bearing.restoring!r} instead.")
    model = tag()
    if kind == "coulomb":
        if friction.name != "constant":
            raise InputError(f"Element 'coulomb' of {owner} needs a ConstantFriction. "
                             f"Got {friction!r} instead.")
        ops.frictionModel("Coulomb", model, friction.mu)
        mu = friction.mu
    else:
        parameters = velocity_dependent_parameters(friction,
                                                   load / count / bearing.contact_area)
        ops.frictionModel("VelDependent", model, *parameters)
        mu = parameters.mu_slow if kinit == "rest" else parameters.mu_fast
    flat = math.isinf(radius) or pendulum == "spring"
    spring = 0.0 if math.isinf(radius) else group / radius
    k_initial = mu * group / bearing.yield_displacement + (0.0 if flat else spring)
    options = ("-P", axial, "-T", torsion, "-My", rocking, "-Mz", rocking,
               "-orient", *ORIENTATION,
               "-iter", ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * group)
    element = tag()
    if flat:
        ops.element("flatSliderBearing", element, bottom, top, model, k_initial, *options)
        if spring > 0.0:
            material = tag()
            ops.uniaxialMaterial("Elastic", material, spring)
            ops.element("zeroLength", tag(), bottom, top, "-mat", material, material,
                        "-dir", 1, 2)
    else:
        ops.element("singleFPBearing", element, bottom, top, model, radius, k_initial, *options)
    temperature = friction.initial_temperature

    def read(ops) -> tuple:
        values = ops.eleResponse(element, "force")
        slider = np.array([values[_TOP_X], values[_TOP_Y]]) / count
        normal = ops.eleResponse(element, "frictionModel", "normalForce")[0] / count
        u = np.array([ops.nodeDisp(top, 1), ops.nodeDisp(top, 2)])
        mu = ops.eleResponse(element, "frictionModel", "COF")[0]
        if flat:  # the slider is the friction, the spring our restoring law
            return slider + spring / count * u, slider, normal, mu, temperature, math.nan
        return (slider, slider - singlefp_restoring(normal, u, radius), normal, mu, temperature,
                math.nan)

    name = "flatSliderBearing" if flat else "singleFPBearing"
    return BearingElements(name, _LABELS[kind], flat and spring > 0.0, read)


def _fpbearingptv(ops, tag, bottom: int, top: int, bearing: DCFPBearing, load: float,
                  count: int, kinit: str, owner: str, materials: tuple[int, int, int]):
    """``count`` FPBearingPTV elements of ``load`` [N] each (materials: axial, torsion, rocking)."""
    friction = check_ptv_friction(bearing.friction, owner)
    radius = bearing.effective_radius
    if bearing.restoring != "spherical" or math.isinf(radius):
        raise InputError(f"Element 'ptv' of {owner} has the spherical restoring law "
                         "N u / sqrt(R^2 - u^2) with a finite R. Got a bearing with "
                         f"{bearing.restoring!r} and R = {radius!r} instead.")
    if friction.heating is None and "temperature" in friction.dependencies:
        raise InputError(f"Element 'ptv' of {owner} always heats its surface; a temperature "
                         "dependent PTVFriction without heating has no OpenSees twin.")
    axial, torsion, rocking = materials
    mu = (_mu_at_rest(friction, load / bearing.contact_area) if kinit == "rest"
          else friction.mu_t0)
    factors = friction.factors
    flag = {name: int(name in friction.dependencies)
            for name in ("pressure", "temperature", "velocity")}
    k_initial = mu * load / bearing.yield_displacement + load / radius
    tags = [tag() for _ in range(count)]
    for element in tags:
        ops.element(
            "FPBearingPTV", element, bottom, top, friction.mu_t0,
            flag["pressure"], factors.reference_pressure,
            flag["temperature"], friction.thermal.diffusivity, friction.thermal.conductivity,
            flag["velocity"], factors.rate_parameter, radius, bearing.contact_radius,
            k_initial, axial, torsion, rocking, rocking, *ORIENTATION,
            0.0, 0, 0.0,  # shearDist, doRayleigh, mass
            ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * load, 1,  # unit 1: N, m, s, degC
        )
    first = tags[0]

    def read(ops) -> tuple:
        values = ops.eleResponse(first, "force")
        force = np.array([values[_TOP_X], values[_TOP_Y]])
        normal = -ops.eleResponse(first, "basicForce")[0]
        u = np.array([ops.nodeDisp(top, 1), ops.nodeDisp(top, 2)])
        return (force, force - fpbearingptv_restoring(normal, u, radius), normal,
                ops.eleResponse(first, "MuAdjusted")[0], ops.eleResponse(first, "temperature")[0],
                ops.eleResponse(first, "HeatFlux")[0])

    return BearingElements("FPBearingPTV", "", False, read)
