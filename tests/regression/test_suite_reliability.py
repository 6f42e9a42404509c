"""Suites that keep their results through lost workers, a busy folder and runs that run long
(issue 12, point 5).

- a worker process killed in the middle of its batch (SIGKILL, found through the rows it
  stored): Dask redoes the batch on another worker, the runs it had stored are kept as they
  were (same inode and mtime, no second "done" in the log), the others are computed there,
  and every run ends with exactly one stored result;
- two suites into one ``--out``: the second refuses at once (exit status 2, naming the folder
  and the first one's pid) while the first finishes intact, and the lock is gone after it;
- ``--run-timeout``: the run past it is recorded as failed ("timeout after N s") and the
  others finish; the statistics say how many runs failed, and of what, beside the numbers.

The records are built here from the bundled El Centro (finer steps and repeats, so that a run
lasts long enough to be caught); every wait is a poll with a generous deadline.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from dcfpb import cli
from groundmotions.bundled import load_bundled
from structures.config import load_config
from structures.suites.store import RunStore
from structures.suites.suite import Suite, run_suite
from structures.suites.tasks import BATCH_SIZE, batches, local_cluster

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
DEADLINE = 90.0  # [s] for anything awaited; the tests take a few seconds each


@pytest.fixture(scope="module")
def config():
    return load_config(EXAMPLE)


def _write_record(path: Path, acceleration_g: np.ndarray, dt: float) -> Path:
    """A record file in the bundled El Centro's format (8F10.5, units of g)."""
    values = np.round(np.asarray(acceleration_g, dtype=float), 5)
    padded = np.concatenate([values, np.full(-values.size % 8, np.nan)]).reshape(-1, 8)
    rows = ["".join(f"{v:10.5f}" for v in row if np.isfinite(v)) for row in padded]
    header = [f"Test record made from El Centro 1940 N-S ({path.stem})",
              f"{values.size} points at equal spacing of {dt:g} sec, 8F10.5",
              "The units are (g)", f"NPTS= {values.size:6d}, DT= {dt:.5f} SEC"]
    path.write_text("\n".join(header + rows) + "\n")
    return path


def _elcentro(path: Path, *, dt: float, repeats: int = 1, duration: float | None = None) -> Path:
    """El Centro interpolated to ``dt`` [s], ``repeats`` times in a row (or its first
    ``duration`` seconds)."""
    motion = load_bundled("elcentro")
    if duration is not None:
        motion = motion.truncated(duration)
    t = np.arange(0.0, motion.duration + 1e-9, dt)
    g = np.interp(t, motion.time, motion.acceleration) / 9.80665
    return _write_record(path, np.tile(g, repeats), dt)


def _events(out: Path) -> dict[str, int]:
    done: dict[str, int] = {}
    for event, run_id in RunStore(out).events():
        if event == "done":
            done[run_id] = done.get(run_id, 0) + 1
    return done


def _stamps(store: RunStore, run_id: str) -> list[tuple[int, int]]:
    return [(p.stat().st_ino, p.stat().st_mtime_ns)
            for p in (store.result_path(run_id), store.row_path(run_id))]


def _kill_mid_batch(store: RunStore, plan: list, state: dict) -> None:
    """Kill the worker of a batch with at least one run stored and two still to come, once;
    note what was stored at that moment."""
    import psutil

    deadline = time.monotonic() + DEADLINE
    while time.monotonic() < deadline and "pid" not in state:
        for batch in plan:
            stored = [row for row in (store.completed_row(s.run_id) for s in batch) if row]
            if stored and len(stored) <= len(batch) - 2:
                pid = int(stored[0]["worker"].rsplit(":", 1)[1])
                os.kill(pid, signal.SIGKILL)
                with contextlib.suppress(psutil.NoSuchProcess):
                    psutil.Process(pid).wait(timeout=DEADLINE)
                finished = {s.run_id for b in plan for s in b
                            if store.completed_row(s.run_id) is not None}
                state.update(pid=pid, batch=[s.run_id for s in batch], finished=finished,
                             stamps={rid: _stamps(store, rid) for rid in finished})
                return
        time.sleep(0.002)


