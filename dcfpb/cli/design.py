"""``dcfpb design``: the ASCE/SEI 7-16 Chapter 17 analysis of a building in plan under a suite
of ground-motion pairs, and its report.

The equivalent lateral force procedure (17.5) at the upper and lower bound, the response
history (17.6 with 17.3) at both bounds and the accidental positions of the centre of mass on
Dask (:func:`structures.design.design`, resumable: the runs are kept in ``OUT/runs``), and the
report folder of :mod:`dcfpb.report.design` (``report.md``, ``report.html``, ``design.json``,
``peaks.csv``, the figures). A suite of fewer pairs than 17.3.2 asks is refused (exit status 2)
before any run starts, unless ``--allow-fewer``. Exit status 0 when the report is written,
whether the checks pass or not (the summary line and the report say which fail); 1 when a run
failed or the report could not be written.
"""

from __future__ import annotations

import argparse
import shlex
import warnings
from pathlib import Path

from dcfpb.common.errors import EXIT_OK, EXIT_RUN_FAILED, InputError, InputWarning
from dcfpb.common.validation import check_real, parse_floats

_COMMAND = "dcfpb design"

LAMBDA_FACTORS = ("ae_max", "ae_min", "test_max", "test_min", "spec_max", "spec_min",
                  "test_heating_max", "test_heating_min", "test_includes_heating")
"""The keys ``--lambda-factors`` takes (those of
:class:`structures.design.PropertyModification`)."""

POSITIONS = ("+x", "-x", "+y", "-y", "nominal")
"""The positions of the centre of mass ``--positions`` takes."""

