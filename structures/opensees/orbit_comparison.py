"""Our bidirectional element side by side with OpenSees 3D, one bearing under one orbit.

:func:`run_orbit_comparison` drives the same orbit through our element
(:func:`isolator.testrig.run_orbit`) and through the OpenSees 3D element
(:func:`structures.opensees.bearing3d.opensees_orbit`); :func:`compare_orbit_results`
measures the differences. Both runs share the orbit's samples, so the force histories (x, y)
are compared sample by sample. Differences are OpenSees's relative to ours:

- ``peak_resultant_force``: ``max|F_OS| / max|F_ours| - 1`` with ``|F| = hypot(F_x, F_y)``;
- ``nrmse_force_x``, ``nrmse_force_y``: ``sqrt(mean((F_OS,i - F_ours,i)^2)) / max|F_ours,i|``
  for each component (relative to our peak resultant instead where our component is zero,
  as across a line along an axis);
- ``largest_force_gap``: ``max |F_OS - F_ours|`` (vector) over our peak resultant;
- ``energy``: the work of the force over the orbit's closed blocks (the ``lead-in`` left out),
  ``sum of integral F . du``, which is the energy dissipated by the orbit, relative;
- ``max_temperature_gap`` [degC] where both sides have a temperature (FPBearingPTV), else None;
  left out are the samples where FPBearingPTV does not compute one (it holds 20 degC on its
  first two steps and wherever u is exactly at the centre, ``FPBearingPTV.cpp``).

``wall_time_ratio`` is our wall time over OpenSees's (model building included for OpenSees).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, NamedTuple

import numpy as np

from dcfpb.common.validation import check_choice
from isolator.bearing import DCFPBearing
from isolator.orbits import Orbit
from isolator.testrig import BearingTestResult, path_integral, run_orbit
from structures.opensees.bearing3d import ELEMENTS_3D, opensees_orbit, singlefp3d_normal_force

__all__ = ["OrbitComparison", "compare_orbit_results", "orbit_cycles", "run_orbit_comparison"]

_ZERO_COMPONENT = 1.0e-9  # a component below this fraction of the peak resultant counts as zero
_PTV_COLD_SAMPLES = 3  # the initial state and FPBearingPTV's first two steps (held at 20 degC)


class OrbitComparison(NamedTuple):
    """Both orbit tests and their differences.

    Attributes
    ----------
    ours, opensees : BearingTestResult
        Our element's and the OpenSees element's histories; ``force[:, 0]`` and
        ``force[:, 1]`` are the per-axis force histories [N].
    summary : dict
        :func:`compare_orbit_results` of the two (JSON-ready).
    """

    ours: BearingTestResult
    opensees: BearingTestResult
    summary: dict[str, Any]


def orbit_cycles(orbit: Orbit) -> list[slice]:
    """The orbit's closed blocks: every segment but the ``lead-in`` (the whole orbit if it has
    no segments)."""
    blocks = [slice(start, stop) for label, start, stop in orbit.segments if label != "lead-in"]
    return blocks or [slice(None)]


def _energy(result: BearingTestResult, cycles: list[slice]) -> float:
    return sum(path_integral(result.displacement[s], result.force[s]) for s in cycles)


def compare_orbit_results(ours: BearingTestResult, opensees: BearingTestResult,
                          cycles: list[slice] | None = None) -> dict[str, Any]:
    """Peaks, energies and differences of two orbit tests on the same samples (JSON-ready).

    Parameters
    ----------
    ours, opensees : BearingTestResult
        The two tests, sample by sample on one time grid.
    cycles : list of slice, optional
        The closed blocks whose work is the dissipated energy (:func:`orbit_cycles`); by
        default the whole history.

    Returns
    -------
    dict
        ``{"ours": {...}, "opensees": {...}, "difference": {...}, "wall_time_ratio": r}``;
        each side holds ``peak_resultant_force`` [N], ``energy`` [J] and
        ``peak_temperature`` [degC] (None without one); ``difference`` the measures of the
        module docstring.

    Raises
    ------
    ValueError
        If the two tests do not share their samples.
    """
    if ours.time.shape != opensees.time.shape or not np.allclose(ours.time, opensees.time,
                                                                 rtol=0.0, atol=1e-12):
        raise ValueError("The orbit tests compared by compare_orbit_results must share their "
                         f"samples. Got {ours.time.size} and {opensees.time.size} samples "
                         "instead.")
    cycles = [slice(None)] if cycles is None else cycles
    resultant = {side: np.hypot(r.force[:, 0], r.force[:, 1])
                 for side, r in (("ours", ours), ("opensees", opensees))}
    peak = float(np.max(resultant["ours"]))
    gap = opensees.force - ours.force
    difference: dict[str, Any] = {
        "peak_resultant_force": float(np.max(resultant["opensees"])) / peak - 1.0}
    for i, axis in enumerate("xy"):
        scale = float(np.max(np.abs(ours.force[:, i])))
        scale = scale if scale > _ZERO_COMPONENT * peak else peak
        difference[f"nrmse_force_{axis}"] = float(np.sqrt(np.mean(gap[:, i] ** 2))) / scale
    difference["largest_force_gap"] = float(np.max(np.hypot(gap[:, 0], gap[:, 1]))) / peak
    energy = {side: _energy(r, cycles) for side, r in (("ours", ours), ("opensees", opensees))}
    difference["energy"] = energy["opensees"] / energy["ours"] - 1.0
    both = np.isfinite(ours.temperature) & np.isfinite(opensees.temperature)
    both[:_PTV_COLD_SAMPLES] = False
    both &= np.any(opensees.displacement != 0.0, axis=1)
    heated = bool(np.any(np.isfinite(opensees.temperature)))
    difference["max_temperature_gap"] = (
        float(np.max(np.abs(opensees.temperature - ours.temperature)[both])) if heated
        else None)
    summary: dict[str, Any] = {"difference": difference}
    for side, r in (("ours", ours), ("opensees", opensees)):
        summary[side] = {"name": r.name, "peak_resultant_force": float(np.max(resultant[side])),
                         "energy": energy[side],
                         "peak_temperature": (float(np.nanmax(r.temperature)) if heated
                                              else None)}
    summary["wall_time_ratio"] = ours.wall_time / opensees.wall_time
    return summary


def run_orbit_comparison(
    bearing: DCFPBearing,
    orbit: Orbit,
    *,
    element: str = "coulomb",
    ours_bearing: DCFPBearing | None = None,
    match_normal_force: bool = False,
    grid_orientation: float | None = None,
) -> OrbitComparison:
    """Run ``orbit`` on our bidirectional element and on the OpenSees 3D element; compare.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing OpenSees builds (see :func:`structures.opensees.bearing3d.run_opensees_orbit`:
        a ConstantFriction for ``"coulomb"``, a PTVFriction shaped by
        :func:`~structures.opensees.equivalents.fpbearingptv_equivalent` for ``"ptv"``).
    orbit : Orbit
        The imposed orbit (:mod:`isolator.orbits`), starting at the centre.
    element : {"coulomb", "ptv"}
        singleFPBearing 3D with Coulomb friction, or FPBearingPTV.
    ours_bearing : DCFPBearing, optional
        The bearing our element runs; by default ``bearing`` (e.g. the precise model here
        against FPBearingPTV's centre point).
    match_normal_force : bool
        Give our bearing singleFPBearing's normal force ``W + F . u / R``
        (:func:`~structures.opensees.bearing3d.singlefp3d_normal_force`) instead of W; only
        with ``"coulomb"``.
    grid_orientation : float or None
        Orientation of our precise model's monitor grid [deg]; None follows the motion.

    Raises
    ------
    ValueError
        For ``match_normal_force`` with ``"ptv"`` (FPBearingPTV keeps N = W), and as the runs.
    """
    element = check_choice(element, "element", "run_orbit_comparison", ELEMENTS_3D)
    ours_bearing = bearing if ours_bearing is None else ours_bearing
    if match_normal_force:
        if element != "coulomb":
            raise ValueError(f"The 'match_normal_force' parameter of run_orbit_comparison "
                             f"applies to element 'coulomb' only (FPBearingPTV keeps N = W). "
                             f"Got element {element!r} instead.")
        normal = singlefp3d_normal_force(ours_bearing, orbit.time, orbit.displacement,
                                         orbit.velocity)
        ours_bearing = replace(ours_bearing, axial_load=normal)
    opensees = opensees_orbit(bearing, orbit, element=element)
    ours = run_orbit(ours_bearing, orbit, grid_orientation=grid_orientation)
    return OrbitComparison(ours, opensees, compare_orbit_results(ours, opensees,
                                                                 orbit_cycles(orbit)))
