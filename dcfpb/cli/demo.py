"""``dcfpb demo``: the five-storey example under El Centro 1940, and what its isolation buys;
``dcfpb demo --plan``: the same building in plan under a synthetic pair.

The bundled building runs on its bearings with the precise, simplified and constant friction
models, and its superstructure on a fixed base (:mod:`structures.fixed_base`). The command
prints the peaks table with the fixed base as a fourth row and each isolated peak (storey drift,
storey shear, roof acceleration, base shear) as a ratio to the fixed base, and writes the plots
of :func:`dcfpb.plotting.plot_runs` with the fixed base beside the isolated runs, among them the
5 %-damped floor response spectra and the ratios. On a cold numba cache the engine compiles in
two processes meanwhile (:mod:`structures.compiled.ahead`).

With ``--plan`` the bundled ``five_storey_plan.toml`` (six bearings at their plan positions, the
centre of mass 5 % of the plan off the centre of stiffness) runs under a seeded synthetic
Kanai-Tajimi pair (about the El Centro 1940 PGA in x, 0.8 of it in y): the peaks in plan, the
corner bearing against the centre, the ratios per direction, and the figures in plan (bearing
orbits, the plate's temperature field).
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

from dcfpb.cli.run import FIXED_BASE
from dcfpb.common.errors import EXIT_OK, EXIT_RUN_FAILED
from dcfpb.common.units import STANDARD_GRAVITY

MODELS = ("precise", "simplified", "constant")
"""The friction models the demo compares."""


def register(sub: argparse._SubParsersAction) -> None:
    """Add ``dcfpb demo`` to the sub-commands."""
    p = sub.add_parser(
        "demo",
        help="the five-storey example under El Centro 1940, three friction models and the "
        "fixed base",
        description="Runs the bundled five-storey isolated building under the bundled El Centro "
        "1940 N-S record with the precise, simplified and constant friction models, and the "
        "same superstructure on a fixed base; prints a peaks table and the isolated peaks as "
        "ratios to the fixed base, and writes plots (floor response spectra among them).",
    )
    p.add_argument("--plot", metavar="DIR",
                   help="folder for the plots (default: ./dcfpb-demo, with --plan "
                   "./dcfpb-demo-plan; the demo's own default folder takes the new plots "
                   "over its earlier ones, a folder you give needs --overwrite for that)")
    p.add_argument("--plan", action="store_true",
                   help="the same building in plan (six bearings, eccentric centre of mass) "
                   "under a synthetic pair of records: bearing orbits coloured by "
                   "temperature, torsion at the corner bearings, the plate's temperature field")
    p.add_argument("--overwrite", action="store_true",
                   help="replace output files that exist (never an input of the command)")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb demo``; returns the exit status."""
    from dcfpb.cli.outputs import PLAN_FIGURES, RUN_FIGURES, check_outputs
    from structures.compiled.ahead import compile_ahead

    own_folder = args.plot is None  # the demo's default folder holds only the demo's plots
    args.plot = args.plot or ("dcfpb-demo-plan" if args.plan else "dcfpb-demo")
    check_outputs(folders={"--plot": args.plot}, overwrite=args.overwrite or own_folder,
                  writes={"--plot": PLAN_FIGURES if args.plan else RUN_FIGURES})
    with compile_ahead() as ahead:
        ahead.help()  # on a cold cache: compile a share of the engine, then do the rest
        from dcfpb.cli.run import example_path
        from groundmotions.bundled import load_bundled
        from structures.analysis import peaks
        from structures.analysis import run as run_building
        from structures.config import load_config
        from structures.fixed_base import ratios_to_fixed_base, run_fixed_base
        from structures.floor_spectra import with_floor_spectra, with_floor_spectra_all

        config = load_config(example_path("five_storey_plan.toml" if args.plan
                                          else "five_storey.toml"))
        motion = plan_demo_pair() if args.plan else load_bundled("elcentro")
        dt = PLAN_STEP if args.plan else config.dt
        fixed = run_fixed_base(config.building, motion, dt=dt)  # no compiled code
        if ahead.started:  # while the engine compiles: the spectra and matplotlib
            from dcfpb.plotting.base import pyplot

            fixed = with_floor_spectra(fixed, motion)
            pyplot()
        ahead.wait()
        bearing = dataclasses.replace(config.bearing(), axial_load=None)
        results = {model: run_building(
            config.building, dataclasses.replace(config.bearing(model), axial_load=None),
            motion, config.integrator,
            n_bearings=None if args.plan else config.n_bearings, dt=dt) for model in MODELS}
    rows = {model: peaks(result) for model, result in results.items()}
    if "floor_spectrum" not in fixed:  # all four in one pass of the spectrum code
        results = {FIXED_BASE: fixed} | results
    results = with_floor_spectra_all(results, motion)
    fixed = results.pop(FIXED_BASE, fixed)
    from dcfpb.cli.run import print_failure, print_peaks, print_ratios

    print_peaks(rows, _heading(config, motion, bearing, dt, args.plan), fixed_base=fixed)
    if args.plan:
        _print_torsion(rows, config.plan)
    ratios = {model: ratios_to_fixed_base(result, fixed) for model, result in results.items()}
    print()
    print_ratios(ratios, fixed, float(abs(fixed["ground_acceleration"]).max()))
    for model, summary in rows.items():
        print_failure(summary, results[model].attrs["message"])
    from dcfpb.cli.outputs import writing
    from dcfpb.plotting import plot_runs

    with writing("--plot", args.plot):
        written = plot_runs(results, args.plot, title=f"{config.name}: {motion.name}",
                            fixed_base=fixed, processes=2)  # half of the figures in a fork
    print(f"plots written to {Path(args.plot).resolve()}/: "
          + ", ".join(p.name for p in written))
    return EXIT_OK if all(r.attrs["success"] for r in results.values()) else EXIT_RUN_FAILED


