"""`GroundMotionPair`, two horizontal components of one recording and an optional vertical,
and its readers: `read_pair` (two or three record files) and `read_pair_manifest` (the pairs
listed in a CSV file). A bad pair is refused, never repaired.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.validation import check_path, check_real
from groundmotions.readers import read_record
from groundmotions.records import GroundMotion, PathLike

__all__ = ["GroundMotionPair", "ManifestRow", "manifest_rows", "read_pair", "read_pair_manifest"]

MANIFEST_COLUMNS = ("name", "x", "y", "z", "dt", "units")
"""Columns a pair manifest may have; ``name``, ``x`` and ``y`` are required."""

_DT_TOLERANCE = 1e-9  # relative: the time steps of two components must agree to this


def _label(role: str, motion: GroundMotion) -> str:
    """``"y component (CHY023-W.AT2)"``: the role and the file (else the name) of a record."""
    source = motion.metadata.get("source_file") or motion.name or "unnamed"
    return f"{role} component ({source})"


@dataclass(frozen=True, eq=False)
class GroundMotionPair:
    """Two orthogonal horizontal components of one recording and an optional vertical one.

    Parameters
    ----------
    x, y : GroundMotion
        The horizontal components [m/s^2]; ``y`` is 90 degrees counter-clockwise from ``x``.
    z : GroundMotion, optional
        The vertical component [m/s^2].
    name : str
        The pair's name (e.g. the station).

    Raises
    ------
    InputError
        Components of different time steps (relative difference above 1e-9) or numbers of
        samples, naming both and the way out (``resampled``, ``truncated_to_common``).
    """

    x: GroundMotion
    y: GroundMotion
    z: GroundMotion | None = None
    name: str = ""

    def __post_init__(self) -> None:
        for role in ("x", "y", "z"):
            value = getattr(self, role)
            if not (isinstance(value, GroundMotion) or (role == "z" and value is None)):
                kind = "a GroundMotion or None" if role == "z" else "a GroundMotion"
                raise InputTypeError(f"The {role!r} parameter of GroundMotionPair must be "
                                     f"{kind}. Got {value!r} instead.")
        if not isinstance(self.name, str):
            raise InputTypeError(f"The 'name' parameter of GroundMotionPair must be a str. "
                                 f"Got {self.name!r} instead.")
        _check_steps(self.name, self.roles())
        first_role, first = self.roles()[0]
        for role, motion in self.roles()[1:]:
            if motion.npts != first.npts:
                longer, shorter = (first_role, first), (role, motion)
                if motion.npts > first.npts:
                    longer, shorter = shorter, longer
                extra = longer[1].npts - shorter[1].npts
                raise InputError(
                    f"Pair {self.name!r}: the {_label(*longer)} has {longer[1].npts} samples, "
                    f"{extra} more than the {_label(*shorter)} with {shorter[1].npts}; the "
                    f"components of a pair must have one length. Truncate to the shorter with "
                    f"GroundMotionPair.truncated_to_common(x, y[, z]) (read_pair(..., "
                    f"truncate=True)) if they start together."
                )

    def roles(self) -> tuple[tuple[str, GroundMotion], ...]:
        """``(("x", x), ("y", y)[, ("z", z)])``: the components with their roles."""
        out = (("x", self.x), ("y", self.y))
        return out if self.z is None else (*out, ("z", self.z))

    def __iter__(self) -> Iterator[GroundMotion]:
        """The components x, y (and z)."""
        return (motion for _, motion in self.roles())

    def __repr__(self) -> str:
        vertical = "" if self.z is None else f", pga_z={self.z.pga:.4g}"
        return (f"GroundMotionPair(name={self.name!r}, npts={self.npts}, dt={self.dt:g} s, "
                f"pga_x={self.x.pga:.4g}, pga_y={self.y.pga:.4g}{vertical} m/s^2)")

    @property
    def dt(self) -> float:
        """Time step [s] (that of ``x``; the others agree to 1e-9)."""
        return self.x.dt

    @property
    def npts(self) -> int:
        """Number of samples of each component [-]."""
        return self.x.npts

    @property
    def duration(self) -> float:
        """Time of the last sample [s]."""
        return self.x.duration

    @property
    def has_vertical(self) -> bool:
        """Whether the pair carries a vertical component."""
        return self.z is not None

    @classmethod
    def truncated_to_common(cls, x: GroundMotion, y: GroundMotion,
                            z: GroundMotion | None = None, name: str = "") -> GroundMotionPair:
        """A pair of components of one time step, each cut to the shortest one's samples (the cut
        recorded in its ``processing``). They must start together: nothing here can check that."""
        motions = {"x": x, "y": y} if z is None else {"x": x, "y": y, "z": z}
        for role, motion in motions.items():
            if not isinstance(motion, GroundMotion):
                raise InputTypeError(f"The {role!r} parameter of GroundMotionPair."
                                     f"truncated_to_common must be a GroundMotion. "
                                     f"Got {motion!r} instead.")
        _check_steps(name, tuple(motions.items()))
        n = min(m.npts for m in motions.values())
        cut = {role: m if m.npts == n else m.derived(
                   m.acceleration[:n], f"truncated to the pair's common {n} samples")
               for role, m in motions.items()}
        return cls(cut["x"], cut["y"], cut.get("z"), name)

    def _each(self, operation: Callable[[GroundMotion], GroundMotion]) -> GroundMotionPair:
        """The pair of ``operation`` applied to every component (the vertical included)."""
        z = None if self.z is None else operation(self.z)
        return GroundMotionPair(operation(self.x), operation(self.y), z, self.name)

    def scaled(self, factor: float) -> GroundMotionPair:
        """The pair with every component (vertical included) multiplied by ``factor`` [-]."""
        k = check_real(factor, "factor", "GroundMotionPair.scaled")
        return self._each(lambda motion: motion.scaled(k))

    def truncated(self, duration: float) -> GroundMotionPair:
        """The first ``duration`` [s], in [dt, self.duration], of every component."""
        d = check_real(duration, "duration", "GroundMotionPair.truncated", low=self.dt,
                       high=self.duration)
        return self._each(lambda motion: motion.truncated(d))

    def resampled(self, dt: float, *, anti_alias: bool = True) -> GroundMotionPair:
        """Every component at the time step ``dt`` [s] (`groundmotions.processing.resampled`)."""
        return self._each(lambda motion: motion.resampled(dt, anti_alias=anti_alias))

    def rotated(self, angle_deg: float) -> GroundMotionPair:
        """The horizontal components along axes turned by ``angle_deg`` [deg] counter-clockwise:
        ``x' = cos(a) x + sin(a) y``, ``y' = -sin(a) x + cos(a) y``; the vertical is kept."""
        a = check_real(angle_deg, "angle_deg", "GroundMotionPair.rotated")
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        ax, ay = self.x.acceleration, self.y.acceleration
        step = f"pair axes rotated by {a:g} deg"
        return GroundMotionPair(self.x.derived(c * ax + s * ay, step),
                                self.y.derived(-s * ax + c * ay, step), self.z, self.name)


def _check_steps(name: str, roles: tuple[tuple[str, GroundMotion], ...]) -> None:
    first_role, first = roles[0]
    for role, motion in roles[1:]:
        if abs(motion.dt - first.dt) > _DT_TOLERANCE * max(first.dt, motion.dt):
            raise InputError(
                f"Pair {name!r}: the {_label(first_role, first)} has dt = {first.dt:g} s but "
                f"the {_label(role, motion)} has dt = {motion.dt:g} s; the components of a "
                f"pair must have one time step. Resample one to the other's step first "
                f"({role}.resampled({first.dt:g}), or read_pair(..., resample_to={first.dt:g})); "
                f"GroundMotionPair.resampled(dt) then changes the step of the whole pair."
            )


def _read_component(path: Path, role: str, pair: str, dt: float | None,
                    units: str | None, where: str) -> GroundMotion:
    """One component file; ``where`` (``"<manifest>, line <n>"`` or "") starts the message."""
    start = f"{where}, column {role!r}: pair {pair!r}" if where else f"Pair {pair!r}"
    if not path.is_file():
        raise InputError(f"{start}: the {role} component file {str(path)!r} does not exist.")
    try:
        return read_record(path, dt=dt, units=units)
    except InputError as error:
        hint = ""
        if "'dt' parameter" in str(error):
            hint = (" (give the step of one-column records with read_pair(..., dt=...) or a "
                    "'dt' column in a pair manifest)")
        raise InputError(f"{start}: the {role} component cannot be used: {error}{hint}"
                         ) from error


def _pair_name(x: Path, y: Path) -> str:
    n = 0  # the stems' common start, character by character
    while n < min(len(x.stem), len(y.stem)) and x.stem[n] == y.stem[n]:
        n += 1
    return x.stem[:n].rstrip("-_. ") or f"{x.stem}+{y.stem}"


def read_pair(
    x_path: PathLike, y_path: PathLike, z_path: PathLike | None = None, *,
    name: str | None = None, dt: float | None = None, units: str | None = None,
    resample_to: float | None = None, truncate: bool = False,
) -> GroundMotionPair:
    """Read a pair (and optionally a vertical) from two or three record files.

    Parameters
    ----------
    x_path, y_path, z_path : str or path-like
        The horizontal components and the optional vertical, each read by `read_record` (PEER
        .AT2 or text).
    name : str, optional
        The pair's name; by default the common start of the file stems (``CHY023-N``,
        ``CHY023-W`` -> ``CHY023``).
    dt, units : optional
        Time step of one-column text records [s] and units of files whose header states none,
        passed to `read_record`.
    resample_to : float, optional
        Resample (anti-aliased) every component whose step differs to this step [s].
    truncate : bool
        Cut the components to the shortest one (they must start together).

    Raises
    ------
    InputError
        A missing file or a component that cannot be read (naming the component and the file), or
        components of different steps or lengths.
    """
    paths = {"x": Path(check_path(x_path, "x_path", "read_pair")),
             "y": Path(check_path(y_path, "y_path", "read_pair"))}
    if z_path is not None:
        paths["z"] = Path(check_path(z_path, "z_path", "read_pair"))
    label = name if name is not None else _pair_name(paths["x"], paths["y"])
    return _read_pair(paths, label, dt, units, resample_to, truncate, "")


def _read_pair(paths: dict[str, Path], name: str, dt: float | None, units: str | None,
               resample_to: float | None, truncate: bool, where: str) -> GroundMotionPair:
    motions = {role: _read_component(p, role, name, dt, units, where)
               for role, p in paths.items()}
    if resample_to is not None:
        step = check_real(resample_to, "resample_to", "read_pair", low=0.0, low_open=True)
        motions = {role: m if abs(m.dt - step) <= _DT_TOLERANCE * step else m.resampled(step)
                   for role, m in motions.items()}
    try:
        if truncate:
            return GroundMotionPair.truncated_to_common(motions["x"], motions["y"],
                                                        motions.get("z"), name)
        return GroundMotionPair(motions["x"], motions["y"], motions.get("z"), name)
    except InputError as error:
        if not where:
            raise
        raise InputError(f"{where}: {error}") from error


class ManifestRow(NamedTuple):
    """One pair of a manifest, checked but not read (`manifest_rows`): its ``name``, its
    component ``files`` by role (``x``, ``y``, ``z`` when given; paths from the current folder),
    ``dt`` of one-column text records [s] and ``units`` of files whose header states none (or None),
    and ``where``, ``"<manifest>, line <n>"``, which starts the messages about the row."""

    name: str
    files: dict[str, Path]
    dt: float | None
    units: str | None
    where: str


MAX_MANIFEST_BYTES = 10 * 2**20
"""Largest pair manifest read [bytes] (some hundred thousand pairs)."""


def manifest_rows(path: PathLike) -> tuple[ManifestRow, ...]:
    """The rows of a pair manifest (`read_pair_manifest`), checked without reading a component;
    a bad manifest raises `InputError` starting with ``"<manifest>, line <n>"`` and naming the
    column."""
    path = Path(path)
    if not path.is_file():
        what = ("is not a regular file (a folder, a device or a pipe)" if path.exists()
                else "does not exist")
        raise InputError(f"The pair manifest {str(path)!r} {what}.")
    if path.stat().st_size > MAX_MANIFEST_BYTES:
        raise InputError(f"{path.name}: {path.stat().st_size:,} bytes, more than the "
                         f"{MAX_MANIFEST_BYTES:,} of a pair manifest; is it one?")
    try:
        with open(path, newline="", encoding="utf-8-sig") as handle:
            lines = [(n, line) for n, line in enumerate(handle.read().splitlines(), start=1)
                     if line.strip() and not line.lstrip().startswith("#")]
    except UnicodeDecodeError as error:
        raise InputError(f"{path.name}: not a UTF-8 CSV pair manifest ({error}).") from None
    if not lines:
        raise InputError(f"{path.name}: the pair manifest is empty; it needs a header row "
                         f"naming the columns name, x, y (and optionally z, dt, units).")
    rows = list(csv.reader(line for _, line in lines))
    header_line, header = lines[0][0], [cell.strip() for cell in rows[0]]
    where = f"{path.name}, line {header_line}: the header"
    for column in header:
        if column not in MANIFEST_COLUMNS:
            raise InputError(f"{where} names an unknown column {column!r}; the columns of a "
                             f"pair manifest are {', '.join(MANIFEST_COLUMNS)}.")
    for column in ("name", "x", "y"):
        if column not in header:
            raise InputError(f"{where}: the required column {column!r} is missing (found "
                             f"{', '.join(header) or 'none'}); a pair manifest needs name, x "
                             f"and y.")
    if len(set(header)) != len(header):
        repeated = next(c for c in header if header.count(c) > 1)
        raise InputError(f"{where}: the column {repeated!r} appears twice.")
    found: list[ManifestRow] = []
    seen: dict[str, int] = {}
    for (number, _), cells in zip(lines[1:], rows[1:], strict=True):
        where = f"{path.name}, line {number}"
        if len(cells) != len(header):
            raise InputError(f"{where}: expected {len(header)} cells ({', '.join(header)}) "
                             f"but found {len(cells)}.")
        row = {column: cell.strip() for column, cell in zip(header, cells, strict=True)}
        for column in ("name", "x", "y"):
            if not row[column]:
                raise InputError(f"{where}, column {column!r}: the cell is empty.")
        if row["name"] in seen:
            raise InputError(f"{where}, column 'name': the pair {row['name']!r} is already "
                             f"named on line {seen[row['name']]}.")
        seen[row["name"]] = number
        step = None
        if row.get("dt"):
            try:
                step = float(row["dt"])
            except ValueError:
                step = math.nan
            if not (step > 0.0 and math.isfinite(step)):
                raise InputError(f"{where}, column 'dt': the time step must be a number in "
                                 f"(0, inf) [s]. Got {row['dt']!r} instead.")
        files = {role: path.parent / row[role] for role in ("x", "y", "z") if row.get(role)}
        found.append(ManifestRow(row["name"], files, step, row.get("units") or None, where))
    if not found:
        raise InputError(f"{path.name}: the pair manifest lists no pairs (only a header).")
    return tuple(found)


def read_pair_manifest(path: PathLike) -> tuple[GroundMotionPair, ...]:
    """Read every pair listed in a CSV manifest, in the order of the rows: a header row naming
    the columns ``name``, ``x``, ``y`` (required), ``z`` (vertical), ``dt`` (of one-column text
    records [s]) and ``units`` (of files whose header states none; the last three may be empty),
    paths relative to the manifest's folder; blank lines and ``#`` lines are skipped.

    Raises
    ------
    InputError
        A bad manifest (`manifest_rows`), a missing or unreadable file or a bad pair: the message
        starts with ``"<manifest>, line <n>"`` and names the column or the component.
    """
    check_path(path, "path", "read_pair_manifest")
    return tuple(_read_pair(row.files, row.name, row.dt, row.units, None, False, row.where)
                 for row in manifest_rows(path))
