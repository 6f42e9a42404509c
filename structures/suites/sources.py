"""Where the ground motions of a suite are: record files, or the component files of pairs.

A :class:`MotionSource` names one ground motion and its files (a record: a run in one
direction; the components of a pair: a run in plan); :func:`motion_sources` lists them without
reading them. A list that cannot be understood is an error before any work; a file that cannot
be read fails its runs only.
"""

from __future__ import annotations

import csv
import hashlib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from dcfpb.common.errors import InputError

__all__ = ["MOTION_COLUMNS", "MotionSource", "file_digest", "motion_sources"]

MOTION_COLUMNS = {"record": ("record", "record_file"),
                  "pair": ("pair", "x_file", "y_file", "z_file")}
"""The columns naming a motion in a peaks-table row, by kind (:meth:`MotionSource.columns`)."""
_LIST_HEADERS = {"file", "filename", "file_name", "record", "path"}


def file_digest(path: str | Path) -> str:
    """sha256 of a file's bytes (16 hex digits), or ``"missing"`` if it cannot be read."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
    except OSError:
        return "missing"


@dataclass(frozen=True)
class MotionSource:
    """One ground motion of a suite: its ``name`` (a record file's stem, or a pair's name), its
    ``files`` (absolute paths: one record, or a pair's x, y and optionally z components), the
    step ``dt`` [s] of one-column text records and the ``units`` of files whose header has none."""

    name: str
    files: tuple[str, ...]
    dt: float | None = None
    units: str | None = None

    def __post_init__(self) -> None:
        if not 1 <= len(self.files) <= 3:
            raise InputError(f"The 'files' parameter of MotionSource must hold one record file "
                             f"or the 2 or 3 components of a pair. Got {self.files!r} instead.")
        object.__setattr__(self, "files", tuple(str(Path(f).absolute()) for f in self.files))

    @classmethod
    def record(cls, path: str | Path) -> MotionSource:
        """The source of one record file, named by its stem."""
        return cls(Path(path).stem, (str(path),))

    @property
    def kind(self) -> str:
        """``"record"`` (one direction) or ``"pair"`` (in plan)."""
        return "record" if len(self.files) == 1 else "pair"

    def columns(self) -> dict[str, Any]:
        """The columns naming the motion in a peaks-table row (:data:`MOTION_COLUMNS`; ``z_file``
        None without a vertical), file names without their folder."""
        names = [self.name, *(Path(f).name for f in self.files), None]
        return dict(zip(MOTION_COLUMNS[self.kind], names, strict=False))

    def identity(self, digests: tuple[str, ...]) -> dict[str, Any]:
        """What of the motion a run's id covers: file names, ``digests``, how a pair is read."""
        columns = self.columns()
        if self.kind == "record":
            return {"record_file": columns["record_file"], "record_digest": digests[0]}
        return columns | {"digests": list(digests), "read_dt": self.dt, "units": self.units}

    def digests(self) -> tuple[str, ...]:
        """:func:`file_digest` of each file."""
        return tuple(file_digest(f) for f in self.files)

    def read(self) -> Any:
        """The motion, unscaled and untruncated: a ``GroundMotion`` or a ``GroundMotionPair``
        (raises for a missing or unreadable file, or a pair's mismatched components)."""
        if self.kind == "record":
            from groundmotions.readers import read_record

            return read_record(self.files[0], dt=self.dt, units=self.units)
        from groundmotions.pairs import read_pair

        return read_pair(*self.files[:2], *self.files[2:], name=self.name, dt=self.dt,
                         units=self.units)


MAX_LIST_BYTES = 10 * 2**20
"""Largest CSV list of records read [bytes] (some hundred thousand rows)."""


def motion_sources(path: str | Path, *, pairs: bool = False) -> tuple[MotionSource, ...]:
    """The motions of a record list or, with ``pairs``, of a pair manifest, without reading them.

    A record list is a folder (its ``*.AT2`` files, any case) or a CSV whose first column holds
    record files relative to it (a first cell ``file``, ``filename``, ``file_name``, ``record``
    or ``path`` is a header; other columns are ignored); a pair manifest is that of
    :func:`groundmotions.pairs.read_pair_manifest` (columns ``name``, ``x``, ``y`` and optionally
    ``z``, ``dt`` [s], ``units``).

    Raises
    ------
    InputError
        Records: no such folder or file, or no records in it. Pairs: no such file, or a manifest
        empty or with a bad column, row, cell, pair name or ``dt`` (``"<manifest>, line <n>"``).
    """
    if pairs:
        from groundmotions.pairs.pair import manifest_rows

        return tuple(MotionSource(row.name, tuple(map(str, row.files.values())), row.dt,
                                  row.units) for row in manifest_rows(path))
    path = Path(path)
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if p.is_file() and p.suffix.lower() == ".at2")
    elif path.is_file():
        if path.stat().st_size > MAX_LIST_BYTES:
            raise InputError(f"{path}: {path.stat().st_size:,} bytes, more than the "
                             f"{MAX_LIST_BYTES:,} of a list of records; is it one?")
        try:
            with open(path, newline="", encoding="utf-8") as handle:
                rows = [row for row in csv.reader(handle) if row and row[0].strip()]
        except (UnicodeDecodeError, csv.Error) as error:
            raise InputError(f"{path}: not a UTF-8 CSV list of records ({error}).") from None
        if rows and rows[0][0].strip().lower() in _LIST_HEADERS:
            rows = rows[1:]
        files = [path.parent / row[0].strip() for row in rows
                 if not row[0].lstrip().startswith("#")]
    else:
        raise InputError(f"{path}: no such folder of records or manifest file.")
    if not files:
        raise InputError(f"{path}: no record files (*.AT2 in a folder, or rows of a manifest).")
    return tuple(MotionSource.record(f) for f in files)
