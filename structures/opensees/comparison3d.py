"""The building in plan side by side with OpenSees 3D: both runs, the differences, the times.

:func:`run_comparison_3d` runs :func:`structures.spatial.analysis.run_spatial` (ours, the
reference engine) and :func:`structures.opensees.building3d.run_opensees_3d` on the same
building, bearing, pair, integrator and step; :func:`compare_3d` measures them. Ours runs
without the overturning of the floors' inertia forces unless asked (the OpenSees model has
zero-length storeys and none); with ``overturning=True`` the gap it makes is measured too.

Measures, OpenSees's relative to ours (the histories over their common samples):

- **peak** ``max|x_OS| / max|x_ours| - 1`` of the peaks of
  :func:`structures.spatial.peaks.plan_peaks` (those of ``dcfpb run``): resultants
  ``|x| = hypot(x_x, x_y)`` of the isolator displacement (the largest of any bearing), of
  the base slab at the centre of stiffness (``centre``) and of the corner bearing (ours's
  largest, the same bearing in both runs), and of the base shear; the roof's absolute
  acceleration and the storey drift per direction; the base slab's rotation;
- **NRMSE** ``sqrt(mean((x_OS - x_ours)^2)) / max|x_ours|`` of each component: the
  isolator displacement x and y (the largest over the bearings, the corner bearing's), the
  centre's, the base slab's rotation, the base shear x and y, the roof acceleration x and
  y.

``wall_time_ratio`` is our wall time over OpenSees's (each Dataset's ``wall_time``: the
integration with its recording; for OpenSees model building included).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from groundmotions.pairs import GroundMotionPair
from isolator.bearing import DCFPBearing
from structures.integrators import HHT, Newmark
from structures.opensees.building3d import run_opensees_3d
from structures.opensees.comparison import nrmse
from structures.spatial.analysis import run_spatial
from structures.spatial.building import SpatialBuilding
from structures.spatial.peaks import plan_peaks

__all__ = ["SpatialComparison", "compare_3d", "run_comparison_3d"]

_DIRECTIONS = ("x", "y")
_COMPARED_PEAKS = ("peak_isolator_displacement", "peak_centre_displacement",
                   "peak_corner_displacement", "peak_base_shear", "peak_roof_acceleration_x",
                   "peak_roof_acceleration_y", "peak_storey_drift_x", "peak_storey_drift_y",
                   "peak_base_rotation")


class SpatialComparison(NamedTuple):
    """Both runs and their differences.

    Attributes
    ----------
    ours, opensees : xarray.Dataset
        Results of :func:`~structures.spatial.analysis.run_spatial` and
        :func:`~structures.opensees.building3d.run_opensees_3d`: per-bearing
        (``bearing_displacement``, ``bearing_force``, ``axial_load``, ...) and per-floor
        (``displacement``, ``rotation``, ``absolute_acceleration``, ...) histories.
    summary : dict
        :func:`compare_3d` of the two (JSON-ready).
    """

    ours: Any
    opensees: Any
    summary: dict[str, Any]


def _peaks(ds, corner: int) -> dict[str, Any]:
    """:func:`~structures.spatial.peaks.plan_peaks` with the resultant displacement of
    bearing ``corner`` besides (``peak_corner_displacement`` [m])."""
    out = plan_peaks(ds)
    reach = np.hypot(*np.moveaxis(ds["bearing_displacement"].values[:, corner], -1, 0))
    out["peak_corner_displacement"] = float(reach.max())
    out["success"], out["message"] = bool(ds.attrs["success"]), str(ds.attrs["message"])
    return out


def compare_3d(ours, opensees) -> dict[str, Any]:
    """Peaks of both runs, their differences (module docstring) and the wall-time ratio.

    Returns
    -------
    dict
        ``{"ours": peaks, "opensees": peaks, "difference": {...}, "corner_bearing": i,
        "wall_time_ratio": r}``: the peaks of
        :func:`~structures.spatial.peaks.plan_peaks` with ``peak_corner_displacement`` (the
        bearing ``corner_bearing``, ours's largest), ``success`` and ``message``;
        ``difference`` holds ``peak_<name>`` (relative) and ``nrmse_<history>_<component>``.

    Raises
    ------
    ValueError
        If the runs do not share their time step or their bearings.
    """
    if not np.allclose(ours["time"].values[:2], opensees["time"].values[:2]):
        raise ValueError("The runs compared by compare_3d must share their time step. Got "
                         f"{ours.attrs['dt']!r} s and {opensees.attrs['dt']!r} s instead.")
    if not (np.array_equal(ours["bearing_x"].values, opensees["bearing_x"].values)
            and np.array_equal(ours["bearing_y"].values, opensees["bearing_y"].values)):
        raise ValueError("The runs compared by compare_3d must have the same bearings.")
    n = min(ours.sizes["time"], opensees.sizes["time"])
    a, b = ours.isel(time=slice(0, n)), opensees.isel(time=slice(0, n))
    corner = plan_peaks(a)["corner_bearing"]
    pa, pb = _peaks(a, corner), _peaks(b, corner)
    difference: dict[str, float] = {
        key: pb[key] / pa[key] - 1.0 if pa[key] > 0.0 else float(pb[key] - pa[key])
        for key in _COMPARED_PEAKS}
    ua, ub = a["bearing_displacement"].values, b["bearing_displacement"].values
    centre = (a["displacement"].values[:, 0], b["displacement"].values[:, 0])
    for k, d in enumerate(_DIRECTIONS):
        difference[f"nrmse_isolator_displacement_{d}"] = max(
            nrmse(ua[:, i, k], ub[:, i, k]) for i in range(ua.shape[1]))
        difference[f"nrmse_corner_displacement_{d}"] = nrmse(ua[:, corner, k],
                                                             ub[:, corner, k])
        difference[f"nrmse_centre_displacement_{d}"] = nrmse(centre[0][:, k], centre[1][:, k])
    difference["nrmse_base_rotation"] = nrmse(a["rotation"].values[:, 0],
                                              b["rotation"].values[:, 0])
    for k, d in enumerate(_DIRECTIONS):
        difference[f"nrmse_base_shear_{d}"] = nrmse(a["base_shear"].values[:, k],
                                                    b["base_shear"].values[:, k])
        difference[f"nrmse_roof_acceleration_{d}"] = nrmse(
            a["absolute_acceleration"].values[:, -1, k],
            b["absolute_acceleration"].values[:, -1, k])
    summary = {"ours": _peaks(ours, corner), "opensees": _peaks(opensees, corner),
               "difference": difference, "corner_bearing": corner}
    summary["ours"]["overturning"] = bool(ours.attrs["overturning"])
    summary["opensees"]["element"] = opensees.attrs["element"]
    summary["wall_time_ratio"] = ours.attrs["wall_time"] / opensees.attrs["wall_time"]
    return summary


def run_comparison_3d(
    building: SpatialBuilding,
    bearing: DCFPBearing,
    motion: GroundMotionPair,
    integrator: str | Newmark | HHT = "newmark",
    *,
    dt: float | None = None,
    pendulum: str = "singlefp",
    overturning: bool = False,
    **run_options: Any,
) -> SpatialComparison:
    """Run the building in plan both ways and compare.

    Parameters
    ----------
    building : SpatialBuilding
        The building and its plan (Rayleigh damping).
    bearing : DCFPBearing
        The bearing of every position (ConstantFriction, linear law); each carries its
        gravity share.
    motion : GroundMotionPair
        x, y and optionally z [m/s^2].
    integrator, dt
        As :func:`~structures.spatial.analysis.run_spatial`.
    pendulum : {"singlefp", "spring"}
        As :func:`~structures.opensees.building3d.run_opensees_3d`.
    overturning : bool
        Run ours with the overturning of the floors' inertia forces (OpenSees has none, so
        the comparison then measures it too). Default False.
    **run_options
        Passed to :func:`~structures.spatial.analysis.run_spatial` only (``tolerance``,
        ``max_steps``, ...).
    """
    import dataclasses

    bearing = dataclasses.replace(bearing, axial_load=None)  # each takes its gravity share
    ours = run_spatial(building, bearing, motion, integrator, overturning=overturning, dt=dt,
                       **run_options)
    opensees = run_opensees_3d(building, bearing, motion, integrator, dt=dt,
                               pendulum=pendulum)
    return SpatialComparison(ours, opensees, compare_3d(ours, opensees))
