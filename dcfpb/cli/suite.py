"""``dcfpb suite``: a building file under a suite of records, scale factors and friction models,
or, with ``--pairs``, a building file with a ``[plan]`` table under a suite of pairs.

Runs go through Dask (a local cluster, or ``--scheduler ADDRESS``); results, peaks table,
per-model statistics and plots go to ``--out``. Running the same command again finishes an
interrupted suite and retries its failures.
"""

from __future__ import annotations

import argparse
import csv
import json
from pathlib import Path

import numpy as np

from dcfpb.common.errors import EXIT_OK, EXIT_RUN_FAILED, InputError
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import parse_floats


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``suite`` sub-command to the ``dcfpb`` parser."""
    p = sub.add_parser(
        "suite",
        help="run a building under a suite of records x scales x friction models (Dask)",
        description="Run a building file under every record of a folder (*.AT2) or manifest "
        "CSV, at each scale factor, with each friction model, through Dask; or, with --pairs, "
        "a building file with a [plan] table under every pair of a pair manifest. One result "
        "file per run in OUT/runs; rerun the same command to finish an interrupted suite. "
        "Exit status 1 when some runs failed (see OUT/failures.json).",
    )
    p.add_argument("building", metavar="BUILDING.toml", help="building file")
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--records", metavar="DIR_OR_MANIFEST",
                        help="folder of .AT2 files, or a CSV whose first column holds file "
                        "names relative to it")
    source.add_argument("--pairs", metavar="MANIFEST.csv",
                        help="pairs of records: a CSV with the columns name, x, y (and "
                        "optionally z, dt, units), paths relative to it; runs the building "
                        "in plan of a file with a [plan] table, one row of plan peaks per run")
    p.add_argument("--target", metavar="SPECTRUM",
                   help="target spectrum: a CSV of rows 'period,sa' in [s, g], or "
                   "asce7:S_DS,S_D1,T_L (asce7-mce:... for MCE_R); each record is scaled "
                   "to it, each pair on its RotD100 (groundmotions.scaling.scale_suite, "
                   "ASCE 7-16); --scales then multiplies those factors")
    p.add_argument("--period-range", metavar="TMIN,TMAX",
                   help="period range of the scaling [s] (default 0.75 and 1.25 times the "
                   "isolated period 2 pi sqrt(R_eff / g); with an asce7-mce: target and a "
                   "building file whose [design] gives lambda, ASCE 7-16 17.3.3's 0.75 T_M of "
                   "the upper bound to 1.25 T_M of the lower bound)")
    p.add_argument("--scales", default="1.0", metavar="S1,S2,...",
                   help="scale factors [-] (default 1.0)")
    p.add_argument("--models", default="precise,simplified,constant", metavar="M1,M2,...",
                   help="friction models (default: precise,simplified,constant)")
    p.add_argument("--modifiers", default="1.0", metavar="L1,L2,...",
                   help="property modifiers on the friction coefficient [-], e.g. 0.8,1.0,1.3 "
                   "(default 1.0)")
    p.add_argument("--duration", type=float, help="keep the first DURATION s of each record")
    p.add_argument("--dt", type=float, help="analysis time step [s] (default: the file's; a "
                   "record with a finer step runs at its own)")
    p.add_argument("--workers", type=int, help="local worker processes (default and at most: "
                   "the CPU cores available; more warns and uses those)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="use a running Dask scheduler, e.g. tcp://10.0.0.5:8786 (refused, exit "
                   "status 2, if it does not answer as one within 5 s)")
    p.add_argument("--out", default="dcfpb-suite", metavar="DIR",
                   help="result folder (default ./dcfpb-suite); one suite at a time: a "
                   "second one into it refuses (exit status 2) unless --wait-lock")
    p.add_argument("--wait-lock", nargs="?", type=float, const=float("inf"), default=0.0,
                   metavar="SECONDS", help="wait for a suite running into --out to finish "
                   "(as long as it takes, or at most SECONDS) instead of refusing")
    p.add_argument("--run-timeout", type=float, metavar="SECONDS",
                   help="wall-clock limit of each run [s] (default: none); a run past it is "
                   "recorded as failed ('timeout after N s') and the suite goes on")
    p.add_argument("--max-steps", type=int, default=2_000_000, metavar="N",
                   help="refuse a run of more time steps (default 2,000,000); such a run is "
                   "recorded as failed with its step count and the suite goes on")
    p.add_argument("--overwrite", action="store_true",
                   help="write the suite's tables and plots into an --out folder that is not a "
                   "suite folder but holds files of their names (a suite folder is resumed "
                   "without it); never over an input")
    p.add_argument("--storage", choices=("full", "float32", "peaks"), default="full",
                   help="what each run keeps in runs/: its result as netCDF in float64 "
                   "(default) or float32 (about half the size; the peaks are computed before "
                   "the cast), or its peaks row only")
    p.add_argument("--no-plots", action="store_true", help="do not draw the figures")
    p.add_argument("--no-progress", action="store_true", help="hide the progress bar")
    p.add_argument("--json", action="store_true", help="print the outcome as JSON")
    p.set_defaults(handler=_run)


MAX_TARGET_BYTES = 10 * 2**20
"""Largest target spectrum file read [bytes] (a few hundred rows are usual)."""


def read_target(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """A target spectrum as periods [s] and Sa [g]: from a CSV of ``period,sa`` rows (rows that are
    not two numbers, such as a header or comments, are skipped; periods must increase), or from
    ``asce7:S_DS,S_D1,T_L`` (S_DS and S_D1 [g], T_L [s]) for the ASCE 7-16 design spectrum
    (``asce7-mce:...`` for the MCE_R spectrum, 1.5 times it)."""
    text = str(path)
    if text.lower().startswith(("asce7:", "asce7-mce:")):
        from groundmotions.scaling import asce7_design_spectrum

        kind, _, values = text.partition(":")
        try:
            s_ds, s_d1, t_l = (float(v) for v in values.split(","))
        except ValueError as error:
            raise InputError(f"--target {text!r}: write asce7:S_DS,S_D1,T_L, e.g. "
                             "asce7:1.0,0.6,8 (S_DS and S_D1 in g, T_L in s).") from error
        level = "mce" if kind.lower() == "asce7-mce" else "design"
        try:
            spectrum = asce7_design_spectrum(s_ds, s_d1, t_l, level=level)
        except ValueError as error:
            raise InputError(f"--target {text!r}: {error} S_DS and S_D1 are in g (1.0 for "
                             "1 g, not 100), T_L in s.") from None
        periods = np.asarray(spectrum.periods, dtype=float)
        keep = periods > 0
        return periods[keep], np.asarray(spectrum.sa, dtype=float)[keep] / STANDARD_GRAVITY
    try:
        from groundmotions.scaling import MAX_TARGET_SA
    except ImportError:  # target_hook says what is missing
        MAX_TARGET_SA = 10.0  # the same limit [g]

    file = Path(path)
    if not file.is_file():
        what = ("not a regular file (a folder, a device or a pipe)" if file.exists()
                else "no such file")
        raise InputError(f"--target {path}: {what}; give a CSV of 'period,sa' rows [s, g] or "
                         "asce7:S_DS,S_D1,T_L.")
    if file.stat().st_size > MAX_TARGET_BYTES:
        raise InputError(f"--target {path}: {file.stat().st_size:,} bytes, more than the "
                         f"{MAX_TARGET_BYTES:,} of a target spectrum; is it one?")
    rows, lines = [], []
    try:
        with open(file, newline="", encoding="utf-8") as handle:
            reader = csv.reader(handle)
            for row in reader:
                try:
                    rows.append((float(row[0]), float(row[1])))
                    lines.append(reader.line_num)
                except (ValueError, IndexError):
                    continue
    except (UnicodeDecodeError, csv.Error) as error:
        raise InputError(f"--target {path}: not a UTF-8 CSV file ({error}).") from None
    data = np.array(rows, dtype=float).reshape(-1, 2)
    periods, sa = data[:, 0], data[:, 1]
    if len(rows) < 2 or np.any(np.diff(periods) <= 0) or periods[0] < 0 or np.any(sa <= 0):
        raise InputError(f"{path}: a target spectrum needs at least two rows 'period,sa' [s, g] "
                         "with increasing periods >= 0 and sa > 0.")
    high = np.flatnonzero(~(sa <= MAX_TARGET_SA))
    if high.size:
        i = int(high[0])
        raise InputError(f"--target {path}, line {lines[i]}: column 'sa' is in g and must be at "
                         f"most {MAX_TARGET_SA:g} g. Got {sa[i]:g} instead: the values look like "
                         f"%g or cm/s^2; write Sa in g (1.5 for 1.5 g).")
    return periods, sa


def target_hook(periods: np.ndarray, sa_g: np.ndarray, period_range: tuple[float, float]):
    """The factor hook of a target spectrum (periods [s], Sa [g]) for a suite of records or of
    pairs: the factors of ``groundmotions.scaling.scale_suite`` over ``period_range`` [s] (a
    record on its spectrum, a pair on its RotD100), in the order of the motions."""
    try:
        from groundmotions.scaling import scale_suite
    except ImportError as error:
        raise InputError(f"--target needs groundmotions.scaling.scale_suite, which cannot be "
                         f"imported here ({error}). Give the scale factors with --scales "
                         "instead.") from None

    def hook(motions):
        target = (periods, sa_g * STANDARD_GRAVITY)
        return scale_suite(motions, target, period_range).scale_factors

    return hook


def chapter17_range(target: str | None, config) -> tuple[float, float] | None:
    """The period range of ASCE 7-16 17.3.3 [s], 0.75 T_M (upper bound) to 1.25 T_M (lower
    bound), for an ``asce7-mce:S_DS,S_D1,T_L`` target (S_M1 = 1.5 S_D1) on a building file
    whose ``[design]`` gives lambda; None otherwise (the target is not Chapter 17's, or the
    file gives no lambda)."""
    text = str(target or "")
    if not text.lower().startswith("asce7-mce:") or not config.design:
        return None
    from structures.design.response import building_design, scaling_period_range

    lambda_ = building_design(config)["lambda"]
    if lambda_ is None:
        return None
    s_d1 = float(text.partition(":")[2].split(",")[1])  # read_target checked it
    return scaling_period_range(config, 1.5 * s_d1, lambda_)


def _period_range(text: str | None, config, target: str | None = None) -> tuple[float, float]:
    if text:
        values = parse_floats(text, "--period-range")
        if len(values) != 2:
            raise InputError(f"--period-range must be two periods TMIN,TMAX [s] with "
                             f"0 < TMIN < TMAX. Got {text!r}.")
        low, high = values
        if not 0 < low < high < np.inf:
            raise InputError(f"--period-range must be TMIN,TMAX with 0 < TMIN < TMAX. "
                             f"Got {text!r}.")
        return low, high
    chapter17 = chapter17_range(target, config)
    if chapter17 is not None:
        return chapter17
    radius = config.bearing_geometry["effective_radius"]
    period = 2.0 * np.pi * np.sqrt(radius / STANDARD_GRAVITY)
    return 0.75 * period, 1.25 * period


def _check_period_range(period_range: tuple[float, float], periods: np.ndarray,
                        args: argparse.Namespace) -> None:
    """The scaling's period range within the target spectrum's periods, refused naming
    --period-range (given, or its default from the building file) and --target."""
    low, high = period_range
    first, last = float(periods[0]), float(periods[-1])
    if first <= low and high <= last:
        return
    given = (f"--period-range {args.period_range}" if args.period_range else
             f"the default --period-range {low:.4g},{high:.4g} s (0.75 and 1.25 times the "
             f"isolated period, or T_M of the upper and lower bound, of the building file "
             f"{args.building})")
    raise InputError(f"{given} is not within the periods of --target {args.target}, "
                     f"{first:g} to {last:g} s: extend the target spectrum to cover it, or "
                     "give a --period-range inside it.")


def _suite(args: argparse.Namespace, config, factors):
    """The suite of records, or of pairs (``--pairs``; refused before any work for a building
    file without ``[plan]``)."""
    from structures.suites.sources import motion_sources
    from structures.suites.suite import Suite, check_modifiers

    if args.pairs is not None and config.plan is None:
        raise InputError(f"--pairs runs a building in plan, but the building file "
                         f"{args.building!r} has no [plan] table (bearing_coordinates, "
                         "eccentricity, ...; see README, 'A building in plan'). Give --records "
                         "to run it in one direction under single records.")
    check_modifiers(config, args.models.split(","), parse_floats(args.modifiers, "--modifiers"),
                    name="--modifiers", owner="dcfpb suite")
    motions = motion_sources(args.pairs or args.records, pairs=args.pairs is not None)
    return Suite(config, motions, models=args.models.split(","),
                 scales=parse_floats(args.scales, "--scales"),
                 property_modifiers=parse_floats(args.modifiers, "--modifiers"), factors=factors,
                 duration=args.duration, dt=args.dt)


def _run(args: argparse.Namespace) -> int:
    from dcfpb.cli.outputs import check_suite_folder
    from dcfpb.common.validation import check_int, check_real
    from structures.config import load_config
    from structures.suites.lock import SuiteLock
    from structures.suites.suite import run_suite

    target_file = args.target if args.target and not str(args.target).lower().startswith(
        ("asce7:", "asce7-mce:")) else None
    check_suite_folder(args.out, "--out", overwrite=args.overwrite, inputs={
        "the building file": args.building, "the record manifest (--records)": args.records,
        "the pair manifest (--pairs)": args.pairs, "the target spectrum (--target)": target_file})
    if args.run_timeout is not None:
        check_real(args.run_timeout, "--run-timeout", "dcfpb suite", low=0.0, low_open=True)
    check_real(args.wait_lock, "--wait-lock", "dcfpb suite", low=0.0, allow_inf=True)
    check_int(args.max_steps, "--max-steps", "dcfpb suite", low=1)
    for flag, value in (("--duration", args.duration), ("--dt", args.dt)):
        if value is not None:
            check_real(value, flag, "dcfpb suite", low=0.0, low_open=True)
    from isolator.experiments import MODELS as SUITE_MODELS

    for model in args.models.split(","):
        if model not in SUITE_MODELS:
            raise InputError(f"--models must be a comma-separated list of "
                             f"{', '.join(SUITE_MODELS)}. Got {model!r} in {args.models!r}.")
    for scale in parse_floats(args.scales, "--scales"):
        check_real(scale, "--scales", "dcfpb suite", low=0.0, low_open=True)
    if args.period_range and not args.target:
        raise InputError("--period-range applies to --target only.")
    workers = cluster_flags(args, "dcfpb suite")
    config = load_config(args.building)
    target, period_range = None, None
    if args.target:
        target = read_target(args.target)
        period_range = _period_range(args.period_range, config, args.target)
        _check_period_range(period_range, target[0], args)
    suite = _suite(args, config, None if target is None else target_hook(*target, period_range))
    with SuiteLock(args.out, wait=args.wait_lock):  # the plots and tables too
        try:
            result = run_suite(suite, args.out, n_workers=workers,
                               scheduler_address=args.scheduler, progress=not args.no_progress,
                               run_timeout=args.run_timeout, lock=False,
                               max_steps=args.max_steps, storage=args.storage)
        except KeyboardInterrupt:
            print(f"interrupted: finished runs are kept in {args.out}; run the same command "
                  "again to finish the suite.")
            return 130
        from dcfpb.cli.outputs import writing

        with writing("--out", args.out):
            plots = [] if args.no_plots else _plots(result, suite, target, period_range)
        _report(result, plots, args.json)
    return EXIT_OK if not result.failures else EXIT_RUN_FAILED


def cluster_flags(args: argparse.Namespace, command: str) -> int | None:
    """The local workers of ``--workers`` (capped at the cores) or None, after checking that
    ``--workers`` and ``--scheduler`` are not both given and that the scheduler answers."""
    from structures.suites.tasks import capped_workers, check_scheduler

    if args.workers is not None and args.scheduler is not None:
        raise InputError("give --workers (a local cluster) or --scheduler, not both.")
    if args.scheduler is not None:
        check_scheduler(args.scheduler, "--scheduler")
    elif args.workers is not None:
        return capped_workers(args.workers, "--workers", command)
    return args.workers


def _plots(result, suite, target, period_range) -> list[Path]:
    from dcfpb.plotting.suite import plot_peak_distributions, plot_scaled_spectra

    out = Path(result.out_dir) / "plots"
    kind = "peaks in plan" if suite.kind == "pair" else "peaks"
    written = [plot_peak_distributions(result.peaks, out / "peak_distributions.png",
                                       title=f"{suite.config.name}: {kind} per friction model")]
    if target is not None:
        written.append(plot_scaled_spectra(_scaled_suite(result, suite), *target,
                                           out / "scaled_spectra.png",
                                           period_range=period_range))
    return written


def _scaled_suite(result, suite) -> list:
    """The records or the pairs as scaled (and truncated) for the suite's runs."""
    factors = {spec.motion: spec.record_factor for spec in result.runs}
    motions, _ = suite.read()
    scaled = []
    for source, motion in motions.items():
        if suite.duration is not None:  # the part that was run
            motion = motion.truncated(min(suite.duration, motion.duration))
        scaled.append(motion.scaled(float(factors[source])))
    return scaled


