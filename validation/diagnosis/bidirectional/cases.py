"""The bidirectional panel's design: its records (a test, a case) and its 28 cases in 14 pairs.

Each *scenario* (a set of true effects, possibly none) is made twice: one case goes to the
**tune** half, the other to the **test** half. The two cases of a pair share the labelled
effects and differ in their orbits, campaign and nuisance. Every case is made by the
bidirectional truth (:mod:`validation.diagnosis.bidirectional`); ``spec`` gives its bearing's
parameters (``base``, always on, and ``effects``, switched on with each labelled effect).

Nuisance, never labelled, varied over the cases: sampling 100-500 Hz; force noise 0.5-1.2 % of
mu0 W, white, AR(1) (rho 0.8-0.9) or band-limited; displacement noise 0.02 mm; 16-bit
converters (force over +-1.5 MN, displacement over +-0.5 m) or none; spikes of 30 % of the RMS
force on a few samples; a force channel stuck for 20 samples; a gain error of 2-3 % on one
axis's force or displacement channel; actuators following their command through a
second-order filter of 8-25 Hz; a force-channel lag up to 1.5 samples; the transition
(rigid-plastic, elastic-plastic 0.5-1 mm, smooth 0.5-1 mm).

Where there is a play the truth assumes that the bearing stands still in an open gap (its
static friction, taken as mu0, holds it against the restoring force): the designs keep |u| / R
below mu0 there (peak |u| 0.16 m at R 4.5 m). With a speed law beside the play (B14) the
sliding friction at low speed is lower than that; the assumption is kept.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from validation.diagnosis.bidirectional.bearing import SpeedLaw, WearLaw

SLIDER = 0.3  # [m]
RADIUS = 4.5  # [m]
AREA = math.pi * (0.5 * SLIDER) ** 2
PRESSURE = 60.0  # [N/mm^2] nominal
W = PRESSURE * 1.0e6 * AREA  # [N] 4.24 MN
MU0 = 0.041
LABEL_MIN = 0.03  # a labelled effect: RMS contribution >= 3 % of the RMS force
LAG_LABEL_MIN = 5.0  # [samples] a lag is labelled from 5 samples up; nuisance up to 1.5
NIGHT = 86400.0  # [s]
HALVES = ("tune", "test")
EFFECTS = ("heating", "velocity", "pressure", "wear", "backlash", "lag")
FORCE_RANGE = 1.5e6  # [N] the load cell's converter full scale
DISPLACEMENT_RANGE = 0.5  # [m]


@dataclass(frozen=True)
class Run:
    """One test of a campaign.

    orbit : ``("circular", A, T, cycles)``, ``("eight", A_x, A_y, T, cycles)``,
        ``("square", A, speed, cycles)`` or ``("quake", pair, peak)`` (see
        :mod:`~validation.diagnosis.bidirectional.orbits`).
    pressure : the test's nominal contact pressure [N/mm^2] (sets its axial load).
    varying : relative amplitude of an axial load varying in time,
        N(t) = N (1 + varying sin(2 pi t / varying_period)).
    rest : rest before the test [s] (None: the first test, or a night for a later one).
    temperature : initial temperature [degC].
    """

    orbit: tuple
    pressure: float = PRESSURE
    varying: float = 0.0
    varying_period: float = 1.7
    rest: float | None = None
    temperature: float = 20.0


@dataclass(frozen=True)
class Case:
    """One case of the panel.

    spec : ``base`` (Bearing2D keywords always on) and ``effects`` (keywords per labelled
        effect; ``lag`` is the force channels' lag in samples).
    noise : force noise as a fraction of mu0 W; ``noise_kind`` white, ar1 or band, ``rho``.
    lag_samples : the nuisance lag of the force channels [samples] (below 1.5).
    actuator : (frequency [Hz], damping) of the actuators' dynamics, or None.
    quantise : whether the channels pass 16-bit converters.
    spikes, stuck : sensor faults (count of spikes, length of a stuck run).
    gain : (channel, relative error) or None.
    gzip : write the tests as ``.csv.gz``.
    """

    pair: str
    effects: tuple[str, ...]
    half: str
    truth: str
    tests: tuple[Run, ...]
    spec: dict = field(default_factory=dict)
    dt: float = 0.005
    noise: float = 0.01
    noise_kind: str = "white"
    rho: float = 0.0
    displacement_noise: float = 2.0e-5
    lag_samples: float = 0.0
    actuator: tuple[float, float] | None = None
    quantise: bool = False
    spikes: int = 0
    stuck: int = 0
    gain: tuple[str, float] | None = None
    velocity_column: bool = False
    axial_column: bool = False
    gzip: bool = False
    baseline: str = "constant"
    without: tuple[str, ...] = ()
    radius: float = RADIUS
    weight: float = W
    mu0: float = MU0


def axial_load(case: Case, run: Run) -> float:
    """The nominal axial load of one test [N] (its pressure times the area)."""
    return case.weight * run.pressure / PRESSURE


def rest_before(case: Case, k: int) -> float | None:
    """The rest before the ``k``-th test [s] (None for the first, a night when not given)."""
    if k == 0:
        return None
    rest = case.tests[k].rest
    return NIGHT if rest is None else float(rest)


# --- the cases ------------------------------------------------------------------------------

R = Run
EP = "elastic-plastic"
SPEED_EXP = {"speed": SpeedLaw("exp", ratio=0.5, speed=0.03)}
SPEED_PAPER = {"speed": SpeedLaw("paper")}
HEAT = {"heating": True}
PRESS = {"pressure": True}

CASES: tuple[Case, ...] = (
    # --- no effect: 5 pairs (three of them decoys) ---
    Case("B01", (), "tune", "constant friction, circle and figure-eight, 200 Hz, white noise",
         (R(("circular", 0.15, 3.0, 3)), R(("eight", 0.2, 0.1, 4.0, 3), rest=600.0)),
         noise=0.01),
    Case("B01", (), "test", "constant friction, square and circle, 250 Hz, AR(1) noise, "
         "16-bit converters", (R(("square", 0.12, 0.25, 2)),
                               R(("circular", 0.2, 4.0, 2), rest=900.0)),
         {"base": {"yield_displacement": 1.0e-3}}, dt=0.004, noise=0.008, noise_kind="ar1",
         rho=0.9, quantise=True),
    Case("B02", (), "tune", "constant friction, earthquake orbit (CHY023) and a circle, "
         "band-limited noise, 3 spikes, actuators at 20 Hz", (R(("quake", "CHY023", 0.2)),
                                                            R(("circular", 0.1, 2.5, 3))),
         dt=0.005, noise=0.008, noise_kind="band", spikes=3, actuator=(20.0, 0.7), gzip=True),
    Case("B02", (), "test", "constant friction, smooth transition, earthquake orbit (ILA061) "
         "and a figure-eight, a stuck force channel, actuators at 15 Hz, lag 1 sample",
         (R(("quake", "ILA061", 0.25)), R(("eight", 0.15, 0.15, 3.0, 3), rest=1200.0)),
         {"base": {"transition": "smooth", "yield_displacement": 8.0e-4}}, dt=0.005,
         noise=0.006, stuck=20, actuator=(15.0, 0.5), lag_samples=1.0, gzip=True),
    Case("B03", (), "tune", "decoy: a 2 % gain error on force_y, smooth transition, "
         "figure-eights", (R(("eight", 0.2, 0.1, 3.0, 3)), R(("eight", 0.1, 0.2, 4.0, 2))),
         {"base": {"transition": "smooth", "yield_displacement": 1.0e-3}}, dt=0.01,
         noise=0.005, gain=("force_y", 0.02), velocity_column=True),
    Case("B03", (), "test", "decoy: a 3 % gain error on force_x, rigid-plastic, 500 Hz",
         (R(("circular", 0.12, 2.5, 3)), R(("square", 0.1, 0.2, 2), rest=600.0)),
         {"base": {"transition": "rigid-plastic"}}, dt=0.002, noise=0.012,
         gain=("force_x", 0.03)),
    Case("B04", (), "tune", "decoy: circles at 0.03-0.47 m/s with no speed effect, lag 1.5 "
         "samples", (R(("circular", 0.15, 2.0, 3)), R(("circular", 0.15, 8.0, 1.5)),
                     R(("circular", 0.1, 20.0, 1))), dt=0.01, noise=0.01, lag_samples=1.5),
    Case("B04", (), "test", "decoy: figure-eights and a slow square with no speed effect, "
         "actuators at 8 Hz (damping 0.4), lag 0.5 samples",
         (R(("eight", 0.2, 0.1, 2.5, 3)), R(("eight", 0.1, 0.05, 10.0, 1)),
          R(("square", 0.08, 0.02, 1))), dt=0.005, noise=0.01, noise_kind="ar1", rho=0.8,
         actuator=(8.0, 0.4), lag_samples=0.5),
    Case("B05", (), "tune", "decoy: tests at 30, 60 and 90 N/mm^2 with no pressure effect, "
         "axial-force column", (R(("circular", 0.12, 3.0, 2), 30.0),
                                R(("circular", 0.12, 3.0, 2), 60.0, rest=600.0),
                                R(("circular", 0.12, 3.0, 2), 90.0, rest=600.0)),
         dt=0.005, noise=0.008, axial_column=True),
    Case("B05", (), "test", "decoy: axial load varying in time by 40 % with no pressure "
         "effect, 16-bit converters", (R(("eight", 0.15, 0.1, 3.0, 3), varying=0.4),
                                       R(("circular", 0.1, 2.5, 3), varying=0.4, rest=600.0)),
         dt=0.004, noise=0.01, axial_column=True, quantise=True),
    # --- one effect: 6 pairs ---
    Case("B06", ("heating",), "tune", "heating (Eq. 3-5 on the plate's field, normalised at "
         "20 degC), circles then a figure-eight after 300 s",
         (R(("circular", 0.1, 2.5, 4)), R(("eight", 0.2, 0.1, 3.0, 3), rest=300.0)),
         {"effects": {"heating": HEAT}}, dt=0.005, noise=0.008),
    Case("B06", ("heating",), "test", "heating on an earthquake orbit (TAP084) and a circle "
         "after 600 s, AR(1) noise", (R(("quake", "TAP084", 0.2)),
                                      R(("circular", 0.15, 3.0, 3), rest=600.0)),
         {"effects": {"heating": HEAT}}, dt=0.004, noise=0.01, noise_kind="ar1", rho=0.85,
         actuator=(20.0, 0.7)),
    Case("B07", ("velocity",), "tune", "velocity on |v| (mu_slow / mu_fast 0.7, 30 mm/s), "
         "circles at 0.03-0.47 m/s", (R(("circular", 0.15, 2.0, 3)),
                                      R(("circular", 0.15, 8.0, 1.5), rest=600.0),
                                      R(("circular", 0.1, 20.0, 1), rest=600.0)),
         {"effects": {"velocity": {"speed": SpeedLaw("exp", ratio=0.7, speed=0.03)}}},
         dt=0.01, noise=0.01),
    Case("B07", ("velocity",), "test", "velocity on |v| (Eq. 2 normalised at 400 mm/s), "
         "figure-eights and a slow square, smooth transition",
         (R(("eight", 0.2, 0.1, 2.5, 3)), R(("eight", 0.1, 0.05, 10.0, 1), rest=600.0),
          R(("square", 0.08, 0.02, 1), rest=600.0)),
         {"base": {"transition": "smooth", "yield_displacement": 6.0e-4},
          "effects": {"velocity": SPEED_PAPER}}, dt=0.005, noise=0.008, noise_kind="band"),
    Case("B08", ("pressure",), "tune", "pressure (Eq. 1 normalised at 60 N/mm^2), tests at "
         "30, 90 and 45 N/mm^2", (R(("circular", 0.12, 3.0, 2), 30.0),
                                  R(("eight", 0.15, 0.1, 3.0, 2), 90.0, rest=600.0),
                                  R(("circular", 0.12, 3.0, 2), 45.0, rest=600.0)),
         {"effects": {"pressure": PRESS}}, dt=0.005, noise=0.008),
    Case("B08", ("pressure",), "test", "pressure (Eq. 1) with the axial load varying in time "
         "by 45 %, axial-force column, rigid-plastic",
         (R(("eight", 0.15, 0.1, 3.0, 3), varying=0.45, varying_period=2.3),
          R(("circular", 0.1, 2.5, 3), 40.0, varying=0.45, varying_period=2.3, rest=600.0)),
         {"base": {"transition": "rigid-plastic"}, "effects": {"pressure": PRESS}},
         dt=0.004, noise=0.006, axial_column=True),
    Case("B09", ("wear",), "tune", "friction drops 7 % from test to test, four tests",
         (R(("circular", 0.15, 3.0, 2)), R(("eight", 0.15, 0.1, 3.0, 2), rest=1800.0),
          R(("circular", 0.1, 2.5, 2), rest=1800.0), R(("square", 0.1, 0.2, 1), rest=1800.0)),
         {"effects": {"wear": {"wear": WearLaw("step", 0.07)}}}, dt=0.01, noise=0.005),
    Case("B09", ("wear",), "test", "friction falls 25 % over the campaign's travel, "
         "earthquake orbit (TAP094) and circles, 16-bit converters",
         (R(("circular", 0.15, 3.0, 3)), R(("quake", "TAP094", 0.2), rest=900.0),
          R(("circular", 0.15, 3.0, 3), rest=900.0)),
         {"effects": {"wear": {"wear": WearLaw("travel", 0.25, 12.0)}}}, dt=0.005,
         noise=0.006, quantise=True, lag_samples=0.7),
    Case("B10", ("backlash",), "tune", "a play of 2 mm on each axis, figure-eight and circle",
         (R(("eight", 0.15, 0.1, 3.0, 3)), R(("circular", 0.1, 2.5, 3), rest=600.0)),
         {"effects": {"backlash": {"play": (0.002, 0.002)}}}, dt=0.004, noise=0.008),
    Case("B10", ("backlash",), "test", "a play of 5 mm in x and 3 mm in y, square and "
         "earthquake orbit (CHY023), smooth transition",
         (R(("square", 0.1, 0.2, 2)), R(("quake", "CHY023", 0.15), rest=600.0)),
         {"base": {"transition": "smooth", "yield_displacement": 5.0e-4},
          "effects": {"backlash": {"play": (0.005, 0.003)}}}, dt=0.005, noise=0.008,
         noise_kind="ar1", rho=0.9),
    Case("B11", ("lag",), "tune", "the force channels 8 samples late (40 ms)",
         (R(("circular", 0.15, 3.0, 3)), R(("eight", 0.2, 0.1, 4.0, 2), rest=600.0)),
         {"effects": {"lag": 8.0}}, dt=0.005, noise=0.01),
    Case("B11", ("lag",), "test", "the force channels 6 samples late (24 ms) at 250 Hz, "
         "band-limited noise", (R(("eight", 0.15, 0.15, 2.5, 3)),
                                R(("square", 0.1, 0.25, 2), rest=600.0)),
         {"effects": {"lag": 6.0}}, dt=0.004, noise=0.008, noise_kind="band", spikes=2),
    # --- two effects: 3 pairs ---
    Case("B12", ("backlash", "heating"), "tune", "a play of 4 mm per axis beside heating, "
         "circles", (R(("circular", 0.1, 2.5, 4)), R(("circular", 0.15, 3.0, 3), rest=300.0)),
         {"effects": {"heating": HEAT, "backlash": {"play": (0.004, 0.004)}}}, dt=0.005,
         noise=0.008),
    Case("B12", ("backlash", "heating"), "test", "a play of 3 mm in x and 5 mm in y beside "
         "heating, earthquake orbit (TAP094) and a figure-eight",
         (R(("quake", "TAP094", 0.15)), R(("eight", 0.12, 0.08, 3.0, 3), rest=300.0)),
         {"effects": {"heating": HEAT, "backlash": {"play": (0.003, 0.005)}}}, dt=0.005,
         noise=0.01, noise_kind="ar1", rho=0.85, actuator=(25.0, 0.7)),
    Case("B13", ("pressure", "velocity"), "tune", "velocity on |v| and pressure, circles at "
         "several speeds and pressures", (R(("circular", 0.15, 2.0, 2), 30.0),
                                          R(("circular", 0.15, 8.0, 1.5), 90.0, rest=600.0),
                                          R(("circular", 0.1, 20.0, 1), 60.0, rest=600.0)),
         {"effects": {"velocity": SPEED_EXP, "pressure": PRESS}}, dt=0.01, noise=0.01),
    Case("B13", ("pressure", "velocity"), "test", "velocity (Eq. 2) and pressure (Eq. 1), "
         "figure-eights and a slow square at 30-90 N/mm^2, axial-force column",
         (R(("eight", 0.2, 0.1, 2.5, 2), 90.0), R(("eight", 0.1, 0.05, 10.0, 1), 30.0,
                                                  rest=600.0),
          R(("square", 0.08, 0.02, 1), 60.0, rest=600.0)),
         {"effects": {"velocity": SPEED_PAPER, "pressure": PRESS}}, dt=0.005, noise=0.008,
         axial_column=True, gain=("displacement_y", -0.02)),
    Case("B14", ("backlash", "velocity"), "tune", "a play of 3 mm per axis beside velocity "
         "on |v|, circles at several speeds",
         (R(("circular", 0.15, 2.0, 3)), R(("circular", 0.15, 8.0, 1.5), rest=600.0),
          R(("circular", 0.1, 20.0, 1), rest=600.0)),
         {"effects": {"velocity": SPEED_EXP, "backlash": {"play": (0.003, 0.003)}}},
         dt=0.01, noise=0.008),
    Case("B14", ("backlash", "velocity"), "test", "a play of 4 mm in x, 2 mm in y beside "
         "velocity (Eq. 2), earthquake orbit (ILA061) and figure-eights, spikes",
         (R(("quake", "ILA061", 0.12)), R(("eight", 0.12, 0.08, 2.5, 2), rest=600.0),
          R(("eight", 0.1, 0.05, 10.0, 1), rest=600.0)),
         {"effects": {"velocity": SPEED_PAPER, "backlash": {"play": (0.004, 0.002)}}},
         dt=0.005, noise=0.008, spikes=3),
)


def check_design() -> None:
    """Each pair has one tune and one test case with the same effects; effects are known."""
    pairs: dict[str, list[Case]] = {}
    for case in CASES:
        pairs.setdefault(case.pair, []).append(case)
        if not set(case.effects) <= set(EFFECTS):
            raise ValueError(f"{case.pair}: unknown effect in {case.effects}")
        if "lag" not in case.effects and case.lag_samples > 1.5:
            raise ValueError(f"{case.pair}: a nuisance lag above 1.5 samples")
    for name, cases in pairs.items():
        if sorted(c.half for c in cases) != ["test", "tune"]:
            raise ValueError(f"pair {name} is not one tune and one test case")
        if len({tuple(sorted(c.effects)) for c in cases}) != 1:
            raise ValueError(f"pair {name}: the two cases differ in effects")
