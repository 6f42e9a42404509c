"""``dcfpb compare-opensees`` and ``dcfpb compare-opensees-bearing``: our runs against OpenSees.

A building file (:func:`~structures.opensees.comparison.run_comparison`) or one bearing under a
sine (:func:`~structures.opensees.comparison.run_bearing_comparison`); peaks, differences and
wall times printed. Registered in ``dcfpb.cli.COMMAND_MODULES``.
"""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

from dcfpb.cli.run import (
    add_integration_flags,
    add_max_steps,
    add_pair_options,
    add_record_options,
)
from dcfpb.common.errors import EXIT_BAD_INPUT, EXIT_OK, EXIT_RUN_FAILED

MODELS = ("constant", "velocity", "ptv")
_ELEMENT = {"constant": "coulomb", "velocity": "velocity", "ptv": "ptv"}


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add ``compare-opensees`` and ``compare-opensees-bearing`` to the ``dcfpb`` parser."""
    from dcfpb.cli.protocol import add_sine_flags

    p = subparsers.add_parser(
        "compare-opensees",
        help="run a building file with our engine and with OpenSees, and compare",
        description="Run a building file (TOML) under a ground motion, or a building file with "
        "a [plan] table under a pair, with our engine and with openseespy (same masses, "
        "stiffnesses, damping, bearings, record and integrator) and compare peaks, histories "
        "(NRMSE = RMS difference / peak of ours) and wall times. All values in SI units.",
    )
    p.add_argument("building", metavar="BUILDING.toml", help="building file")
    p.add_argument("--record", required=True, metavar="FILE", help="ground-motion record")
    p.add_argument("--model", choices=MODELS, default="constant",
                   help="friction model: constant (Coulomb), velocity (VelDependent) or ptv "
                   "(FPBearingPTV; its cost grows as the square of the steps: see "
                   "--duration) (default: constant)")
    p.add_argument("--scale", type=float, default=1.0, help="amplitude scale factor [-]")
    p.add_argument("--duration", type=float, help="use only the first DURATION s of the record")
    p.add_argument("--pendulum", choices=("singlefp", "spring"), default="singlefp",
                   help="OpenSees pendulum: singleFPBearing (its normal force is W + F u/R) or "
                   "flatSliderBearing plus a linear spring W/R (N = W, as ours) "
                   "(default: singlefp)")
    add_integration_flags(p, " (OpenSees: 1 + alpha)")
    add_max_steps(p, "each run")
    add_record_options(p)
    add_pair_options(p)
    p.add_argument("--overturning", action=argparse.BooleanOptionalAction,
                   help="with a pair: the overturning of the floors' inertia forces on both "
                   "sides (ours's axial loads; the OpenSees floors at their storey heights) "
                   "(default: when the file's [plan] has storey_heights)")
    p.add_argument("--json", action="store_true", help="print the comparison as JSON")
    p.add_argument("--plot", metavar="DIR", help="write overlay plots to this folder")
    p.add_argument("--overwrite", action="store_true",
                   help="replace output files that exist (never an input of the command)")
    p.set_defaults(handler=run_building)

    b = subparsers.add_parser(
        "compare-opensees-bearing",
        help="one bearing under an imposed sine, ours against OpenSees",
        description="Impose a sine displacement on one bearing in our virtual test machine and "
        "on its OpenSees element; compare force, EDC and temperature. SI units.",
    )
    b.add_argument("--model", choices=MODELS, default="constant",
                   help="friction model (default: constant)")
    b.add_argument("--slider-diameter", type=float, default=0.3, help="slider diameter [m]")
    b.add_argument("--pressure", type=float, default=60e6, help="contact pressure [Pa]")
    add_sine_flags(b, amplitude=0.2)
    b.add_argument("--mu-t0", type=float, default=None,
                   help="mu_t0 (velocity, ptv; default 0.075; with constant a warning: no "
                   "effect)")
    b.add_argument("--json", action="store_true", help="print the comparison as JSON")
    b.set_defaults(handler=run_bearing)


def _import_error(command: str, error: ImportError) -> int:
    import sys

    print(f"dcfpb {command}: error: {error}", file=sys.stderr)
    return EXIT_BAD_INPUT


def _inputs(args: argparse.Namespace, command: str):
    """The building file, the integrator, the (scaled, truncated) record or pair and the
    analysis step, every flag checked and the run's length bounded before any work
    (:func:`dcfpb.cli.run.building_run_inputs`)."""
    from dcfpb.cli.run import (
        analysis_dt,
        building_run_inputs,
        check_building_outputs,
        check_run_length,
    )
    from dcfpb.common.errors import InputError
    from dcfpb.common.validation import check_real
    from structures.opensees.comparison import truncated

    if args.overturning and args.record_y is None and args.record_z is None:
        raise InputError("--overturning applies to a building in plan under a pair: give "
                         "--record-y (and a building file with a [plan] table).")
    check_building_outputs(args, folders={"--plot": args.plot})
    if args.duration is not None:
        check_real(args.duration, "--duration", command, low=0.0, low_open=True)
    config, integrator, motion = building_run_inputs(args, command)
    if args.overturning and config.plan is not None and config.plan.storey_heights is None:
        raise InputError("--overturning needs the storey heights of the building file's [plan] "
                         "table (storey_heights, the lever arms of the floors' inertia forces); "
                         f"{args.building} has none.")
    if args.duration is not None:
        motion = truncated(motion, args.duration)
    check_run_length(args, config, motion, command)
    return config, integrator, motion, analysis_dt(args, config, motion)


def run_building(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb compare-opensees``; returns the exit status."""
    from dcfpb.cli.run import print_failure, report_failure
    from structures.opensees.comparison import comparison_bearing, run_comparison

    config, integrator, motion, dt = _inputs(args, "dcfpb compare-opensees")
    bearing = comparison_bearing(config, args.model)
    try:
        result = run_comparison(config.building, bearing, motion, integrator,
                                n_bearings=config.n_bearings, dt=dt, pendulum=args.pendulum,
                                overturning=args.overturning, max_steps=args.max_steps)
    except ImportError as error:
        return _import_error("compare-opensees", error)
    summary = result.summary
    plan = config.building.plan is not None
    if args.plot:
        from dcfpb.cli.outputs import writing
        from dcfpb.plotting import plot_runs

        with writing("--plot", args.plot):
            plot_runs({"ours": result.ours, "opensees": result.opensees}, args.plot,
                      title=f"{config.name}: {motion.name}, {args.model} model, ours and "
                      "OpenSees")
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        from dcfpb.cli.run import print_peaks

        print_peaks({"ours": summary["ours"], "opensees": summary["opensees"]},
                    f"{config.name} under {'the pair ' if plan else ''}{motion.name} (scale "
                    f"{args.scale:g}, {integrator!r}), {args.model} model; OpenSees: "
                    f"{summary['opensees']['element']}")
        print_differences(summary)
        for side in ("ours", "opensees"):
            print_failure(summary[side], f"{side}: {summary[side]['message']}")
    for side in ("ours", "opensees"):
        report_failure("compare-opensees", summary[side], f"{side}: {summary[side]['message']}")
    ok = summary["ours"]["success"] and summary["opensees"]["success"]
    return EXIT_OK if ok else EXIT_RUN_FAILED


