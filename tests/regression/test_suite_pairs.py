"""Suites of pairs (issue 13 point 5): a building in plan under pairs of records, run by the one
suite of :mod:`structures.suites` as records are.

- a suite's row of a pair is ``structures.peaks(structures.run(config, pair, model=..., dt=...,
  scale=...))`` to the last digit (synthetic pairs written to files; a recorded Chi-Chi pair of
  ../shared when it is there);
- a pair that cannot be read (a missing component, components of two time steps) is a failed
  run with its reason while the others finish; a rerun keeps the finished runs (no second
  "done" in the log) and retries the failures;
- factors to a target on RotD100 (the hook of ``dcfpb suite --target``) are those of
  ``scale_suite``; ``run_timeout`` and
  ``max_steps`` reach each run;
- ``dcfpb suite --pairs``: the resumed suite, its JSON, tables and plots; a building file in one
  direction refused before any work, naming the flag and the file.

The building is small (two storeys on four bearings) and the pairs 1.5 s at 10 ms: the
reference engine of the building in plan runs about 150 steps a second here.
"""

from __future__ import annotations

import dataclasses
import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import structures
from dcfpb import cli
from dcfpb.cli.suite import target_hook
from dcfpb.common.errors import InputError, InputWarning
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.pairs import read_pair
from groundmotions.records import GroundMotion
from groundmotions.scaling import asce7_design_spectrum, scale_suite
from groundmotions.synthetic import synthetic_pair
from structures.analysis import peaks
from structures.config import load_config
from structures.suites.runs import PEAK_COLUMNS, execute_run
from structures.suites.sources import motion_sources
from structures.suites.store import RunStore
from structures.suites.suite import Suite, run_suite
from structures.suites.tasks import local_cluster

REPO = Path(__file__).resolve().parents[2]
PHYSICS = [c for c in PEAK_COLUMNS["pair"] if c != "wall_time"]


def pair_sources(manifest):
    return motion_sources(manifest, pairs=True)

BUILDING = """
name = "two-storey test building in plan"

[building]
floor_masses = [300e3, 300e3]
storey_stiffnesses = [6e8, 5e8]
base_mass = 350e3

[building.damping]
kind = "rayleigh"
ratios = [0.02, 0.02]
modes = [1, 2]

[bearing]
count = 4
effective_radius = 3.0
slider_diameter = 0.3
yield_displacement = 0.0005
displacement_capacity = 0.5

[friction]
model = "simplified"
mu_t0 = 0.075
refinement = 0.5
design_velocity = 0.4

[analysis]
integrator = "newmark"
dt = 0.01

[plan]
bearing_coordinates = [[-6.0, -4.0], [6.0, -4.0], [-6.0, 4.0], [6.0, 4.0]]
eccentricity = [0.6, 0.4]
dimensions = [12.0, 8.0]
storey_heights = 3.5
"""


def _write_record(motion: GroundMotion, path: Path) -> Path:
    """A record file of one value a line in g (read back by ``read_record``)."""
    g = motion.acceleration / STANDARD_GRAVITY
    header = [f"synthetic test record {path.stem}", "one value a line", "UNITS OF G",
              f"NPTS= {g.size}, DT= {motion.dt:.5f} SEC"]
    path.write_text("\n".join(header + [f"{v:.7e}" for v in g]) + "\n")
    return path


def _pair(seed: int, dt: float = 0.01):
    return synthetic_pair("kanai-tajimi", seed, duration=1.5, dt=dt, target_pga=2.0,
                          ground_frequency=15.0, ground_damping=0.6)


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    """The building file, two synthetic pairs and their manifest (``good.csv``), and a
    manifest with a missing component and a pair of two time steps beside one good pair
    (``broken.csv``)."""
    folder = tmp_path_factory.mktemp("pairs")
    (folder / "building.toml").write_text(BUILDING)
    for seed in (1, 3):
        pair = _pair(seed)
        _write_record(pair.x, folder / f"s{seed}-x.AT2")
        _write_record(pair.y, folder / f"s{seed}-y.AT2")
    _write_record(_pair(5, dt=0.02).y, folder / "coarse-y.AT2")
    (folder / "good.csv").write_text("name,x,y\ns1,s1-x.AT2,s1-y.AT2\ns3,s3-x.AT2,s3-y.AT2\n")
    (folder / "broken.csv").write_text("name,x,y\n# a comment\ns1,s1-x.AT2,s1-y.AT2\n"
                                       "missing,gone-x.AT2,s1-y.AT2\n"
                                       "two-steps,s3-x.AT2,coarse-y.AT2\n")
    return folder


