"""How sure the diagnosis is: a confidence for each named effect and parameter intervals.

Both come from a bootstrap over blocks (half cycles, so the serial correlation within one is
kept):

- **confidence** of a named effect: the share of ``RESAMPLES`` block resamples of the held-out
  errors in which it still closes ``explained_min`` of the weighted excess its reference (the
  model without it) leaves [-];
- **intervals**: the 5th and 95th percentiles of each engineering parameter over ``REFITS``
  refits on block resamples (each block weighted by how often it was drawn).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from isolator.diagnosis.fitting import fit
from isolator.diagnosis.selection import Assessment, Workspace

RESAMPLES = 400
REFITS = 30
_SEED = 20261123


def _block_sums(work: Workspace, prediction: np.ndarray) -> np.ndarray:
    return work.block_sse(prediction)


def confidence(work: Workspace, reference: Assessment, extended: Assessment,
               explained_min: float, *, resamples: int = RESAMPLES) -> float:
    """Share of block resamples in which ``extended`` closes ``explained_min`` of the excess
    ``reference`` leaves [-]."""
    f = work.features
    ref = _block_sums(work, reference.prediction)
    ext = _block_sums(work, extended.prediction)
    noise = np.bincount(f.block, weights=f.weight * f.noise_variance, minlength=ref.size)
    present = np.bincount(f.block, minlength=ref.size) > 0
    return block_confidence(ref[present], ext[present], noise[present], explained_min,
                            resamples=resamples)


def block_confidence(ref: np.ndarray, ext: np.ndarray, noise: np.ndarray,
                     explained_min: float, *, resamples: int = RESAMPLES) -> float:
    """Share of ``resamples`` block resamples in which the extended model closes
    ``explained_min`` of the excess its reference leaves [-] (NaN for fewer than 2 blocks),
    from the weighted squared residuals summed by block [-] of the reference (``ref``), the
    extended model (``ext``) and noise alone (``noise``): in one direction and in two."""
    if ref.size < 2:
        return float("nan")
    rng = np.random.default_rng(_SEED)
    draws = rng.integers(0, ref.size, size=(resamples, ref.size))
    gain = (ref - ext)[draws].sum(axis=1)
    left = (ref - noise)[draws].sum(axis=1)
    ok = (left > 0.0) & (gain >= explained_min * left)
    return float(np.mean(ok))


def intervals(work: Workspace, chosen: Assessment, *, refits: int = REFITS,
              percentiles: tuple[float, float] = (5.0, 95.0)) -> dict[str, dict]:
    """``{effect: {parameter: [low, high]}}`` of the chosen model's own parameters."""
    f = work.features
    blocks = np.unique(f.block)
    if blocks.size < 3 or chosen.fit is None:
        return {}
    rng = np.random.default_rng(_SEED + 1)
    model, context = chosen.model, work.context
    samples: dict[str, dict[str, list[float]]] = {}
    for _ in range(refits):
        counts = np.bincount(rng.choice(blocks, size=blocks.size), minlength=f.block.max() + 1)
        resampled = replace(f, weight=f.weight * counts[f.block])
        keep = np.flatnonzero(counts[f.block] > 0)
        result = fit(model, resampled.take(keep), context, [chosen.fit.theta])
        for effect, part in zip(model.effects, model.slices(), strict=True):
            if not effect.parameters:
                continue
            values = effect.physical_parameters(result.theta[part],
                                                np.zeros(part.stop - part.start), context)
            for key, (value, _, _) in values.items():
                if isinstance(value, int | float):
                    samples.setdefault(effect.name, {}).setdefault(key, []).append(float(value))
    out: dict[str, dict] = {}
    for name, table in samples.items():
        out[name] = {k: [float(np.percentile(v, percentiles[0])),
                         float(np.percentile(v, percentiles[1]))] for k, v in table.items()}
    return out
