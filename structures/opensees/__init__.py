"""The OpenSees twins of our building (:mod:`~structures.opensees.model`,
:mod:`~structures.opensees.building`) and bearing test (:mod:`~structures.opensees.bearing`,
:mod:`~structures.opensees.elements`, :mod:`~structures.opensees.singlefp`), and the
comparisons (:mod:`~structures.opensees.comparison`). openseespy is imported when needed."""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "run_opensees": "structures.opensees.building",
    "run_opensees_test": "structures.opensees.bearing",
    "compare": "structures.opensees.comparison",
    "comparison_bearing": "structures.opensees.comparison",
    "run_bearing_comparison": "structures.opensees.comparison",
    "run_comparison": "structures.opensees.comparison",
    "fpbearingptv_equivalent": "structures.opensees.elements",
    "run_singlefp_normal": "structures.opensees.singlefp",
    "singlefp_normal_force": "structures.opensees.singlefp",
}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