DEFAULT_POSITIONS = "+x,-x,+y,-y"


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``design`` sub-command to the ``dcfpb`` parser."""
    p = sub.add_parser(
        "design",
        help="ASCE 7-16 Chapter 17 analysis of a building in plan (ELF, response history at "
        "both bounds, checks) and its report",
        description="The ASCE/SEI 7-16 Chapter 17 analysis of a building file with a [plan] "
        "table: the equivalent lateral force procedure (17.5) and the response history "
        "(17.6) at the upper and lower bound properties (17.2.8.4) and at the accidental "
        "positions of the centre of mass, under a suite of at least 7 pairs scaled on their "
        "RotD100 to the MCE_R spectrum (17.3); the runs go through Dask and are resumed by "
        "running the same command again. Writes OUT/report.md, report.html, design.json, "
        "peaks.csv and the figures. Exit status 0 when the report is written, also when "
        "checks fail (the summary says so); 2 for bad input, including a suite of fewer "
        "than 7 pairs without --allow-fewer.",
    )
    p.add_argument("building", metavar="BUILDING.toml",
                   help="building file with a [plan] table (dimensions included)")
    p.add_argument("--pairs", required=True, metavar="MANIFEST.csv",
                   help="pairs of records: a CSV with the columns name, x, y (and optionally "
                   "z, dt, units), paths relative to it")
    p.add_argument("--site", metavar="S_MS,S_M1[,T_L]",
                   help="MCE_R spectral accelerations [g] and the long-period transition "
                   "[s] (default: the building file's [design] table)")
    lam = p.add_mutually_exclusive_group()
    lam.add_argument("--lambda", dest="lambda_", metavar="MAX,MIN",
                     help="property modification factors lambda_max >= 1 and lambda_min in "
                     "(0, 1] as a whole (default: the building file's [design] table)")
    lam.add_argument("--lambda-factors", metavar="KEY=VALUE,...",
                     help="property modification factors by their parts (17.2.8.4): "
                     + ", ".join(LAMBDA_FACTORS) + " (the maxima >= 1, the minima in (0, 1], "
                     "test_includes_heating yes or no); the parts not given are 1")
    p.add_argument("--R", type=float, dest="R", metavar="R",
                   help="response modification coefficient of the superstructure, (0, 10] "
                   "(R_I = 3/8 R in [1, 2]; default: the building file's [design] R)")
    p.add_argument("--model", choices=("precise", "simplified", "constant"),
                   help="friction model of the runs (default: the building file's)")
    p.add_argument("--allow-fewer", action="store_true",
                   help="run a suite of fewer than 7 pairs (17.3.2); the report then says it "
                   "is not compliant")
    p.add_argument("--synthetic", metavar="N|auto", default="0",
                   help="add N synthetic pairs (Clough-Penzien, fixed seeds) to the suite, or "
                   "'auto': as many as complete it to 7 (default 0)")
    p.add_argument("--positions", default=DEFAULT_POSITIONS, metavar="P1,P2,...",
                   help="positions of the centre of mass, moved by 5 %% of the plan dimension: "
                   f"any of {', '.join(POSITIONS)} (default {DEFAULT_POSITIONS})")
    p.add_argument("--loads", choices=("held", "follow"), default="held",
                   help="the bearings' gravity loads where the masses move: held at the "
                   "nominal distribution (the accidental case, default) or following them")
    p.add_argument("--histories", action="store_true",
                   help="keep every run's full history in OUT/runs (default: peaks only)")
    p.add_argument("--out", required=True, metavar="DIR",
                   help="report folder (the runs in DIR/runs; run the same command again to "
                   "finish an interrupted analysis)")
    p.add_argument("--overwrite", action="store_true",
                   help="replace the report files of an earlier analysis in --out")
    p.add_argument("--workers", type=int,
                   help="local worker processes (default and at most: the CPU cores)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="use a running Dask scheduler, e.g. tcp://10.0.0.5:8786")
    p.add_argument("--no-progress", action="store_true", help="hide the progress bars")
    p.set_defaults(handler=_run)


def parse_site(text: str):
    """``--site S_MS,S_M1[,T_L]`` as a :class:`structures.design.Site`."""
    from structures.design import Site

    values = parse_floats(text, "--site", "S_MS,S_M1[,T_L]")
    if len(values) not in (2, 3):
        raise InputError(f"--site must be S_MS,S_M1[,T_L] (S_MS and S_M1 in g in (0, 5], T_L "
                         f"in s in (0, 100]). Got {len(values)} values in {text!r}.")
    try:
        return Site(*values)
    except InputError as error:
        raise InputError(f"--site {text}: {error} (S_MS and S_M1 in g: 1.5 for 1.5 g; T_L in "
                         "s).") from None


def _check_factor(value: float, name: str, command: str) -> float:
    """A property modification factor given by flag: a maximum (``name`` ends in ``MAX`` or
    ``_max``) in [1, 10], a minimum in (0, 1]."""
    if name.lower().endswith("max"):
        return check_real(value, name, command, low=1.0, high=10.0)
    return check_real(value, name, command, low=0.0, high=1.0, low_open=True)


def parse_lambda(overall: str | None, factors: str | None, command: str = "dcfpb design"):
    """``--lambda MAX,MIN`` or ``--lambda-factors KEY=VALUE,...`` as a
    :class:`structures.design.PropertyModification`; None when neither is given. ``command``
    is named in the messages."""
    from structures.design import PropertyModification

    if overall is not None:
        values = parse_floats(overall, "--lambda", "MAX,MIN")
        if len(values) != 2:
            raise InputError(f"--lambda must be MAX,MIN (lambda_max >= 1, lambda_min in "
                             f"(0, 1]). Got {len(values)} values in {overall!r}.")
        for value, name in zip(values, ("--lambda MAX", "--lambda MIN"), strict=True):
            _check_factor(value, name, command)
        try:
            return PropertyModification.overall(*values)
        except InputError as error:
            raise InputError(f"--lambda {overall}: {error}") from None
    if factors is None:
        return None
    parts: dict[str, object] = {}
    for item in str(factors).split(","):
        key, equals, value = item.partition("=")
        key = key.strip()
        if not equals or key not in LAMBDA_FACTORS:
            raise InputError(f"--lambda-factors must be KEY=VALUE pairs separated by commas, "
                             f"the keys among {', '.join(LAMBDA_FACTORS)}. Got {item!r} in "
                             f"{factors!r}.")
        if key in parts:
            raise InputError(f"--lambda-factors gives {key} twice in {factors!r}.")
        if key == "test_includes_heating":
            if value.strip().lower() not in ("yes", "no", "true", "false"):
                raise InputError(f"--lambda-factors test_includes_heating must be yes or no. "
                                 f"Got {value!r}.")
            parts[key] = value.strip().lower() in ("yes", "true")
            continue
        try:
            parts[key] = float(value)
        except ValueError:
            raise InputError(f"--lambda-factors {key} must be a number. Got {value!r}.") from None
        _check_factor(parts[key], f"--lambda-factors {key}", command)
    try:
        return PropertyModification(**parts)
    except InputError as error:
        raise InputError(f"--lambda-factors {factors}: {error}") from None


def parse_synthetic(text: str) -> bool | int:
    """``--synthetic N|auto``: True for ``auto``, else a count in [0, 100]."""
    if str(text).strip().lower() == "auto":
        return True
    try:
        count = int(text)
    except ValueError:
        count = -1
    if not 0 <= count <= 100:
        raise InputError(f"--synthetic must be a whole number of pairs from 0 to 100, or "
                         f"'auto' (as many as complete the suite to 7). Got {text!r}.")
    return count


def parse_positions(text: str) -> tuple[str, ...]:
    """``--positions P1,P2,...`` among :data:`POSITIONS`, each once."""
    positions = tuple(p.strip() for p in str(text).split(",") if p.strip())
    if not positions:
        raise InputError(f"--positions needs at least one of {', '.join(POSITIONS)}. Got "
                         f"{text!r}.")
    for position in positions:
        if position not in POSITIONS:
            raise InputError(f"--positions must be a comma-separated list of "
                             f"{', '.join(POSITIONS)}. Got {position!r} in {text!r}.")
        if positions.count(position) > 1:
            raise InputError(f"--positions names {position!r} twice in {text!r}.")
    return positions


def _missing_design(building: str) -> dict[str, str]:
    """The messages of :func:`structures.design.response.design_inputs` for a site, lambda or
    R given neither by a flag nor by the building file's ``[design]``, naming the flags."""
    return {
        "site": (f"--site S_MS,S_M1[,T_L] must be given: the building file {building} has no "
                 "[design] S_MS and S_M1 (MCE_R spectral accelerations in g, e.g. --site "
                 "1.5,0.6,8)."),
        "lambda": (f"--lambda MAX,MIN (or --lambda-factors) must be given: the building file "
                   f"{building} has no [design] lambda_max and lambda_min (property "
                   "modification, 17.2.8.4; e.g. --lambda 1.8,0.6)."),
        "R": (f"--R must be given: the building file {building} has no [design] R (the "
              "superstructure's response modification coefficient, e.g. --R 2)."),
    }


