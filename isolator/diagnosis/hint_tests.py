"""The tests a "looks like" hint must pass before it is printed.

A hint of :mod:`.signatures` names a pattern in the residual left (measured less predicted
force). Residuals of measured tests are coloured noise plus whatever the model misses, so each
hint is a statistical test against residuals of pure noise (white or AR(1), any level), with
its false-alarm rate per residual at most :data:`ALPHA`:

- **oscillation** (:func:`spectral_peak`): the largest ratio of a test's Hann-windowed
  periodogram to its running-median floor, over the frequencies well above every loading
  frequency of the campaign and away from the harmonics of the test's own loading frequency,
  must exceed ``ln(M) + PEAK_MARGIN`` (M: the frequencies tried over the whole campaign; under
  noise the ratio is about exponential, so the maximum is Gumbel).
- **offset, drift, position** (:func:`block_test`): a least-squares regression of the
  residual on the pattern's design, its covariance the jackknife over contiguous blocks much
  longer than the residual's correlation (so AR(1) noise counts as what it is), and an F or
  t test on the pattern's coefficients with ``blocks - 1`` degrees of freedom.
- **concentration at the reversals** (:func:`block_permutation_test`): the residual energy
  in the reversal zone against its distribution when the same blocks are shuffled within
  each test.

Measured on 2000 noise-only residuals (white and AR(1), phi 0.5-0.95) of the five campaigns
of ``tests/unit/test_diagnosis_hints.py``: the peak statistic ``ratio - ln(M)`` has its 99.9 %
quantile at 6.4 (exceeds ``PEAK_MARGIN`` in 0.05 %), and p < ``ALPHA`` in 0.1 % (offset),
0.1 % (drift), 0.05 % (position) and none (reversals: p < 0.01 in 0.7 %, p < 0.05 in
4.5 %, so its p-values are calibrated). The test checks 100 of each noise kind.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage, stats

ALPHA = 1.0e-3  # false-alarm rate of each hint per noise-only residual
PEAK_MARGIN = 8.0  # ln(M) + this: a spectral peak stands out of the floor of M frequencies
ABOVE_OWN = 4.0  # an oscillation lies above 4 times its test's loading frequency ...
ABOVE_ALL = 2.0  # ... and above twice the highest loading frequency of the campaign
HARMONIC_BINS = 2.0  # bins within this many of a harmonic of the loading are not tried
FLOOR_BINS = 50  # half-width of the running-median floor [bins]
PEAK_BINS = 2  # bins either side of a peak counted in its energy
MIN_SPECTRUM = 256  # samples a test needs to be searched for an oscillation
BLOCK_CORRELATIONS = 10  # a block spans 10 e-folding lags of the residual's correlation ...
MIN_BLOCK = 32  # ... and at least 32 samples ...
MIN_BLOCKS = 20  # ... with at least 20 blocks
PERMUTATIONS = 4000  # block permutations of the concentration test


@dataclass(frozen=True)
class Peak:
    """The strongest spectral peak of a residual, and whether it passes.

    Attributes
    ----------
    frequency : float
        Frequency of the peak [Hz].
    ratio, threshold : float
        Peak over the running-median floor, and the ratio it must exceed [-].
    share : float
        Share of the campaign's residual energy above the floor near ``frequency`` [-].
    tried : int
        Frequencies tried over the campaign.
    """

    frequency: float
    ratio: float
    threshold: float
    share: float
    tried: int

    @property
    def passes(self) -> bool:
        """Whether the peak stands out of the noise floor at :data:`ALPHA`."""
        return self.ratio > self.threshold


def loading_frequency(time: np.ndarray, displacement: np.ndarray) -> float:
    """The displacement's fundamental [Hz]: the largest peak of its spectrum, refined.

    Parameters
    ----------
    time, displacement : ndarray
        Sample times [s] (about even steps) and displacement [m] of one test.
    """
    u = np.asarray(displacement, dtype=float) - float(np.mean(displacement))
    n = u.size
    dt = float(time[-1] - time[0]) / max(n - 1, 1)
    spectrum = np.abs(np.fft.rfft(u)) ** 2
    if spectrum.size < 3:
        return 1.0 / max(n * dt, 1e-12)
    k = 1 + int(np.argmax(spectrum[1:]))
    step = 1.0 / (n * dt)
    grid = np.linspace(max(k - 1, 0.5), k + 1, 41) * step
    t = np.asarray(time, dtype=float) - float(time[0])
    power = [abs(np.sum(u * np.exp(-2j * np.pi * f * t))) for f in grid]
    return float(grid[int(np.argmax(power))])


def spectral_peak(residuals: list[np.ndarray], steps: list[float], loading: list[float],
                  total_energy: float) -> Peak | None:
    """The strongest narrow peak of the residuals' spectra above the loading, or None.

    Parameters
    ----------
    residuals : list of ndarray
        The residual of each test [N].
    steps, loading : list of float
        Each test's sample interval [s] and loading frequency [Hz].
    total_energy : float
        Sum of the squared residual over the campaign [N^2], the reference of the share.
    """
    top = max(loading) if loading else 0.0
    spectra = []
    tried, best = 0, (0.0, 0.0)
    for r, dt, f0 in zip(residuals, steps, loading, strict=True):
        if r.size < MIN_SPECTRUM:
            spectra.append(None)
            continue
        freq, power, floor = _periodogram(r, dt)
        spectra.append((freq, power, floor, float(np.sum(r**2))))
        ratio, frequency, count = _strongest(freq, power, floor, f0, top)
        tried += count
        if ratio > best[0]:
            best = (ratio, frequency)
    if tried == 0:
        return None
    ratio, frequency = best
    share = 0.0
    for item in spectra:
        if item is None:
            continue
        freq, power, floor, energy = item
        near = np.abs(freq - frequency) <= (PEAK_BINS + 0.5) * freq[1]
        excess = float(np.sum(np.maximum(power[near] - floor[near], 0.0)))
        share += energy * excess / float(np.sum(power))
    return Peak(frequency, ratio, float(np.log(tried) + PEAK_MARGIN),
                share / total_energy if total_energy > 0.0 else 0.0, tried)


def _strongest(freq: np.ndarray, power: np.ndarray, floor: np.ndarray, f0: float,
               top: float) -> tuple[float, float, int]:
    """(largest ratio, its frequency [Hz], frequencies tried) over one test's periodogram.

    A frequency off the harmonics of ``f0`` is judged against the noise floor; a harmonic
    j f0 (the largest of the bins within ``HARMONIC_BINS`` of it, counted as that many
    tries) against the noise floor and the harmonics j +- 1 and j +- 2 alike, so the
    loading's own comb of harmonics, which falls off smoothly, is no oscillation.
    """
    step = float(freq[1])
    order = np.round(freq / f0).astype(np.int64)
    harmonic = (np.abs(freq - order * f0) <= HARMONIC_BINS * step) & (order >= 1)
    usable = ((freq > ABOVE_OWN * f0) & (freq > ABOVE_ALL * top) & (freq < 0.95 * freq[-1])
              & (floor > 0.0))
    plain = usable & ~harmonic
    best, at, tried = 0.0, 0.0, int(plain.sum())
    if plain.any():
        ratio = np.where(plain, power / np.where(floor > 0.0, floor, 1.0), 0.0)
        k = int(np.argmax(ratio))
        best, at = float(ratio[k]), float(freq[k])
    highest = int(order[harmonic].max()) if harmonic.any() else 0
    comb = np.zeros(highest + 3)
    np.maximum.at(comb, order[harmonic], power[harmonic])
    width = int(2 * HARMONIC_BINS + 1)
    for j in np.unique(order[harmonic & usable]):
        if j + 2 > highest:
            continue
        k = int(np.argmin(np.abs(freq - j * f0)))
        reference = max(float(floor[k]), float(np.max(comb[[j - 2, j - 1, j + 1, j + 2]])))
        tried += width
        if reference > 0.0 and comb[j] / reference > best:
            best, at = float(comb[j] / reference), float(j * f0)
    return best, at, tried


def _periodogram(r: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Frequencies [Hz], Hann periodogram of the detrended residual and its floor (its
    running median over 2 FLOOR_BINS + 1 bins over ln 2, the median of an exponential)."""
    x = np.arange(r.size, dtype=float)
    slope, intercept = np.polyfit(x, r, 1)
    power = np.abs(np.fft.rfft((r - slope * x - intercept) * np.hanning(r.size))) ** 2
    freq = np.fft.rfftfreq(r.size, dt)
    floor = ndimage.median_filter(power, size=2 * FLOOR_BINS + 1, mode="reflect") / np.log(2.0)
    return freq, power, floor


