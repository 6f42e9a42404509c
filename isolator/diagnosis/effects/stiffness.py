"""``stiffness``: a restoring stiffness other than N / R_eff.

e = k N u / u_ref, u_ref the 99th percentile of |u|: reported as the stiffness per unit
axial load k / u_ref = 1 / R_true - 1 / R_eff and as the apparent effective radius.
"""

from __future__ import annotations

from isolator.diagnosis.effects.base import Effect, Parameter, linear


def _extra(theta, f, c):
    return theta[0] * f.axial_force * f.displacement / c.reference_displacement


def _reading(theta, stderr, c):
    k, sk = linear(theta, stderr, 0)
    per_load = k / c.reference_displacement
    out = {"stiffness_per_axial_load": (per_load, sk / c.reference_displacement, "1/m")}
    inverse = 1.0 / c.effective_radius + per_load
    if inverse > 0.0:
        out["apparent_effective_radius"] = (1.0 / inverse,
                                            sk / c.reference_displacement / inverse**2, "m")
    return out


EFFECT = Effect(
    "stiffness", "a restoring stiffness other than N / R_eff",
    "the pendulum's restoring stiffness is not N / R_eff: another radius, or a spring in "
    "the load path",
    (Parameter("k", 0.0, -1.0, 1.0),), "force", extra=_extra, reading=_reading, order=60)
