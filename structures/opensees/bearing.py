"""One bearing in OpenSees under an imposed history, along one axis or in the plane: the twin
of :func:`isolator.testrig.run_test`. Transient (Newmark 1/2, 1/4), each driven DOF following
``imposedMotion`` with displacement, velocity and acceleration ``Path`` series, so the element
sees the imposed velocity exactly; kInit from the reference mu (mu_fast, MuRef). openseespy
keeps one global model: every call wipes it before and after.
"""

from __future__ import annotations

import time as _time

import numpy as np

from dcfpb.common.errors import InputError, RunFailure
from dcfpb.common.validation import check_choice
from isolator.bearing import DCFPBearing
from isolator.orbits import Orbit
from isolator.testrig import BearingTestResult, imposed_history
from structures.opensees.elements import (
    ELEMENTS,
    FPBEARINGPTV_AMBIENT,
    BearingElements,
    add_bearing,
    constant_axial_load,
    element_kind,
    fpbearingptv_equivalent,
    warn_if_steps_vary,
)
from structures.opensees.runtime import import_opensees

__all__ = ["build_test", "fpbearingptv_equivalent", "opensees_orbit", "run_opensees_test"]

_BOTTOM, _TOP = 1, 2  # node tags
_FIRST_TAG = 10  # first tag of materials, friction models, elements, series, patterns


def run_opensees_test(
    bearing: DCFPBearing,
    time: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray | None = None,
    *,
    element: str | None = None,
    name: str = "imposed history",
) -> BearingTestResult:
    """Drive ``bearing`` built as an OpenSees element through an imposed history ``name``.

    Parameters
    ----------
    bearing : DCFPBearing
        With a constant axial load [N] and a friction model the element represents.
    time : array_like, shape (n,)
        Strictly increasing sample times [s] (shifted to start at 0).
    displacement, velocity : array_like, shape (n,) or (n, 2)
        Imposed displacement [m] along x, or (x, y), starting at 0, and velocity [m/s] (by
        default ``numpy.gradient`` of the displacement).
    element : {"coulomb", "velocity", "ptv"}, optional
        By default the bearing's (:func:`~structures.opensees.elements.element_kind`).

    Returns a :class:`~isolator.testrig.BearingTestResult` named after the element and ``name``:
    one value (or (x, y) row) per sample, sample 0 the initial state (zero force, the axial load,
    mu NaN); ``mu`` the friction model's COF (``MuAdjusted`` for FPBearingPTV), ``axial_load`` the
    element's normal force [N], ``friction_force`` the force less the element's restoring force
    [N], ``z`` that over mu N, ``temperature`` [degC] and ``heat_flux`` FPBearingPTV's (else NaN).
    Raises ImportError without openseespy, ValueError or TypeError for a bearing or history the
    element cannot represent, RuntimeError if an OpenSees step fails; warns (UserWarning) for
    ``"ptv"`` with a non-uniform time step.
    """
    owner = "run_opensees_test"
    element = element_kind(bearing) if element is None else check_choice(
        element, "element", owner, ELEMENTS)
    t, u, v = imposed_history(time, displacement, velocity, owner)
    if np.any(u[0] != 0.0):
        start = "0" if u.ndim == 1 else "(0, 0)"
        raise InputError(f"The 'displacement' parameter of {owner} must start at {start} (the "
                         f"element starts at rest). Got {u[0]!r} instead.")
    weight = constant_axial_load(bearing, owner)
    warn_if_steps_vary(element, t, owner)
    axes = u.ndim  # driven horizontal DOFs: X, or X and Y
    ops = import_opensees()
    start = _time.perf_counter()
    ops.wipe()
    try:
        elements = build_test(ops, bearing, weight, t, u, v, element, owner)
        out = _record(ops, t, elements.read, element, owner)
    finally:
        ops.wipe()
    out["displacement"][0], out["velocity"][0] = 0.0, 0.0
    out["velocity"][0, :axes] = v[0]
    out["axial_load"][0] = weight
    if element == "ptv":
        out["temperature"][0], out["heat_flux"][0] = FPBEARINGPTV_AMBIENT, 0.0
    else:  # the element has no temperature
        out["temperature"][:] = np.nan
    yield_force = (out["mu"] * out["axial_load"])[1:, None]
    out["z"][1:] = np.divide(out["friction_force"][1:], yield_force,
                             out=np.zeros_like(out["friction_force"][1:]),
                             where=yield_force > 0.0)
    if axes == 1:
        out = {key: values[:, 0] if values.ndim == 2 else values for key, values in out.items()}
    label = elements.name + (" 3D" if axes == 2 and element != "ptv" else "")
    label += f" {elements.friction}" if elements.friction else ""
    return BearingTestResult(t, **out, bearing=bearing, name=f"OpenSees {label}: {name}",
                             wall_time=_time.perf_counter() - start)


