"""The plan's statics (gravity shares over a rigid base) and the integrator's vector ground
acceleration."""

from __future__ import annotations

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY
from structures.integrators import integrate
from structures.model import LinearModel
from structures.plan import Plan, axial_distribution, gravity_shares
from structures.shear_building import ModalDamping, ShearBuilding

IRREGULAR = np.array([[-7.0, -4.0], [5.0, -6.0], [8.0, 3.0], [-2.0, 6.0], [1.0, 0.5],
                      [-6.0, 2.0]])


def test_axial_distribution_meets_the_three_equilibrium_equations():
    g = axial_distribution(IRREGULAR)
    a = np.vstack([np.ones(len(IRREGULAR)), IRREGULAR.T])
    assert np.allclose(a @ g, np.eye(3), atol=1e-12)
    # linear in (x, y): N_i = a + b x_i + c y_i for any resultant
    loads = g @ np.array([1e6, 3e5, -2e5])
    coefficients, *_ = np.linalg.lstsq(a.T, loads, rcond=None)
    assert np.allclose(a.T @ coefficients, loads, rtol=1e-12)


def test_gravity_shares_sum_to_the_weight_and_balance_its_moments():
    masses = np.array([5e5, 4e5, 4e5, 3e5])
    centres = np.array([[0.0, 0.0], [1.0, -0.5], [1.5, 0.2], [-0.3, 0.9]])
    shares = gravity_shares(IRREGULAR, masses, centres)
    weight = STANDARD_GRAVITY * masses.sum()
    assert shares.sum() == pytest.approx(weight, rel=1e-13)
    assert shares @ IRREGULAR == pytest.approx(STANDARD_GRAVITY * masses @ centres, rel=1e-12)
    assert np.all(shares > 0.0)


def test_centre_of_mass_at_the_bearings_centroid_gives_equal_shares():
    centroid = IRREGULAR.mean(axis=0)
    shares = gravity_shares(IRREGULAR, [2e5, 3e5], [centroid, centroid])
    assert np.allclose(shares, STANDARD_GRAVITY * 5e5 / len(IRREGULAR), rtol=1e-12)


def test_building_in_plan_shares_follow_the_eccentricity():
    square = [[-5.0, -5.0], [5.0, -5.0], [5.0, 5.0], [-5.0, 5.0]]

    def building(plan: Plan) -> ShearBuilding:
        return ShearBuilding.from_period([4e5, 4e5], 0.4, base_mass=5e5, plan=plan)

    centred = building(Plan(square, dimensions=(10.0, 10.0)))
    assert np.all(centred.gravity_shares == centred.gravity_shares[0])
    shifted = building(Plan(square, eccentricity=(1.0, 0.0), dimensions=(10.0, 10.0)))
    shares = shifted.gravity_shares
    assert shares[1] > shares[0] and shares[1] == pytest.approx(shares[2])
    floors = 8e5 * STANDARD_GRAVITY
    assert shares @ np.array(square)[:, 0] == pytest.approx(floors * 1.0, rel=1e-12)


def test_inertia_and_torsional_stiffness_defaults_from_the_rectangle():
    plan = Plan([[-5.0, -4.0], [5.0, -4.0], [0.0, 4.0]], dimensions=(12.0, 8.0),
                storey_stiffnesses_y=[3e8])
    floors, base = plan.inertias(np.array([4e5]), 5e5)
    assert floors[0] == pytest.approx(4e5 * (144.0 + 64.0) / 12.0)
    assert base == pytest.approx(5e5 * (144.0 + 64.0) / 12.0)
    k = plan.stiffnesses(np.array([2e8]))
    assert k[0, 2] == pytest.approx((2e8 * 64.0 + 3e8 * 144.0) / 12.0)


def test_mass_matrix_is_the_kinetic_energy_of_the_eccentric_floor():
    plan = Plan([[-5.0, -4.0], [5.0, -4.0], [0.0, 4.0]], eccentricity=(1.5, -0.8),
                floor_inertias=[7e6], base_inertia=9e6, torsional_stiffnesses=[1e10])
    mass = ShearBuilding([4e5], [2e8], 5e5, damping=ModalDamping(0.02),
                         plan=plan).isolated_mass_matrix
    rng = np.random.default_rng(3)
    for _ in range(5):
        q = rng.normal(size=6)
        ux, uy, th = q[3:]
        kinetic = 0.5 * 4e5 * ((ux + th * 0.8) ** 2 + (uy + th * 1.5) ** 2) + 0.5 * 7e6 * th**2
        kinetic += 0.5 * 5e5 * (q[0] ** 2 + q[1] ** 2) + 0.5 * 9e6 * q[2] ** 2
        assert 0.5 * q @ mass @ q == pytest.approx(kinetic, rel=1e-12)


def _two_oscillators(influence):
    mass, stiffness = np.diag([2.0, 3.0]), np.diag([80.0, 30.0])
    return LinearModel(mass, 0.02 * stiffness, stiffness, influence)


def test_influence_matrix_of_one_column_is_the_influence_vector_bit_for_bit():
    record = np.sin(np.linspace(0.0, 20.0, 400)) * np.linspace(1.0, 0.0, 400)
    vector = integrate(_two_oscillators([1.0, 0.5]), record, 0.01, "hht")
    matrix = integrate(_two_oscillators([[1.0], [0.5]]), record[:, None], 0.01, "hht")
    assert np.array_equal(vector.displacement, matrix.displacement)
    assert np.array_equal(vector.absolute_acceleration, matrix.absolute_acceleration)


def test_two_components_drive_their_own_degrees_of_freedom():
    t = np.linspace(0.0, 4.0, 401)
    first, second = np.sin(3.0 * t), np.cos(5.0 * t) * t
    both = integrate(_two_oscillators(np.eye(2)), np.column_stack([first, second]), 0.01)
    alone_x = integrate(_two_oscillators([1.0, 0.0]), first, 0.01)
    alone_y = integrate(_two_oscillators([0.0, 1.0]), second, 0.01)
    assert np.allclose(both.displacement[:, 0], alone_x.displacement[:, 0], rtol=0,
                       atol=1e-12 * np.abs(alone_x.displacement).max())
    assert np.allclose(both.displacement[:, 1], alone_y.displacement[:, 1], rtol=0,
                       atol=1e-12 * np.abs(alone_y.displacement).max())
    assert np.allclose(both.absolute_acceleration - both.acceleration,
                       np.column_stack([first, second]))
