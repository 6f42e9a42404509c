"""The compiled engine on the building in plan against the reference engine.

An eccentric 3-storey building on four bearings under a synthetic pair with a vertical and
overturning: every history the run records (levels, bearings, the energies, the plate
temperature field of the precise model) agrees to 1e-9 relative with the constant,
simplified and precise friction, with Newmark and HHT, and the energy balance closes as the
reference's does. The same with the Python original of the engine loop
(``DCFPB_DISABLE_NUMBA=1`` runs all of it as Python: ``test_python_engine_agrees``). Failures
keep the reference's contract (a slider off the monitor grid; a vertical pulse beyond 1 g
lifting every bearing).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from groundmotions.synthetic import synthetic_pair
from isolator.bearing import DCFPBearing
from isolator.experiments import friction_model
from isolator.heating import MonitorLine
from structures.analysis import resampled_record, run
from structures.compiled.engine import bearing_fields, compiled_run
from structures.compiled.view import engine_view
from structures.integrators import as_method
from structures.isolated_building import IsolatedShearBuilding
from structures.plan import Plan
from structures.shear_building import ShearBuilding

SQUARE = [[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0]]
DT = 0.01
TOLERANCE = 1e-9
SKIP = {"time", "floor", "storey", "direction", "bearing"}


@functools.cache
def _building() -> ShearBuilding:
    plan = Plan(SQUARE, eccentricity=(1.2, 0.8), dimensions=(12.0, 10.0), storey_heights=3.5)
    return ShearBuilding.from_period([4e5, 4e5, 4e5], 0.5, base_mass=5e5, plan=plan)


def _bearing(model: str, capacity: float = 0.3) -> DCFPBearing:
    """The paper's 300 mm slider with R_eff 2.5 m; ``capacity`` sizes the monitor grid."""
    load = _building().weight / 4
    friction = friction_model(model, slider_diameter=0.3, design_pressure=load / (
        np.pi * 0.15**2), design_velocity=0.4)
    return DCFPBearing(2.5, 0.3, friction=friction, displacement_capacity=capacity)


@functools.cache
def _pair(duration: float = 4.0) -> GroundMotionPair:
    return synthetic_pair("kanai-tajimi", 11, duration=duration, dt=DT, target_pga=4.0,
                          vertical_ratio=0.6, ground_frequency=15.0, ground_damping=0.6)


@functools.cache
def _runs(model: str, integrator: str):
    return tuple(run(_building(), _bearing(model), _pair(), integrator, dt=DT,
                             engine=engine) for engine in ("reference", "compiled"))


def _relative(got: np.ndarray, expected: np.ndarray) -> float:
    """Largest difference relative to the largest value; NaN (the plate field's padding)
    must be where the reference has it."""
    assert got.shape == expected.shape
    padding = np.isnan(expected)
    assert np.array_equal(np.isnan(got), padding)
    got, expected = got[~padding], expected[~padding]
    scale = np.max(np.abs(expected))
    difference = np.max(np.abs(got - expected), initial=0.0)
    return float(difference / scale) if scale > 0.0 else float(difference)


@pytest.mark.parametrize("integrator", ["newmark", "hht"])
@pytest.mark.parametrize("model", ["constant", "simplified", "precise"])
def test_every_history_agrees_with_the_reference(model, integrator):
    reference, compiled = _runs(model, integrator)
    assert reference.attrs["success"] and compiled.attrs["success"]
    assert compiled.attrs["engine"] == "compiled"
    assert set(compiled.variables) == set(reference.variables)
    worst = {name: _relative(compiled[name].values, reference[name].values)
             for name in reference.variables if name not in SKIP | {"energy_error"}}
    # the balance's error is round-off itself: compared against the input energy
    error = compiled["energy_error"].values - reference["energy_error"].values
    worst["energy_error"] = float(np.max(np.abs(error))
                                  / np.max(np.abs(reference["energy_input"].values)))
    assert max(worst.values()) < TOLERANCE, worst
    assert compiled.attrs["newton_iterations"] == reference.attrs["newton_iterations"]
    if model == "precise":  # the plate field: the same points in the same order
        assert compiled.sizes["plate_point"] == reference.sizes["plate_point"] > 100
        assert reference["temperature"].values.max() > 40.0
    if integrator == "newmark":
        assert compiled.attrs["energy_balance_error"] < 1e-6
    assert abs(compiled.attrs["energy_balance_error"]
               - reference.attrs["energy_balance_error"]) < 1e-9


