"""The shear building against closed-form modal answers and the superstructure-damping rule."""

from __future__ import annotations

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY
from structures.shear_building import (
    ModalDamping,
    RayleighDamping,
    ShearBuilding,
    shear_stiffness_matrix,
)

MASSES = [3.2e5, 3.0e5, 2.6e5, 2.0e5]
STIFFNESSES = [5.0e8, 4.2e8, 3.5e8, 2.4e8]


def modal_ratios(building: ShearBuilding) -> np.ndarray:
    """Damping ratios phi_i^T C phi_i / (2 omega_i) of the fixed-base modes [-]."""
    modes = building.fixed_base_modes()
    generalised = modes.shapes.T @ building.fixed_base_damping_matrix @ modes.shapes
    return np.diag(generalised) / (2.0 * modes.circular_frequencies)


def test_two_storey_periods_and_shapes_match_the_closed_form():
    m1, m2, k1, k2 = 2.0e5, 1.5e5, 3.0e8, 2.0e8
    building = ShearBuilding([m1, m2], [k1, k2], 2.5e5, ModalDamping(0.05))
    # m1 m2 w^4 - (m1 k2 + m2 (k1 + k2)) w^2 + k1 k2 = 0
    b = m1 * k2 + m2 * (k1 + k2)
    root = np.sqrt(b**2 - 4.0 * m1 * m2 * k1 * k2)
    omega = np.sqrt([(b - root) / (2.0 * m1 * m2), (b + root) / (2.0 * m1 * m2)])
    periods, shapes = building.fixed_base_modes()
    np.testing.assert_allclose(periods, 2.0 * np.pi / omega, rtol=1e-12)

    # floor-2 / floor-1 amplitude from the first row: (k1 + k2 - m1 w^2) phi1 = k2 phi2
    np.testing.assert_allclose(shapes[1] / shapes[0], (k1 + k2 - m1 * omega**2) / k2, rtol=1e-10)
    mass = building.fixed_base_mass_matrix
    np.testing.assert_allclose(shapes.T @ mass @ shapes, np.eye(2), atol=1e-12)
    assert np.all(shapes[-1] > 0.0)


def test_stiffness_matrix_is_the_storey_chain():
    k = np.array([5.0, 3.0, 2.0])
    expected = [[8.0, -3.0, 0.0], [-3.0, 5.0, -2.0], [0.0, -2.0, 2.0]]
    np.testing.assert_array_equal(shear_stiffness_matrix(k), expected)


@pytest.mark.parametrize("profile", ["uniform", "triangular", "storey_shear", [4.0, 3.0, 3.0, 1.0]])
def test_from_period_hits_the_target_and_keeps_the_profile(profile):
    building = ShearBuilding.from_period(MASSES, 0.65, base_mass=3.5e5, profile=profile)
    assert building.fixed_base_modes().periods[0] == pytest.approx(0.65, rel=1e-12)
    expected = {
        "uniform": np.ones(4),
        "triangular": np.array([4.0, 3.0, 2.0, 1.0]),
        "storey_shear": np.cumsum(MASSES[::-1])[::-1],
    }.get(profile if isinstance(profile, str) else "", np.asarray(profile))
    ratio = building.storey_stiffnesses / expected
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-12)


@pytest.mark.parametrize("damping", [RayleighDamping((0.02, 0.05), (1, 3)), ModalDamping(0.03)])
def test_superstructure_damping_leaves_rigid_body_motion_undamped(damping):
    building = ShearBuilding(MASSES, STIFFNESSES, 3.5e5, damping)
    ones = np.ones(building.n_storeys + 1)
    c, k = building.isolated_damping_matrix, building.isolated_stiffness_matrix
    assert np.max(np.abs(c @ ones)) < 1e-12 * np.max(np.abs(c))
    assert np.max(np.abs(k @ ones)) < 1e-12 * np.max(np.abs(k))
    # on drifts: the superstructure block equals the fixed-base matrix, the base row balances it
    np.testing.assert_allclose(c[1:, 1:], building.fixed_base_damping_matrix, rtol=1e-14)
    assert c[0, 0] == pytest.approx(building.fixed_base_damping_matrix.sum(), rel=1e-12)


