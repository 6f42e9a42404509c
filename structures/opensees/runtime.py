"""Import openseespy so that a plain ``pip install openseespy`` works: the Linux wheel
(3.7.1.2, the newest for Python 3.11) bundles BLAS, LAPACK and the GNU Fortran runtime in
``openseespylinux/lib``, but its ``liblapack.so.3`` looks for ``libblas.so.3`` and
``libgfortran.so.4`` on the system, so :func:`import_opensees` preloads them with
``RTLD_GLOBAL``. openseespy is imported only there.
"""

from __future__ import annotations

import ctypes
import importlib
import importlib.util
import sys
from pathlib import Path
from types import ModuleType

BUNDLED_LIBRARIES = ("libquadmath.so.0", "libgfortran.so.4", "libblas.so.3", "liblapack.so.3")
"""Bundled libraries of openseespylinux, in load order (each after its own dependencies)."""

INSTALL_HINT = (
    "`pip install openseespy` (or `pip install dcfpb[opensees]`); 3.7.1.2 is the newest wheel "
    "for Python 3.11."
)

_module: ModuleType | None = None
_preloaded: list[ctypes.CDLL] = []  # keep the handles alive for the life of the process


def bundled_library_dir() -> Path | None:
    """Folder of the libraries bundled with the Linux wheel, or None where there is none."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        spec = importlib.util.find_spec("openseespylinux")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    folder = Path(next(iter(spec.submodule_search_locations))) / "lib"
    return folder if folder.is_dir() else None


def preload_bundled_libraries() -> list[str]:
    """Load the wheel's bundled libraries globally; return the names loaded. Missing ones are
    skipped; one present that fails to load raises ``ImportError`` naming it."""
    folder = bundled_library_dir()
    if folder is None:
        return []
    loaded = []
    for name in BUNDLED_LIBRARIES:
        path = folder / name
        if not path.is_file():
            continue
        try:
            _preloaded.append(ctypes.CDLL(str(path), mode=ctypes.RTLD_GLOBAL))
        except OSError as error:
            raise ImportError(
                f"Could not load {path} bundled with openseespy: {error}. "
                "Reinstall openseespy or install a system BLAS/LAPACK (libblas3, liblapack3)."
            ) from error
        loaded.append(name)
    return loaded


def import_opensees() -> ModuleType:
    """Return ``openseespy.opensees`` (the same object on every call), its bundled libraries
    loaded first. Raises ImportError if openseespy is not installed (with the command that
    installs it) or cannot be loaded even with its bundled libraries."""
    global _module
    if _module is not None:
        return _module
    if importlib.util.find_spec("openseespy") is None:
        raise ImportError(f"openseespy is needed for the OpenSees comparison: {INSTALL_HINT}")
    preload_bundled_libraries()
    try:
        _module = importlib.import_module("openseespy.opensees")
    except (ImportError, RuntimeError) as error:  # openseespy turns ImportError into this
        cause: BaseException = error  # openseespy wraps the loader's error twice: unwrap it
        while (cause.__cause__ or cause.__context__) is not None:
            cause = cause.__cause__ or cause.__context__
        raise ImportError(
            f"openseespy is installed but could not be imported ({cause}); reinstall it with "
            f"{INSTALL_HINT} A missing BLAS or LAPACK may also come from the system (libblas3, "
            "liblapack3)."
        ) from error
    return _module
