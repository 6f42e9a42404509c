"""Ours side by side with OpenSees: which bearing, both runs, the differences.

:data:`MODELS`, each as the OpenSees element that represents it: ``"constant"`` (Eq. 8) as
``Coulomb``; ``"velocity"`` (Eq. 7 without heating, the paper's factors) as ``VelDependent``;
``"ptv"`` (Eq. 7, Kumar's factors) as ``FPBearingPTV``. Differences are OpenSees's relative to
ours over the common time samples; ``wall_time_ratio`` is our wall time over OpenSees's (model
building included). Measured: docs/opensees_comparison.md.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, NamedTuple

import numpy as np

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_choice
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from isolator.bearing import DCFPBearing
from isolator.factors import KumarFactors
from isolator.testrig import BearingTestResult, path_integral, run_test
from structures.analysis import peaks, run
from structures.integrators import HHT, Newmark
from structures.opensees.bearing import run_opensees_test
from structures.opensees.building import run_opensees
from structures.opensees.elements import ELEMENTS, element_kind, fpbearingptv_equivalent
from structures.opensees.singlefp import singlefp_normal_force
from structures.results import resultant

__all__ = ["MODELS", "Comparison", "axial_load_summary", "bearing_summary", "closed_blocks",
           "compare", "compare_tests", "comparison_bearing", "nrmse", "outline_bearings",
           "run_bearing_comparison", "run_comparison", "shaped_bearing", "truncated"]

MODELS = ("constant", "velocity", "ptv")
_ZERO_COMPONENT = 1.0e-9  # a component below this fraction of the peak resultant counts as zero
_PTV_COLD_SAMPLES = 3  # the initial state and FPBearingPTV's first two steps (held at 20 degC)


class Comparison(NamedTuple):
    """Both runs (building Datasets or :class:`~isolator.testrig.BearingTestResult`) and the
    JSON-ready summary of their differences."""

    ours: Any
    opensees: Any
    summary: dict[str, Any]


def shaped_bearing(bearing: DCFPBearing, model: str) -> DCFPBearing:
    """``bearing`` with the friction model ``model`` (:data:`MODELS`): the constant model as it
    is, Eq. 7 without heating, or Eq. 7 with Kumar's factors shaped as FPBearingPTV (mu_t0,
    dependencies, thermal properties kept). Raises ValueError if the bearing's friction is of the
    other family (Eq. 7 for ``"constant"``, the constant model otherwise)."""
    owner = "shaped_bearing"
    model = check_choice(model, "model", owner, MODELS)
    friction = bearing.friction
    if (friction.name == "constant") != (model == "constant"):
        wanted = "ConstantFriction" if model == "constant" else "PTVFriction"
        raise InputError(f"The 'bearing' parameter of {owner} must have a {wanted} for model "
                         f"{model!r}. Got {friction!r} instead.")
    if model == "constant":
        return bearing
    if model == "velocity":
        return replace(bearing, friction=replace(friction, heating=None))
    return fpbearingptv_equivalent(replace(bearing, friction=replace(friction,
                                                                     factors=KumarFactors())))


def comparison_bearing(config, model: str) -> DCFPBearing:
    """The bearing of a building file (:func:`structures.config.load_config`) for ``model``:
    the file's constant model, or its simplified model (mu_t0, thermal properties) reshaped by
    :func:`shaped_bearing`."""
    model = check_choice(model, "model", "comparison_bearing", MODELS)
    return shaped_bearing(config.bearing("constant" if model == "constant" else "simplified"),
                          model)


def nrmse(reference: np.ndarray, other: np.ndarray) -> float:
    """``sqrt(mean((other - reference)^2)) / max|reference|`` over common samples [-] (the RMS
    if the reference is zero). Raises ValueError if the histories differ in length."""
    reference, other = np.asarray(reference, dtype=float), np.asarray(other, dtype=float)
    if reference.shape != other.shape:
        raise InputError(f"The histories compared by nrmse must have one length. Got "
                         f"{reference.shape} and {other.shape} instead.")
    scale = float(np.max(np.abs(reference)))
    rms = float(np.sqrt(np.mean((other - reference) ** 2)))
    return rms / scale if scale > 0.0 else rms


def truncated(motion: GroundMotion | GroundMotionPair, duration: float):
    """The first ``duration`` [s] of a record, or of each component of a pair."""
    if isinstance(motion, GroundMotionPair):
        parts = [None if m is None else m.truncated(duration) for m in (motion.x, motion.y,
                                                                         motion.z)]
        return GroundMotionPair(*parts, name=motion.name)
    return motion.truncated(duration)


def _peaks(ds, corner: int | None) -> dict[str, Any]:
    """:func:`~structures.analysis.peaks` with, in plan, the resultant displacement of bearing
    ``corner`` (``peak_corner_displacement`` [m]), and the run's success and message."""
    out = peaks(ds)
    if corner is not None:
        reach = resultant(ds["bearing_displacement"].values[:, corner])
        out["peak_corner_displacement"] = float(reach.max())
    out["success"], out["message"] = bool(ds.attrs["success"]), str(ds.attrs["message"])
    return out


