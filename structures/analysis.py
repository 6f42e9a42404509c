"""Time-history analysis of a shear building on DCFPB isolators: under one record in one
direction, under a pair (x, y and optionally a vertical) in plan.

:func:`run` integrates :class:`~structures.isolated_building.IsolatedShearBuilding` with Newmark
or HHT-alpha on one of two engines giving the same result, :func:`reference_history` (the
integrators on the model objects: the specification) or :mod:`structures.compiled` (the same
algorithm in numba), and returns the Dataset of :func:`structures.results.response_dataset`;
:func:`peaks` reduces it to the numbers engineers look at first.
"""

from __future__ import annotations

import math
import time as _time
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_dataset, check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from structures.compiled.engine import compiled_history, select_engine, time_limit_error
from structures.integrators import HHT, Newmark, as_method, integrate
from structures.isolated_building import IsolatedShearBuilding
from structures.limits import DEFAULT_MAX_STEPS, building_fields, check_run
from structures.results import (
    BEARING_RECORD,
    EngineHistory,
    history_dataset,
    resultant,
    temperature_fields,
    uplift_record,
)
from structures.shear_building import ShearBuilding

DEFAULT_MAX_STEP = 0.005
"""Largest default analysis step [s], at which the bearing's EDC and temperature converge to
0.1 % and 0.2 degC (tests/verification/test_time_step_convergence.py)."""


def default_step(record_dt: float) -> float:
    """The default analysis step: the record's, divided into the fewest equal parts of at most
    :data:`DEFAULT_MAX_STEP` (0.02 s -> 0.005 s; 0.005 s and finer records keep theirs) [s]."""
    record_dt = check_real(record_dt, "record_dt", "default_step", low=0.0, low_open=True)
    return record_dt / math.ceil(record_dt / DEFAULT_MAX_STEP - 1e-6)


def resampled_record(motion: GroundMotion, dt: float | None) -> tuple[np.ndarray, float]:
    """The record on the analysis step ``dt`` (None: :func:`default_step`) [s]: its own, or a
    finer one interpolated linearly (exact for the piecewise-linear record integrated)."""
    if dt is None:
        dt = default_step(motion.dt)
    if abs(dt - motion.dt) <= 1e-12 * motion.dt:
        return np.asarray(motion.acceleration, dtype=float), float(motion.dt)
    check_real(dt, "dt", "run", low=0.0, high=motion.dt, low_open=True)
    n = int(np.floor(motion.duration / dt + 1e-9)) + 1
    t = dt * np.arange(n)
    return np.interp(t, motion.time, motion.acceleration), float(dt)


def ground_record(motion: GroundMotion | GroundMotionPair,
                  dt: float | None) -> tuple[np.ndarray, float]:
    """The horizontal ground acceleration on the analysis step (:func:`resampled_record`):
    shape (nt,) for a record, (nt, 2) for a pair [m/s^2]; and the step [s]."""
    if isinstance(motion, GroundMotionPair):
        x, step = resampled_record(motion.x, dt)
        y, _ = resampled_record(motion.y, step)
        return np.column_stack([x, y]), step
    return resampled_record(motion, dt)


def reference_history(model: IsolatedShearBuilding, acceleration: np.ndarray, step: float,
                      integrator: str | Newmark | HHT, *, tolerance: float,
                      max_iterations: int = 25, max_subdivisions: int,
                      time_limit: float | None = None) -> EngineHistory:
    """The reference engine: :func:`integrate` on the model, recording every bearing position
    at each committed step; arguments as :func:`structures.compiled.engine.compiled_history`
    (``time_limit`` [s] checked after every step)."""
    nt, positions = acceleration.shape[0], len(model.elements)
    record = {name: np.zeros((nt, positions, size) if size else (nt, positions))
              for name, size in BEARING_RECORD.items()}
    restoring = np.zeros((nt, model.mass_matrix.shape[0]))
    dofs = model.level_dofs
    # sum_b T_b^T (m_b F_b) as one product: the (n_b 2) forces times (n_b 2, dofs)
    transposed = np.asarray(model.transformations)[..., :dofs].reshape(-1, dofs)
    multiplicity = np.asarray(model.multiplicity, dtype=float)[:, None]
    columns = [(name, record[name], size) for name, size in BEARING_RECORD.items()]
    deadline = np.inf

    def on_commit(k: int, t: float, u: np.ndarray, *_: np.ndarray) -> None:
        for i, state in enumerate(model.committed_states()):
            for name, values, size in columns:
                value = getattr(state, name)
                if size and isinstance(value, float):  # one direction: x only
                    values[k, i, 0] = value
                else:
                    values[k, i] = value
        restoring[k] = model.superstructure_stiffness @ u
        restoring[k, :dofs] += (record["force"][k] * multiplicity).ravel() @ transposed
        if _time.perf_counter() > deadline:  # ends the run, this step kept
            raise time_limit_error(time_limit, t)

    on_commit(0, 0.0, np.zeros(restoring.shape[1]))
    compile_time = compile_kernels()
    start = _time.perf_counter()
    if time_limit is not None:
        deadline = start + time_limit
    result = integrate(model, acceleration, step, integrator, tolerance=tolerance,
                       max_iterations=max_iterations, max_subdivisions=max_subdivisions,
                       on_commit=on_commit)
    wall = _time.perf_counter() - start
    kept = result.time.size
    record = {name: values[:kept] for name, values in record.items()}
    return EngineHistory(result, record, restoring[:kept], wall, "reference", compile_time,
                         temperature_fields(model))


