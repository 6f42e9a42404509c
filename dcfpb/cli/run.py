"""``dcfpb run``: a building file under a recorded ground motion; and what the other building
commands share with it (the inputs, the integrator flags, the peaks table, the bundled example)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from dcfpb.cli.pairs import add_pair_options


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
    p.add_argument("--integrator", choices=("newmark", "hht"),
                   help="time integration (default: the building file's)")
    p.add_argument("--alpha", type=float, help="HHT alpha in [-1/3, 0]")
    p.add_argument("--dt", type=float, help="analysis time step [s], in (0, 1] and at most "
                   "the record's (default: the file's, else the record's in parts of at most "
                   "5 ms)")
    add_max_steps(p)
    add_record_options(p)
    p.add_argument("--json", action="store_true", help="print the peaks as JSON")
    p.add_argument("--output", metavar="FILE.nc", help="write the full result to netCDF")
    p.add_argument("--plot", metavar="DIR", help="write plots to this folder")
    p.set_defaults(handler=_run_building)


RECORD_UNITS = ("g", "gal", "cm/s^2", "m/s^2", "mm/s^2", "in/s^2", "ft/s^2")
"""The ``--units`` choices: `groundmotions.units.UNIT_NAMES` written out (parsing imports no
numpy; a test holds the two equal)."""


def add_record_options(p: argparse.ArgumentParser, dt_flags: tuple[str, ...] = ("--record-dt",),
                       ) -> None:
    """Add ``--units`` and ``--record-dt`` (the record's own step, not the analysis step) to
    a command that reads ``--record``/``FILE`` with :func:`read_record_from_args`."""
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

    return read_record(path, units=getattr(args, "units", None),
                       dt=getattr(args, "record_dt", None))


def add_max_steps(p: argparse.ArgumentParser, what: str = "the run") -> None:
    """Add ``--max-steps``, the bound on a run's time steps (:mod:`isolator.limits`)."""
    from isolator.limits import DEFAULT_MAX_STEPS

    p.add_argument("--max-steps", type=int, default=DEFAULT_MAX_STEPS, metavar="N",
                   help=f"refuse {what} if it would take more than N time steps (duration / "
                   f"dt) or more memory than is available (default {DEFAULT_MAX_STEPS:,})")


def analysis_dt(args: argparse.Namespace, config) -> float | None:
    """The analysis step [s]: ``--dt`` when given, else the building file's (None: the
    analysis's default, :func:`structures.analysis.default_step`)."""
    return args.dt if args.dt is not None else config.dt


def check_run_length(args: argparse.Namespace, config, motion, command: str) -> None:
    """Refuse a building run past ``--max-steps`` or the memory available, before any work."""
    from structures.analysis import default_step
    from structures.limits import building_fields, check_run

    dt = analysis_dt(args, config)
    check_run(motion, default_step(motion.dt) if dt is None else dt,
              building_fields(config.building.n_storeys), max_steps=args.max_steps,
              raise_with="--max-steps", owner=command)


def integrator_from_args(config, kind: str | None, alpha: float | None):
    """The building file's integrator, or the one ``--integrator``/``--alpha`` ask for (with
    the file's alpha when the file runs HHT and ``--alpha`` is not given)."""
    from structures.integrators import HHT, Newmark

    if kind is None and alpha is None:
        return config.integrator
    if (kind or ("hht" if isinstance(config.integrator, HHT) else "newmark")) == "newmark":
        if alpha is not None:
            raise ValueError("--alpha applies to --integrator hht only.")
        return Newmark()
    if alpha is None:
        alpha = config.integrator.alpha if isinstance(config.integrator, HHT) else -0.05
    return HHT(alpha=alpha)


def building_run_inputs(args: argparse.Namespace, command: str):
    """The building file, the integrator and the (scaled) record of a building command.

    Reads ``args.building``, ``args.integrator``, ``args.alpha``, ``args.record`` (with
    ``args.units`` and ``args.record_dt`` when given) and ``args.scale``, and checks
    ``args.dt`` and ``args.max_steps`` when the command has them; every value is checked
    before any work starts.

    Returns
    -------
    config : BuildingConfig
    integrator : Newmark or HHT
    motion : GroundMotion
    """
    from dcfpb.common.validation import check_int, check_real
    from structures.config import load_config

    check_real(args.scale, "scale", command, low=0.0, low_open=True)
    if getattr(args, "dt", None) is not None:
        check_real(args.dt, "--dt", command, low=0.0, low_open=True, high=1.0)
    if hasattr(args, "max_steps"):
        check_int(args.max_steps, "--max-steps", command, low=1)
    config = load_config(args.building)
    integrator = integrator_from_args(config, args.integrator, args.alpha)
    motion = read_record_from_args(args.record, args)
    if args.scale != 1.0:
        motion = motion.scaled(args.scale)
    return config, integrator, motion


def _run_building(args: argparse.Namespace) -> int:
    from dcfpb.cli.outputs import check_outputs
    from structures.compiled.ahead import compile_ahead

    if args.record_y is not None or args.record_z is not None:
        return run_plan(args)

    check_outputs(files={"--output": args.output}, folders={"--plot": args.plot})
    with compile_ahead() as ahead:  # the engine compiles while the inputs are read
        # bad input (a record of 31 M steps) is refused first, before this process compiles
        config, integrator, motion = building_run_inputs(args, "dcfpb run")
        check_run_length(args, config, motion, "dcfpb run")
        if config.plan is not None:
            import warnings

            from dcfpb.common.errors import InputWarning

            warnings.warn(InputWarning(
                "the building file's [plan] table is not used: one record runs the planar "
                "building along x; give "
                "--record-y to run it in plan"), stacklevel=1)
        ahead.help()
        from structures.analysis import peaks
        from structures.floor_spectra import with_floor_spectra
        from structures.runner import run

        model = args.model or config.friction["model"]
        ahead.wait()
        result = run(config, motion, model=model, integrator=integrator,
                     dt=analysis_dt(args, config), max_steps=args.max_steps)
    summary = peaks(result)
    result = with_floor_spectra(result, motion)
    if args.output:
        result.to_netcdf(args.output)
    if args.plot:
        from dcfpb.plotting import plot_runs

        plot_runs({model: result}, args.plot, title=f"{config.name}: {motion.name}")
    if args.json:
        keys = ("peak_isolator_displacement", "peak_base_shear", "peak_roof_acceleration",
                "energy_balance_error", "steps", "wall_time")
        print(json.dumps({k: summary[k] for k in keys} | {
            "peak_storey_drift": summary["peak_storey_drift"],
            "max_temperature": summary["max_temperature"],
            "success": bool(result.attrs["success"]), "message": result.attrs["message"],
            "peaks_up_to_failure": summary["peaks_up_to_failure"],
            "failed_at": summary["failed_at"], "failure": summary["failure"]},
            indent=2))
    else:
        print_peaks({model: summary}, f"{config.name} under {motion.name} "
                     f"(scale {args.scale:g}, {integrator!r})")
        print_failure(summary, result.attrs["message"])
    return 0 if result.attrs["success"] else 1


def run_plan(args: argparse.Namespace) -> int:
    """``dcfpb run BUILDING.toml --record X --record-y Y [--record-z Z]``: the building in plan
    under the pair (the reference engine)."""
    from dcfpb.cli.outputs import check_outputs
    from dcfpb.cli.pairs import pair_from_args, print_plan_peaks
    from dcfpb.common.validation import check_int, check_real
    from structures.config import load_config
    from structures.limits import check_run
    from structures.spatial.analysis import spatial_fields
    from structures.spatial.peaks import plan_peaks

    command = "dcfpb run"
    check_outputs(files={"--output": args.output}, folders={"--plot": args.plot})
    check_real(args.scale, "scale", command, low=0.0, low_open=True)
    if args.dt is not None:
        check_real(args.dt, "--dt", command, low=0.0, low_open=True, high=1.0)
    check_int(args.max_steps, "--max-steps", command, low=1)
    config = load_config(args.building)
    integrator = integrator_from_args(config, args.integrator, args.alpha)
    pair = pair_from_args(args, config, command)
    from structures.analysis import default_step
    from structures.runner import run

    dt = args.dt if args.dt is not None else config.dt
    check_run(pair.x, default_step(pair.dt) if dt is None else dt,
              spatial_fields(config.building.n_storeys, config.plan.n_bearings),
              max_steps=args.max_steps, raise_with="--max-steps", owner=command)
    model = args.model or config.friction["model"]
    result = run(config, pair, model=model, integrator=integrator, dt=dt,
                 max_steps=args.max_steps)
    summary = plan_peaks(result)
    if args.output:
        result.to_netcdf(args.output)
    if args.plot:
        from dcfpb.plotting.plan import plot_plan_runs

        plot_plan_runs({model: result}, args.plot, title=f"{config.name}: {pair.name}")
    if args.json:
        print(json.dumps(summary | {"success": bool(result.attrs["success"]),
                                    "message": result.attrs["message"]}, indent=2))
    else:
        print_plan_peaks({model: summary}, f"{config.name} under the pair {pair.name} "
                         f"(scale {args.scale:g}, {integrator!r})")
        print_failure(summary, result.attrs["message"])
    return 0 if result.attrs["success"] else 1


def print_failure(summary: dict, message: str) -> None:
    """Say that a run failed, why, and that its peaks are those up to the failure (nothing
    for a run that finished). ``summary`` is :func:`structures.analysis.peaks` of it."""
    if not summary.get("peaks_up_to_failure"):
        return
    print(f"RUN FAILED ({summary['failure']}) at t = {summary['failed_at']:.6g} s: the peaks "
          "above are those up to the failure, not of the whole record.")
    print(f"  {message}")


def print_peaks(rows: dict[str, dict], heading: str, *, fixed_base=None) -> None:
    """Print a peaks table, one row per run, under ``heading``.

    ``fixed_base`` (a :func:`structures.fixed_base.run_fixed_base` Dataset) adds its row: the
    first-storey shear in the base-shear column, no isolator, temperature or energy.
    """
    print(heading)
    print(f"{'model':12s} {'isol. disp':>10s} {'base shear':>11s} {'roof acc':>9s} "
          f"{'drift':>7s} {'T max':>7s} {'energy err':>10s} {'wall':>6s}")
    print(f"{'':12s} {'[mm]':>10s} {'[kN]':>11s} {'[m/s2]':>9s} {'[mm]':>7s} {'[degC]':>7s} "
          f"{'[-]':>10s} {'[s]':>6s}")
    for name, p in rows.items():
        print(f"{name:12s} {1e3 * p['peak_isolator_displacement']:10.1f} "
              f"{p['peak_base_shear'] / 1e3:11.0f} {p['peak_roof_acceleration']:9.2f} "
              f"{1e3 * p['peak_storey_drift']:7.2f} {p['max_temperature']:7.1f} "
              f"{p['energy_balance_error']:10.1e} {p['wall_time']:6.2f}")
    if fixed_base is not None:
        from structures.fixed_base import superstructure_peaks

        p = superstructure_peaks(fixed_base)
        print(f"{'fixed base':12s} {'-':>10s} {p['peak_base_shear'] / 1e3:11.0f} "
              f"{p['peak_roof_acceleration']:9.2f} {1e3 * p['peak_storey_drift']:7.2f} "
              f"{'-':>7s} {'-':>10s} {fixed_base.attrs['wall_time']:6.2f}")


def example_path(name: str) -> Path:
    """The example building file shipped in the package (a copy of ``examples/NAME``)."""
    from importlib.resources import files

    return Path(str(files("dcfpb").joinpath("data", name)))
