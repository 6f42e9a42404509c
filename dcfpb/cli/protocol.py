"""``dcfpb protocol``: a virtual bearing test and its per-cycle force-deflection
characteristics.

The bearing follows a sine displacement history in one direction or, with ``--orbit``, an
orbit in two directions of size ``--amplitude`` (:func:`isolator.orbits.orbit`) and of the
sine's period, cycles and step. An orbit's report gives the characteristics along x and along y
and the energy dissipated, the integral of F . du, over the whole orbit and per cycle.
"""

from __future__ import annotations

import argparse
import json
import math

from dcfpb.common.errors import EXIT_OK


def register(sub: argparse._SubParsersAction) -> None:
    """Add ``dcfpb protocol`` to the sub-commands."""
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
    load.add_argument("--pressure", type=float,
                      help="contact pressure on the slider [Pa], in [1e6, 200e6], i.e. 1 to "
                      "200 MPa (default 60e6: 60 MPa)")
    load.add_argument("--axial-load", type=float,
                      help="axial load [N], at least 1e4 (10 kN), e.g. 4.2e6 for 4200 kN")
    add_sine_flags(p, amplitude=0.3)
    p.add_argument("--refinement", type=float, default=None,
                   help="refinement factor lambda of the simplified model (default 0.5; "
                   "with another model a warning: no effect)")
    p.add_argument("--mu0", type=float, default=None,
                   help="reference friction coefficient of the constant model "
                   "(default 0.041 for a 300 mm slider, 0.038 for 400 mm; with another model "
                   "a warning: no effect)")
    p.add_argument("--mu-t0", type=float, default=None,
                   help="mu_t0 of the precise and simplified models (default 0.075; with the "
                   "constant model a warning: no effect)")
    p.add_argument("--initial-temperature", type=float, default=20.0,
                   help="initial temperature [degC]")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--output", metavar="FILE.csv", help="write the history to a CSV file (the "
                   "name must end in .csv)")
    p.add_argument("--plot", metavar="FILE.png", help="draw the hysteresis loop(s) and the "
                   "temperature")
    p.add_argument("--orbit", choices=ORBIT_CHOICES, default=None,
                   help="impose an orbit in two directions instead of the sine: circle (radius "
                   "--amplitude), figure8, square (half side --amplitude) or line (the sine "
                   "along --angle); reports each axis and the orbit's energy")
    p.add_argument("--angle", type=float, default=None,
                   help="rotation of the orbit, the line's direction [deg] (default 0; with "
                   "--orbit)")
    p.add_argument("--overwrite", action="store_true",
                   help="replace output files that exist (never an input of the command)")
    p.set_defaults(handler=_run_protocol)


def add_sine_flags(p: argparse.ArgumentParser, amplitude: float) -> None:
    """Add the flags of a sine test that :func:`check_sine_flags` checks: ``--effective-radius``
    [m], ``--amplitude`` [m] (default ``amplitude``), ``--period`` [s], ``--cycles``, ``--dt``
    [s] and ``--max-steps``."""
    from dcfpb.cli.run import add_max_steps

    p.add_argument("--effective-radius", type=float, default=4.5, help="effective radius [m]")
    p.add_argument("--amplitude", type=float, default=amplitude,
                   help="displacement amplitude [m]")
    p.add_argument("--period", type=float, default=4.26, help="period of the sine [s]")
    p.add_argument("--cycles", type=int, default=3, help="number of cycles")
    p.add_argument("--dt", type=float, default=0.005,
                   help="time step [s], at most 1/20 of the period (default 0.005)")
    add_max_steps(p, "the test")


ORBIT_CHOICES = ("circle", "figure8", "square", "line")
"""The orbits of :data:`isolator.orbits.ORBITS`, written out so that parsing imports nothing."""


_FLAGS = {  # flag: (low, high, low_open); None: unbounded; finite but for a flat slider's radius
    "slider_diameter": (0.0, 10.0, True),  # --pressure, --axial-load: check_test_load
    "effective_radius": (0.0, None, True),  # inf: a flat slider
    "amplitude": (0.0, 9.5, True),  # the bearing's capacity, 1.05 x amplitude, is at most 10 m
    "period": (0.0, None, True),
    "refinement": (0.0, 2.0, True),
    "mu0": (0.0, 1.0, True),
    "mu_t0": (0.0, 1.0, True),
    "initial_temperature": (-273.15, 1000.0, False),
}


MAX_SLOPE = 0.5
"""Largest displacement over the effective radius of a test [-], as a building file's
``displacement_capacity`` (``structures.config_schema.MAX_SLOPE``: the plates at 30 degrees)."""


