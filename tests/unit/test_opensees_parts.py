"""Parts of the OpenSees comparison that need no OpenSees: the damping network, the
integrator mapping, the element choice, the bearing shapes and the NRMSE."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from isolator.bearing import DCFPBearing
from isolator.factors import KumarFactors
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine
from structures.integrators import HHT, Newmark
from structures.opensees.building import opensees_integrator
from structures.opensees.comparison import nrmse, shaped_bearing
from structures.opensees.model import element_kind, pair_coefficients
from structures.shear_building import ModalDamping, RayleighDamping, ShearBuilding

MASSES = np.array([4.0e5, 3.5e5, 3.0e5, 2.5e5])


def _laplacian(pairs, size):
    matrix = np.zeros((size, size))
    for i, j, c in pairs:
        matrix[[i, j], [i, j]] += c
        matrix[i, j] -= c
        matrix[j, i] -= c
    return matrix


@pytest.mark.parametrize("damping", [RayleighDamping((0.02, 0.05), (1, 3)), ModalDamping(0.03),
                                     ModalDamping((0.02, 0.03, 0.04, 0.05))])
def test_pair_network_reproduces_the_drift_matrices(damping):
    building = ShearBuilding.from_period(MASSES, 0.6, base_mass=5e5, profile="triangular",
                                         damping=damping)
    for matrix in (building.isolated_stiffness_matrix, building.isolated_damping_matrix):
        rebuilt = _laplacian(pair_coefficients(matrix), matrix.shape[0])
        assert np.allclose(rebuilt, matrix, rtol=0.0, atol=1e-10 * np.max(np.abs(matrix)))


def test_rayleigh_network_is_storey_dashpots_plus_floor_to_base_dashpots():
    """C_fb = a0 M + a1 K on the drifts: a1 k_i across storey i, a0 m_i from floor i to the
    base slab, nothing else (so the isolation mode is undamped)."""
    damping = RayleighDamping()
    building = ShearBuilding.from_period(MASSES, 0.6, base_mass=5e5, damping=damping)
    omega = building.fixed_base_modes().circular_frequencies
    a0, a1 = damping.coefficients((omega[0], omega[1]), damping.ratios)
    pairs = {(i, j): c for i, j, c in pair_coefficients(building.isolated_damping_matrix)}
    k = building.storey_stiffnesses
    expected = {(0, 1): a0 * MASSES[0] + a1 * k[0]}
    expected |= {(0, i + 1): a0 * MASSES[i] for i in range(1, 4)}
    expected |= {(i, i + 1): a1 * k[i] for i in range(1, 4)}
    assert pairs.keys() == expected.keys()
    for key, value in expected.items():
        assert pairs[key] == pytest.approx(value, rel=1e-9)


def test_pair_coefficients_refuse_a_matrix_acting_on_rigid_motion():
    with pytest.raises(ValueError, match="zero row sums"):
        pair_coefficients(np.diag([1.0, 2.0]))


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
