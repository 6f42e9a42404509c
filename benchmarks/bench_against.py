"""This tree against another git revision: the same warm workloads, run by run, side by side.

    python benchmarks/bench_against.py --before 16c89dc [--rounds 5]

A refactor must not slow anything down. Each round runs one fresh process per tree (the order
alternating between rounds), and each process times, after a warm-up call that compiles or
loads the engine, the workloads below with ``time.perf_counter``:

* ``building precise`` / ``building constant``: the example building under El Centro 1940 with
  the compiled engine (``structures.analysis.run``);
* ``building reference``: the same with the reference engine, constant friction (the Python
  element through the integrator);
* ``bearing precise``: the paper's test (7 cycles of 0.3 m at 4.26 s, dt = 5 ms) on the
  virtual test machine (``isolator.testrig.run_test``);
* ``plan precise`` / ``plan constant``: the building in plan of ``bench_plan.py`` (four
  bearings, overturning, a vertical) under its 30 s pair with the compiled engine
  (``structures.analysis.run``; ``structures.spatial.analysis.run_spatial`` in trees before
  the one model).

``..., engine`` rows are the same runs' engine time alone (the Dataset's ``wall_time``: the
integration, without building the model and the Dataset). The table gives the median over the
rounds per tree and the ratio this tree / before; shared
machines drift by a factor of 1.5 over a day, so only ratios of one run mean anything. Exits 1
when any ratio is above ``--limit`` (default 1.10).
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

WORKLOAD = r"""
import json, math, time
try:
    from groundmotions.bundled import load_bundled
except ImportError:  # trees before the readers were split
    from groundmotions.records import load_bundled
from isolator.experiments import protocol_bearing
from isolator.protocols import sine
from isolator.testrig import run_test
from structures.analysis import run
from structures.config import load_config

config = load_config("examples/five_storey.toml")
motion = load_bundled("elcentro")


def building(model, engine="auto"):
    return run(config.building, config.bearing(model), motion, config.integrator,
               n_bearings=config.n_bearings, dt=config.dt, engine=engine)


def bearing():
    history = sine(0.3, 4.26, 7, 0.005)
    test = protocol_bearing("precise", design_velocity=2 * math.pi * 0.3 / 4.26)
    return run_test(test, history.time, history.displacement, history.velocity)


ENGINE = {}  # the best engine time (the run's wall_time attribute) of each workload


def timed(call, repeats, name=None):
    best = math.inf
    for _ in range(repeats):
        start = time.perf_counter()
        result = call()
        best = min(best, time.perf_counter() - start)
        if name is not None:
            wall = float(result.attrs["wall_time"])
            ENGINE[name] = min(ENGINE.get(name, math.inf), wall)
    return best


import sys

sys.path.insert(0, "benchmarks")
import bench_plan

try:  # trees before the one model
    from structures.spatial.analysis import run_spatial as run_plan

    frame, plan_building = bench_plan.building()
    weight = frame.weight
except ImportError:  # the one model
    from structures.plan import Plan
    from structures.shear_building import ShearBuilding

    plan_building = ShearBuilding.from_period(
        [4e5, 4e5, 4e5], 0.5, base_mass=5e5,
        plan=Plan(bench_plan.SQUARE, eccentricity=(1.2, 0.8), dimensions=(12.0, 10.0),
                  storey_heights=3.5))
    run_plan, weight = run, plan_building.weight
pair = bench_plan.pair(30.0)


def plan(model):
    return run_plan(plan_building, bench_plan.bearing(model, weight), pair,
                    dt=bench_plan.DT, engine="compiled")


building("constant"), building("precise"), bearing()  # compile or load every engine
plan("constant"), plan("precise")
times = {
    "building precise": timed(lambda: building("precise"), 5, "building precise"),
    "building constant": timed(lambda: building("constant"), 5, "building constant"),
    "building reference": timed(lambda: building("constant", "reference"), 2),
    "bearing precise": timed(bearing, 2),
    "plan precise": timed(lambda: plan("precise"), 5, "plan precise"),
    "plan constant": timed(lambda: plan("constant"), 5, "plan constant"),
}
print(json.dumps({**times, **{f"{name}, engine": wall for name, wall in ENGINE.items()}}))
"""


def _measure(tree: Path) -> dict[str, float]:
    out = subprocess.run([sys.executable, "-c", WORKLOAD], cwd=tree, check=True,
                         capture_output=True, text=True, env={"PYTHONPATH": str(tree),
                                                              **_environment()})
    return json.loads(out.stdout.strip().splitlines()[-1])


def _environment() -> dict[str, str]:
    import os

    return {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", required=True, help="git revision to compare against")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--limit", type=float, default=1.10,
                        help="largest ratio this tree / before accepted (default 1.10)")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as folder:
        before = Path(folder) / "before"
        subprocess.run(["git", "worktree", "add", "--detach", str(before), args.before],
                       cwd=ROOT, check=True, capture_output=True)
        try:
            times: dict[str, dict[str, list[float]]] = {"before": {}, "after": {}}
            for round_ in range(args.rounds):
                order = [("before", before), ("after", ROOT)]
                for label, tree in order if round_ % 2 == 0 else order[::-1]:
                    for name, value in _measure(tree).items():
                        times[label].setdefault(name, []).append(value)
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(before)], cwd=ROOT,
                           check=False, capture_output=True)
    print(f"this tree against {args.before}, median of {args.rounds} rounds (best of repeats "
          "within each process) [s]")
    print(f"{'workload':22s} {'before':>9s} {'after':>9s} {'after/before':>13s}")
    worst = 0.0
    for name in times["before"]:
        b, a = statistics.median(times["before"][name]), statistics.median(times["after"][name])
        worst = max(worst, a / b)
        print(f"{name:22s} {b:9.4f} {a:9.4f} {a / b:13.3f}")
    print(f"largest ratio {worst:.3f} (limit {args.limit:.2f}): "
          f"{'met' if worst <= args.limit else 'MISSED'}")
    return 0 if worst <= args.limit else 1


if __name__ == "__main__":
    sys.exit(main())
