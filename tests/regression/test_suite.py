"""Ground-motion suites through Dask: same answers as single runs, resumable, failures reported.

- (a) a suite on a 2-worker loopback LocalCluster gives exactly the peaks of single runs of
  the same records (bundled El Centro at several scales; three ../shared records with three
  different time steps);
- (b) a suite killed part-way (the whole process group, SIGKILL) and run again keeps every
  finished result (same inode and mtime), computes none twice (one "done" line per run in
  suite.log) and ends with the table of an uninterrupted suite;
- (c) a bad, a missing record file and a run failing inside a worker are reported with their
  reasons while the others finish; failures are retried on rerun;
- the ``dcfpb suite`` command (JSON, summary CSV/Parquet, plots, --target through a stand-in
  of ``groundmotions.scaling``).

Records are truncated and the steps coarse: the physics is checked elsewhere.
"""

from __future__ import annotations

import dataclasses
import json
import os
import shutil
import signal
import subprocess
import sys
import textwrap
import time
import types
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from dcfpb import cli
from groundmotions import scaling
from groundmotions.readers import read_record
from structures.analysis import peaks, run
from structures.config import load_config
from structures.suites.runs import PEAK_COLUMNS, RunSpec, execute_run
from structures.suites.sources import MotionSource, file_digest, motion_sources
from structures.suites.store import RunStore
from structures.suites.suite import Suite, run_suite
from structures.suites.summary import summarize
from structures.suites.tasks import local_cluster

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
ELCENTRO = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"
PHYSICS = [c for c in PEAK_COLUMNS["record"] if c != "wall_time"]
SAME = ["run_id", "record", "scale", "model", "modifier", "dt", "status", *PHYSICS]


@pytest.fixture(scope="module")
def config():
    return load_config(EXAMPLE)


@pytest.fixture(scope="module")
def scheduler():
    """One 2-worker loopback cluster shared by the tests (the ``scheduler_address`` path)."""
    with local_cluster(2) as cluster:
        yield cluster.scheduler_address


def _single(config, spec: RunSpec) -> dict:
    """The peaks of a plain single run of what ``spec`` describes."""
    motion = read_record(spec.motion.files[0])
    if spec.duration is not None:
        motion = motion.truncated(min(spec.duration, motion.duration))
    result = run(config.building, config.bearing(spec.model), motion.scaled(spec.scale),
                 config.integrator, n_bearings=config.n_bearings,
                 dt=min(spec.dt, motion.dt))
    return peaks(result)


def _assert_equals_single_runs(config, suite, result):
    specs, _, _ = suite.runs()
    assert list(result.peaks["run_id"]) == [s.run_id for s in specs]
    assert (result.peaks["status"] == "done").all(), result.failures
    for spec, row in zip(specs, result.peaks.to_dict("records"), strict=True):
        single = _single(config, spec)
        assert {k: row[k] for k in PHYSICS} == {k: single[k] for k in PHYSICS}, spec.run_id


def test_elcentro_suite_on_the_default_local_cluster(config, tmp_path, monkeypatch):
    import distributed

    made = []

    class Spy(distributed.LocalCluster):
        def __init__(self, **kwargs):
            made.append(kwargs)
            super().__init__(**kwargs)
            made.append(self.scheduler_address)

    monkeypatch.setattr(distributed, "LocalCluster", Spy)
    suite = Suite(config, [ELCENTRO], models=("constant", "simplified"),
                  scales=(0.5, 1.0, 2.0), duration=8.0, dt=0.01)
    result = run_suite(suite, tmp_path, n_workers=2, progress=False)
    assert made[0] == {"n_workers": 2, "threads_per_worker": 1, "processes": True,
                       "host": "127.0.0.1", "dashboard_address": None,
                       "scheduler_kwargs": {"dashboard_address": "127.0.0.1:0"}}
    assert made[1].startswith("tcp://127.0.0.1:")
    assert (result.computed, result.skipped, result.failures) == (6, 0, [])
    _assert_equals_single_runs(config, suite, result)
    import xarray as xr

    row = result.peaks.iloc[-1]
    with xr.open_dataset(tmp_path / "runs" / f"{row['run_id']}.nc") as ds:
        assert float(abs(ds["bearing_displacement"]).max()) == row["peak_isolator_displacement"]
        assert ds.attrs["run_id"] == row["run_id"] and ds.attrs["scale"] == 2.0
    summary = pd.read_parquet(tmp_path / "summary.parquet")
    pd.testing.assert_frame_equal(summary, pd.read_csv(tmp_path / "summary.csv"))