def compile_kernels() -> float:
    """Compile the friction and heating kernels of the reference element unless this process
    has them; return the time it took [s] (kept out of the run's ``wall_time``)."""
    from isolator.compiled.kernels import ptv_trial, warm_up

    if not getattr(ptv_trial, "signatures", True):  # numba, nothing compiled yet
        start = _time.perf_counter()
        warm_up()
        return _time.perf_counter() - start
    return 0.0


def check_motion(building: ShearBuilding, motion: GroundMotion | GroundMotionPair,
                 owner: str) -> bool:
    """Whether ``motion`` is a pair, checked to suit ``building``: a building in plan runs under
    a pair of records, a building in one direction under one record. ``owner`` (the function
    checking) is named when ``building`` is no ``ShearBuilding`` or ``motion`` neither kind."""
    pair = isinstance(motion, GroundMotionPair)
    if not isinstance(building, ShearBuilding):
        raise InputTypeError(f"The 'building' parameter of {owner} must be a ShearBuilding. Got "
                             f"{building!r} instead.")
    if not pair and not isinstance(motion, GroundMotion):
        raise InputTypeError(f"The 'motion' parameter of {owner} must be a GroundMotion or a "
                             f"GroundMotionPair. Got {motion!r} instead.")
    if pair != (building.plan is not None):
        has = "has a" if building.plan is not None else "has no"
        raise InputError(
            "A building in plan runs under a pair of records (GroundMotionPair) and a building "
            f"in one direction under one record: the building {has} plan and the motion is "
            f"{'a pair' if pair else 'one record'}.")
    return pair


def check_length(
    building: ShearBuilding,
    motion: GroundMotion | GroundMotionPair,
    dt: float | None = None,
    *,
    max_steps: int = DEFAULT_MAX_STEPS,
    raise_with: str = "the max_steps argument of structures.analysis.run",
    owner: str = "run",
) -> int:
    """Refuse a run of ``building`` under ``motion`` at the analysis step ``dt`` [s] (None:
    :func:`default_step`) past ``max_steps`` time steps or the memory available, before any work;
    return its steps. ``raise_with`` and ``owner`` name how to raise the limit and who checks
    ``dt`` in the messages (:func:`structures.limits.check_run`)."""
    first = motion.x if isinstance(motion, GroundMotionPair) else motion
    fields = building_fields(building.n_storeys, building.level_dofs,
                             len(building.bearing_positions))
    return check_run(first, default_step(first.dt) if dt is None else dt, fields,
                     max_steps=max_steps, raise_with=raise_with, owner=owner)


