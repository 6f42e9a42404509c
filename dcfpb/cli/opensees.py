"""``dcfpb compare-opensees`` and ``dcfpb compare-opensees-bearing``: our runs against OpenSees.

``dcfpb compare-opensees BUILDING.toml --record FILE [--model constant|velocity|ptv]
[--scale S] [--json] [--plot DIR]`` runs the building file under the record with our engine
and with openseespy (:mod:`structures.opensees.comparison`), and prints the peaks of each,
their differences (relative peak difference, and NRMSE = RMS difference / peak of ours, of
the isolator displacement, base shear and roof acceleration), the wall time of each and their
ratio. ``--plot`` overlays the histories and the hysteresis loops.

With ``--record-y Y [--record-z Z]`` (the pair flags of ``dcfpb run``) and a building file with
a ``[plan]`` table, the building in plan is compared with OpenSees 3D
(:func:`run_plan_comparison`: ours without overturning, since the OpenSees storeys have zero
length, and ``--overturning`` measures the gap it makes; OpenSees with one singleFPBearing 3D
per bearing, or with ``--pendulum spring`` flatSliderBearing plus springs N_i / R, our law);
every other flag keeps its meaning.

``dcfpb compare-opensees-bearing [--model ...]`` is the same for one bearing under an imposed
sine (:mod:`structures.opensees.bearing`): peak force, force NRMSE, energy dissipated per
cycle and temperature of each.

Registered by adding ``"dcfpb.cli.opensees"`` to ``dcfpb.cli.COMMAND_MODULES``.
"""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

from dcfpb.cli.pairs import add_pair_options
from dcfpb.cli.run import add_max_steps, add_record_options

