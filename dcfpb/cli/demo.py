"""``dcfpb demo``: the five-storey example under El Centro 1940, and what its isolation buys;
``dcfpb demo --plan``: the same building in plan under a synthetic pair.

The bundled building runs on its bearings with the precise, simplified and constant friction
models, and the same superstructure runs on a fixed base (:mod:`structures.fixed_base`). The
command prints the peaks table with the fixed base as a fourth row, then each isolated peak
(storey drift, storey shear, roof acceleration, base shear) as a ratio to the fixed base, and
writes the plots of :func:`dcfpb.plotting.plot_runs` with the fixed base beside the isolated
runs: among them the 5 %-damped floor response spectra (``floor_spectra.png``) and the ratios
(``isolation_effect.png``).

With ``--plan`` the bundled ``five_storey_plan.toml`` (the demo building on six bearings at
their plan positions, its centre of mass 5 % of the plan off the centre of stiffness) runs
under a seeded synthetic Kanai-Tajimi pair (about the El Centro 1940 PGA in x, 0.8 of it in y)
with the three friction models (:func:`run_plan_demo`): the peaks in plan, the corner bearing
against the centre, and the figures of :func:`dcfpb.plotting.plan.plot_plan_runs`.

On a cold numba cache the engine (the one of both buildings) compiles in two processes while
this one reads the record and computes the fixed base (:mod:`structures.compiled.ahead`).
:func:`register` adds the command, :func:`run` is its handler.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from dcfpb.common.units import STANDARD_GRAVITY

MODELS = ("precise", "simplified", "constant")
"""The friction models the demo compares."""

FIXED_BASE = "fixed base"
"""The label of the fixed-base building in tables and plots."""


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
                   "./dcfpb-demo-plan)")
    p.add_argument("--plan", action="store_true",
                   help="the same building in plan (six bearings, eccentric centre of mass) "
                   "under a synthetic pair of records: bearing orbits coloured by "
                   "temperature, torsion at the corner bearings, the plate's temperature field")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Handler of ``dcfpb demo``; returns the exit status."""
    from dcfpb.cli.outputs import check_outputs

    if args.plan:
        args.plot = args.plot or "dcfpb-demo-plan"
        check_outputs(folders={"--plot": args.plot})
        return run_plan_demo(args.plot)
    from structures.compiled.ahead import compile_ahead

    args.plot = args.plot or "dcfpb-demo"
    check_outputs(folders={"--plot": args.plot})

    with compile_ahead() as ahead:
        ahead.help()  # on a cold cache: compile a share of the engine, then do the rest
        from dcfpb.cli.run import example_path
        from groundmotions.bundled import load_bundled
        from structures.analysis import peaks
        from structures.analysis import run as run_building
        from structures.config import load_config
        from structures.fixed_base import ratios_to_fixed_base, run_fixed_base
        from structures.floor_spectra import with_floor_spectra, with_floor_spectra_all

        config = load_config(example_path("five_storey.toml"))
        motion = load_bundled("elcentro")
        fixed = run_fixed_base(config.building, motion, dt=config.dt)  # no compiled code
        if ahead.started:  # idle until the engine is compiled: spectra and matplotlib now
            from dcfpb.plotting.base import pyplot

            fixed = with_floor_spectra(fixed, motion)
            pyplot()
        ahead.wait()
        results = {model: run_building(config.building, config.bearing(model), motion,
                                       config.integrator, n_bearings=config.n_bearings,
                                       dt=config.dt) for model in MODELS}
    rows = {model: peaks(result) for model, result in results.items()}
    if "floor_spectrum" not in fixed:  # all four in one pass of the spectrum code
        results = {FIXED_BASE: fixed} | results
    results = with_floor_spectra_all(results, motion)
    fixed = results.pop(FIXED_BASE, fixed)
    heading = (f"{config.name} under {motion.name} (PGA {motion.pga / STANDARD_GRAVITY:.2f} g), "
               f"{config.n_bearings} bearings, R_eff = "
               f"{config.bearing_geometry['effective_radius']} m, dt = {config.dt} s")
    from dcfpb.cli.run import print_peaks

    print_peaks(rows, heading, fixed_base=fixed)
    ratios = {model: ratios_to_fixed_base(result, fixed) for model, result in results.items()}
    print()
    print_ratios(ratios, fixed, motion.pga)
    from dcfpb.plotting import plot_runs

    written = plot_runs(results, args.plot, title=f"{config.name}: {motion.name}",
                        fixed_base=fixed, processes=2)  # half of the figures in a fork
    print(f"plots written to {Path(args.plot).resolve()}/: "
          + ", ".join(p.name for p in written))
    return 0


PLAN_PAIR = {"generator": "kanai-tajimi", "seed": 1940, "duration": 15.0, "dt": 0.01,
             "ground_frequency": 12.0, "ground_damping": 0.6}
"""The synthetic pair of ``--plan`` (:func:`groundmotions.pairs.synthetic.synthetic_pair`)."""

PLAN_PGA_X, PLAN_PGA_Y = 3.1, 2.5
"""Peak ground accelerations of the two components [m/s^2] (El Centro 1940 N-S: 3.13)."""

