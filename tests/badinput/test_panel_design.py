"""The bad-input panel of the designer's commands, ``dcfpb design`` and ``dcfpb prototype``.

Each case is one call of the command line (``dcfpb.cli.main`` in-process) on copies in
``tmp_path`` beside an earlier report, and asserts (a) exit status 2, (b) that the message
names the flag, key or file concerned and the allowed range or the way out, and no internal
function where a flag was given, and (c) that no input and no earlier output changed (every
file hashed before and after). Every case is refused before a single run starts.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

from dcfpb.cli import main

REPO = Path(__file__).resolve().parents[2]
BUILDING = REPO / "examples" / "five_storey.toml"
PLAN = REPO / "examples" / "five_storey_plan.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
SITE = ("--site", "1.5,0.6,8", "--lambda", "1.2,0.8", "--R", "2", "--no-progress")


@dataclass
class Inputs:
    """The copies a case works on, in its own folder, and an earlier report beside them."""

    folder: Path

    def path(self, name: str) -> str:
        return str(self.folder / name)

    def manifest(self, name: str, y: str) -> str:
        """A one-pair manifest whose y component is the file ``y``."""
        (self.folder / name).write_text(f"name,x,y\np1,rec.at2,{y}\n")
        return self.path(name)

    def snapshot(self) -> dict[str, str]:
        return {str(p.relative_to(self.folder)): hashlib.sha256(p.read_bytes()).hexdigest()
                for p in sorted(self.folder.rglob("*")) if p.is_file()}


@pytest.fixture
def inputs(tmp_path: Path) -> Inputs:
    (tmp_path / "plan.toml").write_text(PLAN.read_text())
    (tmp_path / "building.toml").write_text(BUILDING.read_text())
    (tmp_path / "rec.at2").write_bytes(RECORD.read_bytes())
    (tmp_path / "pairs.csv").write_text("name,x,y\np1,rec.at2,rec.at2\n")
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "report.md").write_text("the engineer's earlier report\n")
    (tmp_path / "table.csv").write_text("cycle,EDC\n1,1.0\n")
    return Inputs(tmp_path)


def _design(i: Inputs, *extra: str, pairs: str = "pairs.csv", out: str = "new") -> list[str]:
    return ["design", i.path("plan.toml"), "--pairs", i.path(pairs), "--out", i.path(out),
            *SITE, *extra]


def _prototype(i: Inputs, *extra: str) -> list[str]:
    return ["prototype", i.path("building.toml"), *SITE[:-1], *extra]


@dataclass
class Case:
    argv: Callable[[Inputs], list[str]]
    names: tuple[str, ...]
    absent: tuple[str, ...] = ()  # words the message must not hold (an internal name)


CASES: dict[str, Case] = {
    # outputs: never over an input or an earlier report
    "design-out-is-the-building-file": Case(
        lambda i: _design(i, out="plan.toml"), ("--out", "plan.toml", "not a folder")),
    "design-out-holds-an-earlier-report": Case(
        lambda i: _design(i, out="out"), ("--out", "report.md", "--overwrite")),
    "prototype-output-over-the-record": Case(
        lambda i: _prototype(i, "--output", i.path("rec.at2")), ("--output", ".csv", ".json")),
    "prototype-output-over-an-earlier-table": Case(
        lambda i: _prototype(i, "--output", i.path("table.csv")), ("table.csv", "--overwrite")),
    "prototype-plot-is-a-file": Case(
        lambda i: _prototype(i, "--plot", i.path("rec.at2")), ("--plot", "not a folder")),
    # inputs: the building, the suite, the records
    "design-building-without-plan": Case(
        lambda i: ["design", i.path("building.toml"), "--pairs", i.path("pairs.csv"),
                   "--out", i.path("new"), *SITE], ("building.toml", "[plan]")),
    "design-manifest-missing": Case(
        lambda i: _design(i, pairs="nope.csv"), ("nope.csv", "does not exist")),
    "design-fewer-than-seven-pairs": Case(
        lambda i: _design(i), ("--pairs", "17.3.2", "7 pairs", "--allow-fewer", "--synthetic")),
    "design-record-of-a-pair-missing": Case(
        lambda i: _design(i, "--allow-fewer", pairs=i.manifest("m.csv", "missing.at2")),
        ("p1", "missing.at2", "does not exist")),
    "design-record-of-a-pair-not-a-record": Case(
        lambda i: _design(i, "--allow-fewer", pairs=i.manifest("m.csv", "plan.toml")),
        ("p1", "plan.toml")),
    # flags: each named with its allowed range
    "design-R-negative": Case(lambda i: _design(i, "--R", "-1"), ("--R", "(0, 10]")),
    "design-lambda-max-below-one": Case(
        lambda i: _design(i, "--lambda", "0.5,2"), ("--lambda MAX", "[1, 10]", "0.5"),
        absent=("PropertyModification", "overall_max")),
    "design-lambda-factor-min-above-one": Case(
        lambda i: [a for a in _design(i, "--lambda-factors", "ae_max=1.2,test_min=1.3")
                   if a not in ("--lambda", "1.2,0.8")],
        ("--lambda-factors test_min", "(0, 1]", "1.3"), absent=("PropertyModification",)),
    "design-site-not-numbers": Case(
        lambda i: _design(i, "--site", "high,low"), ("--site",)),
    "design-position-unknown": Case(
        lambda i: _design(i, "--positions", "+z"), ("--positions", "+x, -x, +y, -y", "+z")),
    "design-synthetic-negative": Case(
        lambda i: _design(i, "--synthetic", "-1"), ("--synthetic", "0 to 100", "auto")),
    "design-workers-zero": Case(
        lambda i: _design(i, "--workers", "0"), ("--workers", "[1, inf)")),
    "prototype-displacements-out-of-order": Case(
        lambda i: _prototype(i, "--displacements", "0.3,0.2", "--period", "3"),
        ("--displacements", "D_TM", "0.2")),
    "prototype-dt-negative": Case(lambda i: _prototype(i, "--dt", "-1"), ("--dt", "(0, 1]")),
    "prototype-wind-nan": Case(lambda i: _prototype(i, "--wind", "nan"), ("--wind", "nan")),
    "prototype-lambda-min-zero": Case(
        lambda i: _prototype(i, "--lambda", "1.2,0"), ("--lambda MIN", "dcfpb prototype",
                                                      "(0, 1]"), absent=("PropertyModification",)),
    "prototype-lambda-test-min-above-one": Case(
        lambda i: _prototype(i, "--lambda-test", "1.2,1.5"), ("--lambda-test",)),
}


@pytest.mark.parametrize("case", CASES, ids=list(CASES))
def test_panel_design(case, inputs, capsys):
    spec = CASES[case]
    argv = spec.argv(inputs)
    before = inputs.snapshot()
    status = main(argv)
    err = capsys.readouterr().err
    assert status == 2, err
    for name in spec.names:
        assert name in err, (name, err)
    for word in (*spec.absent, "Traceback"):
        assert word not in err, (word, err)
    assert inputs.snapshot() == before
    assert not (inputs.folder / "new").exists()  # refused before any output was made
