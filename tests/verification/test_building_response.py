"""The isolated five-storey building under El Centro: energy balance, symmetry, convergence."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from groundmotions.bundled import load_bundled
from structures.analysis import peaks, run
from structures.config import load_config
from structures.integrators import HHT

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "five_storey.toml"


@pytest.fixture(scope="module")
def config():
    return load_config(EXAMPLE)


@pytest.fixture(scope="module")
def motion():
    return load_bundled("elcentro")


@pytest.mark.parametrize("model", ["precise", "simplified", "constant"])
def test_energy_balance_closes_on_el_centro(config, motion, model):
    result = run(config.building, config.bearing(model), motion, n_bearings=config.n_bearings,
                 dt=0.005)
    assert result.attrs["success"]
    # average acceleration satisfies the trapezoid work identity exactly: round-off only
    assert result.attrs["energy_balance_error"] < 1e-9
    friction = float(result["energy_friction"][-1])
    assert friction > 0.5 * float(result["energy_input"][-1])  # the isolators dissipate most
    hht = run(config.building, config.bearing(model), motion, HHT(alpha=-0.05),
              n_bearings=config.n_bearings, dt=0.005)
    assert hht.attrs["energy_balance_error"] < 1e-3  # HHT's numerical dissipation


def test_negated_ground_motion_negates_the_response(config, motion):
    bearing = config.bearing("precise")
    a = run(config.building, bearing, motion, n_bearings=config.n_bearings, dt=0.005)
    b = run(config.building, bearing, motion.negated(), n_bearings=config.n_bearings, dt=0.005)
    scale = float(np.abs(a["displacement"]).max())
    assert float(np.abs(a["displacement"] + b["displacement"]).max()) < 1e-8 * scale
    assert np.allclose(a["temperature"], b["temperature"], rtol=1e-9, atol=0.0)


def test_response_converges_as_dt_halves(config, motion):
    bearing = config.bearing("precise")
    values = {}
    for dt in (0.01, 0.005, 0.0025):
        result = run(config.building, bearing, motion, n_bearings=config.n_bearings, dt=dt)
        values[dt] = peaks(result)
        history = result["bearing_displacement"].values[:, 0, 0]
        values[dt]["history"] = history[:: round(0.01 / dt)]
    for key in ("peak_isolator_displacement", "peak_base_shear", "max_temperature"):
        coarse = abs(values[0.01][key] - values[0.0025][key])
        fine = abs(values[0.005][key] - values[0.0025][key])
        assert fine <= coarse + 1e-12 * abs(values[0.0025][key]), key
        assert fine < 0.03 * abs(values[0.0025][key]), key
    err_coarse = np.abs(values[0.01]["history"] - values[0.0025]["history"]).max()
    err_fine = np.abs(values[0.005]["history"] - values[0.0025]["history"]).max()
    assert err_fine < err_coarse
    assert err_fine < 0.05 * values[0.0025]["peak_isolator_displacement"]


def test_isolators_reduce_the_base_shear_against_the_fixed_base_building(config, motion):
    """The fixed-base building's base shear is several times the isolated one's."""
    from structures.integrators import integrate

    fixed = config.building.fixed_base_model()
    response = integrate(fixed, motion.acceleration, motion.dt)
    masses = np.diag(config.building.fixed_base_mass_matrix)
    fixed_shear = np.abs(response.absolute_acceleration @ masses).max()
    isolated = run(config.building, config.bearing("precise"), motion,
                   n_bearings=config.n_bearings, dt=0.005)
    assert float(np.abs(isolated["base_shear"]).max()) < 0.5 * fixed_shear


@pytest.mark.parametrize("model", ["constant", "simplified"])
def test_displacement_beyond_capacity_is_a_failed_run(config, motion, model):
    """Every friction model is held to the bearing's displacement capacity (the precise
    model's monitor line ends there and raises; the others finish but are flagged)."""
    from dataclasses import replace

    bearing = replace(config.bearing(model), displacement_capacity=0.05)
    result = run(config.building, bearing, motion, n_bearings=config.n_bearings, dt=0.01)
    assert result.attrs["success"] == 0
    assert "displacement_capacity" in result.attrs["message"]
    assert float(np.abs(result["bearing_displacement"].values[:, 0, 0]).max()) > 0.05
