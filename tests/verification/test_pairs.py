"""Pairs of records: RotD50/RotD100 by their exact properties (a lone component, identical
components, rotation invariance, one direction against a rotated record's own spectrum), the
ASCE 7-16 scaling of a suite of pairs on RotD100, synthetic pairs by seed, the pair's own
operations and the four real two-component records of ``../shared/groundmotions/pairs``."""

from __future__ import annotations

import re

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY as G
from groundmotions import (
    GroundMotion,
    GroundMotionPair,
    ScalingReport,
    asce7_design_spectrum,
    isolated_period_range,
    read_pair,
    read_pair_manifest,
    response_spectra,
    rotd_spectra,
    scale_suite,
    spectrum,
    synthetic_pair,
)

KT = {"ground_frequency": 15.6, "ground_damping": 0.6, "target_pga": 3.0}
PERIODS = np.array([0.0, 0.1, 0.3, 0.7, 1.5, 3.0])


@pytest.fixture(scope="module")
def pair() -> GroundMotionPair:
    return synthetic_pair("kanai-tajimi", 11, duration=10.0, dt=0.01, **KT)


def _at2(path, values_g, dt) -> None:
    rows = [" ".join(f"{v:.7E}" for v in values_g[i:i + 5]) for i in range(0, len(values_g), 5)]
    path.write_text("PEER STRONG MOTION DATABASE RECORD\nTEST 01/01/00, STATION, 000\n"
                    "ACCELERATION TIME HISTORY IN UNITS OF G\n"
                    f"NPTS= {len(values_g)}, DT= {dt:.4f} SEC\n" + "\n".join(rows) + "\n")


# ---------------------------------------------------------------------------------- RotD


def test_rotd100_of_a_lone_component_is_its_spectrum_exactly(pair):
    lone = GroundMotionPair(pair.x, pair.x.scaled(0.0))
    rotd = rotd_spectra(lone, PERIODS)
    np.testing.assert_array_equal(rotd.rotd100, spectrum(pair.x, PERIODS).sa)
    assert (rotd.rotd100_angle == 0.0).all()


def test_identical_components_give_sqrt2_and_the_component_median(pair):
    same = GroundMotionPair(pair.x, pair.x)
    rotd, sa = rotd_spectra(same, PERIODS), spectrum(pair.x, PERIODS).sa
    np.testing.assert_allclose(rotd.rotd100, np.sqrt(2.0) * sa, rtol=1e-12)  # at 45 deg
    # u_theta = sqrt(2) sin(theta + 45 deg) u_x: 89 angles above 1, 89 below, 0 and 90 deg at
    # 1 exactly, so the median of the 180 peaks is the component's own: bounds and the value.
    assert (rotd.rotd50 <= rotd.rotd100).all() and (rotd.rotd50 >= rotd.sa_by_angle.min(1)).all()
    np.testing.assert_allclose(rotd.rotd50, sa, rtol=1e-12)


@pytest.mark.parametrize("angle", [37.0, 90.0, -128.0])
def test_rotd_is_invariant_under_whole_degree_rotation(pair, angle):
    before, after = rotd_spectra(pair, PERIODS), rotd_spectra(pair.rotated(angle), PERIODS)
    np.testing.assert_allclose(after.sa, before.sa, rtol=1e-12)


def test_one_direction_is_the_rotated_records_own_spectrum(pair):
    rotd = rotd_spectra(pair, PERIODS)
    for angle in (30, 117):
        direct = spectrum(pair.rotated(angle).x, PERIODS).sa
        np.testing.assert_allclose(rotd.sa_by_angle[:, angle], direct, rtol=1e-12)


def test_rotd_ordering(pair):
    rotd = rotd_spectra(pair, PERIODS, percentiles=(0, 50, 100))
    for component in (pair.x, pair.y):
        assert (rotd.rotd100 >= spectrum(component, PERIODS).sa * (1 - 1e-12)).all()
    assert (rotd.rotd(0) <= rotd.rotd50).all() and (rotd.rotd50 <= rotd.rotd100).all()
    np.testing.assert_allclose(rotd.rotd100, rotd.sa_by_angle.max(axis=1), rtol=0)
    assert rotd.angles.size == 180 and rotd.rotd100[0] >= max(pair.x.pga, pair.y.pga)


# ------------------------------------------------------------------------------- scaling


def test_scaled_suite_mean_rotd100_envelopes_and_touches_the_target():
    suite = [synthetic_pair("clough-penzien", seed, duration=12.0, dt=0.01, filter_frequency=1.5,
                            filter_damping=0.6, **KT) for seed in (1, 5, 9)]
    target = asce7_design_spectrum(1.0, 0.6, 8.0, level="mce")
    t_range = isolated_period_range(2.4, 3.0)
    report = scale_suite(suite, target, t_range, n_periods=10)
    assert isinstance(report, ScalingReport) and report.measure == "rotd100"
    assert report.period_range == pytest.approx((1.8, 3.75))
    # recomputed from the scaled pairs themselves, independently of the report's arithmetic
    mean100 = np.mean([rotd_spectra(p, report.periods).rotd100 for p in report.motions], axis=0)
    ratio = mean100 / target.sa_at(report.periods)
    assert ratio.min() == pytest.approx(1.0, abs=1e-9) and (ratio >= 1.0 - 1e-9).all()
    means = report.mean_spectra
    np.testing.assert_allclose(means["rotd100"], mean100, rtol=1e-12)
    np.testing.assert_array_equal(report.mean_sa, means["rotd100"])
    assert (means["rotd50"] <= means["rotd100"]).all()
    for before, after, k in zip(suite, report.motions, report.scale_factors, strict=True):
        np.testing.assert_allclose(after.y.acceleration, k * before.y.acceleration, rtol=1e-15)
    frame = report.to_frame()
    assert frame.index.name == "pair" and list(frame.index) == [p.name for p in suite]
    assert list(frame.columns) == ["individual_factor", "common_factor", "scale_factor",
                                   "scaled_pga_x", "scaled_pga_y"]
    assert list(report.spectrum_frame().columns) == ["target_sa", "mean_rotd100",
                                                     "mean_rotd50", "ratio"]
    individual = scale_suite(suite, target, t_range, method="individual", n_periods=10)
    each = individual.spectra["rotd100"] / individual.target_sa
    assert each.min(axis=1) == pytest.approx(1.0)
    # on RotD50 instead: the same steps on the median direction, so larger factors
    median = scale_suite(suite, target, t_range, measure="rotd50", n_periods=10)
    assert median.min_ratio == pytest.approx(1.0, abs=1e-12)
    assert (median.scale_factors > report.scale_factors).all()


