"""``dcfpb diagnose``: the sim-to-real gap of a friction model on measured bearing tests.

Each FILE is one test of a campaign, in the order run: a CSV with ``time``, ``displacement``,
``force`` and optionally ``axial_force``, ``velocity``, ``temperature`` [SI units]. A manifest
lists them instead, with each test's axial load, initial temperature and rest before it
(:mod:`isolator.diagnosis.manifest`). The command calibrates the baseline and says where the
held-out gap lies, which candidate effect closes it and how far it shrinks
(:mod:`isolator.diagnosis`). ``--json`` prints the summary (keys ``baseline``, ``gap``,
``where``, ``effects``, ``verdict`` ...); ``--report`` writes ``summary.md``,
``diagnosis.json`` and plots to a folder.
"""

from __future__ import annotations

import argparse
import json

from dcfpb.common.errors import EXIT_OK

FLAG_NAMES = {"effective_radius": "--effective-radius", "slider_diameter": "--slider-diameter",
              "axial_load": "--axial-load"}
"""The command-line flag of each argument a manifest may also give."""


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``diagnose`` sub-command to the ``dcfpb`` parser."""
    from isolator.diagnosis import BASELINE_MODELS, EFFECT_NAMES, REMOVABLE_EFFECTS

    p = subparsers.add_parser(
        "diagnose",
        help="where a friction model misses measured bearing tests, and which effect explains it",
        description="Calibrate a baseline friction model on measured bearing tests, locate "
        "its held-out force error, test a library of candidate effects on held-out data and "
        "report the verdict and how far the gap shrinks. All values in SI units.",
    )
    p.add_argument("files", nargs="*", metavar="FILE",
                   help="CSV test files of one campaign, in the order run")
    p.add_argument("--manifest", metavar="FILE",
                   help="campaign manifest (CSV or TOML): the files in run order with each "
                   "test's axial_load [N], initial_temperature [degC], rest_before [s]")
    p.add_argument("--model", required=True, choices=BASELINE_MODELS,
                   help="baseline friction model")
    p.add_argument("--effective-radius", type=float, metavar="R",
                   help="effective radius [m]; 'inf' for a flat slider or a friction damper "
                   "(required unless a TOML manifest gives it)")
    p.add_argument("--slider-diameter", type=float, metavar="D",
                   help="slider diameter [m] (required unless a TOML manifest gives it)")
    p.add_argument("--axial-load", type=float, metavar="N",
                   help="constant axial load [N] for files without an axial_force column")
    p.add_argument("--without", nargs="+", action="extend", default=[], metavar="EFFECT",
                   choices=REMOVABLE_EFFECTS,
                   help="effects of the simplified or precise model to switch off")
    p.add_argument("--exclude", nargs="+", action="extend", default=[], metavar="EFFECT",
                   choices=EFFECT_NAMES, help="candidate effects to withhold from the library")
    p.add_argument("--yield-displacement", type=float, metavar="UY",
                   help="yield displacement of the return map [m] (default: calibrated)")
    p.add_argument("--max-rows", type=int, default=None, metavar="N",
                   help="most data rows a test file may have, estimated from its size before "
                   "it is read (default 2,000,000)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.add_argument("--report", metavar="DIR", help="write summary.md, JSON and plots here")
    p.add_argument("--overwrite", action="store_true",
                   help="replace output files that exist (never an input of the command)")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Run the diagnosis for parsed arguments; returns the exit status."""
    from dcfpb.cli.outputs import REPORT_FILES, check_outputs

    check_outputs(folders={"--report": args.report}, overwrite=args.overwrite,
                  inputs={"the test file": list(args.files), "the manifest": args.manifest},
                  writes={"--report": REPORT_FILES})  # before the slow imports
    from isolator.diagnosis import BaselineSpec, DataError, diagnose
    from isolator.diagnosis.data import MAX_ROWS, load_any_campaign
    from isolator.diagnosis.manifest import load_manifest

    max_rows = MAX_ROWS if args.max_rows is None else args.max_rows
    _check_flags(args)

    spec = BaselineSpec(args.model, tuple(args.without), args.yield_displacement)
    if args.manifest and args.files:
        raise DataError("give the test files or --manifest, not both.")
    if args.manifest:
        campaign = load_manifest(args.manifest, effective_radius=args.effective_radius,
                                 slider_diameter=args.slider_diameter,
                                 axial_load=args.axial_load, max_rows=max_rows,
                                 must_agree=True, argument_names=FLAG_NAMES)
    else:
        if not args.files:
            raise DataError("give one or more test files, or --manifest.")
        for name, value in (("--effective-radius", args.effective_radius),
                            ("--slider-diameter", args.slider_diameter)):
            if value is None:
                raise DataError(f"{name} is required (or a TOML --manifest that gives it).")
        campaign = load_any_campaign(args.files, effective_radius=args.effective_radius,
                                     slider_diameter=args.slider_diameter,
                                     axial_load=args.axial_load, max_rows=max_rows)
    diagnosis = diagnose(campaign, spec, exclude=tuple(args.exclude))
    summary = diagnosis.to_json()
    if args.report:
        from dcfpb.cli.outputs import writing

        with writing("--report", args.report):
            from isolator.diagnosis.report import write_report

            written = write_report(diagnosis, args.report, "\n".join(_lines(summary)))
        summary["report"] = [str(p) for p in written]
    print(json.dumps(summary, indent=2) if args.json else "\n".join(_lines(summary)))
    return EXIT_OK


