"""The isolated shear building, in one direction or in plan, built in openseespy
(``-ndm 3 -ndf 6``) from our dynamic model.

:func:`build_model` turns an :class:`~structures.isolated_building.IsolatedShearBuilding`
into an OpenSees model whose every mass, stiffness, damping coefficient and gravity load is read
from it, and returns what a time-history driver needs (:class:`Twin`).

Two layouts: flat (without overturning: in one direction, or in plan without it) and tall (in
plan with the overturning of the floors' inertia forces, ``model.overturning``).

Flat layout. Every node lies in the plane Z = 0 (every element has zero length). Each level
(0: the base slab, 1..n: the floors) is a ``rigidDiaphragm`` (perpendicular Z) whose master
node sits at the level's centre of mass and carries its mass in X and Y and its mass moment of
inertia about Z: with the diaphragm this is exactly our eccentric mass matrix at the centre of
stiffness O. The other nodes of a level are constrained to it: one at O, where our degrees of
freedom are recorded, and those the elements below need. In one direction every level's master
is at O and moves along X only (its Y and twist fixed), and the other nodes follow its X
(``equalDOF``: a diaphragm would tie them to the master's fixed DOFs, which the
``Transformation`` handler does not honour). The masters' and the other nodes' Z and rotations
about X and Y are fixed.

Superstructure. Our stiffness and damping on the levels, ``K = T^T K_fb T`` and
``C = T^T C_fb T``, act on the drifts only: their level blocks ``A_kl`` sum to zero along a
block row, so ``A = sum over level pairs k < l of (e_k - e_l)(e_k - e_l)^T (x) B_kl`` with
``B_kl = -A_kl``, as long as each ``A_kl`` is symmetric (:func:`pair_network`). Each
``B_kl`` is one ``zeroLength`` element between levels k and l at the point where its
translation and twist decouple, turned to its principal axes, with ``Elastic`` materials of
stiffness ``E`` and damping ``eta`` in local directions 1, 2 and 6 (ZeroLength puts
``eta * strain rate`` into its force and eta into its damping matrix). For Rayleigh damping
these are our storeys at O (``k``, ``a1 k``) and ``a0 M_j`` at floor j's centre of mass, the
mass-proportional part included and the isolation modes undamped (OpenSees's own ``rayleigh``
would damp them). Modal damping is a full matrix on the drifts: still exact in one direction
(coefficients of either sign) and in plan whenever its level blocks are symmetric, as for
every level with the same eccentricity and stiffness proportions; otherwise the network takes
their symmetric part, with a warning saying how much is left out (the whole stays symmetric
and acts on the drifts only).

Bearings. At each bearing position a fixed node and a node of the base slab free vertically
(massless, on the stiff axial material of the element under its gravity load): the elements of
:func:`structures.opensees.elements.add_bearing` for the position's bearings (one group of
``n_bearings`` at O in one direction). Each position carries its own gravity load.

Tall layout. The same masters, masses, network and bearings, with every level at its height
above the isolation level (:func:`level_heights`, the plan's storey heights) and rigid in and
out of plane: its other nodes follow its master by ``rigidLink beam``, and no node but the
bearings' bottoms is fixed. Each link of the network is a vertical ``twoNodeLink`` of real
length (local x up, y along the link's first axis) with its coefficients in directions 2, 3
(the shears) and 4 (the twist); TwoNodeLink's basic shears subtract the ends' rotations and
its end moments balance the couple of its shears (shearDist 0.5), so a storey carries its
shear to the level below with its moment. A link with a storey stiffness k is also rigid
axially (``STOREY_RIGIDITY k``) and in bending (``STOREY_RIGIDITY k L^2``, L its height): the
floors neither rise nor turn about X or Y relative to the base slab, as in our shear building,
and the overturning moment of the floors' inertia forces (at their masters, ``H_j F_j``)
reaches the base slab, whatever that rigidity, by the links' equilibrium. The base slab rests
on the bearings' axial springs alone: equal stiffness at every position (the mean gravity
load over ``AXIAL_SHORTENING``) and no moment (``hinged``: the top nodes turn with the slab,
the elements' P-Delta moments go to their fixed bottoms), so the slab shares the vertical
loads and the moments linearly over the positions, ``G`` of
:func:`structures.plan.axial_distribution`: the gravity loads on the top nodes give back the
gravity shares, their vertical scaling ``-P_i a_z / g`` its share, and the overturning the
axial loads of :meth:`~structures.isolated_building.IsolatedShearBuilding.axial_loads`. The
slab rocks on those springs by about 1e-8 rad, which moves the floors by ``H_j`` times that
(rigidly, without a drift).

openseespy keeps one global model: the caller wipes it.
"""

