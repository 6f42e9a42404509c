"""Output paths checked before any work starts, so that a bad one does not lose a run.

Every command calls :func:`check_outputs` on its output flags first. A file (``--output``,
``--plot FILE.png``) or a folder (``--plot DIR``, ``--report``, ``--out``) is accepted when:

- a file is not a folder, and an existing one is writable; a folder is not a file;
- the folder it goes in (a folder: itself) exists, or can be made: its nearest existing
  ancestor is a folder and every missing name fits the file system;
- that folder takes a temporary file, created and removed (an access-rights check alone says
  yes to root on a read-only file system, /proc or /sys), and so does a new file's own name;
- a figure's name ends in a format matplotlib writes, or in none (PNG); a data file's name ends
  in a suffix of a format the command writes (``--output run.nc``; ``run.csv`` is refused);
- it is none of the command's inputs (the record, the building file, a manifest: compared with
  :func:`os.path.samefile`), nor is any file the command writes into a folder output;
- it does not exist, nor does any file the command writes into a folder output, unless
  ``--overwrite`` is given; a suite's folder holding a suite's state is resumed
  (:func:`check_suite_folder`).

The files themselves are written atomically (:func:`dcfpb.common.files.atomic_output`), so a
failed write leaves an earlier file whole.

A folder asked for is left to its writer to make; the missing folders above a file are made once
checked, since the file writers (netCDF, CSV, a figure) do not make them. A bad path raises
:class:`dcfpb.common.errors.InputError` naming the flag and the path (exit status 2).
"""

from __future__ import annotations

import errno
import os
import stat
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from dcfpb.common.errors import InputError, RunFailure

__all__ = ["FIGURE_FORMATS", "PLAN_FIGURES", "REPORT_FILES", "RUN_FIGURES", "SUITE_FILES",
           "check_output_dir", "check_output_file", "check_outputs", "check_suite_folder",
           "writing"]

FIGURE_FORMATS = frozenset({"png", "pdf", "svg", "svgz", "jpg", "jpeg", "eps", "ps", "tif",
                            "tiff", "webp", "pgf", "raw", "rgba", "avif"})
"""File suffixes a figure may have (matplotlib's Agg, PDF, SVG and PS back ends)."""


def _refuse(flag: str, path: object, why: str) -> InputError:
    return InputError(f"{flag} {path}: {why}")


def _as_path(path: str | os.PathLike, flag: str) -> Path:
    text = os.fspath(path)
    if not text or not str(text).strip():
        raise _refuse(flag, repr(text), "an empty path; give a file or folder name.")
    if "\0" in str(text):
        raise _refuse(flag, repr(text), "the path holds a NUL character.")
    return Path(text)


def _try_folder(folder: Path, flag: str, path: Path) -> None:
    """Create and remove a temporary file in ``folder``; refuse when that fails."""
    try:
        handle, name = tempfile.mkstemp(prefix=".dcfpb-check-", dir=folder)
    except OSError as error:
        raise _refuse(flag, path, f"cannot write in the folder {folder} "
                      f"({error.strerror or error}).") from None
    os.close(handle)
    os.unlink(name)


def _name_max(folder: Path) -> int:
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        return 255


def _kind(path: Path, flag: str, shown: Path) -> str:
    """``"dir"``, ``"file"`` (anything else that exists) or ``"missing"``; refuses a path the
    system will not look at (a name too long, no access)."""
    try:
        return "dir" if stat.S_ISDIR(os.stat(path).st_mode) else "file"
    except (FileNotFoundError, NotADirectoryError):
        return "missing"
    except OSError as error:
        why = ("a name in it is longer than the file system allows."
               if error.errno == errno.ENAMETOOLONG else
               f"cannot be looked at ({error.strerror or error}).")
        raise _refuse(flag, shown, why) from None


def _existing_ancestor(path: Path, flag: str, shown: Path) -> Path:
    """The nearest existing ancestor of ``path`` (a folder), the missing names checked."""
    missing = []
    folder = path.absolute()
    while folder != folder.parent and _kind(folder, flag, shown) == "missing":
        missing.append(folder.name)
        folder = folder.parent
    if not folder.is_dir():
        raise _refuse(flag, shown, f"{folder} is a file, not a folder, so nothing can be "
                      "written under it.")
    longest = _name_max(folder)
    for name in missing:
        if len(os.fsencode(name)) > longest:
            raise _refuse(flag, shown, f"the name {name[:40]}... is longer than the "
                          f"{longest} bytes the file system allows.")
    return folder