PLAN_STEP = 0.01
"""The analysis step of ``--plan`` [s] (the record's; the building file's 5 ms halves it)."""


def plan_demo_pair():
    """The pair of ``--plan``: x scaled to :data:`PLAN_PGA_X`, y to :data:`PLAN_PGA_Y` [m/s^2]."""
    from groundmotions.pairs import GroundMotionPair
    from groundmotions.pairs.synthetic import synthetic_pair

    spec = PLAN_PAIR
    pair = synthetic_pair(spec["generator"], spec["seed"], duration=spec["duration"],
                          dt=spec["dt"], target_pga=1.0,
                          ground_frequency=spec["ground_frequency"],
                          ground_damping=spec["ground_damping"],
                          name=f"synthetic Kanai-Tajimi pair (seed {spec['seed']})")
    return GroundMotionPair(pair.x.scaled(PLAN_PGA_X / pair.x.pga),
                            pair.y.scaled(PLAN_PGA_Y / pair.y.pga), name=pair.name)


def run_plan_demo(folder: str | Path) -> int:
    """Run the demo in plan, print its table and write its figures to ``folder``; return the
    exit status."""
    from structures.compiled.ahead import compile_ahead

    with compile_ahead() as ahead:  # on a cold cache the engine compiles in two processes
        ahead.help()
        from dcfpb.cli.pairs import print_plan_peaks
        from dcfpb.cli.run import example_path, print_failure
        from dcfpb.common.units import STANDARD_GRAVITY
        from dcfpb.plotting.plan import plot_plan_runs
        from structures.config import load_config
        from structures.runner import run
        from structures.spatial.peaks import plan_peaks

        config = load_config(example_path("five_storey_plan.toml"))
        pair = plan_demo_pair()
        if ahead.started:  # idle until the engine is compiled: matplotlib now
            from dcfpb.plotting.base import pyplot

            pyplot()
        ahead.wait()
        results = {model: run(config, pair, model=model, dt=PLAN_STEP) for model in MODELS}
    rows = {model: plan_peaks(result) for model, result in results.items()}
    plan = config.plan
    print_plan_peaks(rows, (
        f"{config.name} under a {pair.name}, PGA {pair.x.pga / STANDARD_GRAVITY:.2f} g (x) and "
        f"{pair.y.pga / STANDARD_GRAVITY:.2f} g (y); {plan.n_bearings} bearings, "
        f"eccentricity ({plan.eccentricity[0, 0]:g}, {plan.eccentricity[0, 1]:g}) m, "
        f"dt = {PLAN_STEP} s"))
    for model, summary in rows.items():
        corner = summary["corner_bearing"]
        x, y = plan.bearing_coordinates[corner]
        print(f"{model}: the corner bearing {corner} at ({x:g}, {y:g}) m moves "
              f"{summary['peak_isolator_displacement'] / summary['peak_centre_displacement']:.3f}"
              " x the centre (torsion)")
        print_failure(summary, results[model].attrs["message"])
    print("Friction pendulums follow the load: each bearing's stiffness N / R_eff and friction "
          "mu N grow with its share\nof the weight, so the isolation's centre of stiffness "
          "sits under the centre of mass and the\neccentric building hardly turns on it.")
    written = plot_plan_runs(results, folder, title=f"{config.name}: {pair.name}",
                             processes=2)
    print(f"plots written to {Path(folder).resolve()}/: " + ", ".join(p.name for p in written))
    return 0 if all(r.attrs["success"] for r in results.values()) else 1


def print_ratios(ratios: dict[str, dict[str, float]], fixed_base, pga: float) -> None:
    """Print each isolated run's peaks over the fixed base's, and the roof over the ground.

    Parameters
    ----------
    ratios : dict of str to dict
        :func:`structures.fixed_base.ratios_to_fixed_base` of each run, keyed by its label.
    fixed_base : xarray.Dataset
        The fixed-base run.
    pga : float
        Peak ground acceleration [m/s^2].
    """
    from structures.fixed_base import superstructure_peaks

    print("isolated / fixed base (below 1: the isolation reduces it)")
    print(f"{'model':12s} {'drift':>7s} {'storey shear':>13s} {'roof acc':>9s} "
          f"{'base shear':>11s}")
    for name, r in ratios.items():
        print(f"{name:12s} {r['peak_storey_drift']:7.3f} {r['peak_storey_shear']:13.3f} "
              f"{r['peak_roof_acceleration']:9.3f} {r['peak_base_shear']:11.3f}")
    roof = superstructure_peaks(fixed_base)["peak_roof_acceleration"]
    isolated = ", ".join(f"{name} {r['peak_roof_acceleration'] * roof / pga:.2f}"
                         for name, r in ratios.items())
    print(f"roof acceleration / PGA ({pga:.2f} m/s2): fixed base {roof / pga:.2f}; {isolated}.")
    print("An isolated roof above the PGA comes from the friction force reversing at each "
          "stick-slip (a step of\nabout 2 mu W of base shear) exciting the sliding building's "
          "own modes; it hardly depends on the\nbearings' u_y and falls with the "
          "superstructure's damping: docs/presliding_study.md.")
