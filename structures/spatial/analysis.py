"""Time-history analysis of a building in plan on DCFPB isolators under a pair of records.

:func:`run_spatial` builds :class:`~structures.spatial.isolated.SpatialIsolatedBuilding`, integrates
it with Newmark or HHT-alpha (:func:`structures.integrators.integrate`, the ground acceleration
a vector (x, y) per step), records every bearing at each committed step and returns an
``xarray.Dataset`` with a ``direction`` dimension (:mod:`structures.spatial.results`). Its own
integration is the readable reference (plain numpy, one Python loop over the bearings per
Newton iteration); by default the same run goes to the compiled engine of
:mod:`structures.compiled` when numba is there (the same histories to about 1e-13; the
first run compiles it, once per environment), the engine of the planar
:func:`structures.analysis.run` too.
"""

from __future__ import annotations

import time as _time

import numpy as np

from dcfpb.common.errors import InputTypeError
from groundmotions.pairs import GroundMotionPair
from isolator.bearing import DCFPBearing
from structures.analysis import compile_kernels, default_step, resampled_record
from structures.compiled.engine import time_limit_error
from structures.integrators import HHT, IntegrationResult, Newmark, as_method, integrate
from structures.limits import DEFAULT_MAX_STEPS, check_run
from structures.spatial.building import SpatialBuilding
from structures.spatial.isolated import SpatialIsolatedBuilding
from structures.spatial.results import BEARING_RECORD, spatial_dataset

__all__ = ["run_spatial", "spatial_fields", "spatial_history"]


def spatial_fields(n_storeys: int, n_bearings: int) -> int:
    """Values a run in plan holds per step: the Dataset's and the integrator's, about
    ``3 (n + 1)`` per level history, ``12`` per bearing and a few scalars."""
    return 21 * (n_storeys + 1) + 6 * n_storeys + 12 * n_bearings + 24


def spatial_history(model: SpatialIsolatedBuilding, acceleration: np.ndarray, step: float,
                    integrator: str | Newmark | HHT, *, tolerance: float,
                    max_iterations: int = 25, max_subdivisions: int,
                    time_limit: float | None = None,
                    ) -> tuple[IntegrationResult, dict[str, np.ndarray], np.ndarray, float]:
    """Integrate the model, recording every bearing at each committed step.

    Parameters
    ----------
    model : SpatialIsolatedBuilding
        The building at rest.
    acceleration : numpy.ndarray
        Ground acceleration (x, y) on the analysis steps, shape (nt, 2) [m/s^2].
    step : float
        Analysis step [s].
    integrator, tolerance, max_iterations, max_subdivisions
        As :func:`structures.integrators.integrate`.
    time_limit : float, optional
        Wall-clock limit [s], checked after every step (the run then fails, ``"timeout"``).

    Returns
    -------
    tuple
        The :class:`~structures.integrators.IntegrationResult`, the bearings' histories
        (:data:`structures.spatial.results.BEARING_RECORD`, first axis time, second the
        bearing), the total restoring force (nt, n_dof) [N, N m] and the wall time [s].
    """
    nt, n_b = acceleration.shape[0], model.n_bearings
    record = {name: np.zeros((nt, n_b, *shape)) for name, shape in BEARING_RECORD.items()}
    restoring = np.zeros((nt, model.building.n_dof))
    deadline = np.inf

    def on_commit(k: int, t: float, u: np.ndarray, *_: np.ndarray) -> None:
        forces = np.empty((n_b, 2))
        for i, state in enumerate(model.committed_states()):
            for name in BEARING_RECORD:
                record[name][k, i] = getattr(state, name)
            forces[i] = state.force
        restoring[k] = model.superstructure_stiffness @ u
        restoring[k, :3] += np.einsum("bij,bi->j", np.asarray(model.transformations), forces)
        if _time.perf_counter() > deadline:  # ends the run, this step kept
            raise time_limit_error(time_limit, t)

    on_commit(0, 0.0, np.zeros(restoring.shape[1]))
    compile_kernels()
    start = _time.perf_counter()
    if time_limit is not None:
        deadline = start + time_limit
    result = integrate(model, acceleration, step, integrator, tolerance=tolerance,
                       max_iterations=max_iterations, max_subdivisions=max_subdivisions,
                       on_commit=on_commit)
    kept = result.time.size
    record = {name: values[:kept] for name, values in record.items()}
    return result, record, restoring[:kept], _time.perf_counter() - start


