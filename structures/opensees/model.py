"""The isolated shear building, in one direction or in plan, built in openseespy
(``-ndm 3 -ndf 6``) from our :class:`~structures.isolated_building.IsolatedShearBuilding`.

Every mass [kg], inertia [kg m^2], stiffness, damping and gravity load [N] is read from our
model: a master node per level at its centre of mass, a network of two-node elements on the
drifts (:func:`pair_network`), and at each bearing position a fixed node under the elements of
:func:`~structures.opensees.elements.add_bearing`. Flat layout (without overturning): every node
at Z = 0, levels as ``rigidDiaphragm`` (``equalDOF`` in one direction), ``zeroLength`` links.
Tall layout (``model.overturning``): levels at their heights (:func:`level_heights`) as rigid
bodies, vertical ``twoNodeLink`` storeys, the base slab on the bearings' axial springs. Details:
docs/opensees_comparison.md. openseespy keeps one global model: the caller wipes it.
"""

from __future__ import annotations

import itertools
import math
import warnings
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from dcfpb.common.errors import InputError, InputWarning
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
    """One two-node element of the superstructure network: the ``levels`` (k < l) it joins,
    its ``point`` (x, y) in the plan [m], its local x at ``angle`` from global X [rad], and its
    ``stiffness`` and ``damping`` in the local directions (1,) or (1, 2, 6) [N/m, N m/rad; N s/m,
    N m s/rad]."""

    levels: tuple[int, int]
    point: tuple[float, float]
    angle: float
    stiffness: tuple[float, ...]
    damping: tuple[float, ...]


class Twin(NamedTuple):
    """What the driver needs of a built model: ``levels``, the node at O of each level, base slab
    first (our degrees of freedom), and ``dofs``, their recorded DOFs, ``(1,)`` or ``(1, 2, 6)``;
    ``nodes``, every node that moves with a level; ``tops``, each bearing position's top node, and
    ``loads``, its gravity load, all its bearings [N]; ``element``, what the bearings are in
    OpenSees; ``read(ops) -> dict``, one bearing at each position (the fields of
    :data:`structures.results.BEARING_RECORD`, arrays (n_b, 2) and (n_b,)); ``initial``, the same
    at rest."""

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
    """The two-node elements whose stiffness and damping sum to the given level matrices: one
    :class:`Link` per level pair with non-zero blocks (two where stiffness and damping do not share
    a point and axes). ``stiffness`` and ``damping`` [N/m, N s/m, ...] are symmetric, on the drifts
    only, shape ((n+1) L, (n+1) L), L = ``level_dofs``: 1 (x) or 3 (x, y, theta at O).

    Raises ValueError if a matrix is not symmetric or acts on a rigid motion. Warns
    (``InputWarning``) if it couples two levels unsymmetrically, which no two-node network
    reproduces: the network takes the symmetric part of each level block.
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
    """Build ``model`` (our building, SI units; with ``model.overturning`` the tall layout) on
    its bearings in the (wiped) openseespy domain ``ops`` and return its :class:`Twin`;
    ``pendulum`` as :func:`~structures.opensees.elements.add_bearing` (not used for FPBearingPTV).
    Raises ValueError for a bearing or damping the model cannot represent."""
    owner = "build_model"
    pendulum = check_choice(pendulum, "pendulum", owner, PENDULUMS)
    bearing, building = model.bearing, model.building
    kind = element_kind(bearing)
    if kind == "ptv" and fpbearingptv_equivalent(bearing) != bearing:
        raise InputError(f"The bearing of {owner} must be shaped as FPBearingPTV models it "
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
        elif not plan:  # X only (a diaphragm would tie them to fixed DOFs)
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
    """``link`` as a vertical ``twoNodeLink`` from ``lower`` up to ``upper``: its coefficients
    in local directions 2, 3 (shears) and 4 (twist); with a storey stiffness k, rigid in 1
    (axial, ``STOREY_RIGIDITY k``) and 5, 6 (bending, ``STOREY_RIGIDITY k L^2``, L its length)."""
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
    """The twin's element label: ``singleFPBearing Coulomb``, ``6 x FPBearingPTV``, ..."""
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
