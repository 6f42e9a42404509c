"""The baseline model to diagnose, calibrated on the data first.

A baseline is one of the paper's friction models, ``constant`` (Eq. 8), ``simplified`` or
``precise`` (Eq. 7), possibly without some of its effects (``precise --without heating``).
Calibration fits its own parameters, so that the gap left is what its *form* cannot explain:
mu (constant model) or mu_t0, the yield displacement u_y (unless given) and a lag of the force
channel of up to ``NUISANCE_LAG_SAMPLES`` samples, to a fraction of a sample.

For an imposed displacement z(t) depends on u(t) and u_y only, so
F = N u / R_eff + mu(t) N z(t) and mu is a linear least-squares factor for each u_y; u_y is
found on a logarithmic grid refined by a bounded scalar search. A PTV model's mu(t) comes from
the virtual test machine (:func:`isolator.testrig.run_test`) on the measured displacement,
velocity and axial load; it is proportional to mu_t0 but for the heating, so mu_t0 is
rescaled by the fitted factor and the run repeated until the factor is 1 to 1e-3.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import minimize_scalar

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_choice, check_real
from isolator.bearing import AxialLoadHistory, DCFPBearing
from isolator.diagnosis.data import Campaign, check_plausible
from isolator.diagnosis.features import (
    Features,
    measured_temperature_rise,
    pendulum_force,
    return_map,
    with_baseline,
)
from isolator.diagnosis.kinematics import shifted
from isolator.diagnosis.transition import NUISANCE_LAG_SAMPLES
from isolator.friction import DEPENDENCIES, PTVFriction
from isolator.heating import CentrePoint, MonitorLine, ThermalProperties
from isolator.testrig import run_test

BASELINE_MODELS = ("constant", "simplified", "precise")
REMOVABLE_EFFECTS = ("heating", "velocity", "pressure")
DEFAULT_MU_T0 = 0.075  # the paper's mu_t0, the start of the calibration
SIMPLIFIED_REFINEMENT = 0.5  # the paper's lambda
YIELD_DISPLACEMENT_MAX = 2.5e-3  # [m] the largest pre-sliding transition calibrated
RIGID_PLASTIC_LIMIT = 1.0e-5  # [m] the smallest: the force reverses at the displacement peak
_YIELD_GRID = np.geomspace(RIGID_PLASTIC_LIMIT, YIELD_DISPLACEMENT_MAX, 26)  # [m] candidates
_LAG_GRID = np.arange(-NUISANCE_LAG_SAMPLES, NUISANCE_LAG_SAMPLES + 0.25, 0.5)
_MAX_ITERATIONS = 6
_SCALE_TOLERANCE = 1.0e-3


@dataclass(frozen=True)
class BaselineSpec:
    """Which baseline to diagnose.

    Parameters
    ----------
    model : {"constant", "simplified", "precise"}
        The paper's friction model.
    without : tuple of str
        Effects of a ``simplified`` or ``precise`` model switched off (``REMOVABLE_EFFECTS``).
    yield_displacement : float or None
        Yield displacement u_y of the return map [m]; None calibrates it.
    """

    model: str
    without: tuple[str, ...] = ()
    yield_displacement: float | None = None

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_choice(self.model, "model", owner, BASELINE_MODELS)
        without = tuple(dict.fromkeys(self.without))
        for name in without:
            check_choice(name, "without", owner, REMOVABLE_EFFECTS)
        if self.model == "constant" and without:
            raise InputError(f"The 'without' parameter of {owner} must be empty for the "
                             f"constant model, which has no effects to remove. Got {without!r}.")
        object.__setattr__(self, "without", without)
        if self.yield_displacement is not None:
            check_real(self.yield_displacement, "yield_displacement", owner, low=0.0,
                       low_open=True, high=0.1)

    @property
    def label(self) -> str:
        """The baseline as a user writes it, e.g. ``"precise --without heating"``."""
        return " ".join([self.model, *(f"--without {w}" for w in self.without)])

    @property
    def heats(self) -> bool:
        """Whether the baseline tracks a contact temperature."""
        return self.model != "constant" and "heating" not in self.without

    def layout(self) -> MonitorLine | CentrePoint:
        """Monitor points of the baseline's heating (the precise model's line by default)."""
        if self.model == "simplified":
            return CentrePoint(refinement=SIMPLIFIED_REFINEMENT)
        return MonitorLine()

    def friction(self, mu_t0: float, initial_temperature: float) -> PTVFriction:
        """The PTV friction model of a ``simplified`` or ``precise`` baseline."""
        if self.model == "constant":
            raise ValueError("The constant baseline has no PTV friction model.")
        dependencies = tuple(d for d in DEPENDENCIES
                             if not (d == "temperature" and "heating" in self.without)
                             and d not in self.without)
        return PTVFriction(mu_t0=mu_t0, heating=self.layout() if self.heats else None,
                           dependencies=dependencies,
                           thermal=ThermalProperties(initial_temperature=initial_temperature))


@dataclass(frozen=True)
class BaselineFit:
    """A calibrated baseline.

    Attributes
    ----------
    spec, parameters : BaselineSpec, dict
        The baseline and its calibrated ``mu`` (constant) or ``mu_t0`` [-] and
        ``yield_displacement`` [m].
    features : Features
        The campaign's features with the baseline's z, pendulum force, mu(t) and temperature
        rises.
    iterations : int
        Runs of the virtual test machine (0 for the constant model).
    lag : float
        Calibrated lag of the force channel behind the displacement [s], applied to the
        features' displacement.
    sample_interval : float
        Median sampling interval [s].
    """

    spec: BaselineSpec
    parameters: dict[str, float]
    features: Features
    iterations: int
    lag: float = 0.0
    sample_interval: float = 0.01
    yield_range: tuple[float, float] = (RIGID_PLASTIC_LIMIT, YIELD_DISPLACEMENT_MAX)


EDGE_TOLERANCE = 0.03  # a nuisance within 3 % of its range's end (in log u_y, in samples) is at it


def nuisance_edges(fit: BaselineFit) -> dict[str, str]:
    """The baseline's nuisance parameters fitted at an edge of their range: a finding, not a
    calibration. ``{"yield_displacement": "top"}`` when u_y sits at the top of its grid (a play
    or a soft transition it may stand in for; its bottom is the rigid-plastic limit, a physical
    reading) and ``{"lag": "lead" | "late"}`` when the channel offset sits at
    +-``NUISANCE_LAG_SAMPLES`` (``lead``: the force leads the displacement)."""
    samples = fit.lag / fit.sample_interval if fit.sample_interval else 0.0
    return edges_of(fit.parameters["yield_displacement"], fit.yield_range, samples,
                    calibrated=fit.spec.yield_displacement is None)


def edges_of(yield_displacement: float, yield_range: tuple[float, float], lag_samples: float,
             *, calibrated: bool = True) -> dict[str, str]:
    """:func:`nuisance_edges` of a u_y [m] calibrated (``calibrated``) within
    ``yield_range`` [m] and a channel lag of ``lag_samples`` [samples]: in one direction and
    in two."""
    edges: dict[str, str] = {}
    if calibrated:
        low, high = (np.log10(x) for x in yield_range)
        value = np.log10(yield_displacement)
        if high > low and value >= high - EDGE_TOLERANCE * (high - low):
            edges["yield_displacement"] = "top"
    if abs(lag_samples) >= (1.0 - EDGE_TOLERANCE) * NUISANCE_LAG_SAMPLES:
        edges["lag"] = "late" if lag_samples > 0.0 else "lead"
    return edges


def calibrate(campaign: Campaign, features: Features, spec: BaselineSpec) -> BaselineFit:
    """Calibrate the baseline on the whole campaign (see the module docstring), once the
    tests' levels pass :func:`~isolator.diagnosis.data.check_plausible`."""
    check_plausible(campaign)
    dt = float(np.median(np.diff(features.time)[np.diff(features.test) == 0]))
    t0 = _initial_temperature(campaign)
    iterations = 0
    if spec.model == "constant":
        shape = np.ones(len(features))
        mu_t0 = 1.0
    else:
        mu_t0 = DEFAULT_MU_T0
        shape = _run_baseline(campaign, features, spec, mu_t0, t0, spec.yield_displacement
                              or 5.0e-4)
        iterations = 1
    while True:
        lag = _fit_lag(campaign, features, shape, spec.yield_displacement, dt)
        moved = _shifted_features(features, lag)
        pendulum = pendulum_force(moved, campaign.effective_radius)
        target = moved.force - pendulum
        u_y, scale, _ = _fit_yield_and_scale(moved, target, shape, spec.yield_displacement)
        if spec.model == "constant" or not spec.heats or abs(scale - 1.0) <= _SCALE_TOLERANCE:
            break
        if iterations >= _MAX_ITERATIONS:
            break
        mu_t0 *= scale
        shape = _run_baseline(campaign, features, spec, mu_t0, t0, u_y)
        iterations += 1
    mu_t0 *= scale
    mu_base = shape * scale
    z = return_map(moved, u_y)
    name = "mu" if spec.model == "constant" else "mu_t0"
    thermal = ThermalProperties(initial_temperature=t0)
    done = with_baseline(moved, z=z, pendulum=pendulum, mu_base=mu_base)
    line = measured_temperature_rise(done, campaign, MonitorLine(), thermal)
    centre = measured_temperature_rise(done, campaign, CentrePoint(SIMPLIFIED_REFINEMENT),
                                       thermal)
    return BaselineFit(spec, {name: float(mu_t0), "yield_displacement": float(u_y)},
                       with_baseline(done, temperature_rise=line, centre_rise=centre),
                       iterations, lag, dt, _yield_range(moved))


