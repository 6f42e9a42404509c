"""A building and its isolators from a TOML file (see ``examples/five_storey.toml``).

One place turns the file into the objects every workflow uses (single runs, suites, the
OpenSees comparison), so they all build the same model. Unknown keys are errors: a typo must
not silently fall back to a default.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.errors import InputError
from dcfpb.validation import check_choice, check_real
from isolator.bearing import DCFPBearing
from isolator.experiments import MODELS, friction_model
from structures.integrators import HHT, Newmark
from structures.shear_building import ModalDamping, RayleighDamping, ShearBuilding

_KEYS = {
    "": {"name", "building", "bearing", "friction", "analysis"},
    "building": {"floor_masses", "storey_stiffnesses", "fixed_base_period",
                 "stiffness_profile", "base_mass", "damping"},
    "building.damping": {"kind", "ratios", "modes", "ratio"},
    "bearing": {"count", "effective_radius", "slider_diameter", "yield_displacement",
                "displacement_capacity"},
    "friction": {"model", "mu_t0", "refinement", "mu0", "design_velocity",
                 "initial_temperature"},
    "analysis": {"integrator", "alpha", "dt"},
}


class ConfigError(InputError):
    """A building file that cannot be used, with the file and the key named."""


@dataclass(frozen=True)
class BuildingConfig:
    """Everything a run needs besides the ground motion."""

    name: str
    building: ShearBuilding
    n_bearings: int
    bearing_geometry: dict[str, float]
    friction: dict[str, Any]
    integrator: Newmark | HHT
    dt: float | None

    def bearing(self, model: str | None = None) -> DCFPBearing:
        """One bearing with friction ``model`` (default: the file's), loaded by W / count."""
        model = check_choice(model or self.friction["model"], "model", "BuildingConfig", MODELS)
        load = self.building.weight / self.n_bearings
        area = math.pi * (0.5 * self.bearing_geometry["slider_diameter"]) ** 2
        friction = friction_model(
            model,
            slider_diameter=self.bearing_geometry["slider_diameter"],
            design_pressure=load / area,
            design_velocity=self.friction.get("design_velocity", 0.4),
            refinement=self.friction.get("refinement", 0.5),
            mu0=self.friction.get("mu0"),
            mu_t0=self.friction.get("mu_t0", 0.075),
            initial_temperature=self.friction.get("initial_temperature", 20.0),
        )
        return DCFPBearing(axial_load=load, friction=friction, **self.bearing_geometry)


def _check_keys(table: dict, section: str, path: Path) -> None:
    unknown = set(table) - _KEYS[section]
    if unknown:
        raise ConfigError(f"{path}: unknown key(s) {sorted(unknown)} in [{section or 'top'}]; "
                          f"allowed: {sorted(_KEYS[section])}.")


def _damping(table: dict, path: Path) -> RayleighDamping | ModalDamping:
    _check_keys(table, "building.damping", path)
    kind = table.get("kind", "rayleigh")
    if kind == "rayleigh":
        return RayleighDamping(ratios=tuple(table.get("ratios", (0.02, 0.02))),
                               modes=tuple(table.get("modes", (1, 2))))
    if kind == "modal":
        return ModalDamping(table.get("ratio", table.get("ratios", 0.02)))
    raise ConfigError(f"{path}: [building.damping] kind must be 'rayleigh' or 'modal'. "
                      f"Got {kind!r} instead.")


def load_config(path: str | Path) -> BuildingConfig:
    """Read a building file.

    Raises
    ------
    ConfigError
        For a missing file, bad TOML, unknown keys, or missing required keys.
    ValueError
        From the model objects, naming the parameter, its range and the value given.
    """
    path = Path(path)
    try:
        raw = tomllib.loads(path.read_text())
    except FileNotFoundError as error:
        raise ConfigError(f"{path}: no such building file.") from error
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{path}: not valid TOML: {error}") from error
    _check_keys(raw, "", path)
    for section in ("building", "bearing", "friction", "analysis"):
        raw.setdefault(section, {})
        _check_keys(raw[section], section, path)
    b = raw["building"]
    try:
        masses = np.asarray(b["floor_masses"], dtype=float)
        base_mass = b["base_mass"]
    except KeyError as error:
        raise ConfigError(f"{path}: [building] needs {error.args[0]!r}.") from error
    damping = _damping(b.get("damping", {}), path)
    if "storey_stiffnesses" in b:
        building = ShearBuilding(masses, np.asarray(b["storey_stiffnesses"], dtype=float),
                                 base_mass, damping)
    elif "fixed_base_period" in b:
        building = ShearBuilding.from_period(masses, b["fixed_base_period"], base_mass=base_mass,
                                             damping=damping,
                                             profile=b.get("stiffness_profile", "uniform"))
    else:
        raise ConfigError(f"{path}: [building] needs 'storey_stiffnesses' or "
                          "'fixed_base_period'.")
    bearing = dict(raw["bearing"])
    count = bearing.pop("count", 1)
    for key in ("effective_radius", "slider_diameter"):
        if key not in bearing:
            raise ConfigError(f"{path}: [bearing] needs {key!r}.")
    friction = dict(raw["friction"])
    friction["model"] = check_choice(friction.get("model", "precise"), "model", str(path), MODELS)
    analysis = raw["analysis"]
    kind = check_choice(analysis.get("integrator", "newmark"), "integrator", str(path),
                        ("newmark", "hht"))
    integrator = HHT(alpha=analysis.get("alpha", -0.05)) if kind == "hht" else Newmark()
    dt = analysis.get("dt")
    if dt is not None:
        check_real(dt, "dt", str(path), low=0.0, low_open=True, high=1.0)
    config = BuildingConfig(raw.get("name", path.stem), building, int(count), bearing, friction,
                            integrator, dt)
    config.bearing()  # validate the bearing now, before any run starts
    return config
