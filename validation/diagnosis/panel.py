"""The diagnosis's validation panel: 48 cases in 24 scenario pairs, labels kept apart.

Each *scenario* (a set of true effects, possibly none) is made twice: one case goes to the
**tune** half (the only half thresholds may be chosen on), the other to the **test** half (the
half scores are reported on). The two cases of a pair share the labelled effects and differ in
their truth source and in nuisance: amplitudes (0.02-0.4 m), sampling (100-500 Hz), white,
AR(1) or band-limited noise (0.3-1.5 % of the nominal friction force mu0 W on the force,
0.01-0.05 mm on the displacement), a channel lag of up to 1.5 samples, the pre-sliding
transition (rigid-plastic, elastic-plastic 0.1-1.5 mm, smooth Bouc-Wen), campaigns of one to
four tests (sines at several amplitudes and periods, ASCE-like 3-cycle sines at 4.26 s, a slow
wind-like test at about 15 mm/s), a velocity column or not, an axial-force column or not.

Truth sources
-------------
``independent``
    :mod:`validation.diagnosis.independent_truths` (numpy only, written from the paper and from
    physics; it shares no code with the package).
``opensees``
    OpenSees ``singleFPBearing`` / ``flatSliderBearing`` (Coulomb, VelDependent) and
    ``FPBearingPTV`` through
    :func:`structures.opensees.bearing.run_opensees_test`; instrument effects (lag, noise) are
    applied to its output.
``package``
    Our own element with the truths' extra physics,
    :func:`structures.diagnosis.truths.element_truth`.

Label rule
----------
An effect is labelled when its own contribution to the clean force, the truth with it less the
truth without it (everything else equal, no noise), has an RMS of at least 3 % of the RMS
force over the campaign (``design.contribution``). Physics the truth has but the label and the
told baseline do not (singleFPBearing's normal-force coupling N = W + F u / R at small u / R,
FPBearingPTV's spherical restoring law at R = 4.5 m, the independent precise model's
differences from the package's) contributes at most 1 % (``design.unlabelled``). The share
left after refitting the friction level of the truth without the effect (what a calibrated
mu could absorb) is stored too (``design.contribution_refit``). Instrument nuisance (a lag of
up to 1.5 samples, the noise, the transition's shape) is never labelled.

Files
-----
``folder/case_NN/test_01.csv ...``: a header line, then time [s], displacement [m] (the
actuator's), force [N], and velocity [m/s] and axial_force [N] where the case has them.
``folder/case_NN/manifest.csv``: ``file,axial_load,initial_temperature,rest_before``, the tests
in run order (axial load empty when the file has the column; rest empty for the first test; a
rest of 86400 s is a night, the plates are cold). ``folder/case_NN/bearing.json``: what a user
tells the diagnosis (effective radius, ``Infinity`` for a flat slider, slider diameter,
baseline, ``without``, and the axial load when the files have no column). ``folder/labels.json``
holds the labels, ``folder/panel.json`` the seed. Case numbers are a seeded shuffle, so
neither a name nor a file tells the truth.

    python -m validation.diagnosis.panel FOLDER [--seed 2026] [--no-opensees]
"""

from __future__ import annotations

import argparse
import json
import math
import time as _time
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from validation.diagnosis import independent_truths as ind
from validation.diagnosis.cases import opensees_available

SLIDER = 0.3  # [m]
RADIUS = 4.5  # [m]
AREA = math.pi * (0.5 * SLIDER) ** 2
PRESSURE = 60.0  # [N/mm^2] nominal
W = PRESSURE * 1.0e6 * AREA  # [N] 4.24 MN
MU0 = 0.041  # the paper's mu_0 for a 300 mm slider
LABEL_MIN = 0.03  # a labelled effect: RMS contribution >= 3 % of the RMS force
UNLABELLED_MAX = 0.01  # physics left unlabelled: <= 1 %
NIGHT = 86400.0  # [s] a rest after which the plates are cold
VELOCITY_NOISE = 2.0e-3  # [m/s]
AXIAL_NOISE = 0.003  # [-] relative
HALVES = ("tune", "test")
SOURCES = ("independent", "opensees", "package")
EFFECTS = ("heating", "velocity", "pressure", "breakaway", "wear", "stiffness", "asymmetry",
           "backlash", "geometry", "lag")


@dataclass(frozen=True)
class Sine:
    """One test: u = A sin(2 pi t / T) for ``cycles`` periods.

    pressure : nominal contact pressure of the test [N/mm^2] (sets its axial load).
    varying : relative amplitude of an axial load varying in time,
        N(t) = N (1 + varying sin(2 pi t / varying_period + phase)).
    rest : rest before the test [s] (None: the first test, or a night for later ones).
    temperature : initial temperature [degC].
    """

    amplitude: float
    period: float
    cycles: float
    pressure: float = PRESSURE
    varying: float = 0.0
    varying_period: float = 1.7
    rest: float | None = None
    temperature: float = 20.0


