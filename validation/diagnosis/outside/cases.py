"""The outside panel's design: its records (a test, a case) and its 68 cases in 34 pairs.

Each *scenario* (a set of true effects, possibly none) is made twice: one case goes to the
**tune** half, the other to the **test** half. The two cases of a pair share the labelled
effects and differ in their truth source and in nuisance (see
:mod:`validation.diagnosis.outside` for the ranges). A case names its truth source
(:mod:`validation.diagnosis.outside.sources`) and gives it its parameters in ``spec``;
:func:`check_design` checks the pairing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

from validation.diagnosis import independent as ind

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
    drift : a slow drift of the force channel's zero over each test, as a fraction of mu0 W
        (a ramp from -drift to +drift plus a half sine; instrument nuisance, never labelled).
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
    drift: float = 0.0
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


# --- a case's tests ---------------------------------------------------------------------------


def axial_load(case: Case, sine: Sine) -> float:
    """The nominal axial load of one test of ``case`` [N] (its pressure times the area)."""
    return case.weight * sine.pressure / PRESSURE


def rest_before(case: Case, k: int) -> float | None:
    """The rest before the ``k``-th test of ``case`` [s] (None for the first, a night when the
    test gives none)."""
    if k == 0:
        return None
    rest = case.tests[k].rest
    return NIGHT if rest is None else float(rest)


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
    # --- issue 21: the four kinds, in one direction: 10 pairs ---
    # a nuisance that could swallow an effect: a play of a few mm (u_y's grid ends at 2.5 mm)
    Case("P25", ("backlash",), "tune", "independent", "2 mm play behind a smooth 1 mm "
         "transition on a pendulum", (S(0.1, 2.5, 3), S(0.15, 3.0, 3, rest=600.0)),
         {"base": {"transition": "smooth", "yield_displacement": 1.0e-3},
          "effects": {"backlash": {"backlash": 0.002}}}, dt=0.005, noise=0.008),
    Case("P25", ("backlash",), "test", "independent", "3 mm play behind a 1.5 mm "
         "elastic-plastic transition, friction damper (flat, W 1 MN, mu 0.08), AR(1) noise",
         (S(0.03, 2.0, 4), S(0.045, 3.0, 3, rest=600.0)),
         {"base": {"yield_displacement": 1.5e-3}, "effects": {"backlash": {"backlash": 0.003}}},
         dt=0.004, radius=math.inf, weight=1.0e6, mu0=0.08, noise=0.008, noise_kind="ar1",
         rho=0.8),
    Case("P26", ("backlash",), "tune", "independent", "5 mm play, rigid-plastic, friction "
         "damper (flat, W 1 MN, mu 0.08), lag 1 sample", DAMPER,
         {"base": {"transition": "rigid-plastic"}, "effects": {"backlash": {"backlash": 0.005}}},
         dt=0.004, radius=math.inf, weight=1.0e6, mu0=0.08, lag_samples=1.0),
    Case("P26", ("backlash",), "test", "independent", "3.5 mm play behind a smooth 2 mm "
         "transition on a pendulum, 500 Hz", (S(0.08, 2.5, 3), S(0.12, 3.0, 2, rest=900.0)),
         {"base": {"transition": "smooth", "yield_displacement": 2.0e-3},
          "effects": {"backlash": {"backlash": 0.0035}}}, dt=0.002, noise=0.01),
    # a speed effect in a campaign at different periods (what a lag would be asked to mimic)
    Case("P27", ("velocity",), "tune", "independent", "velocity: mu_slow / mu_fast 0.55, v_c "
         "60 mm/s, one amplitude at periods 1.5-8 s", (S(0.1, 1.5, 3), S(0.1, 3.0, 3, rest=600.0),
                                                      S(0.1, 8.0, 2, rest=600.0)),
         {"effects": {"velocity": {"velocity": ind.Velocity("exp", ratio=0.55, speed=0.06)}}},
         dt=0.005, noise=0.008),
    Case("P27", ("velocity",), "test", "independent", "Stribeck: friction 50 % higher at rest, "
         "v_s 50 mm/s, one amplitude at periods 1-6 s, lag 1 sample",
         (S(0.08, 1.0, 4), S(0.08, 2.5, 3, rest=600.0), S(0.08, 6.0, 2, rest=600.0)),
         {"effects": {"velocity": {"velocity": ind.Velocity("stribeck", peak=0.5,
                                                            speed=0.05)}}},
         dt=0.004, noise=0.008, lag_samples=1.0),
    Case("P28", ("velocity",), "tune", "opensees", "OpenSees singleFPBearing VelDependent at "
         "periods 1-6 s, one amplitude", (S(0.06, 1.0, 4), S(0.06, 2.5, 3), S(0.06, 6.0, 2)),
         {"element": "velocity"}, dt=0.004, velocity_column=False),
    Case("P28", ("velocity",), "test", "independent", "velocity (the paper's Eq. 2), "
         "periods 0.8-5 s at 50-150 mm, smooth transition",
         (S(0.05, 0.8, 4), S(0.1, 2.0, 3, rest=600.0), S(0.15, 5.0, 2, rest=600.0)),
         {"base": {"transition": "smooth", "yield_displacement": 4e-4},
          "effects": {"velocity": {"velocity": ind.Velocity("paper-normalised")}}},
         dt=0.004, noise=0.01, noise_kind="ar1", rho=0.85),
    # the residual energy inside the transition window
    Case("P29", ("breakaway",), "tune", "independent", "breakaway 80 % fading linearly over "
         "2 mm (all within a few mm of each reversal)", (S(0.05, 2.0, 4), S(0.08, 2.5, 3)),
         {"effects": {"breakaway": {"breakaway": ind.Breakaway("linear", 0.8, 0.002)}}},
         dt=0.004, noise=0.006),
    Case("P29", ("breakaway",), "test", "independent", "Gaussian breakaway 70 % over 2.5 mm, "
         "rigid-plastic, friction damper (flat, W 1 MN, mu 0.08)",
         (S(0.03, 2.0, 4), S(0.04, 3.0, 3, rest=600.0)),
         {"base": {"transition": "rigid-plastic"},
          "effects": {"breakaway": {"breakaway": ind.Breakaway("gauss", 0.7, 0.0025)}}},
         dt=0.004, radius=math.inf, weight=1.0e6, mu0=0.08, noise=0.006),
    Case("P30", ("backlash",), "tune", "independent", "1.8 mm play, rigid-plastic pendulum, "
         "500 Hz (the residual lies at the reversals only)", (S(0.1, 2.5, 3), S(0.2, 3.0, 2)),
         {"base": {"transition": "rigid-plastic"}, "effects": {"backlash": {"backlash": 0.0018}}},
         dt=0.002, noise=0.008),
    Case("P30", ("backlash",), "test", "independent", "2 mm play with a 0.3 mm transition, "
         "pendulum, 500 Hz, band-limited noise", (S(0.06, 2.0, 3), S(0.12, 2.5, 3, rest=600.0)),
         {"base": {"yield_displacement": 3e-4}, "effects": {"backlash": {"backlash": 0.002}}},
         dt=0.002, noise=0.008, noise_kind="band"),
    # a play beside a friction law (heating)
    Case("P31", ("backlash", "heating"), "tune", "independent", "3 mm play and temperature "
         "dependence (normalised at 20 degC), heat carried over rests", HEAT_SET,
         {"base": {"yield_displacement": 3.0e-4},
          "effects": {"backlash": {"backlash": 0.003}, "heating": HEAT}}, dt=0.005),
    Case("P31", ("backlash", "heating"), "test", "independent", "4 mm play and temperature "
         "dependence (normalised), ASCE-like tests, AR(1) noise", ASCE,
         {"base": {"yield_displacement": 5.0e-4},
          "effects": {"backlash": {"backlash": 0.004}, "heating": HEAT}},
         noise=0.008, noise_kind="ar1", rho=0.8),
    Case("P32", ("backlash", "heating"), "tune", "independent", "2.5 mm play and temperature "
         "dependence, smooth transition, 3 tests after short rests",
         (S(0.15, 2.5, 3), S(0.2, 3.0, 3, rest=300.0), S(0.25, 3.0, 2, rest=300.0)),
         {"base": {"transition": "smooth", "yield_displacement": 4.0e-4},
          "effects": {"backlash": {"backlash": 0.0025}, "heating": HEAT}}, dt=0.005,
         noise=0.006),
    Case("P32", ("backlash", "heating"), "test", "independent", "3 mm play and temperature "
         "dependence, rigid-plastic, 500 Hz, lag 1 sample",
         (S(0.2, 3.0, 3), S(0.15, 2.5, 4, rest=600.0)),
         {"base": {"transition": "rigid-plastic"},
          "effects": {"backlash": {"backlash": 0.003}, "heating": HEAT}}, dt=0.002,
         noise=0.01, lag_samples=1.0),
    # no effect: pure noise and a drift of the force channel's zero (hints must stay silent)
    Case("P33", (), "tune", "independent", "constant friction, white noise and a drift of the "
         "force zero of 0.4 % of mu W", (S(0.15, 2.5, 3), S(0.2, 3.0, 3, rest=900.0)),
         {"base": {"yield_displacement": 5e-4}}, noise=0.008, drift=0.004),
    Case("P33", (), "test", "independent", "constant friction, AR(1) noise and a drift of the "
         "force zero of 0.5 % of mu W, 200 Hz", (S(0.1, 2.5, 3), S(0.25, 4.0, 2, rest=900.0)),
         {"base": {"yield_displacement": 3e-4}}, dt=0.005, noise=0.008, noise_kind="ar1",
         rho=0.85, drift=0.005),
    Case("P34", (), "tune", "package", "constant friction, white noise and a drift of the force "
         "zero of 0.5 % of mu W, tests at 0.25-2 Hz", (S(0.05, 0.5, 6), S(0.1, 2.0, 3),
                                                       S(0.2, 4.0, 2)),
         {"u_y": 3e-4}, dt=0.005, noise=0.01, drift=0.005),
    Case("P34", (), "test", "independent", "rigid-plastic constant friction at 0.25-2 Hz, white "
         "noise and a drift of the force zero of 0.3 % of mu W, 500 Hz",
         (S(0.05, 0.5, 6), S(0.1, 2.0, 3, rest=600.0), S(0.2, 4.0, 2, rest=600.0)),
         {"base": {"transition": "rigid-plastic"}}, dt=0.002, noise=0.012, drift=0.003),
)


ISSUE21_PAIRS = ("P25", "P26", "P27", "P28", "P29", "P30", "P31", "P32", "P33", "P34")
"""The pairs of issue 21's four kinds (a play a nuisance could swallow, a speed effect at
several periods, residual inside the transition windows, a play beside heating; noise and a
drift with no effect)."""
ISSUE21_TRUTHS = frozenset(c.truth for c in CASES if c.pair in ISSUE21_PAIRS)


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