MODELS = ("constant", "velocity", "ptv")
_ELEMENT = {"constant": "coulomb", "velocity": "velocity", "ptv": "ptv"}
_ROWS = (("isolator_displacement", "isolator displacement"), ("base_shear", "base shear"),
         ("roof_acceleration", "roof acceleration"))


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add ``compare-opensees`` and ``compare-opensees-bearing`` to the ``dcfpb`` parser."""
    p = subparsers.add_parser(
        "compare-opensees",
        help="run a building file with our engine and with OpenSees, and compare",
        description="Run a building file (TOML) under a ground motion with our engine and with "
        "openseespy (same masses, stiffnesses, damping, bearing, record and integrator) and "
        "compare peaks, histories (NRMSE = RMS difference / peak of ours) and wall times. "
        "All values in SI units.",
    )
    p.add_argument("building", metavar="BUILDING.toml", help="building file")
    p.add_argument("--record", required=True, metavar="FILE", help="ground-motion record")
    p.add_argument("--model", choices=MODELS, default="constant",
                   help="friction model: constant (Coulomb), velocity (VelDependent) or ptv "
                   "(FPBearingPTV, 3D; its cost grows as the square of the steps: see "
                   "--duration) (default: constant)")
    p.add_argument("--scale", type=float, default=1.0, help="amplitude scale factor [-]")
    p.add_argument("--duration", type=float, help="use only the first DURATION s of the record")
    p.add_argument("--pendulum", choices=("singlefp", "spring"), default="singlefp",
                   help="OpenSees pendulum: singleFPBearing (its normal force is W + F u/R) or "
                   "flatSliderBearing plus a linear spring W/R (N = W, as ours) "
                   "(default: singlefp)")
    p.add_argument("--integrator", choices=("newmark", "hht"),
                   help="time integration (default: the building file's)")
    p.add_argument("--alpha", type=float, help="HHT alpha in [-1/3, 0] (OpenSees: 1 + alpha)")
    p.add_argument("--dt", type=float, help="analysis time step [s], in (0, 1] and at most "
                   "the record's (default: the file's, else the record's in parts of at most "
                   "5 ms)")
    add_max_steps(p, "each run")
    add_record_options(p)
    add_pair_options(p)
    add_plan_options(p)
    p.add_argument("--json", action="store_true", help="print the comparison as JSON")
    p.add_argument("--plot", metavar="DIR", help="write overlay plots to this folder")
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
    b.add_argument("--effective-radius", type=float, default=4.5, help="effective radius [m]")
    b.add_argument("--amplitude", type=float, default=0.2, help="displacement amplitude [m]")
    b.add_argument("--period", type=float, default=4.26, help="period of the sine [s]")
    b.add_argument("--cycles", type=int, default=3, help="number of cycles")
    b.add_argument("--dt", type=float, default=0.005,
                   help="time step [s], at most 1/20 of the period (default 0.005)")
    add_max_steps(b, "the test")
    b.add_argument("--mu-t0", type=float, default=0.075, help="mu_t0 (velocity, ptv)")
    b.add_argument("--json", action="store_true", help="print the comparison as JSON")
    b.set_defaults(handler=run_bearing)


def _import_error(command: str, error: ImportError) -> int:
    import sys

    print(f"dcfpb {command}: error: {error}", file=sys.stderr)
    return 2


def run_building(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb compare-opensees``; returns the exit status."""
    if args.record_y is not None or args.record_z is not None:
        return run_plan_comparison(args)
    if args.overturning:
        from dcfpb.common.errors import InputError

        raise InputError("--overturning applies to a building in plan under a pair: give "
                         "--record-y (and a building file with a [plan] table).")
    from dcfpb.cli.outputs import check_outputs

    check_outputs(folders={"--plot": args.plot})
    from dcfpb.cli.run import analysis_dt, building_run_inputs, check_run_length, print_peaks
    from structures.opensees.comparison import comparison_bearing, run_comparison

    command = "dcfpb compare-opensees"
    config, integrator, motion = building_run_inputs(args, command)
    if args.duration is not None:
        motion = motion.truncated(args.duration)
    check_run_length(args, config, motion, command)
    bearing = comparison_bearing(config, args.model)
    try:
        result = run_comparison(config.building, bearing, motion, integrator,
                                n_bearings=config.n_bearings, dt=analysis_dt(args, config),
                                pendulum=args.pendulum, max_steps=args.max_steps)
    except ImportError as error:
        return _import_error("compare-opensees", error)
    summary = result.summary
    if args.plot:
        from dcfpb.plotting import plot_runs

        plot_runs({"ours": result.ours, "opensees": result.opensees}, args.plot,
                  title=f"{config.name}: {motion.name}, {args.model} model, ours and OpenSees")
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print_peaks({"ours": summary["ours"], "opensees": summary["opensees"]},
                     f"{config.name} under {motion.name} (scale {args.scale:g}, "
                     f"{integrator!r}), {args.model} model; OpenSees: "
                     f"{summary['opensees']['element']}")
        _print_differences(summary)
        from dcfpb.cli.run import print_failure

        for side in ("ours", "opensees"):
            print_failure(summary[side], f"{side}: {summary[side]['message']}")
    ok = summary["ours"]["success"] and summary["opensees"]["success"]
    return 0 if ok else 1


def _print_differences(summary: dict[str, Any]) -> None:
    difference = summary["difference"]
    print(f"\n{'OpenSees against ours':24s} {'peak [%]':>9s} {'NRMSE [%]':>10s}")
    for key, label in _ROWS:
        print(f"{label:24s} {100 * difference[f'peak_{key}']:9.3f} "
              f"{100 * difference[f'nrmse_{key}']:10.3f}")
    print(f"largest temperature gap: {difference['max_temperature_gap']:.2f} degC")
    ours, opensees = summary["ours"]["wall_time"], summary["opensees"]["wall_time"]
    print(f"wall time: ours {ours:.3f} s, OpenSees {opensees:.3f} s, ratio ours/OpenSees "
          f"{summary['wall_time_ratio']:.3g}")
    for side in ("ours", "opensees"):
        if not summary[side]["success"]:
            print(f"warning: the {side} run stopped early: {summary[side]['message']}")


