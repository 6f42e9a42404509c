"""The project's own exceptions: bad input (exit status 2) and a run that fails on its own terms
(exit status 1).

Every error a user can cause derives from :class:`InputError`, itself a ``ValueError`` so that
code written against the standard exceptions keeps working: records
(:class:`groundmotions.records.RecordFormatError`), building files
(:class:`structures.config.ConfigError`), bearing-test data
(:class:`isolator.diagnosis.data.DataError`) and parameters checked by
:mod:`dcfpb.common.validation`.
A run that was given good input but cannot finish (a bearing pushed past its displacement
capacity, a run past its time limit) raises :class:`RunFailure`.

This module sits in the lowest layer with :mod:`dcfpb.common.validation` and
:mod:`dcfpb.common.units`: every package may import it, and it imports nothing of the project.
"""

from __future__ import annotations

EXIT_OK = 0
"""Exit status of a command that finished."""
EXIT_RUN_FAILED = 1
"""Exit status of a run that failed on its own terms (:class:`RunFailure`)."""
EXIT_BAD_INPUT = 2
"""Exit status of bad input: a file, a flag or a value outside its allowed range."""


class InputError(ValueError):
    """Bad input: the message names the file, field or parameter and what is allowed."""


class InputTypeError(InputError, TypeError):
    """Bad input of the wrong kind (a string where a number belongs): an :class:`InputError`
    that is also a ``TypeError``, as Python's own checks of a kind raise."""


class RunFailure(RuntimeError):
    """A run with good input that cannot finish; the message says why and when.

    Raised inside a time integration (by the model or by the ``on_commit`` hook), it ends
    the run with ``success=False`` and the message, keeping the steps already committed
    (:func:`structures.integrators.integrate`). ``kind`` names the reason for tables:
    ``"capacity"``, ``"timeout"``, ``"model"``...
    """

    kind = "error"


class CapacityExceeded(RunFailure, ValueError):
    """A bearing pushed past its displacement capacity, or past the range its model covers
    (the precise model's monitor line, the spherical law's radius).

    Also a ``ValueError``, as the element and the heating model raised before a run could
    end on it: callers of the element that catch ``ValueError`` keep working.

    Parameters
    ----------
    message : str
        What was exceeded, by which displacement [m], at what time [s].
    kind : str
        ``"capacity"`` (beyond the displacement capacity) or ``"model"`` (within it, but
        beyond the model's range, e.g. a monitor line given shorter than the capacity).
    """

    def __init__(self, message: str, kind: str = "capacity") -> None:
        super().__init__(message)
        self.kind = kind


class TimeLimitExceeded(RunFailure):
    """A run past its wall-clock time limit."""

    kind = "timeout"


class InputWarning(UserWarning):
    """A value given that does not apply, or is replaced, where the run goes on regardless: the
    message names it and what is used instead."""