from __future__ import annotations

import itertools
import math
import warnings
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import InputWarning
from dcfpb.common.validation import check_choice
from structures.isolated_building import IsolatedShearBuilding
from structures.opensees.elements import (
    AXIAL_SHORTENING,
    add_bearing,
    element_kind,
    fpbearingptv_equivalent,
)

__all__ = ["PENDULUMS", "STOREY_RIGIDITY", "Link", "Twin", "build_model", "level_heights",
           "pair_network"]

PENDULUMS = ("singlefp", "spring")
_PAIR_CUTOFF = 1.0e-12  # coefficients below this share of the largest are round-off
_ASYMMETRY = 1.0e-9  # an antisymmetric part above this share of the largest is a warning
_FIXED, _FREE = 1, 0
_SAME_POINT = 1.0e-9  # [m] a point this close to a master is the master's
STOREY_RIGIDITY = 1.0e8
"""With overturning: a storey's axial stiffness over its lateral stiffness [-] (its bending
stiffness over the lateral stiffness times its height squared)."""


class Link(NamedTuple):
    """One two-node element of the superstructure network.

    Attributes
    ----------
    levels : tuple of int
        The two levels (k < l) it joins.
    point : tuple of float
        Where it stands in the plan (x, y) [m].
    angle : float
        Its local x from the global X [rad].
    stiffness, damping : tuple of float
        Its coefficients in the local directions (1,) or (1, 2, 6) [N/m, N m/rad; N s/m, ...].
    """

    levels: tuple[int, int]
    point: tuple[float, float]
    angle: float
    stiffness: tuple[float, ...]
    damping: tuple[float, ...]


class Twin(NamedTuple):
    """What the driver needs of a built model.

    Attributes
    ----------
    levels : tuple of int
        The node at O of each level, base slab first (our degrees of freedom).
    dofs : tuple of int
        The recorded degrees of freedom of a level: ``(1,)`` or ``(1, 2, 6)``.
    nodes : tuple of int
        Every node that moves with a level (masters and constrained nodes).
    tops : tuple of int
        Each bearing position's top node (its vertical DOF carries the gravity load).
    loads : numpy.ndarray
        The gravity load of each position, all its bearings [N].
    element : str
        What the bearings are in OpenSees.
    read : callable
        ``read(ops) -> dict`` of one bearing at each position (the fields of
        :data:`structures.results.BEARING_RECORD`, arrays (n_b, 2) and (n_b,)).
    initial : dict
        The same at rest before the first step.
    """

    levels: tuple[int, ...]
    dofs: tuple[int, ...]
    nodes: tuple[int, ...]
    tops: tuple[int, ...]
    loads: np.ndarray
    element: str
    read: Callable[[object], dict]
    initial: dict


def _frame(block: np.ndarray, scale: float) -> tuple[tuple[float, float], float, np.ndarray]:
    """Point, angle and local coefficients of a symmetric block on (x, y, theta) at O."""
    if block.shape == (1, 1):
        return (0.0, 0.0), 0.0, block[0]
    translation, coupling = block[:2, :2], block[:2, 2]
    point = (0.0, 0.0)
    twist = block[2, 2]
    if np.max(np.abs(coupling)) > _PAIR_CUTOFF * scale:  # move to where they decouple
        t = -np.linalg.solve(translation, coupling)  # (p_y, -p_x)
        point = (float(-t[1]), float(t[0]))
        twist = block[2, 2] + coupling @ t
    if abs(translation[0, 1]) <= _PAIR_CUTOFF * scale:
        return point, 0.0, np.array([translation[0, 0], translation[1, 1], twist])
    angle = 0.5 * math.atan2(2.0 * translation[0, 1], translation[0, 0] - translation[1, 1])
    c, s = math.cos(angle), math.sin(angle)
    axes = np.array([[c, -s], [s, c]])
    local = axes.T @ translation @ axes
    return point, angle, np.array([local[0, 0], local[1, 1], twist])


