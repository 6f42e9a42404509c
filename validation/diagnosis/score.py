"""Score the diagnosis on a validation panel: diagnose from the data alone, then read labels.

A panel folder (written by :mod:`validation.diagnosis.tuning` or
:mod:`validation.diagnosis.outside`) holds one folder per case with the test files,
``manifest.csv`` (the tests in run order) and ``bearing.json`` (what a user tells the
diagnosis), and ``labels.json`` apart. :func:`diagnose_cases` runs the diagnosis on
the cases of one half from their files only; :func:`score` then reads the labels and judges
each verdict; :func:`summarize` gives the figures the issue asks for.

A verdict is *exactly right* when the effects it names are the truth's set (``unexplained``
may follow them) or, for a case with no effect, when it is ``["none"]``. A *false name* is a
named effect the truth does not have. Leave-one-effect-out: each true effect of a labelled
case is withheld from the library in turn; the run is right when its verdict says
``unexplained`` and names no effect the truth does not have.

    python -m validation.diagnosis.score PANEL [--half test] [--cases case_49,case_52]
        [--markdown FILE] [--json FILE]
    python -m validation.diagnosis.score --panel bidirectional [FOLDER] [--half test]

``--panel bidirectional`` first writes that half of the bidirectional panel
(:mod:`validation.diagnosis.bidirectional`, two-direction tests) to FOLDER or a temporary
folder; its cases are then diagnosed like the others, through ``load_campaign`` /
``load_manifest`` and ``diagnose``. A diagnosis in two directions has no reselection
without a refit, so its leave-one-effect-out runs diagnose the case again from its data with
the effect withheld (the same held-out evidence as in one direction, at the cost of one more
diagnosis per true effect; ``--no-loo-2d`` reports them as not run).
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from isolator.diagnosis import BaselineSpec, Diagnosis, diagnose, load_campaign, reselect
from isolator.diagnosis.manifest import load_manifest
from isolator.diagnosis.thresholds import Thresholds

HALVES = ("tune", "test")


def load_case(folder: str | Path):
    """(campaign, baseline spec) of one case folder, from its data, manifest and
    bearing.json only."""
    folder = Path(folder)
    info = json.loads((folder / "bearing.json").read_text())
    manifest = folder / "manifest.csv"
    if manifest.is_file():
        campaign = load_manifest(manifest, effective_radius=info["effective_radius"],
                                 slider_diameter=info["slider_diameter"],
                                 axial_load=info.get("axial_load"))
    else:
        campaign = load_campaign(sorted(folder.glob("test_*.csv")),
                                 effective_radius=info["effective_radius"],
                                 slider_diameter=info["slider_diameter"],
                                 axial_load=info.get("axial_load"))
    return campaign, BaselineSpec(info["baseline"], tuple(info.get("without", ())))


def case_names(folder: str | Path, half: str | None) -> list[str]:
    """The cases of one half (all with None); the halves are kept with the labels, so this
    is the one place besides :func:`score` that opens the labels file, for the halves only."""
    labels = json.loads((Path(folder) / "labels.json").read_text())
    return sorted(n for n, v in labels.items() if half is None or v["half"] == half)


def diagnose_cases(folder: str | Path, names: list[str],
                   thresholds: Thresholds | None = None,
                   progress: bool = False) -> dict[str, tuple[Diagnosis, float]]:
    """``{case: (diagnosis, seconds)}`` from each case's files alone. ``progress`` prints a
    line per case with its time only: the verdicts are shown once, in the table the scorer
    prints after the whole half is diagnosed and the labels read, so that no verdict of a
    held-out half is seen while it can still be acted on."""
    out = {}
    for name in names:
        start = time.perf_counter()
        campaign, spec = load_case(Path(folder) / name)
        out[name] = (diagnose(campaign, spec, thresholds=thresholds),
                     time.perf_counter() - start)
        if progress:
            print(f"  {name}: diagnosed ({out[name][1]:.1f} s)", flush=True)
    return out


def named(verdict: list[str]) -> set[str]:
    """The effects a verdict names."""
    return {v for v in verdict if v not in ("none", "unexplained")}


def exactly_right(verdict: list[str], truth: list[str]) -> bool:
    """Whether ``verdict`` is exactly right for the true effects ``truth``."""
    if not truth:
        return verdict == ["none"]
    return named(verdict) == set(truth)


def score(diagnoses: dict[str, tuple[Diagnosis, float]], labels: dict,
          thresholds: Thresholds | None = None, loo_2d: bool = True) -> list[dict]:
    """One row per case: verdict, truth, right or not, false names, shrink, leave-one-out.

    A diagnosis in two directions has no reselection without a refit: its leave-one-out runs
    diagnose the case again with the effect withheld (``loo_2d``; else reported as not run)."""
    rows = []
    for name, (d, seconds) in diagnoses.items():
        truth = list(labels[name]["effects"])
        if thresholds is not None:
            d = reselect(d, (), thresholds)
        summary = d.to_json()
        chosen = summary["chosen"]
        row = {"case": name, "truth": labels[name]["truth"], "effects": truth,
               "source": labels[name].get("source"), "verdict": list(d.verdict),
               "right": exactly_right(d.verdict, truth),
               "false_names": sorted(named(d.verdict) - set(truth)),
               **_gaps(d, summary),
               "shrink": chosen["shrink"] if chosen else 0.0, "seconds": seconds, "loo": []}
        for effect in truth:
            if hasattr(d, "selection"):
                loo = reselect(d, (effect,), thresholds)
            elif loo_2d:  # two directions: no reselection without a refit, so diagnosed again
                loo = diagnose(d.campaign, d.baseline.spec, thresholds=thresholds,
                               exclude=(*d.excluded, effect))
            else:
                row["loo"].append({"withheld": effect, "verdict": None, "right": None})
                continue
            row["loo"].append({"withheld": effect, "verdict": list(loo.verdict),
                               "right": ("unexplained" in loo.verdict
                                         and named(loo.verdict) <= set(truth) - {effect})})
        rows.append(row)
    return rows


def _gaps(d, summary: dict) -> dict:
    """The force NRMSE before and after and the noise's: the attributes of a diagnosis in one
    direction, else the summary's ``gap`` and ``chosen`` (a diagnosis in two directions)."""
    if hasattr(d, "gap_before"):
        return {"gap_before": d.gap_before, "gap_after": d.gap_after, "noise": d.noise_nrmse}
    gap, chosen = summary["gap"], summary["chosen"]
    return {"gap_before": gap["value"], "gap_after": chosen["gap_after"] if chosen else
            gap["value"], "noise": gap["noise"]}