def print_differences(summary: dict[str, Any]) -> None:
    """The differences of :func:`structures.opensees.comparison.compare` as two tables: the
    peaks, and the NRMSE of each history per direction."""
    d = summary["difference"]
    plan = "corner_bearing" in summary
    overturning = " (both with overturning)" if summary["ours"].get("overturning") else ""
    print(f"\nOpenSees against ours{overturning}: peak = max|OS| / max|ours| - 1"
          f"{' of the resultant' if plan else ''}; NRMSE = RMS difference / peak of ours"
          f"{', per component' if plan else ''}")
    print(f"{'':40s} {'peak [%]':>9s}")
    for key, value in d.items():
        if key.startswith("peak_"):
            print(f"{key[5:].replace('_', ' '):40s} {100 * value:9.3f}")
    suffixes = ("_x", "_y") if plan else ("",)
    rows: dict[str, list[float]] = {}
    for key, value in d.items():
        if key.startswith("nrmse_") and key != "nrmse_axial_load":
            name = key[6:]
            base = name[:-2] if name[-2:] in suffixes else name
            rows.setdefault(base, []).append(value)
    print(f"{'':40s}" + "".join(f" {'NRMSE' + s.replace('_', ' ') + ' [%]':>12s}"
                                for s in suffixes))
    for name, values in rows.items():
        print(f"{name.replace('_', ' '):40s}" + "".join(f" {100 * v:12.3f}" for v in values))
    if "axial_load" in summary:
        print_axial_loads(summary)
    if not math.isnan(d["max_temperature_gap"]):
        print(f"largest temperature gap: {d['max_temperature_gap']:.2f} degC")
    ours, opensees = summary["ours"]["wall_time"], summary["opensees"]["wall_time"]
    print(f"wall time: ours {ours:.3f} s, OpenSees {opensees:.3f} s, ratio ours/OpenSees "
          f"{summary['wall_time_ratio']:.3g}")
    for side in ("ours", "opensees"):
        if not summary[side]["success"]:
            print(f"warning: the {side} run stopped early: {summary[side]['message']}")


