"""The peaks of a run of a building in plan: resultant isolator displacement at the centre and
at the corner bearing, resultant base shear, roof acceleration and storey drift per direction,
the highest contact temperature, and the run's bookkeeping as :func:`structures.analysis.peaks`
gives it for a planar run."""

from __future__ import annotations

from typing import Any

import numpy as np

from structures.analysis import run_bookkeeping

__all__ = ["PLAN_PEAK_KEYS", "plan_peaks"]

PLAN_PEAK_KEYS = (
    "peak_isolator_displacement", "peak_centre_displacement", "corner_bearing",
    "peak_base_shear", "peak_roof_acceleration_x", "peak_roof_acceleration_y",
    "peak_storey_drift_x", "peak_storey_drift_y", "peak_base_rotation", "max_temperature",
    "energy_balance_error", "steps", "wall_time", "peaks_up_to_failure", "failed_at",
    "failure",
)
"""The keys of :func:`plan_peaks`, in order."""


def _resultant(values: np.ndarray) -> np.ndarray:
    """The length of the (x, y) vectors of the last axis."""
    return np.hypot(values[..., 0], values[..., 1])


def plan_peaks(result) -> dict[str, Any]:
    """Peak responses of a run in plan (SI units) and the run's bookkeeping.

    Parameters
    ----------
    result : xarray.Dataset
        :func:`structures.spatial.analysis.run_spatial`.

    Returns
    -------
    dict
        ``peak_isolator_displacement`` [m], the largest resultant displacement of any bearing
        (the corner bearing, ``corner_bearing`` its index); ``peak_centre_displacement`` [m],
        that of the base slab at the plan's reference point; ``peak_base_shear`` [N],
        resultant; ``peak_roof_acceleration_x``/``_y`` [m/s^2], absolute;
        ``peak_storey_drift_x``/``_y`` [m], over the storeys; ``peak_base_rotation`` [rad];
        ``max_temperature`` [degC], the highest contact temperature of any bearing; and as
        :func:`structures.analysis.peaks`: ``energy_balance_error``, ``steps``,
        ``wall_time``, ``peaks_up_to_failure``, ``failed_at``, ``failure``.
    """
    bearing_reach = _resultant(result["bearing_displacement"].values).max(axis=0)
    roof = np.abs(result["absolute_acceleration"].isel(floor=-1).values).max(axis=0)
    drift = np.abs(result["storey_drift"].values).max(axis=(0, 1))
    return {
        "peak_isolator_displacement": float(bearing_reach.max()),
        "peak_centre_displacement": float(
            _resultant(result["displacement"].isel(floor=0).values).max()),
        "corner_bearing": int(np.argmax(bearing_reach)),
        "peak_base_shear": float(_resultant(result["base_shear"].values).max()),
        "peak_roof_acceleration_x": float(roof[0]),
        "peak_roof_acceleration_y": float(roof[1]),
        "peak_storey_drift_x": float(drift[0]),
        "peak_storey_drift_y": float(drift[1]),
        "peak_base_rotation": float(np.abs(result["rotation"].isel(floor=0).values).max()),
        "max_temperature": float(result["temperature"].max()),
    } | run_bookkeeping(result)
