"""The compiled engine of :func:`structures.analysis.run`: the whole run as one numba function
(:mod:`~structures.compiled.integrator`), its view of a model (:mod:`~structures.compiled.view`),
the adapter packing that view and unpacking the result (:mod:`~structures.compiled.engine`), its
numerical pieces (:mod:`~structures.compiled.linear`, :mod:`~structures.compiled.lapack`) and the
compilation in a second process (:mod:`~structures.compiled.ahead`). Without numba the same
source runs as Python."""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "compiled_history": "structures.compiled.engine",
    "compiled_run": "structures.compiled.engine",
    "engine_view": "structures.compiled.view",
    "EngineView": "structures.compiled.view",
    "select_engine": "structures.compiled.choice",
    "compile_engine": "structures.compiled.engine",
    "warm_up": "structures.compiled.engine",
    "compile_ahead": "structures.compiled.ahead",
}
__all__ = [
    "EngineView",
    "compile_ahead",
    "compile_engine",
    "compiled_history",
    "compiled_run",
    "engine_view",
    "select_engine",
    "warm_up",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
