"""The tuning panel's records (a test, a case) and its three truth sources.

Each source takes a case of :mod:`validation.diagnosis.tuning.cases` and the set of its effects
switched on, and returns per test the clean (noise-free) channels: ``time``, ``displacement``,
``velocity``, ``axial_force``, ``force`` and the ``bearing``'s displacement.

- ``independent``: :mod:`validation.diagnosis.tuning.truths` (numpy only, written from
  the paper and physics; shares no code with the package);
- ``opensees``: OpenSees singleFPBearing (Coulomb, VelDependent) and FPBearingPTV through
  :func:`structures.diagnosis.truths.opensees_truth`;
- ``package``: our own element (:func:`structures.diagnosis.truths.element_truth`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from validation.diagnosis.tuning import truths as ind

SLIDER = 0.3  # [m]
RADIUS = 4.5  # [m]
AREA = math.pi * (0.5 * SLIDER) ** 2
W = 60.0e6 * AREA  # [N] 4.24 MN at 60 N/mm^2
MU0 = 0.041  # the paper's mu_0, 300 mm slider
LABEL_MIN = 0.03  # a labelled effect: >= 3 % of the RMS force
UNLABELLED_MAX = 0.01  # unlabelled physics: <= 1 %


@dataclass(frozen=True)
class Test:
    """One test of a design: sine amplitude [m], period [s], cycles, axial load factor, the
    relative amplitude of an axial load varying in time, rest before it [s]."""

    amplitude: float
    period: float
    cycles: int
    load: float = 1.0
    varying: float = 0.0
    rest: float | None = None


@dataclass(frozen=True)
class Case:
    """One case: its true effects, source, truth, campaign and nuisance."""

    effects: tuple[str, ...]
    half: str
    source: str
    truth: str
    tests: tuple[Test, ...]
    make: Callable  # make(case, active effects) -> list of clean dicts per test
    dt: float = 0.01
    noise: float = 0.01
    colour: float = 0.0
    drift: float = 0.0  # a drift of the force zero over each test, a fraction of mu0 W
    displacement_noise: float = 2.0e-5
    lag_samples: float = 0.0  # nuisance lag (<= 1.5 samples) or a labelled lag
    velocity_column: bool = True
    axial_column: bool = False
    baseline: str = "constant"
    without: tuple[str, ...] = ()
    radius: float = RADIUS  # what the diagnosis is told
    options: dict = field(default_factory=dict)


def _sine(test: Test, dt: float) -> tuple[np.ndarray, Callable]:
    n = round(test.cycles * test.period / dt)
    t = np.arange(n + 1) * dt
    omega = 2.0 * math.pi / test.period
    return t, (lambda x: test.amplitude * np.sin(omega * x))


def _axial(test: Test, t: np.ndarray, k: int) -> np.ndarray:
    load = test.load * W
    if test.varying:
        return load * (1.0 + test.varying * np.sin(2.0 * math.pi * t / 1.7 + k))
    return np.full(t.size, load)


# --- truth makers ---------------------------------------------------------------------------


def independent(case: Case, active: set[str]) -> list[dict]:
    """The independent truth of ``case`` with the effects ``active`` switched on."""
    o = case.options
    truth = ind.Truth(
        weight=W, radius=o.get("true_radius", case.radius), slider_diameter=SLIDER,
        mu0=o.get("mu0", MU0), transition=o.get("transition", "elastic-plastic"),
        yield_displacement=o.get("u_y", 5e-4),
        geometry="spherical" if "geometry" in active else "linear",
        velocity=o.get("velocity") if "velocity" in active else o.get("base_velocity"),
        pressure="pressure" in active or o.get("base_pressure", False),
        heating="heating" in active or o.get("base_heating", False),
        breakaway=o.get("breakaway") if "breakaway" in active else None,
        direction=o.get("direction", 0.0) if "asymmetry" in active else 0.0,
        backlash=o.get("backlash", 0.0) if "backlash" in active else 0.0)
    if "stiffness" not in active:
        truth = replace(truth, radius=case.radius)
    out, plate, clock = [], None, 0.0
    if truth.heating:
        reach = max(t.amplitude for t in case.tests) / 2.0
        plate = ind.Plate(reach, truth.contact_radius)
    lag = case.lag_samples * case.dt if ("lag" in active or "lag" not in case.effects) else 0.0
    for k, test in enumerate(case.tests):
        t, motion = _sine(test, case.dt)
        if truth.heating and k > 0 and test.rest is None:  # a long rest: the plate is cold
            plate = ind.Plate(reach, truth.contact_radius)
        clock += (test.rest or 0.0)
        axial = _axial(test, t, k)
        if lag:
            clean = ind.lagged(truth, t, motion, lag,
                               axial_of=lambda x, tt=test, kk=k: _axial(tt, x, kk))
        else:
            clean = ind.simulate(truth, t, motion(t), axial=axial, plate=plate,
                                 start_time=clock)
        clock += float(t[-1])
        factor = 1.0
        if "wear" in active and o.get("wear_drop"):
            factor = 1.0 + o["wear_drop"] * k
        elif "wear" in active and o.get("wear_power"):
            change, power = o["wear_power"]
            factor = 1.0 + change * ((k + 1) / len(case.tests)) ** power
        if factor != 1.0:
            restoring = (np.zeros(t.size) if math.isinf(truth.radius)
                         else clean["axial_force"] * clean["bearing"] / truth.radius)
            clean["force"] = restoring + factor * (clean["force"] - restoring)
        clean["displacement"] = motion(t)
        clean["velocity"] = np.gradient(clean["displacement"], t)
        out.append(clean)
    return out


def package(case: Case, active: set[str]) -> list[dict]:
    """Our element (``structures.diagnosis.truths``) with ``active`` effects."""
    from isolator.bearing import DCFPBearing
    from isolator.friction import ConstantFriction, PTVFriction
    from isolator.heating import MonitorLine
    from isolator.protocols import ImposedHistory
    from structures.diagnosis.truths import Breakaway, Wear, element_truth

    o = case.options
    deps = tuple(d for d, e in (("pressure", "pressure"), ("velocity", "velocity"),
                                ("temperature", "heating"))
                 if e in active or d in o.get("base_dependencies", ()))
    ptv = any(e in ("pressure", "velocity", "heating") for e in case.effects) or \
        o.get("base_dependencies")
    if ptv:  # with an effect switched off, the same PTV model without that dependency
        friction = PTVFriction(0.075, heating=MonitorLine() if "temperature" in deps else None,
                               dependencies=deps)
    else:
        friction = ConstantFriction(MU0)
    radius = o.get("true_radius", case.radius) if "stiffness" in active else case.radius
    histories = [_sine(test, case.dt) for test in case.tests]
    total = sum(float(np.sum(np.abs(np.diff(m(t))))) for t, m in histories)
    wear = Wear(campaign_travel=total, **o.get("wear", {})) if "wear" in active else None
    breakaway = Breakaway(**o.get("breakaway_pkg", {})) if "breakaway" in active else None
    out, travel = [], 0.0
    lag = case.lag_samples * case.dt if ("lag" in active or "lag" not in case.effects) else 0.0
    for k, (test, (t, motion)) in enumerate(zip(case.tests, histories, strict=True)):
        bearing = DCFPBearing(radius, SLIDER, test.load * W, friction,
                              yield_displacement=o.get("u_y", 5e-4))
        grid = np.arange(t[0], t[-1] + case.dt / 20, case.dt / 10) if lag else t
        u = motion(grid)
        v = np.gradient(u, grid)
        history = ImposedHistory(grid, u, v, "sine")
        axial = _axial(test, grid, k) if test.varying else None
        truth = element_truth(bearing, history, axial_load=axial, breakaway=breakaway,
                              wear=wear, travel_before=travel)
        travel += float(np.sum(np.abs(np.diff(u))))
        force = np.interp(t - lag, grid, truth.force, left=0.0) if lag else truth.force
        out.append({"time": t, "displacement": motion(t), "force": force,
                    "axial_force": np.interp(t, grid, truth.axial_force),
                    "velocity": np.gradient(motion(t), t), "bearing": motion(t)})
    return out


def opensees(case: Case, active: set[str]) -> list[dict]:
    """OpenSees singleFPBearing or FPBearingPTV (``options['element']``)."""
    from isolator.bearing import DCFPBearing
    from isolator.factors import KumarFactors
    from isolator.friction import ConstantFriction, PTVFriction
    from isolator.heating import MonitorLine
    from isolator.protocols import ImposedHistory
    from structures.diagnosis.truths import opensees_truth
    from structures.opensees.bearing import fpbearingptv_equivalent

    o = case.options
    element = o["element"] if (active or not case.effects) else "coulomb"
    radius = o.get("true_radius", case.radius) if "stiffness" in active else case.radius
    out = []
    for test in case.tests:
        t, motion = _sine(test, case.dt)
        u = motion(t)
        history = ImposedHistory(t, u, np.gradient(u, t), "sine")
        if element == "coulomb":
            bearing = DCFPBearing(radius, SLIDER, test.load * W, ConstantFriction(MU0))
        elif element == "velocity":
            bearing = DCFPBearing(radius, SLIDER, test.load * W,
                                  PTVFriction(0.075, heating=None, dependencies=("velocity",)))
        else:
            friction = PTVFriction(0.075, heating=MonitorLine(), factors=KumarFactors(),
                                   dependencies=("temperature",))
            bearing = fpbearingptv_equivalent(DCFPBearing(radius, SLIDER, test.load * W,
                                                          friction))
        truth = opensees_truth(bearing, history, element)
        force = truth.force
        if case.lag_samples:
            force = np.interp(t - case.lag_samples * case.dt, t, force, left=0.0)
        out.append({"time": t, "displacement": u, "force": force,
                    "axial_force": truth.axial_force, "velocity": np.gradient(u, t),
                    "bearing": u})
    return out


SOURCES = {"independent": independent, "package": package, "opensees": opensees}
