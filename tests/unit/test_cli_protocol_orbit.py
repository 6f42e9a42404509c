"""``dcfpb protocol --orbit ... --angle ...``: the 2D virtual test machine from the command line."""

from __future__ import annotations

import csv
import json

import pytest

from dcfpb.cli import main
from dcfpb.cli.protocol import ORBIT_CHOICES
from isolator.orbits import ORBITS

ARGS = ["protocol", "--model", "constant", "--slider-diameter", "0.3", "--pressure", "60e6",
        "--amplitude", "0.2", "--period", "2.0", "--cycles", "2", "--dt", "0.02"]


def _json(capsys, *extra):
    assert main([*ARGS, *extra, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_choices_are_the_orbits():
    assert ORBIT_CHOICES == ORBITS


@pytest.mark.parametrize("kind", ORBIT_CHOICES)
def test_each_orbit_reports_both_axes_and_its_energy(capsys, kind):
    out = _json(capsys, "--orbit", kind, "--angle", "20")
    assert (out["orbit"], out["angle"], out["model"]) == (kind, 20.0, "constant")
    assert len(out["energy_per_cycle"]) == 2
    assert all(e > 0.0 for e in out["energy_per_cycle"])
    assert out["dissipated_energy"] >= sum(out["energy_per_cycle"]) - 1e-6  # + the lead-in
    assert set(out["cycles"]) == {"x", "y"}
    assert all(len(rows) >= 1 for rows in out["cycles"].values())


def test_a_line_along_x_reports_the_loops_in_one_direction(capsys):
    one_direction = _json(capsys)
    line = _json(capsys, "--orbit", "line")
    assert line["cycles"]["y"] == []
    for got, expected in zip(line["cycles"]["x"], one_direction["cycles"], strict=True):
        for key in ("Fmax", "Fmin", "EDC", "Keff"):
            assert got[key] == pytest.approx(expected[key], rel=1e-9)


def test_text_report_and_csv(capsys, tmp_path):
    target = tmp_path / "orbit.csv"
    assert main([*ARGS, "--orbit", "figure8", "--output", str(target)]) == 0
    text = capsys.readouterr().out
    assert "orbit: figure8" in text and "x axis" in text and "y axis" in text
    with target.open() as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == ["time", "displacement_x", "displacement_y", "velocity_x", "velocity_y",
                       "force_x", "force_y", "mu", "temperature"]
    assert len(rows) == 1 + 201


def test_plot_draws_an_orbit(capsys, tmp_path):
    """--plot with --orbit draws the loops along x and y and the temperature (it was refused
    before the one test rig)."""
    target = tmp_path / "orbit.png"
    assert main([*ARGS, "--orbit", "circle", "--plot", str(target)]) == 0
    capsys.readouterr()
    assert target.stat().st_size > 10_000


@pytest.mark.parametrize(("extra", "message"), [
    (["--orbit", "circle", "--angle", "400"], "--angle"),
    (["--angle", "20"], "--angle"),  # an angle turns an orbit: refused without --orbit
    (["--orbit", "square", "--dt", "0.5"], "--dt"),
])
def test_bad_orbit_flags_exit_2_naming_the_flag(capsys, extra, message):
    assert main([*ARGS[:-2], "--dt", "0.02", *extra]) == 2
    assert message in capsys.readouterr().err


def test_unknown_orbit_is_refused_by_the_parser(capsys):
    with pytest.raises(SystemExit) as stop:
        main([*ARGS, "--orbit", "ellipse"])
    assert stop.value.code == 2
