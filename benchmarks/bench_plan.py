"""Benchmark of the compiled engine on the building in plan (issue 13), every case in one run.

The building: 3 storeys (400 t floors, 500 t base slab, T_fixed = 0.5 s) on four DCFPBs (R_eff
2.5 m, 300 mm slider) at the corners of a 12 m x 10 m plan with the centre of mass 1.2 m / 0.8 m
off the centre of stiffness, overturning on, under a synthetic Kanai-Tajimi pair with a
vertical (PGA 4 m/s^2) at dt = 5 ms. Best of interleaved repeats, each a whole
:func:`structures.analysis.run` call (model, integration, energy balance, Dataset) and the
integration alone:

(a) the building in one direction (the same storeys, four bearings) with the precise model
    under the pair's x component, compiled, 30 s;
(a0) the same building with constant friction, compiled, 30 s: (a) - (a0) is what the
    precise friction of one bearing in one direction costs;
(b) the building in plan with the precise model (the 2D monitor grid), compiled, 30 s;
    target (b) / (a) <= 3;
(c) the building in plan with constant friction, compiled, 30 s;
(d) OpenSees 3D (``singleFPBearing`` Coulomb,
    :func:`structures.opensees.building.run_opensees`) on the same building with
    constant friction, 30 s; target (d) / (c) >= 20;
(e) the cost per step of (b) and (c) on 10 s against 30 s of the pair; target: flat.

The bound printed with (b) / (a): the building in plan as it costs with constant friction (c),
plus four bearings whose precise friction each costs what one in one direction does with its
line of monitor points, (a) - (a0): (c) + 4 ((a) - (a0)). The plan's bearings evaluate the same
friction kernels (Eq. 7, the pressure and velocity factors) and a 2D grid instead of the line,
so (b) cannot be below it unless the grid costs less than the line.

Run: ``python benchmarks/bench_plan.py [--repeats N] [--no-opensees] [--reference]``
(``--reference`` adds the reference engine in plan on 10 s, slow); the results as a
Markdown table on stdout: ``benchmarks/PLAN.md`` holds a measured one.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

DT = 0.005
SQUARE = [[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0]]


def building():
    """The 3-storey shear building in one direction and the same storeys in plan."""
    from structures.plan import Plan
    from structures.shear_building import ShearBuilding

    plan = Plan(SQUARE, eccentricity=(1.2, 0.8), dimensions=(12.0, 10.0), storey_heights=3.5)
    return tuple(ShearBuilding.from_period([4e5, 4e5, 4e5], 0.5, base_mass=5e5, plan=p)
                 for p in (None, plan))


def bearing(model: str, weight: float):
    """One of four bearings with the friction ``model`` (constant, precise)."""
    from isolator.bearing import DCFPBearing
    from isolator.experiments import friction_model

    load = weight / 4
    friction = friction_model(model, slider_diameter=0.3, design_pressure=load / (
        np.pi * 0.15**2), design_velocity=0.4)
    return DCFPBearing(2.5, 0.3, friction=friction)


def pair(duration: float):
    """The synthetic 10 s pair with a vertical at ``DT``, repeated to ``duration`` [s] (so
    that every length sees the same shaking)."""
    from groundmotions.pairs import GroundMotionPair
    from groundmotions.records import GroundMotion
    from groundmotions.synthetic import synthetic_pair

    base = synthetic_pair("kanai-tajimi", 11, duration=10.0, dt=DT, target_pga=4.0,
                          vertical_ratio=0.6, ground_frequency=15.0, ground_damping=0.6)
    times = round(duration / 10.0)

    def tiled(motion):
        return GroundMotion(np.tile(motion.acceleration[:-1], times), DT, motion.name)

    return GroundMotionPair(tiled(base.x), tiled(base.y), tiled(base.z), name=base.name)


def cases(with_opensees: bool, with_reference: bool) -> dict:
    """name -> (callable returning the Dataset, steps)."""
    from structures.analysis import run

    frame, in_plan = building()
    motions = {d: pair(d) for d in (10.0, 30.0)}
    out = {}
    for model, name in (("precise", "a one direction precise 30 s"),
                        ("constant", "a0 one direction constant 30 s")):
        out[name] = (lambda m=model: run(
            frame, bearing(m, frame.weight), motions[30.0].x, n_bearings=4, dt=DT,
            engine="compiled"), motions[30.0].x.acceleration.size)
    for model in ("precise", "constant"):
        for d in (30.0, 10.0):
            tag = "b" if model == "precise" else "c"
            out[f"{tag} plan {model} {d:g} s"] = (
                lambda m=model, d=d: run(in_plan, bearing(m, frame.weight), motions[d],
                                                 dt=DT, engine="compiled"),
                motions[d].x.acceleration.size)
    if with_opensees:
        from structures.opensees.building import run_opensees

        out["d OpenSees singleFPBearing 3D 30 s"] = (lambda: run_opensees(
            in_plan, bearing("constant", frame.weight), motions[30.0], dt=DT),
            motions[30.0].x.acceleration.size)
    if with_reference:
        out["reference plan constant 10 s"] = (lambda: run(
            in_plan, bearing("constant", frame.weight), motions[10.0], dt=DT,
            engine="reference"), motions[10.0].x.acceleration.size)
    return out


def measure(repeats: int, with_opensees: bool, with_reference: bool) -> dict:
    """Best whole-call and integration times of every case, interleaved."""
    from structures.compiled.engine import compile_engine

    start = time.perf_counter()
    compile_engine()
    print(f"engine compiled or loaded in {time.perf_counter() - start:.2f} s")
    runs = cases(with_opensees, with_reference)
    best = {name: [np.inf, np.inf, steps] for name, (_, steps) in runs.items()}
    for function, _ in runs.values():  # warm: compile, caches
        function()
    for _ in range(repeats):
        for name, (function, _) in runs.items():
            if name.startswith("reference") and np.isfinite(best[name][0]):
                continue
            tic = time.perf_counter()
            dataset = function()
            whole = time.perf_counter() - tic
            assert dataset.attrs["success"], (name, dataset.attrs["message"])
            wall = float(dataset.attrs.get("wall_time", np.nan))
            best[name][0] = min(best[name][0], whole)
            best[name][1] = min(best[name][1], wall)
    return best


def main() -> int:
    """Measure, print the table and the ratios; 1 when a target is missed."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--no-opensees", action="store_true")
    parser.add_argument("--reference", action="store_true")
    arguments = parser.parse_args()
    with_opensees = not arguments.no_opensees
    if with_opensees:
        try:
            from structures.opensees.runtime import import_opensees

            import_opensees()
        except (ImportError, RuntimeError) as error:
            print(f"OpenSees left out: {error}")
            with_opensees = False
    best = measure(arguments.repeats, with_opensees, arguments.reference)
    print("| case | run [ms] | integration [ms] | per step [us] |")
    print("| --- | --- | --- | --- |")
    for name, (whole, wall, steps) in best.items():
        print(f"| {name} | {whole * 1e3:.1f} | {wall * 1e3:.2f} | {wall / steps * 1e6:.2f} |")
    a, b = best["a one direction precise 30 s"], best["b plan precise 30 s"]
    c = best["c plan constant 30 s"]
    missed = []
    print(f"\n(b)/(a) precise in plan over precise in one direction: run {b[0] / a[0]:.2f}, "
          f"integration {b[1] / a[1]:.2f} (target <= 3)")
    if b[0] / a[0] > 3.0:
        missed.append("(b)/(a) <= 3")
    a0 = best["a0 one direction constant 30 s"]
    bound = [c[k] + 4.0 * (a[k] - a0[k]) for k in (0, 1)]
    print(f"    bound with the grid as cheap as the line, (c) + 4 ((a) - (a0)): run "
          f"{bound[0] / a[0]:.2f}, integration {bound[1] / a[1]:.2f} times (a)")
    if "d OpenSees singleFPBearing 3D 30 s" in best:
        d = best["d OpenSees singleFPBearing 3D 30 s"]
        print(f"(d)/(c) OpenSees over plan constant: run {d[0] / c[0]:.1f} (target >= 20)")
        if d[0] / c[0] < 20.0:
            missed.append("(d)/(c) >= 20")
    for tag, model in (("b", "precise"), ("c", "constant")):
        long, short = best[f"{tag} plan {model} 30 s"], best[f"{tag} plan {model} 10 s"]
        growth = (long[1] / long[2]) / (short[1] / short[2])
        print(f"(e) {model}: per step 30 s / 10 s = {growth:.2f} (target: flat, <= 1.2)")
        if growth > 1.2:
            missed.append(f"(e) {model} flat")
    print("targets: " + ("MISSED " + ", ".join(missed) if missed else "all met"))
    return 1 if missed else 0


if __name__ == "__main__":
    sys.exit(main())
