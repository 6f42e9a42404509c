"""Sample-by-sample covariates of a campaign, its tests one after the other.

:func:`kinematic_features` computes what the measured histories alone decide; the baseline
calibration and the noise model fill in the rest (:func:`with_baseline`). The displacement
is the measured one through a short smoothing filter (:func:`smoothed_displacement`), and a
reversal must come back by several times the displacement noise, so sensor noise neither
makes reversals nor accumulates as travel.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

import numpy as np

from isolator.diagnosis.data import Campaign
from isolator.diagnosis.kinematics import (
    hysteretic_variable,
    noise_std,
    reversal_travel,
    turning_points,
)
from isolator.heating import (
    CentrePoint,
    MonitorLine,
    SurfaceHeating,
    ThermalProperties,
    sum_of_exponentials,
)

SURFACES = 2  # a DCFPB: the slider travels u / 2 over each plate and each takes half the heat
_REVERSAL_NOISE_MULTIPLE = 6.0  # a reversal must come back by 6 sigma of displacement noise
_REVERSAL_STROKE_FRACTION = 0.005  # ... and by 0.5 % of the stroke
SMOOTHING_WINDOW = 7  # samples of the cubic Savitzky-Golay filter on the displacement


@dataclass(frozen=True, eq=False)
class Features:
    """Covariates per sample, all tests one after the other.

    Attributes
    ----------
    sample, test : ndarray of int
        Index of the sample in the whole campaign (kept by :meth:`take`), and of its test.
    time, displacement, velocity, speed, force, axial_force, pressure : ndarray
        [s], [m], [m/s], [m/s] (|v|), [N], [N], [Pa] (N / contact area).
    since_reversal, travel, campaign_travel : ndarray
        Travel since the last reversal, from the start of the test, and from the start of
        the campaign (tests in the order run) [m].
    steps_since_reversal : ndarray of int
        Samples since the last reversal (0 at the reversal).
    cycle : ndarray of int
        Cycle of the sample within its test, from 1 (two reversals make a cycle).
    block : ndarray of int
        A number unique to each (test, half cycle): the unit of the block statistics.
    z, pendulum, mu_base : ndarray
        Return-map variable [-], N u / R_eff [N], the calibrated baseline's friction
        coefficient [-].
    temperature_rise, centre_rise : ndarray
        Contact-temperature rise from the measured friction power [degC] over the contact on
        the precise model's monitor line, and at the simplified model's centre point.
    noise_variance, weight : ndarray
        Variance of the force error noise alone leaves [N^2] (:mod:`.noise`), and the weight
        1 / (noise variance + the baseline's excess variance) [1/N^2] of fits and selection.
    """

    sample: np.ndarray
    test: np.ndarray
    time: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    speed: np.ndarray
    force: np.ndarray
    axial_force: np.ndarray
    pressure: np.ndarray
    since_reversal: np.ndarray
    travel: np.ndarray
    campaign_travel: np.ndarray
    steps_since_reversal: np.ndarray
    cycle: np.ndarray
    block: np.ndarray
    z: np.ndarray
    pendulum: np.ndarray
    mu_base: np.ndarray
    temperature_rise: np.ndarray
    centre_rise: np.ndarray
    noise_variance: np.ndarray
    weight: np.ndarray

    def __len__(self) -> int:
        return int(self.force.size)

    def take(self, index: np.ndarray) -> Features:
        """The features of the samples ``index`` only."""
        return Features(**{f.name: getattr(self, f.name)[index] for f in fields(self)})

    @property
    def friction_force(self) -> np.ndarray:
        """Measured force less the pendulum force [N]."""
        return self.force - self.pendulum

    @property
    def baseline_force(self) -> np.ndarray:
        """Force of the calibrated baseline, N u / R + mu N z [N]."""
        return self.pendulum + self.mu_base * self.axial_force * self.z


@dataclass(frozen=True)
class KinematicInfo:
    """Per-test scalars found with the kinematic features.

    Attributes
    ----------
    force_noise, displacement_noise, axial_noise : ndarray
        White-noise standard deviation of each test's force [N], displacement [m] and axial
        force [N] (zero for a constant axial force).
    turns : tuple of ndarray
        Reversal indices of each test (within the test).
    """

    force_noise: np.ndarray
    displacement_noise: np.ndarray
    axial_noise: np.ndarray
    turns: tuple[np.ndarray, ...]


def kinematic_features(campaign: Campaign) -> tuple[Features, KinematicInfo]:
    """Features that follow from the measured histories alone (z etc. left at zero)."""
    parts: dict[str, list[np.ndarray]] = {f.name: [] for f in fields(Features)}
    force_noise, disp_noise, axial_noise, all_turns = [], [], [], []
    campaign_offset, block_offset = 0.0, 0
    for k, rec in enumerate(campaign.tests):
        n = len(rec)
        sigma_u = noise_std(rec.displacement, order=4)
        u = smoothed_displacement(rec.time, rec.displacement)
        threshold = max(_REVERSAL_NOISE_MULTIPLE * sigma_u,
                        _REVERSAL_STROKE_FRACTION * float(np.ptp(u)))
        turns = turning_points(u, threshold)
        since, travel, half = reversal_travel(u, turns)
        cycle = half // 2 + 1
        values = {
            "sample": np.arange(n, dtype=np.int64) + sum(len(t) for t in campaign.tests[:k]),
            "test": np.full(n, k, dtype=np.int64), "time": rec.time,
            "displacement": u, "velocity": rec.velocity,
            "speed": np.abs(rec.velocity), "force": rec.force, "axial_force": rec.axial_force,
            "pressure": rec.axial_force / campaign.contact_area, "since_reversal": since,
            "travel": travel, "campaign_travel": campaign_offset + travel,
            "steps_since_reversal": np.arange(n) - turns[half], "cycle": cycle,
            "block": block_offset + half,
        }
        for name in ("z", "pendulum", "mu_base", "temperature_rise", "centre_rise",
                     "noise_variance", "weight"):
            values[name] = np.zeros(n)
        for name, value in values.items():
            parts[name].append(np.asarray(value))
        campaign_offset += float(travel[-1])
        block_offset += int(half.max()) + 1
        force_noise.append(noise_std(rec.force, order=3))
        disp_noise.append(sigma_u)
        axial_noise.append(0.0 if rec.constant_axial_force else noise_std(rec.axial_force))
        all_turns.append(turns)
    features = Features(**{name: np.concatenate(p) for name, p in parts.items()})
    return features, KinematicInfo(np.array(force_noise), np.array(disp_noise),
                                   np.array(axial_noise), tuple(all_turns))


def smoothed_displacement(time: np.ndarray, displacement: np.ndarray) -> np.ndarray:
    """The displacement [m] through a cubic Savitzky-Golay filter of ``SMOOTHING_WINDOW``
    samples (uneven steps: unfiltered).

    The bias on a smooth imposed history is of order d^4u/dt^4 window^4, while the filter cuts
    the noise the return map's stiff elastic branch (dz/du = 1/u_y) turns into force noise.
    """
    steps = np.diff(time)
    if displacement.size < 2 * SMOOTHING_WINDOW or np.ptp(steps) > 1e-6 * steps.mean():
        return np.asarray(displacement, dtype=float)
    from scipy.signal import savgol_filter

    return savgol_filter(displacement, SMOOTHING_WINDOW, 3, mode="interp")


def pendulum_force(features: Features, effective_radius: float) -> np.ndarray:
    """N u / R_eff [N] (zero for a flat slider, R_eff = inf)."""
    if math.isinf(effective_radius):
        return np.zeros(len(features))
    return features.axial_force * features.displacement / effective_radius


def return_map(features: Features, yield_displacement: float) -> np.ndarray:
    """z of every test (each starting at z = 0) for the yield displacement [m] given."""
    z = np.empty(len(features))
    for k in np.unique(features.test):
        idx = features.test == k
        z[idx] = hysteretic_variable(np.ascontiguousarray(features.displacement[idx]),
                                     float(yield_displacement))
    return z


def contact_temperature_rise(
    time: np.ndarray,
    position: np.ndarray,
    flux: np.ndarray,
    layout: MonitorLine | CentrePoint,
    contact_radius: float,
    thermal: ThermalProperties,
    *,
    heating: SurfaceHeating | None = None,
) -> np.ndarray:
    """Rise of the contact temperature under a given heat flux history (Eq. 4-6) [degC].

    Parameters
    ----------
    time, position : ndarray
        Sample times [s]; slider centre on the plate, from the plate centre [m].
    flux : ndarray
        Heat flux into the surface over the step ending at each sample [W/m^2], >= 0.
    layout : MonitorLine or CentrePoint
        The monitor points (precise or simplified model).
    contact_radius, thermal : float, ThermalProperties
        Slider radius [m] and the plate's material.
    heating : SurfaceHeating, optional
        A plate's heating history to continue, updated in place (default: a fresh plate).
    """
    if heating is None:
        heating = new_heating(position, layout, contact_radius, thermal)
    rise = np.zeros(time.size)
    if time.size:
        base, _, _ = heating.trial(float(position[0]), 1e-6)
        rise[0] = base - thermal.initial_temperature  # what is left of earlier tests
    for k in range(1, time.size):
        dt = float(time[k] - time[k - 1])
        base, newest, heated = heating.trial(float(position[k]), dt)
        rise[k] = base + newest * flux[k] - thermal.initial_temperature
        heating.commit(dt, heated, float(flux[k]))
    return rise


def new_heating(position: np.ndarray, layout: MonitorLine | CentrePoint, contact_radius: float,
                thermal: ThermalProperties) -> SurfaceHeating:
    """A fresh plate for slider positions up to ``max |position|`` [m]."""
    travel = float(np.max(np.abs(position))) + 1e-3
    return SurfaceHeating(layout, contact_radius, travel, thermal,
                          sum_of_exponentials(1.0e-6, 1.0e4, 1.0e-7))


def measured_temperature_rise(
    features: Features,
    campaign: Campaign,
    layout: MonitorLine | CentrePoint,
    thermal: ThermalProperties,
) -> np.ndarray:
    """Contact-temperature rise of every test from its measured friction power [degC].

    The flux into each of the two sliding surfaces is half the dissipated power
    max((F - N u / R_eff) v, 0) over the contact area. A test with ``rest_before`` (up to
    10^4 s) continues the previous test's plate after that rest, else starts cold; an
    ``initial_temperature`` above the first test's counts as a rise; a measured
    ``temperature`` changing by more than 1 degC is used instead.
    """
    rise = np.zeros(len(features))
    power = np.maximum((features.force - features.pendulum) * features.velocity, 0.0)
    flux = power / (campaign.contact_area * SURFACES)
    reach = np.abs(features.displacement).max() / SURFACES
    first = campaign.tests[0].initial_temperature
    heating = None
    for k, rec in enumerate(campaign.tests):
        idx = features.test == k
        if rec.temperature is not None and np.ptp(rec.temperature) > 1.0:
            rise[idx] = rec.temperature - rec.temperature[0]
            heating = None
            continue
        rest = rec.rest_before
        if heating is None or rest is None or rest > 1.0e4:
            heating = new_heating(np.array([reach]), layout, campaign.contact_radius, thermal)
        else:
            position = float(rec.displacement[0]) / SURFACES
            _, _, heated = heating.trial(position, max(rest, 1e-6))
            heating.commit(max(rest, 1e-6), heated, 0.0)
        offset = 0.0
        if rec.initial_temperature is not None and first is not None:
            offset = rec.initial_temperature - first
        rise[idx] = offset + contact_temperature_rise(
            rec.time, rec.displacement / SURFACES, flux[idx], layout, campaign.contact_radius,
            thermal, heating=heating)
    return rise


def with_baseline(features: Features, **values: np.ndarray) -> Features:
    """A copy with the baseline's arrays (z, pendulum, mu_base, the rises) set."""
    return replace(features, **values)
