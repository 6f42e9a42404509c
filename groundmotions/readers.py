"""Reading a record file: `read_record` chooses `read_peer_at2` (PEER .AT2) or
`read_text_record` (one or two columns), both re-exported here. A file that cannot be read as
written raises `RecordFormatError` naming the file and the line: nothing is silently fixed.
"""

from __future__ import annotations

from pathlib import Path

from dcfpb.common.validation import check_path
from groundmotions.filetext import agreeing_step, read_lines
from groundmotions.peer import has_npts_line, parse_peer, read_peer_at2
from groundmotions.records import GroundMotion, PathLike
from groundmotions.text_records import read_text_record

__all__ = [
    "read_peer_at2",
    "read_record",
    "read_text_record",
]


def read_record(
    path: PathLike, *, dt: float | None = None, units: str | None = None,
    name: str | None = None,
) -> GroundMotion:
    """Read a record: a ``.at2`` file, or any file with an NPTS line before its first row of
    numbers, with `read_peer_at2`; any other with `read_text_record`.

    Parameters
    ----------
    path : str or path-like
        The file.
    dt : float, optional
        Time step [s]: required for a one-column text record; for a two-column text record or a
        PEER file it must agree with the file's to 0.1 % (a PEER file keeps its own DT).
    units : str, optional
        Units of the values when the header states none (`groundmotions.units.UNIT_NAMES` or
        another spelling); by default g. Units that disagree with the header's are refused.
    name : str, optional
        Name of the record; the file stem by default.

    Returns
    -------
    GroundMotion
        Acceleration [m/s^2].

    Raises
    ------
    RecordFormatError
        The file cannot be read as written (see the readers).
    InputError
        ``dt`` or ``units`` bad, or ``dt`` disagreeing with the file.
    """
    path = Path(check_path(path, "path", "read_record"))
    lines = read_lines(path)
    if path.suffix.lower() == ".at2" or has_npts_line(lines):
        motion = parse_peer(path, lines, name, units)
        if dt is not None:
            agreeing_step(dt, motion.dt, "read_record",
                          f"the DT of {path.name} (DT = {motion.dt:g} s)")
        return motion
    return read_text_record(path, dt, units, name=name)
