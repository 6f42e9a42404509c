"""Tune variants of the bidirectional panel's plays (issue 21): plays unequal per axis.

The panel's tune half has plays of the same size on both axes (B10, B12, B14). These variants,
all labelled ``tune`` (they are for finding weaknesses and choosing, never for reporting a
test score), are built like those tune designs but with a play that differs per axis (1.5-6 mm
on one axis, another size or none on the other), on squares, figure-eights, circles and
earthquake orbits, alone or beside a friction law (heating, velocity, pressure, wear), at
100-500 Hz, with the nuisances the panel declares (:mod:`validation.diagnosis.bidirectional.
cases`). They were drawn from those declared ranges, not from the test half's designs.

Every variant is its own pair (``V01``...) with a tune case only; they are written with the
panel's writer (:func:`~validation.diagnosis.bidirectional.write.write_panel` with ``cases``),
so that ``python -m validation.diagnosis.score FOLDER --half tune`` scores them.

    python -m validation.diagnosis.bidirectional FOLDER --play-variants [--seed 7]
"""

from __future__ import annotations

from validation.diagnosis.bidirectional.bearing import SpeedLaw, WearLaw
from validation.diagnosis.bidirectional.cases import Case
from validation.diagnosis.bidirectional.cases import Run as R

__all__ = ["PLAY_VARIANTS"]

EP = "elastic-plastic"
HEAT = {"heating": True}
SPEED = {"speed": SpeedLaw("exp", ratio=0.6, speed=0.03)}
PRESS = {"pressure": True}


def _play(x_mm: float, y_mm: float) -> dict:
    return {"play": (1e-3 * x_mm, 1e-3 * y_mm)}


