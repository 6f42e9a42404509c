"""``dcfpb prototype``: the virtual prototype test of ASCE/SEI 7-16 17.8 on a building file's
bearing (:func:`structures.design.prototype_test`): the cyclic sequence of 17.8.2.2 at D_M,
D_TM and T_M (from the equivalent lateral force procedure of the file, or given), and per
cycle the characteristic strength Q_d = EDC / (4 D), mu = EDC / (4 W D) and its ratio to the
nominal mu, with the test property modification factors it implies.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
from pathlib import Path

from dcfpb.common.errors import EXIT_OK, InputError
from dcfpb.common.files import json_safe
from dcfpb.common.validation import parse_floats

_COMMAND = "dcfpb prototype"

CYCLE_COLUMNS = (("block", ""), ("cycle", ""), ("D", "m"), ("EDC", "J"), ("Q_d", "N"),
                 ("mu", "-"), ("ratio", "-"), ("K_eff", "N/m"), ("beta_eff", "-"),
                 ("peak_temperature", "degC"))
"""The columns of ``--output FILE.csv`` and their units."""

FIGURE = "prototype_hysteresis.png"
"""The file ``--plot DIR`` writes."""


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``prototype`` sub-command to the ``dcfpb`` parser."""
    p = sub.add_parser(
        "prototype",
        help="virtual prototype test of ASCE 7-16 17.8 on a building file's bearing: Q_d, mu "
        "and the test lambda per cycle",
        description="Run the cyclic prototype test sequence of ASCE/SEI 7-16 17.8.2.2 on the "
        "bearing of a building file (loaded by its share of the weight) and print per "
        "complete cycle D, EDC, Q_d = EDC / (4 D), mu = Q_d / W and mu over the nominal mu "
        "(the mean at D_M), with the lambda_test,max and lambda_test,min it implies. D_M, "
        "D_TM and T_M come from the equivalent lateral force procedure (17.5) of the file's "
        "[design] table or of --site and --lambda (the lower bound, which governs the "
        "displacements), or are given with --displacements and --period.",
    )
    p.add_argument("building", metavar="BUILDING.toml", help="building file")
    p.add_argument("--model", choices=("precise", "simplified", "constant"),
                   help="friction model of the bearing (default: the building file's)")
    p.add_argument("--site", metavar="S_MS,S_M1[,T_L]",
                   help="MCE_R spectral accelerations [g] (and T_L [s]) of the ELF that gives "
                   "D_M, D_TM and T_M (default: the building file's [design] table)")
    p.add_argument("--lambda", dest="lambda_", metavar="MAX,MIN",
                   help="property modification factors of that ELF (default: the file's "
                   "[design] table, else 1,1: nominal properties)")
    p.add_argument("--R", type=float, dest="R", default=None,
                   help="R of that ELF (default: the file's [design] R, else 2; it does not "
                   "change D_M, D_TM or T_M)")
    p.add_argument("--displacements", metavar="D_M,D_TM",
                   help="the test's displacements [m], 0 < D_M <= D_TM <= the bearing's "
                   "capacity, instead of the ELF's (with --period)")
    p.add_argument("--period", type=float, metavar="T_M",
                   help="the test's period [s] instead of the ELF's (with --displacements)")
    p.add_argument("--lambda-test", metavar="MAX,MIN",
                   help="the test factors the design assumes (lambda_test,max >= 1, "
                   "lambda_test,min in (0, 1]): the implied ones are compared with them")
    p.add_argument("--wind", type=float, default=0.0, metavar="D_W",
                   help="amplitude of the twenty wind cycles of item 1 [m] (default 0: none)")
    p.add_argument("--dt", type=float, help="time step [s] (default T_M / 200)")
    p.add_argument("--output", metavar="FILE.csv|FILE.json",
                   help="write the per-cycle table (CSV, SI units in the header) or every "
                   "number (JSON)")
    p.add_argument("--plot", metavar="DIR",
                   help=f"write the hysteresis loop and temperature history to DIR/{FIGURE}")
    p.add_argument("--overwrite", action="store_true",
                   help="replace an existing --output file or figure")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.set_defaults(handler=_run)