def _heading(config, motion, bearing, dt: float, plan: bool) -> str:
    """The first line of the demo's table: the building, the motion, the bearings."""
    if not plan:
        return (f"{config.name} under {motion.name} (PGA {motion.pga / STANDARD_GRAVITY:.2f} "
                f"g), {config.n_bearings} bearings, R_eff = {bearing.effective_radius} m, "
                f"dt = {dt} s")
    eccentricity = config.plan.eccentricity[0]
    return (f"{config.name} under a {motion.name}, PGA {motion.x.pga / STANDARD_GRAVITY:.2f} "
            f"g (x) and {motion.y.pga / STANDARD_GRAVITY:.2f} g (y); {config.plan.n_bearings} "
            f"bearings, eccentricity ({eccentricity[0]:g}, {eccentricity[1]:g}) m, dt = {dt} s")


def _print_torsion(rows: dict[str, dict], plan) -> None:
    """Print the corner bearing against the centre, and why the eccentric building hardly turns."""
    for model, summary in rows.items():
        corner = summary["corner_bearing"]
        x, y = plan.bearing_coordinates[corner]
        print(f"{model}: the corner bearing {corner} at ({x:g}, {y:g}) m moves "
              f"{summary['peak_isolator_displacement'] / summary['peak_centre_displacement']:.3f}"
              " x the centre (torsion)")
    print("Friction pendulums follow the load: each bearing's stiffness N / R_eff and friction "
          "mu N grow with its share\nof the weight, so the isolation's centre of stiffness "
          "sits under the centre of mass and the\neccentric building hardly turns on it.")


PLAN_PAIR = {"generator": "kanai-tajimi", "seed": 1940, "duration": 15.0, "dt": 0.01,
             "ground_frequency": 12.0, "ground_damping": 0.6}
"""The synthetic pair of ``--plan`` (:func:`groundmotions.synthetic.synthetic_pair`)."""

PLAN_PGA_X, PLAN_PGA_Y = 3.1, 2.5
"""Peak ground accelerations of the two components [m/s^2] (El Centro 1940 N-S: 3.13)."""

PLAN_STEP = 0.01
"""The analysis step of ``--plan`` [s]: the record's (the building file's 5 ms would halve it)."""


def plan_demo_pair():
    """The pair of ``--plan``: x scaled to :data:`PLAN_PGA_X`, y to :data:`PLAN_PGA_Y` [m/s^2]."""
    from groundmotions.pairs import GroundMotionPair
    from groundmotions.synthetic import synthetic_pair

    spec = PLAN_PAIR
    pair = synthetic_pair(spec["generator"], spec["seed"], duration=spec["duration"],
                          dt=spec["dt"], target_pga=1.0,
                          ground_frequency=spec["ground_frequency"],
                          ground_damping=spec["ground_damping"],
                          name=f"synthetic Kanai-Tajimi pair (seed {spec['seed']})")
    return GroundMotionPair(pair.x.scaled(PLAN_PGA_X / pair.x.pga),
                            pair.y.scaled(PLAN_PGA_Y / pair.y.pga), name=pair.name)
