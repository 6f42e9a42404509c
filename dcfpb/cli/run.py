"""``dcfpb run``: a building file under a recorded ground motion (one record in one direction;
a pair, ``--record-y`` and optionally ``--record-z``, for a building file with a ``[plan]``
table); and what the other building commands share with it (the inputs, the integrator flags,
the peaks table, the bundled example)."""

from __future__ import annotations

import argparse
import dataclasses
import json
import re
from pathlib import Path

from dcfpb.common.errors import EXIT_OK, EXIT_RUN_FAILED, InputError

FIXED_BASE = "fixed base"
"""The label of the fixed-base building in tables and plots."""



def register(sub: argparse._SubParsersAction) -> None:
    """Add ``dcfpb run`` to the sub-commands."""
    p = sub.add_parser(
        "run",
        help="time-history analysis of a building file under a ground motion",
        description="Run a shear building on DCFPB isolators (a TOML building file, see "
        "examples/five_storey.toml) under a recorded ground motion (PEER .AT2 or text).",
    )
    p.add_argument("building", metavar="BUILDING.toml", help="building file")
    p.add_argument("--record", required=True, metavar="FILE",
                   help="ground-motion record (the x component of a pair)")
    add_pair_options(p)
    p.add_argument("--scale", type=float, default=1.0, help="amplitude scale factor [-]")
    p.add_argument("--model", choices=("precise", "simplified", "constant"),
                   help="friction model (default: the building file's)")
    add_integration_flags(p)
    add_max_steps(p)
    add_record_options(p)
    p.add_argument("--json", action="store_true", help="print the peaks as JSON")
    p.add_argument("--output", metavar="FILE.nc", help="write the full result (with floor spectra) "
                   "to netCDF (the name must end in .nc)")
    p.add_argument("--plot", metavar="DIR", help="write plots to this folder")
    p.add_argument("--overwrite", action="store_true",
                   help="replace output files that exist (never an input of the command)")
    p.set_defaults(handler=_run_building)


RECORD_UNITS = ("g", "mg", "gal", "cm/s^2", "m/s^2", "mm/s^2", "in/s^2", "ft/s^2")
"""The ``--units`` choices: `groundmotions.units.UNIT_NAMES` written out, so that parsing
imports no numpy (a test holds the two equal)."""


def add_record_options(p: argparse.ArgumentParser, dt_flags: tuple[str, ...] = ("--record-dt",),
                       ) -> None:
    """Add ``--units`` and ``--record-dt`` (the record's own step, not the analysis step) to a
    command that reads its record with :func:`read_record_from_args`."""
    p.add_argument("--units", choices=RECORD_UNITS,
                   help="units of the record's values when its header states none (default: "
                   "the header's, else g); units that disagree with the header are refused")
    p.add_argument(*dt_flags, dest="record_dt", type=float, metavar="DT",
                   help="time step of a one-column text record [s]; for a two-column or PEER "
                   "record it must agree with the file's")


def read_record_from_args(path: str, args: argparse.Namespace):
    """The record at ``path`` read with ``args.units`` and ``args.record_dt`` (when the command
    has them): a `groundmotions.records.GroundMotion` [m/s^2]."""
    from groundmotions.readers import read_record

    try:
        return read_record(path, units=getattr(args, "units", None),
                           dt=getattr(args, "record_dt", None))
    except InputError as error:
        raise record_dt_named(error, path, getattr(args, "record_dt", None)) from None


_RECORD_DT = re.compile(r"The 'dt' parameter of read_\w+(?: \(--record-dt on the command "
                        r"line\))?")


_API_HINT = re.compile(r" ?\(give the step of one-column records with "
                       r"read_pair\(\.\.\., dt=\.\.\.\) or a 'dt' column in a pair manifest\)")


def record_dt_named(error: Exception, path: str, record_dt: float | None) -> Exception:
    """``error`` of a record reader about its ``dt`` argument, reworded to name ``--record-dt``
    (the flag that gave it) instead of the reader's parameter; any other error as it is."""
    text = str(error)
    if not _RECORD_DT.search(text):
        return error
    text = _API_HINT.sub("", text)
    if record_dt is None and "one-column" in text:
        head = text[:_RECORD_DT.search(text).start()]  # a pair's "Pair 'x': the x component..."
        file = re.search(r"one-column file (.+?) ", text)
        return InputError(f"{head}{file.group(1) if file else path}: a one-column record has no "
                          "time step of its own: give it with --record-dt [s] (e.g. "
                          "--record-dt 0.01).")
    return InputError(_RECORD_DT.sub("--record-dt", text, count=1))