def check_output_dir(path: str | os.PathLike, flag: str) -> Path:
    """``path``, checked to be a folder that exists and is writable, or can be made; an
    :class:`~dcfpb.common.errors.InputError` naming ``flag`` (the option, e.g. ``"--out"``) and the
    path refuses a file in its place, a folder under a file, no write access or a name too long."""
    folder = _as_path(path, flag)
    if _kind(folder, flag, folder) == "file":
        raise _refuse(flag, folder, "is a file, not a folder; give a folder.")
    _try_folder(_existing_ancestor(folder, flag, folder), flag, folder)
    return folder


def check_output_file(path: str | os.PathLike, flag: str, *, figure: bool = False) -> Path:
    """``path``, checked to be a file that can be written (created, or overwritten).

    ``flag`` is the option that named it (e.g. ``"--output"``); with ``figure`` its suffix must be
    one of :data:`FIGURE_FORMATS`, or none. An :class:`~dcfpb.common.errors.InputError` naming
    ``flag`` and the path refuses a folder in its place, a folder above it that is a file or not
    writable, a read-only file, a name too long or an unknown figure format. The missing folders
    above the file are made once the nearest existing one proved writable.
    """
    file = _as_path(path, flag)
    kind = _kind(file, flag, file)
    if kind == "dir" or str(path).endswith(("/", os.sep)):
        raise _refuse(flag, file, "is a folder; give a file name.")
    suffix = file.suffix.lower().lstrip(".")
    if figure and suffix and suffix not in FIGURE_FORMATS:
        raise _refuse(flag, file, f"a figure cannot be written as .{suffix}; use one of "
                      f"{', '.join(sorted(FIGURE_FORMATS))}.")
    folder = _existing_ancestor(file.parent, flag, file)
    _try_folder(folder, flag, file)
    if kind == "file":
        if not os.access(file, os.W_OK):
            raise _refuse(flag, file, "exists and cannot be overwritten (no write access).")
    else:  # make the missing folders, try the very name, then remove it
        try:
            file.parent.mkdir(parents=True, exist_ok=True)
            os.close(os.open(file, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600))
        except FileExistsError:
            return file  # made meanwhile by someone else: it can be named, at least
        except OSError as error:
            why = ("the name is longer than the file system allows."
                   if error.errno == errno.ENAMETOOLONG else
                   f"cannot be created ({error.strerror or error}).")
            raise _refuse(flag, file, why) from None
        file.unlink()
    return file


RUN_FIGURES = ("isolator_hysteresis.png", "temperature.png", "roof_acceleration.png",
               "storey_drift.png", "response_histories.png", "floor_spectra.png",
               "isolation_effect.png")
"""The files :func:`dcfpb.plotting.plot_runs` writes for runs in one direction."""

PLAN_FIGURES = (*RUN_FIGURES, "bearing_orbits.png", "force_orbits.png", "plate_temperature.png")
"""The files :func:`dcfpb.plotting.plot_runs` may write for runs in plan."""

REPORT_FILES = ("summary.md", "diagnosis.json", "loops.png", "residual_breakdown.png",
                "candidates.png", "cycle_errors.png", "residual_history.png")
"""The files :func:`isolator.diagnosis.report.write_report` writes (``dcfpb diagnose
--report``)."""

SUITE_FILES = ("peaks.csv", "failures.json", "summary.csv", "summary.parquet", "suite.log",
               "plots/peak_distributions.png", "plots/scaled_spectra.png")
"""The files a suite writes at the top of its folder (besides ``runs/``, its own state)."""

SUITE_STATE = ("runs", "suite.log")
"""What makes a folder a suite folder, resumed by running the same suite into it again."""


def _same(a: Path, b: object) -> bool:
    """Whether ``a`` and the input ``b`` are one file (both exist; hard and symbolic links
    count)."""
    try:
        return os.path.samefile(a, os.fspath(b))
    except (OSError, TypeError, ValueError):
        return False


def _inputs(inputs: dict[str, object] | None) -> list[tuple[str, object]]:
    """(label, path) of every input given; a label's value may be a path or a list of them."""
    found = []
    for label, value in (inputs or {}).items():
        values = value if isinstance(value, list | tuple) else [value]
        found += [(label, v) for v in values if v is not None and os.fspath(v)]
    return found


def _check_format(flag: str, file: Path, formats: dict[str, str]) -> None:
    suffix = file.suffix.lower()
    if suffix not in formats:
        allowed = ", ".join(f"{ext} ({kind})" for ext, kind in formats.items())
        given = f"the suffix {file.suffix!r}" if file.suffix else "no suffix"
        raise _refuse(flag, file, f"{given} is not a format this command writes; the format "
                      f"follows the suffix, one of: {allowed}.")


def _check_not_input(flag: str, file: Path, inputs: list[tuple[str, object]]) -> None:
    for label, source in inputs:
        if _same(file, source):
            raise _refuse(flag, file, f"is {label} {source}, an input of this command; writing "
                          f"it would destroy it. Give another {flag}.")


