"""One failure contract for the command line (issue 22, point 5 and the Dask half of point 4).

Exit status 2 is bad input only (an ``InputError``, an argparse error, a file given on the command
line that is missing or of the wrong kind), 1 a run that failed on its own terms (with its time
and cause), 3 anything else: an internal error, reported in one line naming a log file that holds
the traceback. A run that fails at its very first step (``yield_displacement = 1e-12``, a record
scaled until the bearings leave their capacity in one step) used to end in "cannot reshape array
of size 0" reported as bad input; it now flows through the results, peaks, floor spectra and
plots and exits 1. ``--workers`` is capped at the cores available; ``--scheduler`` is probed
within a few seconds, so that a closed port, a silent server or one that sends garbage is refused
(exit 2) without a hang.
"""

from __future__ import annotations

import json
import socket
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError, InputWarning, RunFailure

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
EXAMPLE_PLAN = REPO / "examples" / "five_storey_plan.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"


@pytest.fixture
def log_dir(tmp_path, monkeypatch) -> Path:
    folder = tmp_path / "logs"
    monkeypatch.setenv("DCFPB_LOG_DIR", str(folder))
    return folder


def _short_record(folder: Path, samples: int = 60) -> Path:
    """The first ``samples`` values of El Centro [g] as a one-column text record (dt 0.02 s)."""
    from groundmotions.bundled import load_bundled

    path = folder / "short.txt"
    np.savetxt(path, load_bundled("elcentro").acceleration[:samples] / 9.80665)
    return path


def _building(folder: Path, source: Path = EXAMPLE, **replace: str) -> Path:
    text = source.read_text()
    for old, new in replace.items():
        assert old in text
        text = text.replace(old, new)
    path = folder / source.name
    path.write_text(text)
    return path


# --- exit 3: internal errors -------------------------------------------------------------------

@pytest.mark.parametrize("error", [ValueError("bare value error"), TypeError("bare type error"),
                                   IndexError("index 7 is out of bounds"),
                                   ZeroDivisionError("float division by zero")],
                         ids=["ValueError", "TypeError", "IndexError", "ZeroDivisionError"])
def test_an_internal_error_exits_3_with_a_log_holding_the_traceback(error, log_dir, capsys,
                                                                    monkeypatch):
    import dcfpb.cli.protocol as protocol

    def broken(args):
        raise error

    monkeypatch.setattr(protocol, "_run_protocol", broken)
    assert main(["protocol", "--model", "constant"]) == 3
    err = capsys.readouterr().err
    assert err.startswith("dcfpb protocol: internal error: ") and err.count("\n") == 1, err
    assert type(error).__name__ in err and str(error) in err
    assert "please report it at " in err and "with the log " in err
    logs = list(log_dir.glob("dcfpb-protocol-*.log"))
    assert len(logs) == 1 and str(logs[0]) in err
    text = logs[0].read_text()
    assert "Traceback (most recent call last)" in text and "in broken" in text
    assert f"{type(error).__name__}: {error}" in text
    assert "command line: dcfpb protocol --model constant" in text


def test_bad_input_and_run_failures_keep_their_statuses(log_dir, capsys, monkeypatch):
    import dcfpb.cli.protocol as protocol

    def bad(args):
        raise InputError("--amplitude must be positive. Got -1 instead.")

    def failed(args):
        raise RunFailure("Capacity exceeded at t = 1.25 s.")

    monkeypatch.setattr(protocol, "_run_protocol", bad)
    assert main(["protocol"]) == 2
    assert capsys.readouterr().err == ("dcfpb protocol: error: --amplitude must be positive. "
                                       "Got -1 instead.\n")
    monkeypatch.setattr(protocol, "_run_protocol", failed)
    assert main(["protocol"]) == 1
    assert capsys.readouterr().err == ("dcfpb protocol: run failed: Capacity exceeded at "
                                       "t = 1.25 s.\n")
    assert not log_dir.exists()  # no log for either