def check_geometry(args: argparse.Namespace, reach: float, command: str) -> None:
    """Refuse a test whose bearing cannot exist: a slider as wide as the finite
    ``--effective-radius``, or a displacement ``reach`` [m] past :data:`MAX_SLOPE` of it."""
    from dcfpb.common.errors import InputError

    radius = args.effective_radius
    if radius is None or not math.isfinite(radius):
        return
    if args.slider_diameter is not None and args.slider_diameter >= radius:
        raise InputError(f"--slider-diameter {args.slider_diameter:g} m must be below "
                         f"--effective-radius {radius:g} m (the slider sits in concave plates "
                         "of radius about R_eff / 2).")
    if reach > MAX_SLOPE * radius:
        raise InputError(
            f"--amplitude {args.amplitude:g} m takes the bearing to {reach:.4g} m, past "
            f"{MAX_SLOPE:g} x --effective-radius = {MAX_SLOPE * radius:.4g} m: the plates would "
            f"slope {math.degrees(math.asin(min(reach / radius, 1.0))):.0f} degrees (more "
            f"than {math.degrees(math.asin(MAX_SLOPE)):.0f}). Give a smaller --amplitude or a "
            "larger --effective-radius.")


def check_sine_flags(args: argparse.Namespace, command: str) -> None:
    """Check the flags of a sine test (``dcfpb protocol``, ``dcfpb compare-opensees-bearing``)
    by name and range, and its length against ``--max-steps``, before any work."""
    from dcfpb.common.validation import check_int, check_real
    from isolator.experiments import check_test_load
    from isolator.limits import DEFAULT_MAX_STEPS, history_steps

    check_test_load(getattr(args, "pressure", None), getattr(args, "axial_load", None), command,
                    names=("--pressure", "--axial-load"))
    for name, (low, high, low_open) in _FLAGS.items():
        if getattr(args, name, None) is not None:
            check_real(getattr(args, name), "--" + name.replace("_", "-"), command, low=low,
                       high=high, low_open=low_open, allow_inf=name == "effective_radius")
    from dcfpb.common.units import KELVIN_LOOK

    temperature = getattr(args, "initial_temperature", None)
    if temperature is not None and KELVIN_LOOK[0] <= temperature <= KELVIN_LOOK[1]:
        from dcfpb.common.errors import InputError

        raise InputError(f"--initial-temperature {temperature:g} looks like kelvin (plates at "
                         "250 degC or more before a test are implausible); give it in degC "
                         f"({temperature - 273.15:.4g} if it is in kelvin).")
    check_geometry(args, args.amplitude, command)
    cycles = check_int(args.cycles, "--cycles", command, low=1)
    check_real(args.dt, "--dt", command, low=0.0, low_open=True, high=args.period / 20)
    max_steps = getattr(args, "max_steps", DEFAULT_MAX_STEPS)
    check_int(max_steps, "--max-steps", command, low=1)
    history_steps(cycles * args.period, args.dt, max_steps=max_steps,
                  what=f"The test ({cycles} cycles of {args.period:g} s)",
                  raise_with="--max-steps", hint="Check --cycles, --period and --dt")