def outline_bearings(ds) -> list[int]:
    """The corner bearings of a run in plan: the vertices of the convex outline of its
    bearing positions, in the outline's order (bearings on an edge left out)."""
    from scipy.spatial import ConvexHull

    xy = np.column_stack([ds["bearing_x"].values, ds["bearing_y"].values])
    return [int(i) for i in ConvexHull(xy).vertices]


def axial_load_summary(ours, opensees) -> tuple[dict[str, Any], dict[str, float]]:
    """The axial loads of the corner bearings (:func:`outline_bearings`) in two runs in plan on
    the same samples, and their differences: ``(summary, difference)``.

    ``summary``: ``bearings`` (indices), ``gravity_share`` [N], and for ``ours`` and ``opensees``
    the ``max`` and ``min`` of each one's axial load [N] (OpenSees's: the normal force).
    ``difference``: ``max_axial_load``, ``min_axial_load`` (largest gap of the maxima, of the
    minima, signed OpenSees minus ours) and ``nrmse_axial_load`` (largest RMS difference), each
    over ours's largest change of that load from its gravity share (over the share if none) [-].
    """
    corners = outline_bearings(ours)
    gravity = np.asarray(ours.attrs["gravity_shares"], dtype=float)[corners]
    loads = {side: ds["axial_load"].values[:, corners] for side, ds in (("ours", ours),
                                                                        ("opensees", opensees))}
    change = np.max(np.abs(loads["ours"] - gravity), axis=0)
    change = np.where(change > _ZERO_COMPONENT * gravity, change, gravity)
    summary: dict[str, Any] = {"bearings": corners, "gravity_share": gravity.tolist()}
    for side, values in loads.items():
        summary[side] = {"max": values.max(axis=0).tolist(), "min": values.min(axis=0).tolist()}
    difference = {}
    for key, extreme in (("max_axial_load", np.max), ("min_axial_load", np.min)):
        gaps = (extreme(loads["opensees"], axis=0) - extreme(loads["ours"], axis=0)) / change
        difference[key] = float(gaps[np.argmax(np.abs(gaps))])
    rms = np.sqrt(np.mean((loads["opensees"] - loads["ours"]) ** 2, axis=0))
    difference["nrmse_axial_load"] = float(np.max(rms / change))
    return summary, difference


