"""The tuning panel's 58 cases in 29 tune/test pairs, and the test histories they use.

Each case names its labelled effects, its half, its truth source
(:mod:`validation.diagnosis.tuning.sources`), a description, its tests and its nuisance (see
:mod:`validation.diagnosis.tuning` for the ranges). The two cases of a pair share the
labelled effects and differ in truth source and nuisance.
"""

from __future__ import annotations

import math

from validation.diagnosis.tuning.sources import Case, Test, independent, opensees, package

__all__ = [
    "BIG",
    "CASES",
    "DAMPER",
    "EXP_VELOCITY",
    "HEAT_SET",
    "ISSUE21_TRUTHS",
    "ONE",
    "PAIR",
    "PRESSURE_SET",
    "SINE_SET",
    "VARYING",
    "VARYING_STRONG",
    "VELOCITY_SET",
    "WEAR_SET",
]

# --- the cases ------------------------------------------------------------------------------

SINE_SET = (Test(0.1, 2.5, 3), Test(0.2, 3.0, 3), Test(0.3, 3.0, 3), Test(0.15, 2.5, 6))
VELOCITY_SET = (Test(0.2, 2.5, 3), Test(0.2, 8.0, 2), Test(0.05, 4.0, 3), Test(0.02, 8.0, 2))
PRESSURE_SET = (Test(0.15, 2.5, 3, 40 / 60), Test(0.15, 2.5, 3, 80 / 60),
                Test(0.15, 2.5, 3, 20 / 60), Test(0.15, 2.5, 3, 1.0))
VARYING = (Test(0.15, 2.5, 3, 1.0, 0.35), Test(0.25, 3.0, 3, 1.0, 0.35),
           Test(0.1, 2.5, 4, 1.0, 0.35))
VARYING_STRONG = (Test(0.1, 2.5, 3, 1.0, 0.5), Test(0.15, 3.0, 3, 1.0, 0.5),
                  Test(0.08, 2.5, 4, 1.0, 0.5))
HEAT_SET = (Test(0.2, 3.0, 4), Test(0.3, 3.0, 3, rest=600.0), Test(0.15, 2.5, 5, rest=600.0))
PAIR = (Test(0.25, 3.0, 3), Test(0.15, 2.5, 3))
ONE = (Test(0.25, 3.0, 3),)
DAMPER = (Test(0.025, 2.0, 4), Test(0.035, 4.0, 3))
BIG = (Test(0.4, 4.0, 3), Test(0.3, 3.5, 3))
WEAR_SET = (Test(0.2, 3.0, 3), Test(0.2, 3.0, 3, rest=1800.0), Test(0.15, 2.5, 3, rest=1800.0),
            Test(0.25, 3.0, 3, rest=1800.0))