# ----------------------------------------------------------------------- synthetic, the pair


def test_synthetic_pair_is_reproducible_by_seed_with_independent_components():
    a = synthetic_pair("kanai-tajimi", 3, duration=5.0, dt=0.01, vertical_ratio=2 / 3, **KT)
    b = synthetic_pair("kanai-tajimi", 3, duration=5.0, dt=0.01, vertical_ratio=2 / 3, **KT)
    for one, two in zip(a, b, strict=True):
        np.testing.assert_array_equal(one.acceleration, two.acceleration)
    assert [m.metadata["seed"] for m in a] == [3, 4, 5]
    long = synthetic_pair("kanai-tajimi", 3, duration=60.0, dt=0.01, envelope="none", **KT)
    assert abs(np.corrcoef(long.x.acceleration, long.y.acceleration)[0, 1]) < 0.1
    assert a.z is not None and a.z.pga == pytest.approx(2.0, rel=1e-12)  # 2/3 of 3 m/s^2


def test_pair_operations(pair):
    scaled = GroundMotionPair(pair.x, pair.y, pair.x, "p").scaled(2.0)
    assert scaled.z is not None and scaled.z.pga == pytest.approx(2.0 * pair.x.pga)
    quarter = pair.rotated(90.0)
    np.testing.assert_allclose(quarter.x.acceleration, pair.y.acceleration, atol=1e-15)
    np.testing.assert_allclose(quarter.y.acceleration, -pair.x.acceleration, atol=1e-15)
    longer = GroundMotion(np.append(pair.y.acceleration, [0.1, 0.2]), pair.dt)
    cut = GroundMotionPair.truncated_to_common(pair.x, longer, name="cut")
    assert cut.npts == pair.npts and "common" in cut.y.processing[-1]
    assert pair.resampled(0.005).npts == 2 * pair.npts - 1
    short = GroundMotionPair(pair.x, pair.y, pair.x, "p").truncated(2.0)
    assert short.npts == 201 and all(m.processing[-1] == "truncated to 2 s (201 samples)"
                                     for m in short)
    np.testing.assert_array_equal(short.y.acceleration, pair.y.acceleration[:201])
    with pytest.raises(ValueError, match=r"'duration' parameter of GroundMotionPair\.truncated"):
        pair.truncated(2 * pair.duration)


def test_manifest_reads_pairs_relative_to_its_folder(tmp_path):
    (tmp_path / "gm").mkdir()
    t = np.arange(400) * 0.01
    for name, phase in (("A-N", 0.0), ("A-E", 1.0), ("A-V", 2.0)):
        _at2(tmp_path / "gm" / f"{name}.AT2", 0.1 * np.sin(5 * t + phase), 0.01)
    (tmp_path / "suite.csv").write_text(
        "# two pairs of one station\nname,x,y,z\nA,gm/A-N.AT2,gm/A-E.AT2,gm/A-V.AT2\n\n"
        "A2,gm/A-E.AT2,gm/A-N.AT2,\n")
    first, second = read_pair_manifest(tmp_path / "suite.csv")
    assert (first.name, first.has_vertical, second.name, second.has_vertical) == (
        "A", True, "A2", False)
    np.testing.assert_allclose(first.x.pga, 0.1 * G, rtol=1e-4)  # a sampled sine
    assert read_pair(tmp_path / "gm" / "A-N.AT2", tmp_path / "gm" / "A-E.AT2").name == "A"


# ------------------------------------------------------------------- the real pairs (shared)


def _readme_table(folder):
    rows = re.findall(r"^\| (\w+) \| (\S+), (\S+) \| (\d+) \| ([\d.]+) \|",
                      (folder / "README.md").read_text(), flags=re.MULTILINE)
    return [(name, x, y, int(npts), float(dt)) for name, x, y, npts, dt in rows]


@pytest.mark.shared
def test_real_pairs_match_the_readme_and_their_rotd_envelopes(shared_dir):
    folder = shared_dir / "groundmotions" / "pairs"
    table = _readme_table(folder)
    assert [row[0] for row in table] == ["CHY023", "ILA061", "TAP084", "TAP094"]
    periods = np.array([0.0, 0.5, 1.5, 3.0])
    for name, x, y, npts, dt in table:
        pair = read_pair(folder / x, folder / y)
        assert (pair.name, pair.npts, pair.dt) == (name, npts, dt)
        rotd = rotd_spectra(pair, periods)
        both = response_spectra(np.column_stack([pair.x.acceleration, pair.y.acceleration]),
                                pair.dt, periods).sa  # each row = spectrum() of a component
        assert (rotd.rotd100 >= both * (1 - 1e-12)).all()
        assert (rotd.rotd50 <= rotd.rotd100).all() and (rotd.rotd50 > 0).all()
        assert 0.02 * G < rotd.rotd100[0] < 0.1 * G  # weak far-field motions (README)
