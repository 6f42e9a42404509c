"""The OpenSees twin: the same building (:mod:`~structures.opensees.building`,
:mod:`~structures.opensees.model`) and bearing (:mod:`~structures.opensees.bearing`) built in
openseespy, what our bearing becomes there (:mod:`~structures.opensees.equivalents`) and the
side-by-side comparison (:mod:`~structures.opensees.comparison`); the building in plan in 3D
(:mod:`~structures.opensees.building3d`, :mod:`~structures.opensees.comparison3d`). openseespy
is imported when a model is built (:mod:`~structures.opensees.runtime`)."""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "run_opensees": "structures.opensees.building",
    "run_opensees_3d": "structures.opensees.building3d",
    "run_comparison_3d": "structures.opensees.comparison3d",
    "run_opensees_test": "structures.opensees.bearing",
    "compare": "structures.opensees.comparison",
    "comparison_bearing": "structures.opensees.comparison",
    "fpbearingptv_equivalent": "structures.opensees.equivalents",
}
__all__ = [
    "compare",
    "comparison_bearing",
    "fpbearingptv_equivalent",
    "run_comparison_3d",
    "run_opensees",
    "run_opensees_3d",
    "run_opensees_test",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
