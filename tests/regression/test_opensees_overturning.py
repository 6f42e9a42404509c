"""The building in plan with overturning against its OpenSees twin with the floors at their
heights (:mod:`structures.opensees.model`, tall layout).

Script: this file runs both live (no stored fixture), with openseespy 3.7.1.2 (OpenSees 3.7.1)
through :mod:`structures.opensees.model`, :mod:`structures.opensees.building` and
:mod:`structures.opensees.comparison`. The building: ``examples/five_storey_plan.toml``
(5 x 400 t floors 3.5 m apart, 500 t base slab, fixed-base period 0.5 s, Rayleigh 2 %, six
bearings at x = -10, 0, 10 m and y = -5, 5 m, centre of mass at (1.2, 0.6) m, R_eff = 4.5 m,
300 mm slider, u_y = 0.5 mm), its constant model (mu = 0.0403). Ours loads each bearing with
``N_g (1 + a_z / g) + G H F`` (:class:`~structures.isolated_building.IsolatedShearBuilding`).

The pieces, one at a time (measured):

- statics: a lateral load at a floor's centre of mass loads the bearings of the spring twin
  (flatSliderBearing, N = P) as ours, gravity share plus ``G @ (0, H F_x, H F_y)``, to
  8e-14 of the overturning part (singleFPBearing adds its own lift ``F . u / R`` to N);
- modes on the bearings' tangent at rest (kInit = mu N_i / u_y + N_i / R): the periods of
  ``ShearBuilding.isolated_modes`` to 1.5e-5 (4e-14 without overturning): the base slab rocks
  on the bearings' axial springs (1 um under the gravity load), which softens the sticking
  building by about ``H^2 / (k_v sum x_i^2)``; 1.5e-6 and 1.7e-7 with springs 10 and 100
  times stiffer, unchanged with storeys 100 times more or less rigid (1e6 ... 1e8; at 1e10 the
  eigen solution loses digits: 2.5e-4);
- dynamics: the twin's axial force P (the normal force less singleFPBearing's lift) is ours's
  formula evaluated on the twin's own histories (the floors' inertia forces ``-M a`` at their
  heights, the vertical on the gravity shares) to 6e-13 of the loads' change.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.synthetic import synthetic_pair
from structures.config import load_config
from structures.isolated_building import IsolatedShearBuilding
from structures.opensees.building import run_opensees
from structures.opensees.elements import singlefp_restoring
from structures.opensees.model import build_model, level_heights
from structures.opensees.runtime import import_opensees

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "five_storey_plan.toml"
DT = 0.005


@pytest.fixture(scope="module")
def ops():
    try:
        return import_opensees()
    except ImportError as error:
        pytest.skip(f"openseespy cannot be imported: {error}")


@pytest.fixture(scope="module")
def config():
    return load_config(EXAMPLE)


@pytest.fixture(scope="module")
def bearing(config):
    return replace(config.bearing("constant"), axial_load=None)


def _analysis(ops, integrator: tuple) -> None:
    for command, *values in (("constraints", "Transformation"), ("numberer", "Plain"),
                             ("system", "FullGeneral"), ("test", "NormDispIncr", 1e-12, 50),
                             ("algorithm", "Newton"), ("integrator", *integrator)):
        getattr(ops, command)(*values)


@pytest.mark.parametrize(("floor", "force"), [(1, (7e4, -5e4)), (3, (1e5, 0.0)),
                                              (5, (0.0, 1e5))])
def test_a_lateral_load_at_a_floor_loads_the_bearings_as_ours(ops, config, bearing, floor,
                                                               force):
    building = config.building
    model = IsolatedShearBuilding(building, bearing, overturning=True)
    ops.wipe()
    try:
        twin = build_model(ops, model, "spring")
        ops.timeSeries("Constant", 2)
        ops.pattern("Plain", 2, 2)
        ops.load(twin.nodes[floor], *force, 0.0, 0.0, 0.0, 0.0)  # the floor's master
        _analysis(ops, ("LoadControl", 1.0))
        ops.analysis("Static")
        assert ops.analyze(1) == 0
        loads = twin.read(ops)["axial_load"]
    finally:
        ops.wipe()
    height = level_heights(building)[floor]
    overturning = building.axial_distribution @ np.array([0.0, height * force[0],
                                                          height * force[1]])
    assert np.max(np.abs(overturning)) > 1e4  # [N]
    expected = model.gravity_loads + overturning
    assert np.max(np.abs(loads - expected)) < 1e-9 * np.max(np.abs(overturning))


@pytest.mark.parametrize("overturning", [False, True])
def test_the_periods_on_the_bearings_at_rest_are_ours(ops, config, bearing, overturning):
    building = config.building
    model = IsolatedShearBuilding(building, bearing, overturning=overturning)
    loads = building.gravity_shares
    kinit = bearing.friction.mu * loads / bearing.yield_displacement \
        + loads / bearing.effective_radius
    ours = building.isolated_modes(kinit).periods
    ops.wipe()
    try:
        build_model(ops, model, "singlefp")
        _analysis(ops, ("Newmark", 0.5, 0.25))
        ops.analysis("Transient")
        periods = 2.0 * np.pi / np.sqrt(np.array(ops.eigen("-fullGenLapack", len(ours))))
    finally:
        ops.wipe()
    gap = np.max(np.abs(periods / ours - 1.0))
    assert gap < (3e-5 if overturning else 1e-12)  # the slab's rocking on its bearings


@pytest.mark.parametrize("pendulum", ["spring", "singlefp"])
def test_the_axial_loads_are_ours_on_the_twins_histories(ops, config, bearing, pendulum):
    """P = N_g (1 + a_z / g) + G H F with the floors' inertia forces F = -M a of the twin."""
    building = config.building
    pair = synthetic_pair("kanai-tajimi", 3, duration=2.0, dt=DT, target_pga=4.0,
                          ground_frequency=15.0, ground_damping=0.6, vertical_ratio=2 / 3)
    twin = run_opensees(building, bearing, pair, dt=DT, pendulum=pendulum)
    assert twin.attrs["success"] and twin.attrs["overturning"] == 1
    normal = twin["axial_load"].values
    if pendulum == "singlefp":  # less its lift F . u / R (crossed radii)
        u = twin["bearing_displacement"].values
        lever = singlefp_restoring(np.ones(u.shape[:-1]), u, bearing.effective_radius)
        normal = normal - np.sum(twin["bearing_force"].values * lever, axis=-1)
    acceleration = np.zeros((twin.sizes["time"], building.n_dof))
    acceleration[:, 0::3] = twin["absolute_acceleration"].values[..., 0]
    acceleration[:, 1::3] = twin["absolute_acceleration"].values[..., 1]
    acceleration[:, 2::3] = twin["angular_acceleration"].values
    inertia = -acceleration @ building.isolated_mass_matrix.T
    heights = level_heights(building)[1:]
    g = building.axial_distribution
    vertical = np.interp(twin["time"].values, pair.z.time, pair.z.acceleration)
    gravity = np.outer(1.0 + vertical / STANDARD_GRAVITY, building.gravity_shares)
    expected = gravity + np.outer(inertia[:, 3::3] @ heights, g[:, 1]) \
        + np.outer(inertia[:, 4::3] @ heights, g[:, 2])
    change = np.max(np.abs(expected - gravity))
    assert change > 0.1 * np.max(building.gravity_shares)  # the overturning moves the loads
    assert np.max(np.abs(normal - expected)) < 1e-10 * change