def block_length(residual: np.ndarray) -> int:
    """Length of the blocks of :func:`block_test` [samples]: ``BLOCK_CORRELATIONS`` times the
    lag at which the residual's autocorrelation first falls below 1/e, at least ``MIN_BLOCK``,
    and short enough for ``MIN_BLOCKS`` blocks."""
    r = np.asarray(residual, dtype=float) - float(np.mean(residual))
    n = r.size
    most = max(n // MIN_BLOCKS, 1)
    spectrum = np.abs(np.fft.rfft(r, 2 * n)) ** 2
    acf = np.fft.irfft(spectrum)[: min(n, most + 1)]
    if acf[0] <= 0.0:
        return min(MIN_BLOCK, most)
    below = np.flatnonzero(acf / acf[0] < np.exp(-1.0))
    lag = int(below[0]) if below.size else most
    return int(min(max(BLOCK_CORRELATIONS * lag, MIN_BLOCK), most))


def block_test(response: np.ndarray, design: np.ndarray, tested: list[int], length: int, *,
               one_sided: bool = False) -> tuple[np.ndarray, float]:
    """Least-squares coefficients and the p-value that the ``tested`` ones are zero.

    The covariance is the jackknife over contiguous blocks of ``length`` samples (the
    residual's correlation stays within a block; leaving a block out also accounts for
    blocks of high leverage), with a small-sample F (or t) reference on ``blocks - 1``
    degrees of freedom.

    Parameters
    ----------
    response : ndarray
        The residual [N] or its square [N^2], samples in time order.
    design : ndarray
        Regressors, one column each (a column of ones for the mean).
    tested : list of int
        Columns whose coefficients are tested.
    length : int
        Block length [samples] (:func:`block_length`).
    one_sided : bool
        Test one coefficient against the alternative that it is positive.
    """
    y = np.asarray(response, dtype=float)
    x = np.asarray(design, dtype=float).reshape(y.size, -1)
    coef, *_ = np.linalg.lstsq(x, y, rcond=None)
    blocks = max(y.size // max(length, 1), 2)
    label = np.minimum(np.arange(y.size) * blocks // y.size, blocks - 1)
    width = x.shape[1]
    gram = np.zeros((blocks, width, width))
    np.add.at(gram, label, x[:, :, None] * x[:, None, :])
    moment = np.zeros((blocks, width))
    np.add.at(moment, label, x * y[:, None])
    # the block jackknife: the coefficients with each block left out in turn
    ridge = 1e-12 * np.trace(gram.sum(axis=0)) * np.eye(width)
    left_out = np.linalg.solve(gram.sum(axis=0) - gram + ridge,
                               (moment.sum(axis=0) - moment)[:, :, None])[:, :, 0]
    spread = left_out - left_out.mean(axis=0)
    cov = spread.T @ spread * (blocks - 1) / blocks
    sub = np.ix_(tested, tested)
    b = coef[tested]
    df = max(blocks - 1, 1)
    if one_sided:
        se = float(np.sqrt(max(cov[sub][0, 0], 0.0)))
        if se == 0.0:
            return coef, 0.0 if b[0] > 0.0 else 1.0
        return coef, float(stats.t.sf(b[0] / se, df))
    wald = float(b @ np.linalg.pinv(cov[sub]) @ b) / len(tested)
    return coef, float(stats.f.sf(wald, len(tested), df))


def block_permutation_test(values: np.ndarray, zone: np.ndarray, test: np.ndarray, length: int,
                           *, permutations: int = PERMUTATIONS, seed: int = 0) -> float:
    """p-value that ``values`` (e.g. the squared residual) sum higher inside ``zone`` than
    chance puts there, by permuting blocks of ``length`` samples within each test.

    Each test is cut into whole blocks (a remainder shorter than a block is left out); the
    blocks, which keep the residual's correlation, are shuffled among the positions of their
    own test against the fixed ``zone``, so a test of more noise or more reversals than
    another is no concentration. The p-value counts the shuffles that reach the observed sum
    (``(1 + count) / (1 + permutations)``).

    Parameters
    ----------
    values : ndarray
        The quantity whose concentration is tested, per sample (>= 0).
    zone : ndarray of bool
        The samples of the zone (e.g. near a reversal).
    test : ndarray of int
        The test of each sample (tests contiguous, in time order).
    length : int
        Block length [samples] (:func:`block_length`).
    permutations, seed : int
        Number of shuffles and their seed (the diagnosis is deterministic).
    """
    length = max(int(length), 1)
    rows, masks, strata = [], [], []
    for k in np.unique(test):
        idx = np.flatnonzero(test == k)
        count = idx.size // length
        if count == 0:
            continue
        keep = idx[: count * length]
        rows.append(np.asarray(values, dtype=float)[keep].reshape(count, length))
        masks.append(np.asarray(zone, dtype=float)[keep].reshape(count, length))
        strata.append(np.full(count, k))
    if not rows:
        return 1.0
    x, m, stratum = np.concatenate(rows), np.concatenate(masks), np.concatenate(strata)
    cross = x @ m.T  # cross[i, b]: block i's values summed over position b's zone
    blocks = stratum.size
    observed = float(np.trace(cross))
    rng = np.random.default_rng(seed)
    keys = rng.random((permutations, blocks)) + stratum[None, :] * 2.0
    order = np.argsort(keys, axis=1)  # a shuffle within each test's positions
    shuffled = cross[order, np.arange(blocks)[None, :]].sum(axis=1)
    reached = int(np.sum(shuffled >= observed * (1.0 - 1e-12)))
    return (1.0 + reached) / (1.0 + permutations)