def summarize(rows: list[dict]) -> dict:
    """The panel's figures: share exactly right, false names, leave-one-out, shrink."""
    labelled = [r for r in rows if r["effects"]]
    nothing = [r for r in rows if not r["effects"]]
    loo = [x for r in rows for x in r["loo"] if x["right"] is not None]
    return {
        "cases": len(rows),
        "exactly_right": float(np.mean([r["right"] for r in rows])) if rows else float("nan"),
        "right_count": int(sum(r["right"] for r in rows)),
        "cases_with_false_names": int(sum(bool(r["false_names"]) for r in rows)),
        "false_name_rate": (float(np.mean([bool(r["false_names"]) for r in rows]))
                            if rows else float("nan")),
        "false_names_in_no_effect_cases": int(sum(bool(r["false_names"]) for r in nothing)),
        "no_effect_cases": len(nothing),
        "loo_runs": len(loo),
        "loo_unexplained": float(np.mean([x["right"] for x in loo])) if loo else float("nan"),
        "median_shrink": (float(np.median([r["shrink"] for r in labelled]))
                          if labelled else float("nan")),
    }


def markdown(rows: list[dict], figures: dict, half: str) -> str:
    """A table of the rows and the figures, for the issue note."""
    lines = [f"Held-out half: `{half}`, {figures['cases']} cases.", "",
             f"- exactly right: {figures['right_count']}/{figures['cases']} "
             f"({100 * figures['exactly_right']:.0f} %)",
             f"- cases with a false name: {figures['cases_with_false_names']} "
             f"(rate {100 * figures['false_name_rate']:.1f} %); in no-effect cases: "
             f"{figures['false_names_in_no_effect_cases']} of {figures['no_effect_cases']}",
             f"- leave-one-effect-out runs saying unexplained (and no false name): "
             f"{100 * figures['loo_unexplained']:.0f} % of {figures['loo_runs']}",
             f"- median held-out shrink of the labelled cases: "
             f"{100 * figures['median_shrink']:.0f} %", "",
             "| case | source | truth | verdict | right | shrink | leave-one-out |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        loo = "; ".join(f"-{x['withheld']}: not run" if x["verdict"] is None else
                        f"-{x['withheld']}: {', '.join(x['verdict'])}"
                        + ("" if x["right"] else " (wrong)") for x in r["loo"])
        lines.append(f"| {r['case']} | {r['source']} | {', '.join(r['effects']) or 'none'} | "
                     f"{', '.join(r['verdict'])} | {'yes' if r['right'] else 'NO'} | "
                     f"{100 * r['shrink']:.0f} % | {loo} |")
    return "\n".join(lines) + "\n"