EXP_VELOCITY = ("exponential", 0.45, 0.03)
CASES: tuple[Case, ...] = (
    # --- no unmodelled effect (12) ---
    Case((), "tune", "package", "constant friction, elastic-plastic u_y 0.5 mm", SINE_SET,
         package),
    Case((), "test", "package", "constant friction, u_y 0.5 mm, coloured noise, lag 0.7 "
         "samples, 200 Hz", PAIR, package, dt=0.005, noise=0.005, colour=0.9, lag_samples=0.7),
    Case((), "tune", "independent", "rigid-plastic constant friction (the paper's form)", ONE,
         independent, options={"transition": "rigid-plastic"}),
    Case((), "test", "independent", "rigid-plastic constant friction, 500 Hz, 1.5 % noise",
         (Test(0.2, 3.0, 2),), independent, dt=0.002, noise=0.015,
         options={"transition": "rigid-plastic"}),
    Case((), "tune", "opensees", "OpenSees singleFPBearing Coulomb", PAIR, opensees,
         options={"element": "coulomb"}),
    Case((), "test", "opensees", "OpenSees singleFPBearing Coulomb, 200 Hz, lag 1 sample",
         (Test(0.2, 3.0, 3), Test(0.1, 2.5, 3), Test(0.3, 3.0, 2)), opensees, dt=0.005,
         noise=0.008, lag_samples=1.0, options={"element": "coulomb"}),
    Case((), "tune", "independent", "smooth (Bouc-Wen) transition u_y 1 mm, lag 1.2 samples, "
         "coloured noise", PAIR, independent, colour=0.8, lag_samples=1.2,
         options={"transition": "smooth", "u_y": 1e-3}),
    Case((), "test", "independent", "elastic-plastic u_y 1.5 mm, lag 1.5 samples, 0.3 % "
         "noise, no velocity column", (Test(0.05, 2.0, 4), Test(0.1, 2.5, 3)), independent,
         noise=0.003, lag_samples=1.5, velocity_column=False, options={"u_y": 1.5e-3}),
    Case((), "tune", "package", "full precise model, told precise", SINE_SET, package,
         baseline="precise", options={"base_dependencies": ("pressure", "velocity",
                                                            "temperature")}),
    Case((), "test", "package", "full precise model, told precise, 2 tests, 0.5 % noise",
         PAIR, package, noise=0.005, baseline="precise",
         options={"base_dependencies": ("pressure", "velocity", "temperature")}),
    Case((), "tune", "independent", "constant friction, axial load varying in time", VARYING,
         independent, axial_column=True, velocity_column=False),
    Case((), "test", "package", "constant friction, axial load varying in time, u_y 0.2 mm",
         VARYING[:2], package, axial_column=True, options={"u_y": 2e-4}),
    # --- one effect (22) ---
    Case(("heating",), "tune", "independent", "temperature dependence (Eq. 3-5), rests of 600 s",
         HEAT_SET, independent, options={}),
    Case(("heating",), "test", "opensees", "OpenSees FPBearingPTV, temperature (Kumar)", PAIR,
         opensees, options={"element": "ptv"}),
    Case(("velocity",), "tune", "independent", "velocity: mu_slow/mu_fast 0.55, v_c 30 mm/s",
         VELOCITY_SET, independent, velocity_column=False,
         options={"velocity": EXP_VELOCITY}),
    Case(("velocity",), "test", "opensees", "OpenSees singleFPBearing VelDependent (Eq. 2)",
         VELOCITY_SET, opensees, options={"element": "velocity"}),
    Case(("pressure",), "tune", "independent", "pressure (Eq. 1), one load per test",
         PRESSURE_SET, independent, options={}),
    Case(("pressure",), "test", "package", "pressure (Eq. 1), axial load varying in time",
         VARYING, package, axial_column=True, options={}),
    Case(("breakaway",), "tune", "independent", "breakaway 40 % fading linearly over 8 mm",
         SINE_SET[:3], independent, options={"breakaway": (0.4, 0.008)}),
    Case(("breakaway",), "test", "package", "breakaway 35 % fading quadratically over 10 mm",
         PAIR, package, noise=0.006),
    Case(("wear",), "tune", "independent", "friction drops 8 % from test to test", WEAR_SET,
         independent, noise=0.005, options={"wear_drop": -0.08}),
    Case(("wear",), "test", "package", "friction falls 20 % over the campaign as S^0.6",
         SINE_SET, package, noise=0.005),
    Case(("stiffness",), "tune", "independent", "true R_eff 3.6 m, told 4.5 m", SINE_SET[:3],
         independent, options={"true_radius": 3.6}),
    Case(("stiffness",), "test", "opensees", "OpenSees Coulomb, true R_eff 3.6 m, told 4.5",
         PAIR, opensees, options={"element": "coulomb", "true_radius": 3.6}),
    Case(("asymmetry",), "tune", "independent", "mu(+)/mu(-) = 1.35", PAIR, independent,
         options={"direction": 0.15}),
    Case(("asymmetry",), "test", "independent", "mu(+)/mu(-) = 0.79, smooth transition",
         SINE_SET[:2], independent, options={"direction": -0.12, "transition": "smooth",
                                             "u_y": 6e-4}),
    Case(("backlash",), "tune", "independent", "4 mm play, flat slider (R = inf)", DAMPER,
         independent, dt=0.004, radius=math.inf, options={"backlash": 0.004, "u_y": 2e-4}),
    Case(("backlash",), "test", "independent", "3 mm play on a pendulum, 200 Hz",
         (Test(0.05, 2.0, 3), Test(0.1, 2.5, 3)), independent, dt=0.005,
         options={"backlash": 0.003, "u_y": 3e-4}),
    Case(("geometry",), "tune", "independent", "spherical surface, R 1.2 m, 0.4 m", BIG,
         independent, radius=1.2, options={}),
    Case(("geometry",), "test", "independent", "spherical surface, R 1.2 m, rigid-plastic",
         (Test(0.35, 3.5, 3),), independent, radius=1.2, noise=0.006,
         options={"transition": "rigid-plastic"}),
    Case(("lag",), "tune", "independent", "force channel 5 samples late (50 ms)", PAIR,
         independent, lag_samples=5.0),
    Case(("lag",), "test", "package", "force channel 8 samples late at 200 Hz (40 ms)",
         PAIR, package, dt=0.005, lag_samples=8.0),
    Case(("heating",), "tune", "package", "full precise model, told precise without heating",
         SINE_SET, package, baseline="precise", without=("heating",),
         options={"base_dependencies": ("pressure", "velocity")}),
    Case(("heating",), "test", "package", "full precise model, told precise without heating,"
         " 2 tests", PAIR, package, baseline="precise", without=("heating",), noise=0.006,
         options={"base_dependencies": ("pressure", "velocity")}),
    # --- two effects (8) ---
    Case(("heating", "velocity"), "tune", "independent", "temperature and velocity (Eq. 2-5)",
         VELOCITY_SET[:3], independent, options={"velocity": ("paper",)}),
    Case(("heating", "velocity"), "test", "package", "precise model: temperature and velocity",
         VELOCITY_SET, package),
    Case(("pressure", "heating"), "tune", "independent", "pressure and temperature, axial "
         "load varying in time by 50 %", VARYING_STRONG, independent, axial_column=True),
    Case(("pressure", "heating"), "test", "package", "pressure and temperature, axial load "
         "varying in time by 50 %", VARYING_STRONG, package, axial_column=True),
    Case(("backlash", "asymmetry"), "tune", "independent", "3 mm play and mu(+)/mu(-) = 0.7 "
         "(a friction damper)", DAMPER, independent, dt=0.004, radius=math.inf,
         options={"backlash": 0.003, "direction": -0.18, "u_y": 2e-4}),
    Case(("backlash", "asymmetry"), "test", "independent", "4 mm play and mu(+)/mu(-) = 1.4 "
         "on a pendulum", (Test(0.08, 2.5, 3), Test(0.12, 3.0, 3)), independent, dt=0.005,
         options={"backlash": 0.004, "direction": 0.17, "u_y": 3e-4}),
    Case(("wear", "breakaway"), "tune", "independent", "drop of 8 % per test and a 40 % "
         "breakaway over 8 mm", WEAR_SET, independent, noise=0.006,
         options={"wear_drop": -0.08, "breakaway": (0.4, 0.008)}),
    Case(("wear", "breakaway"), "test", "package", "wear S^0.6 (-20 %) and breakaway 35 %",
         SINE_SET, package, noise=0.006),
    # --- issue 21, the four kinds in one direction (16) ---
    # a play of a few mm that the calibrated u_y (grid up to 2.5 mm) could swallow
    Case(("backlash",), "tune", "independent", "2.5 mm play behind a smooth 1.2 mm transition "
         "on a pendulum, 200 Hz", (Test(0.08, 2.5, 3), Test(0.12, 3.0, 3)), independent,
         dt=0.005, noise=0.008, options={"backlash": 0.0025, "transition": "smooth",
                                         "u_y": 1.2e-3}),
    Case(("backlash",), "test", "independent", "3 mm play behind a 2 mm elastic-plastic "
         "transition, flat slider (R = inf), coloured noise", DAMPER, independent, dt=0.004,
         radius=math.inf, colour=0.8, options={"backlash": 0.003, "u_y": 2e-3}),
    # a speed effect in a campaign of one amplitude at several periods
    Case(("velocity",), "tune", "independent", "velocity: mu_slow/mu_fast 0.5, v_c 50 mm/s, "
         "one amplitude at periods 1.2-8 s", (Test(0.1, 1.2, 4), Test(0.1, 3.0, 3, rest=600.0),
                                              Test(0.1, 8.0, 2, rest=600.0)),
         independent, dt=0.005, options={"velocity": ("exponential", 0.5, 0.05)}),
    Case(("velocity",), "test", "independent", "velocity (Eq. 2) at periods 1-6 s, 80 mm, lag "
         "1 sample", (Test(0.08, 1.0, 4), Test(0.08, 2.5, 3, rest=600.0),
                      Test(0.08, 6.0, 2, rest=600.0)),
         independent, dt=0.004, lag_samples=1.0, options={"velocity": ("paper",)}),
    # residual energy inside the transition window
    Case(("breakaway",), "tune", "independent", "breakaway 80 % fading linearly over 2.5 mm",
         (Test(0.05, 2.0, 4), Test(0.1, 2.5, 3)), independent, dt=0.004, noise=0.006,
         options={"breakaway": (0.8, 0.0025)}),
    Case(("breakaway",), "test", "independent", "breakaway 70 % over 3 mm, rigid-plastic, "
         "flat slider (R = inf)", DAMPER, independent, dt=0.004, radius=math.inf,
         options={"breakaway": (0.7, 0.003), "transition": "rigid-plastic"}),
    Case(("backlash",), "tune", "independent", "2 mm play, rigid-plastic pendulum, 500 Hz",
         (Test(0.1, 2.5, 3), Test(0.2, 3.0, 2)), independent, dt=0.002, noise=0.008,
         options={"backlash": 0.002, "transition": "rigid-plastic"}),
    Case(("backlash",), "test", "independent", "1.8 mm play with a 0.3 mm transition, 500 Hz",
         (Test(0.06, 2.0, 3), Test(0.12, 2.5, 3)), independent, dt=0.002, noise=0.008,
         options={"backlash": 0.0018, "u_y": 3e-4}),
    # a play beside heating
    Case(("backlash", "heating"), "tune", "independent", "3 mm play and temperature "
         "dependence, rests of 600 s", HEAT_SET, independent, dt=0.005,
         options={"backlash": 0.003, "u_y": 3e-4}),
    Case(("backlash", "heating"), "test", "independent", "4 mm play and temperature "
         "dependence, coloured noise", (Test(0.2, 3.0, 4), Test(0.25, 3.0, 3, rest=300.0)),
         independent, colour=0.8, options={"backlash": 0.004, "u_y": 5e-4}),
    Case(("backlash", "heating"), "tune", "independent", "2 mm play and temperature "
         "dependence, smooth transition", (Test(0.15, 2.5, 4), Test(0.2, 3.0, 3, rest=300.0)),
         independent, dt=0.005, noise=0.006,
         options={"backlash": 0.002, "transition": "smooth", "u_y": 4e-4}),
    Case(("backlash", "heating"), "test", "independent", "3 mm play and temperature "
         "dependence, rigid-plastic, 500 Hz", (Test(0.2, 3.0, 3),
                                               Test(0.15, 2.5, 4, rest=600.0)),
         independent, dt=0.002, options={"backlash": 0.003, "transition": "rigid-plastic"}),
    # no effect: noise plus a drift of the force zero (what a hint must not call a finding)
    Case((), "tune", "independent", "constant friction, white noise and a drift of the force "
         "zero of 0.4 % of mu W", (Test(0.15, 2.5, 3), Test(0.2, 3.0, 3)), independent,
         noise=0.008, drift=0.004),
    Case((), "test", "package", "constant friction, coloured noise and a drift of 0.5 % of "
         "mu W, 200 Hz", (Test(0.1, 2.5, 3), Test(0.25, 4.0, 2)), package, dt=0.005,
         noise=0.008, colour=0.85, drift=0.005),
    Case((), "tune", "package", "constant friction at 0.25-2 Hz, a drift of 0.5 % of mu W",
         (Test(0.05, 0.5, 6), Test(0.1, 2.0, 3), Test(0.2, 4.0, 2)), package, dt=0.005,
         noise=0.01, drift=0.005),
    Case((), "test", "independent", "rigid-plastic constant friction at 0.25-2 Hz, 500 Hz, a "
         "drift of 0.3 % of mu W", (Test(0.05, 0.5, 6), Test(0.1, 2.0, 3), Test(0.2, 4.0, 2)),
         independent, dt=0.002, noise=0.012, drift=0.003,
         options={"transition": "rigid-plastic"}),
)

ISSUE21_TRUTHS = frozenset(c.truth for c in CASES[42:])
"""The 16 cases of issue 21's four kinds (the last 8 pairs)."""
