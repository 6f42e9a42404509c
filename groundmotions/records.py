"""`GroundMotion`, one ground-acceleration record [m/s^2] at a fixed time step, and
`RecordFormatError`, the error of its readers. A record's methods return new records and append
what they did to ``processing``.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_array, check_instance, check_real
from groundmotions.processing import baseline_corrected, filtered, resampled

__all__ = ["GroundMotion", "RecordFormatError"]

PathLike = str | os.PathLike[str]


class RecordFormatError(InputError):
    """A record file that cannot be read as written: the message reads
    ``"<file name>, line <n>: <reason>"``, the parts kept as ``file``, ``line`` and ``reason``."""

    def __init__(self, file: PathLike, line: int, reason: str) -> None:
        self.file = Path(file).name
        self.line = line
        self.reason = reason
        super().__init__(f"{self.file}, line {line}: {reason}")

    def __reduce__(self) -> tuple[Any, ...]:  # picklable across processes (Dask suites)
        return (type(self), (self.file, self.line, self.reason))


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """One horizontal ground-acceleration record at a fixed time step (equality is identity:
    compare ``acceleration`` arrays to compare records).

    Parameters
    ----------
    acceleration : array_like
        Ground acceleration [m/s^2], at least 2 finite samples; stored as a read-only copy.
    dt : float
        Time step [s], > 0.
    name : str
        Short name (the readers use the file stem).
    metadata : dict
        Header information (``event``, ``date``, ``station``, ``component``, ``source_file``,
        ``units_in_file``, ``header_lines`` ...); a shallow copy is stored.
    processing : tuple of str
        What was done to the record, oldest first.
    """

    acceleration: np.ndarray
    dt: float
    name: str = ""
    metadata: dict[str, Any] = field(default_factory=dict)
    processing: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        owner = "GroundMotion"
        dt = check_real(self.dt, "dt", owner, low=0.0, low_open=True)
        acc = np.array(check_array(self.acceleration, "acceleration", owner, min_length=2))
        acc.flags.writeable = False
        steps = self.processing
        check_instance(self.name, "name", owner, str, "a str")
        check_instance(self.metadata, "metadata", owner, Mapping, "a mapping")
        if not (isinstance(steps, tuple | list) and all(isinstance(s, str) for s in steps)):
            raise InputTypeError(f"The 'processing' parameter of {owner} must be a tuple of str. "
                                 f"Got {steps!r} instead.")
        object.__setattr__(self, "acceleration", acc)
        object.__setattr__(self, "dt", dt)
        object.__setattr__(self, "metadata", dict(self.metadata))
        object.__setattr__(self, "processing", tuple(steps))

    def __repr__(self) -> str:
        return (
            f"GroundMotion(name={self.name!r}, npts={self.npts}, dt={self.dt:g} s, "
            f"pga={self.pga:.4g} m/s^2, processing={len(self.processing)} steps)"
        )

    @property
    def npts(self) -> int:
        """Number of samples [-]."""
        return int(self.acceleration.size)

    @property
    def time(self) -> np.ndarray:
        """Sample times, starting at 0 [s]."""
        return np.arange(self.npts) * self.dt

    @property
    def duration(self) -> float:
        """Time of the last sample, ``(npts - 1) * dt`` [s] (PEER tables quote ``npts * dt``)."""
        return (self.npts - 1) * self.dt

    @property
    def pga(self) -> float:
        """Peak ground acceleration, max |a| [m/s^2]."""
        return float(np.max(np.abs(self.acceleration)))

    def derived(self, acceleration: np.ndarray, step: str) -> GroundMotion:
        """A new record of this step, name and metadata with ``acceleration`` [m/s^2], and
        ``step`` (what was done) appended to ``processing``."""
        return GroundMotion(
            acceleration, self.dt, self.name, dict(self.metadata), (*self.processing, step)
        )

    def scaled(self, factor: float) -> GroundMotion:
        """A new record with the acceleration multiplied by ``factor`` [-]."""
        k = check_real(factor, "factor", "GroundMotion.scaled")
        return self.derived(self.acceleration * k, f"scaled by {k:.12g}")

    def negated(self) -> GroundMotion:
        """A new record with the sign of the acceleration reversed."""
        return self.derived(-self.acceleration, "negated")

    def truncated(self, duration: float) -> GroundMotion:
        """A new record of the samples at t <= ``duration`` [s], ``duration`` in
        [dt, self.duration]."""
        d = check_real(
            duration, "duration", "GroundMotion.truncated", low=self.dt, high=self.duration
        )
        n = min(self.npts, math.floor(d / self.dt + 1e-9) + 1)
        return self.derived(self.acceleration[:n], f"truncated to {d:g} s ({n} samples)")

    def baseline_corrected(self, order: int = 1) -> GroundMotion:
        """`groundmotions.processing.baseline_corrected` of this record."""
        return baseline_corrected(self, order)

    def filtered(
        self, low: float | None = None, high: float | None = None, order: int = 4
    ) -> GroundMotion:
        """`groundmotions.processing.filtered` of this record (corners [Hz])."""
        return filtered(self, low, high, order)

    def resampled(self, dt: float, *, anti_alias: bool = True) -> GroundMotion:
        """`groundmotions.processing.resampled` of this record (new time step ``dt`` [s])."""
        return resampled(self, dt, anti_alias=anti_alias)
