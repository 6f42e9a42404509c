"""The result of a run in plan as an ``xarray.Dataset`` with a ``direction`` dimension.

:func:`spatial_dataset` turns the histories of :func:`structures.spatial.analysis.run_spatial`
into the Dataset it documents, with the energy balance (:mod:`structures.spatial.energy`) and
the displacement-capacity check of every bearing (the planar failure contract: the first
committed step at which a bearing's displacement, the length of its (x, y) vector, exceeds the
``displacement_capacity`` ends the run there).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from groundmotions.pairs import GroundMotionPair
from isolator.bearing import beyond_capacity_message
from structures.integrators import IntegrationResult
from structures.results import friction_name
from structures.spatial.energy import spatial_energy_balance
from structures.spatial.isolated import SpatialIsolatedBuilding

__all__ = ["BEARING_RECORD", "plate_fields", "spatial_dataset"]

BEARING_RECORD: dict[str, tuple[int, ...]] = {
    "displacement": (2,), "force": (2,), "friction_force": (2,), "mu": (), "temperature": (),
    "heat_flux": (), "axial_load": (),
}
"""What is recorded of each bearing at each committed step (its shape besides time and
bearing): the fields of :class:`isolator.bearing.BearingState`."""

_ENERGIES = ("input", "kinetic", "damping", "strain", "friction", "error")


def _capacity(record: dict[str, np.ndarray], capacity: float, step: float) -> tuple[int, str]:
    """The steps kept and the capacity failure's message ("" if none)."""
    reach = np.hypot(*np.moveaxis(record["displacement"], -1, 0)).max(axis=1)
    beyond = np.flatnonzero(reach > capacity)
    if not beyond.size:
        return reach.size, ""
    kept = int(beyond[0]) + 1
    return kept, beyond_capacity_message(reach[kept - 1], step * (kept - 1), capacity)


def plate_fields(model: SpatialIsolatedBuilding) -> tuple[np.ndarray, np.ndarray] | None:
    """The temperature field each bearing's monitor grid holds after the last commit (the
    precise model; None for the others): positions (n_bearings, m, 2) [m] in plate
    coordinates and temperatures (n_bearings, m) [degC], padded with NaN to the bearing with
    the most points ever touched."""
    from isolator.monitor_grid import GridHeating

    grids = [getattr(e.friction_state, "heating", None) for e in model.elements]
    if not all(isinstance(g, GridHeating) for g in grids):
        return None
    size = max(g.stored_points for g in grids)
    positions = np.full((len(grids), size, 2), np.nan)
    temperatures = np.full((len(grids), size), np.nan)
    for b, grid in enumerate(grids):
        m = grid.stored_points
        positions[b, :m] = grid.point_positions()
        temperatures[b, :m] = grid.point_temperatures()
    return positions, temperatures


