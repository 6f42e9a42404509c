"""The response-history analysis of ASCE/SEI 7-16 Sec. 17.6 with the ground motions of 17.3: a
suite of at least seven pairs scaled as one on the MCE_R spectrum, run at the upper and lower
bound properties and with the centre of mass in each accidental position, averaged over the
pairs, enveloped and checked against the ELF (:func:`design`).

The runs are suites (:mod:`structures.suites`): one per mass position, into its own folder, on
one Dask cluster, resumable, peaks only by default. What the standard's text says and what
was verified of it is in :mod:`structures.design.limits`; in short, as read from the
literature on the 2016 edition and not checked against the text here:

- 17.3.2: at least 7 pairs; where too few recorded pairs are at hand, simulated pairs may make
  up the number (:func:`groundmotions.synthetic_pair`, labelled synthetic).
- 17.3.3: one factor per pair, both components alike; the average of the pairs' RotD100
  (maximum-direction) spectra not below the MCE_R spectrum from 0.75 T_M (upper bound) to
  1.25 T_M (lower bound) (:func:`groundmotions.scaling.scale_suite`, ``method="mean"``,
  ``fraction`` = ``LIMITS["rha_scaling_fraction"]``).
- 17.6.2.1 (accidental mass eccentricity): the centre of mass of every level moved from its
  computed place by 5 % of the plan dimension along each of two orthogonal directions,
  separately, both signs: four positions ``"+x"``, ``"-x"`` (5 % of the dimension a along x),
  ``"+y"``, ``"-y"`` (of b). The bearings' gravity loads stay where the computed masses put
  them (``hold_bearing_loads``): the mass moves, the building's weight on its bearings does
  not; a friction pendulum's stiffness and strength follow its load, so loads that followed
  the mass would move the centre of rigidity with it and leave almost no torsion.
- 17.6.3.4 (as read): with at least 7 pairs the average of each response over the pairs is
  the design value, per bound and position; the design takes the envelope over them.
- 17.6.4 (the clause numbers in doubt): D_TM not less than 80 % of the ELF's, V_b not less
  than 90 %, V_s not less than 80 % (100 % for an irregular superstructure) of the ELF's
  (the storey shear of the response history divided by R_I, as 17.6.4.2 reduces the
  superstructure's forces), storey drift ratio at most 0.020 (17.6.4.4).
"""

from __future__ import annotations

import dataclasses
import math
import tempfile
import time
import warnings
from collections.abc import Callable, Sequence
from contextlib import ExitStack
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_choice, check_instance, check_int
from structures.config import BuildingConfig
from structures.design.elf import CLAUSES, UNITS, ELFResult, Site, elf
from structures.design.limits import LIMITS, limit
from structures.design.properties import BOUNDS, PropertyModification
from structures.design.result import (
    PEAK_UNITS,
    Check,
    DesignResult,
    PairInfo,
    ScaledSpectra,
    Table,
)
from structures.suites.sources import MotionSource, motion_sources

__all__ = ["POSITIONS", "SYNTHETIC", "building_design", "design", "design_positions",
           "period_range", "scaling_period_range"]

G = STANDARD_GRAVITY
_OWNER = "design"

POSITIONS = ("+x", "-x", "+y", "-y")
"""The accidental positions of the centre of mass (17.6.2.1 as read): moved by 5 % of the plan
dimension along x (a) or y (b), each sign; ``"nominal"`` (no move) may be asked besides."""

SYNTHETIC: dict[str, Any] = {
    "generator": "clough-penzien", "seed": 1700, "seed_step": 10, "duration": 40.0,
    "ground_frequency": 15.6, "ground_damping": 0.6, "filter_frequency": 1.5,
    "filter_damping": 0.6, "pga_over_S_MS": 0.4,
}
"""How synthetic pairs complete a suite (a package convention, not from the standard):
Clough-Penzien filtered white noise of firm ground (w_g = 15.6 rad/s, z_g = 0.6; the high-pass
w_f = 1.5 rad/s, z_f = 0.6 takes out the long-period content recorded motions lack, which
Kanai-Tajimi noise keeps and which drove isolators some 30 % further on the example building)
under the Jennings envelope, 40 s, on the building file's step; pair k has seed
``seed + k seed_step`` (x the seed, y the seed + 1), its peak ground acceleration 0.4 S_MS g
(the MCE_R spectrum at T = 0) before the suite's scaling, which treats it as any other pair
(factors near 0.7 on the example)."""

SCALE_FACTOR_RANGE = (0.25, 4.0)
"""Scale factors outside this range [-] are named in the notes (a package convention, not
from the standard: the literature on 17.3.3 suites keeps factors within about 0.25 to 4, since
a larger factor distorts the record's other intensities and durations)."""

DEFAULT_T_L = 8.0
"""T_L [s] of the MCE_R target where the site gives none (a package default, noted)."""

_MIN_COLUMNS = ("axial_load_min", "mu_min")  # enveloped by their smallest average


def period_range(result: ELFResult) -> tuple[float, float]:
    """The scaling period range of 17.3.3 [s]: 0.75 T_M of the upper bound to 1.25 T_M of the
    lower bound (``LIMITS["period_range_low"]``, ``["period_range_high"]``)."""
    check_instance(result, "result", "period_range", ELFResult, "an ELFResult")
    return (limit("period_range_low") * result.upper.T_M,
            limit("period_range_high") * result.lower.T_M)