def bearing_summary(ours, opensees) -> dict[str, Any]:
    """Peak force, EDC and temperature of both bearing tests, and their differences."""
    import numpy as np

    from structures.opensees.comparison import nrmse

    def side(result) -> dict[str, Any]:
        cycles = [c.EDC for c in result.characteristics()]
        heated = np.isfinite(result.temperature)  # NaN where an element has no temperature
        return {"peak_force": float(np.max(np.abs(result.force))), "EDC": cycles,
                "max_temperature": float(np.max(result.temperature[heated]))
                if heated.any() else None, "wall_time": result.wall_time}

    a, b = side(ours), side(opensees)
    edc = [abs(y - x) / max(a["EDC"]) for x, y in zip(a["EDC"], b["EDC"], strict=False)]
    temperatures = (a["max_temperature"], b["max_temperature"])
    difference = {"peak_force": b["peak_force"] / a["peak_force"] - 1.0,
                  "nrmse_force": nrmse(ours.force, opensees.force),
                  "edc": max(edc, default=math.nan),
                  "max_temperature": None if None in temperatures
                  else temperatures[1] - temperatures[0]}
    ratio = a["wall_time"] / b["wall_time"] if b["wall_time"] > 0 else math.nan
    return {"ours": a, "opensees": b, "difference": difference, "wall_time_ratio": ratio}


