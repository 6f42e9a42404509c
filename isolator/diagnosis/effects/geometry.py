"""``geometry``: the spherical sliding surface, exactly.

The baseline's force is N u / R_eff + mu N z with N the axial load. On a spherical surface
the restoring force is N u / sqrt(R_eff^2 - u^2), and the normal force on the surface carries
the horizontal force's share, N_eff = N + F u / R_eff (OpenSees singleFPBearing), so that

    F = (N u / sqrt(R^2 - u^2) + mu N z) / (1 - mu z u / R).

The effect scales both corrections by g (1: an exact spherical surface). Untestable on a flat
slider or when the displacement is a tiny fraction of R_eff.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.diagnosis.effects.base import Context, Effect, Parameter, linear

MIN_DISPLACEMENT_RATIO = 0.02  # u / R_eff below this: the geometry is invisible


def _transform(theta, f, c, pendulum, friction):
    g = theta[0]
    radius = c.effective_radius
    ratio = np.clip(f.displacement / radius, -0.95, 0.95)
    spherical = pendulum * (1.0 / np.sqrt(1.0 - ratio**2) - 1.0)
    coupling = (friction / f.axial_force) * ratio
    return (pendulum + g * spherical + friction) / (1.0 - g * coupling)


def _requires(c: Context) -> str | None:
    if math.isinf(c.effective_radius):
        return "a flat slider (R_eff = inf) has no spherical geometry"
    if c.reference_displacement < MIN_DISPLACEMENT_RATIO * c.effective_radius:
        return (f"the displacement stays below {100 * MIN_DISPLACEMENT_RATIO:.0f} % of R_eff, "
                "where the geometry hardly changes the force")
    return None


def _reading(theta, stderr, c):
    return {"geometry_factor": (*linear(theta, stderr, 0), "-")}


EFFECT = Effect(
    "geometry", "the spherical surface: exact restoring law and normal-force coupling",
    "a spherical sliding surface: the restoring force is N u / sqrt(R^2 - u^2) and the normal "
    "force carries F u / R, which the linear pendulum N u / R with N = W leaves out",
    (Parameter("g", 1.0, 0.0, 3.0),), "force", transform=_transform, requires=_requires,
    reading=_reading, order=85)