def compare(ours, opensees) -> dict[str, Any]:
    """Peaks of both building runs, their differences and the wall-time ratio (JSON-ready):
    ``{"ours": peaks, "opensees": peaks, "difference": {...}, "wall_time_ratio": r}``.

    Each side holds its :func:`~structures.analysis.peaks` with ``success`` and ``message``
    (OpenSees's with its ``element``). ``difference``: ``peak_<name>``
    (``max|x_OS| / max|x_ours| - 1``, resultants in plan), ``nrmse_<history>`` (:func:`nrmse`,
    ``_x``/``_y`` per component in plan; the isolator displacement's the largest over the
    bearings) and ``max_temperature_gap`` [degC]. In plan also ``corner_bearing`` (ours's largest;
    both sides report its ``peak_corner_displacement`` [m]), each side's ``overturning``,
    ``axial_load`` and the differences of :func:`axial_load_summary`. Raises ValueError if the runs
    do not share their time step or their bearings.
    """
    if not np.isclose(float(ours.attrs["dt"]), float(opensees.attrs["dt"])):
        raise InputError("The runs compared must share their time step. Got "
                         f"{ours.attrs['dt']!r} s and {opensees.attrs['dt']!r} s instead.")
    if not all(np.array_equal(ours[name].values, opensees[name].values)
               for name in ("bearing_x", "bearing_y", "bearing_count")):
        raise InputError("The runs compared must have the same bearings.")
    n = min(ours.sizes["time"], opensees.sizes["time"])
    a, b = ours.isel(time=slice(0, n)), opensees.isel(time=slice(0, n))
    plan = ours.sizes["direction"] == 2
    corner = peaks(a)["corner_bearing"] if plan else None
    pa, pb = _peaks(a, corner), _peaks(b, corner)
    difference: dict[str, float] = {
        key: pb[key] / pa[key] - 1.0 if pa[key] > 0.0 else float(pb[key] - pa[key])
        for key in pa if key.startswith("peak_")}
    suffixes = [f"_{d}" if plan else "" for d in ours["direction"].values]
    ua, ub = a["bearing_displacement"].values, b["bearing_displacement"].values
    for k, s in enumerate(suffixes):
        difference[f"nrmse_isolator_displacement{s}"] = max(
            nrmse(ua[:, i, k], ub[:, i, k]) for i in range(ua.shape[1]))
        if plan:
            difference[f"nrmse_corner_displacement{s}"] = nrmse(ua[:, corner, k],
                                                                ub[:, corner, k])
            difference[f"nrmse_centre_displacement{s}"] = nrmse(
                a["displacement"].values[:, 0, k], b["displacement"].values[:, 0, k])
    if plan:
        difference["nrmse_base_rotation"] = nrmse(a["rotation"].values[:, 0],
                                                  b["rotation"].values[:, 0])
    for k, s in enumerate(suffixes):
        difference[f"nrmse_base_shear{s}"] = nrmse(a["base_shear"].values[:, k],
                                                   b["base_shear"].values[:, k])
        difference[f"nrmse_roof_acceleration{s}"] = nrmse(
            a["absolute_acceleration"].values[:, -1, k],
            b["absolute_acceleration"].values[:, -1, k])
    gap = np.abs(b["temperature"].values - a["temperature"].values)
    difference["max_temperature_gap"] = float(np.nanmax(gap))
    summary = {"ours": _peaks(ours, corner), "opensees": _peaks(opensees, corner),
               "difference": difference}
    if plan:
        summary["corner_bearing"] = corner
        summary["ours"]["overturning"] = bool(ours.attrs["overturning"])
        summary["opensees"]["overturning"] = bool(opensees.attrs["overturning"])
        summary["axial_load"], gaps = axial_load_summary(a, b)
        difference.update(gaps)
    summary["opensees"]["element"] = opensees.attrs["element"]
    summary["wall_time_ratio"] = ours.attrs["wall_time"] / opensees.attrs["wall_time"]
    return summary


