"""How much of a force error measurement noise alone explains, sample by sample.

Three sources add up: the force sensor's white noise
(:func:`isolator.diagnosis.kinematics.noise_std` of each test's force), a measured axial
force's noise through d F / d N = mu z + u / R, and the displacement sensor's noise through
the model. The model is driven by the measured displacement (errors in the variables) and
the return map's elastic branch is stiff (dz/du = 1 / u_y), so a few hundredths of a mm move
the force by a good part of mu N right after a reversal. That part is a Monte Carlo estimate:
the displacement perturbed by its noise and smoothed as the features are, the mean square
change of the baseline's force averaged over replicates (not the variance, so the bias noise
brings to the clipped return map counts too). Standardised by this variance, the residual of
noise alone has a mean square of one at every sample.
"""

from __future__ import annotations

import numpy as np

from isolator.diagnosis.data import Campaign
from isolator.diagnosis.features import Features, smoothed_displacement
from isolator.diagnosis.kinematics import hysteretic_variable, shifted

REPLICATES = 12


def sample_noise_variance(
    features: Features,
    campaign: Campaign,
    force_noise: np.ndarray,
    displacement_noise: np.ndarray,
    axial_noise: np.ndarray,
    yield_displacement: float,
    *,
    replicates: int = REPLICATES,
    seed: int = 0,
    lag: float = 0.0,
) -> np.ndarray:
    """Variance of the force error that measurement noise leaves at each sample [N^2].

    Parameters
    ----------
    features, campaign : Features, Campaign
        The calibrated baseline's features (z, mu_base, the smoothed displacement) and the
        measured tests, whose raw displacement is perturbed.
    force_noise, displacement_noise, axial_noise : ndarray
        Noise standard deviation of each test's force [N], displacement [m], axial force [N].
    yield_displacement : float
        The baseline's u_y [m].
    replicates, seed : int
        Monte Carlo replicates and their seed (the diagnosis is deterministic).
    lag : float
        The baseline's channel lag [s], applied to the perturbed displacement too.
    """
    rng = np.random.default_rng(seed)
    variance = np.empty(len(features))
    radius = campaign.effective_radius
    for k, rec in enumerate(campaign.tests):
        idx = features.test == k
        n, mu = features.axial_force[idx], features.mu_base[idx]
        variance[idx] = force_noise[k] ** 2 + (axial_noise[k] * (
            mu * features.z[idx] + features.displacement[idx] / radius)) ** 2
        if displacement_noise[k] == 0.0:
            continue
        base = n * (mu * features.z[idx] + features.displacement[idx] / radius)
        spread = np.zeros(len(rec))
        for _ in range(replicates):
            noisy = rec.displacement + rng.normal(0.0, displacement_noise[k], len(rec))
            u = shifted(rec.time, smoothed_displacement(rec.time, noisy), lag)
            z = hysteretic_variable(np.ascontiguousarray(u), float(yield_displacement))
            spread += (n * (mu * z + u / radius) - base) ** 2
        variance[idx] += spread / replicates
    floor = 1e-12 * float(np.mean(features.force**2)) + 1e-300
    return np.maximum(variance, floor)
