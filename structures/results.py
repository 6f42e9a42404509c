"""The result of a building run as an ``xarray.Dataset``: one form for every program.

:func:`response_dataset` turns the histories of a run (ours, with either engine, or OpenSees's)
into the Dataset that :func:`structures.analysis.run` documents, with the energy balance and the
displacement-capacity check, so every producer gives the same variables, units and attributes.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from groundmotions.records import GroundMotion
from isolator.bearing import beyond_capacity_message
from isolator.friction import ConstantFriction, PTVFriction
from structures.energy import energy_balance
from structures.isolated_building import IsolatedShearBuilding

ISOLATOR_FIELDS = ("force", "friction_force", "mu", "temperature", "heat_flux")
"""Isolator histories a producer hands over: force and friction force of all bearings [N],
mu [-], contact temperature [degC] and heat flux [W/m^2] of one bearing."""


def friction_name(friction: ConstantFriction | PTVFriction) -> str:
    """``"constant"``, ``"precise"``, ``"simplified"`` or ``"ptv-no-heating"``."""
    if isinstance(friction, ConstantFriction):
        return "constant"
    if friction.heating is None:
        return "ptv-no-heating"
    return "precise" if type(friction.heating).__name__ == "MonitorLine" else "simplified"


def response_dataset(
    model: IsolatedShearBuilding,
    motion: GroundMotion,
    step: float,
    ground_acceleration: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray,
    absolute_acceleration: np.ndarray,
    isolator: dict[str, np.ndarray],
    *,
    integrator: str,
    success: bool,
    message: str,
    attrs: dict[str, Any],
    restoring: np.ndarray | None = None,
    failure: str = "",
    failed_at: float | None = None,
):
    """Assemble the Dataset of a run.

    Parameters
    ----------
    model : IsolatedShearBuilding
        The model that was run (building, bearing, number of bearings).
    motion : GroundMotion
        The record (its name and processing go to the attributes).
    step : float
        Analysis time step [s].
    ground_acceleration : ndarray, shape (nt,)
        [m/s^2] on the analysis steps kept.
    displacement, velocity, absolute_acceleration : ndarray, shape (nt, n + 1)
        Relative displacement [m] and velocity [m/s], absolute acceleration [m/s^2].
    isolator : dict of str to ndarray
        The ``ISOLATOR_FIELDS`` histories (force and friction force of all bearings), and
        optionally ``axial_load`` [N] of one bearing.
    integrator : str
        Description of the time integration.
    success, message : bool, str
        The producer's outcome; a response beyond the bearing's displacement capacity turns
        it into a failure with its own message, for every friction model alike.
    attrs : dict
        Producer-specific attributes (iterations, wall time, engine or program...).
    restoring : ndarray, shape (nt, n + 1), optional
        Total restoring force (storey springs + isolators) the producer recorded [N]; by
        default it is formed from the displacements and the isolator force.
    failure : str
        The kind of the producer's failure (``"convergence"``, ``"capacity"``,
        ``"timeout"``...); ``"error"`` when it failed without saying.
    failed_at : float, optional
        Time of the producer's failure [s].

    Notes
    -----
    The failure contract: the first committed step whose isolator displacement exceeds
    ``displacement_capacity`` ends the run there. Every history is cut after that step
    (the response beyond it is not physical) and the run is a failure, ``"capacity"``, at
    that step's time, whatever the producer said (its own failure can only come later).
    A failed run's Dataset has ``success = 0``, ``message`` (the reason, then up to when the
    histories go), ``failure``, ``failed_at`` [s] and ``peaks_up_to_failure = 1``; a run
    that finished has ``failure = ""`` and ``peaks_up_to_failure = 0``.
    """
    import xarray as xr

    building, bearing = model.building, model.bearing
    capacity = bearing.displacement_capacity
    beyond = np.flatnonzero(np.abs(displacement[:, 0]) > capacity)
    if beyond.size:  # the run ends at the first step beyond the capacity
        kept = int(beyond[0]) + 1
        displacement, velocity = displacement[:kept], velocity[:kept]
        ground_acceleration = ground_acceleration[:kept]
        absolute_acceleration = absolute_acceleration[:kept]
        isolator = {name: values[:kept] for name, values in isolator.items()}
        restoring = None if restoring is None else restoring[:kept]
        success, failure, failed_at = False, "capacity", step * (kept - 1)
        message = beyond_capacity_message(displacement[-1, 0], failed_at, capacity)
    if success:
        failure, failed_at = "", None
    else:
        failure = failure or "error"
        if failed_at is None:
            failed_at = step * (displacement.shape[0] - 1)
        message = (f"{message} The histories and peaks are those up to t = "
                   f"{step * (displacement.shape[0] - 1):.6g} s.")
    u, v, ag = displacement, velocity, ground_acceleration
    if restoring is None:
        restoring = u @ model.superstructure_stiffness.T
        restoring[:, 0] += isolator["force"]
    energies = energy_balance(u, v, ag, model.mass_matrix, model.damping_matrix,
                              model.influence, restoring, isolator["friction_force"])
    inertia = -absolute_acceleration * np.diag(model.mass_matrix)  # [N] per floor
    storey_shear = np.cumsum(inertia[:, :0:-1], axis=1)[:, ::-1]  # sum of the floors above

    def var(dims, data, units, long_name):
        return dims, np.asarray(data), {"units": units, "long_name": long_name}

    data = {
        "displacement": var(("time", "floor"), u, "m", "displacement relative to the ground"),
        "velocity": var(("time", "floor"), v, "m/s", "velocity relative to the ground"),
        "absolute_acceleration": var(("time", "floor"), absolute_acceleration, "m/s^2",
                                     "absolute acceleration"),
        "storey_drift": var(("time", "storey"), np.diff(u, axis=1), "m", "storey drift"),
        "storey_shear": var(("time", "storey"), storey_shear, "N",
                            "storey shear (inertia forces of the floors above)"),
        "isolator_displacement": var("time", u[:, 0], "m", "isolator displacement"),
        "isolator_force": var("time", isolator["force"], "N", "isolator force, all bearings"),
        "base_shear": var("time", isolator["force"], "N",
                          "base shear through the isolation level"),
        "friction_force": var("time", isolator["friction_force"], "N",
                              "friction part of the isolator force, all bearings"),
        "mu": var("time", isolator["mu"], "-", "friction coefficient"),
        "temperature": var("time", isolator["temperature"], "degC", "contact temperature"),
        "heat_flux": var("time", isolator["heat_flux"], "W/m^2",
                         "heat flux into each sliding surface"),
        "ground_acceleration": var("time", ag, "m/s^2", "ground acceleration"),
    }
    if "axial_load" in isolator:
        data["axial_load"] = var("time", isolator["axial_load"], "N",
                                 "normal force of one bearing")
    for name in ("input", "kinetic", "damping", "strain", "friction", "error"):
        data[f"energy_{name}"] = var("time", getattr(energies, name), "J", f"{name} energy")
    common: dict[str, Any] = {
        "record": motion.name,
        "record_processing": "; ".join(motion.processing),
        "dt": step,
        "integrator": integrator,
        "friction_model": friction_name(bearing.friction),
        "friction": repr(bearing.friction),
        "n_bearings": model.n_bearings,
        "axial_load_per_bearing": bearing.axial_load_at(0.0),
        "effective_radius": bearing.effective_radius,
        "slider_diameter": bearing.slider_diameter,
        "displacement_capacity": capacity,
        "isolated_period": model.isolated_period(),
        "fixed_base_periods": building.fixed_base_modes().periods.tolist(),
        "total_mass": building.total_mass,
        "success": int(success),
        "message": message,
        "failure": failure,
        "peaks_up_to_failure": int(not success),
        "steps": int(u.shape[0] - 1),
        "energy_balance_error": energies.relative_error,
    }
    n = building.n_storeys
    coords = {"time": ("time", step * np.arange(u.shape[0]), {"units": "s"}),
              "floor": np.arange(n + 1), "storey": np.arange(1, n + 1)}
    if failed_at is not None:
        common["failed_at"] = float(failed_at)
    return xr.Dataset(data, coords=coords, attrs=common | attrs)
