"""Tests in two directions read by ``dcfpb diagnose`` (issue 21): the format and its errors.

A test in two directions has ``time``, ``displacement_x``, ``displacement_y``, ``force_x``,
``force_y`` and optionally ``axial_force``, ``velocity_x``, ``velocity_y``, ``temperature``.
Every bad file is refused with a ``DataError`` (an ``InputError``) naming the file and the
column; a campaign mixing tests in one and two directions is refused naming a file of each;
a manifest of tests in two directions gives a ``Campaign2D``.
"""

from __future__ import annotations

import numpy as np
import pytest

from dcfpb.common.errors import InputError
from isolator.diagnosis import DataError, read_record
from isolator.diagnosis.data import (
    Campaign2D,
    load_any_campaign,
    load_campaign_2d,
    read_record_2d,
)
from isolator.diagnosis.manifest import load_manifest

N = 1.0e6  # [N]


def _columns(n: int = 200) -> dict[str, np.ndarray]:
    t = np.arange(n) * 0.01
    phase = 2 * np.pi * t / 1.0
    ux, uy = 0.05 * np.cos(phase), 0.05 * np.sin(phase)
    return {"time": t, "displacement_x": ux, "displacement_y": uy,
            "force_x": N * (ux / 2.0 - 0.05 * np.sin(phase)),
            "force_y": N * (uy / 2.0 + 0.05 * np.cos(phase)), "axial_force": np.full(n, N)}


def _write(path, columns: dict[str, np.ndarray], header: list[str] | None = None):
    names = header or list(columns)
    np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",",
               header=",".join(names), comments="", fmt="%.9g")
    return path


def test_a_good_file_reads_with_derived_velocity(tmp_path):
    record = read_record_2d(_write(tmp_path / "orbit.csv", _columns()))
    assert record.displacement.shape == (200, 2)
    assert record.force.shape == (200, 2)
    assert not record.velocity_measured
    assert np.all(record.speed > 0.2)  # 0.31 m/s on the circle


@pytest.mark.parametrize("column", ["displacement_y", "force_x", "time"])
def test_a_missing_column_is_named(tmp_path, column):
    columns = _columns()
    del columns[column]
    path = _write(tmp_path / "orbit.csv", columns)
    with pytest.raises(DataError, match=rf"orbit\.csv.*{column}"):
        read_record_2d(path)


def test_a_stated_unit_other_than_si_is_refused(tmp_path):
    columns = _columns()
    header = [f"{c} [kN]" if c == "force_y" else c for c in columns]
    path = _write(tmp_path / "orbit.csv", columns, header)
    with pytest.raises(DataError, match=r"orbit\.csv.*'force_y' is stated in 'kN'"):
        read_record_2d(path)


def test_millimetres_are_refused_naming_the_axis(tmp_path):
    columns = _columns()
    columns["displacement_x"] = 1000.0 * columns["displacement_x"]
    with pytest.raises(DataError, match=r"'displacement_x' reaches 50.*millimetres"):
        read_record_2d(_write(tmp_path / "orbit.csv", columns))


def test_one_velocity_axis_alone_is_refused(tmp_path):
    columns = _columns()
    columns["velocity_x"] = np.gradient(columns["displacement_x"], columns["time"])
    with pytest.raises(DataError, match="velocity_x and velocity_y"):
        read_record_2d(_write(tmp_path / "orbit.csv", columns))


def test_a_velocity_in_mm_per_s_is_refused(tmp_path):
    columns = _columns()
    for axis in ("x", "y"):
        columns[f"velocity_{axis}"] = 1000.0 * np.gradient(columns[f"displacement_{axis}"],
                                                           columns["time"])
    with pytest.raises(DataError, match=r"'velocity_x' is 1e\+03 times"):
        read_record_2d(_write(tmp_path / "orbit.csv", columns))


def test_nan_is_refused_naming_column_and_row(tmp_path):
    columns = _columns()
    columns["force_y"][10] = np.nan
    with pytest.raises(DataError, match=r"'force_y'.*row 12"):
        read_record_2d(_write(tmp_path / "orbit.csv", columns))


