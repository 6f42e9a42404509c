"""Bad building files through ``dcfpb run``: nothing silently wrong.

Each case is the example building (``examples/five_storey.toml``) with one value, key or byte
changed: a count of 2.7, ``true`` or 0, a zero slider diameter or period, strings, booleans,
dates and nested arrays where numbers belong, numbers out of range in every section (friction
parameters of models the file does not choose included), unknown keys and sections, a section
that is not a table, text that is not TOML, and files that are not UTF-8. Each runs through the
CLI entry point and must exit with status 2 before any work, stderr naming the file, the
section and the key (or the problem with the bytes) and what is allowed. Settings without
effect (``alpha`` under Newmark) are accepted with a warning; the warning prints as one line.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from dcfpb.cli import main
from structures.config import ConfigWarning, load_config

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
EXIT_BAD_INPUT = 2


def _changed(tmp_path: Path, pattern: str, replacement: str, *more: str) -> Path:
    """The example with the first match of ``pattern`` replaced (and of each further pair of
    pattern and replacement in ``more``)."""
    text = EXAMPLE.read_text(encoding="utf-8")
    pairs = [(pattern, replacement), *zip(more[::2], more[1::2], strict=True)]
    for old, new in pairs:
        text, n = re.subn(old, new, text, count=1, flags=re.MULTILINE)
        assert n == 1, old
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _refused(path: Path, capsys, *expected: str) -> str:
    assert main(["run", str(path), "--record", str(RECORD)]) == EXIT_BAD_INPUT
    captured = capsys.readouterr()
    assert captured.out == ""  # nothing ran
    err = captured.err
    assert err.startswith("dcfpb run: error: ") and err.count("\n") == 1, err
    assert str(path) in err, err
    for text in expected:
        assert text in err, (text, err)
    return err


# (line pattern, replacement, what stderr must name: section and key, range or type, value)
VALUES = {
    "count 2.7": (r"^count = 6$", "count = 2.7",
                  ("[bearing] 'count'", "an integer in [1, 10000]", "Got 2.7 (a float)")),
    "count true": (r"^count = 6$", "count = true",
                   ("[bearing] 'count'", "an integer in [1, 10000]", "Got true (a boolean)")),
    "count 0": (r"^count = 6$", "count = 0",
                ("[bearing] 'count'", "[1, 10000]", "Got 0 (an integer)")),
    "count string": (r"^count = 6$", 'count = "6"',
                     ("[bearing] 'count'", "[1, 10000]", 'Got "6" (a string)')),
    "count 6.0": (r"^count = 6$", "count = 6.0",
                  ("[bearing] 'count'", "an integer", "Got 6.0 (a float)")),
    "slider diameter 0": (r"^slider_diameter = 0.3$", "slider_diameter = 0",
                          ("[bearing] 'slider_diameter'", "a number in [0.001, 10]", "Got 0")),
    "slider diameter boolean": (r"^slider_diameter = 0.3$", "slider_diameter = true",
                                ("[bearing] 'slider_diameter'", "[0.001, 10]",
                                 "Got true (a boolean)")),
    "effective radius nan": (r"^effective_radius = 4.5$", "effective_radius = nan",
                             ("[bearing] 'effective_radius'", "[0.001, 10000] or inf",
                              "Got nan")),
    "capacity array": (r"^displacement_capacity = 0.6$", "displacement_capacity = [0.6]",
                       ("[bearing] 'displacement_capacity'", "(0, 10]",
                        "Got [0.6] (an array)")),
    "period 0": (r"^fixed_base_period = 0.5$", "fixed_base_period = 0",
                 ("[building] 'fixed_base_period'", "[0.001, 100]", "Got 0 (an integer)")),
    "period negative": (r"^fixed_base_period = 0.5$", "fixed_base_period = -0.5",
                        ("[building] 'fixed_base_period'", "[0.001, 100]", "Got -0.5")),
    "nested masses": (r"^floor_masses = .*$", "floor_masses = [[400e3, 400e3], [400e3]]",
                      ("[building] 'floor_masses'", "numbers in (0, 1e+10]",
                       "(an array) at index 0")),
    "string masses": (r"^floor_masses = .*$", 'floor_masses = "heavy"',
                      ("[building] 'floor_masses'", "an array of 1 to 1000 numbers",
                       '"heavy" (a string)')),
    "table mass": (r"^base_mass = 500e3$", "base_mass = {value = 500e3}",
                   ("[building] 'base_mass'", "(0, 1e+10]", "(a table)")),
    "negative base mass": (r"^base_mass = 500e3$", "base_mass = -5",
                           ("[building] 'base_mass'", "(0, 1e+10]", "Got -5")),
    "profile": (r'^stiffness_profile = "uniform"$', 'stiffness_profile = "parabolic"',
                ("[building] 'stiffness_profile'", '"uniform", "triangular", "storey_shear"',
                 '"parabolic"')),
    "stiffnesses per floor": (r"^# storey_stiffnesses = .*$",
                              "storey_stiffnesses = [1.2e9, 1.1e9]",
                              ("[building] 'storey_stiffnesses'", "one value per floor (5",
                               "Got 2 values")),
    "rayleigh one ratio": (r"^ratios = \[0.02, 0.02\]$", "ratios = [0.02]",
                           ("[building.damping] 'ratios'", "an array of 2 numbers in [0, 1)",
                            "Got [0.02]")),
    "same modes": (r"^modes = \[1, 2\]$", "modes = [1, 1]",
                   ("[building.damping] 'modes'", "2 distinct mode numbers in [1, 5]",
                    "Got [1, 1]")),
    "refinement of another model": (r"^refinement = 0.5$", "refinement = -3",
                                    ("[friction] 'refinement'", "a number in (0, 2]",
                                     "Got -3")),
    "design velocity string": (r"^design_velocity = 0.4$", 'design_velocity = "fast"',
                               ("[friction] 'design_velocity'", "[0, 100]", '"fast"')),
    "mu0 of another model": (r"^# mu0 = 0.041$", "mu0 = 1.5",
                             ("[friction] 'mu0'", "(0, 1]", "Got 1.5")),
    "temperature": (r"^initial_temperature = 20.0$", "initial_temperature = -300",
                    ("[friction] 'initial_temperature'", "[-273.15, 1000]", "Got -300")),
    "model": (r'^model = "precise"$', 'model = "exact"',
              ("[friction] 'model'", '"precise", "simplified", "constant"', '"exact"')),
    "dt 0": (r"^dt = 0.005$", "dt = 0",
             ("[analysis] 'dt'", "a number in (0, 1]", "Got 0 (an integer)")),
    "dt date": (r"^dt = 0.005$", "dt = 1979-05-27",
                ("[analysis] 'dt'", "(0, 1]", "(a date)")),
    "alpha out of range": (r'^integrator = "newmark"$', 'integrator = "hht"\nalpha = 0.5',
                           ("[analysis] 'alpha'", "[-1/3, 0]", "Got 0.5")),
    "integrator": (r'^integrator = "newmark"$', 'integrator = "euler"',
                   ("[analysis] 'integrator'", '"newmark", "hht"', '"euler"')),
    "name number": (r"^name = .*$", "name = 5", ("[top] 'name'", "a string", "Got 5")),
}


@pytest.mark.parametrize("case", VALUES, ids=list(VALUES))
def test_bad_value_is_refused_by_file_section_key_and_range(case, tmp_path, capsys):
    pattern, replacement, expected = VALUES[case]
    _refused(_changed(tmp_path, pattern, replacement), capsys, *expected)


KEYS = {
    "typo": (r"^slider_diameter = ", "slider_diametre = ",
             ("unknown key(s) 'slider_diametre' (did you mean 'slider_diameter'?) in [bearing]",
              "allowed: ['count', 'displacement_capacity'")),
    "unknown section": (r"^\[analysis\]$", "[solver]\ntolerance = 1e-8\n[analysis]",
                        ("unknown key(s) 'solver' in [top]", "allowed: ['analysis'")),
    "section not a table": (r"^\[building.damping\]\n(?:#.*\n)*kind = .*\nratios = .*\n"
                            r"modes = .*\n", "", r"^base_mass = 500e3$",
                            "base_mass = 500e3\ndamping = 0.02",
                            ("[building] 'damping' must be a table", "Got 0.02 (a float)")),
    "missing key": (r"^floor_masses = .*$", "", ("[building] needs 'floor_masses'",)),
    "not toml": (r"^count = 6$", "count = = 6", ("not valid TOML", "line")),
}


@pytest.mark.parametrize("case", KEYS, ids=list(KEYS))
def test_bad_key_or_section_is_refused_by_name(case, tmp_path, capsys):
    *changes, expected = KEYS[case]
    _refused(_changed(tmp_path, *changes), capsys, *expected)


def test_cp1252_file_is_refused_by_byte_and_offset(tmp_path, capsys):
    text = EXAMPLE.read_text(encoding="utf-8").replace('name = "five-storey',
                                                       'name = "Gebäude, five-storey')
    path = tmp_path / "cp1252.toml"
    path.write_bytes(text.encode("cp1252"))
    offset = text.encode("cp1252").index(b"\xe4")
    _refused(path, capsys, f"not UTF-8 text (byte 0xe4 at offset {offset}); save it as UTF-8")


def test_utf16_file_is_refused_not_guessed(tmp_path, capsys):
    path = tmp_path / "utf16.toml"
    path.write_bytes(EXAMPLE.read_text(encoding="utf-8").encode("utf-16"))
    _refused(path, capsys, "not UTF-8 text (byte 0xff at offset 0)")


def test_utf8_with_and_without_bom_give_the_same_building(tmp_path):
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + EXAMPLE.read_bytes())
    with_bom, plain = load_config(path), load_config(EXAMPLE)
    assert with_bom.name == plain.name and with_bom.n_bearings == plain.n_bearings == 6
    assert with_bom.friction == plain.friction and with_bom.dt == plain.dt
    assert (with_bom.building.storey_stiffnesses == plain.building.storey_stiffnesses).all()


def test_missing_file_is_named(tmp_path, capsys):
    _refused(tmp_path / "absent.toml", capsys, "no such building file")


def test_alpha_under_newmark_is_accepted_with_a_warning(tmp_path, capsys):
    path = _changed(tmp_path, r"^# alpha = -0.05$", "alpha = -0.1")
    with pytest.warns(ConfigWarning, match=r"\[analysis\] 'alpha' is ignored: it applies to "
                      r'integrator = "hht" only'):
        # the record is missing: the run stops there, after the file was read
        assert main(["run", str(path), "--record", str(tmp_path / "none.at2")]) == 2
    assert "none.at2" in capsys.readouterr().err


def test_warning_prints_as_one_line_on_stderr(tmp_path):
    path = _changed(tmp_path, r"^# alpha = -0.05$", "alpha = -0.1")
    env = {**os.environ, "PYTHONPATH": str(REPO), "DCFPB_COMPILE_AHEAD": "0"}
    done = subprocess.run([sys.executable, "-m", "dcfpb.cli", "run", str(path), "--record",
                           str(tmp_path / "none.at2")], capture_output=True, text=True, env=env,
                          timeout=120)
    assert done.returncode == EXIT_BAD_INPUT
    lines = done.stderr.splitlines()
    assert lines[0] == (f"dcfpb run: warning: {path}: [analysis] 'alpha' is ignored: it applies "
                        'to integrator = "hht" only, and this file runs "newmark".')
    assert len(lines) == 2 and lines[1].startswith("dcfpb run: error: ")
