"""``dcfpb protocol --orbit circle|figure8|square|line [--angle DEG]``: the virtual test
machine in 2D (:mod:`isolator.orbits`,
:func:`isolator.testrig.run_orbit`).

The orbit's size is ``--amplitude`` (the circle's radius, the figure-eight's and the line's
amplitude, the square's half side), its period, cycles and step those of the sine. The report
gives the per-cycle characteristics along x and along y and the energy dissipated, integral of
F . du, over the whole orbit and per cycle. Without ``--orbit`` the command is unchanged.
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable

ORBIT_CHOICES = ("circle", "figure8", "square", "line")
"""The orbits of :data:`isolator.orbits.ORBITS`, written out so that parsing imports
nothing."""


def add_orbit_flags(parser: argparse.ArgumentParser) -> None:
    """Add ``--orbit`` and ``--angle`` to ``dcfpb protocol``."""
    parser.add_argument("--orbit", choices=ORBIT_CHOICES, default=None,
                        help="impose a 2D orbit instead of the sine: circle (radius "
                        "--amplitude), figure8, square (half side --amplitude) or line (the "
                        "sine along --angle); reports each axis and the orbit's energy")
    parser.add_argument("--angle", type=float, default=0.0,
                        help="rotation of the orbit, the line's direction [deg] (default 0)")


def run_orbit_protocol(args: argparse.Namespace,
                       check_sine_flags: Callable[[argparse.Namespace, str], None]) -> int:
    """Run ``dcfpb protocol --orbit ...``; exit status 0. ``check_sine_flags`` is the sine's
    check of the shared flags (:func:`dcfpb.cli.protocol.check_sine_flags`, passed in: this
    module does not import the command that calls it)."""
    from dcfpb.cli.outputs import check_outputs
    from dcfpb.common.errors import InputError
    from dcfpb.common.validation import check_real
    from isolator.orbits import orbit
    from isolator.testrig import run_orbit
    from isolator.experiments import protocol_bearing

    command = "dcfpb protocol"
    if args.plot:
        raise InputError(f"{command}: --plot draws planar tests only; leave it out with "
                         f"--orbit (write the histories with --output FILE.csv instead).")
    check_outputs(files={"--output": args.output})
    check_sine_flags(args, command)
    angle = check_real(args.angle, "--angle", command, low=-360.0, high=360.0)
    path = orbit(args.orbit, args.amplitude, args.period, args.cycles, args.dt, angle=angle,
                 max_steps=args.max_steps)
    speed = path.velocity[:, 0] ** 2 + path.velocity[:, 1] ** 2
    reach = path.displacement[:, 0] ** 2 + path.displacement[:, 1] ** 2
    bearing = protocol_bearing(
        model=args.model, slider_diameter=args.slider_diameter,
        effective_radius=args.effective_radius, pressure=args.pressure,
        axial_load=args.axial_load, design_velocity=float(speed.max()) ** 0.5,
        refinement=args.refinement, mu0=args.mu0, mu_t0=args.mu_t0,
        initial_temperature=args.initial_temperature,
        displacement_capacity=max(0.6, 1.05 * float(reach.max()) ** 0.5))
    result = run_orbit(bearing, path)
    cycles = {}
    for axis in ("x", "y"):
        try:
            cycles[axis] = [c.to_dict() for c in result.characteristics(axis)]
        except ValueError:  # no complete loop along this axis (a line across it)
            cycles[axis] = []
    blocks = [slice(start, stop) for label, start, stop in path.segments if label != "lead-in"]
    summary = {
        "model": args.model,
        "orbit": args.orbit,
        "angle": angle,
        "max_temperature": float(result.temperature.max()),
        "axial_load": bearing.axial_load_at(0.0),
        "dissipated_energy": result.dissipated_energy(),
        "energy_per_cycle": [result.dissipated_energy(block) for block in blocks],
        "cycles": cycles,
    }
    if args.output:
        result.to_csv(args.output)
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        _print(summary)
    return 0


def _print(summary: dict) -> None:
    print(f"model: {summary['model']}   orbit: {summary['orbit']} at {summary['angle']:g} deg"
          f"   max temperature: {summary['max_temperature']:.1f} degC"
          f"   axial load: {summary['axial_load'] / 1e3:.1f} kN")
    per_cycle = " ".join(f"{e / 1e3:.2f}" for e in summary["energy_per_cycle"])
    print(f"dissipated energy: {summary['dissipated_energy'] / 1e3:.2f} kJ   "
          f"per cycle: {per_cycle} kJ")
    header = f"{'cycle':>5} {'Fmax kN':>9} {'Fmin kN':>9} {'Kru kN/m':>9} {'Krl kN/m':>9} " \
             f"{'EDC kJ':>8} {'Keff kN/m':>10} {'beta_eff':>8}"
    for axis, rows in summary["cycles"].items():
        print(f"{axis} axis" + ("" if rows else ": no complete cycle"))
        if rows:
            print(header)
        for c in rows:
            print(f"{c['cycle']:>5d} {c['Fmax'] / 1e3:9.2f} {c['Fmin'] / 1e3:9.2f} "
                  f"{c['Kru'] / 1e3:9.1f} {c['Krl'] / 1e3:9.1f} {c['EDC'] / 1e3:8.2f} "
                  f"{c['Keff'] / 1e3:10.1f} {c['beta_eff']:8.3f}")
