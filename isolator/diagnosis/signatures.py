"""What a gap that no candidate closes looks like, in a few plain sentences.

:func:`signature` looks at the residual left (measured less predicted force) for patterns an
engineer recognises: a dead band or lag after the reversals (backlash, slack in the rig), a
constant force offset (a load-cell zero), an oscillation well above the loading frequency
(dynamics of the rig or the specimen), a drift from cycle to cycle, a dependence on position.
Each sentence carries its share of the residual energy, so the strongest comes first.
"""

from __future__ import annotations

import numpy as np

from isolator.diagnosis.data import Campaign
from isolator.diagnosis.features import Features

_MIN_SHARE = 0.1  # a pattern must carry 10 % of the residual energy to be mentioned
_HIGH_FREQUENCY_MULTIPLE = 10.0  # "oscillation": above 10 times the loading frequency
_DEAD_BAND_MIN = 5.0e-4  # [m] a dwell near zero force this much longer than the model's


def signature(features: Features, prediction: np.ndarray, campaign: Campaign,
              near: float) -> list[str]:
    """Sentences on what the residual looks like, strongest first."""
    f = features
    residual = f.force - prediction
    energy = float(np.sum(residual**2)) or 1.0
    found: list[tuple[float, str]] = []
    found.extend(_reversals(f, prediction, residual, energy, near))
    bias = float(residual.mean())
    share = bias**2 * residual.size / energy
    if share >= _MIN_SHARE:
        ratio = 100 * abs(bias) / float(np.max(np.abs(f.force)))
        found.append((share, f"a constant force offset of {bias:.4g} N ({ratio:.1f} % of the "
                             f"peak force; {100 * share:.0f} % of the residual energy), like a "
                             "load-cell zero error"))
    found.extend(_oscillation(f, residual, campaign, energy))
    found.extend(_drift(f, residual, energy))
    found.extend(_position(f, residual, energy))
    found.sort(reverse=True)
    sentences = [text for _, text in found]
    if not sentences:
        sentences = ["no simple pattern (not concentrated at reversals, no offset, oscillation, "
                     "drift or position dependence); see the residual plots"]
    return sentences


def _reversals(f: Features, prediction: np.ndarray, residual: np.ndarray, energy: float,
               near: float) -> list[tuple[float, str]]:
    """Whether the force swings over to the new sliding level differently after a reversal.

    Compares the medians, over half cycles with a clear swing and at least half the typical
    stroke, of the travel over which the measured and the predicted friction force dwell
    near zero (within 20 % of the new level) and of the travel to half the swing.
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
    dwell_data, dwell_model = np.median(np.array(dwell), axis=0)
    half_data, half_model = np.median(np.array(half), axis=0)
    reach = max(2.0 * half_data, 2.0 * half_model, near)
    zone = f.since_reversal < reach
    share = float(np.sum(residual[zone] ** 2)) / energy
    dead_band = dwell_data > 1.5 * dwell_model and dwell_data - dwell_model > _DEAD_BAND_MIN
    if share < _MIN_SHARE or (share < 1.5 * zone.mean() and not dead_band):
        return []
    text = (f"{100 * share:.0f} % of the residual energy lies within {1e3 * reach:.3g} mm of "
            f"a reversal ({100 * zone.mean():.0f} % of the samples)")
    if dead_band:
        text += (f": after each reversal the measured force dwells near zero for about "
                 f"{1e3 * dwell_data:.3g} mm of travel (the model: {1e3 * dwell_model:.3g} mm)"
                 " before it rises to the new sliding level, a dead band (backlash, slack in "
                 "the load path) that the return map does not have")
    elif half_data > 1.3 * half_model:
        text += (f": the measured force swings over more slowly than the model (half way "
                 f"after {1e3 * half_data:.3g} mm against {1e3 * half_model:.3g} mm), a softer "
                 "transition")
    elif half_data < half_model / 1.3:
        text += (f": the measured force swings over sooner than the model (half way after "
                 f"{1e3 * half_data:.3g} mm against {1e3 * half_model:.3g} mm), a stiffer "
                 "transition or a breakaway peak")
    return [(share, text)]


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
    high, total, peak_power, peak_freq = 0.0, 0.0, 0.0, 0.0
    for k, rec in enumerate(campaign.tests):
        r = residual[f.test == k]
        dt = float(np.median(np.diff(rec.time)))
        if r.size < 64:
            continue
        spectrum = np.abs(np.fft.rfft(r - r.mean())) ** 2
        freq = np.fft.rfftfreq(r.size, dt)
        motion = np.abs(np.fft.rfft(rec.displacement - rec.displacement.mean())) ** 2
        loading = float(freq[1:][np.argmax(motion[1:])])
        above = freq > _HIGH_FREQUENCY_MULTIPLE * loading
        high += float(spectrum[above].sum())
        total += float(spectrum.sum())
        if above.any() and spectrum[above].max() > peak_power:
            peak_power = float(spectrum[above].max())
            peak_freq = float(freq[above][np.argmax(spectrum[above])])
    share = high / total if total else 0.0
    if share < _MIN_SHARE:
        return []
    return [(share, f"an oscillation well above the loading frequency (strongest near "
                    f"{peak_freq:.3g} Hz; {100 * share:.0f} % of the residual energy): dynamics "
                    "of the rig or the specimen, not friction")]


def _drift(f: Features, residual: np.ndarray, energy: float) -> list[tuple[float, str]]:
    blocks = np.unique(f.block)
    if blocks.size < 4:
        return []
    count = np.bincount(f.block)[blocks]
    mean = np.bincount(f.block, weights=residual)[blocks] / count
    order = np.bincount(f.block, weights=f.cycle)[blocks] / count
    if np.ptp(order) == 0.0:
        return []
    slope, intercept = np.polyfit(order, mean, 1)
    explained = np.sum(count * (slope * order + intercept - mean.mean()) ** 2) / energy
    if explained < _MIN_SHARE:
        return []
    return [(float(explained), f"a drift of the force from cycle to cycle ({slope:+.4g} N per "
                               f"cycle; {100 * explained:.0f} % of the residual energy)")]


def _position(f: Features, residual: np.ndarray, energy: float) -> list[tuple[float, str]]:
    u = f.displacement
    design = np.column_stack([np.ones_like(u), u, np.abs(u)])
    coef, *_ = np.linalg.lstsq(design, residual, rcond=None)
    fitted = design @ coef - residual.mean()
    share = float(np.sum(fitted**2)) / energy
    if share < _MIN_SHARE:
        return []
    kind = "with |u| (friction changes across the plate)" if abs(coef[2]) * np.ptp(
        np.abs(u)) > abs(coef[1]) * np.ptp(u) else "with u (a stiffness)"
    return [(share, f"a residual that grows {kind}; {100 * share:.0f} % of the residual energy")]
