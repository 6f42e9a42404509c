"""The diagnosis of tests in two directions (issue 21): verdicts on synthetic orbit campaigns.

Campaigns of a circle and a figure-eight (two figure-eights at 6 s and 2 s for the speed
effect) are run through the package's bidirectional element with ``run_orbit`` by the
documented example ``examples/diagnose_2d_campaign.py``, each with one effect switched on
through the friction model's parameters or the load train, and sensor noise (force 0.4 % of
the peak |F|, displacement 10 um): the precise model's heating against a constant baseline,
the speed dependence, a play of 4 mm along x and 2 mm along y (no force on an axis while its
gap is open), a force channel 4 samples late. Checked: ``none`` on clean data with noise, each
single effect named alone (no other effect beside it; beside the play an ``unexplained`` may
stand), its parameters recovered, the shrink of the held-out gap reported, and the
command line's printed where / which / how far; and the element as baseline (the precise
model without speed and pressure factors) leaves no gap on its own data. About 40 s.
"""

from __future__ import annotations

import importlib.util
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from isolator.diagnosis.data import BearingRecord2D, Campaign2D
from isolator.diagnosis.two_directions import diagnose_2d

pytestmark = pytest.mark.slow

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "diagnose_2d_campaign.py"
SMALL = (("circle", 0.08, 4.0, 1), ("figure8", 0.10, 2.0, 2))
SPEEDS = (("figure8", 0.10, 6.0, 1), ("figure8", 0.10, 2.0, 2))


