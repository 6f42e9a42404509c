"""Run every benchmark of the project and exit non-zero when any target is missed.

    python benchmarks/run.py            # all targets (about 3 minutes on 2 cores)
    python benchmarks/run.py --quick    # skip the from-scratch numba compilation timings

Each benchmark prints its own table of ratios measured side by side in one process:

* ``bench_isolator.py``: friction models on the bearing test machine (precise / constant <= 3,
  cost per step flat from 3,000 to 48,000 steps);
* ``bench_building.py --opensees``: the building run against OpenSees (<= 0.5 x), precise /
  constant (<= 2 x), per-step cost flat to 64,000 steps, FPBearingPTV / ours at 32,000 steps
  (>= 20 x), memory of a 64,000-step run (< 200 MB);
* ``bench_suite.py``: the 60-record suite x 3 friction models, 2 / 1 worker speed-up (>= 1.8);
  it needs ``../shared/groundmotions`` and is skipped (with a note) without it;
* ``bench_plan.py``: the building in plan's compiled engine: precise in plan / precise planar
  (<= 3), OpenSees singleFPBearing 3D / constant in plan (>= 20), per-step cost flat from 10 to
  30 s (benchmarks/PLAN.md);
* ``bench_cold_start.py``: a user's first ``dcfpb demo`` with an empty numba cache (< 8 s) and a
  later one (not with ``--quick``).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
SHARED = HERE.parent.parent / "shared" / "groundmotions"


def main() -> int:
    quick = "--quick" in sys.argv[1:]
    commands = [["bench_isolator.py"],
                ["bench_building.py", "--opensees", *(["--skip-compile"] if quick else [])]]
    commands.append(["bench_plan.py", "--repeats", "3" if quick else "5"])
    if not quick:
        commands.append(["bench_cold_start.py"])
    if SHARED.is_dir():
        commands.append(["bench_suite.py"])
    else:
        print(f"bench_suite.py skipped: {SHARED} is absent (the 60-record suite lives there)")
    failed = []
    for command in commands:
        print(f"\n=== {' '.join(command)} ===", flush=True)
        status = subprocess.call([sys.executable, str(HERE / command[0]), *command[1:]])
        if status != 0:
            failed.append(command[0])
    print(f"\nbenchmarks: {'targets MISSED in ' + ', '.join(failed) if failed else 'all met'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
