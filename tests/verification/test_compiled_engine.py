"""The compiled engine reproduces the reference run of the building in one direction
(structures.compiled.integrator vs structures.integrators).

The two engines do the same arithmetic in a different order (a Sherman-Morrison solve instead
of LU, the window's heat history held as a group instead of point by point), so they agree to
round-off: 1e-9 relative is the bar, the examples reach about 1e-13.
"""

from __future__ import annotations

import dataclasses
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from groundmotions.bundled import load_bundled
from isolator.compiled.kernels import COMPILED
from isolator.factors import KumarFactors
from isolator.friction import PTVFriction
from isolator.heating import CentrePoint, MonitorLine
from structures.analysis import reference_history, run
from structures.compiled.engine import compiled_history, select_engine, unsupported
from structures.config import load_config
from structures.integrators import HHT, Newmark
from structures.isolated_building import IsolatedShearBuilding
from structures.model import LinearModel

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RELATIVE = 1e-9


@pytest.fixture(scope="module")
def config():
    return load_config(EXAMPLE)


@pytest.fixture(scope="module")
def motion():
    return load_bundled("elcentro")


def _relative_difference(a, b) -> float:
    a, b = np.asarray(a), np.asarray(b)
    return float(np.max(np.abs(a - b)) / np.max(np.abs(a)))


def _assert_same_run(reference, compiled, relative=RELATIVE):
    assert compiled.attrs["engine"] == "compiled"
    assert reference.attrs["engine"] == "reference"
    assert compiled.sizes == reference.sizes
    for name in ("bearing_displacement", "base_shear"):
        assert _relative_difference(reference[name], compiled[name]) <= relative, name
    for name in ("displacement", "absolute_acceleration", "temperature", "mu",
                 "energy_input", "energy_friction"):
        assert _relative_difference(reference[name], compiled[name]) <= 1e3 * relative, name
    for key in ("success", "message", "steps", "newton_iterations", "subdivisions"):
        assert compiled.attrs[key] == reference.attrs[key], key


@pytest.mark.parametrize("integrator", [Newmark(), HHT(alpha=-0.05)], ids=["newmark", "hht"])
@pytest.mark.parametrize("model", ["precise", "simplified", "constant"])
def test_compiled_engine_reproduces_the_reference_on_el_centro(config, motion, model,
                                                               integrator):
    bearing = config.bearing(model)
    kwargs = {"n_bearings": config.n_bearings, "dt": 0.005}
    reference = run(config.building, bearing, motion, integrator, engine="reference", **kwargs)
    compiled = run(config.building, bearing, motion, integrator, engine="compiled", **kwargs)
    _assert_same_run(reference, compiled)
    if isinstance(integrator, Newmark):  # the trapezoid work identity: round-off only
        assert compiled.attrs["energy_balance_error"] < 1e-9
    else:  # HHT's numerical dissipation, the same in both
        assert compiled.attrs["energy_balance_error"] == pytest.approx(
            reference.attrs["energy_balance_error"], rel=1e-6)


def test_the_dataset_has_the_reference_form(config, motion):
    short = motion.truncated(2.0)
    bearing = config.bearing("precise")
    a = run(config.building, bearing, short, n_bearings=config.n_bearings, engine="reference")
    b = run(config.building, bearing, short, n_bearings=config.n_bearings, engine="compiled")
    assert list(a.data_vars) == list(b.data_vars)
    assert list(a.coords) == list(b.coords)
    assert list(a.attrs) == list(b.attrs)
    for name in a.variables:
        assert a[name].dims == b[name].dims, name
        assert a[name].attrs == b[name].attrs, name
        assert a[name].dtype == b[name].dtype, name
    different = {k for k in a.attrs if k not in ("wall_time", "engine")
                 and a.attrs[k] != b.attrs[k]}
    assert different <= {"energy_balance_error"}  # round-off of an error of round-off


def _variant(bearing, **friction):
    return dataclasses.replace(bearing, friction=dataclasses.replace(bearing.friction,
                                                                      **friction))


@pytest.mark.parametrize("case", ["kumar", "pressure-velocity only", "no heating",
                                  "unrefined centre point", "spherical", "coarse line"])
