"""The ``dcfpb`` command line: parses, calls the library, prints and plots.

Sub-commands
------------
protocol
    A virtual bearing test: a sine displacement history imposed on a DCFPB with the precise,
    simplified or constant friction model; per-cycle characteristics.
run
    A building file (TOML) under a recorded ground motion; peaks, netCDF, plots.
demo
    The main job on bundled data: the five-storey example under El Centro 1940 with the three
    friction models side by side and the same superstructure on a fixed base
    (:mod:`dcfpb.cli_demo`).

A command of this module builds a parser of this module's commands only, so that it does not
import the others' modules (``dcfpb diagnose`` alone costs about 2 s of imports); ``dcfpb
--help`` and the other commands see them all.
"""

from __future__ import annotations

import argparse
import importlib
import json
import math
import sys
from collections.abc import Sequence
from pathlib import Path

from dcfpb import __version__


def _protocol_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "protocol",
        help="impose a displacement history on a bearing (virtual test machine)",
        description="Impose a sine displacement history on a DCFPB and report the per-cycle "
        "force-deflection characteristics (paper Section 3.1). All values in SI units.",
    )
    p.add_argument("--model", choices=("precise", "simplified", "constant"), default="precise",
                   help="friction model (default: precise)")
    p.add_argument("--slider-diameter", type=float, default=0.3, help="slider diameter [m]")
    load = p.add_mutually_exclusive_group()
    load.add_argument("--pressure", type=float, help="contact pressure [Pa] (default 60e6)")
    load.add_argument("--axial-load", type=float, help="axial load [N]")
    p.add_argument("--effective-radius", type=float, default=4.5, help="effective radius [m]")
    p.add_argument("--amplitude", type=float, default=0.3, help="displacement amplitude [m]")
    p.add_argument("--period", type=float, default=4.26, help="period of the sine [s]")
    p.add_argument("--cycles", type=int, default=3, help="number of cycles")
    p.add_argument("--dt", type=float, default=0.005, help="time step [s]")
    p.add_argument("--refinement", type=float, default=0.5,
                   help="refinement factor lambda of the simplified model (default 0.5)")
    p.add_argument("--mu0", type=float, default=None,
                   help="reference friction coefficient of the constant model "
                   "(default 0.041 for a 300 mm slider, 0.038 for 400 mm)")
    p.add_argument("--mu-t0", type=float, default=0.075,
                   help="mu_t0 of the precise and simplified models (default 0.075)")
    p.add_argument("--initial-temperature", type=float, default=20.0,
                   help="initial temperature [degC]")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--output", metavar="FILE.csv", help="write the history to a CSV file")
    p.add_argument("--plot", metavar="FILE.png", help="draw the hysteresis loop and temperature")
    p.set_defaults(handler=_run_protocol)


def _run_protocol(args: argparse.Namespace) -> int:
    from isolator.experiments import protocol_bearing
    from isolator.protocols import sine

    bearing = protocol_bearing(
        model=args.model,
        slider_diameter=args.slider_diameter,
        effective_radius=args.effective_radius,
        pressure=args.pressure,
        axial_load=args.axial_load,
        design_velocity=2.0 * math.pi * args.amplitude / args.period,
        refinement=args.refinement,
        mu0=args.mu0,
        mu_t0=args.mu_t0,
        initial_temperature=args.initial_temperature,
        displacement_capacity=max(0.6, 1.05 * args.amplitude),
    )
    history = sine(args.amplitude, args.period, args.cycles, args.dt)
    from isolator.testrig import run_test

    result = run_test(bearing, history.time, history.displacement, history.velocity,
                      name=history.name)
    cycles = [c.to_dict() for c in result.characteristics()]
    summary = {
        "model": args.model,
        "max_temperature": float(result.temperature.max()),
        "axial_load": bearing.axial_load_at(0.0),
        "cycles": cycles,
    }
    if args.output:
        result.to_csv(args.output)
    if args.plot:
        from dcfpb.plotting import plot_bearing_test

        plot_bearing_test(result, args.plot, title=f"{args.model} model")
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        _print_cycles(summary)
    return 0


def _print_cycles(summary: dict) -> None:
    print(f"model: {summary['model']}   max temperature: {summary['max_temperature']:.1f} degC"
          f"   axial load: {summary['axial_load'] / 1e3:.1f} kN")
    header = f"{'cycle':>5} {'Fmax kN':>9} {'Fmin kN':>9} {'Kru kN/m':>9} {'Krl kN/m':>9} " \
             f"{'EDC kJ':>8} {'Keff kN/m':>10} {'beta_eff':>8}"
    print(header)
    for c in summary["cycles"]:
        print(f"{c['cycle']:>5d} {c['Fmax'] / 1e3:9.2f} {c['Fmin'] / 1e3:9.2f} "
              f"{c['Kru'] / 1e3:9.1f} {c['Krl'] / 1e3:9.1f} {c['EDC'] / 1e3:8.2f} "
              f"{c['Keff'] / 1e3:10.1f} {c['beta_eff']:8.3f}")


