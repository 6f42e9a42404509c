"""The DCFPB element for the compiled engine: :mod:`~isolator.compiled.kernels` (the hot path),
:mod:`~isolator.compiled.element` (the element as arrays per bearing row),
:mod:`~isolator.compiled.plate` (the monitor points as a group), :mod:`~isolator.compiled.packing`
(a bearing into those arrays and back), :mod:`~isolator.compiled.layout` (friction constants)."""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "pack_ptv": "isolator.compiled.layout",
    "PTV_PARAMETERS": "isolator.compiled.layout",
    "COMPILED": "isolator.compiled.kernels",
}
__all__ = [
    "COMPILED",
    "PTV_PARAMETERS",
    "pack_ptv",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
