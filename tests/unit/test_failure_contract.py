"""One failure contract for every friction model and both engines (issue 12, point 4).

The bundled five-storey building under El Centro scaled until the bearings pass their
displacement capacity (0.6 m): every model and engine ends the same way, with a result
(``success = 0``), the reason in ``message`` (which displacement, which capacity, when), the
histories up to the failure and their peaks marked as such; ``dcfpb run`` prints them with a
line saying so and exits 1. A time limit ends a run the same way. Runs that finish are not
touched (the chunked compiled engine computes the same digits).
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main
from dcfpb.common.errors import CapacityExceeded
from groundmotions.bundled import load_bundled
from structures.analysis import peaks, run
from structures.config import load_config

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
MODELS = ("precise", "simplified", "constant")


@pytest.fixture(scope="module")
def config():
    return load_config(EXAMPLE)


@pytest.fixture(scope="module")
def elcentro():
    return load_bundled("elcentro")


def _run(config, motion, model, engine, dt=0.005, **kwargs):
    return run(config.building, config.bearing(model), motion, config.integrator,
               n_bearings=config.n_bearings, dt=dt, engine=engine, **kwargs)


def _assert_failed_on_capacity(result):
    capacity = result.attrs["displacement_capacity"]
    u = np.abs(result["bearing_displacement"].values[:, 0, 0])
    time = result["time"].values
    assert result.attrs["success"] == 0 and result.attrs["failure"] == "capacity"
    assert result.attrs["peaks_up_to_failure"] == 1
    message = result.attrs["message"]
    assert message.startswith(("Capacity exceeded:", "Step "))
    assert "Capacity exceeded" in message
    assert f"displacement_capacity {capacity:g} m" in message
    assert f"at t = {result.attrs['failed_at']:.6g} s" in message
    assert f"those up to t = {time[-1]:.6g} s" in message
    assert np.all(u[:-1] <= capacity)  # nothing after the failure is kept
    assert result.attrs["steps"] == time.size - 1
    for name in ("base_shear", "temperature", "energy_input", "ground_acceleration"):
        assert result[name].sizes["time"] == time.size, name
    summary = peaks(result)
    assert summary["peaks_up_to_failure"] is True and summary["failure"] == "capacity"
    assert summary["failed_at"] == result.attrs["failed_at"]
    assert summary["peak_isolator_displacement"] == u.max()
    return summary


@pytest.mark.parametrize("model", MODELS)
def test_every_model_and_engine_fails_the_same_way_beyond_capacity(config, elcentro, model):
    motion = elcentro.scaled(20.0)
    results = {engine: _run(config, motion, model, engine)
               for engine in ("compiled", "reference")}
    summaries = {engine: _assert_failed_on_capacity(r) for engine, r in results.items()}
    compiled, reference = results["compiled"], results["reference"]
    assert compiled.attrs["message"] == reference.attrs["message"]
    assert compiled.attrs["failed_at"] == reference.attrs["failed_at"]
    assert compiled.sizes == reference.sizes
    # the step past the capacity is the last one: 0.6 m < peak < 0.62 m, at about 1.2 s
    assert 0.6 < summaries["compiled"]["peak_isolator_displacement"] < 0.62
    assert summaries["compiled"]["peak_isolator_displacement"] == pytest.approx(
        summaries["reference"]["peak_isolator_displacement"], rel=1e-9)
    assert 1.0 < compiled.attrs["failed_at"] < 1.5


def test_a_trial_off_the_monitor_line_is_the_same_capacity_failure(config, elcentro):
    """At a coarse step the precise model's trial leaves its monitor line before a committed
    step passes the capacity: the run still ends as a capacity failure, with the trial's
    displacement and time, and the committed histories before it."""
    results = [_run(config, elcentro.scaled(30.0), "precise", engine, dt=0.02)
               for engine in ("compiled", "reference")]
    for result in results:
        message = result.attrs["message"]
        assert result.attrs["failure"] == "capacity" and result.attrs["success"] == 0
        assert "in a trial of the step" in message and "monitor line" in message
        assert "beyond the bearing's displacement_capacity 0.6 m" in message
        assert result["time"].values[-1] < result.attrs["failed_at"]
        assert np.abs(result["bearing_displacement"].values[:, 0, 0]).max() <= 0.6
    assert results[0].attrs["message"] == results[1].attrs["message"]
    assert results[0].sizes == results[1].sizes


def test_the_spherical_law_at_its_radius_is_a_capacity_failure(config):
    bearing = dataclasses.replace(config.bearing("constant"), axial_load=1.0e6,
                                  restoring="spherical")
    element = bearing.element()
    with pytest.raises(CapacityExceeded, match=r"effective radius 4\.5 m") as error:
        element.set_trial(4.5, 0.1, 0.01)
    assert error.value.kind == "capacity" and isinstance(error.value, ValueError)
    assert "at t = 0.01 s" in str(error.value)


def test_a_run_that_finishes_is_marked_so(config, elcentro):
    result = _run(config, elcentro.truncated(3.0), "constant", "compiled")
    assert result.attrs["success"] == 1 and result.attrs["failure"] == ""
    assert result.attrs["peaks_up_to_failure"] == 0 and "failed_at" not in result.attrs
    summary = peaks(result)
    assert (summary["peaks_up_to_failure"], summary["failed_at"], summary["failure"]) == (
        False, None, "")


@pytest.mark.parametrize("model", MODELS)
def test_cli_run_prints_the_peaks_up_to_the_failure_and_exits_1(model, capsys):
    base = ["run", str(EXAMPLE), "--record", str(RECORD), "--scale", "20", "--model", model]
    assert main(base) == 1
    out = capsys.readouterr().out
    assert f"\n{model}" in out and "isol. disp" in out  # the table is printed
    assert "RUN FAILED (capacity) at t = " in out
    assert "the peaks above are those up to the failure" in out
    assert "Capacity exceeded: the isolator displacement reached" in out
    assert main([*base, "--json"]) == 1
    report = json.loads(capsys.readouterr().out)
    for key in ("peak_isolator_displacement", "peak_base_shear", "peak_roof_acceleration",
                "energy_balance_error", "steps", "wall_time", "peak_storey_drift",
                "max_temperature", "success", "message"):  # every key of before is kept
        assert key in report, key
    assert report["success"] is False and report["peaks_up_to_failure"] is True
    assert report["failure"] == "capacity" and 1.0 < report["failed_at"] < 1.5
    assert 0.6 < report["peak_isolator_displacement"] < 0.62


@pytest.mark.parametrize("engine", ["compiled", "reference"])
def test_a_time_limit_ends_the_run_as_a_timeout(config, elcentro, engine):
    result = _run(config, elcentro, "constant", engine, time_limit=0.0)
    assert result.attrs["success"] == 0 and result.attrs["failure"] == "timeout"
    assert "timeout after 0 s" in result.attrs["message"]
    assert result.attrs["failed_at"] == result["time"].values[-1]
    assert 1 <= result.attrs["steps"] < 6232
    assert peaks(result)["peaks_up_to_failure"] is True


def test_the_chunked_compiled_engine_computes_the_same_digits(config, elcentro):
    """With a time limit the compiled engine runs CHUNK_STEPS steps per call; a run within
    the limit is the same, to the last bit, as the run in one call."""
    whole = _run(config, elcentro, "precise", "compiled")
    chunked = _run(config, elcentro, "precise", "compiled", time_limit=math.inf)
    assert chunked.attrs["success"] == 1
    for name in ("displacement", "velocity", "absolute_acceleration", "base_shear",
                 "temperature", "mu", "heat_flux", "energy_error"):
        np.testing.assert_array_equal(chunked[name].values, whole[name].values, err_msg=name)
    assert peaks(chunked) | {"wall_time": 0} == peaks(whole) | {"wall_time": 0}