def run_spatial(
    building: SpatialBuilding,
    bearing: DCFPBearing,
    motion: GroundMotionPair,
    integrator: str | Newmark | HHT = "newmark",
    *,
    overturning: bool = True,
    dt: float | None = None,
    tolerance: float = 1e-8,
    max_subdivisions: int = 6,
    time_limit: float | None = None,
    max_steps: int = DEFAULT_MAX_STEPS,
    grid_orientation: float | None = None,
    engine: str = "auto",
):
    """Run a time-history analysis of a building in plan.

    Parameters
    ----------
    building : SpatialBuilding
        The building and its plan.
    bearing : DCFPBearing
        The bearing at every position (``axial_load=None``: each takes its gravity share).
    motion : GroundMotionPair
        Ground acceleration x, y and optionally z (positive up) [m/s^2]; the x and y of the
        pair are those of the plan.
    integrator : {"newmark", "hht"} or Newmark or HHT
        Time integration method (default Newmark average acceleration).
    overturning : bool
        Load the bearings with the overturning moment of the floors' inertia forces (needs
        the plan's ``storey_heights``). Default True.
    dt : float, optional
        Analysis step [s], at most the record's (finer steps interpolate the record
        linearly). Default: :func:`structures.analysis.default_step`.
    tolerance, max_subdivisions
        Passed to :func:`structures.integrators.integrate`.
    time_limit : float, optional
        Wall-clock limit of the integration [s]; past it the run fails (``"timeout"``).
    max_steps : int
        Most time steps the run may take (:func:`structures.limits.check_run`).
    grid_orientation : float, optional
        The precise model's monitor grid orientation [deg] (None: follows the motion).
    engine : {"reference", "compiled", "auto"}
        ``"reference"``: this module's integration on the model objects; ``"compiled"``: the
        numba engine of :mod:`structures.compiled`, the same histories to round-off;
        ``"auto"`` (the default): the compiled one when numba is there.

    Returns
    -------
    xarray.Dataset
        See :func:`structures.spatial.results.spatial_dataset`.
    """
    if not isinstance(motion, GroundMotionPair):
        raise InputTypeError(f"The 'motion' parameter of run_spatial must be a "
                             f"GroundMotionPair. Got {motion!r} instead.")
    if not isinstance(building, SpatialBuilding):
        raise InputTypeError(f"The 'building' parameter of run_spatial must be a "
                             f"SpatialBuilding. Got {building!r} instead.")
    check_run(motion.x, default_step(motion.dt) if dt is None else dt,
              spatial_fields(building.n_storeys, building.plan.n_bearings),
              max_steps=max_steps, raise_with="the max_steps argument of run_spatial",
              owner="run_spatial")
    model = SpatialIsolatedBuilding(building, bearing, overturning=overturning,
                                    vertical=motion.z, grid_orientation=grid_orientation)
    x, step = resampled_record(motion.x, dt)
    y, _ = resampled_record(motion.y, step)
    acceleration = np.column_stack([x, y])
    method = as_method(integrator)
    from structures.compiled.engine import bearing_fields, compiled_run, select_engine
    from structures.compiled.view import engine_view

    chosen = select_engine(engine, model, method, "run_spatial")
    plate = None
    if chosen == "compiled":
        run = compiled_run(engine_view(model), acceleration, step, method, tolerance=tolerance,
                           max_subdivisions=max_subdivisions, time_limit=time_limit)
        result, record, restoring = run.result, bearing_fields(run.record), run.restoring
        wall, plate = run.wall_time, run.plate
    else:
        result, record, restoring, wall = spatial_history(
            model, acceleration, step, method, tolerance=tolerance,
            max_subdivisions=max_subdivisions, time_limit=time_limit)
    attrs = {"newton_iterations": int(result.iterations.sum()),
             "subdivisions": int(result.subdivisions.sum()), "wall_time": wall,
             "engine": chosen}
    return spatial_dataset(model, motion, step, acceleration[:result.time.size], result,
                           record, restoring, attrs=attrs, plate=plate)