def run(
    building: ShearBuilding,
    bearing: DCFPBearing,
    motion: GroundMotion | GroundMotionPair,
    integrator: str | Newmark | HHT = "newmark",
    *,
    n_bearings: int | None = None,
    dt: float | None = None,
    tolerance: float = 1e-8,
    max_subdivisions: int = 6,
    engine: str = "auto",
    floor_spectra: bool = False,
    time_limit: float | None = None,
    max_steps: int = DEFAULT_MAX_STEPS,
    overturning: bool = True,
    grid_orientation: float | None = None,
):
    """Run a time-history analysis.

    Parameters
    ----------
    building : ShearBuilding
        The superstructure and base slab; with a plan, the building in plan.
    bearing : DCFPBearing
        The bearing of every position; its axial load becomes the position's share of the
        weight (:class:`~structures.isolated_building.IsolatedShearBuilding`).
    motion : GroundMotion or GroundMotionPair
        Ground acceleration [m/s^2] (scale it first with ``motion.scaled``): one record in one
        direction; in plan a pair (x and y of the plan, optionally a vertical z, positive up).
    integrator : {"newmark", "hht"} or Newmark or HHT
        Time integration method (default Newmark average acceleration).
    n_bearings : int, optional
        Identical bearings sharing the weight in one direction (default 1); in plan, the
        plan's positions (leave it out).
    dt : float, optional
        Analysis step [s], at most the record's (a finer one interpolates the record linearly);
        default :func:`default_step`.
    tolerance, max_subdivisions
        Passed to :func:`structures.integrators.integrate`.
    engine : {"auto", "compiled", "reference"}
        ``"reference"`` (:func:`reference_history`), ``"compiled"``, or ``"auto"`` (default):
        the compiled engine whenever numba is available and supports the configuration.
    floor_spectra : bool
        Add the 5 %-damped floor and ground spectra
        (:func:`structures.floor_spectra.with_floor_spectra`).
    time_limit : float, optional
        Wall-clock limit of the integration [s], compilation not counted (default none): past
        it the run fails, ``"timeout"``, checked after every step (reference) or every
        ``CHUNK_STEPS`` steps (compiled).
    max_steps : int
        Most time steps (default 2,000,000, :mod:`isolator.limits`): a longer run, or one too
        large for memory, is refused first (:func:`structures.limits.check_run`).
    overturning : bool
        In plan, load the bearings with the overturning moment of the floors' inertia forces
        (needs the plan's ``storey_heights``). Default True.
    grid_orientation : float, optional
        The precise model's monitor grid orientation in plan [deg] (None: follows the motion).

    Returns
    -------
    xarray.Dataset
        :func:`structures.results.response_dataset`, with ``attrs`` describing the model and
        the run (``success``, ``message``, ``energy_balance_error``, ``engine``...). A run
        that fails (a bearing beyond its ``displacement_capacity`` or outside the precise
        model's monitor points, no convergence, the ``time_limit``) ends there, for every
        friction model and both engines: see the Notes of ``response_dataset``.
    """
    pair = check_motion(building, motion, "run")
    if dt is not None:
        check_real(dt, "dt", "run", low=0.0, low_open=True)
    check_length(building, motion, dt, max_steps=max_steps)
    model = IsolatedShearBuilding(building, bearing, n_bearings, overturning=overturning,
                                  vertical=motion.z if pair else None,
                                  grid_orientation=grid_orientation)
    acceleration, step = ground_record(motion, dt)
    method = as_method(integrator, "integrator", "run")
    options = {"tolerance": tolerance, "max_subdivisions": max_subdivisions,
               "time_limit": time_limit}
    if select_engine(engine, model, method) == "compiled":
        history = compiled_history(model, acceleration, step, method, **options)
    else:
        history = reference_history(model, acceleration, step, method, **options)
    dataset = history_dataset(model, motion, step, acceleration, history)
    if floor_spectra:
        from structures.floor_spectra import with_floor_spectra

        dataset = with_floor_spectra(dataset, motion)
    return dataset


def _uplift_peaks(result) -> dict[str, Any]:
    """The lift-off keys of :func:`peaks`, from the Dataset's ``axial_load`` (time, bearing)."""
    record = uplift_record(result["axial_load"].values, float(result.attrs["dt"]))
    steps = np.asarray(record["uplift_steps"])
    first = np.asarray(record["uplift_first_time"])
    return {"uplift_bearings": int((steps > 0).sum()), "uplift_steps": int(steps.max()),
            "uplift_first_time": float(first[steps > 0].min()) if (steps > 0).any() else None,
            "uplift_longest": float(max(record["uplift_longest"]))}


