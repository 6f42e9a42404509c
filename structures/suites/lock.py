"""One suite at a time per result folder: a lock file made by an atomic exclusive create.

Two suites in one folder would compute every run twice, and the second would remove the first's
temporary files as strays. :class:`SuiteLock` creates ``OUT/.suite.lock`` with ``O_CREAT |
O_EXCL`` and writes its holder in it (pid, host, UTC start, the process's own start time, the
command); a second suite refuses (:class:`SuiteLocked`) or, with ``wait``, polls. A lock whose
holder is gone (its pid no longer runs on this host, or runs a later process) is stale and taken
over with a warning, one process at a time (``.suite.lock.takeover``); a lock from another host
is respected, and an unreadable one is stale after :data:`UNREADABLE_STALE_AFTER`. Leaving the
``with`` block releases the lock, on errors too; a process killed outright leaves a stale one.
"""

from __future__ import annotations

import json
import math
import os
import socket
import sys
import time
import uuid
import warnings
from datetime import UTC, datetime
from pathlib import Path
from types import TracebackType
from typing import Any

from dcfpb.common.errors import InputError

__all__ = ["LOCK_NAME", "SuiteLock", "SuiteLocked"]

LOCK_NAME = ".suite.lock"
"""The lock file in the result folder."""
UNREADABLE_STALE_AFTER = 10.0
"""Age [s] after which a lock file that holds no readable holder is stale."""
_POLL = 0.25  # [s] between two looks at a held lock, when waiting


class SuiteLocked(InputError):
    """The result folder is locked by another suite (exit status 2)."""


def _process_start(pid: int) -> float | None:
    """The start time of process ``pid`` [s since the epoch], None if unknown."""
    try:
        import psutil

        return float(psutil.Process(pid).create_time())
    except Exception:  # no psutil, no such process, no access: unknown
        return None


def _alive(pid: int, started: float | None) -> bool:
    """Whether process ``pid`` of this host runs and started at ``started`` (not a reused pid)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # someone else's process: it runs
        pass
    except OSError:
        return False
    now = _process_start(pid)
    return started is None or now is None or abs(now - started) < 1.0


def _describe(holder: dict[str, Any]) -> str:
    return (f"pid {holder.get('pid')} on {holder.get('host')}, started "
            f"{holder.get('started')}")


class SuiteLock:
    """The lock of a suite's result ``folder`` (created if needed), as a context manager;
    ``wait`` [s] for a held lock: 0 refuses at once, ``math.inf`` waits as long as it takes.

    Raises
    ------
    SuiteLocked
        On entering, when another suite holds the folder (after ``wait``), naming the folder,
        the holder and the lock file.
    """

    def __init__(self, folder: str | Path, *, wait: float = 0.0) -> None:
        self.folder = Path(folder)
        self.path = self.folder / LOCK_NAME
        self.wait = float(wait)
        self.token = uuid.uuid4().hex
        self.held = False

    def _holder(self) -> dict[str, Any]:
        return {"pid": os.getpid(), "host": socket.gethostname(),
                "started": datetime.now(UTC).isoformat(timespec="seconds"),
                "process_started": _process_start(os.getpid()),
                "command": " ".join(sys.argv)[:500], "token": self.token}

    def _create(self) -> bool:
        """Try the exclusive create; True when this process holds the lock now."""
        try:
            handle = os.open(self.path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            return False
        try:
            with os.fdopen(handle, "w", encoding="utf-8") as file:
                json.dump(self._holder(), file)
        except BaseException:
            self.path.unlink(missing_ok=True)
            raise
        self.held = True
        return True

    def read(self) -> dict[str, Any] | None:
        """The holder written in the lock file, None when there is none to read."""
        try:
            holder = json.loads(self.path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        return holder if isinstance(holder, dict) else None

    def _stale(self, holder: dict[str, Any] | None) -> bool:
        if holder is None:
            try:
                age = time.time() - self.path.stat().st_mtime
            except OSError:
                return False  # gone meanwhile: the next create decides
            return age > UNREADABLE_STALE_AFTER
        if holder.get("host") != socket.gethostname():
            return False  # another machine's process cannot be looked at
        pid = holder.get("pid")
        return not (isinstance(pid, int) and _alive(pid, holder.get("process_started")))

    def _take_over(self, holder: dict[str, Any] | None) -> None:
        """Remove a stale lock, one process at a time, if it is still the same one."""
        guard = self.path.with_name(LOCK_NAME + ".takeover")
        try:
            os.close(os.open(guard, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644))
        except FileExistsError:
            try:  # a guard left by a process killed while taking over
                if time.time() - guard.stat().st_mtime > UNREADABLE_STALE_AFTER:
                    guard.unlink(missing_ok=True)
            except OSError:
                pass
            return
        try:
            if self.read() == holder and self._stale(holder):
                self.path.unlink(missing_ok=True)
                what = "an unreadable lock" if holder is None else (
                    f"the lock of a suite that no longer runs ({_describe(holder)})")
                warnings.warn(f"{self.folder}: took over {what}.", UserWarning, stacklevel=4)
        finally:
            guard.unlink(missing_ok=True)

    def acquire(self) -> None:
        """Take the lock (see the class); raises :class:`SuiteLocked` when it is held."""
        self.folder.mkdir(parents=True, exist_ok=True)
        deadline = time.monotonic() + self.wait
        told = False
        while not self._create():
            holder = self.read()
            if self._stale(holder):
                self._take_over(holder)
                continue
            if time.monotonic() >= deadline:
                who = _describe(holder) if holder else "a suite that is starting"
                waited = f" after waiting {self.wait:g} s" if self.wait > 0 else ""
                raise SuiteLocked(
                    f"{self.folder}: another suite is writing to this folder ({who}; lock "
                    f"file {self.path}){waited}. Wait for it to finish (--wait-lock), or give "
                    "another folder; if no suite runs there, remove the lock file.")
            if not told and self.wait > 0:
                forever = "" if math.isfinite(self.wait) else " as long as it takes"
                print(f"waiting{forever} for the suite holding {self.folder} "
                      f"({_describe(holder) if holder else 'starting'}) to finish...",
                      file=sys.stderr)
                told = True
            time.sleep(min(_POLL, max(deadline - time.monotonic(), 0.0)))

    def release(self) -> None:
        """Remove the lock file if this lock still holds it."""
        if self.held:
            holder = self.read()
            if holder is not None and holder.get("token") == self.token:
                self.path.unlink(missing_ok=True)
            self.held = False

    def __enter__(self) -> SuiteLock:
        self.acquire()
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.release()