def test_a_killed_worker_has_its_runs_redone_and_nothing_finished_is_lost(config, tmp_path):
    record = _elcentro(tmp_path / "long.at2", dt=0.005, repeats=3)  # 18,700 steps a run
    suite = Suite(config, [record], models=("precise",),
                  scales=tuple(0.2 + 0.05 * k for k in range(2 * BATCH_SIZE)))
    specs, _, _ = suite.runs()
    out = tmp_path / "out"
    store = RunStore(out)
    plan = batches(specs, BATCH_SIZE)  # the batches run_suite hands to the workers
    assert len(plan) == 2
    state: dict = {}
    killer = threading.Thread(target=_kill_mid_batch, args=(store, plan, state), daemon=True)
    with local_cluster(2) as cluster:
        killer.start()
        result = run_suite(suite, out, scheduler_address=cluster.scheduler_address,
                           progress=False)
        killer.join(timeout=DEADLINE)
    assert "pid" in state, "no worker was caught in the middle of its batch"
    # the suite completed: every run done, computed in this invocation
    assert result.failures == [] and (result.computed, result.skipped) == (len(specs), 0)
    assert (result.peaks["status"] == "done").all()
    # exactly one stored result per run, and no failure left
    assert sorted(p.stem for p in store.runs.glob("*.nc")) == sorted(s.run_id for s in specs)
    assert sorted(p.name for p in store.runs.glob("*.json")) == sorted(
        f"{s.run_id}.json" for s in specs)
    # nothing that had finished before the kill was lost or computed again
    assert 1 <= len(state["finished"]) < len(specs)
    for run_id, before in state["stamps"].items():
        assert _stamps(store, run_id) == before, run_id
    done = _events(out)
    assert all(count == 1 for count in done.values()), done
    assert {s.run_id for s in specs} - state["finished"] <= set(done)
    # the killed worker's runs still to come were computed by another worker
    rows = result.peaks.set_index("run_id")
    redone = [rid for rid in state["batch"] if rid not in state["finished"]]
    assert len(redone) >= 2
    assert all(not rows.loc[rid, "worker"].endswith(f":{state['pid']}") for rid in redone)
    kept = [rid for rid in state["batch"] if rid in state["finished"]]
    assert kept and all(rows.loc[rid, "worker"].endswith(f":{state['pid']}") for rid in kept)
    assert not (out / ".suite.lock").exists()


def _suite_argv(records: Path, out: Path, *extra: str) -> list[str]:
    return ["suite", str(EXAMPLE), "--records", str(records), "--models", "precise",
            "--no-progress", "--no-plots", "--out", str(out), *extra]


