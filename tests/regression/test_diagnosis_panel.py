"""The diagnosis on validation panels it was not tuned on: no false names, a ``none`` that
means none, ``unexplained`` when the true effect is withheld.

Two panels, each written from three truth sources (a numpy-only implementation written from
the paper, OpenSees elements, the package's own element) with the labels kept apart from the
data (``labels.json``, read only by the scorer, after diagnosing):

- the **tuning panel** (``validation/diagnosis/tuning/`` with its ``truths.py``): 58 cases
  in 29 tune/test pairs (the last 8 pairs: issue 21's four kinds). The thresholds in
  ``isolator/diagnosis/thresholds.json`` were chosen on its tune half (seed 2026) by
  ``validation/diagnosis/tune.py``; its test half is scored here with fresh noise (seed
  2028), never seen by the tuning;
- the **outside panel** (``validation/diagnosis/outside/`` with ``independent/``):
  68 cases designed and written separately (P25-P34: issue 21's four kinds), never used to
  choose anything; its test half (34 cases) is scored here.

Measured (openseespy 3.7.1.2, issue 21, one direction: the heat a named law implies, a play's
width scanned, see docs/diagnosis.md): tuning panel, test half seed 2028: 29/29 exactly
right, no false name, every no-effect case ``none``, leave-one-effect-out 24/27
``unexplained`` (18/19 on the earlier cases), median shrink 0.87. Outside panel, test half:
34/34 exactly right (was 32/34: a play beside heating called ``unexplained``, ``heating``
beside a true ``velocity`` on a precise baseline), no false name, leave-one-effect-out 30/31,
median shrink 0.84 (was 0.85: that velocity's shrink without the heating, 0.86 -> 0.81).
About 3 minutes (2 min 42 s measured before).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from isolator.diagnosis.thresholds import THRESHOLDS_FILE
from validation.diagnosis import outside as outside_panel
from validation.diagnosis import tuning as tuning_panel
from validation.diagnosis.outside.cases import ISSUE21_TRUTHS as ISSUE21_OUTSIDE
from validation.diagnosis.score import case_names, diagnose_cases, score, summarize
from validation.diagnosis.tuning.cases import ISSUE21_TRUTHS as ISSUE21_TUNING

TOLD = {"effective_radius", "slider_diameter", "axial_load", "baseline", "without"}


def _scores(folder) -> tuple[list[dict], dict]:
    diagnoses = diagnose_cases(folder, case_names(folder, "test"))
    labels = json.loads((folder / "labels.json").read_text())  # read after diagnosing
    rows = score(diagnoses, labels)
    return rows, summarize(rows)


@pytest.fixture(scope="module")
def tuning(tmp_path_factory):
    folder = tmp_path_factory.mktemp("tuning_panel")
    tuning_panel.write_panel(folder, seed=2028, half="test")
    return folder, *_scores(folder)


@pytest.fixture(scope="module")
def outside(tmp_path_factory):
    folder = tmp_path_factory.mktemp("outside_panel")
    outside_panel.write_panel(folder, seed=2026, half="test")
    return folder, *_scores(folder)


def test_thresholds_were_chosen_on_the_tune_half_only():
    chosen = json.loads(THRESHOLDS_FILE.read_text())["chosen_on"]
    assert chosen["half"] == "tune" and chosen["panel"]["half"] == "tune"
    assert chosen["panel"]["seed"] == 2026


def test_the_panels_cover_the_designs_asked_for():
    for design in (tuning_panel.CASES, outside_panel.CASES):
        assert len(design) >= 40
        assert {c.source for c in design} == {"independent", "opensees", "package"}
        assert sum(not c.effects for c in design) >= 10
        assert {c.half for c in design} == {"tune", "test"}
    cases = tuning_panel.CASES
    singles = {c.effects[0] for c in cases if len(c.effects) == 1}
    assert singles >= {"heating", "velocity", "pressure", "breakaway", "wear", "stiffness",
                       "asymmetry", "backlash", "geometry", "lag"}
    assert {len(c.tests) for c in cases} >= {1, 2, 3, 4}
    assert {c.dt for c in cases} >= {0.01, 0.005, 0.002}  # 100-500 Hz
    nuisance = [c.lag_samples for c in cases if "lag" not in c.effects]
    assert max(nuisance) == 1.5 and min(nuisance) == 0.0
    noise = [c.noise for c in cases]
    assert min(noise) <= 0.003 and max(noise) >= 0.015 and any(c.colour for c in cases)
    amplitudes = [t.amplitude for c in cases for t in c.tests]
    assert min(amplitudes) <= 0.05 and max(amplitudes) >= 0.4
    assert {c.options.get("transition", "elastic-plastic") for c in cases} == {
        "rigid-plastic", "elastic-plastic", "smooth"}


@pytest.mark.parametrize("which", ["tuning", "outside"])
def test_labels_are_stored_apart_from_the_data(which, request):
    folder, _, _ = request.getfixturevalue(which)
    labels = json.loads((folder / "labels.json").read_text())
    for name in labels:
        files = sorted(p.name for p in (folder / name).iterdir())
        assert files[:2] == ["bearing.json", "manifest.csv"]
        assert all(f.startswith("test_") and f.endswith(".csv") for f in files[2:])
        assert set(json.loads((folder / name / "bearing.json").read_text())) <= TOLD


ISSUE21 = {"tuning": ISSUE21_TUNING, "outside": ISSUE21_OUTSIDE}


@pytest.mark.parametrize("which", ["tuning", "outside"])
def test_verdicts_on_the_held_out_half(which, request):
    _, rows, figures = request.getfixturevalue(which)
    earlier = [r for r in rows if r["truth"] not in ISSUE21[which]]
    wrong = [(r["case"], r["truth"], r["verdict"]) for r in earlier if not r["right"]]
    assert summarize(earlier)["exactly_right"] >= 0.95, wrong
    assert figures["false_names_in_no_effect_cases"] == 0, wrong
    assert figures["no_effect_cases"] >= 5
    for r in rows:
        if not r["effects"]:
            assert r["verdict"] == ["none"], r
            assert r["shrink"] == 0.0


@pytest.mark.parametrize("which", ["tuning", "outside"])
def test_the_kinds_of_issue_21_on_the_held_out_half(which, request):
    """A play a nuisance could swallow, a speed effect at several periods, residual inside the
    transition windows, a play beside heating, noise and a drift: never a false name, never
    `none` on an effect, at most one case not exactly right (issue 21 asks for at most 1 wrong
    in 30 over the whole outside test half; measured: none here on either panel, and none of
    the earlier cases of the outside test half, see docs/diagnosis.md)."""
    _, rows, _ = request.getfixturevalue(which)
    kinds = [r for r in rows if r["truth"] in ISSUE21[which]]
    assert len(kinds) >= 8
    assert not [r for r in kinds if r["false_names"]]
    assert not [r for r in kinds if r["effects"] and r["verdict"] == ["none"]]
    wrong = [(r["case"], r["truth"], r["verdict"]) for r in kinds if not r["right"]]
    assert len(wrong) <= 1, wrong


@pytest.mark.parametrize("which", ["tuning", "outside"])
def test_withholding_the_true_effect_leaves_it_unexplained(which, request):
    _, rows, _ = request.getfixturevalue(which)
    earlier = [r for r in rows if r["truth"] not in ISSUE21[which]]
    runs = [(r["case"], x) for r in earlier for x in r["loo"]]
    assert len(runs) >= 15
    assert summarize(earlier)["loo_unexplained"] >= 0.9, [run for run in runs
                                                          if not run[1]["right"]]
    # issue 21's kinds (measured 6 of 8 on the tuning panel: withholding the velocity of a
    # campaign at several periods names wear; withholding the play beside heating names a
    # breakaway standing in for it)
    kinds = [x for r in rows if r["truth"] in ISSUE21[which] for x in r["loo"]]
    assert np.mean([x["right"] for x in kinds]) >= 0.75, kinds


@pytest.mark.parametrize("which", ["tuning", "outside"])
def test_the_gap_shrinks_when_the_effect_is_named(which, request):
    _, rows, figures = request.getfixturevalue(which)
    assert figures["median_shrink"] >= 0.8
    for r in rows:
        if r["right"] and r["effects"]:
            assert r["gap_after"] < r["gap_before"], r


def test_cli_json_keeps_its_keys_and_adds_the_new_ones(tuning, capsys):
    import dcfpb.cli

    folder, _, _ = tuning
    labels = json.loads((folder / "labels.json").read_text())
    name = next(n for n, v in labels.items()
                if v["effects"] == ["backlash"] and v["truth"] not in ISSUE21_TUNING)
    told = json.loads((folder / name / "bearing.json").read_text())
    args = ["diagnose", "--manifest", str(folder / name / "manifest.csv"), "--model",
            told["baseline"], "--effective-radius", str(told["effective_radius"]),
            "--slider-diameter", str(told["slider_diameter"]), "--json"]
    assert dcfpb.cli.main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert {"baseline", "gap", "where", "effects", "verdict", "transition", "lag",
            "nuisance"} <= set(out)
    assert out["nuisance"]["lag"]["plausible_max"] > 0.0
    assert len(out["nuisance"]["yield_displacement"]["range"]) == 2
    assert out["verdict"][0] == "backlash"
    backlash = out["effects"][0]
    assert {"name", "gap_after", "shrink", "parameters", "confidence", "intervals",
            "acts_on"} <= set(backlash)
    assert backlash["shrink"] == pytest.approx(1.0 - backlash["gap_after"] / out["gap"]["value"])
    low, high = out["chosen"]["intervals"]["backlash"]["width"]
    assert low <= backlash["parameters"]["width"] <= high
    assert 0.0 <= out["chosen"]["confidence"]["backlash"] <= 1.0
    assert math.isfinite(out["transition"]["relative_rms"])
    assert np.isfinite(out["lag"]["samples"])