@dataclass(frozen=True)
class Case:
    """One case of the panel.

    pair : the scenario's id (both cases of a pair share it and the effects).
    spec : the truth's parameters for its source: ``base`` (always on) and ``effects``
        (switched on with each labelled effect), see the source functions.
    noise : force noise as a fraction of mu0 W; ``noise_kind`` white, ar1 or band.
    lag_samples : the force channel's delay in samples (a nuisance up to 1.5, else the
        labelled ``lag``).
    weight, mu0 : the nominal axial load [N] and friction coefficient (the noise scale).
    radius : the effective radius the diagnosis is told [m].
    """

    pair: str
    effects: tuple[str, ...]
    half: str
    source: str
    truth: str
    tests: tuple[Sine, ...]
    spec: dict = field(default_factory=dict)
    dt: float = 0.01
    noise: float = 0.01
    noise_kind: str = "white"
    rho: float = 0.0
    displacement_noise: float = 2.0e-5
    lag_samples: float = 0.0
    velocity_column: bool = True
    axial_column: bool = False
    baseline: str = "constant"
    without: tuple[str, ...] = ()
    radius: float = RADIUS
    weight: float = W
    mu0: float = MU0

    @property
    def samples(self) -> int:
        return sum(round(s.cycles * s.period / self.dt) + 1 for s in self.tests)


# --- test histories ------------------------------------------------------------------------


def _load(case: Case, sine: Sine) -> float:
    return case.weight * sine.pressure / PRESSURE


def _axial_of(case: Case, sine: Sine, k: int):
    load = _load(case, sine)
    if not sine.varying:
        return lambda t: np.full(np.shape(t), load)
    omega = 2.0 * math.pi / sine.varying_period
    return lambda t: load * (1.0 + sine.varying * np.sin(omega * np.asarray(t) + 0.9 * k))


def _rest(case: Case, k: int) -> float | None:
    if k == 0:
        return None
    rest = case.tests[k].rest
    return NIGHT if rest is None else float(rest)


def _ind_tests(case: Case, cold: bool = False) -> list[ind.Test]:
    out = []
    for k, s in enumerate(case.tests):
        rest = None if cold else _rest(case, k)
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


