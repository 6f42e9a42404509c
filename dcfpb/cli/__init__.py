"""The ``dcfpb`` command line: parses, calls the library, prints and plots.

One module per sub-command, each with ``register(subparsers)`` and its handler:
:mod:`~dcfpb.cli.protocol` (a virtual bearing test), :mod:`~dcfpb.cli.run` (a building file
under a ground motion, and what the other building commands share), :mod:`~dcfpb.cli.demo`
(the bundled example), :mod:`~dcfpb.cli.spectrum`, :mod:`~dcfpb.cli.suite`,
:mod:`~dcfpb.cli.opensees`, :mod:`~dcfpb.cli.diagnose`, :mod:`~dcfpb.cli.design` (a Chapter 17
analysis and its report) and :mod:`~dcfpb.cli.prototype` (the virtual prototype test of 17.8).
Parsing one of the light commands
(:data:`OWN_COMMANDS`) imports none of the other modules.

Exit status (:data:`EXIT_STATUSES`, also in ``dcfpb --help``):

0
    success.
1
    a run that failed on its own terms (:class:`dcfpb.common.errors.RunFailure`, or a run that
    stopped early): ``dcfpb <command>: run failed: <message>`` with the time and the cause.
2
    bad input: an :class:`dcfpb.common.errors.InputError` (the message names the flag, key,
    column or file), an argparse error, or a file or folder given on the command line that is
    missing, unreadable or of the wrong kind (:data:`USER_PATH_ERRORS`: ``FileNotFoundError``,
    ``PermissionError``, ``IsADirectoryError``, ``NotADirectoryError``, ``FileExistsError``):
    ``dcfpb <command>: error: <message>`` naming the flag. Such an error about a path the user
    did not give is an internal error.
3
    an internal error, anything else (a plain ``ValueError``, ``TypeError``, ``IndexError``, a
    numba error: a bug): ``dcfpb <command>: internal error: <one line>; please report it ...
    with the log <path>``, the full traceback written to that log (:func:`internal_error_log`).

A warning (:class:`dcfpb.common.errors.InputWarning`) prints as ``dcfpb <command>: warning:
<message>``.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import os
import sys
import time
import traceback
import warnings
from collections.abc import Sequence
from pathlib import Path

from dcfpb import __version__
from dcfpb.common.errors import (
    EXIT_BAD_INPUT,
    EXIT_INTERNAL_ERROR,
    EXIT_RUN_FAILED,
    InputError,
    RunFailure,
)

__all__ = ["build_parser", "console", "main"]


PROGRAM_GC_THRESHOLDS = (50_000, 20, 20)
"""The garbage collector's thresholds in the ``dcfpb`` program (see :func:`console`)."""

OWN_COMMANDS = {"protocol": "dcfpb.cli.protocol", "run": "dcfpb.cli.run",
                "demo": "dcfpb.cli.demo"}
"""The light sub-commands and their modules: parsing one of them imports no other module."""

COMMAND_MODULES: tuple[str, ...] = (
    "dcfpb.cli.spectrum",
    "dcfpb.cli.suite",
    "dcfpb.cli.opensees",
    "dcfpb.cli.design",
    "dcfpb.cli.prototype",
    "dcfpb.cli.diagnose",
)
"""Modules with a ``register(subparsers)`` function adding further sub-commands."""

EXIT_STATUSES = """exit status:
  0  success
  1  a run failed on its own terms (capacity, time limit, no convergence): the time and cause
     are printed, with the peaks up to the failure
  2  bad input: the message names the flag, key, column or file and what is allowed
  3  internal error (a bug): one line on stderr and the full traceback in a log file whose
     path is printed; please report it"""
"""The exit statuses as the ``dcfpb --help`` epilog shows them."""

ISSUES_FALLBACK = "the dcfpb issue tracker"
"""Where to report an internal error when the installed package names no issues URL."""

