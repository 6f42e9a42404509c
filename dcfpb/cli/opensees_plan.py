"""``dcfpb compare-opensees BUILDING.toml --record X --record-y Y [--record-z Z]``: the
building in plan under a pair, ours against OpenSees 3D.

A building file with a ``[plan]`` table under a pair runs
:func:`structures.opensees.comparison3d.run_comparison_3d`: ours on the reference engine
without overturning (the OpenSees storeys have zero length; ``--overturning`` runs ours with
it and measures the gap), OpenSees with one singleFPBearing 3D per bearing (``--pendulum
spring``: flatSliderBearing plus springs N_i / R, our law). The pair flags are those of
``dcfpb run`` (:mod:`dcfpb.cli.pairs`). Printed: the peaks of each run in the table of
``dcfpb run`` in plan, the differences (relative peak differences of the resultants, NRMSE of
each component), the wall time of each and their ratio.
"""

from __future__ import annotations

import argparse
import json
from typing import Any

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


def _truncated(pair, duration: float):
    from groundmotions.pairs import GroundMotionPair

    parts = [None if m is None else m.truncated(duration) for m in (pair.x, pair.y, pair.z)]
    return GroundMotionPair(*parts, name=pair.name)


def run_plan_comparison(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb compare-opensees`` with ``--record-y``; returns the exit status."""
    import dataclasses

    from dcfpb.cli.outputs import check_outputs
    from dcfpb.cli.pairs import pair_from_args, print_plan_peaks
    from dcfpb.cli.run import integrator_from_args, print_failure
    from dcfpb.errors import InputError
    from dcfpb.validation import check_int, check_real
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
        pair = _truncated(pair, args.duration)
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
        import sys

        print(f"{command}: error: {error}", file=sys.stderr)
        return 2
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
