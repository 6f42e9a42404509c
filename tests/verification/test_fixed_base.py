"""The fixed-base reference (structures.fixed_base) against closed forms and the integrator.

Modal superposition with the exact recurrence: a one-storey building is one oscillator, whose
peak drift is the spectral displacement of the record; a five-storey building agrees with
Newmark's average acceleration (structures.integrators) to Newmark's own period error.
"""

from __future__ import annotations

from functools import cached_property
from pathlib import Path

import numpy as np
import pytest

from groundmotions.bundled import load_bundled
from groundmotions.spectra import response_spectrum
from structures.analysis import resampled_record, run
from structures.config import load_config
from structures.fixed_base import (
    PEAK_NAMES,
    ratios_to_fixed_base,
    run_fixed_base,
    superstructure_peaks,
)
from structures.integrators import integrate
from structures.shear_building import ModalDamping, ShearBuilding

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def config():
    return load_config(REPO / "examples" / "five_storey.toml")


@pytest.fixture(scope="module")
def motion():
    return load_bundled("elcentro")


def test_one_storey_building_drifts_by_the_spectral_displacement(motion):
    building = ShearBuilding.from_period([3.0e5], 0.7, base_mass=1.0e5,
                                         damping=ModalDamping(0.05))
    result = run_fixed_base(building, motion, dt=0.005)
    assert result.attrs["modal_damping_ratios"] == pytest.approx([0.05], rel=1e-12)
    acceleration, step = resampled_record(motion, 0.005)
    sd = response_spectrum(acceleration, step, [0.7], 0.05).sd[0]
    assert float(np.abs(result["storey_drift"]).max()) == pytest.approx(sd, rel=1e-12)
    # the first-storey shear is the spring and the damper of that storey
    k, c = building.storey_stiffnesses[0], building.fixed_base_damping_matrix[0, 0]
    u = result["displacement"].sel(floor=1, direction="x").values
    v = result["velocity"].sel(floor=1, direction="x").values
    shear = result["base_shear"].sel(direction="x").values
    np.testing.assert_allclose(shear, k * u + c * v, atol=1e-9 * float(np.abs(shear).max()))


def test_five_storeys_agree_with_newmark(config, motion):
    acceleration, step = resampled_record(motion, 0.001)
    newmark = integrate(config.building.fixed_base_model(), acceleration, step, "newmark")
    modal = run_fixed_base(config.building, motion, dt=0.001)
    scale = np.abs(newmark.absolute_acceleration).max()
    modal_floors = modal["absolute_acceleration"].values[:, 1:, 0]
    error = np.abs(newmark.absolute_acceleration - modal_floors)
    assert error.max() / scale < 3e-3  # measured 1.4e-3: Newmark's period error at dt/T1 = 1/500
    drift = np.abs(np.diff(newmark.displacement, axis=1, prepend=0.0)).max()
    assert superstructure_peaks(modal)["peak_storey_drift"] == pytest.approx(drift, rel=1e-3)


def test_floor_zero_moves_with_the_ground_and_shear_sums_the_floors(config, motion):
    result = run_fixed_base(config.building, motion.truncated(8.0), dt=config.dt)
    assert np.array_equal(result["displacement"].sel(floor=0, direction="x"),
                          np.zeros(result.sizes["time"]))
    assert np.array_equal(result["absolute_acceleration"].sel(floor=0),
                          result["ground_acceleration"])
    masses = config.building.floor_masses
    inertia = -(result["absolute_acceleration"].values[:, 1:, 0] * masses)
    np.testing.assert_allclose(result["base_shear"].sel(direction="x"), inertia.sum(axis=1),
                               rtol=1e-12, atol=1e-6)
    assert result.attrs["configuration"] == "fixed base"


def test_ratios_of_the_demo_building(config, motion):
    short = motion.truncated(8.0)
    fixed = run_fixed_base(config.building, short, dt=config.dt)
    assert ratios_to_fixed_base(fixed, fixed) == dict.fromkeys(PEAK_NAMES, 1.0)
    isolated = run(config.building, config.bearing("constant"), short, config.integrator,
                   n_bearings=config.n_bearings, dt=config.dt)
    ratios = ratios_to_fixed_base(isolated, fixed)
    assert set(ratios) == set(PEAK_NAMES)
    assert all(0.0 < r < 0.5 for r in ratios.values())  # the isolation works on this record


def test_non_classical_damping_is_refused(motion):
    class Coupled(ShearBuilding):
        @cached_property
        def fixed_base_damping_matrix(self):
            return np.array([[2.0e5, 5.0e4], [5.0e4, 1.0e5]])

    building = Coupled(np.array([1.0e5, 1.0e5]), np.array([1.0e8, 1.0e8]), 1.0e5)
    with pytest.raises(ValueError, match="'damping' parameter of ShearBuilding must be classical"):
        run_fixed_base(building, motion)