USER_PATH_ERRORS = (FileNotFoundError, PermissionError, IsADirectoryError, NotADirectoryError,
                    FileExistsError)
"""The operating-system errors that are bad input (exit 2) when about a path given on the
command line (or inside a folder given there)."""


def build_parser(*, modules: bool = True) -> argparse.ArgumentParser:
    """The argument parser of the ``dcfpb`` command; ``modules=False`` leaves out the
    sub-commands of :data:`COMMAND_MODULES` and their imports (enough for :data:`OWN_COMMANDS`)."""
    parser = argparse.ArgumentParser(
        prog="dcfpb",
        description="Time-history analysis of buildings on double concave friction pendulum "
        "bearings.",
        epilog=EXIT_STATUSES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"dcfpb {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    for module in (*OWN_COMMANDS.values(), *(COMMAND_MODULES if modules else ())):
        importlib.import_module(module).register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``dcfpb`` console script; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    command = next((a for a in argv if not a.startswith("-")), None)
    own = command in OWN_COMMANDS and argv.index(command) == 0
    parser = build_parser(modules=not own)
    args = parser.parse_args(argv)
    shown = warnings.formatwarning
    warnings.formatwarning = _warning_line(args.command)
    try:
        return args.handler(args)
    except RunFailure as error:  # caught first: a CapacityExceeded is a ValueError too
        print(f"dcfpb {args.command}: run failed: {error}", file=sys.stderr)
        return EXIT_RUN_FAILED
    except InputError as error:
        print(f"dcfpb {args.command}: error: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except USER_PATH_ERRORS as error:
        message = user_path_message(error, argv, vars(args))
        if message is None:
            return _internal_error(args.command, argv)
        print(f"dcfpb {args.command}: error: {message}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except Exception:  # every other exception is a bug: reported, logged
        return _internal_error(args.command, argv)
    finally:
        warnings.formatwarning = shown


def user_path_message(error: OSError, argv: Sequence[str],
                      values: dict | None = None) -> str | None:
    """The message of an operating-system error about a path given on the command line: the
    flag (or the positional argument) that gave it, the path and the reason; None when the
    error is about no path the user gave (an internal error then).

    A path counts as given when it is an argument of ``argv`` (or the value of a
    ``--flag=value``), or lies inside a folder given there (a record of a ``--records`` folder).
    A positional argument is named by its destination in ``values`` (the parsed arguments).
    """
    if error.filename is None:
        return None
    target = _resolved(error.filename)
    reason = error.strerror or type(error).__name__
    for index, token in enumerate(argv):
        flag, _, value = token.partition("=") if token.startswith("--") else ("", "", token)
        if not value or (value.startswith("-") and not flag):
            continue
        given = _resolved(value)
        if target != given and given not in target.parents:
            continue
        if not flag:
            before = argv[index - 1] if index else ""
            flag = before if before.startswith("-") else next(
                (name for name, held in (values or {}).items()
                 if held == value or (isinstance(held, list) and value in held)), "argument")
        inside = "" if target == given else f" (inside {value})"
        return f"{flag} {value}: {reason}: {error.filename}{inside}"
    return None


def _resolved(path) -> Path:
    try:
        return Path(os.fsdecode(path)).expanduser().resolve()
    except (OSError, ValueError, RuntimeError):
        return Path(os.fsdecode(path)).absolute()


def issues_url() -> str:
    """Where to report a bug: the installed package's ``Issues`` (or ``Bug Tracker``,
    ``Source``, ``Homepage``) project URL, else :data:`ISSUES_FALLBACK`."""
    try:
        from importlib.metadata import metadata

        urls = metadata("dcfpb").get_all("Project-URL") or []
    except Exception:  # not installed, broken metadata: the fallback
        urls = []
    found = {}
    for entry in urls:
        label, _, url = entry.partition(", ")
        found[label.strip().lower()] = url.strip().rstrip("/")
    for label in ("issues", "bug tracker"):
        if found.get(label):
            return found[label]
    for label in ("source", "repository", "homepage"):
        if found.get(label):
            url = found[label]
            return f"{url}/issues" if "github.com" in url else url
    return ISSUES_FALLBACK


def log_folder() -> Path:
    """The folder of the internal-error logs: ``$DCFPB_LOG_DIR`` if set, else
    ``$XDG_STATE_HOME/dcfpb`` (``~/.local/state/dcfpb``); the temporary folder when that
    cannot be created."""
    import tempfile

    chosen = os.environ.get("DCFPB_LOG_DIR")
    if chosen:
        candidates = [Path(chosen)]
    else:
        state = os.environ.get("XDG_STATE_HOME") or os.path.join(
            os.path.expanduser("~"), ".local", "state")
        candidates = [Path(state) / "dcfpb"]
    candidates.append(Path(tempfile.gettempdir()))
    for folder in candidates:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            if os.access(folder, os.W_OK):
                return folder
        except OSError:
            continue
    return Path.cwd()


def internal_error_log(command: str, argv: Sequence[str], text: str) -> Path:
    """Write the traceback ``text`` of an internal error of ``dcfpb <command>`` to a new log
    file (:func:`log_folder`, named by the time and process id) with the command line, the
    versions; returns its path."""
    import platform

    stamp = time.strftime("%Y%m%dT%H%M%S")
    path = log_folder() / f"dcfpb-{command}-{stamp}-{os.getpid()}.log"
    header = (f"dcfpb {__version__} internal error, {time.strftime('%Y-%m-%d %H:%M:%S %z')}\n"
              f"command line: dcfpb {' '.join(argv)}\n"
              f"python {platform.python_version()} on {platform.platform()}\n"
              f"working folder: {os.getcwd()}\n\n")
    path.write_text(header + text, encoding="utf-8")
    return path


def _internal_error(command: str, argv: Sequence[str]) -> int:
    """Report the exception being handled as an internal error: one line on stderr naming the
    log that holds its traceback; returns :data:`EXIT_INTERNAL_ERROR`."""
    kind, error, _ = sys.exc_info()
    text = traceback.format_exc()
    first = " ".join(str(error).split()) or "(no message)"
    if len(first) > 300:
        first = first[:297] + "..."
    try:
        where = f"the log {internal_error_log(command, argv, text)}"
    except OSError as log_error:  # no log possible: the traceback goes to stderr instead
        print(text, file=sys.stderr, end="")
        where = f"the traceback above (no log written: {log_error})"
    name = kind.__name__ if kind is not None else "Exception"
    print(f"dcfpb {command}: internal error: {name}: {first}; please report it at "
          f"{issues_url()} with {where}", file=sys.stderr)
    return EXIT_INTERNAL_ERROR


def console() -> None:
    """The ``dcfpb`` program (console script, ``python -m dcfpb.cli``): :func:`main` on the
    command line's arguments, then exit with its status.

    The garbage collector runs at :data:`PROGRAM_GC_THRESHOLDS` rather than (700, 10, 10): numba's
    compilation on a cold cache allocates millions of objects that frequent collections would walk
    again and again, and a short-lived program gains nothing from collecting cycles early. Before
    exit every object left is frozen (``gc.freeze``), so that the interpreter's teardown does not
    walk them all in a last collection to free memory the operating system takes back anyway;
    output is flushed and ``atexit`` handlers run as usual.
    """
    gc.set_threshold(*PROGRAM_GC_THRESHOLDS)
    status = main()
    gc.freeze()
    sys.exit(status)


def _warning_line(command: str):
    """``warnings.formatwarning`` for the command line: one line, ``dcfpb <command>: warning:
    <message>``, with the category named unless it is an ``InputWarning``."""

    def line(message, category, filename, lineno, text=None) -> str:
        from dcfpb.common.errors import InputWarning

        kind = "" if issubclass(category, InputWarning) else f" ({category.__name__})"
        return f"dcfpb {command}: warning: {message}{kind}\n"

    return line