def run_comparison(
    building,
    bearing: DCFPBearing,
    motion: GroundMotion | GroundMotionPair,
    integrator: str | Newmark | HHT = "newmark",
    *,
    n_bearings: int | None = None,
    dt: float | None = None,
    pendulum: str = "singlefp",
    overturning: bool | None = None,
    warm_up: bool = True,
    **run_options: Any,
) -> Comparison:
    """Run ``bearing`` (shaped, :func:`shaped_bearing`) under the building both ways and
    compare (:func:`compare`). Every position takes its share of the weight (the bearing's own
    load is dropped). ``building``, ``motion``, ``integrator``, ``n_bearings``, ``dt`` as
    :func:`structures.analysis.run`, ``**run_options`` passed to it only (``tolerance``,
    ``max_steps``, ...); ``pendulum`` as :func:`~structures.opensees.building.run_opensees`;
    ``overturning``: in plan, the overturning of the floors' inertia forces on both sides (default:
    when the plan has storey heights); ``warm_up``: run ours first on the record's first 3 samples
    (compilation out of the timing)."""
    bearing = replace(bearing, axial_load=None)
    if overturning is None:
        overturning = building.plan is not None and building.plan.storey_heights is not None
    options = {"n_bearings": n_bearings, "overturning": overturning, **run_options}
    if warm_up and motion.npts >= 3:
        run(building, bearing, truncated(motion, 2 * motion.dt), integrator, **options)
    ours = run(building, bearing, motion, integrator, dt=dt, **options)
    opensees = run_opensees(building, bearing, motion, integrator, n_bearings=n_bearings, dt=dt,
                            pendulum=pendulum, overturning=overturning)
    return Comparison(ours, opensees, compare(ours, opensees))


def bearing_summary(ours: BearingTestResult, opensees: BearingTestResult) -> dict[str, Any]:
    """Peak force [N], energy dissipated per cycle (EDC, along x) [J] and largest temperature
    [degC] of both tests, their differences (relative peak force, force NRMSE, largest EDC gap
    over the largest EDC, temperature gap [degC]) and the wall-time ratio (JSON-ready)."""

    def side(result: BearingTestResult) -> dict[str, Any]:
        heated = np.isfinite(result.temperature)  # NaN where an element has no temperature
        return {"peak_force": float(np.max(np.abs(result.force))),
                "EDC": [c.EDC for c in result.characteristics()],
                "max_temperature": float(np.max(result.temperature[heated]))
                if heated.any() else None, "wall_time": result.wall_time}

    a, b = side(ours), side(opensees)
    edc = [abs(y - x) / max(a["EDC"]) for x, y in zip(a["EDC"], b["EDC"], strict=False)]
    temperatures = (a["max_temperature"], b["max_temperature"])
    difference = {"peak_force": b["peak_force"] / a["peak_force"] - 1.0,
                  "nrmse_force": nrmse(ours.force, opensees.force),
                  "edc": max(edc, default=np.nan),
                  "max_temperature": None if None in temperatures
                  else temperatures[1] - temperatures[0]}
    ratio = a["wall_time"] / b["wall_time"] if b["wall_time"] > 0 else np.nan
    return {"ours": a, "opensees": b, "difference": difference, "wall_time_ratio": ratio}


def closed_blocks(history) -> list[slice]:
    """Every segment of an imposed history or orbit but the ``lead-in`` (all of it if none)."""
    blocks = [slice(start, stop) for label, start, stop in history.segments
              if label != "lead-in"]
    return blocks or [slice(None)]