def add_integration_flags(p: argparse.ArgumentParser, alpha_note: str = "") -> None:
    """Add ``--integrator``, ``--alpha`` (its help ending in ``alpha_note``) and ``--dt``, the
    time integration of a building run (:func:`building_run_inputs` reads them)."""
    p.add_argument("--integrator", choices=("newmark", "hht"),
                   help="time integration (default: the building file's)")
    p.add_argument("--alpha", type=float, help="HHT alpha in [-1/3, 0]" + alpha_note)
    p.add_argument("--dt", type=float, help="analysis time step [s], in (0, 1] and at most "
                   "the record's (default: the file's, else the record's in parts of at most "
                   "5 ms)")


def add_max_steps(p: argparse.ArgumentParser, what: str = "the run") -> None:
    """Add ``--max-steps``, the bound on a run's time steps (:mod:`isolator.limits`)."""
    from isolator.limits import DEFAULT_MAX_STEPS

    p.add_argument("--max-steps", type=int, default=DEFAULT_MAX_STEPS, metavar="N",
                   help=f"refuse {what} if it would take more than N time steps (duration / "
                   f"dt) or more memory than is available (default {DEFAULT_MAX_STEPS:,})")


def analysis_dt(args: argparse.Namespace, config, motion=None) -> float | None:
    """The analysis step [s]: ``--dt`` when given, else the building file's capped at the step
    of ``motion`` (a record or a pair; the run says so when it caps it), else None for
    :func:`structures.analysis.default_step`."""
    if args.dt is not None or config.dt is None:
        return args.dt
    return config.dt if motion is None else min(config.dt, motion.dt)


def check_run_length(args: argparse.Namespace, config, motion, command: str) -> None:
    """Refuse a building run past ``--max-steps`` or the memory available, before any work."""
    from structures.analysis import check_length

    check_length(config.building, motion, analysis_dt(args, config, motion),
                 max_steps=args.max_steps, raise_with="--max-steps", owner=command)


def integrator_from_args(config, kind: str | None, alpha: float | None):
    """The building file's integrator, or the one ``--integrator``/``--alpha`` ask for (HHT
    with the file's alpha when the file runs HHT and ``--alpha`` is not given)."""
    from structures.integrators import HHT, Newmark

    if kind is None and alpha is None:
        return config.integrator
    if (kind or ("hht" if isinstance(config.integrator, HHT) else "newmark")) == "newmark":
        if alpha is not None:
            raise InputError("--alpha applies to --integrator hht only.")
        return Newmark()
    if alpha is None:
        alpha = config.integrator.alpha if isinstance(config.integrator, HHT) else -0.05
    return HHT(alpha=alpha)


def building_run_inputs(args: argparse.Namespace, command: str):
    """The building file, the integrator and the (scaled) record or pair of a building command,
    ``(config, integrator, motion)``, every value checked before any work starts.

    Reads ``args.building``, ``args.integrator``, ``args.alpha``, ``args.record`` (with
    ``args.units`` and ``args.record_dt``; with ``args.record_y`` or ``args.record_z`` a pair,
    :func:`pair_from_args`) and ``args.scale``, and checks ``args.dt`` and ``args.max_steps``
    where the command has them.
    """
    from dcfpb.common.validation import check_int, check_real
    from structures.config import load_config

    check_real(args.scale, "--scale", command, low=0.0, low_open=True)
    if getattr(args, "dt", None) is not None:
        check_real(args.dt, "--dt", command, low=0.0, low_open=True, high=1.0)
    if hasattr(args, "max_steps"):
        check_int(args.max_steps, "--max-steps", command, low=1)
    config = load_config(args.building)
    integrator = integrator_from_args(config, args.integrator, args.alpha)
    if getattr(args, "record_y", None) is not None or getattr(args, "record_z", None) is not None:
        return config, integrator, pair_from_args(args, config, command)
    for flag in ("resample", "truncate"):  # they act on the components of a pair only
        if getattr(args, flag, False):
            import warnings

            from dcfpb.common.errors import InputWarning

            warnings.warn(f"--{flag} has no effect without --record-y: it aligns the components "
                          "of a pair, and one record is run on its own.", InputWarning,
                          stacklevel=2)
    motion = read_record_from_args(args.record, args)
    if args.scale != 1.0:
        motion = motion.scaled(args.scale)
    return config, integrator, motion


