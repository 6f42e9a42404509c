"""What a gap that no candidate closes looks like, in a few plain sentences.

:func:`signature` looks at the residual left (measured less predicted force) for patterns an
engineer recognises: a dead band or lag after the reversals (backlash, slack in the rig), a
constant force offset (a load-cell zero), an oscillation well above the loading frequency
(dynamics of the rig or the specimen), a drift from cycle to cycle, a dependence on position.
Each sentence carries its share of the residual energy, so the strongest comes first.

A pattern is named only when it carries at least a tenth of the residual energy *and* passes
its own test against residuals of pure noise (:mod:`.hint_tests`, false-alarm rate at most
``ALPHA`` per hint): a spectral peak above the noise floor, above the loading frequencies and
away from their harmonics; a mean, a trend over the cycles or a dependence on position
against the residual's block-robust standard error; an energy share near the reversals above
what the residual's blocks shuffled within each test put there. A pattern that fails its test
is not printed.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from isolator.diagnosis.data import Campaign
from isolator.diagnosis.features import Features
from isolator.diagnosis.hint_tests import (
    ALPHA,
    block_length,
    block_permutation_test,
    block_test,
    loading_frequency,
    spectral_peak,
)

_MIN_SHARE = 0.1  # a pattern must carry 10 % of the residual energy to be mentioned
_DESCRIPTION_ALPHA = 0.05  # a sign test over the half cycles for how a reversal hint reads
# (a reading of a concentration that has passed its own test: 5 of 5 half cycles suffice)
_DEAD_BAND_MIN = 5.0e-4  # [m] a dwell near zero force this much longer than the model's


def signature(features: Features, prediction: np.ndarray, campaign: Campaign,
              near: float) -> list[str]:
    """Sentences on what the residual looks like, strongest first, each one passing its test.

    Parameters
    ----------
    features : Features
        The campaign's features, all samples in time order.
    prediction : ndarray
        The model's force at every sample [N].
    campaign : Campaign
        The measured tests (their loading frequencies).
    near : float
        Distance from a reversal counted as "near" [m].
    """
    f = features
    residual = f.force - prediction
    energy = float(np.sum(residual**2)) or 1.0
    length = block_length(residual)
    found: list[tuple[float, str]] = []
    found.extend(_reversals(f, prediction, residual, energy, near, length))
    found.extend(offset_hint(residual, float(np.max(np.abs(f.force))), energy, length))
    found.extend(_oscillation(f, residual, campaign, energy))
    found.extend(drift_hint(residual, f.block, f.cycle, energy, length))
    found.extend(position_hint(residual, f.displacement, energy, length))
    return sentences(found)


def sentences(found: list[tuple[float, str]]) -> list[str]:
    """The hints ``found`` ((share, sentence) pairs), strongest first, or the sentence that
    none passed."""
    found.sort(reverse=True)
    out = [text for _, text in found]
    if not out:
        out = ["no simple pattern (no concentration at reversals, offset, oscillation, drift or "
               "position dependence passes its test against noise); see the residual plots"]
    return out


def offset_hint(residual: np.ndarray, peak_force: float, energy: float,
                length: int) -> list[tuple[float, str]]:
    """A constant force offset of ``residual`` [N] (a block-jackknife t on its mean), its share
    of the residual ``energy`` [N^2]; ``peak_force`` [N] for its size."""
    bias = float(residual.mean())
    share = bias**2 * residual.size / energy
    if share < _MIN_SHARE or block_test(residual, np.ones(residual.size), [0],
                                        length)[1] >= ALPHA:
        return []
    ratio = 100 * abs(bias) / peak_force
    return [(share, f"a constant force offset of {bias:.4g} N ({ratio:.1f} % of the peak "
                    f"force; {100 * share:.0f} % of the residual energy), like a load-cell zero "
                    "error (or friction that differs with the sliding direction, which over "
                    "whole cycles leaves the same offset)")]


def _reversals(f: Features, prediction: np.ndarray, residual: np.ndarray, energy: float,
               near: float, length: int) -> list[tuple[float, str]]:
    """Whether the force swings over to the new sliding level differently after a reversal.

    Compares the medians, over half cycles with a clear swing and at least half the typical
    stroke, of the travel over which the measured and the predicted friction force dwell
    near zero (within 20 % of the new level) and of the travel to half the swing. The share of
    the residual energy near the reversals must pass a block permutation test against the
    share the same residual blocks shuffled within each test put there; a dead band, softer
    or stiffer swing is read into it only when a sign test over the half cycles says so at
    ``_DESCRIPTION_ALPHA``.
    """
    data = f.force - f.pendulum
    model = prediction - f.pendulum
    stroke = 0.5 * float(np.percentile(np.abs(f.displacement), 99))
    dwell, half = [], []
    for block in np.unique(f.block):
        idx = np.flatnonzero(f.block == block)
        s = f.since_reversal[idx]
        if idx.size < 6 or s[-1] < stroke:  # only half cycles of a good stroke
            continue
        d = _swing(s, data[idx])
        m = _swing(s, model[idx])
        if d is not None and m is not None:
            dwell.append((d[0], m[0]))
            half.append((d[1], m[1]))
    if len(dwell) < 2:
        return []
    dwell_arr, half_arr = np.array(dwell), np.array(half)
    dwell_data, dwell_model = np.median(dwell_arr, axis=0)
    half_data, half_model = np.median(half_arr, axis=0)
    reach = max(2.0 * half_data, 2.0 * half_model, near)
    zone = f.since_reversal < reach
    share = float(np.sum(residual[zone] ** 2)) / energy
    dead_band = (dwell_data > 1.5 * dwell_model and dwell_data - dwell_model > _DEAD_BAND_MIN
                 and _most(dwell_arr[:, 0] - dwell_arr[:, 1] > _DEAD_BAND_MIN))
    if share < _MIN_SHARE or (share < 1.5 * zone.mean() and not dead_band):
        return []
    if block_permutation_test(residual**2, zone, f.test, length) >= ALPHA:
        return []
    text = (f"{100 * share:.0f} % of the residual energy lies within {1e3 * reach:.3g} mm of "
            f"a reversal ({100 * zone.mean():.0f} % of the samples)")
    if dead_band:
        text += (f": after each reversal the measured force dwells near zero for about "
                 f"{1e3 * dwell_data:.3g} mm of travel (the model: {1e3 * dwell_model:.3g} mm)"
                 " before it rises to the new sliding level, a dead band (backlash, slack in "
                 "the load path) that the return map does not have")
    elif half_data > 1.3 * half_model and _most(half_arr[:, 0] > half_arr[:, 1]):
        text += (f": the measured force swings over more slowly than the model (half way "
                 f"after {1e3 * half_data:.3g} mm against {1e3 * half_model:.3g} mm), a softer "
                 "transition")
    elif half_data < half_model / 1.3 and _most(half_arr[:, 0] < half_arr[:, 1]):
        text += (f": the measured force swings over sooner than the model (half way after "
                 f"{1e3 * half_data:.3g} mm against {1e3 * half_model:.3g} mm), a stiffer "
                 "transition or a breakaway peak")
    return [(share, text)]


def _most(wins: np.ndarray) -> bool:
    """Whether ``wins`` is true in more half cycles than chance (one-sided sign test)."""
    return bool(stats.binom.sf(int(np.sum(wins)) - 1, wins.size, 0.5) < _DESCRIPTION_ALPHA)


def _swing(travel: np.ndarray, friction: np.ndarray) -> tuple[float, float] | None:
    """(travel dwelling near zero, travel to half the swing) after a reversal, or None."""
    tail = travel >= 0.7 * travel[-1]
    end = float(np.median(friction[tail]))
    start = float(friction[0])
    if abs(end) == 0.0 or abs(end - start) < 0.5 * abs(end):
        return None
    along = friction * np.sign(end)
    entered = np.flatnonzero(along > -0.2 * abs(end))
    left = np.flatnonzero(along > 0.2 * abs(end))
    halfway = np.flatnonzero((friction - start) / (end - start) >= 0.5)
    if not (entered.size and left.size and halfway.size):
        return None
    return (float(travel[left[0]] - travel[entered[0]]), float(travel[halfway[0]]))


def _oscillation(f: Features, residual: np.ndarray, campaign: Campaign,
                 energy: float) -> list[tuple[float, str]]:
    """A narrow spectral peak well above every loading frequency and off their harmonics."""
    residuals, steps, loading = [], [], []
    for k, rec in enumerate(campaign.tests):
        idx = f.test == k
        residuals.append(residual[idx])
        steps.append(float(np.median(np.diff(rec.time))))
        loading.append(loading_frequency(f.time[idx], f.displacement[idx]))
    return oscillation_hint(residuals, steps, loading, energy)


def oscillation_hint(residuals: list[np.ndarray], steps: list[float], loading: list[float],
                     energy: float) -> list[tuple[float, str]]:
    """:func:`~isolator.diagnosis.hint_tests.spectral_peak` of each test's residual [N], its
    sample interval [s] and loading frequency [Hz], as a hint with its share of ``energy``."""
    peak = spectral_peak(residuals, steps, loading, energy)
    if peak is None or not peak.passes or peak.share < _MIN_SHARE:
        return []
    return [(peak.share, f"an oscillation well above the loading frequencies (near "
                         f"{peak.frequency:.3g} Hz, {peak.ratio:.0f} times the residual's "
                         f"spectral floor there; {100 * peak.share:.0f} % of the residual "
                         "energy): dynamics of the rig or the specimen, not friction")]


def drift_hint(residual: np.ndarray, block: np.ndarray, progress: np.ndarray, energy: float,
               length: int, *, along: tuple[str, str] = ("from cycle to cycle", "cycle"),
               ) -> list[tuple[float, str]]:
    """A drift of ``residual`` [N] with ``progress`` (the cycle number, or the path travelled
    [m]) over the ``block`` means, tested by a block-jackknife t; ``along``: how the sentence
    reads it (where, per what)."""
    blocks = np.unique(block)
    if blocks.size < 4:
        return []
    count = np.bincount(block)[blocks]
    mean = np.bincount(block, weights=residual)[blocks] / count
    order = np.bincount(block, weights=progress)[blocks] / count
    if np.ptp(order) == 0.0:
        return []
    slope, intercept = np.polyfit(order, mean, 1)
    explained = np.sum(count * (slope * order + intercept - mean.mean()) ** 2) / energy
    if explained < _MIN_SHARE:
        return []
    design = np.column_stack([np.ones(residual.size), progress.astype(float)])
    if block_test(residual, design, [1], length)[1] >= ALPHA:
        return []
    return [(float(explained), f"a drift of the force {along[0]} ({slope:+.4g} N per "
                               f"{along[1]}; {100 * explained:.0f} % of the residual energy)")]


def position_hint(residual: np.ndarray, u: np.ndarray, energy: float,
                  length: int) -> list[tuple[float, str]]:
    """A ``residual`` [N] that grows with the displacement ``u`` [m] or with its size (a
    block-jackknife F on both coefficients)."""
    design = np.column_stack([np.ones_like(u), u, np.abs(u)])
    coef, *_ = np.linalg.lstsq(design, residual, rcond=None)
    fitted = design @ coef - residual.mean()
    share = float(np.sum(fitted**2)) / energy
    if share < _MIN_SHARE or block_test(residual, design, [1, 2], length)[1] >= ALPHA:
        return []
    kind = "with |u| (friction changes across the plate)" if abs(coef[2]) * np.ptp(
        np.abs(u)) > abs(coef[1]) * np.ptp(u) else "with u (a stiffness)"
    return [(share, f"a residual that grows {kind}; {100 * share:.0f} % of the residual energy")]
