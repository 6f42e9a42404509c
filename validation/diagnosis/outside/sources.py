"""The outside panel's three truth sources: the clean channels of a case's campaign.

Each source takes a case of :mod:`validation.diagnosis.outside.cases` and the set of its
effects switched on, and returns per test the clean (noise-free) channels: ``time``,
``displacement``, ``velocity``, ``axial_force``, ``force`` and the ``restoring`` part of the
force, and, where the truth has physics the labels leave out, its ``unlabelled`` shares.

``independent``
    :mod:`validation.diagnosis.independent` (numpy only, written from the paper and from
    physics; it shares no code with the package).
``opensees``
    OpenSees ``singleFPBearing`` / ``flatSliderBearing`` (Coulomb, VelDependent) and
    ``FPBearingPTV`` through
    :func:`structures.opensees.bearing.run_opensees_test`; instrument effects (lag, noise) are
    applied to its output.
``package``
    Our own element with the truths' extra physics,
    :func:`structures.diagnosis.truths.element_truth`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np

from validation.diagnosis import independent as ind
from validation.diagnosis.outside.cases import (
    NIGHT,
    SLIDER,
    Case,
    Sine,
    axial_load,
    rest_before,
)

# --- test histories ------------------------------------------------------------------------


def _axial_of(case: Case, sine: Sine, k: int):
    load = axial_load(case, sine)
    if not sine.varying:
        return lambda t: np.full(np.shape(t), load)
    omega = 2.0 * math.pi / sine.varying_period
    return lambda t: load * (1.0 + sine.varying * np.sin(omega * np.asarray(t) + 0.9 * k))


def _ind_tests(case: Case, cold: bool = False) -> list[ind.Test]:
    out = []
    for k, s in enumerate(case.tests):
        rest = None if cold else rest_before(case, k)
        out.append(ind.sine_test(s.amplitude, s.period, s.cycles, case.dt, _axial_of(case, s, k),
                                 initial_temperature=s.temperature, rest_before=rest))
    return out


def _lag(case: Case, active: set[str]) -> float:
    """The force channel's delay [s]: the nuisance lag, or the labelled one when active."""
    if "lag" in case.effects and "lag" not in active:
        return 0.0
    return case.lag_samples * case.dt


def _channels(case: Case, active: set[str]):
    """Per test: (record times, the force channel's times, u_a, v_a on those, axial)."""
    lag = _lag(case, active)
    for k, s in enumerate(case.tests):
        test = ind.sine_test(s.amplitude, s.period, s.cycles, case.dt, _axial_of(case, s, k))
        t = test.time
        shifted = t - lag
        on = shifted >= 0.0
        u = np.where(on, test.displacement(np.maximum(shifted, 0.0)), 0.0)
        v = np.where(on, test.velocity(np.maximum(shifted, 0.0)), 0.0)
        yield k, s, test, shifted, u, v


def _clean(test: ind.Test, force: np.ndarray, restoring: np.ndarray, **extra) -> dict:
    return {"time": test.time, "displacement": test.displacement(test.time),
            "velocity": test.velocity(test.time), "axial_force": test.axial(test.time),
            "force": np.asarray(force, float), "restoring": np.asarray(restoring, float),
            **extra}


# --- the three sources ----------------------------------------------------------------------


def independent_truth_bearing(case: Case, active: set[str]) -> ind.Bearing:
    """The independent truth's bearing with the effects ``active``: ``spec['base']`` holds the
    Bearing arguments always on, ``spec['effects'][e]`` those switched on with effect e."""
    kwargs = {"weight": case.weight, "radius": case.radius, "slider_diameter": SLIDER,
              "mu0": case.mu0, **case.spec.get("base", {})}
    for effect in sorted(active):
        kwargs.update(case.spec.get("effects", {}).get(effect, {}))
    if isinstance(kwargs.get("wear"), ind.Wear) and kwargs["wear"].kind == "power":
        travel = sum(4.0 * s.amplitude * s.cycles for s in case.tests)
        kwargs["wear"] = replace(kwargs["wear"], campaign_travel=travel)
    return ind.Bearing(**kwargs)


def independent(case: Case, active: set[str], *, cold: bool = False) -> list[dict]:
    """The independent truth (:func:`independent_truth_bearing`) through the case's campaign;
    ``cold`` forgets the heat between tests."""
    return ind.simulate(independent_truth_bearing(case, active), _ind_tests(case, cold),
                        lag=_lag(case, active))