def add_pair_options(p: argparse.ArgumentParser) -> None:
    """Add ``--record-y``, ``--record-z``, ``--resample`` and ``--truncate`` to a command that
    reads ``--record``."""
    p.add_argument("--record-y", metavar="FILE",
                   help="second horizontal component (y of the plan); with --record (x) it "
                   "runs a building file with a [plan] table in plan")
    p.add_argument("--record-z", metavar="FILE",
                   help="vertical component (positive up), with --record-y")
    p.add_argument("--resample", action="store_true",
                   help="resample components whose time step differs from the x component's")
    p.add_argument("--truncate", action="store_true",
                   help="cut the components to the shortest (they must start together)")


def pair_from_args(args: argparse.Namespace, config, command: str):
    """The (scaled) `GroundMotionPair` of ``--record``/``--record-y``/``--record-z``, checked
    before anything is read: a pair needs a ``[plan]`` table, ``--record-z`` needs ``--record-y``.
    """
    from dcfpb.common.errors import InputError
    from groundmotions.pairs import read_pair

    if args.record_y is None:
        raise InputError("--record-z needs --record-y (the vertical comes with a "
                         "pair of horizontal components).")
    if config.plan is None:
        raise InputError(
            "--record-y runs a building in plan, but the building file "
            f"{args.building!r} has no [plan] table (bearing_coordinates, eccentricity, ...; "
            "see README, 'A building in plan'). Drop --record-y to run it in one direction.")
    step = None
    if args.resample:
        step = read_record_from_args(args.record, args).dt
    try:
        pair = read_pair(args.record, args.record_y, args.record_z,
                         dt=getattr(args, "record_dt", None),
                         units=getattr(args, "units", None), resample_to=step,
                         truncate=args.truncate)
    except InputError as error:
        named = record_dt_named(error, args.record, getattr(args, "record_dt", None))
        if named is not error:  # the step given or missing, not a mismatch of the components
            raise named from None
        hint = ""
        if "time step" in str(error) and not args.resample:
            hint = "--resample resamples the y (and z) component to the x component's step."
        elif "samples" in str(error) and not args.truncate:
            hint = "--truncate cuts the components to the shortest."
        if hint:
            raise InputError(f"{error} On the command line: {hint}") from None
        raise
    return pair.scaled(args.scale) if args.scale != 1.0 else pair


def _run_building(args: argparse.Namespace) -> int:
    from structures.compiled.ahead import compile_ahead

    check_building_outputs(args, files={"--output": args.output}, folders={"--plot": args.plot})
    with compile_ahead() as ahead:  # the engine compiles while the inputs are read
        # bad input (a record of 31 M steps) is refused first, before this process compiles
        config, integrator, motion = building_run_inputs(args, "dcfpb run")
        check_run_length(args, config, motion, "dcfpb run")
        ahead.help()
        from structures.analysis import peaks
        from structures.fixed_base import ratios_to_fixed_base, run_fixed_base
        from structures.floor_spectra import with_floor_spectra_all
        from structures.runner import run

        model = args.model or config.friction["model"]
        ahead.wait()
        result = run(config, motion, model=model, integrator=integrator,
                     dt=args.dt, max_steps=args.max_steps)
    summary = peaks(result)
    warn_uplift(summary, result.sizes["bearing"])
    building = config.building if result.sizes["direction"] == 2 else dataclasses.replace(
        config.building, plan=None)
    fixed = run_fixed_base(building, motion, dt=result.attrs["dt"], max_steps=args.max_steps)
    results = with_floor_spectra_all({model: result, FIXED_BASE: fixed}, motion)
    result, fixed = results[model], results[FIXED_BASE]
    ratios = ratios_to_fixed_base(result, fixed)
    from dcfpb.cli.outputs import writing

    if args.output:
        from structures.results import write_netcdf

        with writing("--output", args.output):
            write_netcdf(result, args.output)
    if args.plot:
        from dcfpb.plotting import plot_runs

        with writing("--plot", args.plot):
            plot_runs({model: result}, args.plot, title=f"{config.name}: {motion.name}",
                      fixed_base=fixed)
    if args.json:
        print(json.dumps(summary | {"success": bool(result.attrs["success"]),
                                    "message": result.attrs["message"],
                                    "ratios_to_fixed_base": ratios}, indent=2))
    else:
        what = "the pair " if result.sizes["direction"] == 2 else ""
        print_peaks({model: summary}, f"{config.name} under {what}{motion.name} "
                    f"(scale {args.scale:g}, {integrator!r})", fixed_base=fixed)
        print()
        print_ratios({model: ratios}, fixed, float(abs(fixed["ground_acceleration"]).max()))
        print_failure(summary, result.attrs["message"])
    report_failure("run", summary, result.attrs["message"])
    return EXIT_OK if result.attrs["success"] else EXIT_RUN_FAILED