def _report(result, plots: list[Path], as_json: bool) -> None:
    from structures.suites.summary import STATISTICS_OVER, failure_counts, summary_dict

    done = int((result.peaks["status"] == "done").sum())
    summary = summary_dict(result.summary)
    counts = failure_counts(result.peaks)
    if as_json:
        print(json.dumps({"runs": len(result.peaks), "done": done, "failed": result.failures,
                          "n_failed": counts.pop("failed"), "failures_by_kind": counts,
                          "statistics_over": STATISTICS_OVER,
                          "wall_time": result.wall_time, "computed": result.computed,
                          "skipped": result.skipped, "out": str(result.out_dir),
                          "summary": summary}, indent=2))
        return
    print(f"{len(result.peaks)} runs: {done} done ({result.skipped} kept from before), "
          f"{len(result.failures)} failed{_kinds(counts)}, {result.wall_time:.1f} s; results "
          f"in {result.out_dir}")
    _print_statistics(summary)
    for failure in result.failures:
        print(f"failed: {failure['run']}: {failure['reason']}")
    if counts["failed"]:
        print(f"warning: {counts['failed']} of {len(result.peaks)} runs failed"
              f"{_kinds(counts)}: the statistics are over the {STATISTICS_OVER} only (column "
              "'ok'); the failed runs are often the strongest (past the bearings' capacity), "
              "so a group with failures understates its responses.")
    if plots:
        print("plots: " + ", ".join(str(p) for p in plots))


