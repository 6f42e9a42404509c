"""Synthetic records: bit-for-bit reproducibility, the Kanai-Tajimi and Clough-Penzien power
spectral densities of long stationary realisations (Welch), and the time envelopes."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate, signal

from groundmotions.synthetic import (
    PiecewiseEnvelope,
    SaragoniHartEnvelope,
    clough_penzien,
    clough_penzien_psd,
    kanai_tajimi,
    kanai_tajimi_psd,
)

KT = {"ground_frequency": 15.0, "ground_damping": 0.4}
CP = {**KT, "filter_frequency": 1.5, "filter_damping": 0.6}
DT = 0.01
N_LONG = 2**19  # 87 min at 100 Hz: 1023 half-overlapping Welch segments of 1024 samples


def test_same_seed_same_record_bit_for_bit_and_another_seed_differs():
    a = kanai_tajimi(20.0, DT, **KT, target_pga=3.0, seed=7)
    b = kanai_tajimi(20.0, DT, **KT, target_pga=3.0, seed=7)
    c = kanai_tajimi(20.0, DT, **KT, target_pga=3.0, seed=8)
    assert a.acceleration.tobytes() == b.acceleration.tobytes()
    assert not np.array_equal(a.acceleration, c.acceleration)
    d = clough_penzien(20.0, DT, **CP, intensity=0.01, envelope="saragoni-hart", seed=7)
    e = clough_penzien(20.0, DT, **CP, intensity=0.01, envelope="saragoni-hart", seed=7)
    assert d.acceleration.tobytes() == e.acceleration.tobytes()
    assert a.npts == 2001 and a.dt == DT and a.pga == pytest.approx(3.0, rel=1e-15)


def test_metadata_records_every_parameter_and_rebuilds_the_record():
    motion = clough_penzien(15.0, DT, **CP, target_pga=2.0, seed=11, envelope="jennings")
    meta = motion.metadata
    for key, value in {**CP, "seed": 11, "target_pga": 2.0, "duration": 15.0, "dt": DT,
                       "bit_generator": "PCG64"}.items():
        assert meta[key] == value, key
    assert meta["envelope"] == {"kind": "PiecewiseEnvelope", "rise_time": 1.5,
                                "plateau_end": 7.5, "decay": pytest.approx(np.log(20) / 7.5)}
    assert motion.processing == ("generated: Clough-Penzien filtered white noise, seed 11",)
    # The recorded intensity (S0 equivalent to the target PGA) gives the same record.
    envelope = PiecewiseEnvelope(**{k: v for k, v in meta["envelope"].items() if k != "kind"})
    again = clough_penzien(15.0, DT, **CP, intensity=meta["intensity"], envelope=envelope,
                           seed=11)
    np.testing.assert_allclose(again.acceleration, motion.acceleration, rtol=1e-12, atol=1e-15)


def _welch_ratio(motion, psd):
    """Welch one-sided PSD per Hz over the theoretical one, G(f) = 4 pi S(2 pi f), without
    the DC bin."""
    f, estimate = signal.welch(motion.acceleration, fs=1 / motion.dt, nperseg=1024,
                               detrend=False)
    return f[1:], estimate[1:] / (4 * np.pi * psd(2 * np.pi * f[1:]))


def test_kanai_tajimi_psd_of_a_long_stationary_realisation():
    """Each Welch bin averages ~1000 segments: relative standard error ~1.06/sqrt(1023) =
    3.3 %; bins (DC and Nyquist excluded) are held to 5 standard errors, 16-bin bands to 5 %
    and the mean over all bins to 1 %."""
    s0 = 0.02
    motion = kanai_tajimi((N_LONG - 1) * DT, DT, **KT, intensity=s0, envelope="none", seed=3)
    _, ratio = _welch_ratio(motion, lambda w: kanai_tajimi_psd(w, **KT, intensity=s0))
    ratio = ratio[:-1]
    assert np.max(np.abs(ratio - 1)) < 5 * 0.033
    assert np.max(np.abs(ratio[:496].reshape(-1, 16).mean(axis=1) - 1)) < 0.05
    assert abs(ratio.mean() - 1) < 0.01
    # Variance: pi S0 w_g (1 + 4 z_g^2) / (2 z_g) minus the tail beyond the Nyquist frequency.
    nyquist = np.pi / DT
    tail = 2 * integrate.quad(lambda w: kanai_tajimi_psd(w, **KT, intensity=s0), nyquist,
                              np.inf)[0]
    zg, wg = KT["ground_damping"], KT["ground_frequency"]
    variance = np.pi * s0 * wg * (1 + 4 * zg**2) / (2 * zg) - tail
    assert np.var(motion.acceleration) == pytest.approx(variance, rel=0.03)


def test_clough_penzien_psd_and_its_low_frequency_cut():
    s0 = 0.02
    motion = clough_penzien((N_LONG - 1) * DT, DT, **CP, intensity=s0, envelope=None, seed=5)
    f, ratio = _welch_ratio(motion, lambda w: clough_penzien_psd(w, **CP, intensity=s0))
    above = (f >= 0.5) & (f < f[-1])  # below 0.5 Hz the omega^4 drop is swamped by leakage
    assert np.max(np.abs(ratio[above] - 1)) < 5 * 0.033
    # Towards omega = 0 the PSD vanishes as (omega / w_f)^4 times the Kanai-Tajimi PSD.
    w = 2 * np.pi * np.array([0.001, 0.01])
    np.testing.assert_allclose(clough_penzien_psd(w, **CP) / kanai_tajimi_psd(w, **KT),
                               w**4 / CP["filter_frequency"] ** 4, rtol=2e-3)


def test_piecewise_envelope_shape():
    env = PiecewiseEnvelope(rise_time=2.0, plateau_end=8.0, decay=0.5)
    t = np.array([0.0, 1.0, 2.0, 5.0, 8.0, 10.0])
    np.testing.assert_allclose(env(t), [0.0, 0.25, 1.0, 1.0, 1.0, np.exp(-1.0)], rtol=1e-15)
    default = PiecewiseEnvelope.for_duration(20.0)
    assert (default.rise_time, default.plateau_end) == (2.0, 10.0)
    assert default(20.0) == pytest.approx(0.05, rel=1e-14)


def test_saragoni_hart_envelope_peaks_at_epsilon_and_ends_at_eta():
    env = SaragoniHartEnvelope(duration=20.0, peak_fraction=0.2, end_value=0.05)
    t = np.linspace(0.0, 20.0, 20_001)
    values = env(t)
    assert values[0] == 0.0
    assert t[np.argmax(values)] == pytest.approx(4.0, abs=1e-3)
    assert values.max() == pytest.approx(1.0, rel=1e-12)
    assert values[-1] == pytest.approx(0.05, rel=1e-12)


@pytest.mark.parametrize("envelope", ["jennings", "saragoni-hart"])
def test_ensemble_variance_follows_the_envelope_squared(envelope):
    """Over 300 seeds the mean square of a(t) in 1 s windows is e(t)^2 sigma^2 (to 4 standard
    errors of a chi-square estimate with ~300 x 100 / correlation samples)."""
    duration, s0 = 20.0, 0.05
    records = np.array([kanai_tajimi(duration, DT, **KT, intensity=s0, envelope=envelope,
                                     seed=seed).acceleration for seed in range(300)])
    stationary = np.array([kanai_tajimi(duration, DT, **KT, intensity=s0, envelope="none",
                                        seed=seed).acceleration for seed in range(300)])
    t = np.arange(records.shape[1]) * DT
    shape = (PiecewiseEnvelope.for_duration(duration) if envelope == "jennings"
             else SaragoniHartEnvelope(duration))
    sigma2 = stationary.var()
    windows = [(t >= a) & (t < a + 1.0) for a in np.arange(0.0, 20.0, 1.0)]
    measured = np.array([np.mean(records[:, w] ** 2) for w in windows])
    expected = np.array([np.mean(shape(t[w]) ** 2) * sigma2 for w in windows])
    assert np.max(np.abs(measured / expected - 1)) < 0.08
    # The envelope multiplies the same stationary noise: a(t) = e(t) x(t) sample by sample.
    np.testing.assert_allclose(records, stationary * shape(t), rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"intensity": 0.01, "target_pga": 3.0}, ["Exactly one of", "'target_pga'"]),
        ({}, ["Exactly one of"]),
        ({"intensity": 0.01, "ground_frequency": 400.0}, ["'ground_frequency'",
                                                          "(0, 314.159)", "400.0"]),
        ({"intensity": -1.0}, ["'intensity'", "(0, inf)"]),
        ({"intensity": 0.01, "seed": -3}, ["'seed'", "[0, inf)", "-3"]),
        ({"intensity": 0.01, "seed": 1.5}, ["'seed'", "an int"]),
        ({"intensity": 0.01, "envelope": "boxcar"}, ["'envelope'", "'jennings'"]),
    ],
)
def test_parameter_errors(kwargs, words):
    args = {**KT, "seed": 1, **kwargs}
    with pytest.raises((ValueError, TypeError)) as error:
        kanai_tajimi(10.0, DT, **args)
    for word in words:
        assert word in str(error.value)
