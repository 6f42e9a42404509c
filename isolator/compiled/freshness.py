"""numba's disk cache of our compiled functions, invalidated by the code they depend on.

numba keys a cached function on its own source file only, but ours use functions and constants
of other modules (the engine inlines the element and the workspace's layout), so after an edit
there numba would load stale machine code. :class:`DependencyStampLocator` (first in numba's
locators, by :func:`install`) stamps the cache with a digest of the function's file and every
module of ours it imports, transitively, read from the import statements without importing.
"""

from __future__ import annotations

import ast
import functools
import hashlib
import importlib.util
from pathlib import Path

__all__ = ["DependencyStampLocator", "dependency_closure", "dependency_stamp", "install"]

PACKAGES = ("dcfpb", "groundmotions", "isolator", "structures")
"""The top-level packages whose modules are followed."""


@functools.cache
def _module_file(name: str) -> Path | None:
    """The source file of module ``name`` of our packages (None if it has none)."""
    if name.split(".")[0] not in PACKAGES:
        return None
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):
        return None
    if spec is None or spec.origin is None or not spec.origin.endswith(".py"):
        return None
    return Path(spec.origin)


def _module_level(body: list[ast.stmt]):
    """The import statements run when the module is imported: at module level, inside ``try``
    and ``if`` blocks, but not under ``if TYPE_CHECKING:`` nor in functions or classes."""
    for node in body:
        if isinstance(node, ast.Import | ast.ImportFrom):
            yield node
        elif isinstance(node, ast.If):
            if not (isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING"):
                yield from _module_level(node.body)
                yield from _module_level(node.orelse)
        elif isinstance(node, ast.Try):
            for block in (node.body, node.orelse, node.finalbody,
                          *(handler.body for handler in node.handlers)):
                yield from _module_level(block)


@functools.cache
def _imports(path: Path) -> frozenset[str]:
    """The modules of our packages that the file at ``path`` imports when it is imported
    (``import a.b``, ``from a.b import c``: ``a.b``, and ``a.b.c`` when that is a module).
    Parent packages are not followed: ours hold no compiled code and import lazily."""
    tree = ast.parse(path.read_bytes(), str(path))
    names: set[str] = set()
    for node in _module_level(tree.body):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif node.module and node.level == 0:
            names.add(node.module)
            names.update(f"{node.module}.{alias.name}" for alias in node.names)
    return frozenset(name for name in names if name.split(".")[0] in PACKAGES)


@functools.cache
def dependency_closure(py_file: str) -> tuple[Path, ...]:
    """The source file ``py_file`` (a path) and the files of every module of ours it imports,
    transitively, as a sorted tuple of Path."""
    start = Path(py_file).resolve()
    seen, todo = {start}, [start]
    while todo:
        for name in _imports(todo.pop()):
            path = _module_file(name)
            if path is not None and path.resolve() not in seen:
                seen.add(path.resolve())
                todo.append(path.resolve())
    return tuple(sorted(seen))


@functools.cache
def dependency_stamp(py_file: str) -> str:
    """SHA-256 of the contents of :func:`dependency_closure` of ``py_file`` (hex); computed
    once per file and process, as numba reads its cache index once per function."""
    digest = hashlib.sha256()
    for path in dependency_closure(py_file):
        digest.update(str(path.name).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


try:  # pragma: no cover - whichever numba runs the tests
    from numba.core import caching as _caching

    _Base = _caching._CacheLocator
except (ImportError, AttributeError):  # no numba, or one without locators
    _caching, _Base = None, object


class DependencyStampLocator(_Base):  # type: ignore[misc, valid-type]
    """numba's own locator for a function of our packages (where the cache lives), with the
    source stamp of :func:`dependency_stamp` instead of the function's file alone."""

    def __init__(self, inner, py_file: str) -> None:
        self._inner = inner
        self._py_file = py_file

    def ensure_cache_path(self) -> None:
        self._inner.ensure_cache_path()

    def get_cache_path(self) -> str:
        return self._inner.get_cache_path()

    def get_source_stamp(self) -> str:
        return dependency_stamp(self._py_file)

    def get_disambiguator(self) -> str:
        return self._inner.get_disambiguator()

    @classmethod
    def from_function(cls, py_func, py_file):
        path = Path(py_file)
        if not path.is_file() or not any(part in PACKAGES for part in path.parts[-4:-1]):
            return None
        for locator in _caching.CacheImpl._locator_classes:
            if locator is cls:
                continue
            inner = locator.from_function(py_func, py_file)
            if inner is not None:
                return cls(inner, py_file)
        return None


def install() -> bool:
    """Put :class:`DependencyStampLocator` first in numba's list of cache locators (once);
    whether it is in place (False without numba or with a numba that has no such list)."""
    if _caching is None or not hasattr(_caching, "CacheImpl"):
        return False
    classes = _caching.CacheImpl._locator_classes
    if DependencyStampLocator not in classes:
        classes.insert(0, DependencyStampLocator)
    return True