def _check_flags(args: argparse.Namespace) -> None:
    """The numeric flags given, checked by their names and with the ranges the diagnosis takes
    (before the classes it builds would name their own parameters)."""
    from dcfpb.common.validation import check_real

    owner = "dcfpb diagnose"
    if args.effective_radius is not None:
        check_real(args.effective_radius, "--effective-radius", owner, low=0.0, low_open=True,
                   allow_inf=True)
    if args.slider_diameter is not None:
        check_real(args.slider_diameter, "--slider-diameter", owner, low=0.0, low_open=True,
                   high=10.0)
    if args.axial_load is not None:
        check_real(args.axial_load, "--axial-load", owner, low=0.0, low_open=True)
    if args.yield_displacement is not None:
        check_real(args.yield_displacement, "--yield-displacement", owner, low=0.0,
                   low_open=True, high=0.1)


def _lines(summary: dict) -> list[str]:
    """The printed summary, line by line (one direction or two)."""
    out: list[str] = []
    emit = out.append
    gap = summary["gap"]
    two = summary.get("dimension") == 2
    if two:
        emit("tests in two directions: " + "; ".join(
            f"{o['test']} (peak |u| {1e3 * o['peak_radius']:.0f} mm, "
            f"{o['heading_turns']:+.1f} turns of the heading)" for o in summary["orbits"]))
    emit(f"baseline: {summary['baseline']['model']}  ("
          + ", ".join(f"{k} = {v:.4g}" for k, v in summary["baseline"]["parameters"].items())
          + ")")
    emit(f"held-out force NRMSE: {gap['value']:.4f}   noise: {gap['noise']:.4f}   "
          f"({gap['holdout']})")
    emit(f"where: {summary['where']['statement']}")
    if summary.get("transition"):
        label = "direction changes" if two else "transition"
        emit(f"{label}: {summary['transition']['statement']}")
        after = summary["transition"].get("after_named")
        if after and after["far_above_noise"]:
            emit(f"{label}, with the named effects: still {after['score'] ** 0.5:.3g} x "
                 f"the noise there (an excess of {100 * after['excess']:.2g} % of the RMS "
                 f"force over the whole test)")
    for note in summary.get("baseline_notes", []):
        emit(f"baseline: {note}")
    lag = summary.get("lag")
    if lag:
        emit(f"channel lag: {1e3 * lag['seconds']:.3g} ms ({lag['samples']:.2f} samples)"
              + (" - named" if lag["named"] else " - calibrated in the baseline"))
    nuisance = summary.get("nuisance")
    if nuisance:
        uy, lg = nuisance["yield_displacement"], nuisance["lag"]
        edge = {"top": " - AT THE TOP OF ITS RANGE (a finding, not a calibration)"}
        lead = {"lead": " - AT ITS EDGE, force leading", "late": " - AT ITS EDGE, force late"}
        emit(f"nuisance: u_y {1e3 * uy['value']:.3g} mm in {1e3 * uy['range'][0]:.3g}-"
              f"{1e3 * uy['range'][1]:.3g} mm{edge.get(uy['at_edge'], '')}; lag "
              f"{lg['samples']:.2f} samples in +-{lg['range_samples'][1]:g}"
              f"{lead.get(lg['at_edge'], '')}")
        cand = nuisance.get("lag_candidate")
        if cand and cand.get("per_test_samples"):
            emit("lag fitted test by test: "
                  + ", ".join(f"{x:.1f}" for x in cand["per_test_samples"])
                  + f" samples (a channel lag is one for all tests, force late, at most "
                  f"{1e3 * lg['plausible_max']:.0f} ms)")
    emit(f"{'effect':11s} {'NRMSE':>8s} {'shrink':>7s} {'z':>6s}  role")
    for e in summary["effects"]:
        if e.get("gap_after") is not None:
            emit(f"{e['name']:11s} {e['gap_after']:8.4f} {100 * e['shrink']:6.0f}% "
                  f"{e['held_out_z']:6.1f}  {e['role']}")
        else:
            emit(f"{e['name']:11s} {'-':>8s} {'-':>7s} {'-':>6s}  {e['role']}")
    emit(f"verdict: {', '.join(summary['verdict'])}")
    chosen = summary["chosen"]
    if chosen is not None and summary["verdict"] != ["unexplained"]:
        emit(f"gap with {' + '.join(chosen['names'])}: {chosen['gap_before']:.4f} -> "
              f"{chosen['gap_after']:.4f} (shrink {100 * chosen['shrink']:.0f} %)")
        heat = chosen.get("baseline_heat")
        if heat and heat["laws"]:
            emit(f"baseline heat: {heat['statement']}")
        for name, value in chosen.get("confidence", {}).items():
            if value is not None:
                emit(f"confidence in {name}: {100 * value:.0f} % of block resamples")
    if two and chosen is not None:
        for name, values in chosen["parameters"].items():
            emit(f"  {name}: " + ", ".join(f"{k} = {v:.4g}" for k, v in values.items()))
    if two:
        axes = summary["axes"]
        emit("force error RMS by axis: " + ", ".join(
            f"{a} {1e-3 * v['error_rms_before']:.3g} -> {1e-3 * v['error_rms_after']:.3g} kN"
            for a, v in axes.items()))
        for note in summary.get("notes", []):
            if note not in summary.get("baseline_notes", []):
                emit(f"note: {note}")
    if summary["unexplained"]:
        emit(f"unexplained: {summary['unexplained']['statement']}")
        for text in summary["unexplained"]["looks_like"]:
            emit(f"unexplained: looks like {text}")
    for path in summary.get("report", []):
        emit(f"wrote {path}")
    return out
