"""The bidirectional panel's tune variants: drawn within the declared ranges, written as
scorable, labelled tune cases, each labelled effect above the label rule."""

from __future__ import annotations

import json

import numpy as np
import pytest

from validation.diagnosis.bidirectional.cases import (
    EFFECTS,
    LABEL_MIN,
    LAG_LABEL_MIN,
)
from validation.diagnosis.bidirectional.variants import (
    MAX_SAMPLES,
    SAMPLING,
    draw_case,
    parse_effects,
    write_variants,
)
from validation.diagnosis.bidirectional.write import main, make_orbit
from validation.diagnosis.score import case_names, load_case


def test_draws_stay_in_the_declared_ranges():
    """200 draws of every kind: sampling, noise, nuisances, transition, campaign, effects."""
    rng = np.random.default_rng(5)
    for _ in range(200):
        case = draw_case(rng)
        assert set(case.effects) <= set(EFFECTS)
        assert case.half == "tune"
        assert round(1.0 / case.dt) in SAMPLING
        assert 0.005 <= case.noise <= 0.012
        assert case.noise_kind in ("white", "ar1", "band")
        assert case.noise_kind != "ar1" or 0.8 <= case.rho <= 0.9
        assert 0.0 <= case.lag_samples <= 1.5
        assert case.actuator is None or 8.0 <= case.actuator[0] <= 25.0
        assert case.gain is None or 0.02 <= abs(case.gain[1]) <= 0.03
        assert case.stuck in (0, 20) and case.spikes in (0, 2, 3)
        base = case.spec["base"]
        assert base["transition"] in ("rigid-plastic", "elastic-plastic", "smooth")
        if base["transition"] != "rigid-plastic":
            assert 5.0e-4 <= base["yield_displacement"] <= 1.0e-3
        assert 2 <= len(case.tests) <= 3
        for k, run in enumerate(case.tests):
            assert 30.0 <= run.pressure <= 90.0 and 0.0 <= run.varying <= 0.45
            assert (run.rest is None) == (k == 0)
            if run.orbit[0] != "quake":  # an earthquake orbit is its 20 s window
                duration = make_orbit(run.orbit).duration
                assert duration <= max(MAX_SAMPLES * case.dt, 60.0) + 1.0
        if "pressure" in case.effects:  # the pressure must vary to show
            assert (len({r.pressure for r in case.tests}) > 1
                    or all(r.varying > 0 for r in case.tests))
        if "lag" in case.effects:
            assert case.spec["effects"]["lag"] >= LAG_LABEL_MIN


def test_parse_effects():
    assert parse_effects(None) is None
    assert parse_effects("none") == ()
    assert parse_effects("velocity, pressure") == ("pressure", "velocity")
    with pytest.raises(ValueError, match="unknown effect"):
        parse_effects("pressure,friction")


def test_variants_are_written_scorable_and_labelled(tmp_path):
    """A no-effect variant and a speed + pressure variant: files the scorer loads, labels
    of the tune half marked as variants, each labelled effect above the label rule."""
    write_variants(tmp_path, 1, seed=101, effects=(), first=2)
    write_variants(tmp_path, 1, seed=201, effects=("pressure", "velocity"), first=4)
    labels = json.loads((tmp_path / "labels.json").read_text())
    assert sorted(labels) == ["case_02", "case_04"]
    assert case_names(tmp_path, "tune") == ["case_02", "case_04"]
    assert case_names(tmp_path, "test") == []
    assert labels["case_02"]["effects"] == []
    assert labels["case_04"]["effects"] == ["pressure", "velocity"]
    for name, label in labels.items():
        assert label["half"] == "tune" and label["variant"] is True
        assert label["source"] == "bidirectional"
        design = label["design"]
        assert design["label_rule_met"] is True
        assert all(v >= LABEL_MIN for v in design["contribution"].values())
        assert set(design["contribution"]) == set(label["effects"])
        campaign, spec = load_case(tmp_path / name)
        assert len(campaign.tests) == len(design["tests"])
        assert campaign.tests[0].displacement.shape[1] == 2
        assert spec.model == "constant"
    panel = json.loads((tmp_path / "panel.json").read_text())
    assert panel["variants"] is True and panel["half"] == "tune"


def test_the_command_line_writes_tune_variants_only(tmp_path, capsys):
    assert main([str(tmp_path), "--variants", "1", "--seed", "101", "--first", "2",
                 "--effects", "none"]) == 0
    assert "case_02 none" in capsys.readouterr().out
    assert json.loads((tmp_path / "labels.json").read_text())["case_02"]["half"] == "tune"
    with pytest.raises(SystemExit):
        main([str(tmp_path), "--variants", "1", "--half", "test"])
    with pytest.raises(SystemExit):
        main([str(tmp_path), "--effects", "none"])
    with pytest.raises(SystemExit):
        main([str(tmp_path), "--variants", "1", "--effects", "friction"])