def build_test(ops, bearing: DCFPBearing, weight: float, time: np.ndarray,
               displacement: np.ndarray, velocity: np.ndarray, element: str,
               owner: str = "build_test") -> BearingElements:
    """Build the test of :func:`run_opensees_test` in the (wiped) openseespy domain, up to
    the transient analysis: the element under ``weight`` [N], its top node driven through the
    (checked) history (times [s] from 0; displacement [m] and velocity [m/s] of shape (n,) or
    (n, 2)). Returns the element's reader."""
    axes = displacement.ndim
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(_BOTTOM, 0.0, 0.0, 0.0)
    ops.node(_TOP, 0.0, 0.0, 0.0)  # zero length: the orientation vectors hold
    ops.fix(_BOTTOM, 1, 1, 1, 1, 1, 1)
    ops.fix(_TOP, 0, 0 if axes == 2 else 1, 0, 1, 1, 1)
    tags = iter(range(_FIRST_TAG, 10**6))
    elements = add_bearing(ops, lambda: next(tags), _BOTTOM, _TOP, bearing, weight,
                           kind=element, kinit="reference", owner=owner)
    series = next(tags)
    ops.timeSeries("Constant", series)
    ops.pattern("Plain", next(tags), series)
    ops.load(_TOP, 0.0, 0.0, -weight, 0.0, 0.0, 0.0)
    _impose(ops, tags, time - time[0], displacement.reshape(time.size, axes),
            velocity.reshape(time.size, axes))
    for command, *values in (("constraints", "Transformation"), ("numberer", "Plain"),
                             ("system", "FullGeneral"), ("test", "NormDispIncr", 1.0e-12, 25),
                             ("algorithm", "Newton"), ("integrator", "Newmark", 0.5, 0.25),
                             ("analysis", "Transient")):
        getattr(ops, command)(*values)
    return elements


def opensees_orbit(bearing: DCFPBearing, orbit: Orbit, *,
                   element: str | None = None) -> BearingTestResult:
    """:func:`run_opensees_test` on an :class:`~isolator.orbits.Orbit` (its exact velocity)."""
    return run_opensees_test(bearing, orbit.time, orbit.displacement, orbit.velocity,
                             element=element, name=orbit.name)


def _impose(ops, tags, time: np.ndarray, displacement: np.ndarray,
            velocity: np.ndarray) -> None:
    """Drive X (and Y) of the top node through the history (exact velocity, module docstring)."""
    acceleration = np.gradient(velocity, time, axis=0)  # only completes the ground motion
    ops.pattern("MultipleSupport", next(tags))
    for axis in range(displacement.shape[1]):
        series = []
        for values in (displacement, velocity, acceleration):
            series.append(next(tags))
            ops.timeSeries("Path", series[-1], "-time", *time.tolist(), "-values",
                           *values[:, axis].tolist(), "-useLast")  # summed steps may pass the end
        ops.groundMotion(axis + 1, "Plain", "-disp", series[0], "-vel", series[1],
                         "-accel", series[2])
        ops.imposedMotion(_TOP, axis + 1, axis + 1)


def _record(ops, t: np.ndarray, read, element: str, owner: str) -> dict[str, np.ndarray]:
    """Analyse one step per interval of ``t`` [s] and record the element after each."""
    out = {key: np.full((t.size, 2), np.nan) for key in ("displacement", "velocity", "force",
                                                         "friction_force", "z")}
    out |= {key: np.full(t.size, np.nan) for key in ("mu", "temperature", "heat_flux",
                                                     "axial_load")}
    for key in ("force", "friction_force", "z"):
        out[key][0] = 0.0
    for k, dt in enumerate(np.diff(t), start=1):
        if ops.analyze(1, float(dt)) != 0:
            raise RunFailure(f"OpenSees failed at step {k} (t = {t[k] - t[0]:g} s) of "
                             f"{owner} with element {element!r}.")
        force, friction_force, normal, mu, temperature, heat_flux = read(ops)
        out["displacement"][k] = ops.nodeDisp(_TOP, 1), ops.nodeDisp(_TOP, 2)
        out["velocity"][k] = ops.nodeVel(_TOP, 1), ops.nodeVel(_TOP, 2)
        out["force"][k], out["friction_force"][k], out["axial_load"][k] = (force, friction_force,
                                                                           normal)
        out["mu"][k], out["temperature"][k], out["heat_flux"][k] = mu, temperature, heat_flux
    return out
