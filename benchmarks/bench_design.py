"""The response-history design analysis of issue 20 on the shared pairs, timed.

    python benchmarks/bench_design.py [--out FOLDER] [--workers 2] [--store peaks]

``structures.design.design`` on ``examples/five_storey_plan.toml`` (precise model) with the four
recorded Chi-Chi pairs of ``../shared/groundmotions/pairs`` completed to seven with synthetic
pairs: 2 bounds x 4 accidental mass positions x 7 pairs = 56 runs in plan, peaks only. Prints
the wall time of each stage (ELF, reading, scaling, the runs on Dask, the governing run again
with floor spectra), the runs' mean integration and task times, then calls it again into the
same folder (every run read back). Site S_MS = 1.5 g, S_M1 = 0.6 g, lambda 1.8 / 0.6, R = 2.

Measured on the shared 2-core machine (2026-11-26, 2 workers, other jobs running, load average
2 to 6): 37 to 73 s for the first call (runs 27 to 59 s, scaling 7 to 16 s, governing run
1 to 3 s), 6 to 10 s for the second (most of it the spectra again).
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAIRS = ROOT.parent / "shared" / "groundmotions" / "pairs"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", help="folder of the runs (default: a temporary one)")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--store", default="peaks", choices=("peaks", "float32", "full"))
    args = parser.parse_args()
    if not PAIRS.is_dir():
        print(f"skipped: {PAIRS} is absent (the shared pairs)")
        return 0
    sys.path.insert(0, str(ROOT))
    from structures.config import load_config
    from structures.design import PropertyModification, Site, design

    with tempfile.TemporaryDirectory() as scratch:
        manifest = Path(scratch) / "pairs.csv"
        rows = ["name,x,y"] + [f"{a.split('-')[0]},{PAIRS / a},{PAIRS / b}" for a, b in (
            ("CHY023-N.AT2", "CHY023-W.AT2"), ("ILA061-N.AT2", "ILA061-W.AT2"),
            ("TAP084-N.AT2", "TAP084-W.AT2"), ("TAP094-E.AT2", "TAP094-N.AT2"))]
        manifest.write_text("\n".join(rows) + "\n")
        out = Path(args.out) if args.out else Path(scratch) / "out"
        config = load_config(ROOT / "examples" / "five_storey_plan.toml")
        kwargs = {"complete_with_synthetic": True, "out_dir": out, "n_workers": args.workers,
                  "store": args.store, "progress": False}
        for call in ("first", "second"):
            start = time.perf_counter()
            result = design(config, manifest, Site(1.5, 0.6),
                            PropertyModification.overall(1.8, 0.6), R=2.0, **kwargs)
            wall = time.perf_counter() - start
            stages = {k: round(v, 1) for k, v in result.options["timings"].items()}
            print(f"{call} call: {wall:.1f} s {json.dumps(stages)}")
            if call == "first":
                runs = [json.loads(p.read_text())
                        for p in out.glob("positions/*/runs/*.json")]
                task = [r["task_time"] for r in runs]
                engine = [r["wall_time"] for r in runs]
                print(f"  {len(runs)} runs: integration {sum(engine) / len(engine):.2f} s, "
                      f"task {sum(task) / len(task):.2f} s on average")
        print(f"checks passed: {sum(c.passed for c in result.checks)} of "
              f"{len(result.checks)}; D_TM {result.envelope['isolator_displacement']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