@pytest.fixture(scope="module")
def config(files):
    return load_config(files / "building.toml")


@pytest.fixture(scope="module")
def scheduler():
    with local_cluster(2) as cluster:
        yield cluster.scheduler_address


@pytest.fixture(scope="module")
def good_suite(files, config, scheduler, tmp_path_factory):
    """The two synthetic pairs at 1.5 times, simplified model, run on the cluster."""
    suite = Suite(config, pair_sources(files / "good.csv"), models=("simplified",),
                  scales=(1.5,))
    out = tmp_path_factory.mktemp("good") / "out"
    return run_suite(suite, out, scheduler_address=scheduler, progress=False)


def test_a_row_is_the_peaks_of_structures_run(files, config, good_suite):
    result = good_suite
    assert (result.computed, result.skipped, result.failures) == (2, 0, [])
    keys = set(peaks(structures.run(config, _pair(1), model="constant", dt=0.01)))
    assert keys - {"failed_at", "failure"} <= set(result.peaks.columns)
    for row in result.peaks.to_dict("records"):
        pair = read_pair(files / row["x_file"], files / row["y_file"], name=row["pair"])
        single = peaks(structures.run(config, pair, model="simplified", dt=0.01, scale=1.5))
        assert {k: row[k] for k in PHYSICS} == {k: single[k] for k in PHYSICS}, row["run_id"]
        assert (row["scale"], row["dt"], row["status"]) == (1.5, 0.01, "done")
    import xarray as xr

    row = result.peaks.iloc[0]
    with xr.open_dataset(result.out_dir / "runs" / f"{row['run_id']}.nc") as ds:
        reach = np.hypot(ds["bearing_displacement"].values[..., 0],
                         ds["bearing_displacement"].values[..., 1]).max()
        assert reach == row["peak_isolator_displacement"] and ds.attrs["pair"] == "s1"
    summary = result.summary.set_index("quantity")
    assert set(summary.index) >= {"peak_isolator_displacement", "peak_roof_acceleration_x",
                                  "peak_roof_acceleration_y", "peak_base_shear"}
    corner = summary.loc["peak_isolator_displacement"]
    values = result.peaks["peak_isolator_displacement"]
    assert (corner["n"], corner["median"]) == (2, float(np.median(values)))
    assert corner["p84"] == pytest.approx(np.percentile(values, 84.0))


def test_broken_pairs_fail_with_their_reason_and_a_rerun_resumes(files, config, scheduler,
                                                                 tmp_path):
    suite = Suite(config, pair_sources(files / "broken.csv"), models=("simplified",))
    out = tmp_path / "out"
    result = run_suite(suite, out, scheduler_address=scheduler, progress=False)
    status = dict(zip(result.peaks["pair"], result.peaks["status"], strict=True))
    assert status == {"s1": "done", "missing": "failed", "two-steps": "failed"}
    reasons = {f["run"].split("_x")[0]: f["reason"] for f in result.failures}
    assert reasons["missing"].startswith("InputError: Pair 'missing': the x component file")
    assert "gone-x.AT2' does not exist" in reasons["missing"]
    assert "two-steps" in reasons["two-steps"] and "one time step" in reasons["two-steps"]
    assert json.loads((out / "failures.json").read_text()) == result.failures

    again = run_suite(suite, out, scheduler_address=scheduler, write="client",
                      progress=False)  # read here this time: the bad ones fail here
    assert (again.skipped, again.computed, len(again.failures)) == (1, 0, 2)
    assert [f["reason"] for f in again.failures] == [f["reason"] for f in result.failures]
    events = RunStore(out).events()
    assert [e for e, _ in events].count("done") == 1  # the finished run was not run again
    assert [e for e, _ in events].count("failed") == 4  # the failures were retried
    pd.testing.assert_frame_equal(again.peaks[["run_id", "status", *PHYSICS]],
                                  result.peaks[["run_id", "status", *PHYSICS]])


