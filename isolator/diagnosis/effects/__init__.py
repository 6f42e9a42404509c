"""The library of candidate effects, one module per effect.

Every module here that defines ``EFFECT`` (an :class:`~.base.Effect`) is part of the library;
:data:`LIBRARY` lists them by their ``order``. Adding an effect is adding such a module.
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Sequence

from dcfpb.common.errors import InputError
from isolator.diagnosis.effects.base import ACTS_ON, Context, Effect, Parameter


def _discover() -> tuple[Effect, ...]:
    found = []
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_") or info.name == "base":
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        effect = getattr(module, "EFFECT", None)
        if isinstance(effect, Effect):
            found.append(effect)
    names = [e.name for e in found]
    if len(set(names)) != len(names):
        raise ImportError(f"Two effect modules define the same effect name: {sorted(names)}.")
    return tuple(sorted(found, key=lambda e: (e.order, e.name)))


LIBRARY: tuple[Effect, ...] = _discover()
EFFECT_NAMES = tuple(e.name for e in LIBRARY)


def effects_named(names: Sequence[str]) -> tuple[Effect, ...]:
    """The library's effects called ``names``, in that order."""
    table = {e.name: e for e in LIBRARY}
    unknown = [n for n in names if n not in table]
    if unknown:
        raise InputError(f"Unknown effect(s) {unknown}; the library has {list(EFFECT_NAMES)}.")
    return tuple(table[n] for n in names)


def physical_parameters(effect: Effect, theta, stderr, context: Context) -> dict:
    """``{name: (value, standard error, unit)}`` of a fitted effect, in engineering terms."""
    return effect.physical_parameters(theta, stderr, context)


__all__ = ["ACTS_ON", "EFFECT_NAMES", "LIBRARY", "Context", "Effect", "Parameter",
           "effects_named", "physical_parameters"]