def _ind_bearing(case: Case, active: set[str]) -> ind.Bearing:
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
    """The independent truth (:func:`_ind_bearing`) through the case's campaign; ``cold``
    forgets the heat between tests."""
    return ind.simulate(_ind_bearing(case, active), _ind_tests(case, cold),
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
    if "temperature" in order and any((_rest(case, k) or NIGHT) < 1.0e4
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
        bearing = DCFPBearing(radius, SLIDER, _load(case, s), friction,
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
        load = _load(case, s)
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


# --- the cases ------------------------------------------------------------------------------

S = Sine
SINE_SET = (S(0.1, 2.5, 3), S(0.2, 3.0, 3), S(0.3, 4.26, 3), S(0.15, 2.5, 6))
ASCE = (S(0.1, 4.26, 3), S(0.2, 4.26, 3, rest=600.0), S(0.02, 8.4, 2, rest=600.0))
PAIR = (S(0.25, 3.0, 3), S(0.15, 2.5, 3))
VELOCITY_SET = (S(0.2, 2.5, 3), S(0.05, 4.0, 3), S(0.02, 8.4, 2))
HEAT_SET = (S(0.2, 3.0, 3), S(0.25, 3.0, 3, rest=300.0), S(0.15, 2.5, 4, rest=1200.0))
NIGHTS_PRECISE = (S(0.1, 2.5, 3), S(0.2, 3.0, 3, temperature=25.0),
                  S(0.3, 4.26, 3, temperature=15.0), S(0.02, 8.4, 2))
PRESSURES = (S(0.15, 2.5, 3, 40.0), S(0.15, 2.5, 3, 80.0, rest=600.0),
             S(0.15, 2.5, 3, 20.0, rest=600.0), S(0.15, 2.5, 3, 60.0, rest=600.0))
VARYING = (S(0.1, 2.5, 3, varying=0.5), S(0.15, 3.0, 3, varying=0.5),
           S(0.08, 2.5, 4, varying=0.5))
WEAR_SET = (S(0.2, 3.0, 3), S(0.2, 3.0, 3, rest=1800.0), S(0.15, 2.5, 3, rest=1800.0),
            S(0.25, 3.0, 3, rest=1800.0))
DAMPER = (S(0.025, 2.0, 4), S(0.035, 4.0, 3))

PRECISE_BASE = {"mu0": ind.MU_T0, "velocity": ind.Velocity("paper"), "pressure": "paper",
                "temperature": "paper"}
HEAT = {"temperature": "normalised"}
EP = "elastic-plastic"

CASES: tuple[Case, ...] = (
    # --- no unmodelled effect: 5 pairs ---
    Case("P01", (), "tune", "package", "constant friction, elastic-plastic u_y 0.5 mm",
         SINE_SET),
    Case("P01", (), "test", "independent", "rigid-plastic constant friction (the paper's form, "
         "linear restoring law) at R 1.5 m and 0.2-0.3 m, 500 Hz, 1.5 % white noise",
         (S(0.3, 3.0, 2), S(0.2, 2.5, 2, rest=900.0)), {"base": {"transition": "rigid-plastic"}},
         dt=0.002, noise=0.015, displacement_noise=1e-5, velocity_column=False, radius=1.5),
    Case("P02", (), "tune", "opensees", "OpenSees singleFPBearing Coulomb, 200 Hz, lag 1 "
         "sample, AR(1) noise", (S(0.2, 3.0, 3), S(0.12, 2.5, 3)), {"element": "coulomb"},
         dt=0.005, noise=0.008, noise_kind="ar1", rho=0.9, lag_samples=1.0),
    Case("P02", (), "test", "independent", "constant friction with a 1.5 mm pre-sliding "
         "transition, lag 1.2 samples, AR(1) noise, tests at 40 and 75 N/mm^2",
         (S(0.2, 4.26, 3, 40.0), S(0.1, 2.5, 3, 75.0, rest=1800.0)),
         {"base": {"yield_displacement": 1.5e-3}}, noise=0.01, noise_kind="ar1", rho=0.9,
         lag_samples=1.2, displacement_noise=3e-5),
    Case("P03", (), "tune", "independent", "constant friction, smooth (Bouc-Wen) u_y 1 mm, "
         "axial load varying in time by 30 %", (S(0.15, 2.5, 3, varying=0.3),
                                                S(0.25, 3.0, 2, varying=0.3, rest=900.0)),
         {"base": {"transition": "smooth", "yield_displacement": 1.0e-3}}, dt=0.004,
         noise=0.006, noise_kind="band", velocity_column=False, axial_column=True),
    Case("P03", (), "test", "package", "constant friction, u_y 0.2 mm, axial load varying in "
         "time by 30 %", (S(0.1, 2.5, 3, varying=0.3), S(0.2, 3.0, 3, varying=0.3)),
         {"u_y": 2.0e-4}, axial_column=True, lag_samples=0.5),
    Case("P04", (), "tune", "package", "full precise model (Eq. 7) told precise, nights "
         "between tests, initial temperatures 20/25/15/20 degC", NIGHTS_PRECISE,
         {"dependencies": ("pressure", "velocity", "temperature")}, baseline="precise"),
    Case("P04", (), "test", "independent", "independent precise model (Eq. 1-7, direct Eq. 4 "
         "convolution) told precise, rests of 2 h", (S(0.2, 3.0, 3), S(0.1, 2.5, 4, rest=7200.0),
                                                      S(0.25, 4.26, 2, rest=7200.0)),
         {"base": PRECISE_BASE}, dt=0.005, noise=0.005, baseline="precise"),
    Case("P05", (), "tune", "independent", "rigid-plastic constant friction, ASCE-like 3-cycle "
         "sines at 4.26 s and a wind-like test", ASCE, {"base": {"transition": "rigid-plastic"}},
         noise=0.01, displacement_noise=5e-5),
    Case("P05", (), "test", "opensees", "OpenSees flatSliderBearing Coulomb (a friction damper, "
         "W 1 MN), lag 0.5 samples, 0.5 % noise", (S(0.03, 2.0, 4), S(0.02, 3.0, 3)),
         {"element": "coulomb", "u_y": 2e-4}, dt=0.004, noise=0.005, lag_samples=0.5,
         velocity_column=False, radius=math.inf, weight=1.0e6, mu0=0.08),
    # --- one effect: 13 pairs ---
    Case("P06", ("heating",), "tune", "independent", "temperature dependence (Eq. 3-5) "
         "normalised at 20 degC, heat carried over rests of 300 s and 1200 s", HEAT_SET,
         {"base": {"yield_displacement": 3.0e-4}, "effects": {"heating": HEAT}}),
    Case("P06", ("heating",), "test", "opensees", "OpenSees FPBearingPTV, temperature "
         "dependence only (Kumar's factors, mu_ref 0.06)", (S(0.2, 3.0, 3), S(0.1, 2.5, 3)),
         {"element": "ptv", "ptv": {"heating": "temperature"}}, dt=0.005, noise=0.008),
    Case("P07", ("velocity",), "tune", "opensees", "OpenSees singleFPBearing VelDependent "
         "(Eq. 2: mu_slow / mu_fast 0.45, 19 s/m)", VELOCITY_SET, {"element": "velocity"},
         velocity_column=False),
    Case("P07", ("velocity",), "test", "independent", "velocity: mu_slow / mu_fast 0.5 with "
         "v_c 20 mm/s, smooth transition", (S(0.15, 2.5, 3), S(0.03, 6.0, 2, rest=600.0),
                                             S(0.02, 8.4, 1, rest=600.0)),
         {"base": {"transition": "smooth", "yield_displacement": 5e-4},
          "effects": {"velocity": {"velocity": ind.Velocity("exp", ratio=0.5, speed=0.02)}}},
         dt=0.005, noise=0.008, noise_kind="ar1", rho=0.85),
    Case("P08", ("pressure",), "tune", "independent", "pressure (Eq. 1, normalised at 60 "
         "N/mm^2), tests at 40, 80, 20 and 60 N/mm^2", PRESSURES,
         {"effects": {"pressure": {"pressure": "normalised"}}}),
    Case("P08", ("pressure",), "test", "opensees", "OpenSees FPBearingPTV, pressure "
         "dependence only (Kumar), tests at 30, 90 and 45 N/mm^2",
         (S(0.15, 2.5, 3, 30.0), S(0.2, 3.0, 3, 90.0), S(0.1, 2.5, 3, 45.0)),
         {"element": "ptv", "ptv": {"pressure": "pressure"}, "mu_t0": 0.045}, dt=0.005,
         axial_column=True, lag_samples=0.7),
    Case("P09", ("pressure",), "tune", "package", "pressure only (Eq. 1), axial load varying "
         "in time by 50 %", VARYING, {"ptv": True, "mu_t0": 0.041}, axial_column=True),
    Case("P09", ("pressure",), "test", "independent", "pressure (Eq. 1), axial load varying in "
         "time by 45 %", (S(0.12, 2.5, 3, varying=0.45, varying_period=2.3),
                          S(0.08, 2.0, 4, varying=0.45, varying_period=2.3, rest=600.0)),
         {"base": {"transition": "rigid-plastic"},
          "effects": {"pressure": {"pressure": "normalised"}}}, dt=0.004, noise=0.006,
         axial_column=True, velocity_column=False),
    Case("P10", ("breakaway",), "tune", "independent", "breakaway 50 % fading linearly over "
         "6 mm", SINE_SET[:3],
         {"effects": {"breakaway": {"breakaway": ind.Breakaway("linear", 0.5, 0.006)}}}),
    Case("P10", ("breakaway",), "test", "package", "breakaway 40 % fading quadratically over "
         "10 mm", (S(0.1, 2.5, 3), S(0.2, 3.0, 3)), {"breakaway": {"ratio": 0.4,
                                                                    "length": 0.01}},
         dt=0.005, noise=0.006),
    Case("P11", ("wear",), "tune", "independent", "friction drops 7 % from test to test",
         WEAR_SET, {"effects": {"wear": {"wear": ind.Wear("step", 0.07)}}}, noise=0.005),
    Case("P11", ("wear",), "test", "package", "friction falls 25 % over the campaign as "
         "S^0.6", SINE_SET, {"wear": {"change": -0.25, "power": 0.6}}, noise=0.005,
         lag_samples=1.0),
    Case("P12", ("stiffness",), "tune", "opensees", "OpenSees Coulomb, true R_eff 3.6 m, told "
         "4.5 m", (S(0.15, 2.5, 3), S(0.2, 3.0, 3)),
         {"element": "coulomb", "true_radius": 3.6}, noise=0.003, displacement_noise=1e-5),
    Case("P12", ("stiffness",), "test", "independent", "true R_eff 3.6 m, told 4.5 m, "
         "rigid-plastic", SINE_SET[:3],
         {"base": {"transition": "rigid-plastic"}, "effects": {"stiffness": {"radius": 3.6}}},
         noise=0.012),
    Case("P13", ("asymmetry",), "tune", "independent", "mu(+) / mu(-) = 1.35 (direction-"
         "dependent friction capacity)", PAIR,
         {"effects": {"asymmetry": {"asymmetry": 0.15}}}),
    Case("P13", ("asymmetry",), "test", "independent", "mu(+) / mu(-) = 0.79, smooth "
         "transition, 200 Hz", (S(0.1, 2.5, 3), S(0.2, 3.0, 3)),
         {"base": {"transition": "smooth", "yield_displacement": 6e-4},
          "effects": {"asymmetry": {"asymmetry": -0.12}}}, dt=0.005, noise=0.01,
         noise_kind="ar1", rho=0.8),
    Case("P14", ("backlash",), "tune", "independent", "4 mm play, friction damper (flat, "
         "W 1 MN, mu 0.08)", DAMPER,
         {"base": {"yield_displacement": 2e-4}, "effects": {"backlash": {"backlash": 0.004}}},
         dt=0.004, radius=math.inf, weight=1.0e6, mu0=0.08),
    Case("P14", ("backlash",), "test", "independent", "2.5 mm play on a pendulum, 200 Hz",
         (S(0.06, 2.0, 3), S(0.1, 2.5, 3)),
         {"base": {"yield_displacement": 3e-4}, "effects": {"backlash": {"backlash": 0.0025}}},
         dt=0.005, noise=0.008),
    Case("P15", ("geometry",), "tune", "independent", "spherical surface with the normal "
         "force coupling, R 1.2 m, 0.35-0.4 m", (S(0.4, 4.0, 3), S(0.35, 3.5, 2, rest=900.0)),
         {"effects": {"geometry": {"restoring": "spherical"}}}, radius=1.2),
    Case("P15", ("geometry",), "test", "opensees", "OpenSees singleFPBearing Coulomb at large "
         "u/R (normal force N = W + F u/R), R 1.5 m, 0.35 m", (S(0.35, 3.5, 3),),
         {"element": "coulomb"}, radius=1.5, noise=0.006),
    Case("P16", ("lag",), "tune", "independent", "force channel 5 samples late (50 ms)", PAIR,
         {}, lag_samples=5.0),
    Case("P16", ("lag",), "test", "opensees", "OpenSees Coulomb, force channel 8 samples late "
         "at 200 Hz (40 ms)", (S(0.15, 2.5, 3), S(0.25, 3.0, 2)), {"element": "coulomb"},
         dt=0.005, lag_samples=8.0),
    Case("P17", ("heating",), "tune", "package", "full precise model, told precise without "
         "heating, initial temperatures 20/30/12/20 degC after nights",
         tuple(replace(t, temperature=T) for t, T in zip(SINE_SET, (20.0, 30.0, 12.0, 20.0),
                                                         strict=True)),
         {"dependencies": ("pressure", "velocity")},
         baseline="precise", without=("heating",)),
    Case("P17", ("heating",), "test", "independent", "independent precise model, told precise "
         "without heating", (S(0.2, 3.0, 3), S(0.15, 2.5, 3, rest=1800.0)),
         {"base": {**PRECISE_BASE, "temperature": None},
          "effects": {"heating": {"temperature": "paper"}}}, dt=0.005, noise=0.006,
         baseline="precise", without=("heating",)),
    Case("P18", ("velocity",), "tune", "independent", "Stribeck: friction 60 % higher at rest, "
         "v_s 30 mm/s", VELOCITY_SET,
         {"effects": {"velocity": {"velocity": ind.Velocity("stribeck", peak=0.6,
                                                            speed=0.03)}}}),
    Case("P18", ("velocity",), "test", "package", "full precise model, told precise without "
         "velocity", VELOCITY_SET, {"dependencies": ("pressure", "temperature")},
         baseline="precise", without=("velocity",), dt=0.005, noise=0.006),
    # --- two effects: 4 pairs ---
    Case("P19", ("heating", "velocity"), "tune", "independent", "temperature and velocity "
         "(Eq. 2-5, normalised), ASCE-like tests", ASCE,
         {"effects": {"heating": HEAT,
                      "velocity": {"velocity": ind.Velocity("paper-normalised")}}}),
    Case("P19", ("heating", "velocity"), "test", "package", "precise model: temperature and "
         "velocity, ASCE-like tests and a wind-like test after nights",
         (S(0.15, 4.26, 3), S(0.25, 4.26, 3), S(0.02, 8.4, 2)), {"mu_t0": 0.075}, dt=0.005,
         velocity_column=False),
    Case("P20", ("pressure", "heating"), "tune", "package", "pressure and temperature, axial "
         "load varying in time by 50 %", VARYING, {"mu_t0": 0.075}, axial_column=True),
    Case("P20", ("pressure", "heating"), "test", "independent", "pressure and temperature "
         "(normalised), axial load varying by 50 %",
         (S(0.15, 3.0, 3, varying=0.5, varying_period=2.1),
          S(0.1, 2.5, 3, varying=0.5, varying_period=2.1, rest=600.0)),
         {"effects": {"heating": HEAT, "pressure": {"pressure": "normalised"}}},
         axial_column=True, noise=0.008),
    Case("P21", ("backlash", "asymmetry"), "tune", "independent", "3 mm play and mu(+) / mu(-) "
         "= 0.7, friction damper (flat, W 1 MN, mu 0.08)", DAMPER,
         {"base": {"yield_displacement": 2e-4},
          "effects": {"backlash": {"backlash": 0.003}, "asymmetry": {"asymmetry": -0.18}}},
         dt=0.004, radius=math.inf, weight=1.0e6, mu0=0.08, noise=0.008),
    Case("P21", ("backlash", "asymmetry"), "test", "independent", "4 mm play and mu(+) / mu(-) "
         "= 1.4 on a pendulum", (S(0.08, 2.5, 3), S(0.12, 3.0, 3)),
         {"base": {"yield_displacement": 3e-4},
          "effects": {"backlash": {"backlash": 0.004}, "asymmetry": {"asymmetry": 0.17}}},
         dt=0.005),
    Case("P22", ("wear", "breakaway"), "tune", "independent", "drop of 7 % per test and a "
         "Gaussian breakaway of 50 % over 5 mm", WEAR_SET,
         {"effects": {"wear": {"wear": ind.Wear("step", 0.07)},
                      "breakaway": {"breakaway": ind.Breakaway("gauss", 0.5, 0.005)}}},
         noise=0.006),
    Case("P22", ("wear", "breakaway"), "test", "package", "wear S^0.6 (-25 %) and breakaway "
         "40 % over 10 mm", SINE_SET, {"wear": {"change": -0.25, "power": 0.6},
                                       "breakaway": {"ratio": 0.4, "length": 0.01}},
         noise=0.006),
    # --- decoys: no unmodelled effect, told what the effect cases are told: 2 pairs ---
    Case("P23", (), "tune", "package", "precise model without temperature dependence, told "
         "precise without heating", PAIR, {"dependencies": ("pressure", "velocity")},
         baseline="precise", without=("heating",), dt=0.005, noise=0.006),
    Case("P23", (), "test", "independent", "independent precise model without velocity "
         "dependence, told precise without velocity", VELOCITY_SET,
         {"base": {**PRECISE_BASE, "velocity": None}}, baseline="precise",
         without=("velocity",), noise=0.008, noise_kind="ar1", rho=0.85),
    Case("P24", (), "tune", "independent", "constant friction, friction damper (flat, W 1 MN, "
         "mu 0.08), smooth transition u_y 0.3 mm", (S(0.03, 2.0, 4), S(0.04, 4.0, 2, rest=600.0)),
         {"base": {"transition": "smooth", "yield_displacement": 3e-4}}, dt=0.004,
         radius=math.inf, weight=1.0e6, mu0=0.08, noise=0.01, noise_kind="band"),
    Case("P24", (), "test", "package", "constant friction, friction damper (flat, W 1 MN, "
         "mu 0.08), u_y 0.1 mm", (S(0.025, 2.0, 4),), {"u_y": 1e-4}, dt=0.004,
         radius=math.inf, weight=1.0e6, mu0=0.08, noise=0.012, lag_samples=1.5),
)


def check_design(cases: tuple[Case, ...] = CASES) -> None:
    """Raise ValueError unless every pair has one tune and one test case with the same known
    effects, and every case's source and sample count are admissible."""
    pairs: dict[str, list[Case]] = {}
    for case in cases:
        pairs.setdefault(case.pair, []).append(case)
        if not set(case.effects) <= set(EFFECTS) or case.source not in SOURCES:
            raise ValueError(f"{case.pair}: unknown effect or source in {case}")
        if case.samples > 20000:
            raise ValueError(f"{case.pair} {case.half}: {case.samples} samples (at most 20000)")
    for name, members in pairs.items():
        if sorted(c.half for c in members) != sorted(HALVES) or \
                len({frozenset(c.effects) for c in members}) != 1:
            raise ValueError(f"{name}: a pair needs one tune and one test case with one effect set")


# --- contributions, noise, writing -----------------------------------------------------------


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


def _concat(runs: list[dict], key: str) -> np.ndarray:
    return np.concatenate([r[key] for r in runs])


def _refit_share(force: np.ndarray, other: np.ndarray, restoring: np.ndarray) -> float:
    """RMS of ``force`` less the truth without the effect whose friction part is rescaled by
    least squares (what a calibrated friction level absorbs), over RMS(force)."""
    part = other - restoring
    target = force - restoring
    scale = float(np.dot(part, target) / np.dot(part, part)) if np.any(part) else 0.0
    return _rms(target - scale * part) / _rms(force)


def contributions(case: Case, clean: list[dict]) -> dict:
    """Each labelled effect's share (raw and after a refit) and the unlabelled shares."""
    run = SOURCE_FUNCTIONS[case.source]
    force = _concat(clean, "force")
    total = _rms(force)
    raw, refit = {}, {}
    for effect in case.effects:
        other = run(case, set(case.effects) - {effect})
        raw[effect] = _rms(force - _concat(other, "force")) / total
        refit[effect] = _refit_share(force, _concat(other, "force"), _concat(other, "restoring"))
    unlabelled = {}
    for name in {n for c in clean for n in c.get("unlabelled", {})}:
        unlabelled[name] = _rms(np.concatenate([c["unlabelled"][name] for c in clean])) / total
    if case.source == "independent" and case.baseline == "precise":
        unlabelled.update(_precise_difference(case))
    return {"contribution": raw, "contribution_refit": refit, "unlabelled": unlabelled}


def _precise_difference(case: Case) -> dict:
    """The independent precise model against the package's on the same tests (cold starts,
    all of the truth's effects on): physics the two differ in is left unlabelled. Also the
    share of the heat carried over the rests (physics of the told precise model)."""
    from isolator.bearing import DCFPBearing
    from isolator.friction import PTVFriction
    from isolator.heating import MonitorLine, ThermalProperties
    from isolator.testrig import run_test

    mine = independent(case, set(case.effects), cold=True)
    truth = _ind_bearing(case, set(case.effects))
    deps = tuple(name for name, on in (("pressure", truth.pressure), ("velocity", truth.velocity),
                                       ("temperature", truth.temperature)) if on)
    u_y = truth.yield_displacement
    diffs = []
    for s, out in zip(case.tests, mine, strict=True):
        friction = PTVFriction(truth.mu0, dependencies=deps,
                               heating=MonitorLine() if "temperature" in deps else None,
                               thermal=ThermalProperties(initial_temperature=s.temperature))
        bearing = DCFPBearing(case.radius, SLIDER, _load(case, s), friction,
                              yield_displacement=u_y)
        theirs = run_test(bearing, out["time"], out["displacement"], out["velocity"]).force
        diffs.append(out["force"] - theirs)
    total = _rms(_concat(mine, "force"))
    carried = _concat(independent(case, set(case.effects)), "force") - _concat(mine, "force")
    return {"independent precise vs package precise (cold starts)":
            _rms(np.concatenate(diffs)) / total,
            "heat carried over the rests (part of the told precise model)":
            _rms(carried) / total}


def measured(case: Case, clean: dict, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """The columns a test machine writes: the clean channels plus measurement noise."""
    n = clean["time"].size
    out = {"time": clean["time"],
           "displacement": clean["displacement"] + rng.normal(0.0, case.displacement_noise, n),
           "force": clean["force"] + ind.noise(rng, n, case.noise * case.mu0 * case.weight,
                                               case.noise_kind, case.rho)}
    if case.velocity_column:
        out["velocity"] = clean["velocity"] + rng.normal(0.0, VELOCITY_NOISE, n)
    if case.axial_column:
        out["axial_force"] = clean["axial_force"] * (1.0 + rng.normal(0.0, AXIAL_NOISE, n))
    return out


def _design(case: Case, shares: dict) -> dict:
    base = case.spec.get("base", {})
    transition = base.get("transition", "elastic-plastic")
    if case.source != "independent":
        transition = "elastic-plastic"
    u_y = None if transition == "rigid-plastic" else base.get(
        "yield_displacement", case.spec.get("u_y", 5.0e-4))
    return {
        "pair": case.pair,
        "tests": [{"amplitude": s.amplitude, "period": s.period, "cycles": s.cycles,
                   "pressure_N_mm2": s.pressure, "axial_variation": s.varying,
                   "rest_before": _rest(case, k), "initial_temperature": s.temperature}
                  for k, s in enumerate(case.tests)],
        "amplitudes": [s.amplitude for s in case.tests],
        "dt": case.dt, "samples": case.samples,
        "noise": {"force_fraction_of_mu0_W": case.noise, "kind": case.noise_kind,
                  "rho": case.rho, "displacement_m": case.displacement_noise,
                  "velocity_m_s": VELOCITY_NOISE if case.velocity_column else None,
                  "axial_relative": AXIAL_NOISE if case.axial_column else None},
        "lag_samples": case.lag_samples,
        "transition": transition, "yield_displacement": u_y,
        "velocity_column": case.velocity_column, "axial_column": case.axial_column,
        "baseline": case.baseline, "without": list(case.without),
        "told_radius": case.radius, "weight": case.weight, "mu0": case.mu0,
        "truth_parameters": _jsonable(case.spec),
        **shares,
        "label_rule_met": (all(v >= LABEL_MIN for v in shares["contribution"].values())
                           and all(v <= UNLABELLED_MAX for k, v in shares["unlabelled"].items()
                                   if not k.startswith("heat carried"))),
    }


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if hasattr(value, "__dataclass_fields__"):
        return {"type": type(value).__name__, **{k: _jsonable(getattr(value, k))
                                                 for k in value.__dataclass_fields__}}
    if isinstance(value, float) and math.isinf(value):
        return "inf"
    return value


def _write_case(case: Case, out: Path, rng: np.random.Generator) -> dict:
    """Write one case's files; return its contributions."""
    clean = SOURCE_FUNCTIONS[case.source](case, set(case.effects))
    shares = contributions(case, clean)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for k, (sine, data) in enumerate(zip(case.tests, clean, strict=True), start=1):
        columns = measured(case, data, rng)
        name = f"test_{k:02d}.csv"
        np.savetxt(out / name, np.column_stack(list(columns.values())), delimiter=",",
                   header=",".join(columns), comments="", fmt="%.10g")
        load = "" if case.axial_column else f"{_load(case, sine):.6f}"
        rest = _rest(case, k - 1)
        rows.append(f"{name},{load},{sine.temperature:g},{'' if rest is None else f'{rest:g}'}")
    (out / "manifest.csv").write_text(
        "file,axial_load,initial_temperature,rest_before\n" + "\n".join(rows) + "\n")
    told = {"effective_radius": case.radius, "slider_diameter": SLIDER,
            "baseline": case.baseline, "without": list(case.without)}
    if not case.axial_column:
        told["axial_load"] = _load(case, case.tests[0])
    (out / "bearing.json").write_text(json.dumps(told, indent=2) + "\n")
    return shares


def write_panel(folder: str | Path, *, seed: int = 2026, opensees: bool | None = None,
                half: str | None = None, progress: bool = False) -> Path:
    """Write the panel to ``folder`` (see the module docstring); return the labels file.

    Parameters
    ----------
    folder : str or Path
        Where to write (created; existing case folders are overwritten).
    seed : int
        Seed of the case numbering and of the measurement noise.
    opensees : bool or None
        Include the cases made by OpenSees; None: when openseespy can be imported.
    half : {"tune", "test"} or None
        Write one half only (None: both).
    progress : bool
        Print a line per case.
    """
    check_design()
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    if opensees is None:
        opensees = opensees_available()
    order = np.random.default_rng(seed).permutation(len(CASES))
    labels, start_all = {}, _time.perf_counter()
    for number, index in enumerate(order, start=1):
        case = CASES[int(index)]
        if (case.source == "opensees" and not opensees) or (half and case.half != half):
            continue
        start = _time.perf_counter()
        name = f"case_{number:02d}"
        rng = np.random.default_rng([seed, int(index)])
        shares = _write_case(case, folder / name, rng)
        design = _design(case, shares)
        if not design["label_rule_met"]:
            warnings.warn(f"{name} ({case.pair} {case.half}) breaks the label rule: {shares}",
                          stacklevel=2)
        labels[name] = {"effects": list(case.effects), "truth": case.truth,
                        "source": case.source, "half": case.half, "design": design}
        if progress:
            pct = ", ".join(f"{k} {100 * v:.1f}%" for k, v in shares["contribution"].items())
            print(f"{name} {case.pair} {case.half:4s} {case.source:11s} "
                  f"{','.join(case.effects) or 'none':18s} {pct} "
                  f"({_time.perf_counter() - start:.1f} s)", flush=True)
    path = folder / "labels.json"
    path.write_text(json.dumps(dict(sorted(labels.items())), indent=1) + "\n")
    (folder / "panel.json").write_text(json.dumps({
        "seed": seed, "cases": len(labels), "half": half or "all", "opensees": bool(opensees),
        "seconds": round(_time.perf_counter() - start_all, 1)}, indent=2) + "\n")
    return path


def load_labels(folder: str | Path) -> dict:
    """The labels of a panel written by :func:`write_panel` (read them after diagnosing)."""
    return json.loads((Path(folder) / "labels.json").read_text())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Write the diagnosis's validation panel.")
    parser.add_argument("folder")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--half", choices=HALVES)
    parser.add_argument("--no-opensees", action="store_true")
    args = parser.parse_args(argv)
    write_panel(args.folder, seed=args.seed, half=args.half,
                opensees=False if args.no_opensees else None, progress=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