def test_a_second_suite_into_the_same_folder_refuses_while_the_first_finishes(tmp_path,
                                                                               capsys):
    records = tmp_path / "records"
    records.mkdir()
    _elcentro(records / "long.at2", dt=0.002, repeats=2)
    out = tmp_path / "out"
    env = os.environ | {"PYTHONPATH": os.pathsep.join([str(REPO),
                                                       os.environ.get("PYTHONPATH", "")])}
    argv = _suite_argv(records, out, "--scales", "0.5,1", "--json")
    first = subprocess.Popen([sys.executable, "-m", "dcfpb.cli", *argv, "--workers", "2"],
                             env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lock = out / ".suite.lock"
    try:
        deadline = time.monotonic() + DEADLINE
        holder = None
        while holder is None:  # the lock, written whole (its holder readable)
            assert first.poll() is None, first.communicate()
            assert time.monotonic() < deadline, "the first suite never took the lock"
            try:
                holder = json.loads(lock.read_text())
            except (OSError, ValueError):
                time.sleep(0.01)
        assert holder["pid"] == first.pid
        start = time.perf_counter()
        assert cli.main(argv) == 2  # while the first one runs
        assert time.perf_counter() - start < 5.0
        err = capsys.readouterr().err
        assert str(out) in err and f"pid {first.pid}" in err and holder["started"] in err
        assert first.poll() is None, "the first suite ended before the second was refused"
        stdout, stderr = first.communicate(timeout=DEADLINE)
    finally:
        if first.poll() is None:
            first.kill()
            first.wait()
    assert first.returncode == 0, stderr
    report = json.loads(stdout)
    assert (report["runs"], report["done"], report["failed"]) == (2, 2, [])
    assert all(count == 1 for count in _events(out).values()) and len(_events(out)) == 2
    assert not lock.exists()


@pytest.fixture(scope="module")
def scheduler():
    with local_cluster(2) as cluster:
        yield cluster.scheduler_address


def test_run_timeout_and_failures_beside_the_statistics(tmp_path, scheduler, capsys):
    """A long record (748,000 steps, about a second compiled, minutes on the reference
    engine) under a 0.3 s limit times out; a short one (400 steps: 0.06 s on the reference
    engine, and never looked at by the compiled engine, which looks at the clock every 1024
    steps) finishes; at 20 times El Centro both pass the bearings' capacity (the long one
    after 606 steps, 0.14 s on the reference engine). The limit leaves room for a machine
    several times slower than a quiet one on either engine. The summary counts each group's
    runs and failures by kind beside statistics over the successful runs, and says so."""
    records = tmp_path / "records"
    records.mkdir()
    _elcentro(records / "long.at2", dt=0.002, repeats=48)
    _elcentro(records / "short.at2", dt=0.02, duration=2.0)
    out = tmp_path / "out"
    argv = _suite_argv(records, out, "--scales", "1,20", "--run-timeout", "0.3",
                       "--scheduler", scheduler)
    assert cli.main([*argv, "--json"]) == 1
    report = json.loads(capsys.readouterr().out)
    assert (report["runs"], report["done"], report["n_failed"]) == (4, 1, 3)
    assert report["failures_by_kind"] == {"capacity": 2, "convergence": 0, "timeout": 1,
                                          "error": 0}
    reasons = {f["run"].split("_m1")[0]: f["reason"] for f in report["failed"]}
    assert reasons["long_x1_precise"].startswith("timeout after 0.3 s: the run was stopped")
    assert "Capacity exceeded" in reasons["long_x20_precise"]
    assert "Capacity exceeded" in reasons["short_x20_precise"]
    x1, x20 = (report["summary"][f"precise, scale x{s}"]["peak_base_shear"] for s in (1, 20))
    assert (x1["n"], x1["n_runs"], x1["n_failed"], x1["n_timeout"]) == (1, 2, 1, 1)
    assert x1["median"] > 0 and x1["over"] == "successful runs"
    assert (x20["n"], x20["n_runs"], x20["n_capacity"], x20["median"]) == (0, 2, 2, None)
    table = json.loads((out / "failures.json").read_text())
    assert len(table) == 3
    peaks = pd.read_csv(out / "peaks.csv").set_index("record")
    timed_out = peaks[peaks["failure"] == "timeout"]
    assert list(timed_out.index) == ["long"] and 0 < timed_out["failed_at"].iloc[0] < 1496.0

    assert cli.main(argv) == 1  # again, as text: the done run kept, the failed ones retried
    text = capsys.readouterr().out
    assert "4 runs: 1 done (1 kept from before), 3 failed (capacity 2, timeout 1)" in text
    assert "statistics over the successful runs" in text
    lines = {line.split()[2]: line for line in text.splitlines()
             if line.startswith("precise, scale") and " median " in line}
    assert lines["x1"].rstrip().endswith("1/2     1 (timeout 1)")
    assert lines["x20"].rstrip().endswith("0/2     2 (capacity 2)")
    assert "warning: 3 of 4 runs failed (capacity 2, timeout 1): the statistics are over the " \
        "successful runs only" in text
