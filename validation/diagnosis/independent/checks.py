"""The independent truth's closed-form self-checks.

``python -m validation.diagnosis.independent`` runs :func:`checks`: a rigid-plastic flat
slider dissipates 4 mu W A per cycle (and 4 mu W (A - b/2) with a play b); a constant flux on
a half-space heats by 2 q sqrt(D t / pi) / k; the closed-form Bouc-Wen matches a sub-stepped
integration; a frictionless spherical surface gives W u / sqrt(R^2 - u^2); an integer lag is
a shift of the samples.

Like the rest of :mod:`validation.diagnosis.independent`, this module imports only numpy, the
standard library and its siblings.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from validation.diagnosis.independent.bearing import (
    CONDUCTIVITY,
    DIFFUSIVITY,
    Bearing,
    Plate,
    bouc_wen_step,
)
from validation.diagnosis.independent.rig import simulate, sine_test

__all__ = ["checks"]


# --- sanity checks -------------------------------------------------------------------------


def _loop_energy(force: np.ndarray, displacement: np.ndarray) -> float:
    """Energy dissipated along a closed path, the trapezoidal integral of F du [J]."""
    return float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(displacement)))


def checks(verbose: bool = True) -> dict[str, float]:
    """Run the sanity checks of the module docstring; return each relative error."""
    errors = {}
    w, mu, amp = 1.0e6, 0.05, 0.1
    # 1. rigid-plastic flat slider: EDC = 4 mu W A (second cycle)
    flat = Bearing(w, radius=math.inf, mu0=mu, transition="rigid-plastic")
    test = sine_test(amp, 2.0, 2, 0.001, w)
    out = simulate(flat, [test])[0]
    second = out["time"] >= 2.0 - 1e-9
    edc = _loop_energy(out["force"][second], out["displacement"][second])
    errors["edc rigid-plastic"] = abs(edc / (4 * mu * w * amp) - 1.0)
    # ... and with a play b: the bearing travels A - b/2 each way
    play = Bearing(w, radius=math.inf, mu0=mu, transition="rigid-plastic", backlash=0.004)
    out = simulate(play, [test])[0]
    edc = _loop_energy(out["force"][second], out["displacement"][second])
    errors["edc with play"] = abs(edc / (4 * mu * w * (amp - 0.002)) - 1.0)
    # 2. constant flux on a half-space: 2 q sqrt(D t / pi) / k
    plate = Plate(0.15)
    q, steps = 1.0e5, np.linspace(0.0, 10.0, 101)
    for a, b in itertools.pairwise(steps):
        plate.add(float(a), float(b), 0.0, q)
    exact = 2.0 * q * math.sqrt(DIFFUSIVITY * 10.0 / math.pi) / CONDUCTIVITY
    errors["half-space flux"] = abs(plate.rise(10.0, 0.0) / exact - 1.0)
    # after a rest: the solution of a pulse, 2 q (sqrt(t) - sqrt(t - 10)) sqrt(D / pi) / k
    later = 2.0 * q * (math.sqrt(40.0) - math.sqrt(30.0)) * math.sqrt(DIFFUSIVITY / math.pi)
    errors["half-space pulse"] = abs(plate.rise(40.0, 0.0) / (later / CONDUCTIVITY) - 1.0)
    # 3. Bouc-Wen closed form against 2000 explicit sub-steps per step
    u = 0.004 * np.sin(np.linspace(0.0, 4.0 * math.pi, 400))
    z_exact, z_sub, worst = 0.0, 0.0, 0.0
    for du in np.diff(u):
        z_exact = bouc_wen_step(z_exact, float(du), 1.0e-3, 1.2, 0.8)
        for _ in range(2000):
            h = du / 2000.0
            cap = 1.2 if (z_sub > 0.0 or (z_sub == 0.0 and h > 0.0)) else 0.8
            z = z_sub / cap
            z_sub += cap * (1.0 - z * z * math.copysign(1.0, h * z)) * h / (cap * 1.0e-3)
        worst = max(worst, abs(z_exact - z_sub))
    errors["bouc-wen sub-steps"] = worst
    # 4. a frictionless spherical surface
    sphere = Bearing(w, radius=1.5, mu0=1e-12, restoring="spherical")
    out = simulate(sphere, [sine_test(0.4, 4.0, 0.25, 0.01, w)])[0]
    u_end = out["bearing"][-1]
    errors["spherical restoring"] = abs(out["force"][-1] / (w * u_end / math.sqrt(1.5**2 - u_end
                                                                                   ** 2)) - 1)
    # 5. an integer lag is a shift of the samples
    pendulum = Bearing(w, mu0=mu)
    test = sine_test(0.1, 2.0, 1, 0.01, w)
    base = simulate(pendulum, [test])[0]["force"]
    late = simulate(pendulum, [test], lag=0.03)[0]["force"]
    errors["integer lag"] = float(np.max(np.abs(late[3:] - base[:-3]))) / (mu * w)
    if verbose:
        for name, value in errors.items():
            print(f"{name:22s} {value:.2e}")
    return errors