PLAY_VARIANTS: tuple[Case, ...] = (
    # --- a play alone, unequal per axis ---
    Case("V01", ("backlash",), "tune", "tune variant: a play of 3 mm in x, 1.5 mm in y, square "
         "then circle, 250 Hz",
         (R(("square", 0.1, 0.1, 1)), R(("circular", 0.12, 3.0, 3), rest=600.0)),
         {"effects": {"backlash": _play(3.0, 1.5)}}, dt=0.004, noise=0.008),
    Case("V02", ("backlash",), "tune", "tune variant: a play of 5 mm in x only, figure-eight "
         "and circle, 200 Hz, AR(1) noise",
         (R(("eight", 0.15, 0.08, 3.0, 3)), R(("circular", 0.1, 2.5, 3), rest=600.0)),
         {"effects": {"backlash": _play(5.0, 0.0)}}, dt=0.005, noise=0.008,
         noise_kind="ar1", rho=0.85),
    Case("V03", ("backlash",), "tune", "tune variant: a play of 4 mm in y only, circles, "
         "400 Hz, band-limited noise, 16-bit",
         (R(("circular", 0.12, 3.0, 3)), R(("circular", 0.08, 2.0, 3), rest=300.0)),
         {"effects": {"backlash": _play(0.0, 4.0)}}, dt=0.0025, noise=0.01,
         noise_kind="band", quantise=True),
    Case("V04", ("backlash",), "tune", "tune variant: a play of 2.5 mm in x, 6 mm in y, "
         "earthquake orbit (TAP094) and a circle, 100 Hz, actuators at 15 Hz",
         (R(("quake", "TAP094", 0.15)), R(("circular", 0.1, 3.0, 2), rest=600.0)),
         {"effects": {"backlash": _play(2.5, 6.0)}}, dt=0.01, noise=0.008,
         actuator=(15.0, 0.7)),
    Case("V05", ("backlash",), "tune", "tune variant: a play of 6 mm in x, 2 mm in y, square "
         "and figure-eight, 500 Hz, smooth transition, spikes",
         (R(("square", 0.12, 0.15, 1)), R(("eight", 0.1, 0.15, 4.0, 2), rest=600.0)),
         {"base": {"transition": "smooth", "yield_displacement": 8e-4},
          "effects": {"backlash": _play(6.0, 2.0)}}, dt=0.002, noise=0.006, spikes=3),
    Case("V06", ("backlash",), "tune", "tune variant: a play of 2 mm in x only, circle, "
         "200 Hz, rigid-plastic",
         (R(("circular", 0.1, 2.5, 4)),),
         {"base": {"transition": "rigid-plastic"}, "effects": {"backlash": _play(2.0, 0.0)}},
         dt=0.005, noise=0.006),
    Case("V07", ("backlash",), "tune", "tune variant: a play of 3.5 mm in x, 1.5 mm in y, one "
         "figure-eight, 300 Hz, a 2 % gain error on force_x",
         (R(("eight", 0.15, 0.1, 3.0, 4)),),
         {"effects": {"backlash": _play(3.5, 1.5)}}, dt=1.0 / 300.0, noise=0.008,
         gain=("force_x", 0.02)),
    Case("V08", ("backlash",), "tune", "tune variant: a play of 2 mm in x, 3 mm in y, "
         "earthquake orbit (CHY023), 200 Hz, a stuck force channel",
         (R(("quake", "CHY023", 0.15)), R(("circular", 0.12, 3.0, 2), rest=600.0)),
         {"effects": {"backlash": _play(2.0, 3.0)}}, dt=0.005, noise=0.008, stuck=20),
    Case("V09", ("backlash",), "tune", "tune variant: a play of 6 mm in x, 4 mm in y, "
         "squares, 100 Hz, a 1.5-sample lag",
         (R(("square", 0.1, 0.1, 1)), R(("square", 0.14, 0.2, 1), rest=600.0)),
         {"effects": {"backlash": _play(6.0, 4.0)}}, dt=0.01, noise=0.008, lag_samples=1.5),
    # --- a play beside a friction law ---
    Case("V10", ("backlash", "heating"), "tune", "tune variant: a play of 4.5 mm in x, 2 mm "
         "in y beside heating, circles then a figure-eight",
         (R(("circular", 0.1, 2.5, 4)), R(("eight", 0.15, 0.1, 3.0, 3), rest=300.0)),
         {"effects": {"heating": HEAT, "backlash": _play(4.5, 2.0)}}, dt=0.005, noise=0.008),
    Case("V11", ("backlash", "heating"), "tune", "tune variant: a play of 5 mm in y only "
         "beside heating, square then circle, 250 Hz, AR(1)",
         (R(("square", 0.12, 0.15, 2)), R(("circular", 0.12, 2.5, 3), rest=300.0)),
         {"effects": {"heating": HEAT, "backlash": _play(0.0, 5.0)}}, dt=0.004, noise=0.008,
         noise_kind="ar1", rho=0.8),
    Case("V12", ("backlash", "heating"), "tune", "tune variant: a play of 2 mm in x, 4 mm in y "
         "beside heating, earthquake orbit (ILA061) then circles, 200 Hz",
         (R(("quake", "ILA061", 0.2)), R(("circular", 0.12, 2.5, 4), rest=120.0)),
         {"effects": {"heating": HEAT, "backlash": _play(2.0, 4.0)}}, dt=0.005, noise=0.008),
    Case("V13", ("backlash", "velocity"), "tune", "tune variant: a play of 2.5 mm in x, 5.5 mm "
         "in y beside velocity on |v|, circles at several speeds",
         (R(("circular", 0.15, 2.0, 3)), R(("circular", 0.15, 8.0, 1.5), rest=600.0),
          R(("circular", 0.1, 20.0, 1), rest=600.0)),
         {"effects": {"velocity": SPEED, "backlash": _play(2.5, 5.5)}}, dt=0.01, noise=0.008),
    Case("V14", ("backlash", "velocity"), "tune", "tune variant: a play of 5 mm in x only "
         "beside velocity on |v|, figure-eights at several periods, 250 Hz",
         (R(("eight", 0.15, 0.1, 2.5, 3)), R(("eight", 0.15, 0.1, 10.0, 1), rest=600.0),
          R(("circular", 0.1, 15.0, 1), rest=600.0)),
         {"effects": {"velocity": SPEED, "backlash": _play(5.0, 0.0)}}, dt=0.004, noise=0.008),
    Case("V15", ("backlash", "pressure"), "tune", "tune variant: a play of 3 mm in x, 1.5 mm "
         "in y beside pressure, circles at 30, 60 and 90 N/mm^2",
         (R(("circular", 0.12, 3.0, 2), 30.0), R(("circular", 0.12, 3.0, 2), 60.0, rest=600.0),
          R(("circular", 0.12, 3.0, 2), 90.0, rest=600.0)),
         {"effects": {"pressure": PRESS, "backlash": _play(3.0, 1.5)}}, dt=0.005,
         noise=0.008),
    Case("V16", ("backlash", "wear"), "tune", "tune variant: a play of 4 mm in y, 2 mm in x "
         "beside wear (7 % per test), four tests",
         (R(("circular", 0.15, 3.0, 2)), R(("eight", 0.15, 0.1, 3.0, 2), rest=1800.0),
          R(("circular", 0.1, 2.5, 2), rest=1800.0), R(("square", 0.1, 0.2, 1), rest=1800.0)),
         {"effects": {"wear": {"wear": WearLaw("step", 0.07)}, "backlash": _play(2.0, 4.0)}},
         dt=0.01, noise=0.006),
)
"""The play variants, one tune case per pair ``V01``-``V16``."""
