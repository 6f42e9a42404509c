"""What our bearing becomes in OpenSees: the VelDependent friction model's parameters, the
bearing FPBearingPTV models (Kumar's factors, one heated centre point) and the normal force of
singleFPBearing.

The conventions read in OpenSees's source (``SingleFPSimple2d.cpp``, ``VelDependent.cpp``,
``FPBearingPTV.cpp``) are in the docstring of :mod:`structures.opensees.bearing`, which drives
the elements these functions describe.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from typing import NamedTuple

import numpy as np

from isolator.bearing import AxialLoadHistory, DCFPBearing
from isolator.factors import KumarFactors
from isolator.friction import PTVFriction
from isolator.heating import CentrePoint
from isolator.testrig import run_test

__all__ = [
    "FPBEARINGPTV_AMBIENT",
    "FPBEARINGPTV_REFINEMENT",
    "VelDependentParameters",
    "fpbearingptv_equivalent",
    "singlefp_normal_force",
    "velocity_dependent_parameters",
]

FPBEARINGPTV_AMBIENT = 20.0
"""Initial (ambient) temperature hard-coded in FPBearingPTV [degC]."""
FPBEARINGPTV_REFINEMENT = 0.5 * math.sqrt(np.pi)
"""FPBearingPTV heats the centre while |u| < r sqrt(pi)/2 (Kumar's unrefined centre point)."""
_FAST_SPEED = 1.0e6  # [m/s] a speed at which an exponential velocity factor has saturated


class VelDependentParameters(NamedTuple):
    """Arguments of OpenSees ``frictionModel VelDependent``.

    Attributes
    ----------
    mu_slow, mu_fast : float
        Friction coefficient at zero and at large sliding speed [-].
    transition_rate : float
        transRate of ``mu = mu_fast - (mu_fast - mu_slow) exp(-transRate |v|)`` [s/m].
    """

    mu_slow: float
    mu_fast: float
    transition_rate: float


def velocity_dependent_parameters(friction: PTVFriction, pressure: float) -> VelDependentParameters:
    """VelDependent parameters reproducing ``friction`` at a constant contact pressure.

    The velocity factors of both factor sets are exponential, ``k(v) = 1 - c exp(-a |v|)``
    (Kumar: c = 0.5, a = rate_parameter; the paper's Eq. 2: c = 0.55, a = 19 s/m), so
    ``mu = C k(v)`` maps to ``mu_fast = C``, ``mu_slow = C (1 - c)``, ``transRate = a``, with
    C = mu_t0 times the pressure factor at ``pressure`` and the temperature factor at the
    initial temperature (where those dependencies act). c and a are read off the factor set
    itself (k(0) and k'(0) / (1 - k(0))), so no constant is repeated here.

    Parameters
    ----------
    friction : PTVFriction
        A model whose mu varies with velocity only: no heating, or temperature not among its
        dependencies.
    pressure : float
        Constant contact pressure [Pa].

    Raises
    ------
    TypeError
        If ``friction`` is not a PTVFriction.
    ValueError
        If mu would vary with temperature, or the velocity factor is not exponential.
    """
    owner = "velocity_dependent_parameters"
    if not isinstance(friction, PTVFriction):
        raise TypeError(f"The 'friction' parameter of {owner} must be a PTVFriction. "
                        f"Got {friction!r} instead.")
    dependencies = friction.dependencies
    if friction.heats and "temperature" in dependencies:
        raise ValueError(
            f"The 'friction' parameter of {owner} must not depend on a heated temperature "
            "(VelDependent has velocity dependence only). Got heating "
            f"{friction.heating!r} with dependencies {dependencies!r} instead."
        )
    factors = friction.factors
    scale = friction.mu_t0
    if "pressure" in dependencies:
        scale *= factors.pressure(pressure)[0]
    if "temperature" in dependencies:
        scale *= factors.temperature(friction.thermal.initial_temperature)[0]
    if "velocity" not in dependencies:
        return VelDependentParameters(scale, scale, 0.0)
    at_rest, slope = factors.velocity(0.0)
    fast = factors.velocity(_FAST_SPEED)[0]
    drop = fast - at_rest
    rate = slope / drop
    probe = 1.0 / rate
    exponential = fast - drop * math.exp(-rate * probe)
    if abs(fast - 1.0) > 1e-12 or abs(factors.velocity(probe)[0] - exponential) > 1e-12:
        raise ValueError(
            f"The velocity factor of {factors!r} is not of the form 1 - c exp(-a |v|) that "
            f"{owner} maps to VelDependent."
        )
    return VelDependentParameters(scale * at_rest, scale * fast, rate)


def fpbearingptv_equivalent(bearing: DCFPBearing) -> DCFPBearing:
    """``bearing`` shaped as OpenSees FPBearingPTV models it, for a like-for-like comparison.

    One sliding surface (``surfaces=1``) heated at its centre while |u| < sqrt(pi)/2 r
    (``CentrePoint(refinement=sqrt(pi)/2)``), the spherical restoring law; friction
    parameters, factors, dependencies and thermal properties are kept.

    Raises
    ------
    ValueError
        If the friction is not a PTVFriction with Kumar factors, or its initial temperature is
        not FPBearingPTV's fixed 20 degC.
    """
    check_ptv_friction(bearing.friction, "fpbearingptv_equivalent")
    friction = replace(bearing.friction, heating=CentrePoint(FPBEARINGPTV_REFINEMENT),
                       surfaces=1)
    return replace(bearing, friction=friction, restoring="spherical")


def singlefp_normal_force(
    bearing: DCFPBearing,
    time: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray | None = None,
    *,
    tolerance: float = 1e-12,
    max_iterations: int = 20,
) -> AxialLoadHistory:
    """The normal force ``N = W + F u / R`` that singleFPBearing uses, from our own element.

    Fixed-point iteration on :func:`~isolator.testrig.run_test`: N_0 = W,
    N_(k+1) = W + F_k u / R_eff. The map contracts by about |u|/R (|u|/R + mu) (0.4 % for
    u = 0.2 m, R = 4.5 m), so a few iterations reach ``tolerance`` (relative to W). Giving the
    result as the axial load of our bearing makes it see what singleFPBearing sees.

    Raises
    ------
    ValueError
        If the axial load is not constant, or the iteration does not converge.
    """
    owner = "singlefp_normal_force"
    weight = constant_axial_load(bearing, owner)
    t = np.asarray(time, dtype=float)
    u = np.asarray(displacement, dtype=float)
    normal = np.full(t.shape, weight)
    for _ in range(max_iterations):
        trial = replace(bearing, axial_load=AxialLoadHistory(t, normal))
        force = run_test(trial, t, u, velocity).force
        updated = weight + force * u / bearing.effective_radius
        change = float(np.max(np.abs(updated - normal))) / weight
        normal = updated
        if change <= tolerance:
            return AxialLoadHistory(t, normal)
    raise ValueError(f"{owner} did not converge in {max_iterations} iterations "
                     f"(last relative change {change:.3g}).")


def constant_axial_load(bearing: DCFPBearing, owner: str) -> float:
    """The bearing's axial load [N] if it is constant (the elements' weight W), else an error."""
    if isinstance(bearing.axial_load, AxialLoadHistory):
        raise ValueError(f"The 'bearing' parameter of {owner} must have a constant axial load. "
                         "Got an AxialLoadHistory instead.")
    return float(bearing.axial_load)


def check_ptv_friction(friction, owner: str) -> PTVFriction:
    """``friction`` if it is a PTVFriction with Kumar's factors (FPBearingPTV's), else an error."""
    if not isinstance(friction, PTVFriction) or not isinstance(friction.factors, KumarFactors):
        raise ValueError(f"The bearing of {owner} must have a PTVFriction with KumarFactors "
                         f"(the factors FPBearingPTV implements). Got {friction!r} instead.")
    if friction.thermal.initial_temperature != FPBEARINGPTV_AMBIENT:
        raise ValueError(
            f"The initial temperature of the bearing of {owner} must be "
            f"{FPBEARINGPTV_AMBIENT:g} degC (hard-coded in FPBearingPTV). Got "
            f"{friction.thermal.initial_temperature!r} instead."
        )
    return friction


ELEMENT_ITERATIONS = 100
"""Element-level iterations of the OpenSees friction pendulum elements (N = W + F u / R in
singleFPBearing)."""
ELEMENT_TOLERANCE = 1.0e-12
"""Their force tolerance, relative to the axial load W [-] (the default is 1e-12 N)."""
_UNIFORM_STEP = 1.0e-9  # relative spread of the steps below which they count as uniform


def warn_if_steps_vary(element: str, time: np.ndarray, owner: str) -> None:
    """Warn (``UserWarning``) when ``element`` is ``"ptv"`` and the steps of ``time`` [s]
    are not uniform: FPBearingPTV takes the times as heating lags and applies the current step
    to its whole flux history."""
    steps = np.diff(time)
    if element == "ptv" and np.ptp(steps) > _UNIFORM_STEP * np.max(steps):
        warnings.warn(f"FPBearingPTV in {owner} takes the times as heating lags and applies the "
                      "current step to its whole flux history: its temperature is only "
                      "meaningful for a uniform time step.", UserWarning, stacklevel=3)


def add_fpbearingptv(ops, bottom: int, top: int, bearing: DCFPBearing, weight: float,
                     owner: str) -> PTVFriction:
    """Add our bearing as FPBearingPTV element 1 between the nodes ``bottom`` and ``top`` of a
    3D model (local x along global Z, the axis; local y along global X), with kInit from the
    reference friction (mu_t0 W / u_y + W / R) and uniaxial materials 1 (axial) and 2 (torsion
    and rocking) defined by the caller; return the friction.

    Raises
    ------
    ValueError
        For a bearing FPBearingPTV cannot be: not the spherical law with a finite R, friction
        not :func:`check_ptv_friction`'s, or a temperature-dependent one without heating.
    """
    friction = check_ptv_friction(bearing.friction, owner)
    if bearing.restoring != "spherical" or math.isinf(bearing.effective_radius):
        raise ValueError(f"Element 'ptv' of {owner} has the spherical restoring law "
                         "N u / sqrt(R^2 - u^2) with a finite R. Got a bearing with "
                         f"{bearing.restoring!r} and R = {bearing.effective_radius!r} instead.")
    if friction.heating is None and "temperature" in friction.dependencies:
        raise ValueError(f"Element 'ptv' of {owner} always heats its surface; a temperature "
                         "dependent PTVFriction without heating has no OpenSees twin.")
    radius, factors = bearing.effective_radius, friction.factors
    flag = {name: int(name in friction.dependencies)
            for name in ("pressure", "temperature", "velocity")}
    k_initial = friction.mu_t0 * weight / bearing.yield_displacement + weight / radius
    ops.element(
        "FPBearingPTV", 1, bottom, top, friction.mu_t0,
        flag["pressure"], factors.reference_pressure,
        flag["temperature"], friction.thermal.diffusivity, friction.thermal.conductivity,
        flag["velocity"], factors.rate_parameter,
        radius, bearing.contact_radius, k_initial,
        1, 2, 2, 2,  # materials: axial, torsion, rocking about local y and z
        0.0, 0.0, 1.0, 1.0, 0.0, 0.0,  # local x = global Z (axial), local y = global X
        0.0, 0, 0.0,  # shearDist, doRayleigh, mass
        ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * weight, 1,  # units: N, m, s, degC
    )
    return friction