def _shifted_features(features: Features, lag: float) -> Features:
    """The features with the displacement a force lagging by ``lag`` [s] belongs to.

    The velocity stays as measured: an unmodelled effect at low speed can bias the lag by a
    sample or two, so the speed an effect on mu reads stays right, and the sliding phase
    refits the lag with every model (:data:`isolator.diagnosis.transition.TIMING`)."""
    if lag == 0.0:
        return features
    u = np.empty(len(features))
    for k in np.unique(features.test):
        idx = features.test == k
        u[idx] = shifted(features.time[idx], features.displacement[idx], lag)
    return replace(features, displacement=u)


def _fit_lag(campaign: Campaign, features: Features, shape: np.ndarray,
             fixed_yield: float | None, dt: float) -> float:
    """The channel offset [s] within ``NUISANCE_LAG_SAMPLES`` that fits the baseline best."""
    def sse(samples: float) -> float:
        moved = _shifted_features(features, samples * dt)
        target = moved.force - pendulum_force(moved, campaign.effective_radius)
        return _fit_yield_and_scale(moved, target, shape, fixed_yield)[2]

    costs = [sse(x) for x in _LAG_GRID]
    i = int(np.argmin(costs))
    lo = _LAG_GRID[max(i - 1, 0)]
    hi = _LAG_GRID[min(i + 1, _LAG_GRID.size - 1)]
    best = minimize_scalar(sse, bounds=(lo, hi), method="bounded", options={"xatol": 0.02})
    samples = float(best.x) if best.fun <= costs[i] else float(_LAG_GRID[i])
    return samples * dt


