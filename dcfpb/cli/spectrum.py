"""``dcfpb spectrum``: peak values, Arias intensity, durations and spectra of a record.

Reads a PEER .AT2 or text record (`groundmotions.readers.read_record`) and prints PGA, PGV, PGD,
the Arias intensity, the D5-75 and D5-95 significant durations and Sd, Sv and Sa at standard (or
the given) periods; ``--plot`` draws the three spectra on a dense period grid. The record is
used as read: no baseline correction or filtering.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.cli.run import add_record_options, read_record_from_args
from dcfpb.common.errors import EXIT_OK
from dcfpb.common.units import STANDARD_GRAVITY

STANDARD_PERIODS = (0.0, 0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0)
"""Periods of the printed table when ``--periods`` is not given [s]."""

PLOT_PERIODS = np.geomspace(0.02, 10.0, 200)
"""Period grid of the plotted spectra [s]."""


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``spectrum`` sub-command to the ``dcfpb`` parser."""
    p = subparsers.add_parser(
        "spectrum",
        help="peak values, Arias intensity, durations and response spectra of a record",
        description="Read a ground-motion record (PEER .AT2 or text; acceleration in the "
        "units its header states, else --units, else g) and "
        "print PGA, PGV, PGD, Arias intensity, D5-75, D5-95 and elastic response spectra "
        "(exact piecewise-linear recurrence). All values in SI units.",
    )
    p.add_argument("record", metavar="FILE", help="ground-motion record")
    add_record_options(p, ("--record-dt", "--dt"))
    p.add_argument("--damping", type=float, default=0.05, help="damping ratio (default 0.05)")
    p.add_argument("--periods", type=float, nargs="+", metavar="T",
                   help="periods of the table [s] (default: 0, 0.05 ... 5 s)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--plot", metavar="FILE.png", help="draw Sa, Sv and Sd against period")
    p.add_argument("--overwrite", action="store_true",
                   help="replace output files that exist (never an input of the command)")
    p.set_defaults(handler=run)


def summarise(motion: Any, periods: Any, damping: float) -> dict[str, Any]:
    """The numbers the command prints, as a JSON-ready dict (SI units)."""
    from groundmotions.processing import arias_intensity, significant_duration
    from groundmotions.spectra import peak_ground_values, spectrum

    pga, pgv, pgd = peak_ground_values(motion.acceleration, motion.dt)
    spec = spectrum(motion, np.asarray(periods, dtype=float), damping)
    return {
        "record": motion.name,
        "npts": motion.npts,
        "dt": motion.dt,
        "duration": motion.duration,
        "pga": pga,
        "pga_g": pga / STANDARD_GRAVITY,
        "pgv": pgv,
        "pgd": pgd,
        "arias_intensity": float(arias_intensity(motion)[1][-1]),
        "d5_75": significant_duration(motion, 0.05, 0.75),
        "d5_95": significant_duration(motion, 0.05, 0.95),
        "damping": spec.damping,
        "spectrum": [
            {"period": float(t), "sd": float(d), "sv": float(v), "sa": float(a)}
            for t, d, v, a in zip(spec.periods, spec.sd, spec.sv, spec.sa, strict=True)
        ],
    }


def run(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb spectrum``; returns the exit status."""
    from dcfpb.cli.outputs import check_outputs
    from dcfpb.common.validation import check_real

    check_outputs(figures={"--plot": args.plot}, overwrite=args.overwrite,
                  inputs={"the record": args.record})
    check_real(args.damping, "--damping", "dcfpb spectrum", low=0.0, high=1.0, high_open=True)
    for period in args.periods or ():
        check_real(period, "--periods", "dcfpb spectrum", low=0.0)
    motion = read_record_from_args(args.record, args)
    periods = STANDARD_PERIODS if args.periods is None else args.periods
    summary = summarise(motion, periods, args.damping)
    if args.plot:
        from dcfpb.cli.outputs import writing

        with writing("--plot", args.plot):
            plot_spectra(motion, args.plot, damping=args.damping)
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print_summary(summary)
    return EXIT_OK


def print_summary(summary: dict[str, Any]) -> None:
    """Print the summary as text: peak values and durations, then the spectrum table."""
    s = summary
    print(f"{s['record']}: {s['npts']} samples at dt = {s['dt']:g} s "
          f"({s['duration']:.2f} s), as read (no baseline correction)")
    print(f"PGA {s['pga']:.4g} m/s^2 ({s['pga_g']:.4g} g)   PGV {s['pgv']:.4g} m/s   "
          f"PGD {s['pgd']:.4g} m")
    print(f"Arias intensity {s['arias_intensity']:.4g} m/s   D5-75 {s['d5_75']:.2f} s   "
          f"D5-95 {s['d5_95']:.2f} s")
    print(f"elastic spectra, damping {s['damping']:g}")
    print(f"{'T [s]':>8} {'Sd [m]':>11} {'Sv [m/s]':>10} {'Sa [m/s2]':>10} {'Sa [g]':>8}")
    for row in s["spectrum"]:
        print(f"{row['period']:8.3f} {row['sd']:11.5f} {row['sv']:10.4f} {row['sa']:10.4f} "
              f"{row['sa'] / STANDARD_GRAVITY:8.4f}")


def plot_spectra(motion: Any, path: str | Path, *, damping: float = 0.05) -> Path:
    """Draw the pseudo-acceleration, pseudo-velocity and displacement spectra of a record
    (`GroundMotion`) at damping ratio ``damping`` [-] to the PNG file ``path``."""
    from dcfpb.plotting.base import finish, pyplot
    from groundmotions.spectra import spectrum

    plt = pyplot()

    spec = spectrum(motion, PLOT_PERIODS, damping)
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.0), constrained_layout=True)
    panels = (
        (spec.sa / STANDARD_GRAVITY, "pseudo-acceleration Sa [g]", "tab:red"),
        (spec.sv, "pseudo-velocity Sv [m/s]", "tab:green"),
        (spec.sd, "displacement Sd [m]", "tab:blue"),
    )
    for ax, (values, label, colour) in zip(axes, panels, strict=True):
        ax.plot(spec.periods, values, color=colour, lw=1.2)
        ax.set_xscale("log")
        ax.set_xlabel("period [s]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3, which="both")
        ax.set_ylim(bottom=0.0)
    fig.suptitle(f"{motion.name}: elastic response spectra, {100 * damping:g} % damping")
    return finish(fig, path)