def write_bidirectional(folder: str | Path | None, seed: int, half: str | None) -> Path:
    """Write the bidirectional panel's ``half`` (None: both) to ``folder`` (None: a new
    temporary folder) with the seed ``seed``; return the folder. The cases are read back
    through the same entry points as in one direction (:func:`load_case`)."""
    import tempfile

    from validation.diagnosis.bidirectional import write_panel

    folder = Path(folder) if folder else Path(tempfile.mkdtemp(prefix="bidirectional_panel_"))
    write_panel(folder, seed=seed, half=half)
    print(f"bidirectional panel (seed {seed}, half {half or 'all'}) written to {folder}",
          flush=True)
    return folder


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("panel", nargs="?", metavar="FOLDER",
                        help="panel folder (validation.diagnosis.tuning, .outside or "
                             ".bidirectional); with --panel, where to write it (default: a "
                             "temporary folder)")
    parser.add_argument("--panel", dest="write", choices=("bidirectional",),
                        help="write this panel's half first (seed --seed), then score it")
    parser.add_argument("--seed", type=int, default=2026, help="seed of a panel written here")
    parser.add_argument("--half", default="test", choices=[*HALVES, "all"])
    parser.add_argument("--markdown", help="write the table here")
    parser.add_argument("--json", help="write the rows and figures here")
    parser.add_argument("--cases", help="comma-separated case folders of the half to score "
                        "(case_49,case_52; default: all of the half)")
    parser.add_argument("--no-loo-2d", action="store_true",
                        help="do not run the leave-one-effect-out diagnoses of two-direction "
                             "cases (one more diagnosis per true effect)")
    args = parser.parse_args(argv)
    half = None if args.half == "all" else args.half
    if args.write:
        args.panel = write_bidirectional(args.panel, args.seed, half)
    elif args.panel is None:
        parser.error("give a panel FOLDER, or --panel bidirectional to write one")
    names = case_names(args.panel, half)
    if args.cases:
        wanted = {c.strip() for c in args.cases.split(",")}
        names = [n for n in names if n in wanted]
    diagnoses = diagnose_cases(args.panel, names, progress=True)
    labels = json.loads((Path(args.panel) / "labels.json").read_text())  # after diagnosing
    rows = score(diagnoses, labels, loo_2d=not args.no_loo_2d)
    figures = summarize(rows)
    text = markdown(rows, figures, args.half)
    print(text)
    if args.markdown:
        Path(args.markdown).write_text(text)
    if args.json:
        Path(args.json).write_text(json.dumps({"figures": figures, "rows": rows}, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
