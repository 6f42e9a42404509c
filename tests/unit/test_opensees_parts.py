"""Parts of the OpenSees comparison that need no OpenSees: the superstructure network, the
integrator mapping, the element choice, the bearing shapes, the NRMSE and the corner
bearings' axial loads."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from dcfpb.common.errors import InputWarning
from isolator.bearing import DCFPBearing
from isolator.factors import KumarFactors
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine
from structures.integrators import HHT, Newmark
from structures.opensees.building import opensees_integrator
from structures.opensees.comparison import (
    axial_load_summary,
    nrmse,
    outline_bearings,
    shaped_bearing,
)
from structures.opensees.elements import element_kind
from structures.opensees.model import pair_network
from structures.plan import Plan
from structures.shear_building import ModalDamping, RayleighDamping, ShearBuilding

MASSES = np.array([4.0e5, 3.5e5, 3.0e5, 2.5e5])
BEARINGS = [[-9.0, -6.0], [0.0, -6.0], [9.0, -6.0], [-9.0, 6.0], [0.0, 6.0], [9.0, 6.0]]


def _rebuilt(links, size, level_dofs):
    """The stiffness and damping matrices a network of links stands for."""
    out = [np.zeros((size, size)), np.zeros((size, size))]
    for link in links:
        (px, py), c, s = link.point, math.cos(link.angle), math.sin(link.angle)
        frame = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]) @ np.array(
            [[1.0, 0.0, -py], [0.0, 1.0, px], [0.0, 0.0, 1.0]])  # local displacement of O's
        frame = frame[:level_dofs, :level_dofs]
        low, high = link.levels
        for matrix, values in zip(out, (link.stiffness, link.damping), strict=True):
            block = frame.T @ np.diag(values) @ frame
            for i, j, sign in ((low, low, 1), (high, high, 1), (low, high, -1), (high, low, -1)):
                matrix[i * level_dofs:(i + 1) * level_dofs,
                       j * level_dofs:(j + 1) * level_dofs] += sign * block
    return out


def _assert_network_exact(building):
    matrices = (building.isolated_stiffness_matrix, building.isolated_damping_matrix)
    links = pair_network(*matrices, building.level_dofs)
    for rebuilt, matrix in zip(_rebuilt(links, matrices[0].shape[0], building.level_dofs),
                               matrices, strict=True):
        assert np.allclose(rebuilt, matrix, rtol=0.0, atol=1e-10 * np.max(np.abs(matrix)))
    return links


@pytest.mark.parametrize("damping", [RayleighDamping((0.02, 0.05), (1, 3)), ModalDamping(0.03),
                                     ModalDamping((0.02, 0.03, 0.04, 0.05))])
def test_pair_network_reproduces_the_drift_matrices(damping):
    building = ShearBuilding.from_period(MASSES, 0.6, base_mass=5e5, profile="triangular",
                                         damping=damping)
    _assert_network_exact(building)


@pytest.mark.parametrize("damping", [RayleighDamping(), ModalDamping(0.05)])
def test_pair_network_in_plan_is_exact(damping):
    """Rayleigh, and modal damping on a plan whose levels share their eccentricity and
    stiffness proportions (its level blocks are symmetric)."""
    plan = Plan(BEARINGS, eccentricity=(0.9, 0.6), dimensions=(18.0, 12.0), storey_heights=3.5)
    building = ShearBuilding.from_period(MASSES, 0.6, base_mass=5e5, damping=damping, plan=plan)
    links = _assert_network_exact(building)
    if isinstance(damping, RayleighDamping):  # storeys at O, a0 M_j at each centre of mass
        centre = tuple(building.level_centres[2])
        assert any(link.levels == (0, 2) and np.allclose(link.point, centre) for link in links)
        assert all(link.point == (0.0, 0.0) for link in links if link.levels[1] > 1
                   and link.levels[0] > 0)


def test_modal_damping_of_an_unsymmetric_plan_takes_the_symmetric_part_with_a_warning():
    """Levels of different eccentricities couple unsymmetrically (5.9e-5 of the largest
    coefficient here): the network is the symmetric part of each level block, still a matrix
    on the drifts only."""
    plan = Plan(BEARINGS, eccentricity=[(0.9, 0.6), (-1.5, 0.2), (0.3, -0.8), (2.0, 1.0)],
                dimensions=(18.0, 12.0))
    building = ShearBuilding.from_period(MASSES, 0.6, base_mass=5e5, damping=ModalDamping(0.05),
                                         plan=plan)
    damping = building.isolated_damping_matrix
    with pytest.warns(InputWarning, match=r"damping.*unsymmetrically.*symmetric part") as caught:
        links = pair_network(building.isolated_stiffness_matrix, damping, 3)
    left_out = float(str(caught[0].message).split("leaves out ")[1].split(" ")[0])
    assert 1e-9 < left_out < 1e-3
    rebuilt = _rebuilt(links, damping.shape[0], 3)[1]
    blocks = damping.reshape(5, 3, 5, 3).transpose(0, 2, 1, 3)
    symmetric = 0.5 * (blocks + blocks.transpose(0, 1, 3, 2))
    expected = symmetric.transpose(0, 2, 1, 3).reshape(damping.shape)
    assert np.allclose(rebuilt, expected, rtol=0.0, atol=1e-10 * np.max(np.abs(damping)))
    assert np.abs(rebuilt - damping).max() == pytest.approx(left_out * np.abs(damping).max(),
                                                            rel=1e-2)  # 3 digits printed
    rigid = np.tile(np.eye(3), (5, 1))  # x, y and the twist of every level together
    assert np.abs(rebuilt @ rigid).max() <= 1e-9 * np.abs(damping).max()


def test_rayleigh_network_is_storey_dashpots_plus_floor_to_base_dashpots():
    """C_fb = a0 M + a1 K on the drifts: a1 k_i across storey i, a0 m_i from floor i to the
    base slab, nothing else (so the isolation mode is undamped)."""
    damping = RayleighDamping()
    building = ShearBuilding.from_period(MASSES, 0.6, base_mass=5e5, damping=damping)
    omega = building.fixed_base_modes().circular_frequencies
    a0, a1 = damping.coefficients((omega[0], omega[1]), damping.ratios)
    links = {link.levels: link for link in pair_network(building.isolated_stiffness_matrix,
                                                         building.isolated_damping_matrix, 1)}
    k = building.storey_stiffnesses
    expected = {(0, 1): (k[0], a0 * MASSES[0] + a1 * k[0])}
    expected |= {(0, i + 1): (0.0, a0 * MASSES[i]) for i in range(1, 4)}
    expected |= {(i, i + 1): (k[i], a1 * k[i]) for i in range(1, 4)}
    assert links.keys() == expected.keys()
    for key, (stiffness, value) in expected.items():
        assert links[key].stiffness[0] == pytest.approx(stiffness, rel=1e-9, abs=1e-6)
        assert links[key].damping[0] == pytest.approx(value, rel=1e-9)


def test_pair_network_refuses_a_matrix_acting_on_rigid_motion():
    with pytest.raises(ValueError, match="zero block-row sums"):
        pair_network(np.diag([1.0, 2.0]), np.zeros((2, 2)), 1)


def test_integrator_mapping():
    assert opensees_integrator("newmark") == ("Newmark", 0.5, 0.25)
    assert opensees_integrator(Newmark(0.6, 0.3025)) == ("Newmark", 0.6, 0.3025)
    name, alpha_os = opensees_integrator(HHT(-0.1))
    assert name == "HHT" and alpha_os == pytest.approx(0.9)
    hht = HHT(-0.1)  # OpenSees HHT.cpp: gamma = 3/2 - alpha, beta = (2 - alpha)^2 / 4
    assert 1.5 - alpha_os == pytest.approx(hht.gamma)
    assert (2.0 - alpha_os) ** 2 / 4.0 == pytest.approx(hht.beta)
    with pytest.raises(TypeError, match="integrator"):
        opensees_integrator(object())


def test_element_choice_and_shapes():
    constant = DCFPBearing(4.5, 0.3, 4e6, ConstantFriction())
    ptv = replace(constant, friction=PTVFriction(0.075, heating=MonitorLine()))
    assert element_kind(constant) == "coulomb"
    velocity = shaped_bearing(ptv, "velocity")
    assert element_kind(velocity) == "velocity" and velocity.friction.heating is None
    shaped = shaped_bearing(ptv, "ptv")
    assert element_kind(shaped) == "ptv" and shaped.restoring == "spherical"
    assert shaped.friction.factors == KumarFactors() and shaped.friction.surfaces == 1
    assert shaped.friction.heating == CentrePoint(np.sqrt(np.pi) / 2.0)
    assert shaped_bearing(constant, "constant") is constant
    with pytest.raises(ValueError, match="PTVFriction"):
        shaped_bearing(constant, "ptv")
    with pytest.raises(ValueError, match="ConstantFriction"):
        shaped_bearing(ptv, "constant")


def test_nrmse_definition():
    reference = np.array([0.0, 2.0, -4.0, 1.0])
    assert nrmse(reference, reference) == 0.0
    assert nrmse(reference, reference + 0.4) == pytest.approx(0.1)  # RMS 0.4 / peak 4
    with pytest.raises(ValueError, match="one length"):
        nrmse(reference, reference[:3])


def test_fpbearingptv_refuses_hht():
    from groundmotions.records import GroundMotion
    from structures.opensees.building import run_opensees

    building = ShearBuilding.from_period(MASSES, 0.6, base_mass=5e5)
    bearing = shaped_bearing(DCFPBearing(4.5, 0.3, None, PTVFriction(0.075)), "ptv")
    motion = GroundMotion(np.zeros(5), 0.01, "zeros")
    with pytest.raises(ValueError, match="Newmark for FPBearingPTV"):
        run_opensees(building, bearing, motion, HHT(-0.05))


def _axial_run(loads: np.ndarray, gravity: np.ndarray):
    import xarray as xr

    xy = np.array(BEARINGS)
    return xr.Dataset({"axial_load": (("time", "bearing"), loads)},
                      coords={"bearing_x": ("bearing", xy[:, 0]),
                              "bearing_y": ("bearing", xy[:, 1])},
                      attrs={"gravity_shares": gravity.tolist()})


def test_corner_bearings_and_their_axial_load_gaps():
    """The corners of a 2 x 3 grid; gaps over ours's largest change of each corner's load,
    or over the gravity share where it does not change."""
    gravity = np.array([3.0, 4.0, 5.0, 3.5, 4.5, 5.5]) * 1e6
    swing = np.array([0.0, 1.0, -1.0, 0.5])[:, None] * np.array([-1, 0, 1, -1, 0, 1]) * 1e6
    ours = _axial_run(gravity + swing, gravity)
    assert sorted(outline_bearings(ours)) == [0, 2, 3, 5]
    other = gravity + 1.02 * swing
    other[:, 3] += 0.1e6  # the largest gap: bearing 3, max and min alike
    summary, difference = axial_load_summary(ours, _axial_run(other, gravity))
    at = summary["bearings"].index(3)
    assert summary["gravity_share"][at] == gravity[3]
    assert summary["ours"]["max"][at] == gravity[3] + 1e6
    assert summary["opensees"]["min"][at] == pytest.approx(gravity[3] - 1.02e6 + 0.1e6)
    assert difference["max_axial_load"] == pytest.approx(0.12)
    assert difference["min_axial_load"] == pytest.approx(0.08)
    rms = np.sqrt(np.mean((0.02 * swing[:, 3] + 0.1e6) ** 2)) / 1e6
    assert difference["nrmse_axial_load"] == pytest.approx(rms)
    still = _axial_run(np.tile(gravity, (4, 1)), gravity)
    _, difference = axial_load_summary(still, _axial_run(np.tile(1.01 * gravity, (4, 1)),
                                                         gravity))
    assert difference["max_axial_load"] == pytest.approx(0.01)
