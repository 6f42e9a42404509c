"""The bad-input panel, part 4 (issue 22): bearing-test flags, suite modifiers and targets,
plans and bearing geometry. Each case is one CLI call (``dcfpb.cli.main`` in process) or one
Python call on copies of the inputs in ``tmp_path``, and asserts (a) the exit status or the
exception class, (b) that the message names the flag, key, column or file concerned and (c)
that no input file and no earlier output changed and nothing new was written."""

from __future__ import annotations

import hashlib
import shutil
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError
from structures.config import ConfigError

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
PLAN = """
[plan]
bearing_coordinates = [[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], [0.0, -5.0],
                       [0.0, 5.0]]
eccentricity = [1.0, 0.5]
dimensions = [12.0, 10.0]
storey_heights = 3.5
"""
GOOD_COORDINATES = ("[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], [0.0, -5.0],\n"
                    "                       [0.0, 5.0]]")


@dataclass(frozen=True)
class Inputs:
    """The copies in ``tmp_path``: the example, the record, an earlier output, a folder."""

    folder: Path

    @property
    def building(self) -> Path:
        return self.folder / "building.toml"

    @property
    def record(self) -> Path:
        return self.folder / "record.at2"

    @property
    def earlier(self) -> Path:
        return self.folder / "earlier.csv"

    def variant(self, name: str, old: str = "", new: str = "", plan: bool = False) -> Path:
        """A building file: the example (with the ``[plan]`` table), ``old`` replaced."""
        text = EXAMPLE.read_text(encoding="utf-8")
        if plan:
            text += PLAN
        if old:
            assert old in text, old
            text = text.replace(old, new)
        path = self.folder / name
        path.write_text(text, encoding="utf-8")
        return path

    def target(self, rows: str) -> Path:
        path = self.folder / "target.csv"
        path.write_text(rows, encoding="utf-8")
        return path


@pytest.fixture
def inputs(tmp_path: Path) -> Inputs:
    shutil.copy(EXAMPLE, tmp_path / "building.toml")
    shutil.copy(RECORD, tmp_path / "record.at2")
    (tmp_path / "earlier.csv").write_text("time,displacement\n0.0,0.0\n", encoding="utf-8")
    (tmp_path / "records").mkdir()
    shutil.copy(RECORD, tmp_path / "records" / "elcentro.at2")
    return Inputs(tmp_path)