def test_shared_records_suite_equals_single_runs(config, shared_dir, scheduler, tmp_path):
    folder = shared_dir / "groundmotions"
    names = ("A-BEN360.AT2", "A-ELC180.AT2", "GCN-WE.AT2")  # dt = 5, 10 and 2.44 ms
    files = [folder / name for name in names]
    suite = Suite(config, files, models=("precise", "constant"), scales=(3.0,), duration=6.0,
                  dt=0.005)
    result = run_suite(suite, tmp_path, scheduler_address=scheduler, progress=False)
    _assert_equals_single_runs(config, suite, result)
    assert sorted(set(result.peaks["dt"])) == [0.00244, 0.005]


KILLED_SUITE = """
import sys
from structures.config import load_config
from structures.suites.suite import Suite, run_suite
if __name__ == "__main__":
    suite = Suite(load_config(sys.argv[1]), [sys.argv[2]], models=("constant", "simplified"),
                  scales=tuple(0.5 + 0.25 * k for k in range(8)), duration=12.0, dt=0.005)
    run_suite(suite, sys.argv[3], n_workers=2, progress=False)
"""


def test_killed_suite_resumes_without_recomputing(config, scheduler, tmp_path):
    script, out = tmp_path / "suite.py", tmp_path / "out"
    script.write_text(textwrap.dedent(KILLED_SUITE))
    env = os.environ | {"PYTHONPATH": os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH",
                                                                                  "")])}
    suite = Suite(config, [ELCENTRO], models=("constant", "simplified"),
                  scales=tuple(0.5 + 0.25 * k for k in range(8)), duration=12.0, dt=0.005)
    specs, _, _ = suite.runs()
    store = RunStore(out)
    proc = subprocess.Popen([sys.executable, str(script), str(EXAMPLE), str(ELCENTRO), str(out)],
                            env=env, start_new_session=True)
    deadline = time.monotonic() + 60
    try:
        while sum(store.row_path(s.run_id).exists() for s in specs) < 4:
            assert proc.poll() is None, "the suite ended before it could be killed"
            assert time.monotonic() < deadline
            time.sleep(0.01)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the client, its scheduler and its workers
        proc.wait()
    finished = {s.run_id for s in specs if store.completed_row(s.run_id) is not None}
    assert 4 <= len(finished) < len(specs)
    stamp = {rid: [(p.stat().st_ino, p.stat().st_mtime_ns)
                   for p in (store.result_path(rid), store.row_path(rid))] for rid in finished}
    (store.runs / ".stray.nc.1.abcd.tmp").write_bytes(b"half a file")
    assert (out / ".suite.lock").exists()  # the killed suite's lock, stale now

    with pytest.warns(UserWarning, match="took over the lock of a suite that no longer runs"):
        result = run_suite(suite, out, scheduler_address=scheduler, progress=False)
    assert not (out / ".suite.lock").exists()
    assert (result.skipped, result.computed) == (len(finished), len(specs) - len(finished))
    for rid, before in stamp.items():  # kept, never rewritten
        assert [(p.stat().st_ino, p.stat().st_mtime_ns)
                for p in (store.result_path(rid), store.row_path(rid))] == before
    done = [rid for event, rid in store.events() if event == "done"]
    assert sorted(done) == sorted(s.run_id for s in specs)  # each computed exactly once
    assert not list(store.runs.glob(".*.tmp"))
    whole = run_suite(suite, tmp_path / "whole", scheduler_address=scheduler, progress=False)
    pd.testing.assert_frame_equal(result.peaks[SAME], whole.peaks[SAME])