def _initial_temperature(campaign: Campaign, test: int = 0) -> float:
    rec = campaign.tests[test]
    if rec.initial_temperature is not None:
        return float(rec.initial_temperature)
    return 20.0 if rec.temperature is None else float(rec.temperature[0])


def _scale_fit(target: np.ndarray, regressor: np.ndarray) -> tuple[float, float]:
    """(least-squares factor, sum of squared residuals) of target ~ factor * regressor."""
    denominator = float(np.dot(regressor, regressor))
    if denominator == 0.0:
        return 0.0, float(np.dot(target, target))
    factor = float(np.dot(regressor, target)) / denominator
    residual = target - factor * regressor
    return factor, float(np.dot(residual, residual))


def _yield_range(features: Features) -> tuple[float, float]:
    """The range of the u_y grid for these features [m] (its top: a quarter of the stroke)."""
    grid = _yield_grid(features)
    return float(grid[0]), float(grid[-1])


def _yield_grid(features: Features) -> np.ndarray:
    stroke = float(np.percentile(np.abs(features.displacement), 99))
    return _YIELD_GRID[max(0.25 * stroke, _YIELD_GRID[1]) >= _YIELD_GRID]


def _fit_yield_and_scale(
    features: Features, target: np.ndarray, shape: np.ndarray, fixed: float | None
) -> tuple[float, float, float]:
    """(u_y [m], the scale of mu [-], the sum of squared residuals [N^2])."""
    regressor = shape * features.axial_force

    def sse(log_uy: float) -> float:
        return _scale_fit(target, regressor * return_map(features, 10.0**log_uy))[1]

    if fixed is not None:
        u_y = float(fixed)
    else:
        grid = _yield_grid(features)
        logs = np.log10(grid)
        costs = [sse(x) for x in logs]
        i = int(np.argmin(costs))
        lo, hi = logs[max(i - 1, 0)], logs[min(i + 1, logs.size - 1)]
        if hi > lo:
            best = minimize_scalar(sse, bounds=(lo, hi), method="bounded",
                                   options={"xatol": 1e-3})
            u_y = float(10.0 ** best.x) if best.fun <= costs[i] else float(grid[i])
        else:
            u_y = float(grid[i])
    scale, cost = _scale_fit(target, regressor * return_map(features, u_y))
    if not scale > 0.0:
        raise InputError("The baseline's friction coefficient came out non-positive: the "
                         "force does not oppose the motion. Check the sign convention of "
                         "'force' (it must resist the imposed displacement).")
    return u_y, scale, cost