def _example():
    spec = importlib.util.spec_from_file_location("diagnose_2d_campaign", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def example():
    return _example()


def _campaign(example, effect: str, seed: int, orbits=SMALL) -> Campaign2D:
    tests = example.synthesise(effect, seed=seed, orbits=orbits)
    records = tuple(
        BearingRecord2D(f"{k + 1:02d}_{t['name']}", t["time"],
                        np.column_stack([t["displacement_x"], t["displacement_y"]]),
                        np.column_stack([t["force_x"], t["force_y"]]), t["axial_force"])
        for k, t in enumerate(tests))
    return Campaign2D(records, example.RADIUS, example.SLIDER)


def _summary(example, effect: str, seed: int = 5, orbits=SMALL) -> dict:
    return diagnose_2d(_campaign(example, effect, seed, orbits), "constant").to_json()


def _check_report(summary: dict) -> None:
    assert summary["dimension"] == 2
    for key in ("baseline", "gap", "where", "effects", "verdict", "transition", "lag",
                "orbits", "axes", "direction_changes"):
        assert key in summary
    assert summary["where"]["statement"]
    assert set(summary["where"]["axes"]) == {"x", "y"}
    # the nuisances and the transition's materiality as in one direction
    assert set(summary["nuisance"]) >= {"yield_displacement", "lag", "findings"}
    assert summary["nuisance"]["lag"]["plausible_max"] == 0.1
    assert {"score", "excess", "after_named"} <= set(summary["transition"])
    if summary["unexplained"] is not None:
        assert summary["unexplained"]["findings"]
    json.dumps(summary)  # plain JSON types


def test_no_effect_with_noise_is_none(example):
    summary = _summary(example, "none", seed=5)
    _check_report(summary)
    assert summary["verdict"] == ["none"]
    assert summary["chosen"] is None


@pytest.mark.parametrize("axis", [1, 0])
def test_a_gain_error_on_one_axis_and_coloured_noise_are_none(example, axis):
    """A 3 % gain on the y or the x load cell (its calibration) and AR(1) force noise (0.9)
    are nuisance: corrected as that load cell's gain, and measured beyond the noise's
    correlation."""
    scale = np.ones(2)
    scale[axis] = 1.03
    tests = example.synthesise("none", seed=5, orbits=SMALL, colour=0.9)
    records = tuple(
        BearingRecord2D(f"{k + 1:02d}_{t['name']}", t["time"],
                        np.column_stack([t["displacement_x"], t["displacement_y"]]),
                        np.column_stack([t["force_x"], t["force_y"]]) * scale,
                        t["axial_force"])
        for k, t in enumerate(tests))
    summary = diagnose_2d(Campaign2D(records, example.RADIUS, example.SLIDER),
                          "constant").to_json()
    assert summary["verdict"] == ["none"]
    found = [n for n in summary["baseline_notes"] if "force channel reads" in n]
    assert len(found) == 1 and found[0].startswith(f"the {'xy'[axis]} force channel reads +")
    assert 2.0 <= float(found[0].split("reads ")[1].split(" %")[0]) <= 4.0


def test_heating_on_the_2d_field_is_named(example):
    summary = _summary(example, "heating", seed=5)
    _check_report(summary)
    assert summary["verdict"] == ["heating"]
    chosen = summary["chosen"]
    assert chosen["shrink"] > 0.6
    sensitivity = chosen["parameters"]["heating"]["thermal_sensitivity"]
    assert 0.003 < sensitivity < 0.012  # the paper's Eq. 3: 0.007 / degC


def test_speed_dependence_is_named_on_the_speed(example):
    summary = _summary(example, "velocity", seed=6, orbits=SPEEDS)
    _check_report(summary)
    assert [n for n in summary["verdict"] if n != "unexplained"] == ["velocity"]
    chosen = summary["chosen"]
    assert chosen["shrink"] > 0.4
    drop = chosen["parameters"]["velocity"]["low_speed_drop"]
    assert 0.3 < drop < 0.8  # the paper's Eq. 2: 0.55


def test_play_per_axis_is_named_with_its_widths(example):
    summary = _summary(example, "backlash", seed=5)
    _check_report(summary)
    # an open gap reads zero force, so where the displacement noise moves a reversal by a
    # sample the axis's force N u / R is missed there: "unexplained" may stand beside it
    assert [n for n in summary["verdict"] if n != "unexplained"] == ["backlash"]
    widths = summary["chosen"]["parameters"]["backlash"]
    assert math.isclose(widths["width_x"], example.PLAY[0], rel_tol=0.25)
    assert math.isclose(widths["width_y"], example.PLAY[1], rel_tol=0.25)
    # the example's play is made without static friction on an open axis: the data choose
    # that model (the validation truth's plays, held by friction, fit a share near 1)
    assert widths["static_share"] < 0.3
    assert summary["chosen"]["shrink"] > 0.6


def test_a_play_beside_heating_names_both(example):
    """Issue 21: a play beside a friction law, each partly supported, named together."""
    summary = _summary(example, "heating+backlash", seed=5)
    assert [n for n in summary["verdict"] if n != "unexplained"] == ["backlash", "heating"]
    widths = summary["chosen"]["parameters"]["backlash"]
    assert math.isclose(widths["width_x"], example.PLAY[0], rel_tol=0.25)


def test_lag_named_through_the_command_line(example, tmp_path, capsys):
    from dcfpb.cli import main

    manifest = example.write(example.synthesise("lag", seed=5, orbits=SMALL), tmp_path)
    report = tmp_path / "report"
    assert main(["diagnose", "--manifest", str(manifest), "--model", "constant",
                 "--report", str(report)]) == 0
    text = capsys.readouterr().out
    # one report for tests in one or two directions (isolator.diagnosis.report)
    for name in ("summary.md", "diagnosis.json", "loops.png", "candidates.png"):
        assert (report / name).stat().st_size > 0, name
        assert f"wrote {report / name}" in text
    assert "verdict: lag" in (report / "summary.md").read_text()
    assert json.loads((report / "diagnosis.json").read_text())["verdict"][0] == "lag"
    for start in ("tests in two directions:", "where:", "direction changes:", "verdict: lag",
                  "gap with lag:", "force error RMS by axis:"):
        assert any(line.startswith(start) for line in text.splitlines()), (start, text)
    shrink = float(text.split("(shrink ")[1].split(" %")[0])
    assert shrink > 60.0
    lag = float(re.search(r"lag: lag = ([0-9.e+-]+)", text).group(1))
    assert math.isclose(lag, 0.04, rel_tol=0.1)  # 4 samples of 10 ms


def test_the_element_as_baseline_leaves_no_gap_on_its_own_data(example):
    """The precise model's heating on the 2D field, told to a precise baseline without the
    speed and pressure factors (the element run through the measured orbits): ``none``."""
    from isolator.diagnosis.baseline import BaselineSpec

    campaign = _campaign(example, "heating", seed=41)
    summary = diagnose_2d(campaign, BaselineSpec("precise", ("velocity", "pressure"))).to_json()
    _check_report(summary)
    assert summary["verdict"] == ["none"]
    assert math.isclose(summary["baseline"]["parameters"]["mu"], example.MU, rel_tol=0.03)


def test_hints_in_two_directions_pass_their_tests_against_noise(example):
    """One direction's hints (signatures.py) per axis and in the direction-change windows: on
    100 residuals of pure noise (white, and AR(1) with phi 0.5-0.95) at most one false hint
    (issue 21's bar; none measured), and an offset on x is named."""
    from isolator.diagnosis import two_directions as td

    d = td._prepare(_campaign(example, "none", seed=5), smooth=False)
    window = td.transition_window(d, td._calibrate(d, td.BaselineSpec("constant")))
    rng = np.random.default_rng(11)
    scale = 0.01 * float(np.sqrt(np.mean(d.force**2)))
    false = 0
    for i in range(100):
        e = rng.normal(0.0, scale, (d.n, 2))
        phi = 0.0 if i % 2 == 0 else rng.uniform(0.5, 0.95)
        for k in range(1, d.n) if phi else ():
            e[k] += phi * e[k - 1]
        false += not td.looks_like_2d(d, d.force - e, window)[0].startswith("no simple")
    assert false <= 1
    e = rng.normal(0.0, scale, (d.n, 2))
    e[:, 0] += 0.8 * scale
    hints = td.looks_like_2d(d, d.force - e, window)
    assert hints[0].startswith("along x, a constant force offset"), hints
