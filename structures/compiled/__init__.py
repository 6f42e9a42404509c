"""The compiled engine of :func:`structures.analysis.run`: the whole run as one numba function
(:mod:`~structures.compiled.integrator`), the adapter that packs the model into arrays and the
result back (:mod:`~structures.compiled.engine`), the two dense LAPACK solves
(:mod:`~structures.compiled.lapack`) and the compilation in a second process on a cold cache
(:mod:`~structures.compiled.ahead`). Without numba the same source runs as Python."""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "compiled_history": "structures.compiled.engine",
    "select_engine": "structures.compiled.choice",
    "compile_engine": "structures.compiled.engine",
    "warm_up": "structures.compiled.engine",
    "compile_ahead": "structures.compiled.ahead",
}
__all__ = [
    "compile_ahead",
    "compile_engine",
    "compiled_history",
    "select_engine",
    "warm_up",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
