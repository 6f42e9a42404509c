"""What our bearing is in OpenSees 3D: singleFPBearing's and FPBearingPTV's restoring forces
in the plane and the normal force of singleFPBearing, for our bidirectional element.

The conventions read in ``SingleFPSimple3d.cpp`` and ``FPBearingPTV.cpp`` are in the docstring
of :mod:`structures.opensees.bearing3d`, which drives the elements these functions describe.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.validation import check_array
from isolator.bearing import AxialLoadHistory, DCFPBearing
from isolator.testrig import run_test
from structures.opensees.equivalents import constant_axial_load

__all__ = [
    "check_orbit",
    "fpbearingptv_restoring",
    "singlefp3d_normal_force",
    "singlefp3d_restoring",
]


def singlefp3d_restoring(normal: ArrayLike, displacement: ArrayLike,
                         radius: float) -> np.ndarray:
    """singleFPBearing's (3D) restoring force ``N (u_X / R_x, u_Y / R_y)`` [N], shape (n, 2).

    ``R_x = sqrt(R^2 - u_Y^2)``, ``R_y = sqrt(R^2 - u_X^2)`` (SingleFPSimple3d.cpp); zero for
    an infinite radius.

    Parameters
    ----------
    normal : array_like, shape (n,)
        Normal force [N].
    displacement : array_like, shape (n, 2)
        Displacement (u_X, u_Y) [m].
    radius : float
        Effective radius R [m].
    """
    n, u = np.asarray(normal, dtype=float), np.asarray(displacement, dtype=float)
    if math.isinf(radius):
        return np.zeros_like(u)
    crossed = np.sqrt(radius**2 - u[:, ::-1] ** 2)
    return n[:, None] * u / crossed


def fpbearingptv_restoring(normal: ArrayLike, displacement: ArrayLike,
                           radius: float) -> np.ndarray:
    """FPBearingPTV's restoring force ``N u_i / sqrt(R^2 - u_i^2)`` on each axis [N], (n, 2).

    Parameters as :func:`singlefp3d_restoring` (FPBearingPTV.cpp: ``R_y = sqrt(R^2 - ub1^2)``).
    """
    n, u = np.asarray(normal, dtype=float), np.asarray(displacement, dtype=float)
    return n[:, None] * u / np.sqrt(radius**2 - u**2)


def singlefp3d_normal_force(
    bearing: DCFPBearing,
    time: ArrayLike,
    displacement: ArrayLike,
    velocity: ArrayLike | None = None,
    *,
    tolerance: float = 1e-12,
    max_iterations: int = 20,
) -> AxialLoadHistory:
    """The normal force singleFPBearing (3D) uses, ``N = W + F_X u_X / R_x + F_Y u_Y / R_y``,
    from our bidirectional element.

    Fixed-point iteration on :func:`~isolator.testrig.run_test`: N_0 = W,
    N_(k+1) = W + F_k . (u_X / R_x, u_Y / R_y) with the radii of
    :func:`singlefp3d_restoring`; the map contracts by about |u| / R (0.4 % for |u| = 0.2 m,
    R = 4.5 m). Given as the axial load of our bearing it makes our element see what
    singleFPBearing sees. The history's times are relative to its first (as the test rig's).

    Parameters
    ----------
    bearing : DCFPBearing
        A bearing with a constant axial load W [N] and a finite radius.
    time, displacement, velocity
        As :func:`run_opensees_orbit`.
    tolerance : float
        Largest change of N between iterations, relative to W [-].
    max_iterations : int
        Iterations allowed.

    Raises
    ------
    ValueError
        If the axial load is not constant, or the iteration does not converge.
    """
    owner = "singlefp3d_normal_force"
    weight = constant_axial_load(bearing, owner)
    t, u, v = check_orbit(time, displacement, velocity, owner)
    lever = singlefp3d_restoring(np.ones(t.size), u, bearing.effective_radius)
    relative = t - t[0]
    normal = np.full(t.size, weight)
    change = math.inf
    for _ in range(max_iterations):
        trial = replace(bearing, axial_load=AxialLoadHistory(relative, normal))
        force = run_test(trial, t, u, v).force
        updated = weight + np.sum(force * lever, axis=1)
        change = float(np.max(np.abs(updated - normal))) / weight
        normal = updated
        if change <= tolerance:
            return AxialLoadHistory(relative, normal)
    raise ValueError(f"{owner} did not converge in {max_iterations} iterations "
                     f"(last relative change {change:.3g}).")


def check_orbit(time: ArrayLike, displacement: ArrayLike, velocity: ArrayLike | None,
                owner: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Checked ``(t [s], u [m], v [m/s])`` of an orbit starting at the centre; by default
    v is ``numpy.gradient`` of u. Errors name ``owner``."""
    t = check_array(time, "time", owner, min_length=2)
    if np.any(np.diff(t) <= 0.0):
        raise ValueError(f"The 'time' parameter of {owner} must be strictly increasing.")
    u = check_array(displacement, "displacement", owner, ndim=2, min_length=2)
    if u.shape != (t.size, 2):
        raise ValueError(f"The 'displacement' parameter of {owner} must have the shape "
                         f"({t.size}, 2). Got {u.shape} instead.")
    if np.any(u[0] != 0.0):
        raise ValueError(f"The 'displacement' parameter of {owner} must start at (0, 0) (the "
                         f"element starts at rest). Got {tuple(u[0])!r} instead.")
    if velocity is None:
        return t, u, np.gradient(u, t, axis=0)
    v = check_array(velocity, "velocity", owner, ndim=2, min_length=2)
    if v.shape != u.shape:
        raise ValueError(f"The 'velocity' parameter of {owner} must have the shape {u.shape}. "
                         f"Got {v.shape} instead.")
    return t, u, v