def test_a_run_killed_between_its_row_and_its_log_line_is_logged_once(config, scheduler,
                                                                        tmp_path):
    """The window (b) can hit: the row is written, the ``done`` line not yet. The next suite
    keeps the run and logs it then (``recovered``), so the log still has one line per run."""
    suite = Suite(config, [ELCENTRO], models=("constant",), scales=(0.5, 1.0), duration=4.0,
                  dt=0.02)
    out = tmp_path / "out"
    first = run_suite(suite, out, scheduler_address=scheduler, progress=False)
    store = RunStore(out)
    lines = store.log_path.read_text().splitlines(keepends=True)
    lost = lines[-1].split(" ")[2]
    store.log_path.write_text("".join(lines[:-1]))  # as if killed before the last line
    stamp = store.row_path(lost).stat().st_mtime_ns

    again = run_suite(suite, out, scheduler_address=scheduler, progress=False)
    assert (again.skipped, again.computed) == (first.computed, 0)
    assert store.row_path(lost).stat().st_mtime_ns == stamp
    done = [rid for event, rid in store.events() if event == "done"]
    assert sorted(done) == sorted(first.peaks["run_id"])
    assert store.log_path.read_text().splitlines()[-1].endswith(f"done {lost} recovered=true")
    assert store.log_recovered(done) == []  # logged once, never again


def _bad_set(tmp_path: Path) -> Path:
    shutil.copy(ELCENTRO, tmp_path / "elcentro.at2")
    (tmp_path / "broken.AT2").write_text("PEER\nEVENT\nUNITS OF G\nNPTS=  5, DT= .0100 SEC\n"
                                         "  .1  .2  .3\n")
    manifest = tmp_path / "set.csv"
    manifest.write_text("file,note\nelcentro.at2,good\nbroken.AT2,3 values for 5\n"
                        "missing.AT2,not there\n")
    return manifest


def test_bad_records_are_reported_and_the_others_finish(config, scheduler, tmp_path):
    suite = Suite(config, motion_sources(_bad_set(tmp_path)), models=("constant",),
                  scales=(1.0, 2.0), duration=4.0, dt=0.02)
    out = tmp_path / "out"
    result = run_suite(suite, out, scheduler_address=scheduler, write="client", progress=False)
    status = result.peaks.groupby("record")["status"].agg(set).to_dict()
    assert status == {"elcentro": {"done"}, "broken": {"failed"}, "missing": {"failed"}}
    reasons = {f["run"].split("_x")[0]: f["reason"] for f in result.failures}
    assert reasons["broken"].startswith("RecordFormatError: broken.AT2, line")
    assert reasons["missing"].startswith("FileNotFoundError")
    assert json.loads((out / "failures.json").read_text()) == result.failures
    failed = [f["run"] for f in result.failures]
    assert all(RunStore(out).failed_row(rid)["reason"] for rid in failed)
    again = run_suite(suite, out, scheduler_address=scheduler, progress=False)
    assert (again.skipped, len(again.failures)) == (2, 4)
    events = RunStore(out).events()
    assert sorted(rid for e, rid in events if e == "failed") == sorted(failed * 2)  # retried
    assert len([e for e, _ in events if e == "done"]) == 2  # not recomputed


def test_failures_inside_a_worker_are_rows_with_their_reason(config, monkeypatch):
    motion = read_record(ELCENTRO).truncated(2.0)
    source = MotionSource.record(ELCENTRO)
    spec = RunSpec(source, source.digests(), "constant", modifier=30.0, dt=0.02)
    row, data = execute_run(spec, motion, config)  # mu0 = 30 x 0.041 > 1
    assert data is None and row["status"] == "failed" and "'mu0'" in row["reason"]

    import structures.analysis as analysis

    real_run = analysis.run

    def stopping(*args, **kwargs):
        result = real_run(*args, **kwargs)
        result.attrs.update(success=0, message="Newton did not converge at step 7")
        return result

    monkeypatch.setattr(analysis, "run", stopping)
    row, data = execute_run(RunSpec(source, ("x",), "constant", dt=0.02), motion, config)
    assert data is None and row["reason"].endswith("Newton did not converge at step 7")
    assert row["steps"] == 100  # the peaks of the part that ran are kept