def test_rayleigh_ratios_are_reproduced_at_the_chosen_modes():
    building = ShearBuilding(MASSES, STIFFNESSES, 3.5e5, RayleighDamping((0.05, 0.05), (1, 3)))
    ratios = modal_ratios(building)
    assert ratios[[0, 2]] == pytest.approx([0.05, 0.05], rel=1e-10)
    assert ratios[1] < 0.05 < ratios[3]  # below between the anchor modes, above beyond them
    modes = building.fixed_base_modes()
    generalised = modes.shapes.T @ building.fixed_base_damping_matrix @ modes.shapes
    assert np.max(np.abs(generalised - np.diag(np.diag(generalised)))) < 1e-10  # classical


def test_modal_damping_gives_each_mode_its_ratio():
    ratios = (0.02, 0.03, 0.04, 0.05)
    building = ShearBuilding(MASSES, STIFFNESSES, 3.5e5, ModalDamping(ratios))
    np.testing.assert_allclose(modal_ratios(building), ratios, rtol=1e-10)


def test_isolated_modes_tend_to_the_rigid_and_fixed_base_limits():
    building = ShearBuilding(MASSES, STIFFNESSES, 3.5e5, ModalDamping(0.02))
    rigid = ShearBuilding(MASSES, np.asarray(STIFFNESSES) * 1e6, 3.5e5, ModalDamping(0.02))
    k_isolator = 2.0e7
    expected = 2.0 * np.pi * np.sqrt(building.total_mass / k_isolator)
    assert rigid.isolated_modes(k_isolator).periods[0] == pytest.approx(expected, rel=1e-6)
    assert building.isolated_modes(k_isolator).periods[0] > expected  # flexible: longer
    stiff = building.isolated_modes(1e8 * STIFFNESSES[0]).periods
    np.testing.assert_allclose(stiff[:-1], building.fixed_base_modes().periods, rtol=1e-6)
    modes = building.isolated_modes(k_isolator)
    mass = building.isolated_mass_matrix
    np.testing.assert_allclose(modes.shapes.T @ mass @ modes.shapes, np.eye(5), atol=1e-12)


def test_masses_and_weight():
    building = ShearBuilding(MASSES, STIFFNESSES, 3.5e5)
    assert building.total_mass == pytest.approx(3.5e5 + sum(MASSES))
    assert building.weight == pytest.approx(building.total_mass * STANDARD_GRAVITY)
    np.testing.assert_array_equal(np.diag(building.isolated_mass_matrix), [3.5e5, *MASSES])
    assert building.damping == RayleighDamping((0.02, 0.02), (1, 2))


@pytest.mark.parametrize(
    ("make", "error", "match"),
    [
        (
            lambda: ShearBuilding([1.0, -2.0], [1.0, 1.0], 1.0),
            ValueError,
            "The 'floor_masses' parameter of ShearBuilding must hold finite floats in \\(0, inf\\)",
        ),
        (lambda: ShearBuilding([1.0, 2.0], [1.0], 1.0), ValueError, "'storey_stiffnesses'"),
        (lambda: ShearBuilding([1.0], [1.0], 0.0), ValueError, "'base_mass' parameter"),
        (lambda: ShearBuilding([1.0], [1.0], 1.0), ValueError, "use ModalDamping"),
        (lambda: ShearBuilding([1.0], [1.0], 1.0, 0.05), TypeError, "'damping' parameter"),
        (
            lambda: ShearBuilding([1.0, 1.0], [1.0, 1.0], 1.0, ModalDamping((0.02,))),
            ValueError,
            "2 per-mode ratios",
        ),
        (lambda: RayleighDamping((0.02, 1.2)), ValueError, "'ratios' parameter of RayleighDamping"),
        (lambda: RayleighDamping(modes=(2, 2)), ValueError, "two distinct mode numbers"),
        (lambda: ModalDamping(-0.1), ValueError, "'ratio' parameter of ModalDamping"),
        (
            lambda: ShearBuilding.from_period([1.0], 0.5, base_mass=1.0, profile="cubic"),
            ValueError,
            "The 'profile' parameter of ShearBuilding.from_period must be one of",
        ),
        (
            lambda: ShearBuilding.from_period([1.0], -0.5, base_mass=1.0),
            ValueError,
            "'fixed_base_period'",
        ),
    ],
)
def test_bad_parameters_raise_with_the_house_template(make, error, match):
    with pytest.raises(error, match=match):
        make()