def package(case: Case, active: set[str]) -> list[dict]:
    """Our element (:func:`structures.diagnosis.truths.element_truth`).

    ``spec``: ``mu_t0`` and ``dependencies`` of a PTVFriction (paper factors, precise monitor
    line when temperature acts; none: ConstantFriction(mu0)), ``u_y``, and per effect:
    ``heating``/``velocity``/``pressure`` add that dependency, ``breakaway`` and ``wear`` the
    truths' modulations (their arguments), ``stiffness`` the true radius. Each test is a fresh
    element, so tests after the first must follow a night's rest when heating acts.
    """
    from isolator.bearing import DCFPBearing
    from isolator.friction import ConstantFriction, PTVFriction
    from isolator.heating import MonitorLine, ThermalProperties
    from isolator.protocols import ImposedHistory
    from structures.diagnosis.truths import Breakaway, Wear, element_truth

    spec = case.spec
    names = {"heating": "temperature", "velocity": "velocity", "pressure": "pressure"}
    deps = set(spec.get("dependencies", ()))
    deps |= {names[e] for e in active if e in names}
    order = tuple(d for d in ("pressure", "velocity", "temperature") if d in deps)
    if "temperature" in order and any((rest_before(case, k) or NIGHT) < 1.0e4
                                      for k in range(len(case.tests))):
        raise ValueError(f"{case.pair}: the package's tests start cold; give nights' rests")
    radius = spec.get("true_radius", case.radius) if "stiffness" in active else case.radius
    total = sum(4.0 * s.amplitude * s.cycles for s in case.tests)
    wear = Wear(campaign_travel=total, **spec["wear"]) if "wear" in active else None
    breakaway = Breakaway(**spec["breakaway"]) if "breakaway" in active else None
    out, travel = [], 0.0
    for _, s, test, shifted, u, v in _channels(case, active):
        if order or spec.get("ptv", False):
            friction = PTVFriction(
                spec.get("mu_t0", 0.075),
                heating=MonitorLine() if "temperature" in order else None,
                dependencies=order,
                thermal=ThermalProperties(initial_temperature=s.temperature))
        else:
            friction = ConstantFriction(case.mu0)
        bearing = DCFPBearing(radius, SLIDER, axial_load(case, s), friction,
                              yield_displacement=spec.get("u_y", 5.0e-4))
        axial = test.axial(np.maximum(shifted, 0.0)) if s.varying else None
        truth = element_truth(bearing, ImposedHistory(shifted, u, v, "sine"), axial_load=axial,
                              breakaway=breakaway, wear=wear, travel_before=travel)
        travel += float(np.sum(np.abs(np.diff(u))))
        restoring = truth.axial_force * u / radius
        out.append(_clean(test, truth.force, restoring))
    return out


def opensees(case: Case, active: set[str]) -> list[dict]:
    """OpenSees through :func:`structures.opensees.bearing.run_opensees_test`.

    ``spec['element']``: ``coulomb`` (singleFPBearing, mu0), ``velocity`` (singleFPBearing
    VelDependent mapped from the paper's Eq. 2 with mu_fast = mu0; without the effect:
    Coulomb at mu0), ``ptv`` (FPBearingPTV, Kumar's factors, ``spec['ptv']`` maps an effect to
    its dependency; without: none, mu = MuRef). ``stiffness`` uses ``spec['true_radius']``.
    The normal-force coupling of singleFPBearing is the ``geometry`` effect when labelled
    (without it: W u / R + (F - N u / R) W / N from the same run), unlabelled otherwise.
    """
    from isolator.bearing import DCFPBearing
    from isolator.factors import KumarFactors
    from isolator.friction import ConstantFriction, PTVFriction
    from isolator.heating import MonitorLine
    from structures.opensees.bearing import fpbearingptv_equivalent, run_opensees_test

    spec = case.spec
    element = spec["element"]
    radius = spec.get("true_radius", case.radius) if "stiffness" in active else case.radius
    out = []
    for _, s, test, shifted, u, v in _channels(case, active):
        load = axial_load(case, s)
        u_y = spec.get("u_y", 5.0e-4)
        if element == "ptv":
            deps = tuple(spec["ptv"][e] for e in sorted(active) if e in spec["ptv"])
            friction = PTVFriction(spec.get("mu_t0", 0.06), heating=MonitorLine(),
                                   factors=KumarFactors(), dependencies=deps)
            bearing = fpbearingptv_equivalent(DCFPBearing(radius, SLIDER, load, friction,
                                                          yield_displacement=u_y))
            kind = "ptv"
        elif element == "velocity" and "velocity" in active:
            friction = PTVFriction(case.mu0, heating=None, dependencies=("velocity",))
            bearing = DCFPBearing(radius, SLIDER, load, friction, yield_displacement=u_y)
            kind = "velocity"
        else:
            bearing = DCFPBearing(radius, SLIDER, load, ConstantFriction(case.mu0),
                                  yield_displacement=u_y)
            kind = "coulomb"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = run_opensees_test(bearing, shifted - shifted[0], u, v, element=kind)
        force, normal = r.force, r.axial_load
        if kind == "ptv":
            spherical = load * u / np.sqrt(radius**2 - u**2)
            linear = load * u / radius
            out.append(_clean(test, force, spherical, unlabelled={
                "spherical restoring law (FPBearingPTV)": spherical - linear}))
            continue
        restoring = normal * u / radius
        decoupled = load * u / radius + (force - restoring) * load / normal
        if "geometry" in case.effects and "geometry" not in active:
            out.append(_clean(test, decoupled, load * u / radius))
            continue
        extra = {} if "geometry" in case.effects else {
            "unlabelled": {"normal-force coupling N = W + F u/R (singleFPBearing)":
                           force - decoupled}}
        out.append(_clean(test, force, restoring, **extra))
    return out


SOURCE_FUNCTIONS = {"independent": independent, "package": package, "opensees": opensees}