def _hashes(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


SHORT = ["--cycles", "1", "--period", "1.0", "--dt", "0.05", "--amplitude", "0.05"]


def _protocol(*flags: str) -> Callable[[Inputs], list[str]]:
    return lambda i: ["protocol", *SHORT, *flags, "--output", str(i.earlier), "--overwrite"]


def _suite(*flags: str, plan_old: str | None = None) -> Callable[[Inputs], list[str]]:
    def argv(i: Inputs) -> list[str]:
        if plan_old is None:
            building, source = i.building, ["--records", str(i.folder / "records")]
        else:
            building = i.variant("plan.toml", GOOD_COORDINATES, plan_old, plan=True)
            source = ["--pairs", str(i.folder / "pairs.csv")]
        return ["suite", str(building), *source, "--out", str(i.folder / "out"),
                "--no-progress", *flags]
    return argv


def _run(old: str, new: str, plan: bool = False) -> Callable[[Inputs], list[str]]:
    def argv(i: Inputs) -> list[str]:
        path = i.variant("bad.toml", old, new, plan=plan)
        return ["run", str(path), "--record", str(i.record), "--output",
                str(i.folder / "new.nc")]
    return argv


CLI = {  # id: (argv maker, exit status, names the message must hold)
    "protocol-pressure-60-pa": (_protocol("--pressure", "60"), 2,
                                ("'--pressure'", "Pa", "1 to 200 MPa")),
    "protocol-pressure-below-1-mpa": (_protocol("--pressure", "5e5"), 2, ("'--pressure'",)),
    "protocol-pressure-above-200-mpa": (_protocol("--pressure", "2.5e8"), 2,
                                        ("'--pressure'", "[1e+06, 2e+08]")),
    "protocol-pressure-nan": (_protocol("--pressure", "nan"), 2, ("'--pressure'",)),
    "protocol-pressure-inf": (_protocol("--pressure", "inf"), 2, ("'--pressure'",)),
    "protocol-axial-load-4200-n": (_protocol("--axial-load", "4200"), 2,
                                   ("'--axial-load'", "N", "10 kN")),
    "protocol-axial-load-negative": (_protocol("--axial-load=-4.2e6"), 2,
                                     ("'--axial-load'",)),
    "protocol-unused-mu0-out-of-range": (_protocol("--model", "precise", "--mu0", "1.5"), 2,
                                         ("'--mu0'",)),
    "protocol-unused-refinement-negative": (_protocol("--model", "constant", "--refinement",
                                                      "-0.5"), 2, ("'--refinement'",)),
    "protocol-unused-mu-t0-above-1": (_protocol("--model", "constant", "--mu-t0", "3"), 2,
                                      ("'--mu-t0'",)),
    "protocol-angle-without-orbit": (_protocol("--angle", "30"), 2, ("--angle", "--orbit")),
    "opensees-bearing-pressure-60-pa": (
        lambda i: ["compare-opensees-bearing", *SHORT, "--pressure", "60"], 2,
        ("'--pressure'", "Pa")),
    "suite-modifiers-100": (_suite("--modifiers", "100"), 2, ("'--modifiers'", "(0, 13.33]")),
    "suite-modifiers-constant-30": (_suite("--models", "constant", "--modifiers", "0.8,30"),
                                    2, ("'--modifiers'", "(0, 24.39]", "'mu0'")),
    "suite-modifiers-negative": (_suite("--modifiers", "-1"), 2, ("'--modifiers'",)),
    "suite-target-csv-in-percent-g": (
        lambda i: _suite("--target", str(i.target("period,sa\n0.1,40\n1.0,150\n")))(i), 2,
        ("target.csv", "line 2", "column 'sa'")),
    "suite-target-csv-in-cm-s2": (
        lambda i: _suite("--target", str(i.target("0.5,981\n2.0,300\n")))(i), 2,
        ("target.csv", "line 1", "10 g")),
    "suite-target-asce7-in-percent-g": (_suite("--target", "asce7:100,60,8"), 2,
                                        ("--target", "'S_DS'")),
    "suite-target-asce7-mce-s-d1-in-percent-g": (_suite("--target", "asce7-mce:1.0,60,8"), 2,
                                                 ("--target", "'S_D1'")),
    "suite-plan-two-bearings-at-one-point": (
        _suite(plan_old="[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], [0.0, -5.0], "
                        "[6.0, 5.0]]"), 2, ("plan.toml", "'bearing_coordinates'", "bearings 2 "
                                            "and 5")),
    "run-plan-two-bearings-at-one-point": (
        _run(GOOD_COORDINATES, "[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], "
             "[-6.0, -5.0002], [0.0, 5.0]]", plan=True), 2,
        ("bad.toml", "[plan] 'bearing_coordinates'", "bearings 0 and 4")),
    "run-plan-bearing-beyond-the-slab": (
        _run(GOOD_COORDINATES, "[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], "
             "[0.0, -5.0], [0.0, 7.0]]", plan=True), 2,
        ("bad.toml", "[plan] 'bearing_coordinates'", "'dimensions'", "along y")),
    "run-plan-eccentricity-beyond-the-plan": (
        _run("eccentricity = [1.0, 0.5]", "eccentricity = [8.0, 0.5]", plan=True), 2,
        ("bad.toml", "[plan] 'eccentricity'", "along x")),
    "run-plan-floor-eccentricity-beyond-the-plan": (
        _run("eccentricity = [1.0, 0.5]", "eccentricity = [[0.0, 0.0], [0.0, 0.0], [0.0, 0.0], "
             "[0.0, 0.0], [0.0, -6.0]]", plan=True), 2,
        ("bad.toml", "[plan] 'eccentricity'", "of floor 5")),
    "run-capacity-beyond-the-radius": (
        _run("displacement_capacity = 0.6", "displacement_capacity = 2.5"), 2,
        ("bad.toml", "[bearing] 'displacement_capacity'", "'effective_radius'")),
    "run-slider-as-wide-as-the-radius": (
        _run("slider_diameter = 0.3", "slider_diameter = 4.5"), 2,
        ("bad.toml", "[bearing] 'slider_diameter'", "'effective_radius' 4.5 m")),
}


@pytest.mark.parametrize("case", CLI, ids=list(CLI))
def test_cli_case(case, inputs, capsys):
    make, status, names = CLI[case]
    argv = make(inputs)
    before = _hashes(inputs.folder)
    assert main(argv) == status
    err = capsys.readouterr().err
    for name in names:
        assert name in err, (name, err)
    assert _hashes(inputs.folder) == before


def _scale_records(amplitude: float):
    from groundmotions import load_bundled
    from groundmotions.records import GroundMotion

    elcentro = load_bundled("elcentro")
    return [elcentro.scaled(amplitude),
            GroundMotion(elcentro.acceleration[::-1] * amplitude, elcentro.dt, "reversed")]


def _api_protocol(**kwargs):
    from isolator.experiments import protocol_bearing

    model = kwargs.pop("model", "precise")
    return lambda i: lambda: protocol_bearing(model, **kwargs)


def _api_load(*changes: tuple[str, str], plan: bool = False):
    """A building file with ``changes`` (old, new) written at preparation, then loaded."""
    from structures.config import load_config

    def prepare(i: Inputs):
        path = i.variant("bad.toml", plan=plan)
        text = path.read_text(encoding="utf-8")
        for old, new in changes:
            assert old in text, old
            text = text.replace(old, new)
        path.write_text(text, encoding="utf-8")
        return lambda: load_config(path)
    return prepare


def _now(call):
    """A call that needs nothing prepared."""
    return lambda i: lambda: call(i)


def _api_scale_suite(i):
    from groundmotions.scaling import asce7_design_spectrum, scale_suite

    scale_suite(_scale_records(1e-3), asce7_design_spectrum(1.0, 0.6, 8.0), (2.0, 5.0))


def _api_target(i):
    from groundmotions.scaling import TargetSpectrum

    TargetSpectrum([0.5, 1.0, 2.0], [9.81, 1471.0, 500.0], name="in cm/s^2")


def _api_asce7(i):
    from groundmotions.scaling import asce7_design_spectrum

    asce7_design_spectrum(150.0, 60.0, 8.0)


def _api_suite(i):
    from structures.config import load_config
    from structures.suites.suite import Suite

    Suite(load_config(i.building), [i.record], models=("simplified",),
          property_modifiers=(1.0, 14.0))


API = {  # id: (preparation returning the call, exception class, names the message holds)
    "api-protocol-bearing-pressure-60-pa": (_api_protocol(pressure=60.0), InputError,
                                            ("'pressure'", "Pa")),
    "api-protocol-bearing-axial-load-4200-n": (_api_protocol(axial_load=4200.0), InputError,
                                               ("'axial_load'", "N")),
    "api-protocol-bearing-unused-refinement-0": (
        _api_protocol(model="constant", refinement=0.0), InputError, ("'refinement'",)),
    "api-target-spectrum-in-cm-s2": (_now(_api_target), InputError,
                                     ("'sa'", "in cm/s^2", "index 1")),
    "api-asce7-s-ds-in-percent-g": (_now(_api_asce7), InputError, ("'S_DS'",)),
    "api-scale-factor-above-100": (_now(_api_scale_suite), InputError,
                                   ("'reversed'", "scale factor")),
    "api-suite-property-modifier-past-mu": (_now(_api_suite), InputError,
                                            ("'property_modifiers'", "simplified", "'mu_t0'")),
    "api-plan-base-eccentricity-beyond-the-plan": (
        _api_load(("storey_heights = 3.5", "storey_heights = 3.5\nbase_eccentricity = "
                   "[7.0, 0.0]"), plan=True), ConfigError,
        ("bad.toml", "[plan] 'base_eccentricity'")),
    "api-plan-bearings-at-one-point": (
        _api_load((GOOD_COORDINATES, "[[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0], "
                   "[0.0, 5.0], [0.0, 5.0]]"), plan=True), ConfigError,
        ("bad.toml", "'bearing_coordinates'", "bearings 4 and 5")),
    "api-default-capacity-beyond-a-small-radius": (
        _api_load(("displacement_capacity = 0.6", ""),
                  ("effective_radius = 4.5", "effective_radius = 1.0")), ConfigError,
        ("bad.toml", "[bearing] 'displacement_capacity'", "(the default)")),
    "api-capacity-beyond-the-radius": (
        _api_load(("effective_radius = 4.5", "effective_radius = 1.0")), ConfigError,
        ("bad.toml", "[bearing] 'displacement_capacity'", "0.5 m")),
}


@pytest.mark.parametrize("case", API, ids=list(API))
def test_api_case(case, inputs):
    prepare, kind, names = API[case]
    call = prepare(inputs)
    before = _hashes(inputs.folder)
    with pytest.raises(kind) as error:
        call()
    for name in names:
        assert name in str(error.value), (name, str(error.value))
    assert _hashes(inputs.folder) == before
