"""``dcfpb demo --plan``: the bundled building in plan under the demo's synthetic pair (here
shortened to 2 s, so that the reference engine runs it in seconds)."""

from __future__ import annotations

from pathlib import Path

import pytest

from dcfpb.cli import demo, main

REPO = Path(__file__).resolve().parents[2]


def test_the_plan_example_shipped_in_the_package_is_the_documented_one():
    shipped = REPO / "dcfpb" / "data" / "five_storey_plan.toml"
    assert shipped.read_bytes() == (REPO / "examples" / "five_storey_plan.toml").read_bytes()


def test_the_demo_pair_has_its_stated_peaks():
    pair = demo.plan_demo_pair()
    assert pair.x.pga == pytest.approx(demo.PLAN_PGA_X, rel=1e-12)
    assert pair.y.pga == pytest.approx(demo.PLAN_PGA_Y, rel=1e-12)
    assert pair.duration == pytest.approx(demo.PLAN_PAIR["duration"], abs=0.02)


def test_demo_plan_prints_the_table_and_writes_its_figures(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(demo.PLAN_PAIR, "duration", 2.0)
    folder = tmp_path / "plan"
    assert main(["demo", "--plan", "--plot", str(folder)]) == 0
    out = capsys.readouterr().out
    for model in demo.MODELS:
        assert f"{model}: the corner bearing" in out
    assert "6 bearings, eccentricity (1.2, 0.6) m" in out
    # the figures of dcfpb demo (a panel or a line style per direction), then those in plan
    assert {p.name for p in folder.iterdir()} == {
        "isolator_hysteresis.png", "temperature.png", "roof_acceleration.png",
        "storey_drift.png", "response_histories.png", "floor_spectra.png",
        "isolation_effect.png", "bearing_orbits.png", "force_orbits.png",
        "plate_temperature.png"}
