"""The ``dcfpb`` command line: parses, calls the library, prints and plots.

One module per sub-command, each with ``register(subparsers)`` and its handler:
:mod:`~dcfpb.cli.protocol` (a virtual bearing test), :mod:`~dcfpb.cli.run` (a building file
under a ground motion, and what the other building commands share), :mod:`~dcfpb.cli.demo`
(the bundled example), :mod:`~dcfpb.cli.spectrum`, :mod:`~dcfpb.cli.suite`,
:mod:`~dcfpb.cli.opensees` and :mod:`~dcfpb.cli.diagnose`. Parsing one of the light commands
(:data:`OWN_COMMANDS`) imports none of the other modules.

Exit status: 0 for success, 1 for a run that failed on its own terms
(:class:`dcfpb.common.errors.RunFailure`, or a run that stopped early), 2 for bad input. An
error prints as one line ``dcfpb <command>: error: <message>`` on stderr, a warning
(:class:`dcfpb.common.errors.InputWarning`) as ``dcfpb <command>: warning: <message>``.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import sys
import warnings
from collections.abc import Sequence

from dcfpb import __version__
from dcfpb.common.errors import RunFailure

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
    "dcfpb.cli.diagnose",
)
"""Modules with a ``register(subparsers)`` function adding further sub-commands."""


def build_parser(*, modules: bool = True) -> argparse.ArgumentParser:
    """The argument parser of the ``dcfpb`` command; ``modules=False`` leaves out the
    sub-commands of :data:`COMMAND_MODULES` and their imports (enough for :data:`OWN_COMMANDS`)."""
    parser = argparse.ArgumentParser(
        prog="dcfpb",
        description="Time-history analysis of buildings on double concave friction pendulum "
        "bearings.",
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
        return 1
    except (ValueError, TypeError, OSError) as error:
        print(f"dcfpb {args.command}: error: {error}", file=sys.stderr)
        return 2
    finally:
        warnings.formatwarning = shown


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