def _run_baseline(
    campaign: Campaign, features: Features, spec: BaselineSpec, mu_t0: float, t0: float,
    yield_displacement: float,
) -> np.ndarray:
    """mu(t) of a PTV baseline run through the virtual test machine on every test."""
    mu = np.empty(len(features))
    for k, rec in enumerate(campaign.tests):
        idx = features.test == k
        start = rec.initial_temperature
        friction = spec.friction(mu_t0, t0 if start is None else float(start))
        time = rec.time - rec.time[0]
        load = (float(rec.axial_force[0]) if rec.constant_axial_force
                else AxialLoadHistory(time, rec.axial_force))
        capacity = max(1.05 * float(np.max(np.abs(rec.displacement))), 0.01)
        radius = campaign.effective_radius
        bearing = DCFPBearing(radius, campaign.slider_diameter, load, friction,
                              yield_displacement=min(yield_displacement, 0.1),
                              displacement_capacity=capacity)
        result = run_test(bearing, time, rec.displacement, rec.velocity, name=rec.name)
        mu[idx] = result.mu
    if not np.all(np.isfinite(mu)):
        raise ValueError(f"The {spec.label} baseline gave a non-finite friction coefficient.")
    return mu


def refit_scale(features: Features, index: np.ndarray | None = None) -> float:
    """Least-squares factor on the baseline's mu(t) over the samples ``index`` [-]."""
    f = features if index is None else features.take(index)
    return _scale_fit(f.force - f.pendulum, f.mu_base * f.axial_force * f.z)[0]


def describe(fit: BaselineFit) -> str:
    """One line: the baseline and its calibrated parameters."""
    parts = [f"{k} = {v:.4g}" + (" m" if k == "yield_displacement" else "")
             for k, v in fit.parameters.items()]
    return f"{fit.spec.label} ({', '.join(parts)})"