def _design_inputs(args: argparse.Namespace, config) -> dict:
    """D_M, D_TM, T_M [m, m, s] (and S_MS, S_M1, B_M for the cycles of item 4) of the test: from
    the flags, or from the ELF's lower bound (the largest D_M; D_TM the largest over the bounds
    and directions)."""
    from dcfpb.cli.design import parse_lambda, parse_site
    from dcfpb.common.validation import check_real
    from structures.design import PropertyModification, elf

    if (args.displacements is None) != (args.period is None):
        raise InputError("--displacements D_M,D_TM and --period T_M go together: give both, or "
                         "neither (then the ELF gives them).")
    if args.displacements is not None:
        d_m, d_tm = parse_floats(args.displacements, "--displacements", "D_M,D_TM in m",
                                 count=2)
        check_real(d_m, "--displacements D_M", _COMMAND, low=0.0, low_open=True, high=5.0)
        check_real(d_tm, "--displacements D_TM", _COMMAND, low=d_m, high=5.0)
        t_m = check_real(args.period, "--period", _COMMAND, low=0.0, high=20.0, low_open=True)
        for flag, value in (("--site", args.site), ("--lambda", args.lambda_),
                            ("--R", args.R)):
            if value is not None:
                import warnings

                from dcfpb.common.errors import InputWarning

                warnings.warn(f"{flag} has no effect with --displacements and --period: the "
                              "ELF is not computed.", InputWarning, stacklevel=2)
        site = parse_site(args.site) if args.site else None
        return {"D_M": d_m, "D_TM": d_tm, "T_M": t_m, "source": "given",
                "S_MS": None if site is None else site.S_MS,
                "S_M1": None if site is None else site.S_M1, "B_M": None}
    from structures.design.response import design_inputs

    missing = {"site": f"--site S_MS,S_M1[,T_L] (or --displacements and --period) must be "
                       f"given: the building file {args.building} has no [design] S_MS and "
                       "S_M1."}
    site, lam, R = design_inputs(
        config, parse_site(args.site) if args.site is not None else None,
        parse_lambda(args.lambda_, None, _COMMAND), args.R, missing=missing,
        defaults={"lambda": PropertyModification.overall(1.0, 1.0), "R": 2.0})
    R = check_real(float(R), "--R", _COMMAND, low=0.0, high=10.0, low_open=True)
    result = elf(config, site, lam, R=R, model=args.model)
    bound = max(result.bounds.values(), key=lambda b: b.D_M)
    d_tm = max(d.D_TM for b in result.bounds.values() for d in b.directions.values())
    return {"D_M": bound.D_M, "D_TM": d_tm, "T_M": bound.T_M, "source": f"ELF, {bound.bound} "
            f"bound (lambda {bound.lambda_:g})", "S_MS": site.S_MS, "S_M1": site.S_M1,
            "B_M": bound.B_M}