def compare_tests(ours: BearingTestResult, opensees: BearingTestResult,
                  cycles: list[slice] | None = None) -> dict[str, Any]:
    """Peaks, energies and differences of two bearing tests on the same samples (JSON-ready):
    ``{"ours": {...}, "opensees": {...}, "difference": {...}, "wall_time_ratio": r}``.

    Each side holds its ``name``, ``peak_resultant_force`` [N], ``energy`` [J] (the force's work
    over the ``cycles``) and ``peak_temperature`` [degC] (None without one). ``difference``,
    OpenSees's relative to ours: ``peak_resultant_force``, ``nrmse_force_x`` (and ``_y``; over our
    peak resultant where our component is zero), ``largest_force_gap`` (``max|F_OS - F_ours|``
    over our peak resultant), ``energy`` and ``max_temperature_gap`` [degC] (None unless both have
    a temperature; FPBearingPTV's samples without one left out). Raises ValueError if the tests do
    not share their samples.
    """
    if ours.time.shape != opensees.time.shape or not np.allclose(ours.time, opensees.time,
                                                                 rtol=0.0, atol=1e-12):
        raise InputError("The tests compared by compare_tests must share their samples. Got "
                         f"{ours.time.size} and {opensees.time.size} samples instead.")
    cycles = [slice(None)] if cycles is None else cycles
    size = ours.time.size
    forces = {side: np.reshape(r.force, (size, -1)) for side, r in (("ours", ours),
                                                                      ("opensees", opensees))}
    length = {side: resultant(force) for side, force in forces.items()}
    peak = float(np.max(length["ours"]))
    gap = forces["opensees"] - forces["ours"]
    difference: dict[str, Any] = {
        "peak_resultant_force": float(np.max(length["opensees"])) / peak - 1.0}
    for i, axis in enumerate("xy"[:gap.shape[1]]):
        scale = float(np.max(np.abs(forces["ours"][:, i])))
        scale = scale if scale > _ZERO_COMPONENT * peak else peak
        difference[f"nrmse_force_{axis}"] = float(np.sqrt(np.mean(gap[:, i] ** 2))) / scale
    difference["largest_force_gap"] = float(np.max(resultant(gap))) / peak
    energy = {side: sum(path_integral(r.displacement[s], r.force[s]) for s in cycles)
              for side, r in (("ours", ours), ("opensees", opensees))}
    difference["energy"] = energy["opensees"] / energy["ours"] - 1.0
    both = np.isfinite(ours.temperature) & np.isfinite(opensees.temperature)
    both[:_PTV_COLD_SAMPLES] = False
    both &= np.any(np.reshape(opensees.displacement, (size, -1)) != 0.0, axis=1)
    heated = bool(np.any(np.isfinite(opensees.temperature)))
    difference["max_temperature_gap"] = (
        float(np.max(np.abs(opensees.temperature - ours.temperature)[both])) if heated
        else None)
    summary: dict[str, Any] = {"difference": difference}
    for side, r in (("ours", ours), ("opensees", opensees)):
        summary[side] = {"name": r.name, "peak_resultant_force": float(np.max(length[side])),
                         "energy": energy[side],
                         "peak_temperature": (float(np.nanmax(r.temperature)) if heated
                                              else None)}
    summary["wall_time_ratio"] = ours.wall_time / opensees.wall_time
    return summary


def run_bearing_comparison(
    bearing: DCFPBearing,
    history,
    *,
    element: str | None = None,
    ours_bearing: DCFPBearing | None = None,
    match_normal_force: bool = False,
    grid_orientation: float | None = None,
) -> Comparison:
    """Run an imposed ``history`` (ImposedHistory or Orbit: times [s], displacement (n,) or
    (n, 2) [m], exact velocity [m/s]) on our test rig and on the OpenSees element; compare
    (:func:`compare_tests` over :func:`closed_blocks`).

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing OpenSees builds, with a constant axial load [N].
    element, ours_bearing : optional
        The OpenSees element (``"coulomb"``, ``"velocity"`` or ``"ptv"``) and the bearing our rig
        runs; by default the bearing's element and ``bearing``.
    match_normal_force : bool
        Give ours singleFPBearing's normal force ``W + F . u / R``
        (:func:`~structures.opensees.singlefp.singlefp_normal_force`); not with ``"ptv"``.
    grid_orientation : float or None
        Orientation of our precise model's monitor grid [deg]; None follows the motion.

    Raises ValueError for ``match_normal_force`` with ``"ptv"``, and as the runs.
    """
    owner = "run_bearing_comparison"
    element = element_kind(bearing) if element is None else check_choice(
        element, "element", owner, ELEMENTS)
    ours_bearing = bearing if ours_bearing is None else ours_bearing
    t, u, v = history.time, history.displacement, history.velocity
    if match_normal_force:
        if element == "ptv":
            raise InputError(f"The 'match_normal_force' parameter of {owner} applies to "
                             "singleFPBearing only (FPBearingPTV keeps N = W). Got element "
                             f"{element!r} instead.")
        ours_bearing = replace(ours_bearing,
                               axial_load=singlefp_normal_force(ours_bearing, t, u, v))
    opensees = run_opensees_test(bearing, t, u, v, element=element, name=history.name)
    ours = run_test(ours_bearing, t, u, v, name=history.name, grid_orientation=grid_orientation)
    return Comparison(ours, opensees, compare_tests(ours, opensees, closed_blocks(history)))