def test_target_factors_are_those_of_scale_suite(files, config):
    spectrum = asce7_design_spectrum(1.0, 0.6, 8.0)
    periods, sa_g = np.asarray(spectrum.periods)[1:], np.asarray(spectrum.sa)[1:] / STANDARD_GRAVITY
    suite = Suite(config, pair_sources(files / "broken.csv"), models=("constant",),
                  scales=(1.0, 2.0), factors=target_hook(periods, sa_g, (0.8, 2.0)))
    specs, pairs, unreadable = suite.runs(read=False)  # the hook reads the pairs
    pairs = {source.name: pair for source, pair in pairs.items()}
    assert set(pairs) == {"s1"} and {s.name for s in unreadable} == {"missing", "two-steps"}
    target = (periods, sa_g * STANDARD_GRAVITY)  # as the hook makes it
    expected = scale_suite([pairs["s1"]], target, (0.8, 2.0)).scale_factors[0]
    factors = {(s.motion.name, s.multiplier): (s.record_factor, s.scale) for s in specs}
    assert factors[("s1", 1.0)] == (expected, expected)
    assert factors[("s1", 2.0)] == (expected, 2.0 * expected)
    assert factors[("missing", 1.0)][0] == 1.0  # its runs fail with the reason


def test_run_timeout_and_max_steps_reach_a_run(files, config, tmp_path):
    # the compiled engine looks at the clock every CHUNK_STEPS (1024) steps: a pair of 12 s
    long_pair = synthetic_pair("kanai-tajimi", 7, duration=12.0, dt=0.01, target_pga=2.0,
                               ground_frequency=15.0, ground_damping=0.6)
    _write_record(long_pair.x, tmp_path / "long-x.AT2")
    _write_record(long_pair.y, tmp_path / "long-y.AT2")
    (tmp_path / "long.csv").write_text("name,x,y\nlong,long-x.AT2,long-y.AT2\n")
    suite = Suite(config, pair_sources(tmp_path / "long.csv"), models=("simplified",))
    row, data = execute_run(suite.runs(read=False)[0][0], None, config, time_limit=1e-3)
    assert data is None and row["failure"] == "timeout"
    assert row["reason"].startswith("timeout after 0.001 s: the run was stopped at t = ")
    assert row["reason"].endswith(" s of the pair (its peaks are those up to then)")
    suite = Suite(config, pair_sources(files / "good.csv"), models=("simplified",))
    spec = suite.runs(read=False)[0][0]
    row, data = execute_run(spec, None, config, max_steps=50)
    assert data is None and row["status"] == "failed" and "150 steps" in row["reason"]


def test_errors_before_any_work(files, config, tmp_path):
    one_direction = load_config(REPO / "examples" / "five_storey.toml")
    with pytest.raises(InputError, match=r"no \[plan\] table"):
        Suite(one_direction, pair_sources(files / "good.csv"))
    with pytest.raises(InputError, match="all records or all pairs"):
        Suite(config, [*pair_sources(files / "good.csv"), REPO / "examples" / "x.AT2"])
    bad = tmp_path / "bad.csv"
    bad.write_text("name,x,horizontal\na,b,c\n")
    with pytest.raises(InputError, match=r"bad\.csv, line 1: the header"):
        pair_sources(bad)
    bad.write_text("name,x,y\na,b,c\na,d,e\n")
    with pytest.raises(InputError, match="already named on line 2"):
        pair_sources(bad)
    with pytest.raises(InputError, match="does not exist"):
        pair_sources(tmp_path / "nowhere.csv")
    with pytest.raises(ValueError, match="more than once"):
        Suite(config, pair_sources(files / "good.csv"), scales=(1.0, 1.0)).runs()
    good = pair_sources(files / "good.csv")
    with pytest.raises(InputError, match="pair names must differ"):
        Suite(config, [good[0], dataclasses.replace(good[1], name=good[0].name)])