def _run(args: argparse.Namespace) -> int:
    from dcfpb.cli.outputs import check_outputs, writing
    from dcfpb.common.validation import check_real
    from structures.config import load_config
    from structures.design import prototype_test

    check_outputs(files={"--output": args.output}, folders={"--plot": args.plot},
                  inputs={"the building file": args.building}, overwrite=args.overwrite,
                  formats={"--output": {".csv": "CSV", ".json": "JSON"}},
                  writes={"--plot": (FIGURE,)})
    lambda_test = None
    if args.lambda_test is not None:
        lambda_test = parse_floats(args.lambda_test, "--lambda-test", "MAX,MIN", count=2)
        check_real(lambda_test[0], "--lambda-test MAX", _COMMAND, low=1.0, high=10.0)
        check_real(lambda_test[1], "--lambda-test MIN", _COMMAND, low=0.0, high=1.0,
                   low_open=True)
    check_real(args.wind, "--wind", _COMMAND, low=0.0, high=1.0)
    if args.dt is not None:
        check_real(args.dt, "--dt", _COMMAND, low=0.0, high=1.0, low_open=True)
    config = load_config(args.building)
    inputs = _design_inputs(args, config)
    capacity = float(config.bearing(args.model).displacement_capacity)
    if inputs["D_TM"] > capacity:
        how = ("--displacements" if inputs["source"] == "given" else
               f"the {inputs['source']} (--site, --lambda or the file's [design])")
        raise InputError(f"D_TM = {inputs['D_TM']:.4g} m from {how} is beyond the bearing's "
                         f"displacement capacity {capacity:g} m: the bearing cannot be tested "
                         "to it. Give a larger displacement_capacity in the building file, or "
                         "--displacements D_M,D_TM and --period T_M.")
    result = prototype_test(config, inputs["D_M"], inputs["D_TM"], inputs["T_M"],
                            model=args.model, dt=args.dt, S_M1=inputs["S_M1"],
                            S_MS=inputs["S_MS"], B_M=inputs["B_M"],
                            wind_displacement=args.wind)
    comparison = _comparison(result, lambda_test)
    with writing("--output", args.output):
        if args.output:
            _write_output(result, inputs, comparison, Path(args.output))
    figure = None
    if args.plot:
        with writing("--plot", args.plot):
            figure = _plot(result, Path(args.plot), inputs)
    if args.json:
        print(json.dumps(_data(result, inputs, comparison), indent=2, allow_nan=False,
                         default=_none))
    else:
        print(f"D_M, D_TM, T_M from {inputs['source']}")
        print(result.table())
        for line in comparison["lines"]:
            print(line)
        if args.output:
            print(f"table: {args.output}")
        if figure:
            print(f"plot: {figure}")
    return EXIT_OK


def _none(value):
    return None


def _comparison(result, lambda_test: tuple[float, float] | None) -> dict:
    """The implied test factors against those the design assumes (``--lambda-test``)."""
    if lambda_test is None:
        return {"assumed": None, "within": None, "lines": []}
    high, low = lambda_test
    within = result.lambda_test_max <= high and result.lambda_test_min >= low
    line = (f"implied lambda_test {result.lambda_test_max:.4f} / {result.lambda_test_min:.4f} "
            f"{'within' if within else 'OUTSIDE'} the assumed {high:g} / {low:g} (--lambda-test)")
    return {"assumed": {"max": high, "min": low}, "within": within, "lines": [line]}


def _data(result, inputs: dict, comparison: dict) -> dict:
    data = result.to_dict()
    data["inputs"] = dict(inputs)
    data["lambda_test_assumed"] = comparison["assumed"]
    data["lambda_test_within"] = comparison["within"]
    return json_safe(data)


def _write_output(result, inputs: dict, comparison: dict, path: Path) -> None:
    from dcfpb.common.files import atomic_output

    with atomic_output(path) as temporary:
        if path.suffix.lower() == ".json":
            temporary.write_text(json.dumps(_data(result, inputs, comparison), indent=1,
                                            allow_nan=False) + "\n", encoding="utf-8")
            return
        with open(temporary, "w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow([f"{name} [{unit}]" if unit else name
                             for name, unit in CYCLE_COLUMNS])
            for cycle in result.cycles:
                writer.writerow([_cell(getattr(cycle, name)) for name, _ in CYCLE_COLUMNS])


def _cell(value):
    if isinstance(value, float):
        return "" if not math.isfinite(value) else repr(value)
    return value


def _plot(result, folder: Path, inputs: dict) -> Path:
    from dcfpb.plotting.design import plot_prototype

    folder.mkdir(parents=True, exist_ok=True)
    return plot_prototype(result, folder / FIGURE)