def test_other_configurations_agree(config, motion, case):
    bearing = config.bearing("precise")
    integrator = HHT(alpha=-0.1)
    if case == "kumar":
        bearing = _variant(bearing, factors=KumarFactors())
    elif case == "pressure-velocity only":
        bearing = _variant(bearing, dependencies=("pressure", "velocity"))
        integrator = Newmark(gamma=0.6, beta=0.3025)
    elif case == "no heating":
        bearing = _variant(bearing, heating=None)
    elif case == "unrefined centre point":
        bearing = _variant(bearing, heating=CentrePoint(refinement=np.sqrt(np.pi) / 2))
    elif case == "spherical":
        bearing = dataclasses.replace(bearing, restoring="spherical")
    else:
        bearing = _variant(bearing, heating=MonitorLine(spacing=0.02))
    record = motion.truncated(12.0).scaled(1.5)
    kwargs = {"n_bearings": config.n_bearings, "dt": 0.005}
    reference = run(config.building, bearing, record, integrator, engine="reference", **kwargs)
    compiled = run(config.building, bearing, record, integrator, engine="compiled", **kwargs)
    _assert_same_run(reference, compiled)


def _histories(config, motion, model, **kwargs):
    building = IsolatedShearBuilding(config.building, config.bearing(model), config.n_bearings)
    acceleration = np.interp(0.005 * np.arange(1201), motion.time, motion.acceleration)
    args = (acceleration, 0.005, Newmark())
    reference = reference_history(building, *args, tolerance=1e-8, **kwargs)
    building = IsolatedShearBuilding(config.building, config.bearing(model), config.n_bearings)
    return reference, compiled_history(building, *args, tolerance=1e-8, **kwargs)


@pytest.mark.parametrize("model", ["precise", "constant"])
def test_step_halving_matches_the_reference(config, motion, model):
    """Two Newton iterations per attempt: the steps that need more are halved, as in the
    reference (the same depth-first order, the same interpolated ground acceleration)."""
    reference, compiled = _histories(config, motion, model, max_iterations=2,
                                     max_subdivisions=8)
    assert reference.result.success and compiled.result.success
    assert reference.result.subdivisions.sum() > (50 if model == "precise" else 0)
    assert np.array_equal(reference.result.subdivisions, compiled.result.subdivisions)
    assert np.array_equal(reference.result.iterations, compiled.result.iterations)
    u_ref, u = reference.result.displacement[:, 0], compiled.result.displacement[:, 0]
    assert _relative_difference(u_ref, u) <= RELATIVE
    assert _relative_difference(reference.bearings["force"], compiled.bearings["force"]) <= RELATIVE


def test_failure_is_reported_like_the_reference(config, motion):
    reference, compiled = _histories(config, motion, "precise", max_iterations=2,
                                     max_subdivisions=1)
    assert not reference.result.success and not compiled.result.success
    assert compiled.result.message == reference.result.message
    assert "did not converge" in compiled.result.message
    assert compiled.result.time.size == reference.result.time.size
    assert compiled.restoring.shape == reference.restoring.shape
    for name, values in reference.bearings.items():
        assert values.shape == compiled.bearings[name].shape, name


def test_leaving_the_monitor_line_ends_the_run_like_the_reference(config, motion):
    """A trial off the precise model's monitor line is a capacity failure, not an error: both
    engines stop at the same step with the same message (issue 12: one failure contract)."""
    from structures.analysis import resampled_record

    bearing = dataclasses.replace(config.bearing("precise"), displacement_capacity=0.02)
    acceleration, step = resampled_record(motion, 0.005)
    histories = [engine(IsolatedShearBuilding(config.building, bearing, config.n_bearings),
                        acceleration, step, Newmark(), tolerance=1e-8, max_subdivisions=6)
                 for engine in (reference_history, compiled_history)]
    reference, compiled = (h.result for h in histories)
    assert not reference.success and not compiled.success
    assert compiled.message == reference.message
    assert "has left the monitor line" in compiled.message
    assert "beyond the bearing's displacement_capacity 0.02 m" in compiled.message
    assert compiled.failure == reference.failure == "capacity"
    assert compiled.failed_at == reference.failed_at
    assert compiled.time.size == reference.time.size > 1