def _check_file_target(flag: str, file: Path, inputs: list[tuple[str, object]],
                       overwrite: bool) -> None:
    _check_not_input(flag, file, inputs)
    if os.path.lexists(file) and not overwrite:
        raise _refuse(flag, file, f"exists; give --overwrite to replace it, or another {flag}.")


def _check_folder_target(flag: str, folder: Path, names: tuple[str, ...],
                         inputs: list[tuple[str, object]], overwrite: bool,
                         hint: str = "") -> None:
    for name in names:
        for label, source in inputs:
            if _same(folder / name, source):
                raise _refuse(flag, folder, f"this command writes {name} in it, which is "
                              f"{label} {source}, an input of this command; writing it would "
                              f"destroy it. Give another {flag}.")
    if overwrite:
        return
    there = [name for name in names if os.path.lexists(folder / name)]
    if there:
        shown = ", ".join(there[:4]) + (f" and {len(there) - 4} more" if len(there) > 4 else "")
        raise _refuse(flag, folder, f"holds {shown} from before, which this command writes; "
                      f"give --overwrite to replace them, or another {flag}.{hint}")


def check_outputs(files: dict[str, object] | None = None,
                  folders: dict[str, object] | None = None,
                  figures: dict[str, object] | None = None, *,
                  inputs: dict[str, object] | None = None, overwrite: bool = False,
                  formats: dict[str, dict[str, str]] | None = None,
                  writes: dict[str, tuple[str, ...]] | None = None) -> None:
    """Check the output paths a command was given, keyed by flag, before any work.

    Parameters
    ----------
    files, figures, folders : dict of str to path or None
        Data files, figures and folders by flag (``"--output"``); None values are skipped.
    inputs : dict of str to path or list of paths, optional
        The command's input files by what they are (``"the building file"``): an output that
        is one of them (:func:`os.path.samefile`), or a file ``writes`` puts in a folder output
        that is one of them, is refused, ``overwrite`` or not.
    overwrite : bool
        Whether an output file that exists may be replaced (``--overwrite``); without it an
        existing output file, or a file of ``writes`` existing in its folder, is refused.
    formats : dict of str to dict, optional
        Per file flag, the suffixes it may have and the format each writes
        (``{".nc": "netCDF"}``); any other suffix, or none, is refused.
    writes : dict of str to tuple of str, optional
        Per folder flag, the names of the files the command writes in it.

    Raises
    ------
    dcfpb.common.errors.InputError
        Naming the flag, the path and why (exit status 2 on the command line).
    """
    sources = _inputs(inputs)
    for figure, outputs in ((False, files), (True, figures)):
        for flag, path in (outputs or {}).items():
            if path is not None:
                _check_not_input(flag, _as_path(path, flag), sources)  # before it is probed
                file = check_output_file(path, flag, figure=figure)
                if formats and flag in formats:
                    _check_format(flag, file, formats[flag])
                _check_file_target(flag, file, sources, overwrite)
    for flag, path in (folders or {}).items():
        if path is not None:
            folder = check_output_dir(path, flag)
            _check_folder_target(flag, folder, tuple((writes or {}).get(flag, ())), sources,
                                 overwrite)


def check_suite_folder(path: str | os.PathLike, flag: str, *,
                       inputs: dict[str, object] | None = None, overwrite: bool = False) -> Path:
    """Check a suite's result folder before any work: a folder holding a suite's state
    (:data:`SUITE_STATE`) is resumed; a folder that is not one but holds files the suite writes
    (:data:`SUITE_FILES`) is refused without ``overwrite``; an input among those files is
    refused always. Returns the folder."""
    folder = check_output_dir(path, flag)
    sources = _inputs(inputs)
    resumed = any(os.path.lexists(folder / name) for name in SUITE_STATE)
    hint = (" A suite folder (one holding runs/ or suite.log) is resumed by running the same "
            "suite into it again.")
    _check_folder_target(flag, folder, SUITE_FILES, sources, overwrite or resumed, hint)
    return folder


@contextmanager
def writing(flag: str, path: object) -> Iterator[None]:
    """Write the output of ``flag`` (``path``) in this block: an ``OSError`` of the writing (a
    full disk, a folder removed meanwhile) becomes a :class:`~dcfpb.common.errors.RunFailure`
    naming the flag and the path (exit status 1: the input was good). The writers are atomic
    (:func:`dcfpb.common.files.atomic_output`), so a file there before is left whole."""
    try:
        yield
    except OSError as error:
        raise RunFailure(f"{flag} {path}: the output could not be written "
                         f"({error.strerror or error}); a file there before is left as it "
                         "was.") from error
