"""Floor response spectra: what the contents of each floor feel, beside what the ground does.

:func:`with_floor_spectra` adds to a run's Dataset (:func:`structures.analysis.run` or
:func:`structures.fixed_base.run_fixed_base`) the 5 %-damped pseudo-acceleration spectra of each
floor's absolute acceleration and of the record, by the exact recurrence of
:mod:`groundmotions.spectra`. At period 0 a spectrum is the peak absolute acceleration (peak
floor acceleration, or PGA); peaks are taken at the samples, so for periods below a few time
steps a spectrum can miss a peak between them.
"""

from __future__ import annotations

import numpy as np

from dcfpb.common.validation import check_dataset
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from groundmotions.spectra import response_spectra, spectrum

__all__ = ["FLOOR_SPECTRUM_DAMPING", "FLOOR_SPECTRUM_PERIODS", "floor_spectra",
           "with_floor_spectra", "with_floor_spectra_all"]

FLOOR_SPECTRUM_PERIODS = np.concatenate(([0.0], np.geomspace(0.02, 5.0, 64)))
"""Default periods of the floor spectra [s]: 0 (peak acceleration), then 0.02 to 5 s."""

FLOOR_SPECTRUM_DAMPING = 0.05
"""Damping ratio of the floor spectra [-] (the usual 5 %)."""


def _histories(result) -> np.ndarray:
    """Every floor's absolute acceleration per direction as columns (time, floor * direction)."""
    acceleration = np.asarray(result["absolute_acceleration"].transpose("time", "floor",
                                                                          "direction"))
    return acceleration.reshape(acceleration.shape[0], -1)


def _spectra(histories: np.ndarray, step: float, periods: np.ndarray,
             damping: float) -> np.ndarray:
    """Sa [m/s^2] of the columns of ``histories`` (time, column), shape (columns, periods); NaN
    for a history of fewer than two samples (a run that failed at its first step), which has no
    spectrum."""
    histories = np.asarray(histories, dtype=float)
    if histories.shape[0] < 2:
        columns = histories.shape[1] if histories.ndim > 1 else 1
        return np.full((columns, np.size(periods)), np.nan)
    return response_spectra(histories, step, periods, damping).sa


def floor_spectra(result, periods: np.ndarray = FLOOR_SPECTRUM_PERIODS,
                  damping: float = FLOOR_SPECTRUM_DAMPING) -> np.ndarray:
    """Pseudo-acceleration spectra Sa [m/s^2] of every floor's absolute acceleration in each
    direction, shape (floors, directions, len(periods)), floor 0 first, of a run with
    ``absolute_acceleration`` (time, floor, direction) and the attribute ``dt`` [s], at
    ``periods`` >= 0 [s] and the damping ratio ``damping`` in [0, 1) [-]."""
    sa = _spectra(_histories(result), float(result.attrs["dt"]), periods, damping)
    return sa.reshape(result.sizes["floor"], result.sizes["direction"], -1)


def with_floor_spectra(result, motion: GroundMotion | GroundMotionPair | None = None, *,
                       periods: np.ndarray = FLOOR_SPECTRUM_PERIODS,
                       damping: float = FLOOR_SPECTRUM_DAMPING):
    """The run's Dataset with its floor spectra and the ground's spectrum added.

    Parameters
    ----------
    result : xarray.Dataset
        A run (``absolute_acceleration``, ``ground_acceleration``, attribute ``dt``).
    motion : GroundMotion or GroundMotionPair, optional
        The record(s) of the run, scaled as they were: their spectra, on the record's own step
        (as ``dcfpb spectrum`` gives them), are ``ground_spectrum``; without them, the run's
        ``ground_acceleration`` (on the run's step) serves.
    periods, damping : array_like, float
        Periods of the spectra, >= 0 [s], and their damping ratio in [0, 1) [-].

    Returns
    -------
    xarray.Dataset
        A new Dataset with the coordinate ``period`` [s], the variables ``floor_spectrum``
        (floor, direction, period) and ``ground_spectrum`` (direction, period) [m/s^2] and the
        attribute ``spectrum_damping``.
    """
    check_dataset(result, "result", "with_floor_spectra")
    return with_floor_spectra_all({"run": result}, motion, periods=periods,
                                  damping=damping)["run"]


def with_floor_spectra_all(results: dict, motion: GroundMotion | GroundMotionPair | None = None,
                           *, periods: np.ndarray = FLOOR_SPECTRUM_PERIODS,
                           damping: float = FLOOR_SPECTRUM_DAMPING) -> dict:
    """:func:`with_floor_spectra` of several runs of one motion, keyed alike, the runs of one time
    step and length through the spectrum code in one pass."""
    periods = np.atleast_1d(np.asarray(periods, dtype=float))
    groups: dict[tuple[float, int], list] = {}
    for key, result in results.items():
        groups.setdefault((float(result.attrs["dt"]), result.sizes["time"]), []).append(key)
    floors = {}
    for (step, _), keys in groups.items():
        stacked = np.hstack([_histories(results[k]) for k in keys])
        sa = _spectra(stacked, step, periods, damping)
        starts = np.cumsum([0] + [results[k].sizes["floor"] * results[k].sizes["direction"]
                                  for k in keys])
        floors.update({k: sa[starts[i]:starts[i + 1]].reshape(
            results[k].sizes["floor"], results[k].sizes["direction"], -1)
            for i, k in enumerate(keys)})
    ground_cache: dict[str, np.ndarray] = {}
    return {key: _with(result, floors[key], motion, periods, damping, ground_cache)
            for key, result in results.items()}


def _with(result, floors: np.ndarray, motion: GroundMotion | GroundMotionPair | None,
          periods: np.ndarray, damping: float, ground_cache: dict):
    """``result`` with its floor spectra ``floors`` and the ground's spectra added."""
    if motion is not None:
        if "record" not in ground_cache:
            components = (motion.x, motion.y) if isinstance(motion, GroundMotionPair) else (
                motion,)
            ground_cache["record"] = np.array([spectrum(m, periods, damping).sa
                                               for m in components])
        ground = ground_cache["record"]
        source = f"the record {motion.name} as read (dt = {motion.dt:g} s)"
    else:
        ground = _spectra(np.asarray(result["ground_acceleration"]),
                          float(result.attrs["dt"]), periods, damping)
        source = "the run's ground acceleration"
    percent = f"{100 * damping:g} %"
    added = result.assign_coords(period=("period", periods, {"units": "s"})).assign(
        floor_spectrum=(("floor", "direction", "period"), floors, {
            "units": "m/s^2",
            "long_name": f"{percent}-damped pseudo-spectral acceleration of the floor's "
                         "absolute acceleration (period 0: peak floor acceleration)"}),
        ground_spectrum=(("direction", "period"), ground, {
            "units": "m/s^2",
            "long_name": f"{percent}-damped pseudo-spectral acceleration of {source}"}),
    )
    added.attrs["spectrum_damping"] = float(damping)
    return added