def test_the_one_direction_reader_points_to_the_two_direction_one(tmp_path):
    with pytest.raises(InputError, match="two directions"):
        read_record(_write(tmp_path / "orbit.csv", _columns()))


def test_a_campaign_mixing_kinds_is_refused(tmp_path):
    two = _write(tmp_path / "orbit.csv", _columns())
    c = _columns()
    one = _write(tmp_path / "line.csv", {"time": c["time"], "displacement": c["displacement_x"],
                                         "force": c["force_x"], "axial_force": c["axial_force"]})
    with pytest.raises(DataError, match=r"mixes tests in one direction \(.*line\.csv.*orbit\.csv"):
        load_any_campaign([one, two], effective_radius=2.0, slider_diameter=0.25)
    with pytest.raises(DataError, match="mixes"):
        load_campaign_2d([two, one], effective_radius=2.0, slider_diameter=0.25)


def test_mixed_units_between_tests_are_refused(tmp_path):
    a = _write(tmp_path / "a.csv", _columns())
    c = _columns()
    c["force_x"], c["force_y"] = 1e-3 * c["force_x"], 1e-3 * c["force_y"]
    b = _write(tmp_path / "b.csv", c)
    with pytest.raises(DataError, match=r"b\.csv.*peak force \|F\|"):
        load_any_campaign([a, b], effective_radius=2.0, slider_diameter=0.25)


def test_a_manifest_of_orbits_gives_a_two_direction_campaign(tmp_path):
    c = _columns()
    del c["axial_force"]
    _write(tmp_path / "a.csv", c)
    _write(tmp_path / "b.csv", c)
    manifest = tmp_path / "campaign.toml"
    manifest.write_text('effective_radius = 2.0\nslider_diameter = 0.25\n\n[[test]]\n'
                        'file = "a.csv"\naxial_load = 1e6\n\n[[test]]\nfile = "b.csv"\n'
                        'axial_load = 1e6\nrest_before = 60\n')
    campaign = load_manifest(manifest)
    assert isinstance(campaign, Campaign2D)
    assert campaign.tests[1].rest_before == 60.0
    assert campaign.tests[0].axial_force[0] == N


def test_the_command_line_refuses_a_mixed_campaign_naming_both(tmp_path, capsys):
    from dcfpb.cli import main

    two = _write(tmp_path / "orbit.csv", _columns())
    c = _columns()
    one = _write(tmp_path / "line.csv", {"time": c["time"], "displacement": c["displacement_x"],
                                         "force": c["force_x"], "axial_force": c["axial_force"]})
    status = main(["diagnose", str(two), str(one), "--model", "constant",
                   "--effective-radius", "2", "--slider-diameter", "0.25"])
    assert status == 2
    err = capsys.readouterr().err
    assert "orbit.csv" in err and "line.csv" in err and "one kind" in err


def test_one_reader_checks_both_kinds_alike():
    """The record check is the one of a test in one direction: a non-finite value on either
    axis is named with its row (an -inf on y beside a finite x included), and a velocity in
    mm/s is told as such with the axis's header to write."""
    from isolator.diagnosis.data import BearingRecord2D

    c = _columns()
    u = np.column_stack([c["displacement_x"], c["displacement_y"]])
    f = np.column_stack([c["force_x"], c["force_y"]])
    f[7, 1] = -np.inf
    with pytest.raises(DataError, match=r"'force' has 1 infinite value\(s\), the first at row 7"):
        BearingRecord2D("orbit", c["time"], u, f, c["axial_force"])
    f[7, 1] = 0.0
    v = 1000.0 * np.gradient(u, c["time"], axis=0)
    with pytest.raises(DataError, match=r"'velocity_x' is 1e\+03 times d\(displacement_x\)/dt.*"
                                        r"mm/s.*'velocity_x \[mm/s\]'"):
        BearingRecord2D("orbit", c["time"], u, f, c["axial_force"], velocity=v)


def test_a_missing_file_of_a_two_direction_campaign_is_named(tmp_path):
    two = _write(tmp_path / "orbit.csv", _columns())
    with pytest.raises(DataError, match=r"gone\.csv: no such file"):
        load_campaign_2d([two, tmp_path / "gone.csv"], effective_radius=2.0, slider_diameter=0.25)
