"""``dcfpb demo --plan``: the demo's five-storey building in plan under a synthetic pair.

The bundled ``five_storey_plan.toml`` (the demo building on six bearings at their plan
positions, its centre of mass 5 % of the plan off the centre of stiffness) runs under a
synthetic Kanai-Tajimi pair (seeded, so every run is the same; about the El Centro 1940 PGA in
x, y 0.8 of it) with the precise, simplified and constant friction models. The command prints
the peaks in plan (corner and centre displacement, resultant base shear, roof acceleration and
drift per direction) and writes the figures of :func:`dcfpb.plotting.plan.plot_plan_runs`:
the corner bearing's orbit coloured by its temperature, the force orbits, the responses per
direction and the temperature field the precise model leaves on the plate.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["PAIR", "run_plan_demo"]

PAIR = {"generator": "kanai-tajimi", "seed": 1940, "duration": 15.0, "dt": 0.01,
        "ground_frequency": 12.0, "ground_damping": 0.6}
"""The synthetic pair of the demo (:func:`groundmotions.pair_synthetic.synthetic_pair`)."""

PGA_X, PGA_Y = 3.1, 2.5
"""Peak ground accelerations of the two components [m/s^2] (El Centro 1940 N-S: 3.13)."""

MODELS = ("precise", "simplified", "constant")

STEP = 0.01
"""The demo's analysis step [s] (the record's; the building file's 5 ms halves it)."""


def demo_pair():
    """The demo's pair: x scaled to :data:`PGA_X`, y to :data:`PGA_Y` [m/s^2]."""
    from groundmotions.pair_synthetic import synthetic_pair
    from groundmotions.pairs import GroundMotionPair

    pair = synthetic_pair(PAIR["generator"], PAIR["seed"], duration=PAIR["duration"],
                          dt=PAIR["dt"], target_pga=1.0,
                          ground_frequency=PAIR["ground_frequency"],
                          ground_damping=PAIR["ground_damping"],
                          name=f"synthetic Kanai-Tajimi pair (seed {PAIR['seed']})")
    return GroundMotionPair(pair.x.scaled(PGA_X / pair.x.pga),
                            pair.y.scaled(PGA_Y / pair.y.pga), name=pair.name)


def run_plan_demo(folder: str | Path) -> int:
    """Run the demo in plan, print its table and write its figures to ``folder``; return the
    exit status."""
    from dcfpb.cli.pairs import print_plan_peaks
    from dcfpb.cli.run import example_path, print_failure
    from dcfpb.plotting.plan import plot_plan_runs
    from dcfpb.units import STANDARD_GRAVITY
    from structures.config import load_config
    from structures.runner import run
    from structures.spatial.peaks import plan_peaks

    config = load_config(example_path("five_storey_plan.toml"))
    pair = demo_pair()
    results = {model: run(config, pair, model=model, dt=STEP) for model in MODELS}
    rows = {model: plan_peaks(result) for model, result in results.items()}
    plan = config.plan
    print_plan_peaks(rows, (
        f"{config.name} under a {pair.name}, PGA {pair.x.pga / STANDARD_GRAVITY:.2f} g (x) and "
        f"{pair.y.pga / STANDARD_GRAVITY:.2f} g (y); {plan.n_bearings} bearings, "
        f"eccentricity ({plan.eccentricity[0, 0]:g}, {plan.eccentricity[0, 1]:g}) m, "
        f"dt = {STEP} s"))
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
