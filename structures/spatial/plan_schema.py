"""The ``[plan]`` table of a building file: the building in plan, checked key by key.

A building file with a ``[plan]`` table describes a building in plan
(:class:`structures.spatial.plan.Plan`); without one it is the planar building, read and run as
before. Every key is checked here before any object is built, with the messages of
:mod:`structures.config_schema` (file, section, key, what is allowed, the value given)::

    [plan]
    # Bearing positions (x, y) from the centre of stiffness [m]; at least 3, not on a line.
    bearing_coordinates = [[-6.0, -5.0], [6.0, -5.0], [6.0, 5.0], [-6.0, 5.0]]
    # Centre of mass of the floors (e_x, e_y) [m]: one pair, or one per floor.
    eccentricity = [1.2, 0.0]
    # Plan dimensions (a, b) along x and y [m]: the default inertias m (a^2 + b^2) / 12 and
    # torsional stiffnesses (k_x b^2 + k_y a^2) / 12.
    dimensions = [12.0, 10.0]
    # Storey heights [m], one for all or one per storey: the overturning's lever arms.
    storey_heights = 3.5

Optional besides: ``base_eccentricity`` [m], ``floor_inertias`` [kg m^2] (one per floor),
``base_inertia`` [kg m^2], ``storey_stiffnesses_y`` [N/m] and ``torsional_stiffnesses``
[N m/rad] (one per storey). ``[bearing] count``, if given, must equal the number of bearing
coordinates.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from structures.config_schema import (
    MAX_BEARINGS,
    Array,
    ConfigError,
    Either,
    Number,
    Where,
)
from structures.spatial.plan import Plan

__all__ = ["PLAN_SCHEMA", "build_plan", "check_plan"]

_COORDINATE = Number(low=-1e4, high=1e4)  # [m]
_LENGTH = Number(low=0.0, low_open=True, high=1e4)  # [m]


@dataclass(frozen=True)
class Pairs:
    """One ``[x, y]`` pair, or an array of such pairs (``min_length`` to ``max_length``)."""

    item: Number
    what: str
    one: bool = True  # a single pair is accepted
    many: bool = True  # an array of pairs is accepted
    min_length: int = 1
    max_length: int = MAX_BEARINGS

    @property
    def allowed(self) -> str:
        inside = self.item.interval
        kinds = [f"an [x, y] pair of numbers in {inside}"] if self.one else []
        if self.many:
            kinds.append(f"an array of {self.min_length} to {self.max_length} [x, y] pairs of "
                         f"numbers in {inside}")
        return " or ".join(kinds) + f" ({self.what})"

    def check(self, value: object, where: Where) -> Any:
        if not isinstance(value, list) or not value:
            raise where.error(self.allowed, value)
        if not isinstance(value[0], list):  # a single pair
            if not self.one or len(value) != 2 or not all(map(self.item.fits, value)):
                raise where.error(self.allowed, value)
            return value
        if not self.many or not self.min_length <= len(value) <= self.max_length:
            raise ConfigError(f"{where} must be {self.allowed}. Got {len(value)} pairs "
                              "instead.")
        for i, pair in enumerate(value):
            if not isinstance(pair, list) or len(pair) != 2 or not all(
                    map(self.item.fits, pair)):
                raise where.error(self.allowed, pair, f" at index {i}")
        return value


PLAN_SCHEMA: dict[str, Any] = {
    "bearing_coordinates": Pairs(_COORDINATE, "m, from the centre of stiffness", one=False,
                                 min_length=3),
    "eccentricity": Pairs(_COORDINATE, "m, one pair for all floors or one per floor"),
    "base_eccentricity": Pairs(_COORDINATE, "m", many=False),
    "dimensions": Array(_LENGTH, length=2, what="m, a along x and b along y"),
    "floor_inertias": Array(Number(low=0.0, low_open=True, high=1e16),
                            what="kg m^2, first floor up"),
    "base_inertia": Number(low=0.0, low_open=True, high=1e16),
    "storey_stiffnesses_y": Array(Number(low=0.0, low_open=True, high=1e15),
                                  what="N/m, first storey up"),
    "torsional_stiffnesses": Array(Number(low=0.0, low_open=True, high=1e20),
                                   what="N m/rad, first storey up"),
    "storey_heights": Either((Number(low=0.0, low_open=True, high=1000.0),
                              Array(Number(low=0.0, low_open=True, high=1000.0),
                                    what="m, first storey up"))),
}
"""Key of ``[plan]`` -> what its value must be."""

_PER_STOREY = ("floor_inertias", "storey_stiffnesses_y", "torsional_stiffnesses",
               "storey_heights")


def check_plan(raw: dict[str, Any], n_storeys: int, bearing: dict[str, Any],
               path: Path) -> dict[str, Any] | None:
    """Check the ``[plan]`` table of a building file's table ``raw`` (None when absent).

    Parameters
    ----------
    raw : dict
        The whole file's table.
    n_storeys : int
        Floors of ``[building]`` (per-storey keys must hold one value each).
    bearing : dict
        The checked ``[bearing]`` table (its ``count`` must match the coordinates).
    path : Path
        The file, for the messages.

    Raises
    ------
    ConfigError
        Naming the file, ``[plan]``, the key, what is allowed and the value given; for an
        unknown or missing key; for a per-storey key of another length.
    """
    if "plan" not in raw:
        return None
    table = raw["plan"]
    if not isinstance(table, dict):
        raise Where(path, "", "plan").error("a table", table)
    unknown = sorted(set(table) - set(PLAN_SCHEMA))
    if unknown:
        raise ConfigError(f"{path}: unknown key(s) {', '.join(map(repr, unknown))} in [plan]; "
                          f"allowed: {sorted(PLAN_SCHEMA)}.")
    if "bearing_coordinates" not in table:
        raise ConfigError(f"{path}: [plan] needs 'bearing_coordinates' (the bearings' (x, y) "
                          "[m] from the centre of stiffness).")
    for key, value in table.items():
        PLAN_SCHEMA[key].check(value, Where(path, "plan", key))
    for key in _PER_STOREY:
        value = table.get(key)
        if isinstance(value, list) and len(value) != n_storeys:
            raise ConfigError(f"{Where(path, 'plan', key)} must hold one value per storey "
                              f"({n_storeys}, as 'floor_masses'). Got {len(value)} instead.")
    eccentricity = table.get("eccentricity", [0.0, 0.0])
    if isinstance(eccentricity[0], list) and len(eccentricity) != n_storeys:
        raise ConfigError(f"{Where(path, 'plan', 'eccentricity')} must be one [e_x, e_y] pair "
                          f"or one per floor ({n_storeys}). Got {len(eccentricity)} pairs "
                          "instead.")
    count = len(table["bearing_coordinates"])
    if "count" in bearing and bearing["count"] != count:
        raise ConfigError(f"{Where(path, 'bearing', 'count')} must be the number of "
                          f"[plan] 'bearing_coordinates' ({count}) or left out. Got "
                          f"{bearing['count']} instead.")
    return table


def build_plan(table: dict[str, Any]) -> Plan:
    """The :class:`~structures.spatial.plan.Plan` of a checked ``[plan]`` table."""
    return Plan(**table)
