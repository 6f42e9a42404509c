"""The result of a building run as an ``xarray.Dataset``, one layout for every engine and
program: :func:`response_dataset` turns the histories of a run (either engine, or OpenSees)
into it, with the energy balance and the bearings' displacement-capacity check.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from dcfpb.common.files import atomic_output
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from isolator.bearing import beyond_capacity_message
from structures.energy import energy_balance
from structures.integrators import IntegrationResult
from structures.isolated_building import IsolatedShearBuilding

__all__ = ["BEARING_RECORD", "EngineHistory", "UpliftWarning", "response_dataset",
           "temperature_fields", "uplift_record", "write_netcdf"]

BEARING_RECORD: dict[str, int] = {
    "displacement": 2, "force": 2, "friction_force": 2, "mu": 0, "temperature": 0,
    "heat_flux": 0, "axial_load": 0,
}
"""What a producer records of one bearing at each position at each committed step, with the
length of its (x, y) axis (0: a scalar): displacement [m], force and friction force [N], mu [-],
contact temperature [degC], heat flux into each sliding surface [W/m^2], axial load [N]."""

_ENERGIES = ("input", "kinetic", "damping", "strain", "friction", "error")


class UpliftWarning(RuntimeWarning):
    """A run that finished with bearings lifted off for some steps (zero or negative axial
    load: no contact, no friction, no restoring force there); the run's peaks hold how often,
    from when and for how long (:func:`uplift_record`)."""


def uplift_record(axial_load: np.ndarray, step: float) -> dict[str, list]:
    """How the bearings at each position lifted off in a run: at every step where the axial
    load is zero or negative the bearing has no contact (:class:`isolator.bearing.BearingElement`:
    no force, no heat, the plates cool).

    Parameters
    ----------
    axial_load : ndarray, shape (nt, n_positions)
        The axial load of one bearing of each position at each committed step [N].
    step : float
        The analysis time step [s].

    Returns
    -------
    dict
        ``uplift_steps`` (int per position: the steps lifted), ``uplift_first_time`` (float per
        position: the time of the first one [s], -1 for a bearing never lifted, so that the
        attributes compare equal and write to netCDF as they are) and
        ``uplift_longest`` (float per position: the longest lift-off, its consecutive steps
        times ``step`` [s]), each a list over the positions.
    """
    lifted = np.asarray(axial_load, dtype=float) <= 0.0
    if lifted.ndim == 1:
        lifted = lifted[:, None]
    steps = lifted.sum(axis=0)
    first = np.where(steps > 0, step * np.argmax(lifted, axis=0), -1.0)
    longest = np.zeros(lifted.shape[1])
    for b in np.flatnonzero(steps):
        edges = np.diff(np.concatenate(([0], lifted[:, b].astype(np.int8), [0])))
        longest[b] = step * float(np.max(np.flatnonzero(edges < 0) - np.flatnonzero(edges > 0)))
    return {"uplift_steps": [int(n) for n in steps],
            "uplift_first_time": [float(t) for t in first],
            "uplift_longest": [float(t) for t in longest]}


class EngineHistory(NamedTuple):
    """What an engine hands to :func:`history_dataset`: the integration ``result``, the
    ``bearings`` record (:data:`BEARING_RECORD` at every committed step), the total ``restoring``
    force of storeys and bearings, shape (nt, n_dof) [N, N m], the ``wall_time`` of the
    integration and the ``compile_time`` before it (0.0 if compiled already) [s], the
    ``engine`` (``"reference"`` or ``"compiled"``) and the monitor points' ``plate`` temperature
    field at the end (:func:`temperature_fields`; None without monitor points)."""

    result: IntegrationResult
    bearings: dict[str, np.ndarray]
    restoring: np.ndarray
    wall_time: float
    engine: str
    compile_time: float = 0.0
    plate: tuple[np.ndarray, np.ndarray] | None = None


def resultant(values: np.ndarray) -> np.ndarray:
    """The length of the vectors along the last axis, of one or two directions (for one, the
    absolute value) [the values' unit]."""
    return np.abs(values[..., 0]) if values.shape[-1] == 1 else np.hypot(values[..., 0],
                                                                          values[..., 1])


def temperature_fields(model: IsolatedShearBuilding) -> tuple[np.ndarray, np.ndarray] | None:
    """Each bearing's monitor-point temperature field after the last commit (None for the models
    without): positions (n_b, m, 2) [m] and temperatures (n_b, m) [degC], NaN-padded."""
    fields = [element.friction_state.temperature_field() for element in model.elements]
    if any(field is None for field in fields):
        return None
    size = max(field[1].size for field in fields)
    positions = np.full((len(fields), size, 2), np.nan)
    temperatures = np.full((len(fields), size), np.nan)
    for b, (points, values) in enumerate(fields):
        positions[b, :values.size], temperatures[b, :values.size] = points, values
    return positions, temperatures


def _by_position(positions: np.ndarray,
                 temperatures: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each bearing's monitor points ordered by x, then y (NaN padding last), engine-independent."""
    order = np.lexsort((positions[..., 1], positions[..., 0]), axis=-1)
    return (np.take_along_axis(positions, order[..., None], axis=1),
            np.take_along_axis(temperatures, order, axis=1))


def _capacity(reach: np.ndarray, capacity: float, step: float) -> tuple[int, str]:
    """The steps kept and the capacity failure's message ("" if none), from ``reach`` [m], the
    largest bearing displacement at each step."""
    beyond = np.flatnonzero(reach > capacity)
    if not beyond.size:
        return reach.size, ""
    kept = int(beyond[0]) + 1
    return kept, beyond_capacity_message(reach[kept - 1], step * (kept - 1), capacity)


def _motion_attrs(motion: GroundMotion | GroundMotionPair) -> dict[str, Any]:
    if isinstance(motion, GroundMotionPair):
        return {"record": motion.name, "record_x": motion.x.name, "record_y": motion.y.name,
                "record_processing": "; ".join(motion.x.processing)}
    return {"record": motion.name, "record_processing": "; ".join(motion.processing)}


def response_dataset(
    model: IsolatedShearBuilding,
    motion: GroundMotion | GroundMotionPair,
    step: float,
    ground_acceleration: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray,
    absolute_acceleration: np.ndarray,
    bearings: dict[str, np.ndarray],
    *,
    integrator: str,
    success: bool,
    message: str,
    attrs: dict[str, Any],
    restoring: np.ndarray | None = None,
    failure: str = "",
    failed_at: float | None = None,
    plate: tuple[np.ndarray, np.ndarray] | None = None,
):
    """Assemble the Dataset of a run.

    Parameters
    ----------
    model : IsolatedShearBuilding
        The model that was run.
    motion : GroundMotion or GroundMotionPair
        The record or records (names and processing go to the attributes).
    step : float
        Analysis time step [s].
    ground_acceleration : ndarray, shape (nt,) or (nt, 2)
        The horizontal ground acceleration on the analysis steps kept [m/s^2].
    displacement, velocity, absolute_acceleration : ndarray, shape (nt, n_dof)
        Relative displacement [m, rad] and velocity, absolute acceleration, on the model's
        degrees of freedom.
    bearings : dict of str to ndarray
        One bearing at each position at each step, :data:`BEARING_RECORD` (time, position,
        then the (x, y) axis; y = 0 in one direction).
    integrator : str
        Description of the time integration.
    success, message, failure, failed_at : bool, str, str, float or None
        The producer's outcome, the kind of its failure (``"convergence"``, ``"timeout"``...;
        ``"error"`` when it did not say) and its time [s]; see Notes for the capacity check.
    attrs : dict
        Producer-specific attributes (iterations, wall time, engine or program...).
    restoring : ndarray, shape (nt, n_dof), optional
        Total restoring force (storeys and bearings) [N, N m]; by default formed from the
        displacements and the bearing forces.
    plate : tuple of ndarray, optional
        The monitor points' temperature field at the end (:func:`temperature_fields`).

    Returns
    -------
    xarray.Dataset
        Dimensions ``time``, ``floor`` (0 = base slab), ``storey``, ``direction`` (``x``, or
        ``x`` and ``y`` in plan) and ``bearing`` (one per bearing position; coordinates
        ``bearing_x``, ``bearing_y`` [m] and ``bearing_count``, the bearings standing there).
        Level histories at the reference point (the centre of stiffness in plan):
        ``displacement``, ``velocity``, ``absolute_acceleration`` (time, floor, direction);
        in plan also ``rotation``, ``angular_velocity``, ``angular_acceleration`` (time,
        floor) and ``storey_twist`` (time, storey); ``storey_drift`` and ``storey_shear``
        (time, storey, direction); one bearing of each position: ``bearing_displacement``,
        ``bearing_force``, ``bearing_friction_force`` (time, bearing, direction),
        ``axial_load`` (0 on uplift), ``mu``, ``temperature``, ``heat_flux`` (time, bearing);
        ``base_shear`` (time, direction), through the isolation level, all bearings;
        ``ground_acceleration`` (time, direction) and, with a vertical,
        ``vertical_ground_acceleration`` (time); the energies ``energy_input``,
        ``energy_kinetic``, ``energy_damping``, ``energy_strain``, ``energy_friction``,
        ``energy_error`` (time) [J]; with monitor points, ``plate_temperature`` (bearing,
        plate_point) [degC] at ``plate_point_x``, ``plate_point_y`` [m]. SI units throughout.
        The attributes ``uplift_steps``, ``uplift_first_time`` [s] and ``uplift_longest`` [s]
        hold, per bearing position, how the bearings lifted off (:func:`uplift_record`).

    Notes
    -----
    The first committed step at which a bearing's resultant displacement exceeds
    ``displacement_capacity`` ends the run there, for every producer and friction model: every
    history is cut after it and the run fails, ``"capacity"``, at its time (a producer's own
    failure can only come later). A failed run has ``success = 0``, ``message`` (the reason,
    then up to when the histories go), ``failure`` (``"capacity"``, ``"convergence"``,
    ``"timeout"``, ``"model"``, ``"error"``), ``failed_at`` [s] and ``peaks_up_to_failure = 1``;
    a run that finished has ``failure = ""`` and ``peaks_up_to_failure = 0``.
    """
    import xarray as xr

    building, bearing = model.building, model.bearing
    directions = building.directions
    components, dofs = len(directions), model.level_dofs
    reach = resultant(bearings["displacement"])
    kept, beyond = _capacity(reach.max(axis=1), bearing.displacement_capacity, step)
    if beyond:
        success, message, failure, failed_at = False, beyond, "capacity", step * (kept - 1)
    if success:
        failure, failed_at = "", None
    else:
        failure = failure or "error"
        failed_at = step * (kept - 1) if failed_at is None else failed_at
        message = (f"{message} The histories and peaks are those up to t = "
                   f"{step * (kept - 1):.6g} s.")
    u, v, a_abs = displacement[:kept], velocity[:kept], absolute_acceleration[:kept]
    ground = np.reshape(ground_acceleration[:kept], (kept, components))
    records = {name: values[:kept] for name, values in bearings.items()}
    count = model.multiplicity.astype(float)
    group_force = records["force"] * count[:, None]  # all the bearings of each position
    if restoring is None:
        restoring = u @ model.superstructure_stiffness.T
        restoring[:, :dofs] += np.einsum("tbi,bij->tj", group_force,
                                         np.asarray(model.transformations)[..., :dofs])
    else:
        restoring = restoring[:kept]
    influence = np.reshape(model.influence, (u.shape[1], components))
    energies = energy_balance(u, v, ground, model.mass_matrix, model.damping_matrix, influence,
                              restoring, records["displacement"],
                              records["friction_force"] * count[:, None])
    n, nt = building.n_storeys, u.shape[0]
    levels = (nt, n + 1, dofs)
    inertia = -(a_abs @ model.mass_matrix.T).reshape(levels)  # [N, N m] per level
    shear = np.cumsum(inertia[:, :0:-1, :components], axis=1)[:, ::-1]  # the floors above
    drift = np.diff(u.reshape(levels), axis=1)

    def var(dims, data, units, long_name):
        return dims, np.asarray(data), {"units": units, "long_name": long_name}

    where = " (centre of stiffness)" if dofs == 3 else ""
    tfd, tf, tbd, tb = ("time", "floor", "direction"), ("time", "floor"), \
        ("time", "bearing", "direction"), ("time", "bearing")
    data = {
        "displacement": var(tfd, u.reshape(levels)[..., :components], "m",
                            f"displacement relative to the ground{where}"),
        "velocity": var(tfd, v.reshape(levels)[..., :components], "m/s",
                        f"velocity relative to the ground{where}"),
        "absolute_acceleration": var(tfd, a_abs.reshape(levels)[..., :components], "m/s^2",
                                     f"absolute acceleration{where}"),
        "storey_drift": var(("time", "storey", "direction"), drift[..., :components], "m",
                            f"storey drift{where}"),
        "storey_shear": var(("time", "storey", "direction"), shear, "N",
                            "storey shear (inertia forces of the floors above)"),
        "bearing_displacement": var(tbd, records["displacement"][..., :components], "m",
                                    "bearing displacement"),
        "bearing_force": var(tbd, records["force"][..., :components], "N",
                             "force of one bearing"),
        "bearing_friction_force": var(tbd, records["friction_force"][..., :components], "N",
                                      "friction part of the force of one bearing"),
        "axial_load": var(tb, records["axial_load"], "N", "normal force of one bearing (0: "
                          "uplift)"),
        "mu": var(tb, records["mu"], "-", "friction coefficient"),
        "temperature": var(tb, records["temperature"], "degC", "contact temperature"),
        "heat_flux": var(tb, records["heat_flux"], "W/m^2", "heat flux into each sliding "
                         "surface"),
        "base_shear": var(("time", "direction"), group_force.sum(axis=1)[:, :components], "N",
                          "base shear through the isolation level"),
        "ground_acceleration": var(("time", "direction"), ground, "m/s^2",
                                   "ground acceleration"),
    }
    if dofs == 3:
        data |= {
            "rotation": var(tf, u.reshape(levels)[..., 2], "rad", "rotation about the vertical"),
            "angular_velocity": var(tf, v.reshape(levels)[..., 2], "rad/s", "angular velocity"),
            "angular_acceleration": var(tf, a_abs.reshape(levels)[..., 2], "rad/s^2",
                                        "angular acceleration"),
            "storey_twist": var(("time", "storey"), drift[..., 2], "rad", "storey twist"),
        }
    time = step * np.arange(nt)
    if model.vertical is not None:
        data["vertical_ground_acceleration"] = var(
            "time", model.vertical_accelerations(time), "m/s^2",
            "vertical ground acceleration (positive up)")
    if plate is not None:
        plate = _by_position(*plate)
        data["plate_temperature"] = var(("bearing", "plate_point"), plate[1], "degC",
                                        "temperature of the plate's monitor points at the end")
    for name in _ENERGIES:
        data[f"energy_{name}"] = var("time", getattr(energies, name), "J", f"{name} energy")
    xy = model.positions
    coords = {"time": ("time", time, {"units": "s"}), "floor": np.arange(n + 1),
              "storey": np.arange(1, n + 1), "direction": list(directions),
              "bearing": np.arange(xy.shape[0]),
              "bearing_x": ("bearing", xy[:, 0], {"units": "m"}),
              "bearing_y": ("bearing", xy[:, 1], {"units": "m"}),
              "bearing_count": ("bearing", model.multiplicity)}
    if plate is not None:
        for axis, name in enumerate(("plate_point_x", "plate_point_y")):
            coords[name] = (("bearing", "plate_point"), plate[0][..., axis], {"units": "m"})
    common: dict[str, Any] = {
        **_motion_attrs(motion), "dt": step, "integrator": integrator,
        "friction_model": bearing.friction.name, "friction": repr(bearing.friction),
        "n_bearings": model.n_bearings,
        "axial_load_per_bearing": building.weight / model.n_bearings,
        "gravity_shares": model.gravity_loads.tolist(), "overturning": int(model.overturning),
        "vertical": int(model.vertical is not None),
        "effective_radius": bearing.effective_radius, "slider_diameter": bearing.slider_diameter,
        "displacement_capacity": bearing.displacement_capacity,
        "isolated_period": model.isolated_period(),
        "fixed_base_periods": building.fixed_base_modes().periods.tolist(),
        "total_mass": building.total_mass, "success": int(success), "message": message,
        "failure": failure, "peaks_up_to_failure": int(not success), "steps": int(nt - 1),
        "energy_balance_error": energies.relative_error,
        **uplift_record(records["axial_load"], step),
    }
    if failed_at is not None:
        common["failed_at"] = float(failed_at)
    return xr.Dataset(data, coords=coords, attrs=common | attrs)


def history_dataset(model: IsolatedShearBuilding, motion: GroundMotion | GroundMotionPair,
                    step: float, acceleration: np.ndarray, history: EngineHistory, **attrs: Any):
    """:func:`response_dataset` of an engine's ``history`` of ``model`` under ``motion`` at
    ``step`` [s] (``acceleration``: the ground samples run [m/s^2], cut to the steps kept): its
    Newton iterations, subdivisions, wall and compile times [s] and engine as attributes, which
    ``attrs`` extends or overrides."""
    result = history.result
    return response_dataset(
        model, motion, step, acceleration[:result.time.size], result.displacement,
        result.velocity, result.absolute_acceleration, history.bearings,
        integrator=repr(result.method), success=result.success, message=result.message,
        failure=result.failure, failed_at=result.failed_at, restoring=history.restoring,
        plate=history.plate,
        attrs={"newton_iterations": int(result.iterations.sum()),
               "subdivisions": int(result.subdivisions.sum()),
               "wall_time": history.wall_time, "compile_time": history.compile_time,
               "engine": history.engine, **attrs})


def write_netcdf(result: Any, path: str | os.PathLike) -> Path:
    """Write a result Dataset (:func:`response_dataset`) to the netCDF file ``path``
    atomically (:func:`dcfpb.common.files.atomic_output`): a failed or interrupted write leaves
    the file there before whole and no temporary file behind. Returns the path."""
    path = Path(path)
    with atomic_output(path) as temporary:
        result.to_netcdf(temporary)
    return path
