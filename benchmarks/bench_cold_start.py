"""A user's first ``dcfpb demo`` (or ``demo --plan``): wall time with an empty numba cache, and
with a warm one.

Each run is a fresh ``python -m dcfpb.cli demo`` process timed from outside (the wall time a
user waits, imports and plots included). "Cold" gives every run its own new, empty
``NUMBA_CACHE_DIR``; "warm" reuses one that a first run has filled. With ``--before REF`` the
same is measured for the tree at git ``REF`` (extracted to a temporary folder and put first on
``PYTHONPATH``), interleaved run by run with this tree, so both see the same load on a shared
machine; the table gives medians and the ratios after / before. The CPU time (user + system)
of each cold run, the compiling second process included, is printed too: on a machine busy
with other jobs it moves much less than the wall time does.

    python benchmarks/bench_cold_start.py                    # this tree, 3 cold + 3 warm
    python benchmarks/bench_cold_start.py --before b0edd0c~1 --repeats 3
    python benchmarks/bench_cold_start.py --plan              # dcfpb demo --plan

Targets: ``demo`` cold below 8 s (issue 14), ``demo --plan`` cold at most 15 s (issue 19); with
``--before``, the ratios after / before are printed beside them. Exit status 1 when the cold
median misses its target. Results: ``benchmarks/COLD_START.md``.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
COLD_TARGETS = {False: 8.0, True: 15.0}  # [s], demo and demo --plan
DEMO_FLAGS: list[str] = []
LAST_CPU: list[float] = []  # CPU time of each demo_wall call [s], in order


def children_cpu() -> float:
    """User + system CPU time [s] of the waited children of this process so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def demo_wall(tree: Path | None, cache: str, plots: str, extra_env: dict | None = None) -> float:
    """Wall time [s] of one ``dcfpb demo`` (with :data:`DEMO_FLAGS`) in a fresh process
    (``tree``: a source tree first on the path; None: the installed package); its CPU time
    [s], the processes it waited for included, is added to :data:`LAST_CPU`."""
    env = {**os.environ, "NUMBA_CACHE_DIR": cache, **(extra_env or {})}
    env.pop("DCFPB_DISABLE_NUMBA", None)
    if tree is not None:
        env["PYTHONPATH"] = os.pathsep.join(p for p in (str(tree), env.get("PYTHONPATH"))
                                            if p)
    Path(plots).mkdir(parents=True, exist_ok=True)  # a fresh folder each run: no --overwrite
    plots = tempfile.mkdtemp(prefix="plots-", dir=plots)  # (a tree before it has no such flag)
    cpu = children_cpu()
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "dcfpb.cli", "demo", *DEMO_FLAGS, "--plot", plots],
                   env=env,
                   cwd=tempfile.gettempdir(), check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    LAST_CPU.append(children_cpu() - cpu)
    return wall


def extract(ref: str, into: Path) -> Path:
    """The tree of git ``ref`` written to ``into``."""
    archive = subprocess.run(["git", "-C", str(REPO), "archive", ref], check=True,
                             capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", str(into)], input=archive, check=True)
    return into


def measure(trees: dict[str, Path | None], repeats: int, work: Path) -> dict[str, dict]:
    """Cold and warm walls of each tree, interleaved: {label: {"cold": [...], "warm": [...]}}."""
    times = {label: {"cold": [], "warm": [], "cold_cpu": []} for label in trees}
    warm_caches = {label: str(work / f"warm-{i}") for i, label in enumerate(trees)}
    for label, tree in trees.items():  # fill the warm caches (not timed)
        demo_wall(tree, warm_caches[label], str(work / "plots"))
    for _ in range(repeats):
        for label, tree in trees.items():
            cold = tempfile.mkdtemp(dir=work, prefix="cold-")
            times[label]["cold"].append(demo_wall(tree, cold, str(work / "plots")))
            times[label]["cold_cpu"].append(LAST_CPU[-1])
            times[label]["warm"].append(demo_wall(tree, warm_caches[label],
                                                  str(work / "plots")))
    return times


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", metavar="REF", help="git ref to compare with")
    parser.add_argument("--repeats", type=int, default=3, help="runs of each kind (default 3)")
    parser.add_argument("--plan", action="store_true", help="time dcfpb demo --plan")
    args = parser.parse_args()
    if args.plan:
        DEMO_FLAGS.append("--plan")
    target = COLD_TARGETS[args.plan]
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        trees: dict[str, Path | None] = {}
        if args.before:
            trees["before"] = extract(args.before, Path(tempfile.mkdtemp(dir=work)))
        trees["after"] = REPO
        times = measure(trees, args.repeats, work)
    medians = {label: {kind: statistics.median(v) for kind, v in t.items()}
               for label, t in times.items()}
    print(f"dcfpb demo {' '.join(DEMO_FLAGS)}, wall time [s], median of {args.repeats} "
          "(every run listed)")
    print(f"{'tree':8s} {'cold':>7s} {'warm':>7s} {'cold CPU':>9s}   cold runs / warm runs / "
          "cold CPU")
    for label, t in times.items():
        runs = " / ".join(" ".join(f"{x:.2f}" for x in t[kind])
                          for kind in ("cold", "warm", "cold_cpu"))
        print(f"{label:8s} {medians[label]['cold']:7.2f} {medians[label]['warm']:7.2f} "
              f"{medians[label]['cold_cpu']:9.2f}   {runs}")
    if args.before:
        ratio = {kind: medians["after"][kind] / medians["before"][kind]
                 for kind in ("cold", "warm", "cold_cpu")}
        print(f"after / before: cold {ratio['cold']:.2f}, warm {ratio['warm']:.2f}, "
              f"cold CPU {ratio['cold_cpu']:.2f}")
    met = medians["after"]["cold"] <= target
    print(f"target: cold at most {target:g} s: {'met' if met else 'MISSED'}")
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
