"""The folder of a suite's results: atomic files, a completeness test, failures and a log.

Layout of ``OUT/``::

    runs/<run id>.nc            the run's full result (netCDF, written first)
    runs/<run id>.json          its peaks row, written last: the run's completion mark
    runs/<run id>.failed.json   a failed run's row with its reason (removed when it succeeds)
    suite.log                   one line per event: "<UTC time> <event> <run id> <details>"
    peaks.csv, failures.json    the table of the last invocation (``structures.suites.suite``)

Every file is written under a temporary name and renamed with ``os.replace`` (atomic), so a file
under its final name is whole. A run is complete when its row parses, names the run as done and
its netCDF file has the size the row records; anything else is computed again. Files are not
fsynced: one lost to a power cut fails the same test. A log line is one ``write``, kept whole
between processes on a local POSIX file system. A run's ``done`` line follows its row, so a suite
killed between the two leaves a complete run without one; the next suite finds it complete and
logs it then, marked ``recovered=true`` (:meth:`RunStore.log_recovered`): the log holds one
``done`` line per finished run.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from dcfpb.common.files import TEMPORARY_PATTERN, atomic_output, json_safe
from structures.suites.runs import stored_enough

_TEMPORARY = TEMPORARY_PATTERN


def atomic_write(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically (:func:`dcfpb.common.files.atomic_output`: a
    temporary file, then ``os.replace``)."""
    with atomic_output(path) as temporary, open(temporary, "wb") as handle:
        handle.write(data)


def dumps(row: dict[str, Any]) -> bytes:
    """A row as JSON (floats round-trip exactly: Python writes their shortest repr)."""
    return json.dumps(json_safe(row), indent=1,
                      allow_nan=False).encode()


class RunStore:
    """The result folder ``root`` of a suite (created if needed), the run files in ``root/runs``."""

    def __init__(self, root: str | Path) -> None:
        self.root = Path(root)
        self.runs = self.root / "runs"
        self.runs.mkdir(parents=True, exist_ok=True)
        self.log_path = self.root / "suite.log"

    def result_path(self, run_id: str) -> Path:
        """The run's netCDF file."""
        return self.runs / f"{run_id}.nc"

    def row_path(self, run_id: str) -> Path:
        """The run's peaks row (its completion mark)."""
        return self.runs / f"{run_id}.json"

    def failure_path(self, run_id: str) -> Path:
        """The failed run's row with its reason."""
        return self.runs / f"{run_id}.failed.json"

    def clean_temporary(self) -> int:
        """Remove temporary files left by a killed suite; return how many there were."""
        stray = list(self.runs.glob(_TEMPORARY)) + list(self.root.glob(_TEMPORARY))
        for path in stray:
            path.unlink(missing_ok=True)
        return len(stray)

    def _read(self, path: Path) -> dict[str, Any] | None:
        try:
            row = json.loads(path.read_text())
        except (OSError, ValueError):
            return None
        return row if isinstance(row, dict) else None

    def completed_row(self, run_id: str, storage: str = "full",
                      keys: tuple[str, ...] = ()) -> dict[str, Any] | None:
        """The row of a complete run, or None if the run must be computed (again): done, with
        at least what ``storage`` asks kept (``structures.suites.runs.STORAGE``; a file of the
        recorded size unless only the peaks are asked) and every key of ``keys``."""
        row = self._read(self.row_path(run_id))
        if row is None or row.get("run_id") != run_id or row.get("status") != "done":
            return None
        if not stored_enough(row, storage) or any(key not in row for key in keys):
            return None
        if storage == "peaks" and not row.get("result_file"):
            return row
        try:
            size = self.result_path(run_id).stat().st_size
        except OSError:
            return None
        return row if size == row.get("result_bytes") else None

    def failed_row(self, run_id: str) -> dict[str, Any] | None:
        """The row of the run's last failure, if any."""
        return self._read(self.failure_path(run_id))

    def save_done(self, row: dict[str, Any], data: bytes) -> dict[str, Any]:
        """Store a finished run: the netCDF first (none for empty ``data``: peaks only), then
        its row; drop an older failure."""
        run_id = row["run_id"]
        path = self.result_path(run_id)
        if data:
            atomic_write(path, data)
            row = row | {"result_file": f"runs/{path.name}", "result_bytes": len(data)}
        else:  # peaks only: no file (an older one of this run removed)
            path.unlink(missing_ok=True)
            row = row | {"result_file": None, "result_bytes": 0}
        atomic_write(self.row_path(run_id), dumps(row))
        self.failure_path(run_id).unlink(missing_ok=True)
        self.log("done", run_id, worker=row.get("worker"))
        return row

    def save_failure(self, row: dict[str, Any]) -> dict[str, Any]:
        """Store a failed run's row with its reason (it is computed again on the next run)."""
        atomic_write(self.failure_path(row["run_id"]), dumps(row))
        self.log("failed", row["run_id"], reason=row.get("reason"))
        return row

    def log(self, event: str, run_id: str, **details: Any) -> None:
        """Append one line to ``suite.log`` (one ``write`` of an ``O_APPEND`` file)."""
        stamp = datetime.now(UTC).isoformat(timespec="milliseconds")
        extra = " ".join(f"{k}={json.dumps(v)}" for k, v in details.items() if v is not None)
        line = f"{stamp} {event} {run_id} {extra}".rstrip() + "\n"
        with open(self.log_path, "a", encoding="utf-8") as handle:
            handle.write(line)

    def log_recovered(self, run_ids: Iterable[str]) -> list[str]:
        """Log ``done`` (``recovered=true``) for each of ``run_ids`` (runs found complete) that
        has no ``done`` line, as a suite killed between a row and its line leaves it; return
        those run ids."""
        logged = {run_id for event, run_id in self.events() if event == "done"}
        missing = [run_id for run_id in run_ids if run_id not in logged]
        for run_id in missing:
            self.log("done", run_id, recovered=True)
        return missing

    def events(self) -> list[tuple[str, str]]:
        """``(event, run id)`` of every line of the log, oldest first."""
        if not self.log_path.exists():
            return []
        lines = self.log_path.read_text(encoding="utf-8").splitlines()
        return [(parts[1], parts[2]) for parts in (line.split(" ", 3) for line in lines)
                if len(parts) >= 3]