RUN_FORMATS = {".nc": "netCDF"}
"""The suffixes of ``dcfpb run --output`` and the format each writes."""


def building_inputs(args: argparse.Namespace) -> dict[str, object]:
    """The input files of a building command by what they are (for the output checks)."""
    return {"the building file": args.building, "the record (--record)": args.record,
            "the record (--record-y)": getattr(args, "record_y", None),
            "the record (--record-z)": getattr(args, "record_z", None)}


def check_building_outputs(args: argparse.Namespace, *, files: dict | None = None,
                           folders: dict | None = None) -> None:
    """Check the outputs of a building command (``run``, ``compare-opensees``) before any
    work: ``--output`` a netCDF file (:data:`RUN_FORMATS`), ``--plot`` a folder of the figures
    of :func:`dcfpb.plotting.plot_runs`, none of them an input, none there unless
    ``--overwrite``."""
    from dcfpb.cli.outputs import PLAN_FIGURES, RUN_FIGURES, check_outputs

    plan = getattr(args, "record_y", None) is not None
    check_outputs(files=files, folders=folders, inputs=building_inputs(args),
                  overwrite=args.overwrite, formats={"--output": RUN_FORMATS},
                  writes={"--plot": PLAN_FIGURES if plan else RUN_FIGURES})


def warn_uplift(summary: dict, positions: int) -> None:
    """Warn (:class:`structures.results.UpliftWarning`, one line) that bearings lifted off in
    the run; nothing when none did. ``summary`` is :func:`structures.analysis.peaks` of the run,
    ``positions`` its number of bearing positions."""
    if not summary.get("uplift_bearings"):
        return
    import warnings

    from structures.results import UpliftWarning

    warnings.warn(
        f"{summary['uplift_bearings']} of {positions} bearing positions lifted off (axial load "
        f"<= 0: no friction and no restoring force there), first at t = "
        f"{summary['uplift_first_time']:.6g} s, for up to {summary['uplift_steps']} steps, the "
        f"longest {summary['uplift_longest']:.6g} s at a time; see uplift_steps, "
        "uplift_first_time and uplift_longest in the peaks and the Dataset's attributes.",
        UpliftWarning, stacklevel=2)


def report_failure(command: str, summary: dict, message: str) -> None:
    """One line ``dcfpb <command>: run failed (<kind>) at t = <time> s: <message>`` on stderr
    for a run that failed (the exit status 1 of the failure contract), also with ``--json``;
    nothing for a run that finished. ``summary`` is :func:`structures.analysis.peaks`."""
    if not summary.get("peaks_up_to_failure"):
        return
    import sys

    failed_at = summary.get("failed_at")
    when = f" at t = {failed_at:.6g} s" if failed_at is not None else ""
    print(f"dcfpb {command}: run failed ({summary.get('failure') or 'error'}){when}: "
          f"{message}", file=sys.stderr)


def print_failure(summary: dict, message: str) -> None:
    """Say that a run failed, why, and that its peaks are those up to the failure; nothing for
    a run that finished. ``summary`` is :func:`structures.analysis.peaks` of the run."""
    if not summary.get("peaks_up_to_failure"):
        return
    print(f"RUN FAILED ({summary['failure']}) at t = {summary['failed_at']:.6g} s: the peaks "
          "above are those up to the failure, not of the whole record.")
    print(f"  {message}")


