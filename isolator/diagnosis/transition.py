"""The pre-sliding transition after each reversal: its window and what is left in it.

After a reversal the force swings from one sliding level to the other in a way that does not
belong to the friction law: the pre-sliding stiffness (elastic-plastic with u_y,
rigid-plastic, a smooth Bouc-Wen curve), a channel lag of a sample or two, the sampling. The
residual inside the *transition window* (within ``WINDOW_YIELDS`` u_y of travel or
``WINDOW_SAMPLES`` samples of a reversal) is reported on its own, and the friction law is
judged outside it, so a transition mismatch can neither mask an effect nor turn ``none``
into ``unexplained``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from isolator.diagnosis.effects import Effect, Parameter
from isolator.diagnosis.features import Features

WINDOW_YIELDS = 3.0  # the window: within 3 u_y of travel after a reversal ...
WINDOW_SAMPLES = 3  # ... or within 3 samples of it
MIN_WINDOW = 2.0e-4  # [m] the travel window is at least 0.2 mm
NUISANCE_LAG_SAMPLES = 2.0  # the channel offset the baseline calibrates, in samples


def window_travel(yield_displacement: float, half_width: float = 0.0) -> float:
    """Travel after a reversal inside the transition window [m] (a play adds its width)."""
    return max(WINDOW_YIELDS * yield_displacement, MIN_WINDOW) + 2.0 * half_width


def in_transition(features: Features, yield_displacement: float,
                  half_width: float = 0.0) -> np.ndarray:
    """Whether each sample lies in the transition window after a reversal."""
    travel = window_travel(yield_displacement, half_width)
    return (features.since_reversal < travel) | (features.steps_since_reversal < WINDOW_SAMPLES)


def window_statistics(r2: np.ndarray, noise: np.ndarray, samples: int,
                      force_ms: float) -> tuple[float, float]:
    """(the mean squared residual over the noise variance inside the transition windows [-],
    the excess above the noise there as an RMS over the whole test of ``samples`` samples,
    over the RMS force [-]) from the squared residual ``r2`` and the noise variance
    ``noise`` [N^2] of the windows' samples and the mean square force ``force_ms`` [N^2]: the
    transition's materiality, in one direction and in two (both axes summed)."""
    score = float(np.mean(r2 / noise))
    excess = float(np.sum(r2 - noise)) / samples
    return score, float(np.sqrt(max(excess, 0.0) / force_ms))


@dataclass(frozen=True)
class TransitionFinding:
    """What the baseline leaves inside the transition window.

    Attributes
    ----------
    yield_displacement, rigid_plastic : float, bool
        The calibrated u_y [m], and whether it is the rigid-plastic limit.
    window_travel, window_samples : float, int
        Extent of the window after a reversal [m], [samples].
    sample_share, energy_share : float
        Share of the samples and of the held-out residual energy in the window [-].
    rms, sliding_rms : float
        RMS residual inside and outside the window [N].
    relative_rms : float
        ``rms`` over the RMS force [-].
    score, excess : float
        Inside the window: the mean squared residual over the noise variance [-] (about 1 for
        noise alone), and the excess energy above the noise as an RMS over the whole test,
        over the RMS force [-] (the verdict's materiality rule,
        :meth:`isolator.diagnosis.decision.Problem.transition_gap`).
    """

    yield_displacement: float
    rigid_plastic: bool
    window_travel: float
    window_samples: int
    sample_share: float
    energy_share: float
    rms: float
    relative_rms: float
    sliding_rms: float
    score: float = float("nan")
    excess: float = 0.0

    def statement(self) -> str:
        """One sentence on the transition."""
        kind = ("rigid-plastic (the force reverses at the displacement peak)"
                if self.rigid_plastic else
                f"elastic-plastic with u_y = {1e3 * self.yield_displacement:.3g} mm")
        return (f"Pre-sliding transition calibrated as {kind}; inside the window "
                f"({1e3 * self.window_travel:.3g} mm or {self.window_samples} samples after "
                f"each reversal, {100 * self.sample_share:.0f} % of the samples) the residual "
                f"is {self.rms:.4g} N RMS ({100 * self.relative_rms:.2f} % of the RMS force, "
                f"{100 * self.energy_share:.0f} % of the residual energy"
                + (f", {np.sqrt(self.score):.3g} x the noise there" if np.isfinite(self.score)
                   else "")
                + f") against {self.sliding_rms:.4g} N while sliding.")


def transition_finding(features: Features, prediction: np.ndarray, window: np.ndarray,
                       yield_displacement: float, rigid_limit: float,
                       half_width: float = 0.0) -> TransitionFinding:
    """The residual ``force - prediction`` inside and outside the ``window`` mask."""
    residual = features.force - prediction
    energy = residual**2
    total = float(energy.sum()) or 1.0
    force_rms = float(np.sqrt(np.mean(features.force**2))) or 1.0
    inside = float(np.sqrt(np.mean(energy[window]))) if window.any() else 0.0
    outside = float(np.sqrt(np.mean(energy[~window]))) if (~window).any() else 0.0
    score, excess = float("nan"), 0.0
    noise = getattr(features, "noise_variance", None)
    if noise is not None and window.any():
        score = float(np.mean(energy[window] / noise[window]))
        extra = float(np.sum(energy[window] - noise[window])) / energy.size
        excess = float(np.sqrt(max(extra, 0.0))) / force_rms
    return TransitionFinding(float(yield_displacement),
                             bool(yield_displacement <= 1.5 * rigid_limit),
                             window_travel(yield_displacement, half_width), WINDOW_SAMPLES,
                             float(window.mean()), float(energy[window].sum()) / total,
                             inside, inside / force_rms, outside, score, excess)


def _timing_extra(theta, f, c):
    # N u(t - tau) / R = N u / R - tau N v / R to first order: a further lag tau
    return -theta[0] * c.sample_interval * f.axial_force * f.velocity / c.effective_radius


TIMING = Effect(
    "timing", "the channel offset, refitted with every model of the sliding phase",
    "a time offset between the force and displacement channels shifts the pendulum force "
    "by N v tau / R_eff while sliding (the friction force is unchanged away from reversals)",
    (Parameter("samples", 0.0, -NUISANCE_LAG_SAMPLES, NUISANCE_LAG_SAMPLES, edge_ok=True),),
    "force",
    extra=_timing_extra,
    reading=lambda theta, stderr, c: {
        "lag_correction": (float(theta[0]) * c.sample_interval,
                           float(stderr[0]) * c.sample_interval, "s")})
"""A nuisance term of every sliding-phase model, never named: the baseline's lag refitted
within ``NUISANCE_LAG_SAMPLES`` samples, to first order in the pendulum force."""