def _model(model: str, pair: GroundMotionPair, **kwargs) -> IsolatedShearBuilding:
    return IsolatedShearBuilding(_building(), _bearing(model, **kwargs), vertical=pair.z)


def _acceleration(pair: GroundMotionPair) -> np.ndarray:
    x, step = resampled_record(pair.x, DT)
    y, _ = resampled_record(pair.y, step)
    return np.column_stack([x, y])


@pytest.mark.parametrize("model", ["simplified", "precise"])
def test_python_engine_agrees(model):
    """The Python original of the loop (what ``DCFPB_DISABLE_NUMBA=1`` runs) on 1.5 s."""
    pair = _pair()
    acceleration = _acceleration(pair)[:151]
    method = as_method("newmark")
    runs = [compiled_run(engine_view(_model(model, pair)), acceleration, DT, method,
                         tolerance=1e-8, max_subdivisions=6, python=python)
            for python in (False, True)]
    records = [bearing_fields(run.record) for run in runs]
    for name, values in records[0].items():
        assert _relative(records[1][name], values) < TOLERANCE, name
    assert _relative(runs[1].result.displacement, runs[0].result.displacement) < TOLERANCE


@pytest.mark.parametrize("half_length", [None, 0.16])
def test_slider_off_the_grid_fails_as_the_reference(half_length):
    """A bearing whose capacity is too small for the motion (the reference's check of the
    committed displacement), or whose monitor grid is (a trial off the grid): the run ends at
    the same step with the same message."""
    bearing = _bearing("precise", capacity=0.3 if half_length else 0.05)
    if half_length:
        heating = MonitorLine(0.005, half_length)
        bearing = dataclasses.replace(bearing, friction=dataclasses.replace(bearing.friction,
                                                                          heating=heating))
    runs = [run(_building(), bearing, _pair(), dt=DT, engine=engine)
            for engine in ("reference", "compiled")]
    assert not runs[0].attrs["success"]
    assert ("monitor grid" in runs[0].attrs["message"]) == bool(half_length)
    for key in ("success", "failure", "message", "failed_at", "steps"):
        assert runs[1].attrs[key] == runs[0].attrs[key], key
    assert _relative(runs[1]["displacement"].values, runs[0]["displacement"].values) < 1e-9


def test_uplift_under_a_vertical_pulse_as_the_reference():
    """A downward pulse beyond 1 g lifts every bearing: no load, no force, no heat (the plates
    cool over the uplift as the reference's do), then the run goes on."""
    pair = _pair()
    time = pair.x.time
    pulse = np.where((time >= 1.0) & (time <= 1.2), -1.5 * STANDARD_GRAVITY, 0.0)
    lifted = GroundMotionPair(pair.x, pair.y, GroundMotion(pulse, DT, "pulse"))
    runs = [run(_building(), _bearing("precise"), lifted, dt=DT, overturning=False,
                        engine=engine) for engine in ("reference", "compiled")]
    assert runs[0].attrs["success"] and runs[1].attrs["success"]
    assert np.any(runs[0]["axial_load"].values == 0.0)
    for name in ("displacement", "bearing_force", "temperature", "axial_load",
                 "plate_temperature"):
        assert _relative(runs[1][name].values, runs[0][name].values) < TOLERANCE, name


def test_engine_choice_is_checked():
    with pytest.raises(ValueError, match="engine"):
        run(_building(), _bearing("constant"), _pair(), dt=DT, engine="fast")