def print_peaks(rows: dict[str, dict], heading: str, *, fixed_base=None) -> None:
    """Print a peaks table under ``heading``, one row per run (:func:`structures.analysis.peaks`
    of each); in plan with the centre's displacement and the roof acceleration and drift per
    direction. ``fixed_base`` (a :func:`structures.fixed_base.run_fixed_base` Dataset) adds its
    row: the first-storey shear as base shear, no isolator, temperature or energy."""
    plan = "peak_centre_displacement" in next(iter(rows.values()))
    directions = ("_x", "_y") if plan else ("",)
    columns = [("isol. disp", "[mm]", 10,
                lambda p: f"{1e3 * p['peak_isolator_displacement']:.1f}")]
    if plan:
        columns.append(("centre", "[mm]", 8,
                        lambda p: f"{1e3 * p['peak_centre_displacement']:.1f}"))
    columns.append(("base shear", "[kN]", 11, lambda p: f"{p['peak_base_shear'] / 1e3:.0f}"))
    for d in directions:
        columns.append((f"roof acc{d.replace('_', ' ')}", "[m/s2]", 10 if plan else 9,
                        lambda p, d=d: f"{p[f'peak_roof_acceleration{d}']:.2f}"))
    for d in directions:
        columns.append((f"drift{d.replace('_', ' ')}", "[mm]", 7,
                        lambda p, d=d: f"{1e3 * p[f'peak_storey_drift{d}']:.2f}"))
    columns += [("T max", "[degC]", 7, lambda p: f"{p['max_temperature']:.1f}"),
                ("energy err", "[-]", 10, lambda p: f"{p['energy_balance_error']:.1e}"),
                ("wall", "[s]", 6, lambda p: f"{p['wall_time']:.2f}")]
    print(heading)
    for line in (0, 1):
        print(f"{'model' if line == 0 else '':12s} "
              + " ".join(f"{column[line]:>{column[2]}s}" for column in columns))
    for name, p in rows.items():
        print(f"{name:12s} " + " ".join(f"{cell(p):>{width}s}" for _, _, width, cell in columns))
    if fixed_base is not None:
        from structures.fixed_base import superstructure_peaks

        p = superstructure_peaks(fixed_base)
        shear = max(v for k, v in p.items() if k.startswith("peak_base_shear"))
        cells = {"base shear": f"{shear / 1e3:.0f}", "wall": f"{fixed_base.attrs['wall_time']:.2f}"}
        for d in directions:
            cells[f"roof acc{d.replace('_', ' ')}"] = f"{p[f'peak_roof_acceleration{d}']:.2f}"
            cells[f"drift{d.replace('_', ' ')}"] = f"{1e3 * p[f'peak_storey_drift{d}']:.2f}"
        print(f"{FIXED_BASE:12s} " + " ".join(f"{cells.get(name, '-'):>{width}s}"
                                               for name, _, width, _ in columns))
    if plan:
        print("isol. disp: the corner bearing (largest resultant); centre: the base slab at the "
              "plan's reference point; base shear: resultant")


def print_ratios(ratios: dict[str, dict[str, float]], fixed_base, pga: float) -> None:
    """Print each isolated run's peaks over the fixed base's, and the roof acceleration over
    ``pga`` [m/s^2] (in plan the larger component's). ``ratios`` holds
    :func:`structures.fixed_base.ratios_to_fixed_base` of each run by label; ``fixed_base`` is the
    fixed-base run."""
    from structures.fixed_base import superstructure_peaks

    first = next(iter(ratios.values()))
    directions = ("_x", "_y") if "peak_storey_drift_x" in first else ("",)
    print("isolated / fixed base (below 1: the isolation reduces it)")
    for d in directions:
        where = f", {d[1]}" if d else ""
        print(f"{'model' + where:12s} {'drift':>7s} {'storey shear':>13s} {'roof acc':>9s} "
              f"{'base shear':>11s}")
        for name, r in ratios.items():
            print(f"{name:12s} {r[f'peak_storey_drift{d}']:7.3f} "
                  f"{r[f'peak_storey_shear{d}']:13.3f} {r[f'peak_roof_acceleration{d}']:9.3f} "
                  f"{r[f'peak_base_shear{d}']:11.3f}")
    fixed = superstructure_peaks(fixed_base)
    roof = max(v for k, v in fixed.items() if k.startswith("peak_roof_acceleration"))
    def roof_of(r: dict[str, float]) -> float:  # the isolated roof's peak [m/s^2]
        return max(r[f"peak_roof_acceleration{d}"] * fixed[f"peak_roof_acceleration{d}"]
                   for d in directions)

    isolated = ", ".join(f"{name} {roof_of(r) / pga:.2f}" for name, r in ratios.items())
    print(f"roof acceleration / PGA ({pga:.2f} m/s2): fixed base {roof / pga:.2f}; {isolated}.")
    print("An isolated roof above the PGA comes from the friction force reversing at each "
          "stick-slip (a step of\nabout 2 mu W of base shear) exciting the sliding building's "
          "own modes; it hardly depends on the\nbearings' u_y and falls with the "
          "superstructure's damping: docs/presliding_study.md.")


def example_path(name: str) -> Path:
    """The example building file shipped in the package (a copy of ``examples/NAME``)."""
    from importlib.resources import files

    return Path(str(files("dcfpb").joinpath("data", name)))
