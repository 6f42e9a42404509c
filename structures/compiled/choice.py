"""Which engine runs a building: the compiled one when it can, else the readable reference
(:func:`select_engine`: :func:`choose_engine` on the reason :func:`unsupported` gives)."""

from __future__ import annotations

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_choice
from isolator.compiled import kernels
from isolator.compiled.packing import unsupported_reason
from structures.integrators import HHT, Newmark

__all__ = ["ENGINES", "choose_engine", "select_engine", "unsupported"]

ENGINES = ("auto", "compiled", "reference")
"""The values of an ``engine`` argument."""


def unsupported(model: object, method: object) -> str | None:
    """Why the compiled engine cannot run ``model`` with ``method``, or None when it can."""
    from structures.isolated_building import IsolatedShearBuilding

    if type(model) is not IsolatedShearBuilding:
        return f"the model is a {type(model).__name__}, not an IsolatedShearBuilding"
    if not isinstance(method, Newmark | HHT):
        return f"the method {method!r} is not a Newmark or HHT instance"
    return unsupported_reason(model.bearing)


def choose_engine(engine: str, reason: str | None, owner: str) -> str:
    """``"compiled"`` or ``"reference"``: the ``engine`` asked of ``owner`` (one of
    :data:`ENGINES`), given why the compiled one cannot run (``reason``; None when it can).
    Raises ``ValueError`` for an unknown ``engine``, or ``"compiled"`` with a ``reason``."""
    check_choice(engine, "engine", owner, ENGINES)
    if engine == "compiled" and reason is not None:
        raise InputError(f"The 'engine' parameter of {owner} is 'compiled' but {reason}; use "
                         "engine='reference' or 'auto'.")
    if engine == "auto":
        return "compiled" if reason is None and kernels.COMPILED else "reference"
    return engine


def select_engine(engine: str, model: object, method: object, owner: str = "run") -> str:
    """The engine of :func:`structures.analysis.run` (``owner``) for ``model``, ``method``."""
    return choose_engine(engine, unsupported(model, method), owner)