def peaks(result) -> dict[str, Any]:
    """Peak responses of a run [SI units] and its bookkeeping, over the histories the Dataset
    holds (for a failed run, up to the failure).

    Returns
    -------
    dict
        ``peak_isolator_displacement`` [m] (resultant, any bearing), ``peak_base_shear`` [N]
        (resultant), ``max_temperature`` [degC] (contact, any bearing); in one direction
        ``peak_roof_acceleration`` [m/s^2] (absolute) and ``peak_storey_drift`` [m]; in plan
        ``peak_roof_acceleration_x``/``_y``, ``peak_storey_drift_x``/``_y``,
        ``peak_centre_displacement`` [m] (the base slab at the reference point),
        ``corner_bearing`` (index of the bearing of largest displacement) and
        ``peak_base_rotation`` [rad]; then ``energy_balance_error``, ``steps``, ``wall_time``
        [s], ``peaks_up_to_failure`` (bool), ``failed_at`` [s] (None for a run that finished)
        and ``failure`` (its kind, ``""`` for none); last, the lift-off of the bearings (zero
        or negative axial load: no contact, friction or restoring force): ``uplift_bearings``
        (the positions lifted at least once), ``uplift_steps`` (the most steps lifted at one
        position), ``uplift_first_time`` [s] (the first, None if none) and ``uplift_longest``
        [s] (the longest lift-off).
    """
    check_dataset(result, "result", "peaks")
    reach = resultant(result["bearing_displacement"].values).max(axis=0)
    roof = np.abs(result["absolute_acceleration"].isel(floor=-1).values).max(axis=0)
    drift = np.abs(result["storey_drift"].values).max(axis=(0, 1))
    values: dict[str, Any] = {"peak_isolator_displacement": float(reach.max())}
    base_shear = float(resultant(result["base_shear"].values).max())
    if result.sizes["direction"] == 1:
        values |= {"peak_base_shear": base_shear, "peak_roof_acceleration": float(roof[0]),
                   "peak_storey_drift": float(drift[0])}
    else:
        values |= {
            "peak_centre_displacement": float(
                resultant(result["displacement"].isel(floor=0).values).max()),
            "corner_bearing": int(np.argmax(reach)),
            "peak_base_shear": base_shear,
            "peak_roof_acceleration_x": float(roof[0]),
            "peak_roof_acceleration_y": float(roof[1]),
            "peak_storey_drift_x": float(drift[0]),
            "peak_storey_drift_y": float(drift[1]),
            "peak_base_rotation": float(np.abs(result["rotation"].isel(floor=0).values).max()),
        }
    values["max_temperature"] = float(result["temperature"].max())
    failed = not result.attrs["success"]
    failed_at = result.attrs.get("failed_at")
    return values | {
        "energy_balance_error": float(result.attrs["energy_balance_error"]),
        "steps": int(result.attrs["steps"]),
        "wall_time": float(result.attrs["wall_time"]),
        "peaks_up_to_failure": failed,
        "failed_at": float(failed_at) if failed and failed_at is not None else None,
        "failure": str(result.attrs.get("failure", "error" if failed else "")),
    } | _uplift_peaks(result)


SLIDING_SPEED = 0.01
"""Speed of a bearing [m/s] above which it counts as sliding for the friction coefficient's
range of :func:`design_peaks` (a package convention, not from a standard: below it the slider
is at a reversal or at rest, where mu of the velocity-dependent models drops toward its static
value and says nothing of the range seen while sliding)."""


DESIGN_PEAKS = (
    "isolator_displacement", "centre_displacement", "corner_displacement",
    "corner_centre_ratio", "isolator_displacement_x", "isolator_displacement_y",
    "base_shear_x", "base_shear_y", "storey_shear_x", "storey_shear_y", "max_drift_ratio_x",
    "max_drift_ratio_y", "roof_acceleration_x", "roof_acceleration_y", "axial_load_max",
    "axial_load_min", "max_temperature", "mu_min", "mu_max")
"""The keys of :func:`design_peaks` besides the per-storey drift ratios (those of
:data:`structures.design.result.PEAK_UNITS`)."""


