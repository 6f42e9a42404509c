"""The heat a named friction law implies for a baseline that heats (one direction).

A ``simplified`` or ``precise`` baseline tracks its contact temperature from its *own* friction
power (:func:`isolator.diagnosis.baseline._run_baseline`, each test from a cold plate). When an
effect on mu is missing from it (``precise --without velocity`` on a bearing whose friction
does depend on the speed), its heat input is computed with the wrong mu, so its temperature
factor is off too, by a share that follows the missing law. Once that law is named, the
baseline's temperature should follow the named law's friction power: the rise changes by

    dT(t) = R[ P_base (m - 1) ](t),

R the linear heat-conduction operator of the baseline's monitor points (Eq. 4-6, each test
from a cold plate as the baseline runs it), P_base the baseline's friction power
mu_base N max(z v, 0) and m the named law's factor on mu; its temperature factor changes by
exp(s dT), s = d ln beta / dT of the paper's Eq. 3 (-0.007 1/degC). This factor is the
baseline's own physics with the named law's heat, never an effect of its own:
:class:`isolator.diagnosis.decision.Problem` judges a second effect on mu over it too (a
``heating`` beside a named law can be only this).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from isolator.diagnosis.baseline import BaselineSpec
from isolator.diagnosis.data import Campaign
from isolator.diagnosis.features import SURFACES, Features, contact_temperature_rise
from isolator.factors import paper_temperature_factor
from isolator.heating import ThermalProperties

ImpliedHeat = Callable[[np.ndarray], np.ndarray]


def temperature_slope() -> float:
    """d ln beta / dT of the paper's temperature factor (Eq. 3) [1/degC]."""
    beta, slope = paper_temperature_factor(20.0)
    return float(slope / beta)


def implied_heat(campaign: Campaign, features: Features,
                 spec: BaselineSpec) -> ImpliedHeat | None:
    """A function ``m -> ln`` (the change of the baseline's log temperature factor at every
    sample of ``features`` [-] when its friction power is multiplied by ``m``, a factor on mu
    at every sample [-]), or None when the baseline ``spec`` does not heat.

    ``features`` are the calibrated baseline's (``mu_base``, ``z`` set), in the campaign's
    test order.
    """
    if not spec.heats:
        return None
    layout = spec.layout()
    thermal = ThermalProperties()
    slope = temperature_slope()
    power = features.mu_base * features.axial_force * np.maximum(
        features.z * features.velocity, 0.0)
    flux = power / (campaign.contact_area * SURFACES)

    def log_change(m: np.ndarray) -> np.ndarray:
        delta = np.zeros(len(features))
        change = flux * (np.asarray(m, dtype=float) - 1.0)
        for k in range(len(campaign.tests)):
            idx = features.test == k
            delta[idx] = contact_temperature_rise(
                features.time[idx], features.displacement[idx] / SURFACES, change[idx],
                layout, campaign.contact_radius, thermal)
        return slope * delta

    return log_change
