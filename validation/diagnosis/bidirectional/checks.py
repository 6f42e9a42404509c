"""The bidirectional truth's self-checks, against closed forms and the 1D truth.

``python -m validation.diagnosis.bidirectional --checks`` runs :func:`checks`, which returns
each check's error (relative unless said otherwise):

- a flat rigid-plastic slider on a circular orbit at constant speed and constant mu: the force
  has the magnitude mu N (also with the elastic-plastic transition, once past u_y) and the
  energy per cycle is mu N 2 pi A;
- the smooth transition loading from rest along a line follows z = tanh(u / u_y);
- a linear orbit (a line at 30 degrees, with the speed law, the pressure factor, step wear and
  the elastic-plastic transition; and a line along x with a play) equals the one-direction
  truth of :mod:`validation.diagnosis.independent` on the same sine, along the line, with no
  force across it. That module is a separate implementation; it is used here only, as a
  cross-check, never by the model;
- the heating of a slider standing still equals the half-space solution 2 q sqrt(D t / pi) / k,
  and after a rest the pulse solution; the contact temperature of a moving slider (the lens
  sum) equals the mean of the field over a grid of monitor points under the slider;
- a frictionless spherical surface gives N u / sqrt(R^2 - |u|^2);
- an integer lag is a shift of the samples;
- the actuator's second-order filter has the steady gain 1 / sqrt((1 - r^2)^2 + (2 zeta r)^2);
- the converter's rounding error is at most half a step.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from validation.diagnosis.bidirectional.bearing import (
    CONDUCTIVITY,
    DIFFUSIVITY,
    Bearing2D,
    HeatField,
    SpeedLaw,
    WearLaw,
)
from validation.diagnosis.bidirectional.orbits import Orbit, circular, figure_eight
from validation.diagnosis.bidirectional.rig import Rig, Test2D, quantise, simulate

__all__ = ["checks", "line_orbit"]


def line_orbit(amplitude: float, period: float, cycles: float, angle: float) -> Orbit:
    """u = A sin(2 pi t / T) (cos angle, sin angle) [m], the 1D sine on a line."""
    w = 2.0 * math.pi / period
    c, s = math.cos(angle), math.sin(angle)
    return Orbit(f"line at {math.degrees(angle):g} deg", cycles * period,
                 lambda t: amplitude * np.sin(w * t)[:, None] * np.array([c, s]),
                 lambda t: amplitude * w * np.cos(w * t)[:, None] * np.array([c, s]))


def _work(force: np.ndarray, displacement: np.ndarray) -> float:
    """Trapezoidal integral of F . du along the path [J]."""
    return float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(displacement, axis=0)))


def _against_1d(errors: dict[str, float]) -> None:
    from validation.diagnosis import independent as ind

    w, angle = 4.24e6, math.radians(30.0)
    mine = Bearing2D(w, mu0=0.045, speed=SpeedLaw("exp", 0.5, 0.03), pressure=True,
                     wear=WearLaw("step", 0.05), yield_displacement=8e-4)
    theirs = ind.Bearing(w, mu0=0.045, velocity=ind.Velocity("exp", ratio=0.5, speed=0.03),
                         pressure="normalised", wear=ind.Wear("step", 0.05),
                         yield_displacement=8e-4)
    tests2, tests1 = [], []
    for k, (amp, per, load) in enumerate(((0.1, 2.5, 0.7 * w), (0.05, 6.0, 1.2 * w))):
        rest = None if k == 0 else 600.0
        tests2.append(Test2D(line_orbit(amp, per, 2, angle), 0.005, load, rest_before=rest))
        tests1.append(ind.sine_test(amp, per, 2, 0.005, load, rest_before=rest))
    worst, across = 0.0, 0.0
    direction = np.array([math.cos(angle), math.sin(angle)])
    for a, b in zip(simulate(mine, tests2), ind.simulate(theirs, tests1), strict=True):
        along = a["force"] @ direction
        scale = 0.045 * w
        worst = max(worst, float(np.max(np.abs(along - b["force"]))) / scale)
        across = max(across, float(np.max(np.abs(a["force"] @ np.array([-direction[1],
                                                                         direction[0]])))) / scale)
    errors["line = 1D truth (of mu N)"] = worst
    errors["line: no force across (of mu N)"] = across
    play2 = Bearing2D(w, mu0=0.045, play=(0.004, 0.0), transition="rigid-plastic")
    play1 = ind.Bearing(w, mu0=0.045, backlash=0.004, transition="rigid-plastic")
    a = simulate(play2, [Test2D(line_orbit(0.08, 2.0, 2, 0.0), 0.004, w)])[0]
    b = ind.simulate(play1, [ind.sine_test(0.08, 2.0, 2, 0.004, w)])[0]
    errors["line with play = 1D (of mu N)"] = float(np.max(np.abs(a["force"][:, 0]
                                                                  - b["force"]))) / (0.045 * w)


def checks(verbose: bool = True) -> dict[str, float]:
    """Run the self-checks of the module docstring; return each error."""
    errors: dict[str, float] = {}
    w, mu, amp, period = 1.0e6, 0.05, 0.1, 2.0
    # 1. circular orbit at constant speed, constant mu
    flat = Bearing2D(w, radius=math.inf, mu0=mu, transition="rigid-plastic")
    test = Test2D(circular(amp, period, 3), 0.002, w)
    out = simulate(flat, [test])[0]
    steady = (out["time"] >= period) & (out["time"] <= 4.0 * period + 1e-9)
    size = np.hypot(*out["force"][steady].T)
    errors["circle |F| = mu N"] = float(np.max(np.abs(size / (mu * w) - 1.0)))
    cycle = (out["time"] >= 2.0 * period - 1e-9) & (out["time"] <= 3.0 * period + 1e-9)
    edc = _work(out["force"][cycle], out["displacement"][cycle])
    errors["circle EDC = mu N 2 pi A"] = abs(edc / (mu * w * 2.0 * math.pi * amp) - 1.0)
    plastic = Bearing2D(w, radius=math.inf, mu0=mu, yield_displacement=5e-4)
    out = simulate(plastic, [test])[0]
    size = np.hypot(*out["force"][steady].T)
    errors["circle |F| elastic-plastic"] = float(np.max(np.abs(size / (mu * w) - 1.0)))
    # ... the smooth transition loading from rest along a line: z = tanh(u / u_y)
    smooth = Bearing2D(w, radius=math.inf, mu0=mu, transition="smooth", yield_displacement=1e-3)
    out = simulate(smooth, [Test2D(line_orbit(0.01, 4.0, 0.25, math.radians(60.0)), 0.001, w)])[0]
    along = np.hypot(*out["bearing"].T)
    errors["smooth loading = tanh"] = float(np.max(np.abs(np.hypot(*out["z"].T)
                                                          - np.tanh(along / 1e-3))))
    # 2. a line equals the 1D truth
    _against_1d(errors)
    # 3. heating: a slider standing still, a pulse, the field against monitor points
    heat = HeatField(0.15)
    q, steps = 1.0e5, np.linspace(0.0, 10.0, 101)
    for a, b in itertools.pairwise(steps):
        heat.add(float(a), float(b), np.zeros(2), q)
    exact = 2.0 * q * math.sqrt(DIFFUSIVITY * 10.0 / math.pi) / CONDUCTIVITY
    errors["standing slider = half-space"] = abs(heat.contact_rise(10.0, np.zeros(2)) / exact - 1)
    pulse = 2.0 * q * (math.sqrt(40.0) - math.sqrt(30.0)) * math.sqrt(DIFFUSIVITY / math.pi)
    errors["half-space pulse"] = abs(heat.contact_rise(40.0, np.zeros(2)) / (pulse / CONDUCTIVITY)
                                     - 1.0)
    hot = Bearing2D(4.24e6, heating=True)
    out = simulate(hot, [Test2D(figure_eight(0.2, 0.1, 3.0, 2), 0.01, 4.24e6)])
    field = HeatField(0.15)  # rebuild the field of the run to read it at points
    ub, mu_h, t = out[0]["bearing"], out[0]["mu"], out[0]["time"]
    sigma = 4.24e6 / hot.area
    for i in range(1, t.size):
        step = float(np.hypot(*(ub[i] - ub[i - 1])))
        field.add(t[i - 1], t[i], 0.25 * (ub[i] + ub[i - 1]),
                  mu_h[i - 1] * sigma * step / (t[i] - t[i - 1]) / 2.0)
    centre = 0.5 * ub[-1]
    g = np.arange(-0.15, 0.1501, 0.0025)
    grid = np.array([(x, y) for x in g for y in g if x * x + y * y <= 0.15**2]) + centre
    lens = field.contact_rise(t[-1], centre)
    errors["lens sum = monitor grid"] = abs(float(np.mean(field.field(t[-1], grid))) / lens - 1)
    errors["lens sum = the run's rise"] = abs(out[0]["temperature"][-1] - 20.0 - lens) / lens
    # 4. frictionless sphere
    sphere = Bearing2D(w, radius=1.5, mu0=1e-12, restoring="spherical")
    out = simulate(sphere, [Test2D(circular(0.4, 4.0, 1), 0.01, w)])[0]
    u = out["bearing"][len(out["time"]) // 2]
    expected = w * u / math.sqrt(1.5**2 - float(u @ u))
    errors["spherical restoring"] = float(np.max(np.abs(out["force"][len(out["time"]) // 2]
                                                        - expected))) / float(np.hypot(*expected))
    # 5. integer lag
    pend = Bearing2D(w, mu0=mu)
    test = Test2D(figure_eight(0.1, 0.05, 2.0, 1), 0.01, w)
    base = simulate(pend, [test])[0]["force"]
    late = simulate(pend, [test], Rig(lag=0.03))[0]["force"]
    errors["integer lag (of mu N)"] = float(np.max(np.abs(late[3:] - base[:-3]))) / (mu * w)
    # 6. the actuator's filter
    rig = Rig(actuator_frequency=5.0, actuator_damping=0.3)
    test = Test2D(figure_eight(0.1, 0.0, 1.0, 8), 0.002, w)
    out = simulate(Bearing2D(w), [test], rig)[0]
    last = out["time"] >= 6.0
    gain = (np.max(out["displacement"][last, 0]) - np.min(out["displacement"][last, 0])) / 0.2
    r = 1.0 / 5.0
    errors["actuator gain"] = abs(gain * math.sqrt((1 - r * r) ** 2 + (2 * 0.3 * r) ** 2) - 1)
    # 7. the converter
    x = np.random.default_rng(1).uniform(-1.0, 1.0, 10000)
    errors["quantisation (of a step)"] = float(np.max(np.abs(quantise(x, 2.0, 12) - x))) / (
        4.0 / 2**12)
    if verbose:
        for name, value in errors.items():
            print(f"{name:34s} {value:.2e}")
    return errors


# tolerances of the self-checks (what the regression test holds them to)
TOLERANCES = {
    "circle |F| = mu N": 1e-9,
    "circle EDC = mu N 2 pi A": 2e-3,
    "circle |F| elastic-plastic": 1e-9,
    "smooth loading = tanh": 1e-3,
    "line = 1D truth (of mu N)": 1e-6,
    "line: no force across (of mu N)": 1e-9,
    "line with play = 1D (of mu N)": 1e-6,
    "standing slider = half-space": 1e-9,
    "half-space pulse": 1e-9,
    "lens sum = monitor grid": 2e-2,
    "lens sum = the run's rise": 1e-9,
    "spherical restoring": 1e-6,
    "integer lag (of mu N)": 1e-9,
    "actuator gain": 5e-3,
    "quantisation (of a step)": 0.5 + 1e-9,
}
