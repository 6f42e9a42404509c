"""Atomic output files: written under a temporary name beside the final one, then renamed.

:func:`atomic_output` is the one helper every writer of the package uses (the command line's
netCDF, CSV and JSON files, the figures, the diagnosis report, the suites' files): an interrupted
or failed write leaves the file that was there before whole, and no temporary file behind. The
rename (``os.replace``) is atomic on a POSIX file system, since the temporary file lies in the
same folder. Files are not fsynced. :func:`json_safe` makes the data of the JSON files JSON
(no NaN, no numpy numbers).
"""

from __future__ import annotations

import math
import os
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

__all__ = ["MEMINFO", "TEMPORARY_PATTERN", "atomic_output", "available_memory", "json_safe",
           "temporary_name"]

MEMINFO = Path("/proc/meminfo")


def available_memory(meminfo: Path = MEMINFO) -> int | None:
    """Memory available to a new allocation [bytes]: ``MemAvailable`` of ``/proc/meminfo``,
    or None where there is no such file or line (a memory check is then skipped)."""
    try:
        for line in meminfo.read_text().splitlines():
            if line.startswith("MemAvailable:"):
                return int(line.split()[1]) * 1024  # the file gives kB
    except (OSError, ValueError, IndexError):
        return None
    return None


TEMPORARY_PATTERN = ".*.tmp"
"""The glob of the temporary files :func:`atomic_output` makes (``.<name>.<pid>.<hex>.tmp``)."""


def temporary_name(path: str | os.PathLike) -> Path:
    """A fresh temporary path beside ``path``: ``.<name>.<pid>.<8 hex digits>.tmp``, hidden and
    matching :data:`TEMPORARY_PATTERN`."""
    path = Path(path)
    return path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")


@contextmanager
def atomic_output(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path in the folder of ``path`` to write to; on leaving the block
    without an exception it replaces ``path`` (``os.replace``), else it is removed and ``path``
    is left as it was.

    The temporary name ends in ``.tmp``, not in the suffix of ``path``: a writer that picks its
    format from the name (matplotlib's ``savefig``) must be given the format. A file already at
    ``path`` keeps its permission bits in the new one. The folder of ``path`` must exist.

    Parameters
    ----------
    path : str or os.PathLike
        The final file.

    Yields
    ------
    pathlib.Path
        The temporary file to write (not created: the writer creates it).
    """
    final = Path(path)
    temporary = temporary_name(final)
    try:
        yield temporary
        try:
            mode = os.stat(final).st_mode & 0o7777
        except OSError:
            mode = None
        if mode is not None and temporary.exists():
            os.chmod(temporary, mode)
        os.replace(temporary, final)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def json_safe(value: Any) -> Any:
    """``value`` as JSON data for the JSON files and prints of the package: NaN and infinities
    as None (JSON has neither), numpy scalars and arrays as Python numbers and lists, dict keys
    as str, tuples as lists (through dicts and lists at any depth)."""
    if isinstance(value, dict):
        return {str(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [json_safe(v) for v in value]
    if getattr(value, "ndim", 0) and hasattr(value, "tolist"):
        return json_safe(value.tolist())
    if hasattr(value, "item") and not isinstance(value, str | bytes):
        try:
            value = value.item()
        except (ValueError, AttributeError):
            return value
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