def print_axial_loads(summary: dict[str, Any]) -> None:
    """The axial loads of the corner bearings in plan (``summary["axial_load"]`` of
    :func:`structures.opensees.comparison.compare`) and their differences."""
    loads, d = summary["axial_load"], summary["difference"]
    print("axial loads of the corner bearings [kN] (OpenSees: the elements' normal force)")
    print(f"{'bearing':>8s} {'gravity':>9s} {'ours max':>9s} {'OS max':>9s} {'ours min':>9s} "
          f"{'OS min':>9s}")
    for i, bearing in enumerate(loads["bearings"]):
        values = (loads["gravity_share"][i], loads["ours"]["max"][i],
                  loads["opensees"]["max"][i], loads["ours"]["min"][i],
                  loads["opensees"]["min"][i])
        print(f"{bearing:8d} " + " ".join(f"{v / 1e3:9.1f}" for v in values))
    print(f"largest gap over ours's largest change from the gravity share: max "
          f"{100 * d['max_axial_load']:.3f} %, min {100 * d['min_axial_load']:.3f} %, NRMSE "
          f"{100 * d['nrmse_axial_load']:.3f} %")


def run_bearing(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb compare-opensees-bearing``; returns the exit status."""
    from dcfpb.cli.protocol import check_sine_flags, friction_flags
    from isolator.experiments import protocol_bearing
    from isolator.protocols import sine
    from structures.opensees.comparison import (
        bearing_summary,
        run_bearing_comparison,
        shaped_bearing,
    )

    check_sine_flags(args, "dcfpb compare-opensees-bearing")
    given = friction_flags(args, {"mu_t0": ("velocity", "ptv")})
    mu_t0 = None if args.model == "constant" else given.get("mu_t0", 0.075)
    bearing = shaped_bearing(protocol_bearing(
        "constant" if args.model == "constant" else "simplified",
        slider_diameter=args.slider_diameter, effective_radius=args.effective_radius,
        pressure=args.pressure, mu_t0=mu_t0,
        design_velocity=2.0 * math.pi * args.amplitude / args.period,
        displacement_capacity=max(0.6, 1.05 * args.amplitude)), args.model)
    history = sine(args.amplitude, args.period, args.cycles, args.dt, max_steps=args.max_steps)
    try:
        result = run_bearing_comparison(bearing, history, element=_ELEMENT[args.model])
    except ImportError as error:
        return _import_error("compare-opensees-bearing", error)
    summary = bearing_summary(result.ours, result.opensees)
    if args.json:
        print(json.dumps(summary, indent=2))
        return EXIT_OK
    d = summary["difference"]
    print(f"{history.name}, {args.model} model; OpenSees: {result.opensees.name.split(':')[0]}")
    print(f"{'':10s} {'peak force':>11s} {'T max':>7s} {'wall':>7s}")
    print(f"{'':10s} {'[kN]':>11s} {'[degC]':>7s} {'[s]':>7s}")
    for name in ("ours", "opensees"):
        s = summary[name]
        temperature = "-" if s["max_temperature"] is None else f"{s['max_temperature']:.1f}"
        print(f"{name:10s} {s['peak_force'] / 1e3:11.1f} {temperature:>7s} "
              f"{s['wall_time']:7.3f}")
    gap = "" if d["max_temperature"] is None else f", T max {d['max_temperature']:+.2f} degC"
    print(f"OpenSees against ours: peak force {100 * d['peak_force']:.3f} %, force NRMSE "
          f"{100 * d['nrmse_force']:.3f} %, largest EDC gap {100 * d['edc']:.3f} %{gap}; "
          f"wall-time ratio ours/OpenSees {summary['wall_time_ratio']:.3g}")
    return EXIT_OK
