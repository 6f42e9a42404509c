"""Structures layer: the shear building on its isolators, in one direction or in plan, its
integration, results, building files, fixed base and floor spectra (engine:
:mod:`structures.compiled`; workflows: :mod:`structures.opensees`, :mod:`structures.suites`,
:mod:`structures.diagnosis`). The names in ``__all__`` are imported on first use::

    result = structures.run("examples/five_storey.toml", "record.at2", model="precise")
    print(structures.peaks(result))
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "run": "structures.runner",
    "run_building": "structures.analysis:run",
    "peaks": "structures.analysis",
    "default_step": "structures.analysis",
    "BuildingConfig": "structures.config",
    "load_config": "structures.config",
    "ShearBuilding": "structures.shear_building",
    "RayleighDamping": "structures.shear_building",
    "ModalDamping": "structures.shear_building",
    "IsolatedShearBuilding": "structures.isolated_building",
    "Newmark": "structures.integrators",
    "HHT": "structures.integrators",
    "integrate": "structures.integrators",
    "energy_balance": "structures.energy",
    "run_fixed_base": "structures.fixed_base",
    "ratios_to_fixed_base": "structures.fixed_base",
    "with_floor_spectra": "structures.floor_spectra",
    "Plan": "structures.plan",
}
__all__ = [
    "HHT",
    "BuildingConfig",
    "IsolatedShearBuilding",
    "ModalDamping",
    "Newmark",
    "Plan",
    "RayleighDamping",
    "ShearBuilding",
    "default_step",
    "energy_balance",
    "integrate",
    "load_config",
    "peaks",
    "ratios_to_fixed_base",
    "run",
    "run_building",
    "run_fixed_base",
    "with_floor_spectra",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())

if TYPE_CHECKING:
    from structures.analysis import default_step, peaks
    from structures.analysis import run as run_building
    from structures.config import BuildingConfig, load_config
    from structures.energy import energy_balance
    from structures.fixed_base import ratios_to_fixed_base, run_fixed_base
    from structures.floor_spectra import with_floor_spectra
    from structures.integrators import HHT, Newmark, integrate
    from structures.isolated_building import IsolatedShearBuilding
    from structures.plan import Plan
    from structures.runner import run
    from structures.shear_building import ModalDamping, RayleighDamping, ShearBuilding
