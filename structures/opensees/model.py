"""The isolated shear building and its isolation level built in openseespy.

:func:`build_model` turns the objects of a native run (a :class:`ShearBuilding`, one
:class:`~isolator.bearing.DCFPBearing` and the number of bearings) into an OpenSees model and
returns what a time-history driver needs to record it. One source of truth: every mass,
stiffness and damping coefficient is read from the building's own matrices.

Layout. Every node sits at the origin (all elements have zero length). Node 1 is the ground
(fixed), node 2 the base slab (free horizontally and vertically; the vertical DOF is massless
and carries the building's weight W as a nodal load), nodes 3 .. n+2 the floors (horizontal DOF
only). 2D (``-ndm 2 -ndf 3``) for singleFPBearing / flatSliderBearing, 3D (``-ndm 3 -ndf 6``)
for FPBearingPTV, which exists in 3D only. Masses are nodal and horizontal only.

Superstructure. Our matrices on ``[u_b, u_1..u_n]`` are ``K = T^T K_fb T`` and
``C = T^T C_fb T``: symmetric with zero row sums (a rigid-body motion meets no force). Such a
matrix is the Laplacian of a spring or dashpot network: pair (i, j) gets ``-K_ij`` and ``-C_ij``
(:func:`pair_coefficients`). Each pair becomes one ``zeroLength`` element with an ``Elastic``
uniaxial material of stiffness ``-K_ij`` and damping ``eta = -C_ij`` (ZeroLength puts the
material's damping tangent into its damping matrix and ``eta * strain rate`` into its force).
For Rayleigh damping ``C_fb = a0 M_fb + a1 K_fb`` this is a dashpot ``a1 k_i`` beside each
storey spring plus a dashpot ``a0 m_i`` from each floor to the base slab: exactly ours, including
the mass-proportional part, and the isolation mode is not damped (OpenSees's own ``rayleigh``
with alphaM would damp every nodal velocity relative to the ground, the isolation mode with it).
Modal damping gives a full network (coefficients of either sign); it is still exact.

Isolation level (the kind of element follows the friction model, see :func:`element_kind`):

``coulomb`` / ``velocity``
    ``frictionModel Coulomb mu`` or ``VelDependent muSlow muFast transRate``, and with
    ``pendulum="singlefp"`` one ``singleFPBearing`` carrying W, whose force is linear in its
    normal force, so one element stands for the n bearings exactly; its normal force is
    ``N = W + F u / R`` (SingleFPSimple2d.cpp), ours ``N = W``. With ``pendulum="spring"`` a
    ``flatSliderBearing`` (N = W) plus an elastic zeroLength spring ``W / R`` in parallel:
    exactly our linear law. kInit is the total initial stiffness ``mu N / u_y (+ N / R)``.
``ptv``
    n parallel ``FPBearingPTV`` elements (pressure N / (pi r^2) must be per bearing), each
    with W / n, its own heating, MuRef = mu_t0, Kumar factors and the spherical law; its
    kInitial is ``mu N / u_y + N / R`` likewise.

The pre-sliding branch differs by formulation: ours is ``mu(v, T) N z`` with z moving by
du / u_y, so its stiffness follows mu; OpenSees's is a spring of fixed stiffness capped at
mu N. The mu that sets kInit is therefore the one at rest (zero speed, initial temperature,
the bearing's pressure: mu_slow for VelDependent), which the bearing has when it sticks: on
the five-storey example it halves the base-shear NRMSE against VelDependent (5.3 % against
12.8 % with mu_fast) and brings FPBearingPTV's peak displacement from 5.6 % to 1.9 % of ours
(against MuRef = mu_t0).

openseespy keeps one global model: the caller wipes it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from dcfpb.common.validation import check_choice
from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction, PTVFriction
from structures.opensees.equivalents import (
    ELEMENT_ITERATIONS,
    ELEMENT_TOLERANCE,
    fpbearingptv_equivalent,
    velocity_dependent_parameters,
)
from structures.shear_building import ShearBuilding

__all__ = ["PENDULUMS", "BearingRecord", "OpenSeesModel", "build_model", "element_kind",
           "pair_coefficients"]

PENDULUMS = ("singlefp", "spring")
GROUND, BASE = 1, 2
_FLOOR_NODE = 3  # first floor's node tag
_AXIAL_SHORTENING = 1.0e-6  # [m] of the stiff axial spring under its load
_PAIR_CUTOFF = 1.0e-12  # pair coefficients below this share of the largest are round-off
_SI_UNITS = 1  # FPBearingPTV unit code: N, m, s, degC
_FIRST_NETWORK_TAG = 100  # first material and element tag of the storey network
_ORIENT_2D = (0.0, 1.0, 0.0, -1.0, 0.0, 0.0)  # local x up (axial), local y = -global X
_ORIENT_3D = (0.0, 0.0, 1.0, 1.0, 0.0, 0.0)  # local x = global Z (axial), local y = global X


class BearingRecord(NamedTuple):
    """The isolation level's state after a committed step (all bearings together).

    Attributes
    ----------
    force, friction_force : float
        Horizontal force of all bearings and its friction part [N].
    mu : float
        Friction coefficient [-].
    temperature, heat_flux : float
        Contact temperature [degC] and heat flux [W/m^2] (FPBearingPTV only; otherwise the
        initial temperature and NaN: the other elements do not model heating).
    axial_load : float
        Normal force of one bearing [N].
    """

    force: float
    friction_force: float
    mu: float
    temperature: float
    heat_flux: float
    axial_load: float


class OpenSeesModel(NamedTuple):
    """What the driver needs of a built model.

    Attributes
    ----------
    nodes : tuple of int
        Node tags of ``[base slab, floor 1 .. floor n]`` (the DOF order of our model).
    ndf : int
        Degrees of freedom per node (3 in 2D, 6 in 3D); DOF 1 is the horizontal one.
    element : str
        Description of the isolation element(s), e.g. ``"singleFPBearing Coulomb"``.
    record : callable
        ``record(ops) -> BearingRecord`` at the current (committed) state.
    initial : BearingRecord
        The state at rest before the first step (as the native run records it: no force,
        mu 0, the initial temperature, the weight per bearing).
    """

    nodes: tuple[int, ...]
    ndf: int
    element: str
    record: Callable[[object], BearingRecord]
    initial: BearingRecord


def element_kind(bearing: DCFPBearing) -> str:
    """``"coulomb"``, ``"velocity"`` or ``"ptv"``: the OpenSees element for the friction model.

    Raises
    ------
    ValueError
        For a friction model no OpenSees element represents.
    """
    friction = bearing.friction
    if isinstance(friction, ConstantFriction):
        return "coulomb"
    if isinstance(friction, PTVFriction) and not friction.heats:
        return "velocity"
    return "ptv"


def pair_coefficients(matrix: np.ndarray) -> list[tuple[int, int, float]]:
    """The spring or dashpot network ``(i, j, -A_ij)`` whose Laplacian is ``matrix``.

    Parameters
    ----------
    matrix : numpy.ndarray
        Symmetric matrix with zero row sums, shape (m, m) (stiffness [N/m] or damping
        [N s/m] on the drifts).

    Raises
    ------
    ValueError
        If the matrix is not symmetric or its rows do not sum to zero (it would act on a
        rigid-body motion and cannot be a network of two-node elements).
    """
    a = np.asarray(matrix, dtype=float)
    scale = float(np.max(np.abs(a))) if a.size else 0.0
    if scale == 0.0:
        return []
    if not np.allclose(a, a.T, rtol=0.0, atol=1e-12 * scale) or np.max(
            np.abs(a.sum(axis=1))) > 1e-9 * scale:
        raise ValueError("The 'matrix' parameter of pair_coefficients must be symmetric with "
                         "zero row sums (it acts on drifts only). Got row sums "
                         f"{a.sum(axis=1)!r} instead.")
    i, j = np.triu_indices(a.shape[0], k=1)
    keep = np.abs(a[i, j]) > _PAIR_CUTOFF * scale
    return [(int(p), int(q), float(-a[p, q])) for p, q in zip(i[keep], j[keep], strict=True)]


def build_model(ops, building: ShearBuilding, bearing: DCFPBearing, n_bearings: int,
                pendulum: str = "singlefp") -> OpenSeesModel:
    """Build the building on its isolation level in the (wiped) openseespy domain.

    Parameters
    ----------
    ops : module
        ``openseespy.opensees`` from :func:`~structures.opensees.runtime.import_opensees`.
    building : ShearBuilding
        Masses [kg], storey stiffnesses [N/m] and superstructure damping.
    bearing : DCFPBearing
        One bearing; its axial load is replaced by W / n_bearings as in the native run.
    n_bearings : int
        Identical bearings under the base slab.
    pendulum : {"singlefp", "spring"}
        For the 2D elements: singleFPBearing (N = W + F u / R) or flatSliderBearing plus a
        linear spring W / R (N = W, our law). Ignored for FPBearingPTV.

    Raises
    ------
    ValueError
        If the bearing cannot be represented (see :mod:`structures.opensees.bearing`).
    """
    pendulum = check_choice(pendulum, "pendulum", "build_model", PENDULUMS)
    kind = element_kind(bearing)
    weight = building.weight
    ndm, ndf = (3, 6) if kind == "ptv" else (2, 3)
    ops.model("basic", "-ndm", ndm, "-ndf", ndf)
    nodes = (BASE, *range(_FLOOR_NODE, _FLOOR_NODE + building.n_storeys))
    origin = (0.0,) * ndm
    for tag in (GROUND, *nodes):
        ops.node(tag, *origin)
    vertical = ndm  # DOF number of the vertical translation (Y in 2D, Z in 3D)
    ops.fix(GROUND, *([1] * ndf))
    ops.fix(BASE, *[0 if d in (1, vertical) else 1 for d in range(1, ndf + 1)])
    for tag in nodes[1:]:
        ops.fix(tag, *[0 if d == 1 else 1 for d in range(1, ndf + 1)])
    masses = np.diag(building.isolated_mass_matrix)
    for tag, mass in zip(nodes, masses, strict=True):
        ops.mass(tag, float(mass), *([0.0] * (ndf - 1)))
    _superstructure(ops, building, nodes, max(_FIRST_NETWORK_TAG, n_bearings + 4))
    if kind == "ptv":
        record, element = _fpbearingptv(ops, bearing, n_bearings, weight)
    else:
        record, element = _pendulum_2d(ops, bearing, kind, n_bearings, weight, pendulum)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    load = [0.0] * ndf
    load[vertical - 1] = -weight
    ops.load(BASE, *load)
    initial = BearingRecord(0.0, 0.0, 0.0, _initial_temperature(bearing),
                            0.0 if kind == "ptv" else math.nan, weight / n_bearings)
    return OpenSeesModel(nodes, ndf, element, record, initial)


def _superstructure(ops, building: ShearBuilding, nodes: tuple[int, ...], first: int) -> None:
    """zeroLength spring-dashpots with the pair coefficients of K and C (module docstring),
    tagged from ``first`` on (below it: the isolation level's elements and materials)."""
    pairs: dict[tuple[int, int], list[float]] = {}
    for index, matrix in enumerate((building.isolated_stiffness_matrix,
                                    building.isolated_damping_matrix)):
        for i, j, value in pair_coefficients(matrix):
            pairs.setdefault((i, j), [0.0, 0.0])[index] = value
    for tag, ((i, j), (stiffness, damping)) in enumerate(sorted(pairs.items()), start=first):
        ops.uniaxialMaterial("Elastic", tag, stiffness, damping)
        ops.element("zeroLength", tag, nodes[i], nodes[j], "-mat", tag, "-dir", 1)


def _axial_materials(ops, load: float) -> None:
    """Material 1: stiff axial spring (shortens 1e-6 m under ``load``); 2: rotations."""
    ops.uniaxialMaterial("Elastic", 1, load / _AXIAL_SHORTENING)
    ops.uniaxialMaterial("Elastic", 2, load / _AXIAL_SHORTENING)


def _initial_temperature(bearing: DCFPBearing) -> float:
    friction = bearing.friction
    if isinstance(friction, PTVFriction):
        return friction.thermal.initial_temperature
    return friction.initial_temperature


def _mu_at_rest(friction: PTVFriction, pressure: float) -> float:
    """mu at zero speed and the initial temperature under ``pressure`` [Pa] (sets kInit)."""
    factors, mu = friction.factors, friction.mu_t0
    for name, value in (("pressure", pressure), ("velocity", 0.0),
                        ("temperature", friction.thermal.initial_temperature)):
        if name in friction.dependencies:
            mu *= getattr(factors, name)(value)[0]
    return mu


def _pendulum_2d(ops, bearing: DCFPBearing, kind: str, n_bearings: int, weight: float,
                 pendulum: str):
    """singleFPBearing, or flatSliderBearing + spring; one element for all bearings."""
    if bearing.restoring != "linear":
        raise ValueError(f"The {kind!r} elements of build_model have the linear restoring law "
                         f"N u / R. Got a bearing with {bearing.restoring!r} instead.")
    friction, radius = bearing.friction, bearing.effective_radius
    if kind == "coulomb":
        ops.frictionModel("Coulomb", 1, friction.mu)
        mu, label = friction.mu, "Coulomb"
    else:  # mu at the pressure of one bearing, as in the native run
        pressure = weight / n_bearings / bearing.contact_area
        parameters = velocity_dependent_parameters(friction, pressure)
        ops.frictionModel("VelDependent", 1, *parameters)
        mu, label = parameters.mu_slow, "VelDependent"
    _axial_materials(ops, weight)
    flat = math.isinf(radius) or pendulum == "spring"
    stiffness = 0.0 if math.isinf(radius) else weight / radius
    k_initial = mu * weight / bearing.yield_displacement + (0.0 if flat else stiffness)
    options = ("-P", 1, "-Mz", 2, "-orient", *_ORIENT_2D,
               "-iter", ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * weight)
    if flat:
        ops.element("flatSliderBearing", 1, GROUND, BASE, 1, k_initial, *options)
        name = "flatSliderBearing"
        if stiffness > 0.0:
            ops.uniaxialMaterial("Elastic", 3, stiffness)
            ops.element("zeroLength", 2, GROUND, BASE, "-mat", 3, "-dir", 1)
            name += " + linear spring W/R"
    else:
        ops.element("singleFPBearing", 1, GROUND, BASE, 1, radius, k_initial, *options)
        name = "singleFPBearing"
    temperature = _initial_temperature(bearing)

    def record(ops) -> BearingRecord:
        u = ops.nodeDisp(BASE, 1)
        slider = ops.eleResponse(1, "force")[3]
        normal = ops.eleResponse(1, "frictionModel", "normalForce")[0]
        if flat:
            force, friction_force = slider + stiffness * u, slider
        else:
            force, friction_force = slider, slider - normal * u / radius
        mu = ops.eleResponse(1, "frictionModel", "COF")[0]
        return BearingRecord(force, friction_force, mu, temperature, math.nan,
                             normal / n_bearings)

    return record, f"{name} {label}"


def _fpbearingptv(ops, bearing: DCFPBearing, n_bearings: int, weight: float):
    """n parallel FPBearingPTV elements in 3D, each carrying W / n."""
    owner = "build_model"
    friction = bearing.friction
    if fpbearingptv_equivalent(bearing) != bearing:  # also checks Kumar factors and 20 degC
        raise ValueError(f"The bearing of {owner} must be shaped as FPBearingPTV models it "
                         "(structures.opensees.bearing.fpbearingptv_equivalent: one centre-"
                         "heated surface, refinement sqrt(pi)/2, spherical law). Got "
                         f"{bearing!r} instead.")
    load, radius = weight / n_bearings, bearing.effective_radius
    factors = friction.factors
    flag = {name: int(name in friction.dependencies)
            for name in ("pressure", "temperature", "velocity")}
    k_initial = _mu_at_rest(friction, load / bearing.contact_area) * load / (
        bearing.yield_displacement) + load / radius
    _axial_materials(ops, load)
    tags = range(1, n_bearings + 1)
    for tag in tags:
        ops.element(
            "FPBearingPTV", tag, GROUND, BASE, friction.mu_t0,
            flag["pressure"], factors.reference_pressure,
            flag["temperature"], friction.thermal.diffusivity, friction.thermal.conductivity,
            flag["velocity"], factors.rate_parameter,
            radius, bearing.contact_radius, k_initial,
            1, 2, 2, 2,  # materials: axial, torsion, rocking about local y and z
            *_ORIENT_3D, 0.0, 0, 0.0,  # orientation, shearDist, doRayleigh, mass
            ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * load, _SI_UNITS,
        )

    def record(ops) -> BearingRecord:
        u = ops.nodeDisp(BASE, 1)
        force = sum(ops.eleResponse(tag, "force")[6] for tag in tags)
        normal = -ops.eleResponse(1, "basicForce")[0]
        restoring = n_bearings * normal * u / math.sqrt(radius**2 - u * u)
        return BearingRecord(force, force - restoring, ops.eleResponse(1, "MuAdjusted")[0],
                             ops.eleResponse(1, "temperature")[0],
                             ops.eleResponse(1, "HeatFlux")[0], normal)

    return record, f"{n_bearings} x FPBearingPTV"
