"""The bidirectional panel's own parts, without the diagnosis: the truth's self-checks, the
two-direction files, the labels and the scorer's hook.

The bidirectional truth (``validation/diagnosis/bidirectional/``) is a numpy-only 2D bearing
test written apart from the package; its panel has 28 cases in 14 tune/test pairs. Here a few
pairs are written to a temporary folder (the generated data stays out of git) and checked:
the agreed file format (``time, displacement_x, displacement_y, force_x, force_y`` and the
optional ``axial_force, velocity_x, velocity_y``, ``.csv`` or ``.csv.gz``), the manifests and
``bearing.json``, the labels kept apart with the outside panel's structure, the 3 % label rule,
and the scorer's ``--panel bidirectional`` hook (with the diagnosis replaced by a stub, so that
this test does not depend on the two-direction diagnosis written elsewhere). About 20 s.
"""

from __future__ import annotations

import ast
import csv
import functools
import gzip
import json
import math
from pathlib import Path

import numpy as np
import pytest

from validation.diagnosis import bidirectional as bi
from validation.diagnosis import score as scorer
from validation.diagnosis.bidirectional.cases import LABEL_MIN, check_design
from validation.diagnosis.bidirectional.write import chain

PAIRS = ("B01", "B02", "B05", "B10", "B11")  # none (x2, one gzip), decoy, backlash, lag
REQUIRED = ["time", "displacement_x", "displacement_y", "force_x", "force_y"]
OPTIONAL = {"axial_force", "velocity_x", "velocity_y"}
PACKAGE = Path(bi.__file__).parent