def _suite_size(n_pairs: int, synthetic: bool | int) -> int:
    """The pairs of the suite: those of --pairs and the synthetic ones added."""
    from structures.design.response import synthetic_count

    return n_pairs + synthetic_count(synthetic, n_pairs)


def _check_suite_size(args: argparse.Namespace, n_pairs: int, synthetic: bool | int) -> None:
    """Refuse a suite of fewer pairs than 17.3.2 asks without --allow-fewer, before any run
    (:func:`structures.design.response.check_suite_size`, this message naming the flags)."""
    from structures.design.response import check_suite_size

    total = _suite_size(n_pairs, synthetic)
    added = f" and {total - n_pairs} synthetic" if total > n_pairs else ""
    check_suite_size(total, args.allow_fewer, lambda rule: (
        f"--pairs {args.pairs}: the suite has {n_pairs} pairs{added}, but {rule}. Give more "
        "pairs, complete the suite with synthetic ones (--synthetic auto, or --synthetic N), "
        "or give --allow-fewer (the report then says the suite is not compliant)."))


def _unused_flags(args: argparse.Namespace, n_pairs: int, synthetic: bool | int,
                  positions: tuple[str, ...]) -> None:
    """Warn of flags given that have no effect."""
    from structures.design.limits import limit

    minimum = int(limit("min_pairs"))
    total = _suite_size(n_pairs, synthetic)
    if args.allow_fewer and total >= minimum:
        warnings.warn(f"--allow-fewer has no effect: the suite has {total} pairs, at least the "
                      f"{minimum} of 17.3.2.", InputWarning, stacklevel=2)
    if synthetic is True and n_pairs >= minimum:
        warnings.warn(f"--synthetic auto has no effect: --pairs gives {n_pairs} pairs, at "
                      f"least the {minimum} of 17.3.2; no synthetic pair is added.",
                      InputWarning, stacklevel=2)
    if args.loads == "follow" and set(positions) <= {"nominal"}:
        warnings.warn("--loads follow has no effect with --positions nominal only: the masses "
                      "do not move.", InputWarning, stacklevel=2)


def command_line(args: argparse.Namespace) -> str:
    """The command as given (the flags that differ from their defaults), for the report."""
    parts = ["dcfpb", "design", args.building, "--pairs", args.pairs]
    for flag, value in (("--site", args.site), ("--lambda", args.lambda_),
                        ("--lambda-factors", args.lambda_factors), ("--R", args.R),
                        ("--model", args.model)):
        if value is not None:
            parts += [flag, f"{value:g}" if isinstance(value, float) else str(value)]
    if args.allow_fewer:
        parts.append("--allow-fewer")
    if str(args.synthetic) != "0":
        parts += ["--synthetic", str(args.synthetic)]
    if args.positions != DEFAULT_POSITIONS:
        parts += ["--positions", args.positions]
    if args.loads != "held":
        parts += ["--loads", args.loads]
    if args.histories:
        parts.append("--histories")
    parts += ["--out", args.out]
    return shlex.join(parts)