def pair_network(stiffness: np.ndarray, damping: np.ndarray, level_dofs: int) -> list[Link]:
    """The two-node elements whose stiffness and damping sum to the given level matrices.

    Parameters
    ----------
    stiffness, damping : numpy.ndarray
        Symmetric matrices on the levels' degrees of freedom acting on the drifts only, shape
        ((n+1) L, (n+1) L), L = ``level_dofs`` (1: x; 3: x, y, theta at O).
    level_dofs : int
        1 or 3.

    Returns
    -------
    list of Link
        One link per level pair whose blocks are not zero, or two where the stiffness and the
        damping do not share a point and axes.

    Raises
    ------
    ValueError
        If a matrix is not symmetric or acts on a rigid motion.

    Warns
    -----
    InputWarning
        If a matrix couples two levels unsymmetrically (no network of two-node elements
        reproduces that part: the network takes the symmetric part of each level block).
    """
    size = stiffness.shape[0] // level_dofs
    frames = []
    for index, matrix in enumerate((stiffness, damping)):
        a = np.asarray(matrix, dtype=float)
        scale = float(np.max(np.abs(a))) if a.size else 0.0
        blocks = a.reshape(size, level_dofs, size, level_dofs).transpose(0, 2, 1, 3)
        if scale and (not np.allclose(a, a.T, rtol=0.0, atol=1e-12 * scale)
                      or np.max(np.abs(blocks.sum(axis=1))) > 1e-9 * scale):
            raise ValueError("The matrices of pair_network must be symmetric with zero block-row "
                             "sums (they act on the drifts only). Got block-row sums "
                             f"{blocks.sum(axis=1).tolist()!r} instead.")
        asymmetry = 0.5 * np.max(np.abs(blocks - blocks.transpose(0, 1, 3, 2)), initial=0.0)
        if asymmetry > _ASYMMETRY * scale:
            warnings.warn(InputWarning(
                f"The {('stiffness', 'damping')[index]} of the building couples its levels "
                "unsymmetrically, which no network of two-node elements reproduces: the "
                "OpenSees twin takes the symmetric part of each level block and leaves out "
                f"{asymmetry / scale:.3g} of its largest coefficient (modal damping in plan is "
                "exact with every level of the same eccentricity and stiffness proportions, "
                "Rayleigh damping always)."), stacklevel=2)
        frames.append({(i, j): _frame(-0.5 * (blocks[i, j] + blocks[i, j].T), scale)
                       for i in range(size) for j in range(i + 1, size)
                       if np.max(np.abs(blocks[i, j])) > _PAIR_CUTOFF * scale})
    links = []
    zero = (0.0,) * level_dofs
    for pair in sorted(frames[0].keys() | frames[1].keys()):
        k_frame, c_frame = frames[0].get(pair), frames[1].get(pair)
        if k_frame and c_frame and k_frame[:2] == c_frame[:2]:
            links.append(Link(pair, *k_frame[:2], tuple(k_frame[2]), tuple(c_frame[2])))
            continue
        if k_frame:
            links.append(Link(pair, *k_frame[:2], tuple(k_frame[2]), zero))
        if c_frame:
            links.append(Link(pair, *c_frame[:2], zero, tuple(c_frame[2])))
    return links