def design_positions(config: BuildingConfig, positions: Sequence[str] = POSITIONS
                     ) -> dict[str, tuple[float, float]]:
    """The offsets (dx, dy) [m] of the centre of mass of each position: ``"+x"`` is
    (+0.05 a, 0) with a the plan's dimension along x, ``"-y"`` (0, -0.05 b), ``"nominal"``
    (0, 0) (``LIMITS["accidental_shift"]``).

    Raises
    ------
    InputError
        An unknown or repeated position, a building without a plan or without its
        ``dimensions``.
    """
    check_instance(config, "config", _OWNER, BuildingConfig, "a BuildingConfig")
    plan = config.plan
    if plan is None or plan.dimensions is None:
        raise InputError(f"The 'config' parameter of {_OWNER} must be a building in plan with "
                         "[plan] 'dimensions': the accidental positions of the centre of mass "
                         "(17.6.2.1) are 5 % of them. Got "
                         f"{'no plan' if plan is None else 'no dimensions'} instead.")
    if isinstance(positions, str) or not positions:
        raise InputTypeError(f"The 'positions' parameter of {_OWNER} must be a non-empty "
                             f"sequence of {('nominal', *POSITIONS)}. Got {positions!r} "
                             "instead.")
    share = limit("accidental_shift")
    a, b = plan.dimensions
    offsets = {"nominal": (0.0, 0.0), "+x": (share * a, 0.0), "-x": (-share * a, 0.0),
               "+y": (0.0, share * b), "-y": (0.0, -share * b)}
    out = {}
    for position in positions:
        check_choice(position, "positions", _OWNER, tuple(offsets))
        if position in out:
            raise InputError(f"The 'positions' parameter of {_OWNER} must name each position "
                             f"once. Got {position!r} twice.")
        out[position] = offsets[position]
    return out


def _position_config(config: BuildingConfig, offset: tuple[float, float],
                     hold: bool) -> BuildingConfig:
    if offset == (0.0, 0.0):
        return config
    building = config.building
    plan = building.plan.shifted(offset, building.n_storeys, hold_loads=hold)
    return dataclasses.replace(config, building=dataclasses.replace(building, plan=plan))


def _sources(pairs: Any) -> tuple[MotionSource, ...]:
    if isinstance(pairs, str | Path):
        return motion_sources(pairs, pairs=True)
    if isinstance(pairs, Sequence) and all(isinstance(p, MotionSource) for p in pairs):
        sources = tuple(pairs)
        if any(s.kind != "pair" for s in sources):
            raise InputError(f"The 'pairs' parameter of {_OWNER} must hold pairs (two or three "
                             "component files each), not single records.")
        return sources
    raise InputTypeError(f"The 'pairs' parameter of {_OWNER} must be a pair manifest (path) or "
                         f"a sequence of MotionSource (motion_sources(..., pairs=True)). Got "
                         f"{pairs!r:.80} instead.")


def synthetic_count(complete: bool | int, real: int) -> int:
    """The synthetic pairs that complete a suite of ``real`` recorded pairs: True up to the
    minimum of 17.3.2, an int that many, False or None none."""
    if complete is False or complete is None:
        return 0
    if complete is True:
        return max(0, int(limit("min_pairs")) - real)
    return check_int(complete, "complete_with_synthetic", _OWNER, low=0, high=100)


def _synthetic_name(k: int) -> str:
    """The name of the ``k``-th synthetic pair (from 0): ``synthetic-1``, ..."""
    return f"synthetic-{k + 1}"


def _read_pair(source: MotionSource):
    """The pair of ``source``; an unreadable one is an InputError naming the pair."""
    try:
        return source.read()
    except InputError:
        raise
    except Exception as error:
        raise InputError(f"The pair {source.name!r} of {_OWNER} cannot be read: "
                         f"{type(error).__name__}: {error}") from error


def _write_synthetic(count: int, folder: Path, dt: float, site: Site
                     ) -> tuple[list[MotionSource], dict[str, tuple[str, ...]]]:
    """``count`` synthetic pairs as one-column text files (exact to the last digit) in
    ``folder``: their sources and, by name, the generator and seed that made them."""
    from groundmotions import synthetic_pair

    if count:
        folder.mkdir(parents=True, exist_ok=True)
    spec = SYNTHETIC
    pga = spec["pga_over_S_MS"] * site.S_MS * G
    sources, labels = [], {}
    for k in range(count):
        seed = spec["seed"] + k * spec["seed_step"]
        name = _synthetic_name(k)
        pair = synthetic_pair(spec["generator"], seed, duration=spec["duration"], dt=dt,
                              name=name, ground_frequency=spec["ground_frequency"],
                              ground_damping=spec["ground_damping"],
                              filter_frequency=spec["filter_frequency"],
                              filter_damping=spec["filter_damping"], target_pga=pga)
        files = []
        for role in ("x", "y"):
            path = folder / f"{name}-{role}.txt"
            text = (f"# {spec['generator']} synthetic ground motion, {name} {role}, seed "
                    f"{seed + (role == 'y')}, acceleration [m/s^2], dt = {dt!r} s\n")
            values = getattr(pair, role).acceleration
            text += "\n".join(repr(float(v)) for v in values) + "\n"
            if not path.exists() or path.read_text() != text:
                path.write_text(text)
            files.append(str(path))
        sources.append(MotionSource(name, tuple(files), dt, "m/s^2"))
        labels[name] = (f"generator {spec['generator']}", f"seed {seed} (x), {seed + 1} (y)",
                        f"w_g {spec['ground_frequency']:g} rad/s, z_g "
                        f"{spec['ground_damping']:g}, w_f {spec['filter_frequency']:g} rad/s, "
                        f"z_f {spec['filter_damping']:g}, {spec['duration']:g} s, PGA "
                        f"{pga / G:.3g} g before scaling")
    return sources, labels


def building_design(config: BuildingConfig) -> dict[str, Any]:
    """The building file's ``[design]`` table as objects: ``"lambda"`` (a
    :class:`PropertyModification`, from ``lambda_max``/``lambda_min`` or the parts), ``"site"``
    (a :class:`Site`), ``"R"`` and ``"I_e"``, each None where the file does not give it.

    Raises
    ------
    InputError
        Factors the property modification refuses (named, with ``[design]``).
    """
    check_instance(config, "config", "building_design", BuildingConfig, "a BuildingConfig")
    table = dict(config.design or {})
    out: dict[str, Any] = {"lambda": None, "site": None, "R": table.get("R"),
                           "I_e": table.get("I_e")}
    heating = {k: table[k] for k in ("test_includes_heating", "test_heating_max",
                                     "test_heating_min") if k in table}
    parts = {k: table[k] for k in ("ae_max", "ae_min", "test_max", "test_min", "spec_max",
                                   "spec_min") if k in table}
    try:
        if "lambda_max" in table:
            out["lambda"] = PropertyModification.overall(table["lambda_max"],
                                                         table["lambda_min"], **heating)
        elif parts or heating:
            out["lambda"] = PropertyModification(**parts, **heating)
    except InputError as error:
        raise InputError(f"[design] of the building file {config.name!r}: {error}") from None
    if "S_MS" in table:
        out["site"] = Site(table["S_MS"], table["S_M1"], table.get("T_L"))
    return out