def test_a_run_past_max_steps_fails_with_its_step_count(config):
    """The suite's --max-steps reaches each run: refused before anything is allocated."""
    motion = read_record(ELCENTRO).truncated(2.0)
    source = MotionSource.record(ELCENTRO)
    spec = RunSpec(source, source.digests(), "constant", dt=0.02)
    row, data = execute_run(spec, motion, config, max_steps=50)  # 2 s at 0.02 s: 100 steps
    assert data is None and row["status"] == "failed"
    assert "100 steps" in row["reason"] and "limit of 50 steps" in row["reason"]
    row, data = execute_run(spec, motion, config, max_steps=100)
    assert data is not None and row["status"] == "done"


def test_errors_before_any_work(config, tmp_path):
    with pytest.raises(ValueError, match="'mu_t0'"):
        Suite(config, [ELCENTRO], models=("precise",), property_modifiers=(20.0,))
    with pytest.raises(ValueError, match="'models'"):
        Suite(config, [ELCENTRO], models=("exact",))
    with pytest.raises(ValueError, match="more than once"):
        Suite(config, [ELCENTRO], models=("constant",), scales=(1.0, 1.0)).runs()
    with pytest.raises(ValueError, match="no such folder"):
        motion_sources(tmp_path / "nowhere")
    with pytest.raises(ValueError, match="at least one"):
        Suite(config, [])


def test_run_ids_are_stable_and_say_what_changed(config, tmp_path):
    moved = tmp_path / ELCENTRO.name
    shutil.copy(ELCENTRO, moved)
    spec = RunSpec(MotionSource.record(ELCENTRO), (file_digest(ELCENTRO),), "precise", 1.5,
                   2.0, 1.2)
    assert spec.run_id.startswith("elcentro_1940_ns_x3_precise_m1.2-")
    assert RunSpec(MotionSource.record(moved), (file_digest(moved),), "precise", 1.5, 2.0,
                   1.2).run_id == spec.run_id
    changed = [dataclasses.replace(spec, **{k: v}) for k, v in
               [("digests", ("0",)), ("multiplier", 2.0000001), ("model", "constant"),
                ("modifier", 1.1), ("duration", 5.0), ("dt", 0.01), ("settings", "x")]]
    assert len({spec.run_id, *(s.run_id for s in changed)}) == 8


def test_summary_statistics():
    table = pd.DataFrame({"model": ["a"] * 5 + ["b"], "modifier": 1.0, "multiplier": 1.0,
                          "status": ["done"] * 4 + ["failed", "done"],
                          "peak_isolator_displacement": [1.0, 2.0, 3.0, 10.0, 99.0, 7.0],
                          "peak_base_shear": 1.0, "peak_roof_acceleration": 2.0,
                          "peak_storey_drift": 3.0})
    s = summarize(table).set_index(["model", "quantity"])
    row = s.loc[("a", "peak_isolator_displacement")]
    assert (row["n"], row["mean"], row["median"]) == (4, 4.0, 2.5)
    assert row["p84"] == pytest.approx(np.percentile([1, 2, 3, 10], 84))
    assert s.loc[("b", "peak_storey_drift"), "p84"] == 3.0


def _suite_command(monkeypatch, *args: str) -> int:
    return cli.main(["suite", str(EXAMPLE), "--models", "constant", "--duration", "4",
                     "--dt", "0.02", "--no-progress", *args])