def _kinds(counts: dict[str, int]) -> str:
    """`` (capacity 3, timeout 1)`` of the failure counts, empty when none failed."""
    kinds = ", ".join(f"{kind} {n}" for kind, n in counts.items() if kind != "failed" and n)
    return f" ({kinds})" if kinds else ""


_COLUMNS = (  # quantity, heading, unit, factor from SI, width, digits
    ("peak_isolator_displacement", "isol. disp", "[mm]", 1e3, 10, 1),
    ("peak_base_shear", "base shear", "[kN]", 1e-3, 11, 0),
    ("peak_roof_acceleration", "roof acc", "[m/s2]", 1.0, 9, 2),
    ("peak_storey_drift", "drift", "[mm]", 1e3, 7, 2),
)
_PLAN_COLUMNS = (  # a suite of pairs: the corner bearing, the centre, per direction
    ("peak_isolator_displacement", "corner disp", "[mm]", 1e3, 11, 1),
    ("peak_centre_displacement", "centre disp", "[mm]", 1e3, 11, 1),
    ("peak_base_shear", "base shear", "[kN]", 1e-3, 11, 0),
    ("peak_roof_acceleration_x", "roof acc x", "[m/s2]", 1.0, 10, 2),
    ("peak_roof_acceleration_y", "roof acc y", "[m/s2]", 1.0, 10, 2),
    ("peak_storey_drift_x", "drift x", "[mm]", 1e3, 7, 2),
    ("peak_storey_drift_y", "drift y", "[mm]", 1e3, 7, 2),
)


