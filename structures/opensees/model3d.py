"""The building in plan and its bearings built in openseespy (``-ndm 3 -ndf 6``).

:func:`build_model_3d` turns a :class:`~structures.spatial.building.SpatialBuilding` and one
:class:`~isolator.bearing.DCFPBearing` (Coulomb friction, the linear law) into an OpenSees
model whose every mass, stiffness and damping coefficient is read from our building, and
returns the tags a time-history driver needs (:class:`SpatialModel`).

Layout. All nodes lie in the plane Z = 0 (every element has zero length, as in the planar
twin :mod:`structures.opensees.model`); each level is a ``rigidDiaphragm`` (perpendicular
direction Z) of its own:

- the **master** node of level L (0: base slab, 1..n: floors) at the level's centre of mass
  ``G_L = O + e_L`` carries its mass ``m`` in X and Y and its mass moment of inertia ``J_G``
  about Z: with the diaphragm this is exactly our eccentric mass matrix at ``O`` (the kinetic
  energy ``m |v_G|^2 / 2 + J_G theta'^2 / 2``);
- a constrained node of each level at the centre of stiffness ``O`` (the origin): the storey
  ``s`` is one ``zeroLength`` element between the ``O`` nodes of levels s-1 and s with
  ``Elastic`` materials ``k_x``, ``k_y`` (directions 1, 2) and ``k_theta`` (direction 6), the
  uncoupled storey stiffness of :meth:`structures.spatial.plan.Plan.stiffnesses`;
- the bearings' top nodes: constrained nodes of the base slab at ``(x_i, y_i)``, free
  vertically (massless, carrying the gravity share ``N_i`` as a nodal load on a stiff axial
  material: 1 um shortening), their rocking rotations fixed; their bottom nodes fixed.

Damping of the superstructure only (:mod:`structures.spatial.building`), Rayleigh
``C_fb = a0 M_fb + a1 K_fb`` with our coefficients, as a dashpot network, exact:
``a1 k`` in each storey element beside its spring (the ``Elastic`` material's ``eta``), and
``a0 M_j`` on floor j's drift from the base slab, which is the dashpot ``(a0 m_j, a0 m_j,
a0 J_G,j)`` between floor j's master at ``G_j`` and a constrained node of the base slab at the
same plan point (the drift of the centre of mass and the twist:
``T_G^T diag(m, m, J_G) T_G = M_j``). OpenSees's own ``rayleigh`` would damp the isolation
modes too. Modal damping (a full matrix on the drifts) has no two-node network here and is
refused.

Bearings (``pendulum``):

``"singlefp"``
    one ``singleFPBearing`` (3D, ``SingleFPSimple3d``, ``frictionModel Coulomb mu``) per
    bearing, oriented as in :mod:`structures.opensees.bearing3d` (local x = global Z, local
    y = global X, local z = global Y), kInit ``mu N_i / u_y + N_i / R``; its normal force is
    ``N_i + F_X u_X / R_x + F_Y u_Y / R_y`` and its restoring law has crossed radii
    (:func:`~structures.opensees.equivalents3d.singlefp3d_restoring`); ours ``N_i u / R``.
``"spring"``
    ``flatSliderBearing`` (3D, Coulomb, N = N_i) plus a ``zeroLength`` spring ``N_i / R`` in X
    and Y: exactly our linear law and return map, so the building is ours to round-off.

The torsion material of the bearings has zero stiffness (a pot bearing does not resist the
slab's twist about its own axis; ours neither). Vertical ground motion, when given, is the
quasi-static load ``-N_i a_z / g`` on each top node (our building is rigid vertically:
``N_i (1 + a_z / g)``), added by the driver. The overturning of the floors' inertia forces is
not modelled here (zero-length storeys): the comparison runs ours without it.

openseespy keeps one global model: the caller wipes it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from dcfpb.common.validation import check_choice
from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction
from structures.opensees.equivalents import ELEMENT_ITERATIONS, ELEMENT_TOLERANCE
from structures.shear_building import RayleighDamping
from structures.spatial.building import SpatialBuilding

__all__ = ["PENDULUMS_3D", "SpatialModel", "build_model_3d", "rayleigh_coefficients"]

PENDULUMS_3D = ("singlefp", "spring")
_AXIAL_SHORTENING = 1.0e-6  # [m] of the stiff axial material under the gravity share
_ORIENTATION = (0.0, 0.0, 1.0, 1.0, 0.0, 0.0)  # local x = global Z, local y = global X
_TOP_X, _TOP_Y = 6, 7  # global X and Y force on the top node in the element's force vector
_FIXED, _FREE = 1, 0


class SpatialModel(NamedTuple):
    """What the driver needs of a built model.

    Attributes
    ----------
    masters : tuple of int
        Master node of each level (base slab first) at its centre of mass.
    centres : tuple of int
        The constrained node of each level at the centre of stiffness ``O``.
    tops : tuple of int
        Each bearing's top node (vertical DOF free: the gravity share acts on it).
    shares : numpy.ndarray
        Each bearing's gravity share ``N_i`` [N].
    element : str
        What the bearings are in OpenSees.
    record : callable
        ``record(ops) -> (force (n_b, 2), normal (n_b,), mu (n_b,))``: each bearing's
        horizontal force [N], the normal force it uses [N] and its friction coefficient.
    """

    masters: tuple[int, ...]
    centres: tuple[int, ...]
    tops: tuple[int, ...]
    shares: np.ndarray
    element: str
    record: Callable


def rayleigh_coefficients(building: SpatialBuilding) -> tuple[float, float]:
    """``(a0, a1)`` of our superstructure damping ``C_fb = a0 M_fb + a1 K_fb`` [1/s, s].

    Raises
    ------
    ValueError
        For modal damping (see the module docstring).
    """
    damping = building.building.damping
    if not isinstance(damping, RayleighDamping):
        raise ValueError("The 'building' of build_model_3d must have RayleighDamping: modal "
                         "damping is a full matrix on the drifts, which no network of two-node "
                         f"dashpots reproduces in plan. Got {damping!r} instead.")
    omega = building.building.fixed_base_modes().circular_frequencies
    i, j = damping.modes
    a0, a1 = damping.coefficients((omega[i - 1], omega[j - 1]), damping.ratios)
    return float(a0), float(a1)


def _check_bearing(bearing: DCFPBearing) -> float:
    """mu of a bearing singleFPBearing Coulomb represents, else an error."""
    if not isinstance(bearing.friction, ConstantFriction):
        raise ValueError("The bearing of build_model_3d must have a ConstantFriction (OpenSees "
                         f"frictionModel Coulomb). Got {bearing.friction!r} instead.")
    if bearing.restoring != "linear":
        raise ValueError("The bearing of build_model_3d must have the linear restoring law "
                         f"N u / R. Got {bearing.restoring!r} instead.")
    return float(bearing.friction.mu)


class _Tags:
    """Consecutive node, material and element tags."""

    def __init__(self, first: int) -> None:
        self.last = first - 1

    def __call__(self) -> int:
        self.last += 1
        return self.last


def build_model_3d(ops, building: SpatialBuilding, bearing: DCFPBearing,
                   pendulum: str = "singlefp") -> SpatialModel:
    """Build the building in plan on its bearings in the (wiped) openseespy domain.

    Parameters
    ----------
    ops : module
        ``openseespy.opensees`` from :func:`~structures.opensees.runtime.import_opensees`.
    building : SpatialBuilding
        Masses [kg], inertias [kg m^2], eccentricities and bearing positions [m], storey
        stiffnesses [N/m, N m/rad], Rayleigh damping.
    bearing : DCFPBearing
        The bearing of every position (Coulomb friction, linear law); each carries its
        gravity share (:attr:`SpatialBuilding.gravity_shares`).
    pendulum : {"singlefp", "spring"}
        See the module docstring.

    Raises
    ------
    ValueError
        For modal damping, or a bearing OpenSees cannot represent here.
    """
    owner = "build_model_3d"
    pendulum = check_choice(pendulum, "pendulum", owner, PENDULUMS_3D)
    mu = _check_bearing(bearing)
    a0, a1 = rayleigh_coefficients(building)
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    node, material, element = _Tags(1), _Tags(1), _Tags(1)
    n, plan = building.n_storeys, building.plan
    masses, inertias = building.level_masses, building.level_inertias
    masters, centres, slaves = [], [], []
    for level in range(n + 1):
        x, y = building.level_centres[level]
        masters.append(node())
        ops.node(masters[-1], float(x), float(y), 0.0)
        ops.fix(masters[-1], _FREE, _FREE, _FIXED, _FIXED, _FIXED, _FREE)
        ops.mass(masters[-1], float(masses[level]), float(masses[level]), 0.0, 0.0, 0.0,
                 float(inertias[level]))
        centres.append(node())
        ops.node(centres[-1], 0.0, 0.0, 0.0)
        slaves.append([centres[-1]])
    base_points = []  # the base slab under each floor's centre of mass (a0 M dashpots)
    for level in range(1, n + 1):
        x, y = building.level_centres[level]
        base_points.append(node())
        ops.node(base_points[-1], float(x), float(y), 0.0)
        slaves[0].append(base_points[-1])
    shares = np.asarray(building.gravity_shares, dtype=float)
    bottoms, tops = [], []
    for x, y in plan.bearing_coordinates:
        bottoms.append(node())
        ops.node(bottoms[-1], float(x), float(y), 0.0)
        ops.fix(bottoms[-1], *([_FIXED] * 6))
        tops.append(node())
        ops.node(tops[-1], float(x), float(y), 0.0)
        slaves[0].append(tops[-1])
    for level_slaves in slaves:
        for tag in level_slaves:
            free_z = tag in tops
            ops.fix(tag, _FREE, _FREE, _FREE if free_z else _FIXED, _FIXED, _FIXED, _FREE)
    for master, level_slaves in zip(masters, slaves, strict=True):
        ops.rigidDiaphragm(3, master, *level_slaves)
    stiffness = building.storey_stiffnesses
    for storey in range(n):
        tags = []
        for k in stiffness[storey]:
            tags.append(material())
            ops.uniaxialMaterial("Elastic", tags[-1], float(k), a1 * float(k))
        ops.element("zeroLength", element(), centres[storey], centres[storey + 1],
                    "-mat", *tags, "-dir", 1, 2, 6)
    if a0 != 0.0:
        for level in range(1, n + 1):
            tags = []
            for coefficient in (masses[level], masses[level], inertias[level]):
                tags.append(material())
                ops.uniaxialMaterial("Elastic", tags[-1], 0.0, a0 * float(coefficient))
            ops.element("zeroLength", element(), base_points[level - 1], masters[level],
                        "-mat", *tags, "-dir", 1, 2, 6)
    record, label = _bearings(ops, bearing, mu, shares, bottoms, tops, pendulum,
                              material, element)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    for tag, share in zip(tops, shares, strict=True):
        ops.load(tag, 0.0, 0.0, -float(share), 0.0, 0.0, 0.0)
    return SpatialModel(tuple(masters), tuple(centres), tuple(tops), shares, label, record)


def _bearings(ops, bearing: DCFPBearing, mu: float, shares: np.ndarray, bottoms: list[int],
              tops: list[int], pendulum: str, material: _Tags, element: _Tags):
    """One bearing element per position (module docstring); return the recorder and label."""
    radius = bearing.effective_radius
    flat = math.isinf(radius) or pendulum == "spring"
    zero = material()
    ops.uniaxialMaterial("Elastic", zero, 0.0)  # the bearing's torsion: none
    tags, springs = [], []
    for bottom, top, share in zip(bottoms, tops, shares, strict=True):
        friction, axial = material(), material()
        ops.frictionModel("Coulomb", friction, mu)
        ops.uniaxialMaterial("Elastic", axial, float(share) / _AXIAL_SHORTENING)
        pendulum_stiffness = 0.0 if math.isinf(radius) else float(share) / radius
        k_initial = mu * float(share) / bearing.yield_displacement + (
            0.0 if flat else pendulum_stiffness)
        options = ("-P", axial, "-T", zero, "-My", axial, "-Mz", axial,
                   "-orient", *_ORIENTATION,
                   "-iter", ELEMENT_ITERATIONS, ELEMENT_TOLERANCE * float(share))
        tags.append(element())
        if flat:
            ops.element("flatSliderBearing", tags[-1], bottom, top, friction, k_initial,
                        *options)
            if pendulum_stiffness > 0.0:
                spring = material()
                ops.uniaxialMaterial("Elastic", spring, pendulum_stiffness)
                ops.element("zeroLength", element(), bottom, top, "-mat", spring, spring,
                            "-dir", 1, 2)
                springs.append(pendulum_stiffness)
            else:
                springs.append(0.0)
        else:
            ops.element("singleFPBearing", tags[-1], bottom, top, friction, radius, k_initial,
                        *options)
            springs.append(0.0)
    spring_stiffness = np.asarray(springs)

    def record(ops) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        force = np.empty((len(tags), 2))
        normal, cof = np.empty(len(tags)), np.empty(len(tags))
        for i, tag in enumerate(tags):
            values = ops.eleResponse(tag, "force")
            force[i] = values[_TOP_X], values[_TOP_Y]
            normal[i] = ops.eleResponse(tag, "frictionModel", "normalForce")[0]
            cof[i] = ops.eleResponse(tag, "frictionModel", "COF")[0]
        if flat:
            u = np.array([(ops.nodeDisp(t, 1), ops.nodeDisp(t, 2)) for t in tops])
            force += spring_stiffness[:, None] * u
        return force, normal, cof

    if flat:
        label = "flatSliderBearing 3D Coulomb" + (
            " + linear springs N_i/R" if not math.isinf(radius) else "")
    else:
        label = "singleFPBearing 3D Coulomb"
    return record, label