def scaling_period_range(config: BuildingConfig, S_M1: float, lambda_: PropertyModification,
                         model: str | None = None) -> tuple[float, float]:
    """The period range of 17.3.3 [s], 0.75 T_M (upper bound) to 1.25 T_M (lower bound), from
    the ELF's fixed point of D_M alone (:func:`structures.design.elf.fixed_point`: T_M needs
    neither R nor the storey heights) at ``S_M1`` [g], with the friction of ``model`` (default
    the file's) times lambda of each bound as applied to it."""
    from structures.design.elf import fixed_point, nominal_mu

    check_instance(config, "config", "scaling_period_range", BuildingConfig,
                   "a BuildingConfig")
    check_instance(lambda_, "lambda_", "scaling_period_range", PropertyModification,
                   "a PropertyModification")
    model = model or config.friction["model"]
    mu = nominal_mu(config, model)
    friction = config.bearing(model).friction
    radius = float(config.bearing_geometry["effective_radius"])
    weight = config.building.weight
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the heating note is the design's to give
        periods = {bound: fixed_point(weight, radius, mu * lambda_.factor_for(friction, bound),
                                      S_M1)[4] for bound in BOUNDS}
    return (limit("period_range_low") * periods["upper"],
            limit("period_range_high") * periods["lower"])


_MISSING = {
    "site": (f"The 'site' parameter of {_OWNER} must be given (Site or (S_MS, S_M1[, T_L])) "
             "when the building file has no [design] S_MS and S_M1. Got None instead."),
    "lambda": (f"The 'lambda_' parameter of {_OWNER} must be given (a PropertyModification) "
               "when the building file has no [design] lambda: the analysis runs at the upper "
               "and lower bound (17.2.8.4). Got None instead."),
    "R": (f"The 'R' parameter of {_OWNER} must be given when the building file has no "
          "[design] R. Got None instead."),
}


def design_inputs(config: BuildingConfig, site: Any = None, lambda_: Any = None,
                  R: float | None = None, *, missing: dict[str, str] | None = None,
                  defaults: dict[str, Any] | None = None
                  ) -> tuple[Site, PropertyModification, float]:
    """The site [g, g, s], the property modification and R [-] of an analysis (as
    :func:`design` takes them): each as given, else the building file's ``[design]``
    (:func:`building_design`), else ``defaults[name]`` (names ``"site"``, ``"lambda"``,
    ``"R"``); one given nowhere raises an InputError with ``missing[name]`` (default: naming
    the parameter of :func:`design`; the command line names its flags)."""
    from_file = building_design(config)
    given = {"site": site, "lambda": lambda_, "R": R}
    for name, value in given.items():
        if value is None:
            value = from_file[name]
        if value is None and defaults and name in defaults:
            value = defaults[name]
        if value is None:
            raise InputError({**_MISSING, **(missing or {})}[name])
        given[name] = value
    site, lambda_ = given["site"], given["lambda"]
    if isinstance(site, tuple | list) and len(site) in (2, 3):
        site = Site(*site)
    if not isinstance(site, Site):
        raise InputTypeError(f"The 'site' parameter of {_OWNER} must be a Site or (S_MS, S_M1[, "
                             f"T_L]). Got {site!r} instead.")
    if isinstance(lambda_, tuple | list) and len(lambda_) == 2:
        lambda_ = PropertyModification.overall(*lambda_)
    check_instance(lambda_, "lambda_", _OWNER, PropertyModification,
                   "a PropertyModification or (lambda_max, lambda_min)")
    return site, lambda_, given["R"]


def check_suite_size(n_pairs: int, allow_fewer: bool,
                     refusal: Callable[[str], str]) -> str | None:
    """The rule of 17.3.2 on a suite of ``n_pairs`` pairs (synthetic ones included): None
    when it has at least ``min_pairs``; the rule ("ASCE/SEI 7-16 17.3.2 asks for at least 7
    pairs of ground motions") when it has fewer and ``allow_fewer``; else an InputError
    ``refusal(rule)``, in the caller's words (its flags or its parameters)."""
    minimum = int(limit("min_pairs"))
    if n_pairs >= minimum:
        return None
    rule = (f"ASCE/SEI 7-16 {LIMITS['min_pairs'].clause} asks for at least {minimum} pairs "
            "of ground motions")
    if not allow_fewer:
        raise InputError(refusal(rule))
    return rule


def _spectra(motions: Sequence[Any], report: Any, site: Site, t_l: float,
             prange: tuple[float, float], periods: np.ndarray) -> ScaledSpectra:
    """Target and scaled RotD100 of each pair [s], in g: the scaling's own on its grid, and
    on the ``periods`` outside the range computed here (each spectrum computed once)."""
    from groundmotions.pairs.rotd import rotd_spectra
    from groundmotions.scaling import asce7_design_spectrum

    ratio = limit("design_over_mce")
    target = asce7_design_spectrum(ratio * site.S_MS, ratio * site.S_M1, t_l, level="mce")
    lo, hi = report.periods[0], report.periods[-1]
    outside = np.asarray([t for t in periods if t < lo or t > hi], dtype=float)
    grid = np.concatenate([outside, report.periods])
    order = np.argsort(grid)
    pairs = {}
    for k, (motion, factor) in enumerate(zip(motions, report.scale_factors, strict=True)):
        own = report.spectra["rotd100"][k]
        more = (factor * rotd_spectra(motion, outside, 0.05, (100,)).sa[0] if outside.size
                else np.empty(0))
        pairs[motion.name] = np.concatenate([more, own])[order] / G
    grid = grid[order]
    return ScaledSpectra(grid, target.sa_at(grid) / G, pairs, prange)


