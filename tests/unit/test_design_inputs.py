"""The one resolver of an analysis's site, lambda and R (structures.design.response.design_inputs:
as given, else the building file's [design], else the caller's default, else the caller's
message) and the one check of the 17.3.2 suite size (check_suite_size, in the caller's words),
which `dcfpb design`, `dcfpb prototype` and structures.design.design share.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from dcfpb.common.errors import InputError, InputTypeError
from structures.config import load_config
from structures.design import PropertyModification, Site
from structures.design.response import check_suite_size, design_inputs

PLAN_FILE = Path(__file__).resolve().parents[2] / "examples" / "five_storey_plan.toml"


@pytest.fixture(scope="module")
def bare():
    return load_config(PLAN_FILE)  # no [design] table


@pytest.fixture
def with_table(tmp_path):
    path = tmp_path / "building.toml"
    path.write_text(PLAN_FILE.read_text() + "\n[design]\nlambda_max = 1.3\nlambda_min = 0.85\n"
                    "S_MS = 1.0\nS_M1 = 0.4\nR = 2.0\n")
    return load_config(path)


def test_what_is_given_wins_over_the_file_and_the_file_over_the_defaults(with_table):
    site, lam, R = design_inputs(with_table)
    assert (site.S_MS, lam.lambda_max, R) == (1.0, 1.3, 2.0)
    site, lam, R = design_inputs(with_table, (1.5, 0.6, 8.0), (1.8, 0.6), 1.5,
                                 defaults={"R": 3.0})
    assert (site, lam.lambda_min, R) == (Site(1.5, 0.6, 8.0), 0.6, 1.5)


def test_defaults_fill_what_neither_gives_and_the_callers_message_names_the_rest(bare):
    _, lam, R = design_inputs(bare, Site(1.0, 0.4), defaults={
        "lambda": PropertyModification.overall(1.0, 1.0), "R": 2.0})
    assert (lam.lambda_max, R) == (1.0, 2.0)
    with pytest.raises(InputError, match="The 'site' parameter of design must be given"):
        design_inputs(bare)
    with pytest.raises(InputError, match=r"^--R must be given$"):
        design_inputs(bare, Site(1.0, 0.4), (1.8, 0.6), missing={"R": "--R must be given"})
    with pytest.raises(InputTypeError, match="'site' parameter of design must be a Site"):
        design_inputs(bare, "1.0,0.4", (1.8, 0.6), 2.0)


def test_the_suite_size_rule_in_the_callers_words():
    assert check_suite_size(7, False, str) is None
    rule = "ASCE/SEI 7-16 17.3.2 asks for at least 7 pairs of ground motions"
    assert check_suite_size(5, True, str) == rule
    with pytest.raises(InputError, match=r"^--pairs m\.csv: 5 pairs, but ASCE/SEI 7-16 17\.3\.2"):
        check_suite_size(5, False, lambda r: f"--pairs m.csv: 5 pairs, but {r}.")