def test_engine_selection(config):
    model = IsolatedShearBuilding(config.building, config.bearing("precise"), 6)
    assert unsupported(model, Newmark()) is None
    assert select_engine("auto", model, Newmark()) == ("compiled" if COMPILED else "reference")
    assert select_engine("reference", model, Newmark()) == "reference"
    linear = LinearModel(np.eye(2), np.zeros((2, 2)), np.eye(2), np.ones(2))
    assert "LinearModel" in unsupported(linear, Newmark())

    class OwnFriction(PTVFriction):
        pass

    own = IsolatedShearBuilding(config.building, dataclasses.replace(
        config.bearing("precise"), friction=OwnFriction()), 6)
    assert select_engine("auto", own, Newmark()) == "reference"
    with pytest.raises(ValueError, match="'engine' parameter of run is 'compiled'"):
        select_engine("compiled", own, Newmark())
    with pytest.raises(ValueError, match="'engine'"):
        select_engine("fast", model, Newmark())


_FALLBACK = """
import json, sys
import numpy as np
from groundmotions.bundled import load_bundled
from isolator.compiled.kernels import COMPILED
from structures.analysis import run
from structures.config import load_config
from structures.integrators import HHT
config = load_config(sys.argv[1])
motion = load_bundled("elcentro").truncated(3.0)
out = {"compiled": COMPILED}
for model in ("precise", "constant"):
    for engine in ("compiled", "reference"):
        result = run(config.building, config.bearing(model), motion, HHT(alpha=-0.05),
                     n_bearings=config.n_bearings, dt=0.005, engine=engine)
        out[model, engine] = {name: result[name].values.tolist() for name in
                              ("bearing_displacement", "base_shear", "temperature")}
print(json.dumps({" ".join(key) if isinstance(key, tuple) else key: value
                  for key, value in out.items()}))
"""


def test_pure_python_fallback_equals_the_compiled_engine(config, motion):
    """DCFPB_DISABLE_NUMBA=1 runs the engine's own source as Python: the same numbers.

    Within Python the two engines agree to round-off (1e-15 here). Against the compiled run
    the kernels' own exp and power (numba's against numpy's, last bit) leave 2e-12 on this
    record, the same for the reference engine with and without numba.
    """
    env = {**os.environ, "DCFPB_DISABLE_NUMBA": "1", "PYTHONPATH": str(REPO)}
    done = subprocess.run([sys.executable, "-c", _FALLBACK, str(EXAMPLE)], capture_output=True,
                          text=True, env=env, check=True)
    fallback = json.loads(done.stdout)
    assert fallback["compiled"] is False
    short = motion.truncated(3.0)
    for model in ("precise", "constant"):
        compiled = run(config.building, config.bearing(model), short, HHT(alpha=-0.05),
                       n_bearings=config.n_bearings, dt=0.005, engine="compiled")
        python, reference = fallback[f"{model} compiled"], fallback[f"{model} reference"]
        for name, values in python.items():
            assert _relative_difference(reference[name], values) <= 1e-13, (model, name)
            assert _relative_difference(compiled[name], values) <= 1e-10, (model, name)


@pytest.mark.skipif(not COMPILED, reason="numba is disabled: there is no compiled original")
def test_python_original_of_the_loop_equals_the_compiled_one(config, motion):
    """``integrate.py_func`` (the loop in Python, its kernels compiled) agrees."""
    building = IsolatedShearBuilding(config.building, config.bearing("precise"), 6)
    acceleration = np.interp(0.005 * np.arange(201), motion.time, motion.acceleration)
    compiled = compiled_history(building, acceleration, 0.005, Newmark(), tolerance=1e-8,
                                max_subdivisions=6)
    building = IsolatedShearBuilding(config.building, config.bearing("precise"), 6)
    python = compiled_history(building, acceleration, 0.005, Newmark(), tolerance=1e-8,
                              max_subdivisions=6, python=True)
    assert np.array_equal(compiled.result.displacement, python.result.displacement)
    assert np.array_equal(compiled.bearings["temperature"], python.bearings["temperature"])
