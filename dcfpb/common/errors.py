"""The project's exceptions: bad input (exit status 2) and a run that fails on its own terms
(exit status 1). The module imports nothing of the project.

Every error a user can cause derives from :class:`InputError`, a ``ValueError`` (so code written
against the standard exceptions catches it): records
(:class:`groundmotions.records.RecordFormatError`), building files
(:class:`structures.config.ConfigError`), bearing-test data
(:class:`isolator.diagnosis.data.DataError`) and the parameters checked by
:mod:`dcfpb.common.validation`. A run with good input that cannot finish (a bearing past its
displacement capacity, a run past its time limit) raises :class:`RunFailure`.
"""

from __future__ import annotations

EXIT_OK = 0
"""Exit status of a command that finished."""
EXIT_RUN_FAILED = 1
"""Exit status of a run that failed on its own terms (:class:`RunFailure`)."""
EXIT_BAD_INPUT = 2
"""Exit status of bad input: a file, a flag or a value outside its allowed range."""
EXIT_INTERNAL_ERROR = 3
"""Exit status of an internal error: anything but bad input or a run failure (a bug); the
command line writes its traceback to a log file (:mod:`dcfpb.cli`)."""


class InputError(ValueError):
    """Bad input: the message names the file, field or parameter and what is allowed."""


class InputTypeError(InputError, TypeError):
    """Bad input of the wrong kind (a string where a number belongs): an :class:`InputError`
    that is also a ``TypeError``, as Python's own checks of a kind raise."""


class RunFailure(RuntimeError):
    """A run with good input that cannot finish; the message says why and when.

    Raised inside a time integration (by the model or by the ``on_commit`` hook), it ends the run
    with ``success=False`` and the message, keeping the steps already committed
    (:func:`structures.integrators.integrate`). ``kind`` names the reason for tables:
    ``"capacity"``, ``"timeout"``, ``"model"`` ...
    """

    kind = "error"


class CapacityExceeded(RunFailure, ValueError):
    """A bearing pushed past its displacement capacity, or past the range its model covers
    (the precise model's monitor line, the spherical law's radius). Also a ``ValueError``, which
    callers of the element catch.

    ``message`` says what was exceeded, by which displacement [m], at what time [s]; ``kind`` is
    ``"capacity"`` (beyond the displacement capacity) or ``"model"`` (within it, but beyond the
    model's range, e.g. a monitor line shorter than the capacity).
    """

    def __init__(self, message: str, kind: str = "capacity") -> None:
        super().__init__(message)
        self.kind = kind


class TimeLimitExceeded(RunFailure):
    """A run past its wall-clock time limit."""

    kind = "timeout"


class InputWarning(UserWarning):
    """A value given that does not apply, or is replaced, where the run goes on regardless; the
    message names it and what is used instead."""