def _run_protocol(args: argparse.Namespace) -> int:
    from dcfpb.cli.outputs import check_outputs
    from dcfpb.common.errors import InputError
    from dcfpb.common.validation import check_real
    from isolator.experiments import protocol_bearing
    from isolator.orbits import orbit
    from isolator.protocols import sine
    from isolator.testrig import run_orbit, run_test

    command = "dcfpb protocol"
    check_outputs(files={"--output": args.output}, figures={"--plot": args.plot},
                  overwrite=args.overwrite, formats={"--output": {".csv": "CSV"}})
    check_sine_flags(args, command)
    if args.orbit is None and args.angle is not None:
        raise InputError("--angle turns an --orbit; give --orbit or leave it out.")
    angle = check_real(args.angle or 0.0, "--angle", command, low=-360.0, high=360.0)
    friction = friction_flags(args)
    if args.orbit is None:
        history = sine(args.amplitude, args.period, args.cycles, args.dt,
                       max_steps=args.max_steps)
        speed, reach = 2.0 * math.pi * args.amplitude / args.period, args.amplitude
    else:
        history = orbit(args.orbit, args.amplitude, args.period, args.cycles, args.dt,
                        angle=angle, max_steps=args.max_steps)
        speed = float(max(math.hypot(*v) for v in history.velocity))
        reach = float(max(math.hypot(*u) for u in history.displacement))
        check_geometry(args, reach, command)
    bearing = protocol_bearing(
        model=args.model, slider_diameter=args.slider_diameter,
        effective_radius=args.effective_radius, pressure=args.pressure,
        axial_load=args.axial_load, design_velocity=speed, **friction,
        initial_temperature=args.initial_temperature,
        displacement_capacity=max(0.6, 1.05 * reach))
    if args.orbit is None:
        result = run_test(bearing, history.time, history.displacement, history.velocity,
                          name=history.name)
    else:
        result = run_orbit(bearing, history)
    summary = {"model": args.model, "max_temperature": float(result.temperature.max()),
               "axial_load": bearing.axial_load_at(0.0)}
    if args.orbit is None:
        summary["cycles"] = [c.to_dict() for c in result.characteristics()]
    else:
        blocks = [slice(start, stop) for label, start, stop in history.segments
                  if label != "lead-in"]
        summary |= {"orbit": args.orbit, "angle": angle,
                    "dissipated_energy": result.dissipated_energy(),
                    "energy_per_cycle": [result.dissipated_energy(b) for b in blocks],
                    "cycles": {axis: _cycles(result, axis) for axis in ("x", "y")}}
    from dcfpb.cli.outputs import writing

    if args.output:
        from dcfpb.common.files import atomic_output

        with writing("--output", args.output), atomic_output(args.output) as temporary:
            result.to_csv(temporary)
    if args.plot:
        from dcfpb.plotting import plot_bearing_test

        with writing("--plot", args.plot):
            plot_bearing_test(result, args.plot, title=f"{args.model} model"
                              + (f", {args.orbit} orbit" if args.orbit else ""))
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        _print(summary)
    return EXIT_OK


def friction_flags(args: argparse.Namespace, uses: dict | None = None) -> dict[str, float]:
    """The friction flags of ``uses`` (flag: the models it applies to; default those of
    ``dcfpb protocol``, the parameters of :func:`isolator.experiments.protocol_bearing`)
    as given for ``--model``: one the model does not use (checked already) is dropped with an
    :class:`~dcfpb.common.errors.InputWarning` naming the flag, the model and that it has no
    effect."""
    import warnings

    from dcfpb.common.errors import InputWarning
    from isolator.experiments import PARAMETER_MODELS

    uses = PARAMETER_MODELS if uses is None else uses

    given = {}
    for name, models in uses.items():
        value = getattr(args, name)
        if value is None:
            continue
        if args.model in models:
            given[name] = value
        else:
            flag = "--" + name.replace("_", "-")
            warnings.warn(f"{flag} {value:g} has no effect with --model {args.model}: it applies "
                          f"to --model {' and '.join(models)} only; it is ignored.", InputWarning,
                          stacklevel=2)
    return given


def _cycles(result, axis: str) -> list[dict]:
    """The characteristics of the loops along ``axis``; none without a complete loop along it
    (a line across it)."""
    try:
        return [c.to_dict() for c in result.characteristics(axis)]
    except ValueError:
        return []


def _print(summary: dict) -> None:
    orbit = f"   orbit: {summary['orbit']} at {summary['angle']:g} deg" if "orbit" in summary \
        else ""
    print(f"model: {summary['model']}{orbit}   max temperature: "
          f"{summary['max_temperature']:.1f} degC   axial load: "
          f"{summary['axial_load'] / 1e3:.1f} kN")
    if "orbit" in summary:
        per_cycle = " ".join(f"{e / 1e3:.2f}" for e in summary["energy_per_cycle"])
        print(f"dissipated energy: {summary['dissipated_energy'] / 1e3:.2f} kJ   "
              f"per cycle: {per_cycle} kJ")
    cycles = summary["cycles"]
    axes = cycles if isinstance(cycles, dict) else {"": cycles}
    header = f"{'cycle':>5} {'Fmax kN':>9} {'Fmin kN':>9} {'Kru kN/m':>9} {'Krl kN/m':>9} " \
             f"{'EDC kJ':>8} {'Keff kN/m':>10} {'beta_eff':>8}"
    for axis, rows in axes.items():
        if axis:
            print(f"{axis} axis" + ("" if rows else ": no complete cycle"))
        if rows or not axis:
            print(header)
        for c in rows:
            print(f"{c['cycle']:>5d} {c['Fmax'] / 1e3:9.2f} {c['Fmin'] / 1e3:9.2f} "
                  f"{c['Kru'] / 1e3:9.1f} {c['Krl'] / 1e3:9.1f} {c['EDC'] / 1e3:8.2f} "
                  f"{c['Keff'] / 1e3:10.1f} {c['beta_eff']:8.3f}")