def _run(args: argparse.Namespace) -> int:
    from dcfpb.cli.outputs import check_outputs, writing
    from dcfpb.cli.suite import cluster_flags
    from dcfpb.report.design import report_files, write_report
    from structures.config import load_config

    check_outputs(folders={"--out": args.out}, writes={"--out": report_files()},
                  inputs={"the building file": args.building,
                          "the pair manifest (--pairs)": args.pairs},
                  overwrite=args.overwrite)
    site = None if args.site is None else parse_site(args.site)
    lambda_ = parse_lambda(args.lambda_, args.lambda_factors)
    if args.R is not None:
        check_real(args.R, "--R", _COMMAND, low=0.0, high=10.0, low_open=True)
    synthetic = parse_synthetic(args.synthetic)
    positions = parse_positions(args.positions)
    workers = cluster_flags(args, _COMMAND)
    config = load_config(args.building)
    if config.plan is None:
        raise InputError(f"{args.building}: {_COMMAND} runs a building in plan, but the file has "
                         "no [plan] table (bearing_coordinates, dimensions, ...; see README, 'A "
                         "building in plan').")
    if getattr(config.plan, "dimensions", None) is None:
        raise InputError(f"{args.building}: {_COMMAND} needs the plan's dimensions ([plan] "
                         "dimensions = [a, b] in m): the accidental positions of the centre of "
                         "mass are 5 % of them.")
    from structures.design.response import design_inputs
    from structures.suites.sources import motion_sources

    site, lambda_, R = design_inputs(config, site, lambda_, args.R,
                                     missing=_missing_design(args.building))
    sources = motion_sources(args.pairs, pairs=True)
    _check_suite_size(args, len(sources), synthetic)
    _unused_flags(args, len(sources), synthetic, positions)
    from structures.design import design

    out = Path(args.out)
    try:
        result = design(config, sources, site, lambda_, R=R, model=args.model,
                        allow_fewer=args.allow_fewer, complete_with_synthetic=synthetic,
                        positions=positions, hold_bearing_loads=args.loads == "held",
                        out_dir=out / "runs", n_workers=workers,
                        scheduler_address=args.scheduler,
                        store="full" if args.histories else "peaks",
                        progress=not args.no_progress)
    except KeyboardInterrupt:
        print(f"interrupted: finished runs are kept in {out / 'runs'}; run the same command "
              "again to finish the analysis.")
        return 130
    with writing("--out", args.out):
        written = write_report(result, out, command=command_line(args), processes=2)
    return _summary(result, written)


def _summary(result, written: dict[str, Path]) -> int:
    """Print the one-line outcome and the report's path; 1 when a run failed on its own terms
    (a run stopped at the bearings' displacement capacity is a design outcome, checked and
    reported, not a failure of the run)."""
    checks = list(result.checks)
    failed = [c for c in checks if not c.passed]
    verdict = "PASS" if result.passed else "FAIL"
    line = (f"{verdict}: {len(checks) - len(failed)} of {len(checks)} checks passed, "
            f"{len(failed)} failed")
    if failed:
        line += " (" + ", ".join(c.key for c in failed) + ")"
    if not result.compliant_suite:
        line += "; suite NOT COMPLIANT with 17.3.2"
    print(line)
    print(f"report: {written['report.html']} (and report.md, design.json, peaks.csv, "
          f"{len(written) - 4} figures)")
    peaks = result.peaks
    stopped = peaks["status"] != "done" if "status" in peaks else None
    if stopped is None or not stopped.any():
        return EXIT_OK
    kind = peaks.get("failure", None)
    capacity = stopped & (kind == "capacity") if kind is not None else stopped & False
    if capacity.any():
        print(f"{int(capacity.sum())} of {len(peaks)} runs stopped at the bearings' "
              "displacement capacity (a design outcome: see the checks and notes)")
    bad = int((stopped & ~capacity).sum())
    if bad:
        print(f"run failed: {bad} of {len(peaks)} runs did not finish; the report holds their "
              "peaks up to the failure (see its notes and peaks.csv)")
        return EXIT_RUN_FAILED
    return EXIT_OK
