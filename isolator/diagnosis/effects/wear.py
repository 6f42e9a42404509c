"""``wear``: friction drifts with the travel accumulated over the campaign.

m = 1 + a g(S), S the travel accumulated over the campaign (tests in the order run), g rising
from 0 to 1 over the campaign, exponentially with a travel scale tau S_total (linear as tau
grows): a drift of friction by a fraction a. Flexible form: monotone in S with a free step at
the start of every test (a drop from test to test).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.diagnosis.effects.base import Effect, Parameter, exp10, linear


def modulation(a, travel: np.ndarray, scale, *, per_campaign: bool) -> np.ndarray:
    """m = 1 + a g [-], g = 1 - exp(-S / L) of the accumulated ``travel`` S over a travel
    ``scale`` L (the same unit): the effect's form in one direction and in two. With
    ``per_campaign`` S and L are shares of the campaign's travel and g is divided by its
    value at the campaign's end, so that ``a`` is the change over the campaign (one
    direction); without, ``a`` is the change as S grows large (two directions, S and L in m)."""
    growth = -np.expm1(-travel / scale)
    if per_campaign:
        growth = growth / -math.expm1(-1.0 / scale)
    return 1.0 + a * growth


def _factor(theta, f, c):
    share = f.campaign_travel / max(c.campaign_travel, 1e-12)
    return modulation(theta[0], share, 10.0 ** theta[1], per_campaign=True)


def _reading(theta, stderr, c):
    tau, stau = exp10(theta, stderr, 1)
    total = c.campaign_travel
    return {"change_over_campaign": (*linear(theta, stderr, 0), "-"),
            "travel_scale": (tau * total, stau * total, "m"),
            "campaign_travel": (total, 0.0, "m")}


EFFECT = Effect(
    "wear", "friction drifts with the travel accumulated over the campaign",
    "the sliding surface changes with use (run-in, wear of the liner, loss of lubricant): "
    "friction drifts with the travel accumulated over the tests in the order run",
    (Parameter("a", -0.1, -0.9, 3.0),
     Parameter("log_tau", 0.0, -1.3, 1.3, log=True, edge_ok=True)), "mu",
    factor=_factor, variable=lambda f, c: f.campaign_travel, reading=_reading, order=50)
