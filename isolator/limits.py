"""A bound on the time steps of a run and on the memory its histories take, checked before
anything is allocated (:func:`check_steps`), for the bearing tests (:mod:`isolator.protocols`)
and the building runs (:mod:`structures.limits`). :data:`DEFAULT_MAX_STEPS` is well above the
longest records (300 to 600 s at 5 or 1 ms) and holds a five-storey building run in about
1.2 GB; past it the user raises the limit on purpose (``--max-steps``, ``max_steps=``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from dcfpb.common.errors import InputError
from dcfpb.common.files import MEMINFO, available_memory

DEFAULT_MAX_STEPS = 2_000_000
"""Most time steps a run may take unless the caller raises the limit."""



def _size(n_bytes: float) -> str:
    for unit, scale in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n_bytes >= scale:
            return f"{n_bytes / scale:.3g} {unit}"
    return f"{n_bytes:.0f} bytes"


def check_steps(
    steps: int,
    *,
    what: str,
    duration: float,
    dt: float,
    bytes_per_step: float,
    max_steps: int,
    raise_with: str,
    hint: str = "Check the duration and the time step",
    meminfo: Path = MEMINFO,
) -> None:
    """Refuse a run of ``steps`` time steps past ``max_steps`` (>= 1) or past the memory
    available (:func:`available_memory` from ``meminfo``) at ``bytes_per_step`` [bytes]. The
    message names ``what`` is run, the ``duration`` [s] and ``dt`` [s] the steps come from,
    ``hint`` (what to check first) and ``raise_with`` (how to raise the limit, e.g.
    ``"--max-steps"``).

    Raises
    ------
    InputError
        Past the limit (with the steps the run needs) or past the memory available.
    """
    if isinstance(max_steps, bool) or not isinstance(max_steps, int) or max_steps < 1:
        raise InputError(f"{raise_with} must be an integer in [1, inf). Got {max_steps!r} "
                         "instead.")
    need = steps * bytes_per_step
    source = f"{steps:,} steps ({duration:.6g} s at dt = {dt:.6g} s)"
    if steps > max_steps:
        raise InputError(
            f"{what} would take {source}, past the limit of {max_steps:,} steps, and hold about "
            f"{_size(need)}. {hint}; to run it all the same, raise the limit with {raise_with} "
            f"(at least {steps:,}).")
    free = available_memory(meminfo)
    if free is not None and need > free:
        raise InputError(
            f"{what} would take {source} and hold about {_size(need)}, more than the "
            f"{_size(free)} of memory available. {hint}.")


HISTORY_FIELDS = 17
"""Values an imposed history and its bearing test hold per sample: the history as made and as
kept (:class:`isolator.protocols.ImposedHistory`: time, displacement, velocity, and the sample
index and phase of a sine) and the test's nine histories (:func:`isolator.testrig.run_test`)."""


def history_steps(
    duration: float,
    dt: float,
    *,
    max_steps: int = DEFAULT_MAX_STEPS,
    what: str = "The imposed history",
    raise_with: str = "the max_steps argument of isolator.protocols.sine",
    hint: str = "Check the duration and the time step",
) -> int:
    """Number of equal steps no longer than ``dt`` [s] that fill ``duration`` [s] (at least one),
    checked against ``max_steps`` and the memory available (:func:`check_steps`,
    :data:`HISTORY_FIELDS` values per sample); an :class:`InputError` past either."""
    ratio = duration / dt - 1e-9  # relative slack: a step that divides the duration fits
    steps = max(1, math.ceil(ratio)) if math.isfinite(ratio) else sys.maxsize
    check_steps(steps, what=what, duration=duration, dt=dt, bytes_per_step=8 * HISTORY_FIELDS,
                max_steps=max_steps, raise_with=raise_with, hint=hint)
    return steps