def spatial_dataset(model: SpatialIsolatedBuilding, motion: GroundMotionPair, step: float,
                    ground_acceleration: np.ndarray, result: IntegrationResult,
                    record: dict[str, np.ndarray], restoring: np.ndarray, *,
                    attrs: dict[str, Any],
                    plate: tuple[np.ndarray, np.ndarray] | None = None):
    """Assemble the Dataset of a run in plan.

    Parameters
    ----------
    model : SpatialIsolatedBuilding
        The model that was run.
    motion : GroundMotionPair
        The records (names and processing go to the attributes).
    step : float
        Analysis step [s].
    ground_acceleration : numpy.ndarray
        (x, y) on the analysis steps kept, shape (nt, 2) [m/s^2].
    result : IntegrationResult
        The integration (displacements on the model's DOFs).
    record : dict of str to numpy.ndarray
        The bearings' histories (:data:`BEARING_RECORD`).
    restoring : numpy.ndarray
        Total restoring force, shape (nt, n_dof) [N, N m].
    attrs : dict
        Producer-specific attributes (iterations, wall time, engine).
    plate : tuple of numpy.ndarray, optional
        The precise model's plate field (positions (n_bearings, m, 2) [m], temperatures
        (n_bearings, m) [degC], NaN-padded) when the run kept it outside the model (the
        compiled engine's); None: read from the model's elements (:func:`plate_fields`).

    Returns
    -------
    xarray.Dataset
        Dimensions ``time``, ``floor`` (0 = base slab), ``storey``, ``direction`` (x, y) and
        ``bearing``. Level histories at the reference point (the centre of stiffness):
        ``displacement``, ``velocity``, ``absolute_acceleration`` (time, floor, direction),
        ``rotation``, ``angular_velocity``, ``angular_acceleration`` (time, floor);
        ``storey_drift`` and ``storey_shear`` (time, storey, direction), ``storey_twist``
        (time, storey); the bearings' ``bearing_displacement``, ``bearing_force`` and
        ``bearing_friction_force`` (time, bearing, direction), ``axial_load`` (0 on
        uplift), ``mu``, ``temperature``, ``heat_flux`` (time, bearing); ``base_shear``
        (time, direction); ``ground_acceleration`` (time, direction) and, with a vertical,
        ``vertical_ground_acceleration``; the energies ``energy_*`` (time); with the precise
        model, ``plate_temperature`` (bearing, plate_point), the field left on each plate at
        the end (:func:`plate_fields`), at the coordinates ``plate_point_x``,
        ``plate_point_y`` [m]. Coordinates ``bearing_x``, ``bearing_y`` [m]. Attributes as
        the planar run's, with ``success``, ``message``, ``failure``, ``energy_balance_error``.
    """
    import xarray as xr

    building, bearing = model.building, model.bearing
    success, message, failure = result.success, result.message, result.failure
    failed_at = result.failed_at
    kept, beyond = _capacity(record, bearing.displacement_capacity, step)
    if beyond:
        success, message, failure, failed_at = False, beyond, "capacity", step * (kept - 1)
    if success:
        failed_at = None
    else:
        failure = failure or "error"
        failed_at = step * (kept - 1) if failed_at is None else failed_at
        message = (f"{message} The histories and peaks are those up to t = "
                   f"{step * (kept - 1):.6g} s.")
    u, v = result.displacement[:kept], result.velocity[:kept]
    a_abs = result.absolute_acceleration[:kept]
    ag, restoring = ground_acceleration[:kept], restoring[:kept]
    record = {name: values[:kept] for name, values in record.items()}
    energies = spatial_energy_balance(u, v, ag, model.mass_matrix, model.damping_matrix,
                                      model.influence, restoring, record["displacement"],
                                      record["friction_force"])
    n, nt = building.n_storeys, u.shape[0]
    levels = (nt, n + 1, 3)
    inertia = -(a_abs @ model.mass_matrix.T).reshape(levels)  # [N, N m] at O, per level
    shear = np.cumsum(inertia[:, :0:-1, :2], axis=1)[:, ::-1]  # the floors above each storey
    drift = np.diff(u.reshape(levels), axis=1)

    def var(dims, data, units, long_name):
        return dims, np.asarray(data), {"units": units, "long_name": long_name}

    tfd, tf, tbd, tb = ("time", "floor", "direction"), ("time", "floor"), \
        ("time", "bearing", "direction"), ("time", "bearing")
    data = {
        "displacement": var(tfd, u.reshape(levels)[..., :2], "m",
                            "displacement relative to the ground (centre of stiffness)"),
        "velocity": var(tfd, v.reshape(levels)[..., :2], "m/s", "velocity relative to the "
                        "ground (centre of stiffness)"),
        "absolute_acceleration": var(tfd, a_abs.reshape(levels)[..., :2], "m/s^2",
                                     "absolute acceleration (centre of stiffness)"),
        "rotation": var(tf, u.reshape(levels)[..., 2], "rad", "rotation about the vertical"),
        "angular_velocity": var(tf, v.reshape(levels)[..., 2], "rad/s", "angular velocity"),
        "angular_acceleration": var(tf, a_abs.reshape(levels)[..., 2], "rad/s^2",
                                    "angular acceleration"),
        "storey_drift": var(("time", "storey", "direction"), drift[..., :2], "m",
                            "storey drift at the centre of stiffness"),
        "storey_twist": var(("time", "storey"), drift[..., 2], "rad", "storey twist"),
        "storey_shear": var(("time", "storey", "direction"), shear, "N",
                            "storey shear (inertia forces of the floors above)"),
        "bearing_displacement": var(tbd, record["displacement"], "m", "bearing displacement"),
        "bearing_force": var(tbd, record["force"], "N", "bearing force"),
        "bearing_friction_force": var(tbd, record["friction_force"], "N",
                                      "friction part of the bearing force"),
        "axial_load": var(tb, record["axial_load"], "N", "normal force (0: uplift)"),
        "mu": var(tb, record["mu"], "-", "friction coefficient"),
        "temperature": var(tb, record["temperature"], "degC", "contact temperature"),
        "heat_flux": var(tb, record["heat_flux"], "W/m^2", "heat flux into each surface"),
        "base_shear": var(("time", "direction"), record["force"].sum(axis=1), "N",
                          "base shear through the isolation level"),
        "ground_acceleration": var(("time", "direction"), ag, "m/s^2", "ground acceleration"),
    }
    time = step * np.arange(nt)
    if model.vertical is not None:
        data["vertical_ground_acceleration"] = var(
            "time", model.vertical_accelerations(time), "m/s^2",
            "vertical ground acceleration (positive up)")
    if plate is None:
        plate = plate_fields(model)
    if plate is not None:
        data["plate_temperature"] = var(("bearing", "plate_point"), plate[1], "degC",
                                        "temperature of the plate's monitor points at the end")
    for name in _ENERGIES:
        data[f"energy_{name}"] = var("time", getattr(energies, name), "J", f"{name} energy")
    xy = building.plan.bearing_coordinates
    coords = {"time": ("time", time, {"units": "s"}), "floor": np.arange(n + 1),
              "storey": np.arange(1, n + 1), "direction": ["x", "y"],
              "bearing": np.arange(xy.shape[0]),
              "bearing_x": ("bearing", xy[:, 0], {"units": "m"}),
              "bearing_y": ("bearing", xy[:, 1], {"units": "m"})}
    if plate is not None:
        for axis, name in enumerate(("plate_point_x", "plate_point_y")):
            coords[name] = (("bearing", "plate_point"), plate[0][..., axis], {"units": "m"})
    common: dict[str, Any] = {
        "record": motion.name, "record_x": motion.x.name, "record_y": motion.y.name,
        "record_processing": "; ".join(motion.x.processing), "dt": step,
        "integrator": repr(result.method), "friction_model": friction_name(bearing.friction),
        "friction": repr(bearing.friction), "n_bearings": model.n_bearings,
        "gravity_shares": model.gravity_shares.tolist(), "overturning": int(model.overturning),
        "vertical": int(model.vertical is not None),
        "effective_radius": bearing.effective_radius,
        "slider_diameter": bearing.slider_diameter,
        "displacement_capacity": bearing.displacement_capacity,
        "isolated_period": model.isolated_period(),
        "fixed_base_periods": building.fixed_base_modes().periods.tolist(),
        "total_mass": building.total_mass, "success": int(success), "message": message,
        "failure": failure if not success else "", "peaks_up_to_failure": int(not success),
        "steps": int(nt - 1), "energy_balance_error": energies.relative_error,
    }
    if failed_at is not None:
        common["failed_at"] = float(failed_at)
    return xr.Dataset(data, coords=coords, attrs=common | attrs)
