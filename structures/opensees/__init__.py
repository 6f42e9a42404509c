"""The OpenSees twin: the same building, in one direction or in plan
(:mod:`~structures.opensees.model`, run by :mod:`~structures.opensees.building`), and the same
bearing under an imposed history or orbit (:mod:`~structures.opensees.bearing`) built in
openseespy; what our bearing becomes there (:mod:`~structures.opensees.elements`);
singleFPBearing's normal force given to ours (:mod:`~structures.opensees.singlefp`); the
side-by-side comparisons (:mod:`~structures.opensees.comparison`). openseespy is imported when
a model is built (:mod:`~structures.opensees.runtime`)."""

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
