"""Floor response spectra (structures.floor_spectra) are the spectrum code's, to the last digit.

A floor spectrum is the 5 %-damped pseudo-acceleration spectrum of the floor's absolute
acceleration history; the ground's is that of the record as read. Both must be exactly what the
project's spectrum code (groundmotions.spectra, the exact Nigam-Jennings recurrence) and
``dcfpb spectrum`` give for the same histories: nothing is recomputed in another way.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main
from dcfpb.cli.spectrum import STANDARD_PERIODS
from groundmotions.bundled import load_bundled
from groundmotions.spectra import response_spectra, response_spectrum, sdof_response
from structures.analysis import run
from structures.config import load_config
from structures.fixed_base import run_fixed_base
from structures.floor_spectra import (
    FLOOR_SPECTRUM_PERIODS,
    with_floor_spectra,
    with_floor_spectra_all,
)

REPO = Path(__file__).resolve().parents[2]
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"


@pytest.fixture(scope="module")
def config():
    return load_config(REPO / "examples" / "five_storey.toml")


@pytest.fixture(scope="module")
def motion():
    return load_bundled("elcentro")


@pytest.fixture(scope="module")
def fixed(config, motion):
    """The linear fixed-base building of the demo under El Centro, on the demo's step."""
    return with_floor_spectra(run_fixed_base(config.building, motion, dt=config.dt), motion)


def test_roof_spectrum_of_a_linear_fixed_base_building_is_that_of_its_roof_history(fixed):
    roof = fixed["absolute_acceleration"].isel(floor=-1, direction=0).values
    direct = response_spectrum(roof, fixed.attrs["dt"], FLOOR_SPECTRUM_PERIODS, 0.05)
    assert np.array_equal(fixed["floor_spectrum"].isel(floor=-1, direction=0).values, direct.sa)
    assert fixed.attrs["spectrum_damping"] == 0.05
    # every floor alike, and the roof's resonance at the fixed-base period
    for floor in fixed["floor"].values:
        history = fixed["absolute_acceleration"].sel(floor=floor, direction="x").values
        expected = response_spectrum(history, fixed.attrs["dt"], FLOOR_SPECTRUM_PERIODS).sa
        assert np.array_equal(fixed["floor_spectrum"].sel(floor=floor, direction="x").values,
                              expected)
    roof_spectrum = fixed["floor_spectrum"].isel(floor=-1, direction=0).values
    peak_period = fixed["period"].values[np.argmax(roof_spectrum)]
    assert peak_period == pytest.approx(fixed.attrs["fixed_base_periods"][0], rel=0.1)


def test_ground_spectrum_is_dcfpb_spectrum_on_the_record(config, motion, capsys):
    periods = np.asarray(STANDARD_PERIODS)
    result = with_floor_spectra(run_fixed_base(config.building, motion, dt=config.dt), motion,
                                periods=periods)
    assert main(["spectrum", str(RECORD), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["spectrum"]
    assert [r["period"] for r in rows] == periods.tolist()
    assert result["ground_spectrum"].sel(direction="x").values.tolist() == [r["sa"] for r in rows]


def test_period_zero_is_the_peak_absolute_acceleration(fixed, motion):
    assert FLOOR_SPECTRUM_PERIODS[0] == 0.0
    peaks = np.abs(fixed["absolute_acceleration"]).max("time").values
    assert np.array_equal(fixed["floor_spectrum"].isel(period=0).values, peaks)
    assert fixed["ground_spectrum"].values[0, 0] == motion.pga
    # the ground level of a fixed base moves with the ground: its spectrum on the run's step
    on_step = response_spectrum(fixed["ground_acceleration"].values[:, 0], fixed.attrs["dt"],
                                FLOOR_SPECTRUM_PERIODS).sa
    assert np.array_equal(fixed["floor_spectrum"].sel(floor=0, direction="x").values, on_step)


def test_runs_in_one_pass_equal_runs_one_at_a_time(config, motion):
    short = motion.truncated(6.0)
    runs = {model: run(config.building, config.bearing(model), short, config.integrator,
                       n_bearings=config.n_bearings, dt=config.dt)
            for model in ("simplified", "constant")}
    runs["fixed base"] = run_fixed_base(config.building, short, dt=config.dt)
    together = with_floor_spectra_all(runs, short)
    for name, result in runs.items():
        alone = with_floor_spectra(result, short)
        assert np.array_equal(together[name]["floor_spectrum"], alone["floor_spectrum"]), name
        assert np.array_equal(together[name]["ground_spectrum"], alone["ground_spectrum"])
    flagged = run(config.building, config.bearing("constant"), short, config.integrator,
                  n_bearings=config.n_bearings, dt=config.dt, floor_spectra=True)
    assert np.array_equal(flagged["floor_spectrum"], together["constant"]["floor_spectrum"])


def test_without_the_record_the_ground_spectrum_is_the_runs_ground_acceleration(fixed):
    own = with_floor_spectra(fixed.drop_vars(["floor_spectrum", "ground_spectrum", "period"]))
    assert np.array_equal(own["ground_spectrum"].values, own["floor_spectrum"].sel(floor=0))


def test_several_records_in_one_pass_equal_one_at_a_time():
    rng = np.random.default_rng(7)
    records = rng.normal(size=(400, 3)) * np.array([1.0, 0.3, 2.0])
    periods = np.array([0.0, 0.03, 0.2, 1.0, 4.0])
    many = response_spectra(records, 0.01, periods, 0.05)
    for j in range(records.shape[1]):
        one = response_spectrum(records[:, j], 0.01, periods, 0.05)
        for field in ("sd", "sv", "sa"):
            assert np.array_equal(getattr(many, field)[j], getattr(one, field)), field


def test_damping_per_period_equals_one_call_per_period():
    rng = np.random.default_rng(3)
    acceleration = rng.normal(size=300)
    periods, ratios = np.array([0.1, 0.5, 2.0]), np.array([0.02, 0.05, 0.3])
    u, v = sdof_response(acceleration, 0.01, periods, ratios)
    for j in range(periods.size):
        u_j, v_j = sdof_response(acceleration, 0.01, periods[j:j + 1], ratios[j])
        assert np.array_equal(u[:, j], u_j[:, 0]) and np.array_equal(v[:, j], v_j[:, 0])
    with pytest.raises(ValueError, match=r"'damping' parameter of sdof_response .*\[0, 1\)"):
        sdof_response(acceleration, 0.01, periods, [0.02, 1.0, 0.1])
    with pytest.raises(ValueError, match="'damping' parameter of sdof_response"):
        sdof_response(acceleration, 0.01, periods, [0.02, 0.05])
