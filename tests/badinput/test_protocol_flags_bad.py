"""``dcfpb protocol``: a load in the wrong unit is refused naming the flag, its unit, the range
and the value given; a friction flag the chosen model does not use is a warning (issue 22)."""

from __future__ import annotations

import os
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError, InputWarning
from isolator.experiments import protocol_bearing

REPO = Path(__file__).resolve().parents[2]
SHORT = ["protocol", "--cycles", "1", "--period", "1.0", "--dt", "0.05", "--amplitude", "0.05"]


@pytest.mark.parametrize("flags, expected", [
    (["--pressure", "60"], ("'--pressure'", "[1e+06, 2e+08]", "Got 60.0", "Pa (1 to 200 MPa)",
                            "give 6e+07")),
    (["--pressure", "0.5e6"], ("'--pressure'", "Got 500000.0", "0.5 MPa")),
    (["--pressure", "3e8"], ("'--pressure'", "[1e+06, 2e+08]", "Got 300000000.0", "Pa")),
    (["--axial-load", "4200"], ("'--axial-load'", "[10000, inf)", "Got 4200.0",
                                "is N (at least 10 kN)", "4.2 kN", "give 4.2e+06")),
    (["--axial-load", "0"], ("'--axial-load'", "[10000, inf)", "Got 0.0", "N")),
], ids=["pressure-60-pa", "pressure-below-1-mpa", "pressure-above-200-mpa",
        "axial-load-4200-n", "axial-load-0"])
def test_a_load_outside_its_range_is_refused_with_its_unit(flags, expected, capsys):
    assert main([*SHORT, *flags]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    for text in expected:
        assert text in captured.err, (text, captured.err)


def test_the_help_states_the_units(capsys):
    with pytest.raises(SystemExit):
        main(["protocol", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "contact pressure on the slider [Pa], in [1e6, 200e6]" in text
    assert "axial load [N], at least 1e4 (10 kN)" in text


@pytest.mark.parametrize("model, flag, value", [
    ("precise", "--mu0", "0.05"), ("simplified", "--mu0", "0.05"),
    ("constant", "--refinement", "0.7"), ("precise", "--refinement", "0.7"),
    ("constant", "--mu-t0", "0.06"),
])
def test_a_flag_the_model_does_not_use_is_a_warning(model, flag, value, capsys):
    with pytest.warns(InputWarning) as caught:
        assert main([*SHORT, "--model", model, flag, value, "--json"]) == 0
    assert len(caught) == 1
    assert str(caught[0].message).startswith(
        f"{flag} {value} has no effect with --model {model}: it applies to --model ")


@pytest.mark.parametrize("model, flag", [("constant", "--mu0"), ("simplified", "--refinement"),
                                         ("precise", "--mu-t0")])
def test_a_flag_the_model_uses_gives_no_warning(model, flag, capsys):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert main([*SHORT, "--model", model, flag, "0.05", "--json"]) == 0
    assert not [w for w in caught if issubclass(w.category, InputWarning)]
    assert capsys.readouterr().err == ""


def test_the_warning_prints_as_one_line_on_stderr():
    env = {**os.environ, "PYTHONPATH": str(REPO), "DCFPB_COMPILE_AHEAD": "0"}
    done = subprocess.run([sys.executable, "-m", "dcfpb.cli", *SHORT, "--model", "constant",
                           "--refinement", "0.7", "--json"], capture_output=True, text=True,
                          env=env, timeout=120)
    assert done.returncode == 0
    assert done.stderr == ("dcfpb protocol: warning: --refinement 0.7 has no effect with "
                           "--model constant: it applies to --model simplified only; it is "
                           "ignored.\n")


def test_a_flag_without_effect_is_still_checked(capsys):
    assert main([*SHORT, "--model", "precise", "--mu0", "2"]) == 2
    assert "'--mu0'" in capsys.readouterr().err
    assert main([*SHORT, "--model", "constant", "--refinement", "-1"]) == 2
    assert "'--refinement'" in capsys.readouterr().err


def test_the_library_warns_and_refuses_alike():
    with pytest.warns(InputWarning, match="'mu0' parameter of protocol_bearing applies to the "
                                          "constant model only; it has no effect with the "
                                          "precise model"):
        protocol_bearing("precise", mu0=0.05)
    with pytest.warns(InputWarning, match="'refinement'.*no effect with the constant model"):
        protocol_bearing("constant", refinement=0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        protocol_bearing("simplified", refinement=0.7, mu_t0=0.08)
        protocol_bearing("constant", mu0=0.05, pressure=20e6)
    with pytest.raises(InputError, match=r"'pressure' parameter of protocol_bearing .* Got 60 "
                                         r"instead\. The unit of 'pressure' is Pa"):
        protocol_bearing("precise", pressure=60)
    with pytest.raises(InputError, match=r"'axial_load' .* is N \(at least 10 kN\)"):
        protocol_bearing("precise", axial_load=4200.0)
    with pytest.raises(InputError, match="not both"):
        protocol_bearing("precise", axial_load=4.2e6, pressure=60e6)


@pytest.mark.parametrize("flag", ["--resample", "--truncate"])
def test_run_pair_flags_without_a_pair_are_a_warning(flag, tmp_path, capsys):
    example = REPO / "examples" / "five_storey.toml"
    missing = tmp_path / "none.at2"  # the run stops at the record, after the flags' check
    with pytest.warns(InputWarning, match=f"{flag} has no effect without --record-y"):
        assert main(["run", str(example), "--record", str(missing), flag]) == 2
    assert "none.at2" in capsys.readouterr().err


def test_compare_opensees_bearing_mu_t0_with_the_constant_model_is_a_warning(capsys):
    with pytest.warns(InputWarning, match="--mu-t0 0.06 has no effect with --model constant"):
        status = main(["compare-opensees-bearing", *SHORT[1:], "--model", "constant", "--mu-t0",
                       "0.06", "--json"])
    assert status in (0, 2)  # 2: openseespy missing, said so
    capsys.readouterr()
