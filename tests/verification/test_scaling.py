"""Target spectra and suite scaling: the ASCE 7-16 spectrum by hand, the scaled mean spectrum
against the target (not below anywhere on the grid, equal at the tightest period)."""

from __future__ import annotations

import numpy as np
import pytest

from dcfpb.common.units import STANDARD_GRAVITY as G
from groundmotions.bundled import load_bundled
from groundmotions.scaling import (
    ScalingReport,
    TargetSpectrum,
    asce7_design_spectrum,
    isolated_period_range,
    scale_suite,
)
from groundmotions.spectra import spectrum
from groundmotions.synthetic import clough_penzien, kanai_tajimi

# S_DS = 1.0 g, S_D1 = 0.6 g, T_L = 8 s: T_0 = 0.12 s, T_S = 0.6 s.
HAND = [  # period [s], design Sa [g] worked by hand
    (0.0001, 1.0 * (0.4 + 0.6 * 0.0001 / 0.12)),
    (0.06, 0.7),  # halfway up the ramp: 0.4 + 0.3
    (0.12, 1.0),  # T_0
    (0.3, 1.0),
    (0.6, 1.0),  # T_S
    (1.0, 0.6),
    (1.2, 0.5),
    (8.0, 0.075),  # T_L: 0.6 / 8
    (16.0, 0.01875),  # 0.6 * 8 / 16^2
]


@pytest.mark.parametrize("level, factor", [("design", 1.0), ("mce", 1.5)])
def test_asce7_spectrum_at_its_corners_by_hand(level, factor):
    target = asce7_design_spectrum(1.0, 0.6, 8.0, [t for t, _ in HAND], level=level)
    np.testing.assert_allclose(target.periods, [t for t, _ in HAND])  # corners already there
    np.testing.assert_allclose(target.sa, [factor * sa * G for _, sa in HAND], rtol=1e-14)
    assert ("MCE_R" if level == "mce" else "design") in target.name


def test_asce7_default_table_holds_the_corners_and_interpolates_exactly_past_t0():
    target = asce7_design_spectrum(1.0, 0.6, 8.0)
    for corner in (0.12, 0.6, 8.0):
        assert np.any(np.isclose(target.periods, corner, rtol=0, atol=1e-15))
    periods = np.array([0.2, 0.45, 0.7, 2.3, 5.0, 9.5, 13.0])
    exact = np.where(periods <= 0.6, 1.0, np.where(periods <= 8.0, 0.6 / periods,
                                                   4.8 / periods**2)) * G
    np.testing.assert_allclose(target.sa_at(periods), exact, rtol=1e-12)