def run_bearing(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb compare-opensees-bearing``; returns the exit status."""
    from dcfpb.cli.protocol import check_sine_flags
    from isolator.experiments import protocol_bearing
    from isolator.protocols import sine
    from isolator.testrig import run_test
    from structures.opensees.bearing import run_opensees_test
    from structures.opensees.comparison import shaped_bearing

    check_sine_flags(args, "dcfpb compare-opensees-bearing")
    bearing = shaped_bearing(protocol_bearing(
        "constant" if args.model == "constant" else "simplified",
        slider_diameter=args.slider_diameter, effective_radius=args.effective_radius,
        pressure=args.pressure, mu_t0=args.mu_t0,
        design_velocity=2.0 * math.pi * args.amplitude / args.period,
        displacement_capacity=max(0.6, 1.05 * args.amplitude)), args.model)
    history = sine(args.amplitude, args.period, args.cycles, args.dt, max_steps=args.max_steps)
    t, u, v = history.time, history.displacement, history.velocity
    try:
        opensees = run_opensees_test(bearing, t, u, v, element=_ELEMENT[args.model],
                                     name=history.name)
    except ImportError as error:
        return _import_error("compare-opensees-bearing", error)
    ours = run_test(bearing, t, u, v, name=history.name)
    summary = bearing_summary(ours, opensees)
    if args.json:
        print(json.dumps(summary, indent=2))
        return 0
    d = summary["difference"]
    print(f"{history.name}, {args.model} model; OpenSees: {opensees.name.split(':')[0]}")
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
    return 0


_PEAK_ROWS = (("peak_isolator_displacement", "isolator displacement (largest bearing)"),
              ("peak_corner_displacement", "corner bearing displacement"),
              ("peak_centre_displacement", "centre displacement"),
              ("peak_base_shear", "base shear (resultant)"),
              ("peak_roof_acceleration_x", "roof acceleration x"),
              ("peak_roof_acceleration_y", "roof acceleration y"),
              ("peak_base_rotation", "base rotation"))
_NRMSE_ROWS = (("isolator_displacement", "isolator displacement (worst bearing)"),
               ("corner_displacement", "corner bearing displacement"),
               ("centre_displacement", "centre displacement"), ("base_shear", "base shear"),
               ("roof_acceleration", "roof acceleration"))


def add_plan_options(p: argparse.ArgumentParser) -> None:
    """Add ``--overturning`` (the pair flags come from :mod:`dcfpb.cli.pairs`)."""
    p.add_argument("--overturning", action="store_true",
                   help="with a pair: run ours with the overturning of the floors' inertia "
                   "forces (OpenSees has none; the gap it makes is then measured)")


def run_plan_comparison(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb compare-opensees`` with ``--record-y``; returns the exit status."""
    import dataclasses

    from dcfpb.cli.outputs import check_outputs
    from dcfpb.cli.pairs import pair_from_args, print_plan_peaks
    from dcfpb.cli.run import integrator_from_args, print_failure
    from dcfpb.common.errors import InputError
    from dcfpb.common.validation import check_int, check_real
    from structures.analysis import default_step
    from structures.config import load_config
    from structures.limits import check_run
    from structures.spatial.analysis import spatial_fields

    command = "dcfpb compare-opensees"
    check_outputs(folders={"--plot": args.plot})
    if args.model != "constant":
        raise InputError(f"--model {args.model} has no OpenSees element in 3D here: a building "
                         "in plan under a pair compares the constant model (singleFPBearing 3D "
                         "Coulomb). Use --model constant.")
    check_real(args.scale, "scale", command, low=0.0, low_open=True)
    if args.dt is not None:
        check_real(args.dt, "--dt", command, low=0.0, low_open=True, high=1.0)
    if args.duration is not None:
        check_real(args.duration, "--duration", command, low=0.0, low_open=True)
    check_int(args.max_steps, "--max-steps", command, low=1)
    config = load_config(args.building)
    integrator = integrator_from_args(config, args.integrator, args.alpha)
    pair = pair_from_args(args, config, command)
    if args.duration is not None:
        pair = pair.truncated(args.duration)
    dt = args.dt if args.dt is not None else config.dt
    check_run(pair.x, default_step(pair.dt) if dt is None else dt,
              spatial_fields(config.building.n_storeys, config.plan.n_bearings),
              max_steps=args.max_steps, raise_with="--max-steps", owner=command)
    from structures.opensees.comparison3d import run_comparison_3d

    bearing = dataclasses.replace(config.bearing("constant"), axial_load=None)
    try:
        result = run_comparison_3d(config.spatial_building(), bearing, pair, integrator, dt=dt,
                                   pendulum=args.pendulum, overturning=args.overturning,
                                   max_steps=args.max_steps)
    except ImportError as error:
        return _import_error("compare-opensees", error)
    summary = result.summary
    if args.plot:
        from dcfpb.plotting.plan import plot_plan_runs

        plot_plan_runs({"ours": result.ours, "opensees": result.opensees}, args.plot,
                       title=f"{config.name}: {pair.name}, ours and OpenSees")
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print_plan_peaks({"ours": summary["ours"], "opensees": summary["opensees"]},
                         f"{config.name} under the pair {pair.name} (scale {args.scale:g}, "
                         f"{integrator!r}), constant model; OpenSees: "
                         f"{summary['opensees']['element']}")
        print_plan_differences(summary)
        for side in ("ours", "opensees"):
            print_failure(summary[side], f"{side}: {summary[side]['message']}")
    ok = summary["ours"]["success"] and summary["opensees"]["success"]
    return 0 if ok else 1


def print_plan_differences(summary: dict[str, Any]) -> None:
    """The differences of :func:`~structures.opensees.comparison3d.compare_3d` as a table."""
    d = summary["difference"]
    overturning = " (ours with overturning)" if summary["ours"].get("overturning") else ""
    print(f"\nOpenSees against ours{overturning}: peak = max|OS| / max|ours| - 1 of the "
          "resultant; NRMSE = RMS difference / peak of ours, per component")
    print(f"{'':40s} {'peak [%]':>9s}")
    for key, label in _PEAK_ROWS:
        print(f"{label:40s} {100 * d[key]:9.3f}")
    print(f"{'':40s} {'NRMSE x [%]':>11s} {'NRMSE y [%]':>11s}")
    for key, label in _NRMSE_ROWS:
        print(f"{label:40s} {100 * d[f'nrmse_{key}_x']:11.3f} "
              f"{100 * d[f'nrmse_{key}_y']:11.3f}")
    print(f"{'base rotation':40s} {100 * d['nrmse_base_rotation']:11.3f}")
    ours, opensees = summary["ours"]["wall_time"], summary["opensees"]["wall_time"]
    print(f"wall time: ours {ours:.3f} s (reference engine), OpenSees {opensees:.3f} s, ratio "
          f"ours/OpenSees {summary['wall_time_ratio']:.3g}")
    for side in ("ours", "opensees"):
        if not summary[side]["success"]:
            print(f"warning: the {side} run stopped early: {summary[side]['message']}")
