"""Our building analysis side by side with OpenSees: which bearing, both runs, the differences.

The friction models compared (``model``), each as the OpenSees element that represents it:

``"constant"``
    The building file's constant model (Eq. 8) as ``frictionModel Coulomb``.
``"velocity"``
    The building file's Eq. 7 without heating: mu_t0 gamma(p) alpha(v) beta(T_0) with the
    paper's factors, velocity dependent only (constant pressure), as ``VelDependent``.
``"ptv"``
    Eq. 7 with Kumar's factors (``KumarFactors()``) shaped as FPBearingPTV models it
    (:func:`~structures.opensees.bearing.fpbearingptv_equivalent`: one surface heated at its
    centre while |u| < sqrt(pi)/2 r, spherical restoring law), as ``FPBearingPTV``.

Differences are those of OpenSees from ours, relative to ours:

- relative peak difference ``max|x_OS| / max|x_ours| - 1``;
- normalised RMS difference ``NRMSE = sqrt(mean((x_OS - x_ours)^2)) / max|x_ours|``, over
  the common time samples (the two runs share their time grid);

for the isolator displacement, the base shear and the roof's absolute acceleration, and the
largest gap of the contact temperature [degC]. ``wall_time_ratio`` is our wall time over
OpenSees's (each run's ``wall_time`` attribute: the integration with its recording, model
building included for OpenSees; :func:`run_comparison` warms our engine up first, so that a
compiled engine's one-off compilation is not counted).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, NamedTuple

import numpy as np

from dcfpb.common.validation import check_choice
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from isolator.factors import KumarFactors
from isolator.friction import ConstantFriction, PTVFriction
from structures.analysis import peaks, run
from structures.integrators import HHT, Newmark
from structures.opensees.building import run_opensees
from structures.opensees.equivalents import fpbearingptv_equivalent

__all__ = ["COMPARED", "MODELS", "Comparison", "compare", "comparison_bearing", "nrmse",
           "run_comparison", "shaped_bearing"]

MODELS = ("constant", "velocity", "ptv")
COMPARED = {
    "isolator_displacement": lambda ds: ds["isolator_displacement"].values,
    "base_shear": lambda ds: ds["base_shear"].values,
    "roof_acceleration": lambda ds: ds["absolute_acceleration"].isel(floor=-1).values,
}
"""The histories compared, each read from a result Dataset."""


class Comparison(NamedTuple):
    """Both runs and their differences.

    Attributes
    ----------
    ours, opensees : xarray.Dataset
        Results of :func:`structures.analysis.run` and
        :func:`structures.opensees.building.run_opensees`.
    summary : dict
        :func:`compare` of the two (JSON-ready).
    """

    ours: Any
    opensees: Any
    summary: dict[str, Any]


def shaped_bearing(bearing: DCFPBearing, model: str) -> DCFPBearing:
    """``bearing`` with the friction model ``model`` that an OpenSees element represents.

    Parameters
    ----------
    bearing : DCFPBearing
        A bearing with ConstantFriction for ``"constant"``, with PTVFriction (its mu_t0,
        dependencies and thermal properties are kept) for ``"velocity"`` and ``"ptv"``.
    model : {"constant", "velocity", "ptv"}
        See the module docstring.

    Raises
    ------
    ValueError
        If the bearing's friction is of the other family.
    """
    owner = "shaped_bearing"
    model = check_choice(model, "model", owner, MODELS)
    friction = bearing.friction
    wanted = ConstantFriction if model == "constant" else PTVFriction
    if not isinstance(friction, wanted):
        raise ValueError(f"The 'bearing' parameter of {owner} must have a {wanted.__name__} for "
                         f"model {model!r}. Got {friction!r} instead.")
    if model == "constant":
        return bearing
    if model == "velocity":
        return replace(bearing, friction=replace(friction, heating=None))
    return fpbearingptv_equivalent(replace(bearing, friction=replace(friction,
                                                                     factors=KumarFactors())))


def comparison_bearing(config, model: str) -> DCFPBearing:
    """The bearing of a building file for ``model``.

    Parameters
    ----------
    config : BuildingConfig
        A building file read by :func:`structures.config.load_config`.
    model : {"constant", "velocity", "ptv"}
        See the module docstring.

    Returns
    -------
    DCFPBearing
        The file's constant model, or its simplified model (mu_t0, thermal properties)
        reshaped by :func:`shaped_bearing`; loaded by W / count as the file's bearings.
    """
    model = check_choice(model, "model", "comparison_bearing", MODELS)
    return shaped_bearing(config.bearing("constant" if model == "constant" else "simplified"),
                          model)


def nrmse(reference: np.ndarray, other: np.ndarray) -> float:
    """``sqrt(mean((other - reference)^2)) / max|reference|`` over common samples [-].

    Raises
    ------
    ValueError
        If the histories differ in length.
    """
    reference, other = np.asarray(reference, dtype=float), np.asarray(other, dtype=float)
    if reference.shape != other.shape:
        raise ValueError(f"The histories compared by nrmse must have one length. Got "
                         f"{reference.shape} and {other.shape} instead.")
    scale = float(np.max(np.abs(reference)))
    rms = float(np.sqrt(np.mean((other - reference) ** 2)))
    return rms / scale if scale > 0.0 else rms


def compare(ours, opensees) -> dict[str, Any]:
    """Peaks of both runs, their differences and the wall-time ratio (JSON-ready).

    Returns
    -------
    dict
        ``{"ours": peaks, "opensees": peaks, "difference": {...}, "wall_time_ratio": r}``
        with ``difference`` holding ``peak_<name>`` (relative peak difference) and
        ``nrmse_<name>`` for each history of :data:`COMPARED`, and ``max_temperature_gap``
        [degC]; the runs are cut to their common length.
    """
    if not np.allclose(ours["time"].values[:2], opensees["time"].values[:2]):
        raise ValueError("The runs compared must share their time step. Got "
                         f"{ours.attrs['dt']!r} s and {opensees.attrs['dt']!r} s instead.")
    n = min(ours.sizes["time"], opensees.sizes["time"])
    a, b = ours.isel(time=slice(0, n)), opensees.isel(time=slice(0, n))
    difference: dict[str, float] = {}
    for name, read in COMPARED.items():
        x, y = read(a), read(b)
        difference[f"peak_{name}"] = float(np.max(np.abs(y)) / np.max(np.abs(x)) - 1.0)
    for name, read in COMPARED.items():
        difference[f"nrmse_{name}"] = nrmse(read(a), read(b))
    gap = np.abs(b["temperature"].values - a["temperature"].values)
    difference["max_temperature_gap"] = float(np.nanmax(gap))
    summary = {"ours": peaks(ours), "opensees": peaks(opensees), "difference": difference}
    for side, ds in (("ours", ours), ("opensees", opensees)):
        summary[side].update(success=bool(ds.attrs["success"]), message=ds.attrs["message"])
    summary["opensees"]["element"] = opensees.attrs["element"]
    summary["wall_time_ratio"] = ours.attrs["wall_time"] / opensees.attrs["wall_time"]
    return summary


def run_comparison(
    building,
    bearing: DCFPBearing,
    motion: GroundMotion,
    integrator: str | Newmark | HHT = "newmark",
    *,
    n_bearings: int = 1,
    dt: float | None = None,
    pendulum: str = "singlefp",
    warm_up: bool = True,
    **run_options: Any,
) -> Comparison:
    """Run ``bearing`` (already shaped, see :func:`shaped_bearing`) under the building both
    ways and compare.

    Parameters
    ----------
    building, bearing, motion, integrator, n_bearings, dt
        As :func:`structures.analysis.run`.
    pendulum : {"singlefp", "spring"}
        As :func:`structures.opensees.building.run_opensees`.
    warm_up : bool
        Run ours first on the record's first 3 samples, so that the timed run does not
        include a one-off compilation of a compiled engine.
    **run_options
        Passed to :func:`structures.analysis.run` only (e.g. ``tolerance``).
    """
    if warm_up and motion.npts >= 3:
        run(building, bearing, motion.truncated(2 * motion.dt), integrator,
            n_bearings=n_bearings, **run_options)
    ours = run(building, bearing, motion, integrator, n_bearings=n_bearings, dt=dt,
               **run_options)
    opensees = run_opensees(building, bearing, motion, integrator, n_bearings=n_bearings, dt=dt,
                            pendulum=pendulum)
    return Comparison(ours, opensees, compare(ours, opensees))
