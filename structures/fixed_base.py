"""The same superstructure on a fixed base: the reference an isolation system is judged against.

:func:`run_fixed_base` gives the linear response of a :class:`ShearBuilding` on the ground (no
base slab, no isolators) by superposing its classically damped modes, each solved by the exact
recurrence of :mod:`groundmotions.spectra`; :func:`superstructure_peaks` and
:func:`ratios_to_fixed_base` compare it with an isolated run.

References
----------
A. K. Chopra, "Dynamics of Structures", Sec. 13.1 (modal analysis of a shear building under
ground motion) and Sec. 5.2 (the exact recurrence).
"""

from __future__ import annotations

import time as _time

import numpy as np

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_dataset, check_instance, check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from groundmotions.spectra import sdof_response
from structures.analysis import default_step, ground_record
from structures.limits import DEFAULT_MAX_STEPS, check_run, fixed_base_fields
from structures.shear_building import ShearBuilding

__all__ = ["PEAK_NAMES", "ratios_to_fixed_base", "run_fixed_base", "superstructure_peaks"]

PEAK_NAMES = ("peak_storey_drift", "peak_storey_shear", "peak_roof_acceleration",
              "peak_base_shear")
"""Peaks compared between an isolated run and the fixed base (see :func:`superstructure_peaks`)."""


def _modal_damping_ratios(building: ShearBuilding, shapes: np.ndarray,
                          omega: np.ndarray) -> np.ndarray:
    """Damping ratio of each fixed-base mode [-]; raises if the damping is not classical."""
    modal = shapes.T @ building.fixed_base_damping_matrix @ shapes
    diagonal = np.diag(modal)
    coupling = np.abs(modal - np.diag(diagonal)).max(initial=0.0)
    if coupling > 1e-8 * np.abs(diagonal).max(initial=0.0):
        raise InputError(
            "The 'damping' parameter of ShearBuilding must be classical (diagonal in the "
            "fixed-base modes) for run_fixed_base. Got a damping matrix whose modal coupling is "
            f"{coupling:.3g} of its largest modal term instead."
        )
    return diagonal / (2.0 * omega)


