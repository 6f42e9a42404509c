"""The length of a building run, estimated before it starts: its steps and its memory.

:func:`check_run` is called by :func:`structures.analysis.run`,
:func:`structures.fixed_base.run_fixed_base` and the command line (``--max-steps``) before
anything is allocated; the limit and its default are those of :mod:`isolator.limits`.
"""

from __future__ import annotations

import math
import sys

from dcfpb.common.validation import check_real
from groundmotions.records import GroundMotion
from isolator.limits import DEFAULT_MAX_STEPS, check_steps

__all__ = ["DEFAULT_MAX_STEPS", "building_fields", "check_run", "fixed_base_fields",
           "run_steps"]

_BYTES = 8  # one float64 (or int64) per field and step


def building_fields(n_storeys: int, level_dofs: int = 1, positions: int = 1) -> int:
    """Values (8 bytes each) a building run holds per step, for ``level_dofs`` degrees of
    freedom per level (1 in one direction, 3 in plan) and ``positions`` bearing positions: the
    Dataset's (levels' motion per direction and rotations in plan, storey drift and shear, seven
    histories per position, base shear and ground acceleration, six energies, time) and the
    engine's (u, v, a and restoring force per degree of freedom, ten fields per position,
    iterations, subdivisions, record, time)."""
    components = 1 if level_dofs == 1 else 2
    levels = level_dofs * (n_storeys + 1)
    dataset = levels + 2 * components * (n_storeys + 1) + 2 * components * n_storeys \
        + (n_storeys if level_dofs == 3 else 0) + positions * (3 * components + 4) \
        + 2 * components + 8
    engine = 4 * levels + 10 * positions + 3 * components + 4
    return dataset + engine


def fixed_base_fields(n_storeys: int) -> int:
    """Values a fixed-base run holds per step: its Dataset (five histories per floor, base
    shear, ground acceleration, time) and the modal responses (two per mode)."""
    return 7 * n_storeys + 3


def run_steps(motion: GroundMotion, dt: float | None, owner: str = "run") -> tuple[int, float]:
    """The steps and the step [s] of a run on ``motion`` at the analysis step ``dt`` [s]: the
    record's samples for ``dt`` None (or the record's), else ``floor(duration / dt)`` steps on
    the interpolated record (:func:`structures.analysis.resampled_record`); a ``ValueError``
    naming ``owner`` for a ``dt`` outside (0, record dt]."""
    if dt is None or abs(dt - motion.dt) <= 1e-12 * motion.dt:
        return int(motion.acceleration.size) - 1, float(motion.dt)
    check_real(dt, "dt", owner, low=0.0, high=motion.dt, low_open=True)
    ratio = motion.duration / dt + 1e-9  # inf for a step of 1e-320 s
    return (math.floor(ratio) if math.isfinite(ratio) else sys.maxsize), float(dt)


def check_run(
    motion: GroundMotion,
    dt: float | None,
    fields: int,
    *,
    max_steps: int = DEFAULT_MAX_STEPS,
    what: str = "The building run",
    raise_with: str = "the max_steps argument of structures.analysis.run",
    owner: str = "run",
) -> int:
    """Refuse a run on ``motion`` at the analysis step ``dt`` [s] (None: the record's) past
    ``max_steps`` steps or the memory available, for ``fields`` values held per step
    (:func:`building_fields`, :func:`fixed_base_fields`); return its steps. ``what``,
    ``raise_with`` and ``owner`` name the run, how to raise the limit and who checks ``dt`` in
    the messages.

    Raises
    ------
    InputError
        Past the limit or the memory available (:func:`isolator.limits.check_steps`).
    """
    steps, step = run_steps(motion, dt, owner)
    check_steps(steps, what=what, duration=float(motion.duration), dt=step,
                bytes_per_step=fields * _BYTES, max_steps=max_steps, raise_with=raise_with,
                hint="Check the record's time step (DT in its header) and the analysis dt")
    return steps