def _print_statistics(summary: dict) -> None:
    """Print the median and 84th percentile of each group over its successful runs, with its
    finished ('ok') and all runs, and its failures."""
    in_plan = any("peak_roof_acceleration_x" in q for q in summary.values())
    table = _PLAN_COLUMNS if in_plan else _COLUMNS
    names, headings, units, factors, widths, digits = zip(*table, strict=True)
    print("statistics over the successful runs of each group (ok of all runs):")
    print(f"{'group':34s} {'':6s} "
          + " ".join(f"{h:>{w}s}" for h, w in zip(headings, widths, strict=True))
          + f" {'ok/all':>8s}  failed")
    print(f"{'':34s} {'':6s} "
          + " ".join(f"{u:>{w}s}" for u, w in zip(units, widths, strict=True)))
    for group, quantities in summary.items():
        first = next(iter(quantities.values()))
        kinds = {k[2:]: v for k, v in first.items()
                 if k.startswith("n_") and k not in ("n_runs", "n_failed")}
        for stat in ("median", "p84"):
            cells = []
            for f, q, w, d in zip(factors, names, widths, digits, strict=True):
                value = quantities[q][stat]
                cells.append(f"{'-':>{w}s}" if value is None else f"{f * value:{w}.{d}f}")
            tail = ""
            if stat == "median":
                failed = (f"{first['n_failed']}{_kinds(kinds)}" if first["n_failed"] else "-")
                tail = f" {first['n']:>3d}/{first['n_runs']:<4d}  {failed}"
            print(f"{group:34s} {stat:6s} {' '.join(cells)}{tail}")
