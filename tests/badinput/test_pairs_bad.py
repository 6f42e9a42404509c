"""Bad pairs and pair manifests: each raises `InputError` naming the culprit (the component and
its file, the manifest's line and column) and, where there is one, the way out."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from dcfpb.common.errors import InputError
from groundmotions import (
    GroundMotion,
    GroundMotionPair,
    asce7_design_spectrum,
    read_pair,
    read_pair_manifest,
    rotd_spectra,
    scale_suite,
)

HEADER = ("PEER STRONG MOTION DATABASE RECORD\nTEST 01/01/00, STATION, 000\n"
          "{kind} TIME HISTORY IN UNITS OF {units}\n")


def _at2(path: Path, npts: int = 200, dt: float = 0.01, kind: str = "ACCELERATION",
         units: str = "G") -> Path:
    values = 0.05 * np.sin(np.arange(npts) * 0.3)
    rows = [" ".join(f"{v:.6E}" for v in values[i:i + 5]) for i in range(0, npts, 5)]
    path.write_text(HEADER.format(kind=kind, units=units) + f"NPTS= {npts}, DT= {dt:.4f} SEC\n"
                    + "\n".join(rows) + "\n")
    return path


@pytest.fixture
def files(tmp_path: Path) -> dict[str, Path]:
    return {
        "x": _at2(tmp_path / "S1-N.AT2"),
        "y": _at2(tmp_path / "S1-E.AT2"),
        "y_dt": _at2(tmp_path / "S1-E-coarse.AT2", dt=0.02),
        "y_long": _at2(tmp_path / "S1-E-long.AT2", npts=230),
        "velocity": _at2(tmp_path / "S1-E.VT2", kind="VELOCITY", units="CM/S"),
    }


def _raises(call, *words: str) -> InputError:
    with pytest.raises(InputError) as caught:
        call()
    for word in words:
        assert word in str(caught.value), (word, str(caught.value))
    return caught.value


def test_different_time_steps_name_both_files_and_offer_resampling(files):
    _raises(lambda: read_pair(files["x"], files["y_dt"]), "S1-N.AT2", "dt = 0.01 s",
            "S1-E-coarse.AT2", "dt = 0.02 s", "resampled(0.01)", "resample_to=0.01")
    pair = read_pair(files["x"], files["y_dt"], resample_to=0.01, truncate=True)
    assert pair.dt == 0.01


def test_different_lengths_say_which_is_longer_and_offer_truncation(files):
    _raises(lambda: read_pair(files["x"], files["y_long"]), "y component (S1-E-long.AT2) has 230",
            "30 more than the x component (S1-N.AT2) with 200", "truncated_to_common")
    assert read_pair(files["x"], files["y_long"], truncate=True).npts == 200


def test_a_vertical_of_another_length_is_named(files):
    x = GroundMotion(np.ones(10), 0.01, "a")
    _raises(lambda: GroundMotionPair(x, x, GroundMotion(np.ones(8), 0.01, "v"), "p"),
            "Pair 'p'", "x component (a) has 10", "2 more than the z component (v)")


def test_a_missing_component_file_is_named(files, tmp_path):
    _raises(lambda: read_pair(files["x"], tmp_path / "S1-W.AT2"), "y component file",
            "S1-W.AT2", "does not exist")


def test_a_velocity_record_as_a_component_is_refused(files):
    _raises(lambda: read_pair(files["x"], files["velocity"]), "y component",
            "S1-E.VT2", "velocity")


def test_a_one_column_text_record_without_dt_is_named(files, tmp_path):
    text = tmp_path / "S1-V.txt"
    text.write_text("\n".join(str(0.01 * k) for k in range(50)) + "\n")
    _raises(lambda: read_pair(files["x"], files["y"], text), "z component", "S1-V.txt", "'dt'",
            "read_pair(..., dt=...)")


def _manifest(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "pairs.csv"
    path.write_text(text)
    return path


def test_manifest_missing_column(files, tmp_path):
    path = _manifest(tmp_path, "name,x\nS1,S1-N.AT2\n")
    _raises(lambda: read_pair_manifest(path), "pairs.csv, line 1", "column 'y' is missing")


def test_manifest_unknown_column(files, tmp_path):
    path = _manifest(tmp_path, "name,x,y,scale\nS1,S1-N.AT2,S1-E.AT2,2\n")
    _raises(lambda: read_pair_manifest(path), "pairs.csv, line 1", "unknown column 'scale'",
            "name, x, y, z, dt, units")


def test_manifest_row_naming_a_missing_file(files, tmp_path):
    path = _manifest(tmp_path, "name,x,y\nS1,S1-N.AT2,S1-E.AT2\nS2,S2-N.AT2,S1-E.AT2\n")
    _raises(lambda: read_pair_manifest(path), "pairs.csv, line 3, column 'x'", "S2-N.AT2",
            "does not exist")


def test_manifest_row_with_a_bad_pair_names_the_line(files, tmp_path):
    path = _manifest(tmp_path, "name,x,y\nS1,S1-N.AT2,S1-E-coarse.AT2\n")
    _raises(lambda: read_pair_manifest(path), "pairs.csv, line 2", "Pair 'S1'", "dt = 0.02 s")


@pytest.mark.parametrize("text, words", [
    ("name,x,y,dt\nS1,S1-N.AT2,S1-E.AT2,fast\n", ["line 2, column 'dt'", "'fast'"]),
    ("name,x,y\nS1,,S1-E.AT2\n", ["line 2, column 'x'", "empty"]),
    ("name,x,y\nS1,S1-N.AT2,S1-E.AT2\nS1,S1-N.AT2,S1-E.AT2\n", ["line 3", "already named on "
                                                               "line 2"]),
    ("name,x,y\nS1,S1-N.AT2\n", ["line 2", "expected 3 cells"]),
    ("name,x,y\n", ["lists no pairs"]),
])
def test_manifest_bad_cells(files, tmp_path, text, words):
    _raises(lambda: read_pair_manifest(_manifest(tmp_path, text)), "pairs.csv", *words)


def test_bad_parameters_of_rotd_and_scaling(files):
    pair = read_pair(files["x"], files["y"])
    _raises(lambda: rotd_spectra(pair, [1.0], angle_step=7.0), "'angle_step'", "whole number")
    _raises(lambda: rotd_spectra(pair, [-1.0]), "'periods'")
    target = asce7_design_spectrum(1.0, 0.6, 8.0, periods=np.geomspace(0.1, 5.0, 50))
    _raises(lambda: scale_suite([pair], target, (2.0, 6.0)), "'period_range[1]'")
    _raises(lambda: scale_suite([pair, pair.x], target, (2.0, 3.0)), "GroundMotionPair")
    _raises(lambda: scale_suite([pair], target, (2.0, 3.0), measure="sa"), "'measure'",
            "'rotd100'")
    _raises(lambda: scale_suite([pair.x], target, (2.0, 3.0), measure="rotd100"), "'measure'")
    _raises(lambda: scale_suite([pair, pair.scaled(0.0)], target, (2.0, 3.0)),
            "pairs with a non-zero RotD100 spectrum", "index 1")
