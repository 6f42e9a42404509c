"""The same superstructure on a fixed base: the reference an isolation system is judged against.

:func:`run_fixed_base` computes the linear response of a :class:`ShearBuilding` standing on the
ground (no base slab, no isolators) to a ground motion, by modal superposition: the building's
damping is classical (Rayleigh or modal), so each fixed-base mode is a single-degree-of-freedom
oscillator, solved with the exact recurrence of :mod:`groundmotions.spectra` (Nigam & Jennings,
the spectrum code: no integration error for the piecewise-linear record). The result is an
``xarray.Dataset`` with the variables of :func:`structures.analysis.run` that describe the
superstructure (``displacement``, ``velocity``, ``absolute_acceleration``, ``storey_drift``,
``storey_shear``, ``base_shear``, ``ground_acceleration``), so both can be compared and
reduced alike by :func:`superstructure_peaks` and :func:`ratios_to_fixed_base`.

Floor 0 of the fixed-base Dataset is the ground level: it moves with the ground (relative
displacement 0, absolute acceleration a_g). Its base shear is the first-storey shear, the sum of
the inertia forces of the floors above.

References
----------
A. K. Chopra, "Dynamics of Structures", Sec. 13.1 (modal analysis of a shear building under
ground motion) and Sec. 5.2 (the exact recurrence).
"""

from __future__ import annotations

import time as _time

import numpy as np

from groundmotions.records import GroundMotion
from groundmotions.spectra import sdof_response
from structures.analysis import default_step, resampled_record
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
        raise ValueError(
            "The 'damping' parameter of ShearBuilding must be classical (diagonal in the "
            "fixed-base modes) for run_fixed_base. Got a damping matrix whose modal coupling is "
            f"{coupling:.3g} of its largest modal term instead."
        )
    return diagonal / (2.0 * omega)