def test_target_spectrum_validation_and_log_log_interpolation():
    target = TargetSpectrum([1.0, 4.0], [8.0, 0.5], name="power law")  # Sa = 8 T^-2
    assert target.sa_at(2.0)[0] == pytest.approx(2.0, rel=1e-14)
    with pytest.raises(ValueError, match=r"'periods' parameter of TargetSpectrum.sa_at "
                       r"\(power law\) must hold finite floats in \[1, 4\]"):
        target.sa_at(5.0)
    with pytest.raises(ValueError, match=r"strictly increasing\. Got 1\.0 after 2\.0 at index 1"):
        TargetSpectrum([2.0, 1.0], [1.0, 1.0])
    with pytest.raises(ValueError, match="one value per period"):
        TargetSpectrum([1.0, 2.0], [1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="'sa' parameter of TargetSpectrum"):
        TargetSpectrum([1.0, 2.0], [1.0, 0.0])
    with pytest.raises(ValueError, match=r"'T_L' parameter of asce7_design_spectrum must be a "
                       r"float in \(0.6, inf\)"):
        asce7_design_spectrum(1.0, 0.6, 0.5)
    with pytest.raises(ValueError, match="'level'"):
        asce7_design_spectrum(1.0, 0.6, 8.0, level="service")


def test_isolated_period_range():
    """ASCE 7-16 17.3.3: from 0.75 T_M (upper-bound properties, the shorter period) to
    1.25 T_M (lower-bound properties, the longer one)."""
    assert isolated_period_range(2.5, 3.2) == (1.875, 4.0)
    with pytest.raises(ValueError, match=r"'upper_bound_period' .* \[2.5, inf\)"):
        isolated_period_range(2.5, 2.0)


def _suite():
    """El Centro and four synthetic records (no ../shared needed)."""
    kt = {"ground_frequency": 12.0, "ground_damping": 0.6, "target_pga": 3.0}
    cp = {**kt, "filter_frequency": 1.0, "filter_damping": 0.7}
    return [
        load_bundled("elcentro"),
        kanai_tajimi(20.0, 0.01, seed=1, **kt),
        kanai_tajimi(25.0, 0.01, seed=2, envelope="saragoni-hart", **kt),
        clough_penzien(20.0, 0.01, seed=3, **cp),
        clough_penzien(30.0, 0.01, seed=4, **cp),
    ]


SUITE = _suite()
TARGET = asce7_design_spectrum(1.0, 0.6, 8.0, level="mce")


def _check_mean_envelopes_target(report: ScalingReport, motions) -> None:
    """Recompute the spectra of the scaled records independently and compare."""
    assert len(report.motions) == len(motions)
    spectra = np.array([spectrum(m, report.periods, report.damping).sa for m in report.motions])
    ratio = spectra.mean(axis=0) / TARGET.sa_at(report.periods)
    assert ratio.min() >= 1.0 - 1e-9  # not below the target anywhere on the grid
    assert abs(ratio.min() - 1.0) < 1e-9  # and equal to it at the tightest period
    assert report.tightest_period == report.periods[int(np.argmin(ratio))]
    np.testing.assert_allclose(report.ratio, ratio, rtol=1e-12)
    assert report.min_ratio == pytest.approx(1.0, abs=1e-12)
    assert report.periods[0] == report.period_range[0]
    assert report.periods[-1] == pytest.approx(report.period_range[1], rel=1e-14)


def test_scaled_suite_mean_is_not_below_the_target_and_touches_it():
    period_range = isolated_period_range(2.4, 3.0)
    report = scale_suite(SUITE, TARGET, period_range)
    _check_mean_envelopes_target(report, SUITE)
    for original, scaled, k in zip(SUITE, report.motions, report.scale_factors, strict=True):
        np.testing.assert_allclose(scaled.acceleration, k * original.acceleration, rtol=1e-15)
        assert scaled.processing == (*original.processing, f"scaled by {k:.12g}")
    np.testing.assert_allclose(report.scale_factors,
                               report.common_factor * report.individual_factors, rtol=1e-15)


def test_individual_factors_match_the_target_on_average():
    """Step 1: each record times its factor has a geometric-mean ratio of 1 to the target."""
    report = scale_suite(SUITE, TARGET, (1.0, 4.0), n_periods=25)
    target = TARGET.sa_at(report.periods)
    for motion, k in zip(SUITE, report.individual_factors, strict=True):
        sa = spectrum(motion, report.periods).sa * k
        assert np.exp(np.mean(np.log(sa / target))) == pytest.approx(1.0, rel=1e-12)


def test_individual_method_puts_every_record_above_the_target():
    report = scale_suite(SUITE, TARGET, (1.0, 4.0), method="individual", n_periods=25)
    target = TARGET.sa_at(report.periods)
    for motion in report.motions:
        ratio = spectrum(motion, report.periods).sa / target
        assert ratio.min() == pytest.approx(1.0, abs=1e-9)
    assert report.min_ratio >= 1.0 - 1e-12 and report.common_factor == 1.0


def test_report_frames():
    report = scale_suite(SUITE, TARGET, (1.5, 3.5), n_periods=10)
    frame = report.to_frame()
    assert frame.index.name == "record" and list(frame.index) == [m.name for m in SUITE]
    assert list(frame.columns) == ["individual_factor", "common_factor", "scale_factor",
                                   "scaled_pga"]
    np.testing.assert_allclose(frame["scale_factor"], report.scale_factors)
    assert frame.attrs["min_ratio"] == report.min_ratio
    assert frame.attrs["tightest_period"] == report.tightest_period
    periods = report.spectrum_frame()
    assert periods.index.name == "period" and len(periods) == 10
    assert periods["ratio"].min() == pytest.approx(1.0, abs=1e-12)


def test_a_single_period_and_scaling_errors():
    report = scale_suite(SUITE[:2], TARGET, (3.0, 3.0))
    assert report.periods.tolist() == [3.0] and report.min_ratio == pytest.approx(1.0)
    with pytest.raises(ValueError, match=r"'period_range\[1\]' parameter of scale_suite"):
        scale_suite(SUITE, TARGET, (3.0, 2.0))
    with pytest.raises(ValueError, match=r"'period_range\[1\]' .* \[1, 20\]. Got 50.0"):
        scale_suite(SUITE, TARGET, (1.0, 50.0))
    with pytest.raises(TypeError, match="'motions' parameter of scale_suite must be a "
                       "non-empty sequence of GroundMotion"):
        scale_suite([], TARGET, (1.0, 2.0))
    with pytest.raises(TypeError, match="'period_range'"):
        scale_suite(SUITE, TARGET, 2.0)
    with pytest.raises(TypeError, match="'target' parameter of scale_suite must be a "
                       "TargetSpectrum or a"):
        scale_suite(SUITE, [1.0, 2.0], (1.0, 2.0))
    as_table = scale_suite(SUITE[:2], (TARGET.periods, TARGET.sa), (3.0, 3.0))
    np.testing.assert_array_equal(as_table.scale_factors, report.scale_factors)
    with pytest.raises(ValueError, match="'method'"):
        scale_suite(SUITE, TARGET, (1.0, 2.0), method="median")
    silent = SUITE[0].scaled(0.0)
    with pytest.raises(ValueError, match="non-zero spectrum"):
        scale_suite([SUITE[1], silent], TARGET, (1.0, 2.0))


# Eleven records of ../shared from six earthquakes (Cape Mendocino 1992, Borrego Mountain
# 1968, Chalfant Valley 1986, Aqaba 1995, Big Bear 1992, Chi-Chi 1999), chosen for enough
# long-period content that each needs a factor below 7.5 to match the MCE_R spectrum at 2-4 s
# (many records of the folder are weak or high-passed at 0.5 Hz and would need 50-500).
SHARED_RECORDS = ("EUR090", "FOR090", "RIO270", "A-ELC180", "A-LAD180", "A-ZAK360",
                  "EIL-EW", "HOS180", "HWA013-N", "WGK-N", "NST-N")


@pytest.mark.shared
def test_eleven_shared_records_scaled_to_the_asce_mce_spectrum(shared_dir):
    from groundmotions.readers import read_peer_at2

    motions = [read_peer_at2(shared_dir / "groundmotions" / f"{name}.AT2")
               for name in SHARED_RECORDS]
    period_range = isolated_period_range(2.6, 3.4)
    report = scale_suite(motions, TARGET, period_range, n_periods=40)
    _check_mean_envelopes_target(report, motions)
    assert report.names == SHARED_RECORDS
    assert np.all(report.individual_factors < 7.5)
    assert 1.0 < report.common_factor < 1.5
    frame = report.to_frame()
    assert frame.shape == (11, 4)
