"""The building in plan against the building in one direction, closed forms and its energy balance.

- A symmetric plan with equal gravity shares under one horizontal component (along x, along y,
  or one record at an angle phi) is the isolated building in one direction with the same number of
  bearings, rotated: floor displacements to 1e-9 and no rotation (constant and precise PTV
  friction).
- An eccentric centre of mass turns the building; the corner bearings on the far side move
  more than the base at the centre of stiffness.
- Modal periods: a one-storey eccentric building on a fixed base against the closed form of
  the coupled y-theta system; a rigid building on linear pendulum springs (stiffness N_i / R)
  against the closed form (the pendulums' centre of stiffness is the centre of mass).
- Overturning: the axial loads balance the moments of the floors' inertia forces taken from
  the accelerations (an independent route) and the vertical motion scales the weight.
- The energy balance closes to 1e-6 with Newmark on an eccentric building under a synthetic
  pair with a vertical, and under a recorded pair of ../shared (skipped without it).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from pathlib import Path

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.pairs import GroundMotionPair, read_pair
from groundmotions.records import GroundMotion
from groundmotions.synthetic import kanai_tajimi, synthetic_pair
from isolator.bearing import DCFPBearing
from isolator.experiments import friction_model
from structures.analysis import run
from structures.plan import Plan
from structures.shear_building import ModalDamping, ShearBuilding

SQUARE = [[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0]]
SHARED_PAIRS = Path(__file__).resolve().parents[3] / "shared" / "groundmotions" / "pairs"
DT = 0.01


def _relative(got: np.ndarray, expected: np.ndarray) -> float:
    return float(np.max(np.abs(got - expected)) / np.max(np.abs(expected)))


@functools.cache
def _building() -> ShearBuilding:
    return ShearBuilding.from_period([4e5, 4e5, 4e5], 0.5, base_mass=5e5)


def _bearing(model: str) -> DCFPBearing:
    load = _building().weight / 4
    friction = friction_model(model, slider_diameter=0.3, design_pressure=load / (
        np.pi * 0.15**2), design_velocity=0.4)
    return DCFPBearing(2.5, 0.3, friction=friction)


@functools.cache
def _record() -> GroundMotion:
    return kanai_tajimi(4.0, DT, seed=7, target_pga=4.0, ground_frequency=15.0,
                        ground_damping=0.6, name="kt")


def _pair_along(angle_deg: float) -> GroundMotionPair:
    record = _record()
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    x = GroundMotion(c * record.acceleration, DT, "x")
    y = GroundMotion(s * record.acceleration, DT, "y")
    return GroundMotionPair(x, y, name=f"kt at {angle_deg} deg")


@functools.cache
def _one_direction(model: str):
    return run(_building(), _bearing(model), _record(), n_bearings=4, dt=DT,
               engine="reference")


@pytest.mark.parametrize(("model", "angle"), [("constant", 0.0), ("constant", 90.0),
                                              ("constant", 30.0), ("precise", 90.0),
                                              ("precise", 30.0)])
def test_symmetric_plan_is_the_building_in_one_direction_rotated(model, angle):
    in_plan = dataclasses.replace(_building(), plan=Plan(SQUARE, dimensions=(12.0, 10.0)))
    result = run(in_plan, _bearing(model), _pair_along(angle), dt=DT,
                         overturning=False)
    one_direction = _one_direction(model)
    assert result.attrs["success"] and one_direction.attrs["success"]
    direction = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    expected = one_direction["displacement"].values * direction
    assert _relative(result["displacement"].values, expected) < 1e-9
    rotation = result["rotation"].values
    if angle in (0.0, 90.0):  # one component: the other and the rotation stay exactly zero
        assert np.all(rotation == 0.0)
    else:  # rounding only: below 1e-12 of the displacement at the farthest bearing
        assert np.abs(rotation).max() * 8.0 < 1e-12 * np.abs(expected).max()
    bearing = result["bearing_displacement"].values
    assert _relative(bearing, one_direction["bearing_displacement"].values * direction) < 1e-9
    if model == "precise":  # the plates heat alike: every bearing is the one in one direction
        rise = one_direction["temperature"].values - one_direction["temperature"].values[0]
        got = result["temperature"].values - result["temperature"].values[0]
        assert _relative(got, rise) < 1e-9
        assert rise.max() > 1.0


def test_overturning_with_constant_friction_leaves_the_symmetric_response():
    """Overturning shifts load between the bearings but not the total: with a friction that
    does not depend on the load (Eq. 8) the sums, and so the response, are unchanged."""
    plan = Plan(SQUARE, dimensions=(12.0, 10.0), storey_heights=3.5)
    result = run(dataclasses.replace(_building(), plan=plan), _bearing("constant"),
                         _pair_along(0.0), dt=DT)
    load = result["axial_load"].values
    assert np.ptp(load[:, 1] - load[:, 0]) > 0.05 * load.mean()  # the loads do move
    expected = _one_direction("constant")["displacement"].values * [1.0, 0.0]
    assert _relative(result["displacement"].values, expected) < 1e-9


@functools.cache
def _eccentric(friction: str = "constant", vertical: bool = True):
    plan = Plan(SQUARE, eccentricity=(1.2, 0.8), dimensions=(12.0, 10.0), storey_heights=3.5)
    pair = synthetic_pair("kanai-tajimi", 11, duration=4.0, dt=DT, target_pga=4.0,
                          vertical_ratio=0.6 if vertical else None, ground_frequency=15.0,
                          ground_damping=0.6)
    return run(dataclasses.replace(_building(), plan=plan), _bearing(friction), pair, dt=DT)


def test_eccentric_mass_turns_the_building_and_loads_the_far_corners():
    result = _eccentric()
    assert result.attrs["success"]
    rotation = np.abs(result["rotation"].values).max()
    assert rotation > 1e-4  # [rad]: 1 mm at 10 m
    centre = np.hypot(*np.moveaxis(result["displacement"].values[:, 0, :], -1, 0)).max()
    corners = np.hypot(*np.moveaxis(result["bearing_displacement"].values, -1, 0)).max(axis=0)
    assert corners.max() > centre * (1.0 + 1e-3)
    # rigid base: each bearing is the base translation plus the rotation times its arm
    u = result["displacement"].values[:, 0, :]
    theta = result["rotation"].values[:, 0]
    x, y = result["bearing_x"].values, result["bearing_y"].values
    expected = np.stack([u[:, None, 0] - theta[:, None] * y,
                         u[:, None, 1] + theta[:, None] * x], axis=-1)
    assert _relative(result["bearing_displacement"].values, expected) < 1e-12


def test_energy_balance_closes_on_an_eccentric_building_under_a_synthetic_pair():
    for result in (_eccentric(), _eccentric("simplified", vertical=False)):
        assert result.attrs["success"]
        assert result.attrs["energy_balance_error"] < 1e-6
        friction = result["energy_friction"].values[-1]
        assert friction > 0.5 * result["energy_input"].values[-1]  # the bearings dissipate


def test_energy_balance_closes_under_a_recorded_pair():
    if not SHARED_PAIRS.is_dir():
        pytest.skip(f"the recorded pairs of ../shared are absent ({SHARED_PAIRS})")
    pair = read_pair(SHARED_PAIRS / "TAP094-N.AT2", SHARED_PAIRS / "TAP094-E.AT2",
                     truncate=True)
    start = int(np.argmax(np.abs(pair.x.acceleration)) - 2.0 / pair.dt)
    window = slice(max(start, 0), max(start, 0) + int(4.0 / pair.dt) + 1)
    cut = GroundMotionPair(*(GroundMotion(m.acceleration[window], m.dt, m.name)
                             for m in (pair.x, pair.y)), name=pair.name)
    plan = Plan(SQUARE, eccentricity=(-1.0, 1.5), dimensions=(12.0, 10.0), storey_heights=3.5)
    result = run(dataclasses.replace(_building(), plan=plan), _bearing("constant"),
                         cut.scaled(2.0))
    assert result.attrs["success"]
    assert np.abs(result["rotation"].values).max() > 0.0
    assert result.attrs["energy_balance_error"] < 1e-6


def test_axial_loads_balance_gravity_vertical_motion_and_overturning():
    """sum N = W (1 + a_z/g), sum N x = W x_G (1 + a_z/g) + sum_j H_j F_x,j with the floors'
    inertia forces F_j = -(M a_abs)_j from the accelerations (while no bearing uplifts)."""
    result = _eccentric()
    in_plan = dataclasses.replace(_building(), plan=Plan(SQUARE, eccentricity=(1.2, 0.8),
                                                dimensions=(12.0, 10.0), storey_heights=3.5))
    load = result["axial_load"].values
    assert load.min() > 0.0
    scale = 1.0 + result["vertical_ground_acceleration"].values / STANDARD_GRAVITY
    weight = in_plan.weight
    assert np.allclose(load.sum(axis=1), weight * scale, rtol=1e-12)
    masses, centres = in_plan.level_masses, in_plan.level_centres
    accel = result["absolute_acceleration"].values  # at the centre of stiffness
    alpha = result["angular_acceleration"].values
    # acceleration of each floor's centre of mass: a_O + alpha x e (small rotations)
    a_cm_x = accel[..., 0] - alpha * centres[:, 1]
    a_cm_y = accel[..., 1] + alpha * centres[:, 0]
    heights = 3.5 * np.arange(4)  # the base slab has no lever arm
    moment_x = -(masses * a_cm_x * heights).sum(axis=1)
    moment_y = -(masses * a_cm_y * heights).sum(axis=1)
    x, y = result["bearing_x"].values, result["bearing_y"].values
    gravity_x = STANDARD_GRAVITY * masses @ centres[:, 0]
    gravity_y = STANDARD_GRAVITY * masses @ centres[:, 1]
    reference = weight * 6.0
    assert np.max(np.abs(load @ x - gravity_x * scale - moment_x)) < 1e-6 * reference
    assert np.max(np.abs(load @ y - gravity_y * scale - moment_y)) < 1e-6 * reference
    assert np.ptp(moment_x) > 0.05 * reference  # the overturning is not negligible


def test_fixed_base_one_storey_eccentric_periods_closed_form():
    m, k_x, k_y, k_t = 4e5, 2e8, 3e8, 4e9
    e, j = 1.5, 4e5 * (12.0**2 + 10.0**2) / 12.0
    plan = Plan(SQUARE, eccentricity=(e, 0.0), floor_inertias=[j], base_inertia=1e6,
                storey_stiffnesses_y=[k_y], torsional_stiffnesses=[k_t])
    in_plan = ShearBuilding([m], [k_x], 5e5, ModalDamping(0.02), plan)
    periods = np.sort(in_plan.fixed_base_modes().periods)
    # x uncoupled; y and theta: m J lam^2 - (k_y (J + m e^2) + k_t m) lam + k_y k_t = 0
    b = k_y * (j + m * e * e) + k_t * m
    root = math.sqrt(b * b - 4 * m * j * k_y * k_t)
    lams = np.array([k_x / m, (b - root) / (2 * m * j), (b + root) / (2 * m * j)])
    expected = np.sort(2 * np.pi / np.sqrt(lams))
    assert np.allclose(periods, expected, rtol=1e-12)


def test_pendulums_centre_the_stiffness_on_the_mass_closed_form():
    """A rigid building on linear pendulums k_i = N_i / R: translation at 2 pi sqrt(R/g)
    along x and y, and torsion about the centre of mass at sqrt(sum k_i r_i^2 / J_G)."""
    radius = 2.5
    plan = Plan([[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], [0.0, 0.0]],
                eccentricity=(1.0, -0.7), dimensions=(12.0, 10.0))
    rigid = ShearBuilding([4e5], [1e14], 5e5, ModalDamping(0.02))
    in_plan = dataclasses.replace(rigid, plan=plan)
    shares = in_plan.gravity_shares
    periods = np.sort(in_plan.isolated_modes(shares / radius).periods)[::-1][:3]
    masses, centres = in_plan.level_masses, in_plan.level_centres
    total = masses.sum()
    centre = masses @ centres / total
    inertia = in_plan.level_inertias.sum() + masses @ ((centres - centre) ** 2).sum(axis=1)
    arms = ((plan.bearing_coordinates - centre) ** 2).sum(axis=1)
    torsion = 2 * np.pi / math.sqrt((shares / radius) @ arms / inertia)
    pendulum = 2 * np.pi * math.sqrt(radius / STANDARD_GRAVITY)
    assert np.allclose(np.sort(periods), np.sort([pendulum, pendulum, torsion]), rtol=1e-6)
    assert np.isclose(shares.sum(), in_plan.weight, rtol=1e-13)


def test_hht_runs_the_coupled_system():
    plan = Plan(SQUARE, eccentricity=(1.2, 0.8), dimensions=(12.0, 10.0), storey_heights=3.5)
    newmark = _eccentric(vertical=False)
    pair = synthetic_pair("kanai-tajimi", 11, duration=4.0, dt=DT, target_pga=4.0,
                          ground_frequency=15.0, ground_damping=0.6)
    hht = run(dataclasses.replace(_building(), plan=plan), _bearing("constant"), pair, "hht",
                      dt=DT)
    assert hht.attrs["success"] and "HHT" in hht.attrs["integrator"]
    # numerical damping of the high modes only: the isolation response hardly moves
    assert _relative(hht["displacement"].values[:, 0], newmark["displacement"].values[:, 0]) \
        < 0.05
    assert 0.0 < hht.attrs["energy_balance_error"] < 0.05



def test_uplift_under_a_strong_vertical_pulse_as_the_element_handles_it():
    """A downward vertical pulse beyond 1 g unloads every bearing: no force, no friction
    work while it lasts, and the run goes on with the balance closed."""
    horizontal = _pair_along(30.0)
    time = horizontal.x.time
    pulse = np.where((time >= 1.0) & (time <= 1.2), -1.5 * STANDARD_GRAVITY, 0.0)
    pair = GroundMotionPair(horizontal.x, horizontal.y, GroundMotion(pulse, DT, "pulse"))
    plan = Plan(SQUARE, eccentricity=(0.5, 0.0), dimensions=(12.0, 10.0))
    result = run(dataclasses.replace(_building(), plan=plan), _bearing("constant"), pair,
                         dt=DT, overturning=False)
    assert result.attrs["success"] and result.attrs["vertical"] == 1
    load = result["axial_load"].values
    lifted = (time >= 1.0 + 1e-9) & (time <= 1.2 - 1e-9)
    assert np.all(load[lifted] == 0.0) and np.all(load[~lifted & (time < 1.0)] > 0.0)
    assert np.all(result["bearing_force"].values[lifted] == 0.0)
    friction = result["energy_friction"].values
    assert friction[lifted][-1] == friction[lifted][0]
    assert result.attrs["energy_balance_error"] < 1e-6
