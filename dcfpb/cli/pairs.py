"""What the building commands do with a pair of records: ``--record-y`` and ``--record-z``
read beside ``--record`` (checked against the building file's ``[plan]`` table), and the peaks
table of a building in plan. ``dcfpb run`` of a building in plan is
:func:`dcfpb.cli.run.run_plan`."""

from __future__ import annotations

import argparse

__all__ = ["add_pair_options", "pair_from_args", "print_plan_peaks"]


def add_pair_options(p: argparse.ArgumentParser) -> None:
    """Add ``--record-y``, ``--record-z``, ``--resample`` and ``--truncate`` to a command that reads
    ``--record``."""
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
    """The (scaled) pair of ``--record``/``--record-y``/``--record-z``, checked against the
    building file before anything is read: a pair needs a ``[plan]`` table, and
    ``--record-z`` needs ``--record-y``.

    Returns
    -------
    GroundMotionPair
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
            "see README, 'A building in plan'). Drop --record-y to run it planar.")
    step = None
    if args.resample:
        from groundmotions.readers import read_record

        step = read_record(args.record, units=getattr(args, "units", None),
                           dt=getattr(args, "record_dt", None)).dt
    try:
        pair = read_pair(args.record, args.record_y, args.record_z,
                         dt=getattr(args, "record_dt", None),
                         units=getattr(args, "units", None), resample_to=step,
                         truncate=args.truncate)
    except InputError as error:
        hint = ""
        if "time step" in str(error) and not args.resample:
            hint = "--resample resamples the y (and z) component to the x component's step."
        elif "samples" in str(error) and not args.truncate:
            hint = "--truncate cuts the components to the shortest."
        if hint:
            raise InputError(f"{error} On the command line: {hint}") from None
        raise
    return pair.scaled(args.scale) if args.scale != 1.0 else pair


def print_plan_peaks(rows: dict[str, dict], heading: str) -> None:
    """Print the peaks table of runs in plan, one row per run (``plan_peaks`` of each)."""
    print(heading)
    print(f"{'model':12s} {'isol. disp':>10s} {'centre':>8s} {'base shear':>11s} "
          f"{'roof acc x':>10s} {'roof acc y':>10s} {'drift x':>7s} {'drift y':>7s} "
          f"{'T max':>7s} {'energy err':>10s} {'wall':>6s}")
    print(f"{'':12s} {'[mm]':>10s} {'[mm]':>8s} {'[kN]':>11s} {'[m/s2]':>10s} "
          f"{'[m/s2]':>10s} {'[mm]':>7s} {'[mm]':>7s} {'[degC]':>7s} {'[-]':>10s} {'[s]':>6s}")
    for name, p in rows.items():
        print(f"{name:12s} {1e3 * p['peak_isolator_displacement']:10.1f} "
              f"{1e3 * p['peak_centre_displacement']:8.1f} {p['peak_base_shear'] / 1e3:11.0f} "
              f"{p['peak_roof_acceleration_x']:10.2f} {p['peak_roof_acceleration_y']:10.2f} "
              f"{1e3 * p['peak_storey_drift_x']:7.2f} {1e3 * p['peak_storey_drift_y']:7.2f} "
              f"{p['max_temperature']:7.1f} {p['energy_balance_error']:10.1e} "
              f"{p['wall_time']:6.2f}")
    print("isol. disp: the corner bearing (largest resultant); centre: the base slab at the "
          "plan's reference point; base shear: resultant")
