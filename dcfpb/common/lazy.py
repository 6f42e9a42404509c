"""Package-level names imported on first use (PEP 562), for packages whose modules are costly
to import (numba, xarray): ``import structures`` stays cheap, ``structures.run`` works. Static
tools read the same names from the packages' ``if TYPE_CHECKING:`` imports."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any


def lazy_exports(
    package: str, exports: Mapping[str, str], namespace: dict[str, Any]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The ``__getattr__`` and ``__dir__`` of a package that exports names lazily.

    Parameters
    ----------
    package : str
        The package's name (for the error message).
    exports : mapping of str to str
        Public name -> ``"module"``, or ``"module:attribute"`` when the name differs.
    namespace : dict
        The package's ``globals()``, where a name is stored once imported.
    """

    def __getattr__(name: str) -> Any:
        try:
            target = exports[name]
        except KeyError:
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        module, _, attribute = target.partition(":")
        value = getattr(importlib.import_module(module), attribute or name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(exports))

    return __getattr__, __dir__
