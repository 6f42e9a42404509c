"""A building and its isolators from a TOML file (see ``examples/five_storey.toml``): the one
place every workflow (single runs, suites, the OpenSees comparison) builds its model from, once
:mod:`structures.config_schema` has checked every value.
"""

from __future__ import annotations

import codecs
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.common.units import KELVIN_LOOK
from dcfpb.common.validation import check_choice, check_path
from isolator.bearing import DCFPBearing, slider_contact_area
from isolator.experiments import MODELS, friction_model
from structures.config_schema import ConfigError, ConfigWarning, check_plan, check_tables
from structures.integrators import HHT, Newmark
from structures.plan import Plan
from structures.shear_building import ModalDamping, RayleighDamping, ShearBuilding

__all__ = ["BuildingConfig", "ConfigError", "ConfigWarning", "load_config", "read_toml"]

MAX_FILE_BYTES = 10_000_000
"""Largest building file read [bytes]; the example is 4 kB."""


@dataclass(frozen=True)
class BuildingConfig:
    """Everything a run needs besides the ground motion: the ``building`` (in plan for a file
    with a ``[plan]`` table), its bearings' number and geometry, their friction parameters, the
    integrator and the analysis step ``dt`` [s] (None: the record's); and the file's
    ``[design]`` table as given (None without one: the property modification factors, site and
    R of an ASCE 7-16 Chapter 17 design, read by :mod:`structures.design`)."""

    name: str
    building: ShearBuilding
    n_bearings: int
    bearing_geometry: dict[str, float]
    friction: dict[str, Any]
    integrator: Newmark | HHT
    dt: float | None
    design: dict[str, Any] | None = None

    @property
    def plan(self) -> Plan | None:
        """The building's plan (None for a building in one direction)."""
        return self.building.plan

    def bearing(self, model: str | None = None) -> DCFPBearing:
        """One bearing with the friction ``model`` (default: the file's), loaded by W / n [N]."""
        model = check_choice(model or self.friction["model"], "model", "BuildingConfig", MODELS)
        load = self.building.weight / self.n_bearings
        area = slider_contact_area(self.bearing_geometry["slider_diameter"])
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


def read_toml(path: Path) -> dict[str, Any]:
    """The table of a TOML file, read as UTF-8 (a byte-order mark is skipped).

    Raises
    ------
    ConfigError
        For a missing or unreadable file, one larger than :data:`MAX_FILE_BYTES`, bytes that
        are not UTF-8 (the first offending byte and its offset named) or text that is not TOML.
    """
    try:
        if path.exists() and not path.is_file() and not path.is_dir():
            raise ConfigError(f"{path}: not a regular file (a device or a pipe); give the "
                              "building file itself.")
        if path.stat().st_size > MAX_FILE_BYTES:
            raise ConfigError(f"{path}: {path.stat().st_size} bytes is not a building file "
                              f"(at most {MAX_FILE_BYTES} bytes).")
        data = path.read_bytes()
    except FileNotFoundError as error:
        raise ConfigError(f"{path}: no such building file.") from error
    except OSError as error:
        raise ConfigError(f"{path}: cannot be read ({error.strerror or error}).") from error
    skip = len(codecs.BOM_UTF8) if data.startswith(codecs.BOM_UTF8) else 0
    try:
        text = data[skip:].decode("utf-8")
    except UnicodeDecodeError as error:
        at = skip + error.start  # offset in the file
        raise ConfigError(f"{path}: not UTF-8 text (byte 0x{data[at]:02x} at offset {at}); "
                          "save it as UTF-8.") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{path}: not valid TOML: {error}") from error
    except RecursionError:
        raise ConfigError(f"{path}: not valid TOML: arrays or tables nested too deeply.") from None


def _damping(table: dict) -> RayleighDamping | ModalDamping:
    if table.get("kind", "rayleigh") == "rayleigh":
        return RayleighDamping(ratios=tuple(table.get("ratios", (0.02, 0.02))),
                               modes=tuple(table.get("modes", (1, 2))))
    ratio = table.get("ratio", table.get("ratios", 0.02))
    return ModalDamping(tuple(ratio) if isinstance(ratio, list) else ratio)


def _build(tables: dict[str, dict], path: Path) -> BuildingConfig:
    """The objects of a checked file (:func:`structures.config_schema.check_tables`)."""
    b = tables["building"]
    masses = np.asarray(b["floor_masses"], dtype=float)
    damping = _damping(tables["building.damping"])
    plan = None if tables.get("plan") is None else Plan(**tables["plan"])
    if "storey_stiffnesses" in b:
        building = ShearBuilding(masses, np.asarray(b["storey_stiffnesses"], dtype=float),
                                 b["base_mass"], damping, plan)
    else:
        building = ShearBuilding.from_period(masses, b["fixed_base_period"],
                                             base_mass=b["base_mass"], damping=damping,
                                             profile=b.get("stiffness_profile", "uniform"),
                                             plan=plan)
    bearing = dict(tables["bearing"])
    count = bearing.pop("count", 1 if plan is None else plan.n_bearings)
    friction = dict(tables["friction"])
    friction["model"] = friction.get("model", "precise")
    analysis = tables["analysis"]
    hht = analysis.get("integrator", "newmark") == "hht"
    integrator = HHT(alpha=analysis.get("alpha", -0.05)) if hht else Newmark()
    config = BuildingConfig(tables[""].get("name", path.stem), building, count, bearing,
                            friction, integrator, analysis.get("dt"),
                            dict(tables["design"]) or None)
    for model in MODELS:  # every model the file may run (--model, suites), checked now
        config.bearing(model)
    return config


def _check_not_kelvin(tables: dict, path: Path) -> None:
    value = tables.get("friction", {}).get("initial_temperature")
    if value is not None and KELVIN_LOOK[0] <= value <= KELVIN_LOOK[1]:
        raise ConfigError(f"{path}: [friction] 'initial_temperature' is {value:g}, which looks "
                          f"like kelvin (plates at {KELVIN_LOOK[0]:g} degC or more before a run "
                          f"are implausible); give it in degC ({value - 273.15:.4g} degC if "
                          "it is in kelvin).")


def load_config(path: str | Path) -> BuildingConfig:
    """Read a building file (TOML, UTF-8) into a :class:`BuildingConfig`.

    Raises
    ------
    ConfigError
        An :class:`~dcfpb.common.errors.InputError` for anything wrong with the file: missing,
        not UTF-8, not TOML, an unknown or missing key, a value of the wrong type or outside its
        range (file, section and key named), or a combination the model objects refuse.

    Warns
    -----
    ConfigWarning
        For a setting without effect (:func:`structures.config_schema.check_tables`).
    """
    path = Path(check_path(path, "path", "load_config"))
    raw = read_toml(path)
    tables = check_tables(raw, path)
    _check_not_kelvin(tables, path)
    tables["plan"] = check_plan(raw, len(tables["building"]["floor_masses"]),
                                tables["bearing"], path)
    try:
        return _build(tables, path)
    except ConfigError:
        raise
    except (ValueError, TypeError, ArithmeticError) as error:  # a combination of good values
        text = re.sub(r"The '(\w+)' parameter of Plan", r"[plan] '\1'", str(error))
        raise ConfigError(f"{path}: {text}") from error
