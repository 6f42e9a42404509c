"""From a building response to the bearing-level histories the diagnosis reads, as a
shake-table test measures them at the isolation level (relative displacement, force), so that
:func:`isolator.diagnosis.diagnose` treats a computed response as a measured one.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from dcfpb.common.errors import InputError
from isolator.diagnosis import BearingRecord, Campaign

if TYPE_CHECKING:
    import xarray as xr


def bearing_records(result: xr.Dataset, *, name: str | None = None, per_bearing: bool = True,
                    velocity: bool = True) -> list[BearingRecord]:
    """The isolators' histories of a :func:`structures.analysis.run` result in one direction,
    as a list of one record (the bearings are identical: one stands for each).

    Parameters
    ----------
    result : xarray.Dataset
        A run in one direction (a run in plan raises an ``InputError``).
    name : str, optional
        Name of the record (default: the record name of the run).
    per_bearing : bool
        The force [N] and axial load [N] of one bearing (default), else of the isolation level.
    velocity : bool
        Pass the computed isolator velocity [m/s] as the measured one (default); False leaves
        the diagnosis to derive it.
    """
    if result.sizes["direction"] != 1:
        raise InputError("bearing_records reads a building in one direction: the diagnosis "
                         "takes histories along one axis. Got a run in plan.")
    count = int(result.attrs["n_bearings"])
    load = float(result.attrs["axial_load_per_bearing"]) * (1 if per_bearing else count)
    time = np.asarray(result["time"], dtype=float)
    displacement = np.asarray(result["bearing_displacement"][:, 0, 0], dtype=float)
    force = np.asarray(result["bearing_force"][:, 0, 0] if per_bearing
                       else result["base_shear"][:, 0], dtype=float)
    v = np.asarray(result["velocity"][:, 0, 0], dtype=float) if velocity else None
    label = name or str(result.attrs.get("record", "building response"))
    return [BearingRecord(label, time, displacement, force, np.full(time.size, load), v)]


def bearing_campaign(results: Sequence[xr.Dataset], **kwargs: object) -> Campaign:
    """A campaign of the bearing histories of building responses, in order, with the bearing
    geometry they share (``kwargs``: :func:`bearing_records`); a ``ValueError`` if none, or if
    their geometries differ."""
    results = list(results)
    if not results:
        raise InputError("bearing_campaign needs at least one building response.")
    radius = float(results[0].attrs["effective_radius"])
    diameter = float(results[0].attrs["slider_diameter"])
    for r in results[1:]:
        if (float(r.attrs["effective_radius"]), float(r.attrs["slider_diameter"])) != (
                radius, diameter):
            raise InputError("The building responses of one campaign must have the same "
                             "bearing geometry (effective radius and slider diameter).")
    records = [rec for r in results for rec in bearing_records(r, **kwargs)]
    return Campaign(tuple(records), radius, diameter)