def design_peaks(result, storey_heights: Any = None) -> dict[str, Any]:
    """The peaks a design analysis checks (ASCE 7-16 Chapter 17,
    :mod:`structures.design`), of a run in plan or in one direction [SI units].

    Parameters
    ----------
    result : xarray.Dataset
        A run's result (:func:`run`).
    storey_heights : float or array_like, optional
        Storey heights [m], one for all or one per storey: the drift ratios need them (without
        them those keys are NaN).

    Returns
    -------
    dict
        ``isolator_displacement`` (the largest resultant of any bearing), ``centre_displacement``
        (the base slab's resultant at the reference point), ``corner_displacement`` (the
        largest resultant of the bearing farthest from the reference point; of several as
        far, the one that moved most), ``corner_centre_ratio``,
        ``isolator_displacement_x``/``_y`` (the largest |u_x|, |u_y| of any bearing),
        ``base_shear_x``/``_y`` (through the isolation level), ``storey_shear_x``/``_y`` (the
        first storey), ``max_drift_ratio_x``/``_y`` and ``drift_ratio_x_k``/``drift_ratio_y_k``
        per storey k = 1..n (storey drift at the reference point / storey height),
        ``roof_acceleration_x``/``_y`` (absolute), ``axial_load_max`` and ``axial_load_min``
        (one bearing's, over every bearing: <= 0 is uplift), ``max_temperature`` (contact),
        ``mu_min`` and ``mu_max`` (the friction coefficient while sliding, faster than
        :data:`SLIDING_SPEED` and loaded; NaN if never). A run in one direction has NaN for the
        y keys. The time coordinate is the analysis step's; keys in
        :data:`structures.design.result.PEAK_UNITS`.
    """
    check_dataset(result, "result", "design_peaks")
    n = result.sizes["storey"]
    two = result.sizes["direction"] == 2
    u = result["bearing_displacement"].values
    reach = resultant(u).max(axis=0)
    centre = resultant(result["displacement"].isel(floor=0).values)
    distance = np.hypot(result["bearing_x"].values, result["bearing_y"].values)
    farthest = distance >= distance.max() * (1.0 - 1e-9)  # the corners (ties: the largest)
    corner = int(np.flatnonzero(farthest)[np.argmax(reach[farthest])])
    nan = float("nan")

    def per(values: np.ndarray) -> tuple[float, float]:
        peak = np.abs(values).max(axis=0) if values.size else np.full(2, np.nan)
        return float(peak[0]), float(peak[1]) if two else nan

    out: dict[str, Any] = {
        "isolator_displacement": float(reach.max()),
        "centre_displacement": float(centre.max()),
        "corner_displacement": float(reach[corner]),
    }
    out["corner_centre_ratio"] = (out["corner_displacement"] / out["centre_displacement"]
                                  if out["centre_displacement"] > 0 else nan)
    peak_u = np.abs(u).max(axis=(0, 1))
    out["isolator_displacement_x"] = float(peak_u[0])
    out["isolator_displacement_y"] = float(peak_u[1]) if two else nan
    out["base_shear_x"], out["base_shear_y"] = per(result["base_shear"].values)
    out["storey_shear_x"], out["storey_shear_y"] = per(
        result["storey_shear"].isel(storey=0).values)
    drift = np.abs(result["storey_drift"].values).max(axis=0)  # (storey, direction)
    if storey_heights is None:
        heights = np.full(n, np.nan)
    else:
        heights = np.broadcast_to(np.asarray(storey_heights, dtype=float).ravel(), (n,)) \
            if np.size(storey_heights) == 1 else np.asarray(storey_heights, dtype=float)
        if heights.shape != (n,):
            raise InputError(f"The 'storey_heights' parameter of design_peaks must hold one "
                             f"value or one per storey ({n}). Got {heights.size} instead.")
    for d, name in enumerate(("x", "y")):
        ratios = drift[:, d] / heights if (d == 0 or two) else np.full(n, np.nan)
        out[f"max_drift_ratio_{name}"] = float(np.max(ratios))
        for k in range(n):
            out[f"drift_ratio_{name}_{k + 1}"] = float(ratios[k])
    out["roof_acceleration_x"], out["roof_acceleration_y"] = per(
        result["absolute_acceleration"].isel(floor=-1).values)
    axial = result["axial_load"].values
    out["axial_load_max"] = float(axial.max())
    out["axial_load_min"] = float(axial.min())
    out["max_temperature"] = float(result["temperature"].max())
    dt = float(result.attrs["dt"])
    mu = result["mu"].values
    if u.shape[0] > 1:
        speed = resultant(np.diff(u, axis=0)) / dt  # (time - 1, bearing)
        sliding = (speed > SLIDING_SPEED) & (axial[1:] > 0.0)
        values = mu[1:][sliding]
    else:
        values = np.empty(0)
    out["mu_min"] = float(values.min()) if values.size else nan
    out["mu_max"] = float(values.max()) if values.size else nan
    return out