def _scale(motions: Sequence[Any], site: Site, prange: tuple[float, float], n_periods: int
           ) -> tuple[Any, float]:
    """The suite's one set of factors (:func:`groundmotions.scaling.scale_suite` on RotD100),
    and the T_L of the target."""
    from groundmotions.scaling import asce7_design_spectrum, scale_suite

    t_l = DEFAULT_T_L if site.T_L is None else float(site.T_L)
    ratio = limit("design_over_mce")
    s_ds, s_d1 = ratio * site.S_MS, ratio * site.S_M1
    t_l = max(t_l, 1.01 * s_d1 / s_ds)
    target = asce7_design_spectrum(s_ds, s_d1, t_l, level="mce")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # large factors are named in the notes
        report = scale_suite(list(motions), target, prange, method="mean", measure="rotd100",
                             fraction=limit("rha_scaling_fraction"), n_periods=n_periods)
    return report, t_l


def design(config: BuildingConfig, pairs: Any, site: Site | tuple[float, ...] | None = None,
           lambda_: PropertyModification | tuple[float, float] | None = None, *,
           R: float | None = None, I_e: float | None = None, model: str | None = None,
           allow_fewer: bool = False, complete_with_synthetic: bool | int = False,
           positions: Sequence[str] = POSITIONS, hold_bearing_loads: bool = True,
           regular: bool = True, storey_heights: float | list[float] | None = None,
           out_dir: str | Path | None = None, n_workers: int | None = None,
           scheduler_address: str | None = None, store: str = "peaks", progress: bool = True,
           governing_history: bool = True, floor_spectra: bool = True,
           run_timeout: float | None = None, n_periods: int = 30,
           spectrum_periods: Any = None) -> DesignResult:
    """The response-history analysis of ASCE/SEI 7-16 17.6 with its ELF (17.5) and checks.

    Parameters
    ----------
    config : BuildingConfig
        A building in plan with ``dimensions`` (:func:`structures.load_config`).
    pairs : str, Path or sequence of MotionSource
        A pair manifest (:func:`groundmotions.read_pair_manifest`) or its sources
        (:func:`structures.suites.motion_sources` with ``pairs=True``).
    site : Site, (S_MS, S_M1[, T_L]) or None
        MCE_R parameters [g, g, s]; None: the building file's ``[design]``.
    lambda_ : PropertyModification, (lambda_max, lambda_min) or None
        Property modification (17.2.8.4); None: the building file's ``[design]``.
    R, I_e : float or None
        Response modification of the superstructure (R_I = 3/8 R in [1, 2]) and importance
        factor [-]; None: the file's ``[design]`` (I_e 1 where it gives none).
    model : str, optional
        Friction model of the runs and the ELF's nominal mu (default the file's).
    allow_fewer : bool
        Run a suite of fewer pairs than 17.3.2 asks (the result is then not compliant).
    complete_with_synthetic : bool or int
        True: add synthetic pairs (:data:`SYNTHETIC`) up to the 7 of 17.3.2; an int: add that
        many; False: none.
    positions : sequence of str
        The positions of the centre of mass (:data:`POSITIONS`, and ``"nominal"``).
    hold_bearing_loads : bool
        Keep the bearings' gravity loads where the computed masses put them when the masses
        move (True, the accidental case); False lets them follow.
    regular : bool
        A regular superstructure: V_s of the response history at least 80 % of the ELF's, else
        100 %.
    storey_heights : float, list of float or None
        Storey heights [m] (default the plan's): the ELF's, and the runs' (overturning, drift
        ratios) in place of the plan's.
    out_dir : str, Path or None
        Folder of the runs (one suite per position in ``positions/<position>``, the synthetic
        pairs in ``synthetic``); resumable: complete runs, and runs that stopped at the
        bearings' capacity, are read back, not run again. None: a temporary folder, removed
        at the end.
    n_workers, scheduler_address : int, str, optional
        A local Dask cluster of ``n_workers`` processes (default the cores), or a running
        scheduler.
    store : {"peaks", "float32", "full"}
        What each run keeps besides its peaks (:data:`structures.suites.runs.STORAGE`).
    progress : bool
        Progress bars on stderr.
    governing_history, floor_spectra : bool
        Run the governing run again here for its full history (``governing_run``), with floor
        spectra.
    run_timeout : float, optional
        Wall-clock limit of each run [s].
    n_periods : int
        Periods of the scaling grid over the range (log-spaced; the criterion is checked on
        them).
    spectrum_periods : array_like, optional
        Periods [s] of the spectra reported besides the scaling grid (default 30 from 0.1 s to
        twice the range's end; those inside the range are the grid's).

    Returns
    -------
    DesignResult

    Raises
    ------
    InputError
        A bad argument (named); fewer pairs than 17.3.2 asks without ``allow_fewer`` (the
        message names the rule and the clause).
    """
    start = time.perf_counter()
    timings: dict[str, float] = {}
    check_instance(config, "config", _OWNER, BuildingConfig, "a BuildingConfig")
    offsets = design_positions(config, positions)
    sources = _sources(pairs)
    flags = {"allow_fewer": allow_fewer, "hold_bearing_loads": hold_bearing_loads,
             "regular": regular, "progress": progress, "governing_history": governing_history,
             "floor_spectra": floor_spectra}
    for name, value in flags.items():
        if not isinstance(value, bool):
            raise InputTypeError(f"The {name!r} parameter of {_OWNER} must be True or False. "
                                 f"Got {value!r} instead.")
    from structures.suites.runs import STORAGE

    store = check_choice(store, "store", _OWNER, STORAGE)
    n_synthetic = synthetic_count(complete_with_synthetic, len(sources))
    n_pairs = len(sources) + n_synthetic
    notes: list[str] = []
    rule = check_suite_size(n_pairs, allow_fewer, lambda rule: (
        f"{rule}; the suite has {n_pairs}. Give more pairs, complete the suite with synthetic "
        "pairs (complete_with_synthetic), or allow fewer (allow_fewer, --allow-fewer: the "
        "result is then not compliant)."))
    compliant = rule is None
    if not compliant:
        notes.append(f"NOT COMPLIANT: {rule}; the suite has {n_pairs} (allowed by allow_fewer); "
                     f"the averages over {n_pairs} pairs are not the design values of 17.6.3.4, "
                     f"which rest on at least {int(limit('min_pairs'))}.")
    site, lambda_, R = design_inputs(config, site, lambda_, R)
    if I_e is None:
        I_e = building_design(config)["I_e"] or 1.0
    model = model or config.friction["model"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result_elf = elf(config, site, lambda_, R=R, I_e=I_e, model=model,
                         storey_heights=storey_heights)
        friction = config.bearing(model).friction
        factors_by_bound = {bound: lambda_.factor_for(friction, bound) for bound in BOUNDS}
    notes += [str(w.message) for w in caught]
    heights = np.asarray(result_elf.upper.directions["x"].storey_heights, dtype=float)
    if storey_heights is not None:  # the runs' overturning and drift ratios take them too
        plan = dataclasses.replace(config.plan, storey_heights=heights)
        config = dataclasses.replace(config, building=dataclasses.replace(config.building,
                                                                          plan=plan))
    prange = period_range(result_elf)
    timings["elf"] = time.perf_counter() - start

    names = [s.name for s in sources] + [_synthetic_name(k) for k in range(n_synthetic)]
    if len(set(names)) != len(names):
        raise InputError(f"The 'pairs' parameter of {_OWNER} must name each pair once "
                         f"(the synthetic ones are synthetic-1, ...). Got {names}.")
    mark = time.perf_counter()
    motions = [_read_pair(source) for source in sources]  # before any folder is made
    timings["read"] = time.perf_counter() - mark

    temporary = out_dir is None
    with ExitStack() as stack:
        if temporary:
            out_dir = stack.enter_context(tempfile.TemporaryDirectory(prefix="dcfpb-design-"))
        root = Path(out_dir)
        root.mkdir(parents=True, exist_ok=True)
        step = float(config.dt) if config.dt is not None else 0.005
        synthetic_sources, labels = _write_synthetic(n_synthetic, root / "synthetic", step,
                                                     site)
        all_sources = (*sources, *synthetic_sources)
        motions += [_read_pair(source) for source in synthetic_sources]
        mark = time.perf_counter()
        report, t_l = _scale(motions, site, prange, n_periods)
        factors = {name: float(k) for name, k in zip(names, report.scale_factors, strict=True)}
        if spectrum_periods is None:
            spectrum_periods = np.geomspace(0.1, max(2.0 * prange[1], 4.0), 30)
        spectra = _spectra(motions, report, site, t_l, prange,
                           np.asarray(spectrum_periods, dtype=float))
        timings["scaling"] = time.perf_counter() - mark
        low, high = SCALE_FACTOR_RANGE
        odd = {n: k for n, k in factors.items() if not low <= k <= high}
        if odd:
            notes.append(f"scale factors outside {low:g} to {high:g} (a package convention, "
                         "not the standard's: a larger factor distorts the record's other "
                         "intensities): " + ", ".join(f"{n} {k:.3g}" for n, k in odd.items()))
        if n_synthetic:
            notes.append(f"{n_synthetic} synthetic pair(s) complete the suite "
                         f"({SYNTHETIC['generator']}, fixed seeds; 17.3.2 permits simulated "
                         "pairs where recorded ones are too few): "
                         + ", ".join(s.name for s in synthetic_sources))
        if site.T_L is None:
            notes.append(f"T_L not given: the MCE_R target uses T_L = {t_l:g} s (a package "
                         "default; it matters only beyond T_L)")
        pair_info = tuple(PairInfo(s.name, s.name in labels, factors[s.name],
                                   labels.get(s.name, tuple(Path(f).name for f in s.files)))
                          for s in all_sources)

        mark = time.perf_counter()
        rows = _run_positions(config, all_sources, factors, factors_by_bound, offsets,
                              hold_bearing_loads, model, root, store, n_workers,
                              scheduler_address, progress, run_timeout, stack)
        timings["runs"] = time.perf_counter() - mark
        import pandas as pd

        peaks = pd.DataFrame(rows)
        synthetic = {s.name for s in synthetic_sources}
        peaks.insert(1, "synthetic", peaks["pair"].isin(synthetic))
        averages = _averages(peaks)
        envelope = _envelope(averages)
        checks = _checks(result_elf, peaks, averages, envelope, config, regular, n_pairs,
                         heights)
        notes += _run_notes(peaks, config)
        governing = None
        if governing_history:
            mark = time.perf_counter()
            governing = _governing_run(config, peaks, averages, all_sources, motions, factors,
                                       offsets, hold_bearing_loads, model, floor_spectra)
            timings["governing_run"] = time.perf_counter() - mark
    tables = _tables(result_elf, pair_info, averages, envelope, config, checks, heights,
                     spectra)
    timings["total"] = time.perf_counter() - start
    options = {
        "site": {"S_MS": site.S_MS, "S_M1": site.S_M1, "T_L": site.T_L,
                 "T_L_target": t_l},
        "lambda": lambda_.to_dict(), "lambda_applied": factors_by_bound, "R": float(R),
        "I_e": float(I_e), "model": model, "positions": list(offsets),
        "position_offsets": {k: list(v) for k, v in offsets.items()},
        "hold_bearing_loads": hold_bearing_loads, "regular": regular, "store": store,
        "displacement_capacity": float(config.bearing_geometry.get("displacement_capacity",
                                                                   0.6)),
        "allow_fewer": allow_fewer, "n_recorded": len(sources), "n_synthetic": n_synthetic,
        "synthetic": dict(SYNTHETIC) if n_synthetic else None,
        "period_range": list(prange), "scaling_fraction": limit("rha_scaling_fraction"),
        "scale_factor_range": list(SCALE_FACTOR_RANGE),
        "scaling_min_ratio": report.min_ratio, "storey_heights": heights.tolist(),
        "out_dir": None if temporary else str(out_dir),
        "timings": timings,
    }
    return DesignResult(config.name, result_elf, pair_info, compliant, spectra, peaks,
                        averages, envelope, tuple(checks), tuple(tables), governing,
                        tuple(notes), options)


def _run_positions(config: BuildingConfig, sources: Sequence[MotionSource],
                   factors: dict[str, float], by_bound: dict[str, float],
                   offsets: dict[str, tuple[float, float]], hold: bool, model: str,
                   root: Path, store: str, n_workers: int | None,
                   scheduler_address: str | None, progress: bool,
                   run_timeout: float | None, stack: ExitStack) -> list[dict[str, Any]]:
    """One suite per position (its folder ``positions/<position>``) on one cluster; the rows
    of every run with ``pair``, ``bound``, ``position``."""
    from structures.suites.store import RunStore
    from structures.suites.suite import Suite, run_suite
    from structures.suites.tasks import DESIGN_MARK

    modifiers = tuple(dict.fromkeys(by_bound.values()))
    suites = {}
    pending = False
    for position, offset in offsets.items():
        shifted = _position_config(config, offset, hold)
        suite = Suite(shifted, sources, models=(model,), property_modifiers=modifiers,
                      factors=factors)
        folder = root / "positions" / position
        suites[position] = (suite, folder)
        specs, _, _ = suite.runs(read=False)
        done = RunStore(folder) if folder.exists() else None
        pending = pending or done is None or any(
            done.completed_row(s.run_id, store, DESIGN_MARK) is None
            and not _kept_failure(done.failed_row(s.run_id)) for s in specs)
    if pending and scheduler_address is None:
        from structures.suites.tasks import local_cluster

        cluster = local_cluster(n_workers)
        stack.callback(cluster.close)
        scheduler_address = cluster.scheduler_address
    rows = []
    for position, (suite, folder) in suites.items():
        result = run_suite(suite, folder, scheduler_address=scheduler_address,
                           progress=progress, run_timeout=run_timeout, storage=store,
                           design_peaks=True, keep_failed=KEPT_FAILURES,
                           label=f"position {position}")
        for row in result.peaks.to_dict("records"):
            for bound, modifier in by_bound.items():
                if row["modifier"] == modifier:
                    rows.append(_design_row(row, bound, position))
    order = {b: k for k, b in enumerate(BOUNDS)}
    places = {p: k for k, p in enumerate(offsets)}
    names = {s.name: k for k, s in enumerate(sources)}
    rows.sort(key=lambda r: (order[r["bound"]], places[r["position"]], names[r["pair"]]))
    return rows


KEPT_FAILURES = ("capacity",)
"""Failed runs a second call keeps instead of running again: a run past the bearings'
displacement capacity fails the same way each time (its peaks up to the failure are kept)."""


def _kept_failure(row: dict[str, Any] | None) -> bool:
    from structures.suites.runs import failure_kind
    from structures.suites.tasks import DESIGN_MARK

    return (row is not None and failure_kind(row) in KEPT_FAILURES
            and all(key in row for key in DESIGN_MARK))


def _design_row(row: dict[str, Any], bound: str, position: str) -> dict[str, Any]:
    out = {"pair": row["pair"], "bound": bound, "position": position,
           "status": row["status"], "reason": row.get("reason"),
           "failure": row.get("failure") or "", "run_id": row["run_id"],
           "scale": row["scale"], "modifier": row["modifier"]}
    for key, value in row.items():
        if key in PEAK_UNITS or key.startswith("drift_ratio_"):
            out[key] = np.nan if value is None else value
    for key in PEAK_UNITS:
        out.setdefault(key, np.nan)
    return out


def _peak_columns(frame: Any) -> list[str]:
    return [c for c in frame.columns if c in PEAK_UNITS or c.startswith("drift_ratio_")]


def _averages(peaks: Any) -> Any:
    """The mean over pairs of each peak, per (bound, position), with the counts of runs and
    of failed runs (a failed run's peaks are those up to its failure)."""
    import pandas as pd

    columns = _peak_columns(peaks)
    rows = []
    for (bound, position), group in peaks.groupby(["bound", "position"], sort=False):
        row = {"bound": bound, "position": position, "n_pairs": len(group),
               "n_failed": int((group["status"] != "done").sum())}
        row |= {c: float(pd.to_numeric(group[c], errors="coerce").mean()) for c in columns}
        rows.append(row)
    return pd.DataFrame(rows)


def _envelope(averages: Any) -> dict[str, dict[str, Any]]:
    out = {}
    for column in _peak_columns(averages):
        values = averages[column].to_numpy(dtype=float)
        if np.all(np.isnan(values)):
            out[column] = {"value": math.nan, "unit": _unit(column), "bound": "",
                           "position": ""}
            continue
        k = int(np.nanargmin(values) if column in _MIN_COLUMNS else np.nanargmax(values))
        out[column] = {"value": float(values[k]), "unit": _unit(column),
                       "bound": str(averages["bound"].iloc[k]),
                       "position": str(averages["position"].iloc[k])}
    return out


def _unit(column: str) -> str:
    return PEAK_UNITS.get(column, "-")


def _checks(result: ELFResult, peaks: Any, averages: Any, envelope: dict[str, dict[str, Any]],
            config: BuildingConfig, regular: bool, n_pairs: int,
            heights: np.ndarray) -> list[Check]:
    """The checks of 17.3.2, 17.5.3.3, 17.6.4 and the bearings' (module docstring)."""
    checks = [Check("suite_size", LIMITS["min_pairs"].clause,
                    "pairs of ground motions in the suite (recorded and synthetic)",
                    float(n_pairs), limit("min_pairs"), "-", "min")]

    def env(key: str) -> tuple[float, str, str]:
        entry = envelope[key]
        return entry["value"], entry["bound"], entry["position"]

    directions = result.directions
    for d in directions:
        value, bound = result.governing("D_TM", d)
        d_m = getattr(result, bound).D_M
        checks.append(Check(
            f"elf_D_TM_floor_{d}", LIMITS["D_TM_over_D_M_min"].clause,
            f"ELF D_TM ({d}) not less than {limit('D_TM_over_D_M_min'):g} D_M",
            value, limit("D_TM_over_D_M_min") * d_m, "m", "min", bound))
    demand, bound, position = env("isolator_displacement")
    for d in directions:
        value, elf_bound = result.governing("D_TM", d)
        checks.append(Check(
            f"rh_D_TM_vs_elf_{d}", LIMITS["rha_D_TM_min"].clause,
            f"D_TM of the response history (largest bearing resultant, average over pairs) "
            f"not less than {limit('rha_D_TM_min'):.0%} of the ELF's D_TM ({d}, "
            f"{elf_bound} bound); below it the design takes the floor",
            demand, limit("rha_D_TM_min") * value, "m", "floor", bound, position))
    V_b, elf_bound = result.governing("V_b")
    V_s, s_bound = result.governing("V_s")
    key = "rha_V_s_min_regular" if regular else "rha_V_s_min_irregular"
    for d in directions:
        demand, bound, position = env(f"base_shear_{d}")
        checks.append(Check(
            f"rh_V_b_vs_elf_{d}", LIMITS["rha_V_b_min"].clause,
            f"V_b of the response history ({d}, average over pairs) not less than "
            f"{limit('rha_V_b_min'):.0%} of the ELF's V_b ({elf_bound} bound); below it the "
            "design forces are scaled up to it",
            demand, limit("rha_V_b_min") * V_b, "N", "floor", bound, position))
        demand, bound, position = env(f"storey_shear_{d}")
        checks.append(Check(
            f"rh_V_s_vs_elf_{d}", LIMITS[key].clause,
            f"V_s of the response history (first storey shear / R_I = {result.R_I:g}, {d}, "
            f"average over pairs) not less than {limit(key):.0%} of the ELF's V_s "
            f"({s_bound} bound; {'regular' if regular else 'irregular'} superstructure); "
            "below it the design forces are scaled up to it",
            demand / result.R_I, limit(key) * V_s, "N", "floor", bound, position))
    for d in directions:
        demand, bound, position = env(f"max_drift_ratio_{d}")
        if not math.isnan(demand):
            checks.append(Check(
                f"rh_drift_ratio_{d}", LIMITS["drift_rha"].clause,
                f"largest storey drift ratio of the response history ({d}, at the plan's "
                "reference point, average over pairs)",
                demand, limit("drift_rha"), "-", "max", bound, position))
    capacity = float(config.bearing_geometry.get("displacement_capacity", 0.6))
    demand, bound, position = env("isolator_displacement")
    checks.append(Check(
        "bearing_displacement_capacity", LIMITS["bearing_capacity"].clause,
        "largest bearing displacement (average over pairs, enveloped) within the bearings' "
        "displacement capacity", demand, capacity, "m", "max", bound, position))
    failure = peaks["failure"] if "failure" in peaks else peaks["status"].map(lambda _: "")
    beyond = (peaks["status"] != "done") & (failure == "capacity")
    checks.append(Check(
        "bearing_capacity_every_run", LIMITS["bearing_capacity"].clause,
        "runs that stopped at the bearings' displacement capacity (any pair, bound, position)",
        float(beyond.sum()), 0.0, "-", "max"))
    lowest = pd_min(peaks, "axial_load_min")
    checks.append(Check(
        "bearing_uplift", LIMITS["uplift"].clause,
        "smallest axial load of any bearing in any run (0 or less: uplift)",
        lowest["value"], 0.0, "N", "min", lowest["bound"], lowest["position"]))
    return checks


def pd_min(peaks: Any, column: str) -> dict[str, Any]:
    """The smallest value of ``column`` over the runs and where (bound, position)."""
    values = peaks[column].to_numpy(dtype=float)
    if np.all(np.isnan(values)):
        return {"value": math.nan, "bound": "", "position": ""}
    k = int(np.nanargmin(values))
    return {"value": float(values[k]), "bound": str(peaks["bound"].iloc[k]),
            "position": str(peaks["position"].iloc[k])}


def _run_notes(peaks: Any, config: BuildingConfig) -> list[str]:
    notes = []
    failed = peaks[peaks["status"] != "done"]
    if len(failed):
        kinds = failed["failure"].fillna("") if "failure" in failed else failed["status"] * 0
        parts = []
        for kind, group in failed.groupby(kinds.replace("", "error"), sort=False):
            first = str(group["reason"].iloc[0]).split(": the ")[0]  # the first clause
            runs = ", ".join(f"{r.pair} ({r.bound}, {r.position})" for r in group.itertuples())
            parts.append(f"{len(group)} by {kind} ('{first}'): {runs}")
        notes.append(f"{len(failed)} run(s) did not finish; their peaks are those up to the "
                     "failure and enter the averages (which they understate): "
                     + "; ".join(parts) + " (each run's reason: peaks.csv)")
    lifted = peaks["axial_load_min"].to_numpy(dtype=float) <= 0.0
    if lifted.any():
        notes.append(f"uplift: {int(lifted.sum())} run(s) lifted a bearing off (axial load "
                     "<= 0); the model gives a lifted bearing no force and no friction")
    return notes


def _governing_run(config: BuildingConfig, peaks: Any, averages: Any,
                   sources: Sequence[MotionSource], motions: Sequence[Any],
                   factors: dict[str, float], offsets: dict[str, tuple[float, float]],
                   hold: bool, model: str, floor_spectra: bool) -> Any:
    """The run of the largest isolator displacement of the (bound, position) whose average
    governs, run again here in float64 with its full history (and floor spectra)."""
    from structures.analysis import run
    from structures.suites.runs import analysis_step

    values = averages["isolator_displacement"].to_numpy(dtype=float)
    if np.all(np.isnan(values)):
        return None
    k = int(np.nanargmax(values))
    bound, position = averages["bound"].iloc[k], averages["position"].iloc[k]
    group = peaks[(peaks["bound"] == bound) & (peaks["position"] == position)]
    row = group.loc[group["isolator_displacement"].astype(float).idxmax()]
    index = [s.name for s in sources].index(row["pair"])
    motion = motions[index].scaled(factors[row["pair"]])
    shifted = _position_config(config, offsets[position], hold)
    bearing = shifted.bearing(model)
    bearing = dataclasses.replace(bearing, friction=bearing.friction.scaled(row["modifier"]),
                                  axial_load=None)
    step = analysis_step(config.dt, motion.dt)
    result = run(shifted.building, bearing, motion, shifted.integrator, dt=step,
                 floor_spectra=floor_spectra)
    result.attrs.update(pair=row["pair"], bound=bound, position=position,
                        scale=factors[row["pair"]], property_modifier=row["modifier"],
                        synthetic=int(bool(row["synthetic"])))
    return result


def _fmt(value: Any) -> Any:
    if isinstance(value, np.generic):
        return value.item()
    return value


def _tables(result: ELFResult, pairs: Sequence[PairInfo], averages: Any,
            envelope: dict[str, dict[str, Any]], config: BuildingConfig,
            checks: Sequence[Check], heights: np.ndarray, spectra: ScaledSpectra
            ) -> list[Table]:
    up, low = result.upper, result.lower
    elf_rows = [("lambda", "-", up.lambda_, low.lambda_, "17.2.8.4"),
                ("mu", "-", up.mu, low.mu, "17.2.8.4")]
    for key in ("K_M", "beta_M", "B_M", "T_M", "D_M"):
        elf_rows.append((key, UNITS[key], getattr(up, key), getattr(low, key),
                         CLAUSES.get(key, "")))
    for d in result.directions:
        elf_rows.append((f"D_TM ({d})", "m", up.directions[d].D_TM, low.directions[d].D_TM,
                         "17.5.3.3"))
    for key in ("V_b", "V_st", "V_s", "F_1"):
        elf_rows.append((key, "N", getattr(up, key), getattr(low, key),
                         CLAUSES.get(key, "")))
    for d in result.directions:
        elf_rows.append((f"max drift ratio ({d})", "-", up.directions[d].max_drift_ratio,
                         low.directions[d].max_drift_ratio, "17.5.6"))
    tables = [Table("Equivalent lateral force procedure", "17.5",
                    ("quantity", "unit", "upper", "lower", "clause"),
                    ("", "", "", "", ""), tuple(elf_rows),
                    f"R_I = {result.R_I:g}, mu nominal = {result.mu_nominal:.4g} "
                    f"({result.model} model)")]
    lo, hi = spectra.period_range
    tables.append(Table(
        "Ground-motion suite and scale factors", "17.3.2, 17.3.3",
        ("pair", "synthetic", "scale factor", "sources"), ("", "", "-", ""),
        tuple((p.name, p.synthetic, p.scale_factor, "; ".join(p.sources)) for p in pairs),
        f"one factor per pair on the average RotD100 over {lo:.3g} to {hi:.3g} s "
        f"(0.75 T_M upper to 1.25 T_M lower)"))
    shown = ("isolator_displacement", "corner_centre_ratio", "base_shear_x", "base_shear_y",
             "storey_shear_x", "storey_shear_y", "max_drift_ratio_x", "max_drift_ratio_y",
             "axial_load_max", "axial_load_min", "max_temperature", "mu_min", "mu_max")
    tables.append(Table(
        "Average over pairs per bound and position", "17.6.3.4 (as read)",
        ("bound", "position", "n_pairs", "n_failed", *shown),
        ("", "", "-", "-", *(PEAK_UNITS[c] for c in shown)),
        tuple(tuple(_fmt(r[c]) for c in ("bound", "position", "n_pairs", "n_failed", *shown))
              for r in averages.to_dict("records"))))
    tables.append(Table(
        "Envelope of the averages over bounds and positions", "17.6.3.4 (as read)",
        ("quantity", "unit", "value", "bound", "position"), ("", "", "", "", ""),
        tuple((k, v["unit"], v["value"], v["bound"], v["position"])
              for k, v in envelope.items() if not k.startswith("drift_ratio_")),
        "largest average; smallest for axial_load_min and mu_min"))
    capacity = float(config.bearing_geometry.get("displacement_capacity", 0.6))
    bearing_rows = [
        ("displacement (resultant)", "m", envelope["isolator_displacement"]["value"], capacity),
        ("corner / centre displacement", "-", envelope["corner_centre_ratio"]["value"], None),
        ("axial load, largest", "N", envelope["axial_load_max"]["value"], None),
        ("axial load, smallest", "N", envelope["axial_load_min"]["value"], 0.0),
        ("contact temperature, peak", "degC", envelope["max_temperature"]["value"], None),
        ("mu while sliding, smallest", "-", envelope["mu_min"]["value"], None),
        ("mu while sliding, largest", "-", envelope["mu_max"]["value"], None),
    ]
    tables.append(Table(
        "Bearing demands", "17.2.4, 17.6 (as read)", ("quantity", "unit", "demand", "limit"),
        ("", "", "", ""), tuple(bearing_rows),
        "averages over pairs, enveloped; limit: the displacement capacity of the building "
        "file, no uplift"))
    drift_rows = []
    for k, h in enumerate(heights, start=1):
        drift_rows.append((k, float(h), envelope.get(f"drift_ratio_x_{k}", {}).get("value"),
                           envelope.get(f"drift_ratio_y_{k}", {}).get("value"),
                           limit("drift_rha")))
    tables.append(Table(
        "Storey drift ratios", LIMITS["drift_rha"].clause,
        ("storey", "height", "drift ratio x", "drift ratio y", "limit"),
        ("-", "m", "-", "-", "-"), tuple(drift_rows),
        "storey drift at the plan's reference point over the storey height, averages over "
        "pairs enveloped over bounds and positions"))
    return tables