def run_fixed_base(building: ShearBuilding, motion: GroundMotion, *, dt: float | None = None,
                   max_steps: int = DEFAULT_MAX_STEPS):
    """The linear response of the superstructure on a fixed base to a ground motion.

    Parameters
    ----------
    building : ShearBuilding
        The superstructure (its base slab is not part of the fixed-base building).
    motion : GroundMotion
        Ground acceleration [m/s^2] (scale it first with ``motion.scaled``).
    dt : float, optional
        Output step [s], at most the record's; finer steps interpolate the record linearly
        (exactly as :func:`structures.analysis.run` does, so the two share a time axis).
    max_steps : int
        Most time steps the run may take, as in :func:`structures.analysis.run`.

    Returns
    -------
    xarray.Dataset
        Dimensions ``time``, ``floor`` (0 = the ground level, 1..n) and ``storey`` (1..n);
        variables ``displacement``, ``velocity`` (relative to the ground), ``absolute_acceleration``
        (time, floor), ``storey_drift``, ``storey_shear`` (time, storey), ``base_shear`` and
        ``ground_acceleration`` (time); attributes ``configuration = "fixed base"``, the
        record, ``dt``, the modal periods and damping ratios, ``success`` and ``wall_time``.

    Raises
    ------
    ValueError
        For a ``dt`` outside (0, record dt], or a damping that is not classical; an
        :class:`~dcfpb.common.errors.InputError` for a run past ``max_steps`` or the memory
        available.
    """
    import xarray as xr

    limit = {"max_steps": max_steps, "what": "The fixed-base run",
             "raise_with": "the max_steps argument of structures.fixed_base.run_fixed_base"}
    fields = fixed_base_fields(building.n_storeys)
    check_run(motion, default_step(motion.dt) if dt is None else dt, fields, **limit)
    acceleration, step = resampled_record(motion, dt)
    start = _time.perf_counter()
    modes = building.fixed_base_modes()
    omega = modes.circular_frequencies
    ratios = _modal_damping_ratios(building, modes.shapes, omega)
    mass = building.fixed_base_mass_matrix
    participation = modes.shapes.T @ mass @ np.ones(building.n_storeys)  # Gamma_j [kg^1/2]
    n = building.n_storeys
    # q_j = Gamma_j x_j, x_j the oscillator of period T_j and ratio xi_j under -a_g
    x, dx = sdof_response(acceleration, step, modes.periods, ratios)
    u = (x * participation) @ modes.shapes.T
    v = (dx * participation) @ modes.shapes.T
    # M a_abs = -(C v + K u): the absolute acceleration from equilibrium
    damping, stiffness = building.fixed_base_damping_matrix, building.fixed_base_stiffness_matrix
    inertia = -(v @ damping.T + u @ stiffness.T)
    absolute = inertia / building.floor_masses
    wall = _time.perf_counter() - start

    ground = acceleration[:, None]
    displacement = np.hstack([np.zeros_like(ground), u])
    velocity = np.hstack([np.zeros_like(ground), v])
    absolute_acceleration = np.hstack([ground, absolute])
    storey_shear = np.cumsum(-(absolute * building.floor_masses)[:, ::-1], axis=1)[:, ::-1]

    def var(dims, data, units, long_name):
        return dims, np.asarray(data), {"units": units, "long_name": long_name}

    data = {
        "displacement": var(("time", "floor"), displacement, "m",
                            "displacement relative to the ground"),
        "velocity": var(("time", "floor"), velocity, "m/s", "velocity relative to the ground"),
        "absolute_acceleration": var(("time", "floor"), absolute_acceleration, "m/s^2",
                                     "absolute acceleration"),
        "storey_drift": var(("time", "storey"), np.diff(displacement, axis=1), "m",
                            "storey drift"),
        "storey_shear": var(("time", "storey"), storey_shear, "N",
                            "storey shear (inertia forces of the floors above)"),
        "base_shear": var("time", storey_shear[:, 0], "N",
                          "base shear (first-storey shear)"),
        "ground_acceleration": var("time", acceleration, "m/s^2", "ground acceleration"),
    }
    attrs = {
        "configuration": "fixed base",
        "record": motion.name,
        "record_processing": "; ".join(motion.processing),
        "dt": step,
        "integrator": "modal superposition, exact piecewise-linear recurrence",
        "fixed_base_periods": modes.periods.tolist(),
        "modal_damping_ratios": ratios.tolist(),
        "total_mass": float(building.floor_masses.sum()),
        "success": 1,
        "message": "The integration reached the end of the record.",
        "steps": int(acceleration.size - 1),
        "wall_time": wall,
    }
    coords = {"time": ("time", step * np.arange(acceleration.size), {"units": "s"}),
              "floor": np.arange(n + 1), "storey": np.arange(1, n + 1)}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def superstructure_peaks(result) -> dict[str, float]:
    """Peaks of the superstructure of a run, isolated or on a fixed base (SI units).

    Returns
    -------
    dict
        ``peak_storey_drift`` [m] and ``peak_storey_shear`` [N] (largest over the storeys),
        ``peak_roof_acceleration`` (absolute) [m/s^2] and ``peak_base_shear`` [N] (through the
        isolation level of an isolated run; the first-storey shear on a fixed base).
    """
    return {
        "peak_storey_drift": float(np.abs(result["storey_drift"]).max()),
        "peak_storey_shear": float(np.abs(result["storey_shear"]).max()),
        "peak_roof_acceleration": float(np.abs(result["absolute_acceleration"].isel(floor=-1))
                                        .max()),
        "peak_base_shear": float(np.abs(result["base_shear"]).max()),
    }


def ratios_to_fixed_base(result, fixed_base) -> dict[str, float]:
    """Each of :data:`PEAK_NAMES` of ``result`` over the same peak of ``fixed_base`` [-].

    Below 1 where the isolation reduces the response, above 1 where it amplifies it.
    """
    isolated, fixed = superstructure_peaks(result), superstructure_peaks(fixed_base)
    return {name: isolated[name] / fixed[name] for name in PEAK_NAMES}