def run_fixed_base(building: ShearBuilding, motion: GroundMotion | GroundMotionPair, *,
                   dt: float | None = None, max_steps: int = DEFAULT_MAX_STEPS):
    """The linear response of the superstructure on a fixed base to a ground motion.

    Parameters
    ----------
    building : ShearBuilding
        The superstructure (its base slab is no part of it), in one direction or in plan.
    motion : GroundMotion or GroundMotionPair
        Ground acceleration [m/s^2]: one record in one direction, a pair (x, y; a vertical is
        left out) in plan.
    dt, max_steps : float, int, optional
        Output step [s] and most time steps, as in :func:`structures.analysis.run` (so that the
        two share a time axis).

    Returns
    -------
    xarray.Dataset
        The layout of :func:`structures.results.response_dataset` for the superstructure:
        ``displacement``, ``velocity``, ``absolute_acceleration`` (floor 0, the ground level,
        moves with the ground), ``storey_drift``, ``storey_shear``, ``base_shear`` (the
        first-storey shear), ``ground_acceleration`` and, in plan, ``rotation`` and
        ``storey_twist``; attributes ``configuration = "fixed base"``, the record, ``dt``, the
        modal periods and damping ratios, ``success`` and ``wall_time``.

    Raises
    ------
    ValueError
        For a ``dt`` outside (0, record dt], or a damping that is not classical.
    dcfpb.common.errors.InputError
        For a run past ``max_steps`` or the memory available, or a motion that does not fit the
        building (one record in one direction, a pair in plan).
    """
    import xarray as xr

    check_instance(building, "building", "run_fixed_base", ShearBuilding, "a ShearBuilding")
    check_instance(motion, "motion", "run_fixed_base", (GroundMotion, GroundMotionPair),
                   "a GroundMotion or a GroundMotionPair")
    if dt is not None:
        check_real(dt, "dt", "run_fixed_base", low=0.0, low_open=True)
    pair = isinstance(motion, GroundMotionPair)
    if pair != (building.plan is not None):
        raise InputError("The fixed base of a building in plan runs under a pair of records and "
                         "that of a building in one direction under one record.")
    first = motion.x if pair else motion
    limit = {"max_steps": max_steps, "what": "The fixed-base run",
             "raise_with": "the max_steps argument of structures.fixed_base.run_fixed_base"}
    fields = fixed_base_fields(building.n_storeys * building.level_dofs)
    check_run(first, default_step(first.dt) if dt is None else dt, fields, **limit)
    acceleration, step = ground_record(motion, dt)
    start = _time.perf_counter()
    modes = building.fixed_base_modes()
    omega = modes.circular_frequencies
    ratios = _modal_damping_ratios(building, modes.shapes, omega)
    mass = building.fixed_base_mass_matrix
    dofs, n, directions = building.level_dofs, building.n_storeys, building.directions
    nt, components = acceleration.shape[0], len(directions)
    ground = acceleration.reshape(nt, components)
    influence = np.reshape(building.isolated_influence[dofs:], (n * dofs, components))
    participation = modes.shapes.T @ mass @ influence  # Gamma_jc [kg^1/2]
    # q_j = sum_c Gamma_jc x_jc, x_jc the oscillator of period T_j and ratio xi_j under -a_g,c
    u = v = 0.0
    for c in range(components):
        x, dx = sdof_response(ground[:, c], step, modes.periods, ratios)
        u = u + (x * participation[:, c]) @ modes.shapes.T
        v = v + (dx * participation[:, c]) @ modes.shapes.T
    # M a_abs = -(C v + K u): the absolute acceleration from equilibrium
    damping, stiffness = building.fixed_base_damping_matrix, building.fixed_base_stiffness_matrix
    forces = v @ damping.T + u @ stiffness.T  # storey forces on each floor = - M a_abs
    absolute = (-forces / building.floor_masses if dofs == 1
                else np.linalg.solve(mass, -forces.T).T)
    wall = _time.perf_counter() - start
    levels = (nt, n + 1, dofs)
    at_ground = np.zeros((nt, 1, dofs))
    displacement = np.concatenate([at_ground, u.reshape(nt, n, dofs)], axis=1)
    velocity = np.concatenate([at_ground, v.reshape(nt, n, dofs)], axis=1)
    moving = at_ground.copy()
    moving[:, 0, :components] = ground
    absolute_acceleration = np.concatenate([moving, absolute.reshape(nt, n, dofs)], axis=1)
    inertia = forces.reshape(nt, n, dofs)[..., :components]  # the floors' inertia forces
    storey_shear = np.cumsum(inertia[:, ::-1], axis=1)[:, ::-1]
    drift = np.diff(displacement.reshape(levels), axis=1)

    def var(dims, data, units, long_name):
        return dims, np.asarray(data), {"units": units, "long_name": long_name}

    tfd = ("time", "floor", "direction")
    data = {
        "displacement": var(tfd, displacement[..., :components], "m",
                            "displacement relative to the ground"),
        "velocity": var(tfd, velocity[..., :components], "m/s",
                        "velocity relative to the ground"),
        "absolute_acceleration": var(tfd, absolute_acceleration[..., :components], "m/s^2",
                                     "absolute acceleration"),
        "storey_drift": var(("time", "storey", "direction"), drift[..., :components], "m",
                            "storey drift"),
        "storey_shear": var(("time", "storey", "direction"), storey_shear, "N",
                            "storey shear (inertia forces of the floors above)"),
        "base_shear": var(("time", "direction"), storey_shear[:, 0], "N",
                          "base shear (first-storey shear)"),
        "ground_acceleration": var(("time", "direction"), ground, "m/s^2",
                                   "ground acceleration"),
    }
    if dofs == 3:
        data["rotation"] = var(("time", "floor"), displacement[..., 2], "rad",
                               "rotation about the vertical")
        data["storey_twist"] = var(("time", "storey"), drift[..., 2], "rad", "storey twist")
    attrs = {
        "configuration": "fixed base",
        "record": motion.name,
        "record_processing": "; ".join(first.processing),
        "dt": step,
        "integrator": "modal superposition, exact piecewise-linear recurrence",
        "fixed_base_periods": modes.periods.tolist(),
        "modal_damping_ratios": ratios.tolist(),
        "total_mass": float(building.floor_masses.sum()),
        "success": 1,
        "message": "The integration reached the end of the record.",
        "steps": int(nt - 1),
        "wall_time": wall,
    }
    coords = {"time": ("time", step * np.arange(nt), {"units": "s"}),
              "floor": np.arange(n + 1), "storey": np.arange(1, n + 1),
              "direction": list(directions)}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _per_direction(name: str, values: np.ndarray, directions) -> dict[str, float]:
    """``name`` for one direction, ``name_x`` and ``name_y`` in plan."""
    if len(directions) == 1:
        return {name: float(values[0])}
    return {f"{name}_{d}": float(value) for d, value in zip(directions, values, strict=True)}


def superstructure_peaks(result) -> dict[str, float]:
    """Peaks of the superstructure of a run, isolated or on a fixed base: ``peak_storey_drift``
    [m] and ``peak_storey_shear`` [N] (the largest over the storeys), ``peak_roof_acceleration``
    (absolute) [m/s^2] and ``peak_base_shear`` [N] (through the isolation level of an isolated
    run, the first-storey shear on a fixed base); in plan each per direction (``_x``, ``_y``)."""
    directions = list(result["direction"].values)
    roof = result["absolute_acceleration"].isel(floor=-1)
    peaks = {}
    for name, values in (("peak_storey_drift", result["storey_drift"]),
                         ("peak_storey_shear", result["storey_shear"]),
                         ("peak_roof_acceleration", roof),
                         ("peak_base_shear", result["base_shear"])):
        axes = tuple(i for i, dim in enumerate(values.dims) if dim != "direction")
        peaks |= _per_direction(name, np.abs(values.values).max(axis=axes), directions)
    return peaks


def ratios_to_fixed_base(result, fixed_base) -> dict[str, float]:
    """Each of :func:`superstructure_peaks` of ``result`` over that of ``fixed_base`` [-]."""
    check_dataset(result, "result", "ratios_to_fixed_base")
    check_dataset(fixed_base, "fixed_base", "ratios_to_fixed_base")
    isolated, fixed = superstructure_peaks(result), superstructure_peaks(fixed_base)
    return {name: isolated[name] / fixed[name] for name in isolated}