def test_an_os_error_is_bad_input_only_for_a_path_the_user_gave(tmp_path, log_dir, capsys,
                                                                monkeypatch):
    import dcfpb.cli.run as run

    given = tmp_path / "records"
    given.mkdir()
    inside = given / "gone.AT2"

    def missing_inside(args):
        raise FileNotFoundError(2, "No such file or directory", str(inside))

    monkeypatch.setattr(run, "_run_building", missing_inside)
    assert main(["run", str(EXAMPLE), "--record", str(given)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"dcfpb run: error: --record {given}: No such file or directory")
    assert f"(inside {given})" in err

    def missing_elsewhere(args):
        raise FileNotFoundError(2, "No such file or directory", "/nonexistent/cache/index")

    monkeypatch.setattr(run, "_run_building", missing_elsewhere)
    assert main(["run", str(EXAMPLE), "--record", str(given)]) == 3
    assert "internal error: FileNotFoundError" in capsys.readouterr().err


def test_a_missing_or_wrong_kind_path_names_its_flag(tmp_path, capsys):
    assert main(["run", str(EXAMPLE), "--record", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("dcfpb run: error: ") and "--record" in err and str(tmp_path) in err
    missing = tmp_path / "missing.at2"
    assert main(["run", str(EXAMPLE), "--record", str(missing)]) == 2
    assert str(missing) in capsys.readouterr().err


def test_help_lists_the_exit_statuses(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--help"])
    assert stop.value.code == 0
    out = capsys.readouterr().out
    for line in ("exit status:", "0  success", "1  a run failed", "2  bad input",
                 "3  internal error"):
        assert line in out


# --- exit 1: a run that fails at its first step -------------------------------------------------

def test_a_run_failing_at_its_first_step_exits_1_naming_the_time(tmp_path, capsys):
    building = _building(tmp_path, yield_displacement="yield_displacement = 1e-12 #")
    record = _short_record(tmp_path)
    plots, output = tmp_path / "plots", tmp_path / "out.nc"
    status = main(["run", str(building), "--record", str(record), "--record-dt", "0.02",
                   "--units", "g", "--json", "--plot", str(plots), "--output", str(output)])
    captured = capsys.readouterr()
    assert status == 1, captured.err
    summary = json.loads(captured.out)
    assert summary["success"] is False and summary["failure"] == "convergence"
    assert summary["failed_at"] == pytest.approx(0.005) and summary["steps"] == 0
    assert "Step 1: Newton iteration did not converge" in summary["message"]
    assert captured.err.startswith("dcfpb run: run failed (convergence) at t = 0.005 s: Step 1")
    assert output.is_file() and sorted(p.name for p in plots.iterdir())  # written, not crashed


def test_a_building_in_plan_failing_at_its_first_step_plots_and_exits_1(tmp_path, capsys):
    building = _building(tmp_path, EXAMPLE_PLAN,
                         yield_displacement="yield_displacement = 1e-12 #")
    record = _short_record(tmp_path, samples=20)
    plots = tmp_path / "plots"
    status = main(["run", str(building), "--record", str(record), "--record-y", str(record),
                   "--record-dt", "0.02", "--units", "g", "--plot", str(plots)])
    captured = capsys.readouterr()
    assert status == 1, captured.err  # was exit 3: the plate's field of no monitor point
    assert captured.err.startswith("dcfpb run: run failed (convergence) at t = 0.005 s: ")
    assert "bearing_orbits.png" in {p.name for p in plots.iterdir()}


def test_a_record_past_the_capacity_in_one_step_exits_1(tmp_path, capsys):
    record = _short_record(tmp_path, samples=20)
    status = main(["run", str(EXAMPLE), "--record", str(record), "--record-dt", "0.02",
                   "--units", "g", "--scale", "1e7", "--model", "constant"])
    captured = capsys.readouterr()
    assert status == 1, captured.err
    assert "RUN FAILED (capacity)" in captured.out
    assert captured.err.startswith("dcfpb run: run failed (capacity) at t = 0.005 s: ")
    assert "displacement_capacity" in captured.err


def test_compare_opensees_with_our_run_failing_at_its_first_step_exits_1(tmp_path, capsys):
    from structures.opensees.runtime import import_opensees

    try:
        import_opensees()
    except ImportError as error:
        pytest.skip(f"openseespy cannot be imported: {error}")
    building = _building(tmp_path, yield_displacement="yield_displacement = 1e-12 #")
    record = _short_record(tmp_path, samples=20)
    status = main(["compare-opensees", str(building), "--record", str(record), "--record-dt",
                   "0.02", "--units", "g", "--json"])
    captured = capsys.readouterr()
    assert status == 1, captured.err  # was exit 2: "must share their time step ... 0.005 s and
    summary = json.loads(captured.out)  # 0.005 s", the one sample kept read as another step
    assert summary["ours"]["success"] is False and summary["ours"]["steps"] == 0
    assert "dcfpb compare-opensees: run failed (convergence) at t = 0.005 s: ours: Step 1" in \
        captured.err


@pytest.mark.parametrize("plan", [False, True], ids=["one-direction", "plan"])
def test_zero_committed_steps_flow_through_peaks_and_floor_spectra(plan, tmp_path):
    from groundmotions.bundled import load_bundled
    from groundmotions.pairs import GroundMotionPair
    from structures import peaks, run, with_floor_spectra
    from structures.fixed_base import ratios_to_fixed_base, run_fixed_base

    source = EXAMPLE_PLAN if plan else EXAMPLE
    building = _building(tmp_path, source, yield_displacement="yield_displacement = 1e-12 #")
    record = load_bundled("elcentro")
    motion = GroundMotionPair(record, record) if plan else record
    result = run(building, motion, model="constant", engine="reference", floor_spectra=False)
    assert result.attrs["success"] == 0 and result.sizes["time"] == 1
    assert result.attrs["failure"] == "convergence" and result.attrs["failed_at"] > 0
    summary = peaks(result)
    assert summary["steps"] == 0 and summary["peaks_up_to_failure"]
    spectra = with_floor_spectra(result, motion)
    assert np.isnan(spectra["floor_spectrum"].values).all()
    from structures import load_config

    config = load_config(building)
    fixed = run_fixed_base(config.building, motion, dt=result.attrs["dt"])
    ratios = ratios_to_fixed_base(result, fixed)
    assert all(np.isfinite(v) for v in ratios.values())


def test_a_time_limit_hit_at_the_first_step_keeps_one_step_and_its_spectra():
    from groundmotions.bundled import load_bundled
    from structures.analysis import peaks, run
    from structures.config import load_config

    config = load_config(EXAMPLE)
    result = run(config.building, config.bearing("constant"), load_bundled("elcentro"),
                 n_bearings=config.n_bearings, engine="reference", time_limit=1e-12,
                 floor_spectra=True)
    assert result.sizes["time"] == 2 and result.attrs["failure"] == "timeout"
    summary = peaks(result)
    assert summary["steps"] == 1 and summary["failed_at"] == pytest.approx(0.005)
    assert np.isfinite(result["floor_spectrum"].values).all()


def test_the_energy_of_no_step_is_zero():
    from structures.energy import trapezoid_work

    work = trapezoid_work(np.zeros((1, 3, 2)), np.zeros((1, 3, 2)))
    assert work.shape == (1,) and work[0] == 0.0


# --- --workers and --scheduler ------------------------------------------------------------------

def test_workers_above_the_cores_warn_and_are_capped(tmp_path, capsys, monkeypatch):
    import structures.suites.suite as suite_module
    from structures.suites.tasks import available_cores, capped_workers

    cores = available_cores()
    asked = {}

    def fake_run_suite(suite, out, **kwargs):
        asked.update(kwargs)
        raise RunFailure("stopped by the test")

    monkeypatch.setattr(suite_module, "run_suite", fake_run_suite)
    with pytest.warns(InputWarning) as caught:
        status = main(["suite", str(EXAMPLE), "--records", str(RECORD.parent), "--workers",
                       str(cores + 62), "--out", str(tmp_path / "out"), "--no-progress"])
    assert status == 1 and asked["n_workers"] == cores
    assert any(f"--workers {cores + 62} is more than the {cores} CPU core(s) available" in
               str(w.message) for w in caught)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert capped_workers(cores, "--workers") == cores  # no warning at the cap
        assert capped_workers(None) == cores
    with pytest.warns(InputWarning, match="n_workers 1000 is more than"):
        assert capped_workers(1000) == cores
    with pytest.raises(InputError, match="'--workers'"):
        capped_workers(0, "--workers")


def _children() -> set[int]:
    """This process's child processes but multiprocessing's own helpers (the resource tracker,
    the fork server: started once with the first process of a kind, they live as long as the
    parent and are no workers)."""
    import os

    try:
        text = Path(f"/proc/{os.getpid()}/task/{os.getpid()}/children").read_text()
    except OSError:
        pytest.skip("no /proc children list on this system")
    children = set()
    for pid in map(int, text.split()):
        try:
            command = Path(f"/proc/{pid}/cmdline").read_bytes()
        except OSError:
            continue  # gone meanwhile
        if b"multiprocessing.resource_tracker" not in command and \
                b"multiprocessing.forkserver" not in command:
            children.add(pid)
    return children


def test_the_local_cluster_is_closed_even_when_the_suite_fails():
    pytest.importorskip("distributed")
    from structures.suites.tasks import client_for

    before = _children()
    with pytest.raises(RuntimeError, match="boom"), client_for(1, None) as client:
        assert client.scheduler_info()["workers"]
        raise RuntimeError("boom")
    deadline = time.monotonic() + 20  # a loaded machine takes its time to reap them
    while _children() - before and time.monotonic() < deadline:
        time.sleep(0.1)
    left = _children() - before
    assert not left  # no worker process outlives the suite


def _server(payload: bytes, close: bool) -> tuple[str, socket.socket]:
    """A local server that accepts, sends ``payload`` and closes (``close``) or stays silent."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen()
    held = []

    def serve():
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            if payload:
                conn.sendall(payload)
            if close:
                conn.close()
            else:
                held.append(conn)

    threading.Thread(target=serve, daemon=True).start()
    return f"tcp://127.0.0.1:{server.getsockname()[1]}", server


def _closed_port() -> str:
    probe = socket.socket()
    probe.bind(("127.0.0.1", 0))
    port = probe.getsockname()[1]
    probe.close()
    return f"tcp://127.0.0.1:{port}"


SCHEDULERS = {
    "closed-port": (None, "cannot connect"),
    "garbage": ((b"\xff" * 4096, False), "something else than a Dask handshake"),
    "plain-http": ((b"HTTP/1.0 200 OK\r\nContent-Length: 2\r\n\r\nok", True),
                   "something else than a Dask handshake"),
    "silent": ((b"", False), "said nothing within 0.5 s"),
    "hangs-up": ((b"", True), "closed the connection without a word"),
    "huge-length": ((b"\x00\x00\x00\x00\x00\x00\x00\x40", False),
                    "something else than a Dask handshake"),
}


@pytest.mark.parametrize("case", SCHEDULERS, ids=list(SCHEDULERS))
def test_a_scheduler_that_is_not_one_is_refused_at_once(case, tmp_path, capsys, monkeypatch):
    pytest.importorskip("distributed")
    import structures.suites.tasks as tasks

    monkeypatch.setattr(tasks, "SCHEDULER_TIMEOUT", 0.5)
    serve, reason = SCHEDULERS[case]
    server = None
    if serve is None:
        address = _closed_port()
    else:
        address, server = _server(*serve)
    try:
        start = time.monotonic()
        status = main(["suite", str(EXAMPLE), "--records", str(RECORD.parent), "--scheduler",
                       address, "--out", str(tmp_path / "out"), "--no-progress"])
        elapsed = time.monotonic() - start
    finally:
        if server is not None:
            server.close()
    err = capsys.readouterr().err
    assert status == 2, err
    assert err.startswith(f"dcfpb suite: error: --scheduler '{address}': ") and reason in err
    assert elapsed < 5.0
    assert not (tmp_path / "out").exists()  # refused before any work


@pytest.mark.parametrize("address", ["tcp://127.0.0.1", "localhost:port", "ftp://host:21", ""])
def test_a_malformed_scheduler_address_is_refused(address, tmp_path, capsys):
    pytest.importorskip("distributed")
    status = main(["suite", str(EXAMPLE), "--records", str(RECORD.parent), "--scheduler",
                   address, "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert status == 2 and "--scheduler" in err, err


def test_a_real_scheduler_passes_the_probe():
    distributed = pytest.importorskip("distributed")
    from structures.suites.tasks import check_scheduler

    with distributed.LocalCluster(n_workers=0, processes=False, protocol="tcp",
                                  dashboard_address=None) as cluster:
        assert check_scheduler(cluster.scheduler_address, timeout=2.0) == \
            cluster.scheduler_address
