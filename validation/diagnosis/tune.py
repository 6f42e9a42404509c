"""Choose the diagnosis's thresholds on the *tuning* half of the validation panel only.

Every case of the tuning half is diagnosed once (the fits are kept); each decision threshold
of :class:`isolator.diagnosis.thresholds.Thresholds` is then moved over its grid in turn,
holding the others, and the value with the best objective kept (two passes). Re-deciding
costs no refit (:func:`isolator.diagnosis.reselect`). The objective, in order: verdicts
exactly right, leave-one-effect-out runs right, fewer cases with a false name; among the
values that tie for the best, the middle one is taken (the widest margin on either side).
The result goes to ``isolator/diagnosis/thresholds.json`` with the panel's seed, the half
and the tuning score.
The other half is never read here.

    python -m validation.diagnosis.tune PANEL [--write]
"""

from __future__ import annotations

import argparse
import json
from dataclasses import replace
from pathlib import Path

from isolator.diagnosis.thresholds import THRESHOLDS_FILE, Thresholds
from validation.diagnosis.score import (
    case_names,
    diagnose_cases,
    exactly_right,
    named,
    score,
    summarize,
)

GRIDS: dict[str, tuple[float, ...]] = {
    "practical_none": (0.008, 0.01, 0.0125, 0.015, 0.02, 0.025, 0.03),
    "practical_gain": (0.005, 0.0075, 0.01, 0.015, 0.02, 0.025),
    "practical_remain": (0.008, 0.01, 0.012, 0.015, 0.02, 0.03),
    "z_min": (1.5, 2.0, 2.5, 3.0, 4.0),
    "explained_min": (0.1, 0.2, 0.25, 0.35, 0.5),
    "name_min": (0.3, 0.45, 0.6, 0.75),
    "none_margin": (0.05, 0.15, 0.3, 0.6),
    "second_z": (2.0, 3.0, 4.0, 6.0, 8.0),
    "second_explained": (0.15, 0.25, 0.35, 0.5, 0.65),
    "kinematic_z": (2.0, 3.0, 4.0, 6.0),
    "kinematic_explained": (0.1, 0.2, 0.3, 0.45, 0.6),
    "kinematic_practical": (0.01, 0.02, 0.03, 0.05, 0.08),
    "lag_min_samples": (2.0, 2.5, 3.0, 4.0),
    "backlash_min": (5e-4, 1e-3, 1.5e-3, 2e-3),
    "transition_score": (2.0, 3.0, 4.0, 6.0, 9.0),
    "transition_practical": (0.0125, 0.02, 0.03, 0.05),
}


def objective(diagnoses: dict, labels: dict, thresholds: Thresholds) -> tuple[int, int, int]:
    """(right verdicts, right leave-one-out runs, -cases with a false name), from the
    decisions alone (no report is assembled)."""
    right = loo = false = 0
    for name, (d, _) in diagnoses.items():
        truth = labels[name]["effects"]
        verdict = d.problem.select(d.excluded, thresholds).verdict
        right += exactly_right(verdict, truth)
        false += bool(named(verdict) - set(truth))
        for effect in truth:
            out = d.problem.select((*d.excluded, effect), thresholds).verdict
            loo += "unexplained" in out and named(out) <= set(truth) - {effect}
    return right, loo, -false


def tune(diagnoses: dict, labels: dict, start: Thresholds | None = None,
         passes: int = 2) -> tuple[Thresholds, tuple]:
    """Coordinate search of the thresholds on the diagnosed cases (see the module docstring)."""
    current = start or Thresholds()
    best = objective(diagnoses, labels, current)
    for _ in range(passes):
        changed = False
        for name, grid in GRIDS.items():
            results = [objective(diagnoses, labels, replace(current, **{name: value}))
                       for value in grid]
            top = max(results)
            plateau = [i for i, r in enumerate(results) if r == top]
            value = grid[plateau[len(plateau) // 2]]  # the middle of the best values
            if value != getattr(current, name):
                current, changed = replace(current, **{name: value}), True
            best = top
        if not changed:
            break
    return current, best


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("panel", help="tuning panel folder (validation.diagnosis.tuning)")
    parser.add_argument("--write", action="store_true",
                        help=f"write the thresholds to {THRESHOLDS_FILE}")
    args = parser.parse_args(argv)
    names = case_names(args.panel, "tune")
    defaults = Thresholds()
    diagnoses = diagnose_cases(args.panel, names, thresholds=defaults, progress=True)
    labels = json.loads((Path(args.panel) / "labels.json").read_text())
    before = summarize(score(diagnoses, labels, defaults))
    chosen, _ = tune(diagnoses, labels, defaults)
    after = summarize(score(diagnoses, labels, chosen))
    print("defaults:", before)
    print("tuned:   ", after)
    print("thresholds:", chosen.to_dict())
    if args.write:
        info = json.loads((Path(args.panel) / "panel.json").read_text()) \
            if (Path(args.panel) / "panel.json").is_file() else {}
        THRESHOLDS_FILE.write_text(json.dumps({
            "thresholds": chosen.to_dict(),
            "chosen_on": {"panel": info, "half": "tune", "cases": len(names),
                          "score_on_that_half": after,
                          "method": "validation/diagnosis/tune.py: coordinate search, "
                                    "two passes"},
        }, indent=2) + "\n")
        print(f"wrote {THRESHOLDS_FILE}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
