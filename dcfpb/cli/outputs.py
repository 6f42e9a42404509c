"""Output paths checked before any work starts, so that a bad one does not lose a run.

Every command calls :func:`check_outputs` on its output flags first. A file (``--output``,
``--plot FILE.png``) or a folder (``--plot DIR``, ``--report``, ``--out``) is accepted when:

- a file is not a folder, and an existing one is writable; a folder is not a file;
- the folder it goes in (a folder: itself) exists, or can be made: its nearest existing
  ancestor is a folder and every missing name fits the file system;
- that folder takes a temporary file, created and removed (an access-rights check alone says
  yes to root on a read-only file system, /proc or /sys), and so does a new file's own name;
- a figure's name ends in a format matplotlib writes, or in none (PNG).

A folder asked for is left to its writer to make; the missing folders above a file are made once
checked, since the file writers (netCDF, CSV, a figure) do not make them. A bad path raises
:class:`dcfpb.common.errors.InputError` naming the flag and the path (exit status 2).
"""

from __future__ import annotations

import errno
import os
import stat
import tempfile
from pathlib import Path

from dcfpb.common.errors import InputError

__all__ = ["FIGURE_FORMATS", "check_output_dir", "check_output_file", "check_outputs"]

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


def check_outputs(files: dict[str, object] | None = None,
                  folders: dict[str, object] | None = None,
                  figures: dict[str, object] | None = None) -> None:
    """Check the output paths a command was given, keyed by flag: ``files`` (data files),
    ``figures`` and ``folders``; None values are skipped."""
    for flag, path in (files or {}).items():
        if path is not None:
            check_output_file(path, flag)
    for flag, path in (figures or {}).items():
        if path is not None:
            check_output_file(path, flag, figure=True)
    for flag, path in (folders or {}).items():
        if path is not None:
            check_output_dir(path, flag)
