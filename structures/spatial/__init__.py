"""The building in plan: floors with x, y and a rotation, the bearings at their plan positions,
pairs of records (and a vertical) as ground motion.

- :mod:`~structures.spatial.plan` (the plan: bearing coordinates, eccentricity, inertias,
  gravity shares) and :mod:`~structures.spatial.plan_schema` (its ``[plan]`` table in a
  building file);
- :mod:`~structures.spatial.building` (the 3D mass, stiffness and damping matrices) and
  :mod:`~structures.spatial.isolated` (the model on its bidirectional bearings, with the axial
  load from gravity, the vertical motion and overturning);
- :mod:`~structures.spatial.analysis` (:func:`run_spatial`), :mod:`~structures.spatial.results`
  (the Dataset with a ``direction`` dimension), :mod:`~structures.spatial.energy` (the energy
  balance) and :mod:`~structures.spatial.peaks` (:func:`plan_peaks`).

The planar building (:mod:`structures.analysis`) does not depend on any of it.
"""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "Plan": "structures.spatial.plan",
    "SpatialBuilding": "structures.spatial.building",
    "SpatialIsolatedBuilding": "structures.spatial.isolated",
    "run_spatial": "structures.spatial.analysis",
    "plan_peaks": "structures.spatial.peaks",
}
__all__ = ["Plan", "SpatialBuilding", "SpatialIsolatedBuilding", "plan_peaks", "run_spatial"]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