def test_cli_pairs_resumes_the_suite_with_tables_and_plots(files, good_suite, scheduler,
                                                           capsys, tmp_path):
    result = good_suite
    out = tmp_path / "out"
    shutil.copytree(result.out_dir, out)
    code = cli.main(["suite", str(files / "building.toml"), "--pairs", str(files / "good.csv"),
                     "--models", "simplified", "--scales", "1.5", "--scheduler", scheduler,
                     "--out", str(out), "--no-progress", "--json"])
    report = json.loads(capsys.readouterr().out)
    assert code == 0
    assert (report["runs"], report["done"], report["computed"], report["skipped"]) == (
        2, 2, 0, 2)
    corner = report["summary"]["simplified"]["peak_isolator_displacement"]
    assert corner["median"] == float(np.median(result.peaks["peak_isolator_displacement"]))
    assert "peak_roof_acceleration_y" in report["summary"]["simplified"]
    table = pd.read_csv(out / "peaks.csv")
    assert list(table["run_id"]) == list(result.peaks["run_id"])
    assert (out / "plots" / "peak_distributions.png").stat().st_size > 0
    assert {p.name for p in out.iterdir()} >= {"summary.csv", "summary.parquet",
                                               "failures.json", "suite.log"}


def test_cli_pairs_scaled_to_a_target_on_rotd100(files, scheduler, capsys, tmp_path):
    out = tmp_path / "out"
    code = cli.main(["suite", str(files / "building.toml"), "--pairs", str(files / "good.csv"),
                     "--models", "constant", "--target", "asce7:0.3,0.2,8", "--period-range",
                     "0.8,2", "--scheduler", scheduler, "--out", str(out), "--no-progress",
                     "--json"])
    assert code == 0 and json.loads(capsys.readouterr().out)["done"] == 2
    spectrum = asce7_design_spectrum(0.3, 0.2, 8.0)
    target = (spectrum.periods, spectrum.sa / STANDARD_GRAVITY * STANDARD_GRAVITY)
    pairs = [read_pair(files / f"s{seed}-x.AT2", files / f"s{seed}-y.AT2", name=f"s{seed}")
             for seed in (1, 3)]
    expected = scale_suite(pairs, target, (0.8, 2.0)).scale_factors
    table = pd.read_csv(out / "peaks.csv").set_index("pair")
    assert table.loc[["s1", "s3"], "record_factor"].tolist() == pytest.approx(expected,
                                                                              rel=1e-15)
    assert (out / "plots" / "scaled_spectra.png").stat().st_size > 0


def test_cli_refuses_pairs_on_a_building_file_in_one_direction(files, capsys, tmp_path):
    one_direction = REPO / "examples" / "five_storey.toml"
    code = cli.main(["suite", str(one_direction), "--pairs", str(files / "good.csv"),
                     "--out", str(tmp_path / "out"), "--no-progress"])
    error = capsys.readouterr().err
    assert code == 2 and "--pairs" in error and str(one_direction) in error
    assert "no [plan] table" in error
    assert not (tmp_path / "out").exists()
    with pytest.raises(SystemExit) as both:
        cli.main(["suite", str(one_direction), "--pairs", "a.csv", "--records", "b"])
    assert both.value.code == 2 and "not allowed with" in capsys.readouterr().err


def test_cli_records_on_a_plan_file_warn_that_they_run_in_one_direction(files, scheduler, capsys,
                                                              tmp_path):
    records = tmp_path / "records"
    records.mkdir()
    shutil.copy(files / "s1-x.AT2", records / "s1-x.AT2")
    with pytest.warns(InputWarning, match="--pairs"):
        code = cli.main(["suite", str(files / "building.toml"), "--records", str(records),
                         "--models", "constant", "--scheduler", scheduler,
                         "--out", str(tmp_path / "out"), "--no-progress", "--json"])
    assert code == 0 and json.loads(capsys.readouterr().out)["done"] == 1


def test_a_recorded_pair_equals_its_single_run(config, shared_dir, scheduler, tmp_path):
    folder = shared_dir / "groundmotions" / "pairs"
    manifest = tmp_path / "chichi.csv"
    manifest.write_text(f"name,x,y\nTAP094,{folder / 'TAP094-E.AT2'},"
                        f"{folder / 'TAP094-N.AT2'}\n")
    suite = Suite(config, pair_sources(manifest), models=("simplified",), scales=(8.0,),
                  duration=1.5)
    result = run_suite(suite, tmp_path / "out", scheduler_address=scheduler, progress=False)
    row = result.peaks.iloc[0]
    pair = read_pair(folder / "TAP094-E.AT2", folder / "TAP094-N.AT2").truncated(1.5)
    single = peaks(structures.run(config, pair, model="simplified", dt=0.005, scale=8.0))
    assert row["status"] == "done" and row["dt"] == 0.005  # the record's step, finer
    assert {k: row[k] for k in PHYSICS} == {k: single[k] for k in PHYSICS}