def build_model(ops, model: IsolatedShearBuilding, pendulum: str = "singlefp") -> Twin:
    """Build the building on its bearings in the (wiped) openseespy domain.

    Parameters
    ----------
    ops : module
        ``openseespy.opensees`` from :func:`~structures.opensees.runtime.import_opensees`.
    model : IsolatedShearBuilding
        Our model: masses [kg], inertias [kg m^2], storeys [N/m, N m/rad], superstructure
        damping, bearing positions [m] with their counts and gravity loads [N], the bearing;
        with ``model.overturning`` the floors stand at the plan's heights [m] (module
        docstring).
    pendulum : {"singlefp", "spring"}
        singleFPBearing (N = P + F . u / R), or flatSliderBearing plus linear springs N / R
        (N = P: our law without overturning or a vertical). Not used for FPBearingPTV.

    Raises
    ------
    ValueError
        For a bearing or damping the model cannot represent.
    """
    owner = "build_model"
    pendulum = check_choice(pendulum, "pendulum", owner, PENDULUMS)
    bearing, building = model.bearing, model.building
    kind = element_kind(bearing)
    if kind == "ptv" and fpbearingptv_equivalent(bearing) != bearing:
        raise ValueError(f"The bearing of {owner} must be shaped as FPBearingPTV models it "
                         "(structures.opensees.elements.fpbearingptv_equivalent: one centre-"
                         "heated surface, refinement sqrt(pi)/2, spherical law). Got "
                         f"{bearing!r} instead.")
    links = pair_network(building.isolated_stiffness_matrix, building.isolated_damping_matrix,
                         model.level_dofs)
    plan = model.level_dofs == 3
    tall = model.overturning
    heights = level_heights(building) if tall else np.zeros(building.n_storeys + 1)
    in_plane = _FREE if plan else _FIXED  # Y and the twist
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    node, tag = itertools.count(1).__next__, itertools.count(1).__next__
    masters, slaves, points = [], [], {}
    centres = building.level_centres
    for level, mass in enumerate(building.level_masses):
        masters.append(node())
        ops.node(masters[-1], float(centres[level, 0]), float(centres[level, 1]),
                 float(heights[level]))
        if not tall:
            ops.fix(masters[-1], _FREE, in_plane, _FIXED, _FIXED, _FIXED, in_plane)
        inertia = float(building.level_inertias[level]) if plan else 0.0
        ops.mass(masters[-1], float(mass), float(mass), 0.0, 0.0, 0.0, inertia)
        slaves.append([])

    def node_at(level: int, point: tuple[float, float], vertical: int = _FIXED) -> int:
        if vertical == _FIXED and math.dist(point, centres[level]) <= _SAME_POINT:
            return masters[level]
        if vertical == _FIXED and (level, point) in points:
            return points[level, point]
        slaves[level].append(node())
        ops.node(slaves[level][-1], *point, float(heights[level]))
        if not tall:
            ops.fix(slaves[level][-1], _FREE, in_plane, vertical, _FIXED, _FIXED, in_plane)
        if vertical == _FIXED:
            points[level, point] = slaves[level][-1]
        return slaves[level][-1]

    levels = tuple(node_at(level, (0.0, 0.0)) for level in range(len(masters)))
    directions = (1, 2, 6)[:model.level_dofs]
    for link in links:
        lower, upper = link.levels
        if tall:
            _storey_link(ops, tag, link, node_at(lower, link.point), node_at(upper, link.point))
            continue
        materials = []
        for stiffness, damping in zip(link.stiffness, link.damping, strict=True):
            materials.append(tag())
            ops.uniaxialMaterial("Elastic", materials[-1], float(stiffness), float(damping))
        c, s = math.cos(link.angle), math.sin(link.angle)
        orient = () if link.angle == 0.0 else ("-orient", c, s, 0.0, -s, c, 0.0)
        ops.element("zeroLength", tag(), node_at(lower, link.point), node_at(upper, link.point),
                    "-mat", *materials, "-dir", *directions, *orient)
    loads = np.asarray(building.gravity_shares, dtype=float)
    slab = {"axial_stiffness": float(np.mean(loads)) / AXIAL_SHORTENING, "hinged": True} \
        if tall else {}
    tops, elements = [], []
    for (x, y), count, load in zip(model.positions, model.multiplicity, loads, strict=True):
        bottom = node()
        ops.node(bottom, float(x), float(y), 0.0)
        ops.fix(bottom, *([_FIXED] * 6))
        # tall: a node of the rigid slab (shared); flat: a node of its own, free vertically
        tops.append(node_at(0, (float(x), float(y)), vertical=_FIXED if tall else _FREE))
        elements.append(add_bearing(ops, tag, bottom, tops[-1], bearing, float(load),
                                    int(count), kind=kind, pendulum=pendulum, owner=owner,
                                    **slab))
    for master, level_slaves in zip(masters, slaves, strict=True):
        if tall:  # each level a rigid body
            for slave in level_slaves:
                ops.rigidLink("beam", master, slave)
        elif plan and level_slaves:
            ops.rigidDiaphragm(3, master, *level_slaves)
        elif not plan:  # X only (module docstring)
            for slave in level_slaves:
                ops.equalDOF(master, slave, 1)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    for top, load in zip(tops, loads, strict=True):
        ops.load(top, 0.0, 0.0, -float(load), 0.0, 0.0, 0.0)

    def read(ops) -> dict:
        values = [e.read(ops) for e in elements]
        out = {name: np.array([v[i] for v in values])
               for i, name in enumerate(("force", "friction_force", "axial_load", "mu",
                                         "temperature", "heat_flux"))}
        out["displacement"] = np.array([(ops.nodeDisp(t, 1), ops.nodeDisp(t, 2)) for t in tops])
        return out

    return Twin(levels, directions, tuple(masters) + tuple(n for s in slaves for n in s),
                tuple(tops), loads, _label(elements[0], plan, model.n_bearings),
                read, _at_rest(model, kind))


