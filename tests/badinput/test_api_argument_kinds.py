"""The public Python API with an argument of the wrong kind (issue 22, part 5, point 2).

For each main function exported by ``groundmotions``, ``isolator`` and ``structures`` (and the
suite's ``Suite`` and ``run_suite``), every argument in turn is replaced by an object of no use
(neither a number, a string, a path, an array nor a record): the call must raise
:class:`~dcfpb.common.errors.InputError` (an ``InputTypeError``, also a ``TypeError``, for the
wrong kind) whose message names that argument, before any work, never an ``AttributeError`` or a
bare ``TypeError`` from deep inside (which the command line would report as an internal error).
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from dcfpb.common.errors import InputError

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
PERIODS = np.array([0.5, 1.0])


class Useless:
    """An argument of no kind the API takes."""

    def __repr__(self) -> str:
        return "<Useless>"


def _motion():
    from groundmotions import GroundMotion, load_bundled

    record = load_bundled("elcentro")
    return GroundMotion(record.acceleration[:200], record.dt, name="short")


def _pair():
    from groundmotions import GroundMotionPair

    return GroundMotionPair(_motion(), _motion())


def _config():
    from structures import load_config

    return load_config(EXAMPLE)


def _bearing():
    from isolator import protocol_bearing

    return protocol_bearing("constant")


@functools.cache
def _results():
    """A short run and its fixed base (computed once)."""
    from structures import run, run_fixed_base

    result = run(EXAMPLE, _motion(), model="constant", floor_spectra=False)
    return result, run_fixed_base(_config().building, _motion(), dt=result.attrs["dt"])


def _manifest(tmp_path: Path) -> Path:
    path = tmp_path / "pairs.csv"
    if tmp_path.is_dir():
        path.write_text(f"name,x,y\nelcentro,{RECORD},{RECORD}\n")
    return path


def _calls(tmp_path: Path) -> dict[str, tuple[Callable[..., Any], dict[str, Any]]]:
    """Each function and good arguments for it (by name)."""
    import groundmotions as gm
    import isolator as iso
    import structures as st
    from structures.suites import Suite, run_suite

    m = _motion()
    a = m.acceleration
    target = gm.asce7_design_spectrum(1.0, 0.6, 8.0)
    return {
        "arias_intensity": (gm.arias_intensity, {"motion": m}),
        "asce7_design_spectrum": (gm.asce7_design_spectrum,
                                  {"S_DS": 1.0, "S_D1": 0.6, "T_L": 8.0}),
        "baseline_corrected": (gm.baseline_corrected, {"motion": m, "order": 1}),
        "filtered": (gm.filtered, {"motion": m, "low": 0.1, "order": 4}),
        "isolated_period_range": (gm.isolated_period_range,
                                  {"lower_bound_period": 2.0, "upper_bound_period": 3.0}),
        "load_bundled": (gm.load_bundled, {"name": "elcentro"}),
        "parse_units": (gm.parse_units, {"text": "g"}),
        "peak_ground_values": (gm.peak_ground_values, {"acceleration": a, "dt": 0.02}),
        "read_pair": (gm.read_pair, {"x_path": RECORD, "y_path": RECORD}),
        "read_pair_manifest": (gm.read_pair_manifest, {"path": _manifest(tmp_path)}),
        "read_peer_at2": (gm.read_peer_at2, {"path": RECORD}),
        "read_record": (gm.read_record, {"path": RECORD}),
        "resampled": (gm.resampled, {"motion": m, "dt": 0.01}),
        "response_spectra": (gm.response_spectra, {"accelerations": a[:, None], "dt": 0.02,
                                                   "periods": PERIODS, "damping": 0.05}),
        "response_spectrum": (gm.response_spectrum, {"acceleration": a, "dt": 0.02,
                                                     "periods": PERIODS, "damping": 0.05}),
        "rotd_spectra": (gm.rotd_spectra, {"pair": _pair(), "periods": PERIODS,
                                           "damping": 0.05}),
        "scale_suite": (gm.scale_suite, {"motions": [m], "target": target,
                                         "period_range": (1.0, 2.0)}),
        "sdof_response": (gm.sdof_response, {"acceleration": a, "dt": 0.02,
                                             "periods": PERIODS, "damping": 0.05}),
        "significant_duration": (gm.significant_duration, {"motion": m}),
        "spectrum": (gm.spectrum, {"motion": m, "periods": PERIODS, "damping": 0.05}),
        "suite_spectra": (gm.suite_spectra, {"motions": [m], "periods": PERIODS,
                                             "damping": 0.05}),
        "velocity_and_displacement": (gm.velocity_and_displacement,
                                      {"acceleration": a, "dt": 0.02}),
        "zero_residuals": (gm.zero_residuals, {"motion": m, "order": 3}),
        "cycle_characteristics": (iso.cycle_characteristics,
                                  {"displacement": [0.0, 0.1, 0.0, -0.1, 0.0],
                                   "force": [0.0, 1.0, 0.0, -1.0, 0.0]}),
        "friction_model": (iso.friction_model, {"model": "constant", "slider_diameter": 0.3,
                                                "design_pressure": 60e6,
                                                "design_velocity": 0.4}),
        "orbit": (iso.orbit, {"kind": "circle", "amplitude": 0.1, "period": 2.0, "cycles": 1,
                              "dt": 0.05}),
        "protocol_bearing": (iso.protocol_bearing, {"model": "constant"}),
        "run_orbit": (iso.run_orbit, {"bearing": _bearing(),
                                      "orbit": iso.orbit("circle", 0.1, 2.0, 1, 0.05)}),
        "run_test": (iso.run_test, {"bearing": _bearing(), "time": [0.0, 0.1],
                                    "displacement": [0.0, 0.01]}),
        "sine": (iso.sine, {"amplitude": 0.1, "period": 2.0, "cycles": 1, "dt": 0.05}),
        "wind_cycles": (iso.wind_cycles, {"amplitude": 0.01}),
        "default_step": (st.default_step, {"record_dt": 0.02}),
        "load_config": (st.load_config, {"path": EXAMPLE}),
        "peaks": (st.peaks, {"result": None}),
        "ratios_to_fixed_base": (st.ratios_to_fixed_base, {"result": None, "fixed_base": None}),
        "with_floor_spectra": (st.with_floor_spectra, {"result": None}),
        "run": (st.run, {"config": EXAMPLE, "motion": m, "model": "constant",
                         "integrator": "newmark", "dt": 0.01, "scale": 1.0}),
        "run_building": (st.run_building, {"building": _config().building,
                                           "bearing": dataclasses.replace(
                                               _config().bearing("constant"), axial_load=None),
                                           "motion": m,
                                           "integrator": "newmark", "n_bearings": 4,
                                           "dt": 0.01}),
        "run_fixed_base": (st.run_fixed_base, {"building": _config().building, "motion": m,
                                               "dt": 0.01}),
        "Suite": (Suite, {"config": _config(), "motions": [RECORD], "models": ["constant"],
                          "scales": [1.0]}),
        "run_suite": (run_suite, {"suite": None, "out_dir": tmp_path / "suite"}),
    }


def _cases() -> list[tuple[str, str]]:
    names = _calls(Path("/nonexistent"))  # only the names: nothing is read here
    return [(function, argument) for function, (_, kwargs) in names.items()
            for argument in kwargs]


CASES = _cases()


@pytest.mark.parametrize(("function", "argument"), CASES,
                         ids=[f"{f}-{a}" for f, a in CASES])
def test_an_argument_of_the_wrong_kind_is_refused_by_name(function, argument, tmp_path):
    call, kwargs = _calls(tmp_path)[function]
    if function in ("peaks", "ratios_to_fixed_base", "with_floor_spectra"):
        result, fixed = _results()
        kwargs = {"result": result} | ({"fixed_base": fixed} if "fixed_base" in kwargs else {})
    elif function == "run_suite":
        from structures.suites import Suite

        kwargs["suite"] = Suite(_config(), [RECORD], models=["constant"])
    with pytest.raises(InputError) as caught:
        call(**(kwargs | {argument: Useless()}))
    assert f"'{argument}'" in str(caught.value) or f" {argument} " in str(caught.value), \
        str(caught.value)
