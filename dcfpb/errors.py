"""The project's own exceptions: bad input (exit status 2) and a run that fails on its own terms
(exit status 1).

Every error a user can cause derives from :class:`InputError`, itself a ``ValueError`` so that
code written against the standard exceptions keeps working: records
(:class:`groundmotions.records.RecordFormatError`), building files
(:class:`structures.config.ConfigError`), bearing-test data
(:class:`isolator.diagnosis.data.DataError`) and parameters checked by :mod:`dcfpb.validation`.
A run that was given good input but cannot finish (a bearing pushed past its displacement
capacity, a run past its time limit) raises :class:`RunFailure`.

This module sits in the lowest layer with :mod:`dcfpb.validation` and :mod:`dcfpb.units`: every
package may import it, and it imports nothing of the project.
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


class RunFailure(RuntimeError):
    """A run with good input that cannot finish; the message says why and when."""