def level_heights(building) -> np.ndarray:
    """Height of each level above the isolation level, base slab first, shape (n+1,) [m]."""
    return np.concatenate([[0.0], building.plan.floor_heights(building.n_storeys)])


def _storey_link(ops, tag: Callable[[], int], link: Link, lower: int, upper: int) -> None:
    """``link`` as a vertical ``twoNodeLink`` from node ``lower`` up to node ``upper``: its
    coefficients in the local directions 2 and 3 (shears along the link's axes) and 4
    (twist), and, where it has a storey stiffness k (the larger of its two shears), rigid
    directions 1 (axial, ``STOREY_RIGIDITY k``) and 5, 6 (bending, ``STOREY_RIGIDITY k L^2``,
    L the link's length)."""
    pairs = list(zip((2, 3, 4), link.stiffness, link.damping, strict=True))
    lateral = max(link.stiffness[:2])
    if lateral > 0.0:
        lower_z, upper_z = ops.nodeCoord(lower, 3), ops.nodeCoord(upper, 3)
        rigid = STOREY_RIGIDITY * lateral
        pairs += [(1, rigid, 0.0), (5, rigid * (upper_z - lower_z) ** 2, 0.0),
                  (6, rigid * (upper_z - lower_z) ** 2, 0.0)]
    materials = []
    for _, stiffness, damping in pairs:
        materials.append(tag())
        ops.uniaxialMaterial("Elastic", materials[-1], float(stiffness), float(damping))
    c, s = math.cos(link.angle), math.sin(link.angle)
    ops.element("twoNodeLink", tag(), lower, upper, "-mat", *materials,
                "-dir", *(d for d, _, _ in pairs), "-orient", c, s, 0.0)  # local x up, y (c, s)


def _label(first, plan: bool, n_bearings: int) -> str:
    """``singleFPBearing Coulomb``, ``flatSliderBearing 3D Coulomb + linear springs N_i/R``,
    ``6 x FPBearingPTV``, ..."""
    if first.name == "FPBearingPTV":
        return f"{n_bearings} x FPBearingPTV"
    if not plan:
        spring = " + linear spring W/R" if first.spring else ""
        return f"{first.name}{spring} {first.friction}"
    spring = " + linear springs N_i/R" if first.spring else ""
    return f"{first.name} 3D {first.friction}{spring}"


def _at_rest(model: IsolatedShearBuilding, kind: str) -> dict:
    """One bearing at each position before the first step, as ours records it: no force, mu
    at rest, the initial temperature, the gravity load."""
    zero = np.zeros((len(model.elements), 2))
    states = model.committed_states()
    return {"displacement": zero, "force": zero, "friction_force": zero,
            "mu": np.array([s.mu for s in states]),
            "temperature": np.array([s.temperature for s in states]),
            "heat_flux": np.full(len(states), 0.0 if kind == "ptv" else math.nan),
            "axial_load": np.asarray(model.gravity_loads, dtype=float)}