def _run_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "run",
        help="time-history analysis of a building file under a ground motion",
        description="Run a shear building on DCFPB isolators (a TOML building file, see "
        "examples/five_storey.toml) under a recorded ground motion (PEER .AT2 or text).",
    )
    p.add_argument("building", metavar="BUILDING.toml", help="building file")
    p.add_argument("--record", required=True, metavar="FILE", help="ground-motion record")
    p.add_argument("--scale", type=float, default=1.0, help="amplitude scale factor [-]")
    p.add_argument("--model", choices=("precise", "simplified", "constant"),
                   help="friction model (default: the building file's)")
    p.add_argument("--integrator", choices=("newmark", "hht"),
                   help="time integration (default: the building file's)")
    p.add_argument("--alpha", type=float, help="HHT alpha in [-1/3, 0]")
    p.add_argument("--dt", type=float, help="analysis time step [s] (default: the file's)")
    p.add_argument("--json", action="store_true", help="print the peaks as JSON")
    p.add_argument("--output", metavar="FILE.nc", help="write the full result to netCDF")
    p.add_argument("--plot", metavar="DIR", help="write plots to this folder")
    p.set_defaults(handler=_run_building)


def integrator_from_args(config, kind: str | None, alpha: float | None):
    """The building file's integrator, or the one ``--integrator``/``--alpha`` ask for."""
    from structures.integrators import HHT, Newmark

    if kind is None and alpha is None:
        return config.integrator
    if (kind or ("hht" if isinstance(config.integrator, HHT) else "newmark")) == "newmark":
        if alpha is not None:
            raise ValueError("--alpha applies to --integrator hht only.")
        return Newmark()
    return HHT(alpha=-0.05 if alpha is None else alpha)


def building_run_inputs(args: argparse.Namespace, command: str):
    """The building file, the integrator and the (scaled) record of a building command.

    Reads ``args.building``, ``args.integrator``, ``args.alpha``, ``args.record`` and
    ``args.scale``; every value is checked before any work starts.

    Returns
    -------
    config : BuildingConfig
    integrator : Newmark or HHT
    motion : GroundMotion
    """
    from dcfpb.validation import check_real
    from groundmotions.readers import read_record
    from structures.config import load_config

    check_real(args.scale, "scale", command, low=0.0, low_open=True)
    config = load_config(args.building)
    integrator = integrator_from_args(config, args.integrator, args.alpha)
    motion = read_record(args.record)
    if args.scale != 1.0:
        motion = motion.scaled(args.scale)
    return config, integrator, motion


def _run_building(args: argparse.Namespace) -> int:
    from structures.compile_ahead import compile_ahead

    with compile_ahead() as ahead:  # the engine compiles while the inputs are read
        ahead.help()
        from structures.analysis import peaks, run
        from structures.floor_spectra import with_floor_spectra

        config, integrator, motion = building_run_inputs(args, "dcfpb run")
        model = args.model or config.friction["model"]
        ahead.wait()
        result = run(config.building, config.bearing(model), motion, integrator,
                     n_bearings=config.n_bearings, dt=args.dt or config.dt)
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
            "success": bool(result.attrs["success"]), "message": result.attrs["message"]},
            indent=2))
    else:
        print_peaks({model: summary}, f"{config.name} under {motion.name} "
                     f"(scale {args.scale:g}, {integrator!r})")
        if not result.attrs["success"]:
            print(f"warning: the run stopped early: {result.attrs['message']}")
    return 0 if result.attrs["success"] else 1


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


def _demo_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "demo",
        help="the five-storey example under El Centro 1940, three friction models and the "
        "fixed base",
        description="Runs the bundled five-storey isolated building under the bundled El Centro "
        "1940 N-S record with the precise, simplified and constant friction models, and the "
        "same superstructure on a fixed base; prints a peaks table and the isolated peaks as "
        "ratios to the fixed base, and writes plots (floor response spectra among them).",
    )
    p.add_argument("--plot", metavar="DIR", default="dcfpb-demo",
                   help="folder for the plots (default: ./dcfpb-demo)")
    p.set_defaults(handler=_run_demo)


def _run_demo(args: argparse.Namespace) -> int:
    from dcfpb.cli_demo import run

    return run(args)


def _example_path(name: str) -> Path:
    """The example building file shipped in the package (a copy of ``examples/NAME``)."""
    from importlib.resources import files

    return Path(str(files("dcfpb").joinpath("data", name)))


OWN_COMMANDS = ("protocol", "run", "demo")
"""The sub-commands this module defines itself."""

COMMAND_MODULES: tuple[str, ...] = (
    "dcfpb.cli_spectrum",
    "dcfpb.cli_suite",
    "dcfpb.cli_opensees",
    "dcfpb.cli_diagnose",
)
"""Modules with a ``register(subparsers)`` function adding further sub-commands."""


def build_parser(*, modules: bool = True) -> argparse.ArgumentParser:
    """The argument parser of the ``dcfpb`` command.

    ``modules=False`` leaves out the sub-commands of :data:`COMMAND_MODULES` (and their
    imports): enough to parse one of :data:`OWN_COMMANDS`.
    """
    parser = argparse.ArgumentParser(
        prog="dcfpb",
        description="Time-history analysis of buildings on double concave friction pendulum "
        "bearings.",
    )
    parser.add_argument("--version", action="version", version=f"dcfpb {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    _protocol_parser(sub)
    _run_parser(sub)
    _demo_parser(sub)
    for module in COMMAND_MODULES if modules else ():  # sub-commands in modules of their own
        importlib.import_module(module).register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``dcfpb`` console script; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    command = next((a for a in argv if not a.startswith("-")), None)
    own = command in OWN_COMMANDS and argv.index(command) == 0
    parser = build_parser(modules=not own)
    args = parser.parse_args(argv)
    try:
        return args.handler(args)
    except (ValueError, TypeError, OSError) as error:
        print(f"dcfpb {args.command}: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