def test_cli_suite_json_summary_and_plots(monkeypatch, capsys, scheduler, tmp_path):
    shutil.copy(ELCENTRO, tmp_path / "elcentro.at2")
    out = tmp_path / "out"
    assert _suite_command(monkeypatch, "--records", str(tmp_path), "--scales", "1,2",
                          "--scheduler", scheduler, "--out", str(out), "--json") == 0
    report = json.loads(capsys.readouterr().out)
    assert (report["runs"], report["done"], report["failed"]) == (2, 2, [])
    assert report["wall_time"] > 0
    assert set(report["summary"]) == {"constant, scale x1", "constant, scale x2"}
    assert {p.name for p in out.iterdir()} >= {"peaks.csv", "summary.csv", "summary.parquet",
                                               "failures.json", "suite.log", "plots"}
    assert (out / "plots" / "peak_distributions.png").stat().st_size > 0


def test_cli_suite_storage_peaks_keeps_no_histories(monkeypatch, capsys, scheduler, tmp_path):
    """--storage peaks: the same peaks as full storage, no netCDF, the peak temperature in the
    summary."""
    shutil.copy(ELCENTRO, tmp_path / "elcentro.at2")
    tables = {}
    for storage in ("full", "peaks"):
        out = tmp_path / storage
        assert _suite_command(monkeypatch, "--records", str(tmp_path), "--scheduler", scheduler,
                              "--out", str(out), "--storage", storage, "--no-plots") == 0
        tables[storage] = pd.read_csv(out / "peaks.csv")
        summary = pd.read_csv(out / "summary.csv")
        assert "max_temperature" in set(summary["quantity"])
        assert bool(list(out.rglob("*.nc"))) == (storage == "full")
    capsys.readouterr()
    columns = ["peak_isolator_displacement", "peak_base_shear", "max_temperature"]
    pd.testing.assert_frame_equal(tables["full"][columns], tables["peaks"][columns])


@pytest.mark.parametrize(("args", "message"), [
    (["--period-range", "1,2"], "--target only"),
    (["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "not both"),
    (["--models", "exact"], "--models"),
    (["--scales", "1,x"], "--scales"),
])
def test_cli_suite_errors_are_clear(args, message, monkeypatch, capsys, tmp_path):
    assert _suite_command(monkeypatch, "--records", str(ELCENTRO.parent), "--out",
                          str(tmp_path / "out"), *args) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_cli_target_needs_the_scaling_module(monkeypatch, capsys, tmp_path):
    target = tmp_path / "target.csv"
    target.write_text("period,sa\n0.1,1.0\n6.0,0.2\n")
    monkeypatch.setitem(sys.modules, "groundmotions.scaling", None)  # import fails
    assert _suite_command(monkeypatch, "--records", str(ELCENTRO.parent), "--target",
                          str(target), "--out", str(tmp_path / "out")) == 2
    assert "scale_suite" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_cli_target_scales_through_the_hook(monkeypatch, capsys, scheduler, tmp_path):
    seen = {}

    def scale_suite(motions, target, period_range):
        seen.update(names=[m.name for m in motions], target=target, period_range=period_range)
        return types.SimpleNamespace(scale_factors={m.name: 1.5 for m in motions})

    monkeypatch.setattr(scaling, "scale_suite", scale_suite)  # the plots use the rest
    target = tmp_path / "target.csv"
    target.write_text("period,sa\n0.1,1.0\n6.0,0.2\n")
    out = tmp_path / "out"
    assert _suite_command(monkeypatch, "--records", str(_bad_set(tmp_path)), "--target",
                          str(target), "--period-range", "2,5", "--scales", "2",
                          "--scheduler", scheduler, "--out", str(out), "--json") == 1
    report = json.loads(capsys.readouterr().out)
    assert seen["names"] == ["elcentro"] and seen["period_range"] == (2.0, 5.0)
    assert seen["target"][1].tolist() == pytest.approx([9.80665, 0.2 * 9.80665])
    table = pd.read_csv(out / "peaks.csv").set_index("record")
    assert table.loc["elcentro", ["record_factor", "scale"]].tolist() == [1.5, 3.0]
    assert report["done"] == 1 and len(report["failed"]) == 2
    assert (out / "plots" / "scaled_spectra.png").stat().st_size > 0
