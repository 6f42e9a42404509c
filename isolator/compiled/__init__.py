"""The DCFPB element for the compiled engine: the kernels of the hot path
(:mod:`~isolator.compiled.kernels`: Eq. 7 solved with the newest flux, the heat-history update;
compiled by numba or run as Python), the element as arrays for every bearing row of a building
(:mod:`~isolator.compiled.element`), the monitor points held as a group
(:mod:`~isolator.compiled.plate`), the packing of a bearing into those arrays and back
(:mod:`~isolator.compiled.packing`) and the named layout of the friction constants with its
one packer (:mod:`~isolator.compiled.layout`)."""

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
