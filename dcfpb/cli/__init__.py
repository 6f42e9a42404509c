"""The ``dcfpb`` command line: parses, calls the library, prints and plots.

One module per sub-command, each with ``register(subparsers)`` and its handler:

- :mod:`~dcfpb.cli.protocol`: a virtual bearing test and its per-cycle characteristics;
- :mod:`~dcfpb.cli.run`: a building file under a recorded ground motion (and what the other
  building commands share: inputs, integrator flags, the peaks table);
- :mod:`~dcfpb.cli.demo`: the main job on bundled data, three friction models and the fixed base;
- :mod:`~dcfpb.cli.spectrum`, :mod:`~dcfpb.cli.suite`, :mod:`~dcfpb.cli.opensees`,
  :mod:`~dcfpb.cli.diagnose`.

Parsing one of the light commands (:data:`OWN_COMMANDS`) registers those three only, so that
it does not import the others' modules (``dcfpb diagnose`` alone costs about 2 s of imports);
``dcfpb --help`` and the other commands see them all.

Exit status: 0 for success, 1 for a run that failed on its own terms
(:class:`dcfpb.common.errors.RunFailure`, or a run that stopped early), 2 for bad input.
Errors print as one line ``dcfpb <command>: error: <message>`` on stderr, and warnings (e.g.
a building-file setting without effect, :class:`dcfpb.common.errors.InputWarning`) as
``dcfpb <command>: warning: <message>``.
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
    """The argument parser of the ``dcfpb`` command.

    ``modules=False`` leaves out the sub-commands of :data:`COMMAND_MODULES` (and their
    imports): enough to parse one of :data:`OWN_COMMANDS`.
    """
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
    except RunFailure as error:  # good input, a run that cannot finish; caught first, as
        print(f"dcfpb {args.command}: run failed: {error}", file=sys.stderr)  # a capacity
        return 1  # failure is a ValueError too
    except (ValueError, TypeError, OSError) as error:
        print(f"dcfpb {args.command}: error: {error}", file=sys.stderr)
        return 2
    finally:
        warnings.formatwarning = shown


def console() -> None:
    """The ``dcfpb`` program (console script and ``python -m dcfpb.cli``): :func:`main` on the
    command line's arguments, then the process exits with its status.

    The garbage collector runs less often (``gc.set_threshold(50_000, 20, 20)`` instead of
    700, 10, 10): numba's compilation on a cold cache allocates millions of objects, and the
    default thresholds spent about 1.5 s of a first run walking them (0.4 s after the change),
    while a short-lived program gains nothing from collecting cycles early. Before exiting,
    every object left is frozen out of the garbage collector (``gc.freeze``):
    the interpreter's teardown would otherwise walk them all in a last collection (numba's
    compiled engine, xarray and matplotlib make that about 0.4 to 1 s after ``dcfpb demo``)
    to free memory the operating system takes back anyway. Output is flushed and ``atexit``
    handlers run as usual.
    """
    gc.set_threshold(*PROGRAM_GC_THRESHOLDS)
    status = main()
    gc.freeze()
    sys.exit(status)


def _warning_line(command: str):
    """``warnings.formatwarning`` for the command line: one line, ``dcfpb <command>: warning:
    <message>``, the category named unless it is one of ours (an ``InputWarning``)."""

    def line(message, category, filename, lineno, text=None) -> str:
        from dcfpb.common.errors import InputWarning

        kind = "" if issubclass(category, InputWarning) else f" ({category.__name__})"
        return f"dcfpb {command}: warning: {message}{kind}\n"

    return line
