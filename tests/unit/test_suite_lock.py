"""The lock of a suite's result folder (structures.suites.lock): refused while held, waited for
on request, released on errors, a stale one taken over with a warning, another host's kept."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import threading
import time

import pytest

from structures.suites.lock import LOCK_NAME, SuiteLock, SuiteLocked


def _dead_pid() -> int:
    """The pid of a process that has ended."""
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


def _write(folder, **holder) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / LOCK_NAME).write_text(json.dumps(
        {"host": socket.gethostname(), "started": "2030-01-01T00:00:00+00:00",
         "token": "theirs"} | holder))


def test_held_lock_refuses_and_is_released_on_errors(tmp_path):
    first = SuiteLock(tmp_path / "out")
    with pytest.raises(RuntimeError, match="boom"), first:
        holder = json.loads((tmp_path / "out" / LOCK_NAME).read_text())
        assert holder["pid"] == os.getpid() and holder["host"] == socket.gethostname()
        with pytest.raises(SuiteLocked, match=f"pid {os.getpid()} on ") as error:
            SuiteLock(tmp_path / "out").acquire()
        assert str(tmp_path / "out") in str(error.value) and isinstance(error.value, ValueError)
        raise RuntimeError("boom")
    assert not (tmp_path / "out" / LOCK_NAME).exists()
    with SuiteLock(tmp_path / "out"):  # free again
        pass


def test_waiting_for_the_lock(tmp_path):
    first = SuiteLock(tmp_path)
    first.acquire()
    start = time.monotonic()
    with pytest.raises(SuiteLocked, match=r"after waiting 0\.3 s"):
        SuiteLock(tmp_path, wait=0.3).acquire()
    assert time.monotonic() - start >= 0.3
    threading.Timer(0.3, first.release).start()
    with SuiteLock(tmp_path, wait=30.0) as second:  # gets it once the first lets go
        assert json.loads(second.path.read_text())["token"] == second.token


def test_a_stale_lock_is_taken_over_with_a_warning(tmp_path):
    _write(tmp_path, pid=_dead_pid())
    with pytest.warns(UserWarning, match="took over the lock of a suite that no longer runs"):
        lock = SuiteLock(tmp_path)
        lock.acquire()
    assert json.loads(lock.path.read_text())["pid"] == os.getpid()
    lock.release()


def test_a_reused_pid_is_stale_too(tmp_path):
    """The holder's pid runs, but a process that started later than the lock's (this one)."""
    _write(tmp_path, pid=os.getpid(), process_started=1.0)
    with pytest.warns(UserWarning, match="took over"), SuiteLock(tmp_path):
        pass


def test_another_hosts_lock_and_a_fresh_unreadable_one_are_kept(tmp_path):
    _write(tmp_path, pid=_dead_pid(), host="elsewhere")
    with pytest.raises(SuiteLocked, match="on elsewhere"):
        SuiteLock(tmp_path).acquire()
    (tmp_path / LOCK_NAME).write_text("")  # being written by a suite that is starting
    with pytest.raises(SuiteLocked, match="a suite that is starting"):
        SuiteLock(tmp_path).acquire()
    old = time.time() - 60.0  # ... or left empty by one killed while writing it
    os.utime(tmp_path / LOCK_NAME, (old, old))
    with pytest.warns(UserWarning, match="took over an unreadable lock"), SuiteLock(tmp_path):
        pass
