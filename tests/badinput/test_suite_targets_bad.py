"""Suite inputs in the wrong unit or range (issue 22): a target spectrum in %g, an ASCE 7
spectrum with S_DS in %g, scale factors no record needs, and property modifiers that push the
friction coefficient past 1, each refused naming the flag or file, before any run."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError, InputWarning
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions import load_bundled
from groundmotions.records import GroundMotion
from groundmotions.scaling import TargetSpectrum, asce7_design_spectrum, scale_suite
from structures.config import load_config
from structures.suites.suite import Suite, check_modifiers

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"


def _suite(tmp_path: Path, *flags: str) -> tuple[int, Path]:
    out = tmp_path / "out"
    status = main(["suite", str(EXAMPLE), "--records", str(tmp_path / "records"), "--out",
                   str(out), "--no-progress", *flags])
    return status, out


def test_a_target_csv_in_percent_g_is_refused_naming_the_file_and_line(tmp_path, capsys):
    target = tmp_path / "target.csv"
    target.write_text("period,sa\n0.1,80\n1.0,150\n4.0,40\n")
    status, out = _suite(tmp_path, "--target", str(target))
    assert status == 2 and not out.exists()
    err = capsys.readouterr().err
    for text in (f"--target {target}, line 2", "column 'sa' is in g", "at most 10 g",
                 "Got 80", "%g"):
        assert text in err, (text, err)


def test_a_target_csv_in_g_is_accepted(tmp_path):
    from dcfpb.cli.suite import read_target

    target = tmp_path / "target.csv"
    target.write_text("period,sa\n0.1,0.8\n1.0,1.5\n4.0,0.4\n")
    periods, sa = read_target(target)
    assert periods.tolist() == [0.1, 1.0, 4.0]
    assert sa.tolist() == [0.8, 1.5, 0.4]


@pytest.mark.parametrize("spec, name", [("asce7:100,60,8", "S_DS"), ("asce7:1.0,60,8", "S_D1"),
                                        ("asce7-mce:150,90,8", "S_DS")])
def test_an_asce7_target_in_percent_g_is_refused(tmp_path, capsys, spec, name):
    status, out = _suite(tmp_path, "--target", spec)
    assert status == 2 and not out.exists()
    err = capsys.readouterr().err
    for text in (f"--target {spec!r}", f"'{name}'", "(0, 5]", "in g"):
        assert text in err, (text, err)


def test_the_library_refuses_a_target_above_10_g():
    with pytest.raises(InputError, match=r"'sa' parameter of TargetSpectrum \(target\).*at most "
                                         r"98.0665 m/s\^2 \(10 g\)\. Got 1471 m/s\^2 \(150 g\) "
                                         r"at index 1"):
        TargetSpectrum([0.1, 1.0], [9.81, 150 * STANDARD_GRAVITY])
    with pytest.raises(InputError, match=r"'S_DS' parameter of asce7_design_spectrum .*\(0, 5\]"):
        asce7_design_spectrum(150.0, 0.6, 8.0)
    asce7_design_spectrum(5.0, 5.0, 8.0, level="mce")  # 7.5 g: the most allowed


def _records(amplitude: float) -> list[GroundMotion]:
    elcentro = load_bundled("elcentro")
    return [elcentro.scaled(amplitude),
            GroundMotion(elcentro.acceleration[::-1] * amplitude, elcentro.dt, "reversed")]


def test_a_scale_factor_above_100_is_refused_naming_the_record():
    target = asce7_design_spectrum(1.0, 0.6, 8.0)
    with pytest.raises(InputError, match=r"scale_suite: the scale factor of 'reversed' would be "
                                         r"\d+\.?\d*, above the limit of 100 \('max_factor'\): "
                                         r"the target"):
        scale_suite(_records(1e-3), target, (2.0, 5.0))
    with pytest.raises(InputError, match="above the limit of 20"):
        scale_suite(_records(0.02), target, (2.0, 5.0), max_factor=20.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        report = scale_suite(_records(1e-3), target, (2.0, 5.0), max_factor=None)
    assert report.scale_factors.max() > 100


def test_a_scale_factor_above_10_is_a_warning_and_below_none():
    target = asce7_design_spectrum(1.0, 0.6, 8.0)
    with pytest.warns(InputWarning, match=r"scale_suite: 2 scale factor\(s\) above 10, the "
                                          r"largest"):
        report = scale_suite(_records(0.1), target, (2.0, 5.0))
    assert 10 < report.scale_factors.max() < 100
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        report = scale_suite(_records(1.0), target, (2.0, 5.0))
    assert report.scale_factors.max() < 10
    assert np.all(report.scale_factors > 0)


@pytest.mark.parametrize("modifiers, allowed, model", [("100", "(0, 13.33]", "precise"),
                                                       ("0.8,30", "(0, 13.33]", "precise")])
def test_a_modifier_past_the_coefficient_names_the_flag(tmp_path, capsys, modifiers, allowed,
                                                        model):
    status, out = _suite(tmp_path, "--modifiers", modifiers)
    assert status == 2 and not out.exists()
    err = capsys.readouterr().err
    assert "ConstantFriction" not in err and "PTVFriction" not in err
    for text in ("'--modifiers' parameter of dcfpb suite", allowed, f"the {model} model's "
                 "'mu_t0' = 0.075", "Got "):
        assert text in err, (text, err)


def test_the_constant_model_alone_allows_larger_modifiers(tmp_path, capsys):
    status, _ = _suite(tmp_path, "--models", "constant", "--modifiers", "100")
    err = capsys.readouterr().err
    assert status == 2 and "(0, 24.39]" in err and "'mu0' = 0.041" in err
    config = load_config(EXAMPLE)
    check_modifiers(config, ["constant"], [20.0])  # 0.82: allowed


def test_the_suite_names_its_parameter():
    with pytest.raises(InputError, match=r"'property_modifiers' parameter of Suite must be in "
                                         r"\(0, 24\.39\]"):
        Suite(load_config(EXAMPLE), [REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"],
              models=("constant",), property_modifiers=(25.0,))