@pytest.fixture(scope="module")
def panel(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("bidirectional")
    bi.write_panel(folder, seed=2026, pairs=PAIRS)
    return folder


def _read(path: Path) -> tuple[list[str], np.ndarray]:
    text = gzip.decompress(path.read_bytes()).decode() if path.suffix == ".gz" else \
        path.read_text()
    lines = text.splitlines()
    return lines[0].split(","), np.loadtxt(lines[1:], delimiter=",", ndmin=2)


def test_the_self_checks_hold():
    errors = bi.checks(verbose=False)
    assert set(errors) == set(bi.TOLERANCES)
    failed = {k: v for k, v in errors.items() if not v <= bi.TOLERANCES[k]}
    assert not failed


def test_the_truth_imports_nothing_of_the_package():
    banned = ("isolator", "structures", "groundmotions", "dcfpb", "tests")
    for module in PACKAGE.glob("*.py"):
        for node in ast.walk(ast.parse(module.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                     [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            for name in names:
                assert name.split(".")[0] not in banned, f"{module.name} imports {name}"
                if name.startswith("validation.diagnosis."):  # only itself (and the 1D check)
                    assert name.startswith("validation.diagnosis.bidirectional") or (
                        module.name == "checks.py"
                        and name == "validation.diagnosis"), f"{module.name}: {name}"


def test_the_design_covers_what_the_issue_asks():
    check_design()
    cases = bi.CASES
    for half in bi.HALVES:
        assert sum(c.half == half for c in cases) >= 10
    assert sum(not c.effects for c in cases) >= 6
    singles = {c.effects[0] for c in cases if len(c.effects) == 1}
    assert singles == set(bi.EFFECTS)
    assert sum(len(c.effects) == 2 for c in cases) >= 4
    assert sum(c.truth.startswith("decoy") for c in cases) >= 4
    kinds = {r.orbit[0] for c in cases for r in c.tests}
    assert kinds == {"circular", "eight", "square", "quake"}
    assert {c.noise_kind for c in cases} == {"white", "ar1", "band"}
    assert {c.dt for c in cases} >= {0.01, 0.005, 0.004, 0.002}
    assert any(c.actuator for c in cases) and any(c.quantise for c in cases)
    assert any(c.spikes for c in cases) and any(c.stuck for c in cases)
    assert any(c.gain for c in cases)
    nuisance = [c.lag_samples for c in cases if "lag" not in c.effects]
    assert max(nuisance) <= 1.5


def test_the_files_have_the_two_direction_format(panel):
    labels = json.loads((panel / "labels.json").read_text())
    assert len(labels) == 2 * len(PAIRS)
    gz = 0
    for name in labels:
        folder = panel / name
        manifest = list(csv.DictReader((folder / "manifest.csv").open()))
        assert list(manifest[0]) == ["file", "axial_load", "initial_temperature",
                                     "rest_before"]
        assert manifest[0]["rest_before"] == ""
        files = {p.name for p in folder.iterdir()}
        assert files == {"manifest.csv", "bearing.json"} | {row["file"] for row in manifest}
        told = json.loads((folder / "bearing.json").read_text())
        assert {"effective_radius", "slider_diameter", "baseline", "without"} <= set(told)
        assert set(told) <= {"effective_radius", "slider_diameter", "baseline", "without",
                             "axial_load"}
        for row in manifest:
            header, data = _read(folder / row["file"])
            gz += row["file"].endswith(".csv.gz")
            assert header[:5] == REQUIRED and set(header[5:]) <= OPTIONAL
            assert data.shape[1] == len(header) and data.shape[0] > 500
            assert np.all(np.diff(data[:, 0]) > 0.0) and data[0, 0] == 0.0
            assert np.all(np.isfinite(data))
            assert ("axial_force" in header) == (row["axial_load"] == "")
            assert ("axial_load" in told) == (row["axial_load"] != "")
            force = np.hypot(data[:, 3], data[:, 4])
            assert 1.0e4 < np.sqrt(np.mean(force**2)) < 1.0e6  # [N] a 4 MN bearing
            assert np.max(np.hypot(data[:, 1], data[:, 2])) < 0.3  # [m]
    assert gz >= 2


def test_the_labels_are_kept_apart_with_the_outside_structure(panel):
    labels = bi.load_labels(panel)
    for name, label in labels.items():
        assert set(label) == {"effects", "truth", "source", "half", "design"}
        assert label["source"] == "bidirectional" and label["half"] in bi.HALVES
        assert set(label["effects"]) <= set(bi.EFFECTS)
        design = label["design"]
        assert design["label_rule_met"]
        assert set(design["contribution"]) == set(label["effects"])
        assert all(v >= LABEL_MIN for v in design["contribution"].values())
        assert not (panel / name / "labels.json").exists()
    halves = [v["half"] for v in labels.values()]
    assert halves.count("tune") == halves.count("test") == len(PAIRS)


def test_the_label_rule_measures_the_effect_alone():
    case = next(c for c in bi.CASES if c.pair == "B11" and c.half == "tune")  # lag 8 samples
    clean = bi.truth(case, {"lag"})
    plain = bi.truth(case, set())
    shift = 8
    for a, b in zip(clean, plain, strict=True):
        assert np.allclose(a["force"][shift:], b["force"][:-shift], atol=1e-6 * case.weight)
    shares = bi.contributions(case, clean)
    assert shares["contribution"]["lag"] >= LABEL_MIN


def test_the_measurement_is_the_truth_plus_its_nuisance():
    case = next(c for c in bi.CASES if c.pair == "B01" and c.half == "test")  # AR(1), 16 bit
    clean = bi.truth(case, set())[0]
    out = bi.measure(clean, chain(case), np.random.default_rng(3))
    residual = out["force_x"] - clean["force"][:, 0]
    sigma = case.noise * case.mu0 * case.weight
    assert 0.5 * sigma < np.std(residual) < 1.5 * sigma
    lsb = 2.0 * 1.5e6 / 2**16
    assert np.allclose(out["force_x"] / lsb, np.round(out["force_x"] / lsb))
    assert np.max(np.abs(out["displacement_x"] - clean["displacement"][:, 0])) < 2e-4


def test_the_orbits_start_and_end_at_rest():
    from validation.diagnosis.bidirectional.orbits import ground_pair

    # the fallback without shared data: a synthetic stand-in, said in the source and warned
    with pytest.warns(UserWarning, match="NO-SUCH-PAIR is absent"):
        assert "synthetic" in ground_pair("NO-SUCH-PAIR")[2]
    with pytest.warns(UserWarning, match="synthetic stand-in"):
        stand_in = bi.earthquake("NO-SUCH-PAIR", 0.2)
    for orbit in (bi.circular(0.1, 2.0, 2), bi.square(0.1, 0.2, 1),
                  stand_in, bi.earthquake("TAP094", 0.15)):
        t = np.arange(0.0, orbit.duration, 0.002)
        u, v = orbit.displacement(t), orbit.velocity(t)
        assert np.allclose(u[0], 0.0) and np.max(np.abs(u[-1])) < 1e-3
        du = np.gradient(u, t, axis=0)  # the velocity is the displacement's derivative
        off = np.max(np.abs(du - v), axis=1) > 0.02 * np.max(np.abs(v))
        assert np.mean(off) < 0.01  # (a square's corners: a sample each)
    assert math.isclose(np.max(np.hypot(*bi.earthquake("TAP094", 0.15).displacement(
        np.arange(0.0, 20.0, 0.005)).T)), 0.15, rel_tol=0.01)


def test_the_panel_is_reproducible(tmp_path, panel):
    bi.write_panel(tmp_path, seed=2026, pairs=("B01",))
    names = [n for n, v in bi.load_labels(tmp_path).items()]
    for name in names:
        for path in (tmp_path / name).iterdir():
            assert path.read_bytes() == (panel / name / path.name).read_bytes()


def test_the_scorer_hook_writes_the_half_and_diagnoses_its_cases(tmp_path, monkeypatch,
                                                                capsys):
    seen = []

    def fake_diagnose(folder, names, thresholds=None, progress=False):
        seen.extend(names)
        return {}

    monkeypatch.setattr(scorer, "diagnose_cases", fake_diagnose)
    monkeypatch.setattr(bi, "write_panel", functools.partial(bi.write_panel,
                                                             pairs=("B01", "B11")))
    assert scorer.main(["--panel", "bidirectional", str(tmp_path), "--half", "test"]) == 0
    labels = bi.load_labels(tmp_path)
    assert seen == sorted(labels) and len(seen) == 2
    assert all(v["half"] == "test" for v in labels.values())
    assert scorer.case_names(tmp_path, "test") == seen
    assert "written to" in capsys.readouterr().out


def test_the_scorer_rules_apply_to_bidirectional_verdicts():
    assert scorer.exactly_right(["backlash", "heating", "unexplained"], ["backlash", "heating"])
    assert not scorer.exactly_right(["heating"], ["backlash", "heating"])
    assert scorer.exactly_right(["none"], [])
    assert scorer.named(["lag", "unexplained"]) == {"lag"}


class _Stub2D:
    """What the scorer uses of a diagnosis in two directions: its verdict and summary."""

    def __init__(self, verdict: list[str], before: float, after: float | None) -> None:
        self.verdict = verdict
        self._summary = {"gap": {"value": before, "noise": 0.01},
                         "chosen": None if after is None else
                         {"gap_after": after, "shrink": 1.0 - after / before}}

    def to_json(self) -> dict:
        return self._summary


def test_the_scorer_rows_read_a_two_direction_summary():
    labels = {"case_01": {"effects": ["backlash"], "truth": "", "source": "bidirectional",
                          "half": "test"},
              "case_02": {"effects": [], "truth": "", "source": "bidirectional",
                          "half": "test"}}
    diagnoses = {"case_01": (_Stub2D(["backlash", "unexplained"], 0.2, 0.05), 1.0),
                 "case_02": (_Stub2D(["lag"], 0.03, 0.02), 1.0)}
    # a stub cannot be diagnosed again: its leave-one-out runs reported as not run
    # (tests/unit/test_score_loo_2d.py: they are run by default)
    rows = scorer.score(diagnoses, labels, loo_2d=False)
    assert rows[0]["right"] and rows[0]["gap_before"] == 0.2 and rows[0]["gap_after"] == 0.05
    assert math.isclose(rows[0]["shrink"], 0.75)
    assert rows[0]["loo"] == [{"withheld": "backlash", "verdict": None, "right": None}]
    assert rows[1]["false_names"] == ["lag"] and not rows[1]["right"]
    figures = scorer.summarize(rows)
    assert figures["right_count"] == 1 and figures["false_names_in_no_effect_cases"] == 1
    assert figures["loo_runs"] == 0
    assert "-backlash: not run" in scorer.markdown(rows, figures, "test")


def test_the_diagnosis_reads_a_bidirectional_case(panel):
    """Through the same entry points as in one direction (skips until the diagnosis reads
    two-direction tests)."""
    name = next(n for n, v in bi.load_labels(panel).items() if v["design"]["pair"] == "B05")
    try:
        campaign, spec = scorer.load_case(panel / name)
    except Exception as error:  # the two-direction reader is written by another helper
        if "displacement_x" in str(error) or "missing column" in str(error):
            pytest.skip(f"the diagnosis does not read two-direction tests yet: {error}")
        raise
    assert spec.model == "constant" and tuple(spec.without) == ()
    assert len(campaign.tests) == 2
    assert campaign.effective_radius == 4.5 and campaign.slider_diameter == 0.3
