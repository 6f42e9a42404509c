"""The building file's schema: every section and key, its TOML type and allowed range
(:data:`SCHEMA`; :data:`PLAN_SCHEMA` for the ``[plan]`` table of a building in plan, as in
``examples/five_storey_plan.toml``).

:func:`check_tables` and :func:`check_plan` check every value before any object is built:
numbers are numbers (not ``true`` or ``"6"``), integers are integers (not ``2.7`` or ``true``),
arrays hold numbers, values lie in their ranges, and every friction parameter is checked
whatever model the file chooses (``--model`` and suites run the others). An error is a
:class:`ConfigError` naming the file, section, key, what is allowed and the value given, e.g.
``five_storey.toml: [bearing] 'count' must be an integer in [1, 10000]. Got 2.7 (a float)
instead.`` A setting without effect (``alpha`` under Newmark, ``modes`` under modal damping) is
accepted with a :class:`ConfigWarning`.
"""

from __future__ import annotations

import difflib
import math
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputWarning

MAX_STOREYS = 1000
"""Most floors a building file may describe (the tallest buildings have about 160)."""
MAX_BEARINGS = 10_000
"""Most bearings a building file may share its weight among."""
PROFILES = ("uniform", "triangular", "storey_shear")
FRICTION_MODELS = ("precise", "simplified", "constant")
INTEGRATORS = ("newmark", "hht")
DAMPING_KINDS = ("rayleigh", "modal")


class ConfigError(InputError):
    """A building file that cannot be used, with the file, section and key named."""


class ConfigWarning(InputWarning):
    """A setting of a building file that is accepted but has no effect, and why."""


_KINDS = ((bool, "a boolean"), (int, "an integer"), (float, "a float"), (str, "a string"),
          (list, "an array"), (dict, "a table"))


def _kind(value: object) -> str:
    """The TOML type of a parsed value, with its article."""
    return next((name for kind, name in _KINDS if isinstance(value, kind)),
                f"a {type(value).__name__.replace('datetime', 'date-time')}")


def _values(n: int) -> str:
    return "1 value" if n == 1 else f"{n} values"


def _shown(value: object) -> str:
    """A value as the file would write it, cut short."""
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, str):
        text = '"' + value.replace('"', '\\"') + '"'
    else:
        text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


@dataclass(frozen=True)
class Where:
    """A key of a building file, for the messages."""

    path: Path
    section: str
    key: str

    def __str__(self) -> str:
        return f"{self.path}: [{self.section or 'top'}] {self.key!r}"

    def error(self, allowed: str, value: object, detail: str = "") -> ConfigError:
        """The error for ``value`` where ``allowed`` was expected."""
        return ConfigError(f"{self} must be {allowed}. Got {_shown(value)} ({_kind(value)})"
                           f"{detail} instead.")

    def warn(self, text: str) -> None:
        """Say that this key is ignored, and why."""
        warnings.warn(f"{self} is ignored: {text}.", ConfigWarning, stacklevel=2)


@dataclass(frozen=True)
class Number:
    """A real number (TOML integer or float) in an interval; ``allow_inf`` admits +inf."""

    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    allow_inf: bool = False
    text: str | None = None  # how the interval is written, when not by its bounds

    @property
    def interval(self) -> str:
        if self.text:
            return self.text
        left = "(" if self.low is None or self.low_open else "["
        right = ")" if self.high is None or (self.high_open and not self.allow_inf) else "]"
        low = "-inf" if self.low is None else f"{self.low:g}"
        high = "inf" if self.high is None or self.allow_inf else f"{self.high:g}"
        return f"{left}{low}, {high}{right}"

    @property
    def allowed(self) -> str:
        return f"a number in {self.interval}"

    def fits(self, value: object) -> bool:
        if isinstance(value, bool) or not isinstance(value, int | float):
            return False
        x = float(value)
        if math.isnan(x) or (math.isinf(x) and not (self.allow_inf and x > 0)):
            return False
        if self.low is not None and (x < self.low or (self.low_open and x == self.low)):
            return False
        return self.high is None or math.isinf(x) or x < self.high or (
            x == self.high and not self.high_open)

    def check(self, value: object, where: Where) -> Any:
        if not self.fits(value):
            raise where.error(self.allowed, value)
        return value


@dataclass(frozen=True)
class Integer:
    """A TOML integer (not a float, not a boolean) in ``[low, high]``."""

    low: int
    high: int

    @property
    def allowed(self) -> str:
        return f"an integer in [{self.low}, {self.high}]"

    def check(self, value: object, where: Where) -> Any:
        if isinstance(value, bool) or not isinstance(value, int) or not (
                self.low <= value <= self.high):
            raise where.error(self.allowed, value)
        return value


@dataclass(frozen=True)
class Choice:
    """One of a few strings."""

    choices: tuple[str, ...]

    @property
    def allowed(self) -> str:
        return "one of " + ", ".join(f'"{c}"' for c in self.choices)

    def fits(self, value: object) -> bool:
        return isinstance(value, str) and value in self.choices

    def check(self, value: object, where: Where) -> Any:
        if not self.fits(value):
            raise where.error(self.allowed, value)
        return value


@dataclass(frozen=True)
class Boolean:
    """true or false."""

    allowed: str = "true or false"

    def check(self, value: object, where: Where) -> Any:
        if not isinstance(value, bool):
            raise where.error(self.allowed, value)
        return value


@dataclass(frozen=True)
class Text:
    """Any string."""

    allowed: str = "a string"

    def check(self, value: object, where: Where) -> Any:
        if not isinstance(value, str):
            raise where.error(self.allowed, value)
        return value


@dataclass(frozen=True)
class Array:
    """An array of ``item`` values: ``length`` of them, or ``min_length`` to ``max_length``."""

    item: Number | Integer
    min_length: int = 1
    max_length: int = MAX_STOREYS
    length: int | None = None
    what: str = "values"

    @property
    def allowed(self) -> str:
        count = (f"{self.length}" if self.length is not None
                 else f"{self.min_length} to {self.max_length}")
        inside = self.item.allowed.removeprefix("a number ").removeprefix("an integer ")
        kind = "integers" if isinstance(self.item, Integer) else "numbers"
        return f"an array of {count} {kind} {inside}".rstrip() + f" ({self.what})"

    def check(self, value: object, where: Where) -> Any:
        if not isinstance(value, list):
            raise where.error(self.allowed, value)
        low, high = ((self.length, self.length) if self.length is not None
                     else (self.min_length, self.max_length))
        if not low <= len(value) <= high:
            raise ConfigError(f"{where} must be {self.allowed}. Got {_values(len(value))} "
                              "instead.")
        for i, item in enumerate(value):
            try:
                self.item.check(item, where)
            except ConfigError:
                raise where.error(self.allowed, item, f" at index {i}") from None
        return value


@dataclass(frozen=True)
class Either:
    """A value of the first kind that fits, e.g. one ratio or an array of them."""

    kinds: tuple[Number | Array | Choice, ...]

    @property
    def allowed(self) -> str:
        return " or ".join(kind.allowed for kind in self.kinds)

    def check(self, value: object, where: Where) -> Any:
        wanted = Array if isinstance(value, list) else Choice if isinstance(value, str) else Number
        kind = next((k for k in self.kinds if isinstance(k, wanted)), None)
        if kind is None or (wanted is not Array and not kind.fits(value)):
            raise where.error(self.allowed, value)
        return kind.check(value, where)


_MASS = Number(low=0.0, low_open=True, high=1e10)  # [kg]; ten million tonnes a floor
_RATIO = Number(low=0.0, high=1.0, high_open=True)
_TABLE = "a table"

SCHEMA: dict[str, dict[str, Any]] = {
    "": {"name": Text(), "building": _TABLE, "bearing": _TABLE, "friction": _TABLE,
         "analysis": _TABLE, "plan": _TABLE,  # [plan]: PLAN_SCHEMA below
         "design": _TABLE},
    "building": {
        "floor_masses": Array(_MASS, what="kg, first floor up"),
        "storey_stiffnesses": Array(Number(low=0.0, low_open=True, high=1e15),
                                    what="N/m, first storey up"),
        "fixed_base_period": Number(low=1e-3, high=100.0),
        "stiffness_profile": Either((Choice(PROFILES), Array(Number(low=1e-6, high=1e6),
                                                             what="relative, first storey up"))),
        "base_mass": _MASS,
        "damping": _TABLE,
    },
    "building.damping": {
        "kind": Choice(DAMPING_KINDS),
        "ratios": Either((_RATIO, Array(_RATIO, what="-"))),
        "modes": Array(Integer(1, MAX_STOREYS), length=2, what="1-based mode numbers"),
        "ratio": Either((_RATIO, Array(_RATIO, what="-, one per mode"))),
    },
    "bearing": {
        "count": Integer(1, MAX_BEARINGS),
        "effective_radius": Number(low=1e-3, high=1e4, allow_inf=True,
                                   text="[0.001, 10000] or inf (a flat slider)"),
        "slider_diameter": Number(low=1e-3, high=10.0),
        "yield_displacement": Number(low=0.0, low_open=True, high=0.1),
        "displacement_capacity": Number(low=0.0, low_open=True, high=10.0),
    },
    "friction": {
        "model": Choice(FRICTION_MODELS),
        "mu_t0": Number(low=0.0, low_open=True, high=1.0),
        "refinement": Number(low=0.0, low_open=True, high=2.0),
        "mu0": Number(low=0.0, low_open=True, high=1.0),
        "design_velocity": Number(low=0.0, high=100.0),
        "initial_temperature": Number(low=-273.15, high=1000.0),
    },
    "design": {  # ASCE 7-16 Chapter 17 (structures.design): lambda as overall or as parts
        "lambda_max": Number(low=1.0, high=10.0),
        "lambda_min": Number(low=0.0, low_open=True, high=1.0),
        "ae_max": Number(low=1.0, high=10.0),
        "ae_min": Number(low=0.0, low_open=True, high=1.0),
        "test_max": Number(low=1.0, high=10.0),
        "test_min": Number(low=0.0, low_open=True, high=1.0),
        "spec_max": Number(low=1.0, high=10.0),
        "spec_min": Number(low=0.0, low_open=True, high=1.0),
        "test_includes_heating": Boolean(),
        "test_heating_max": Number(low=1.0, high=10.0),
        "test_heating_min": Number(low=0.0, low_open=True, high=1.0),
        "S_MS": Number(low=0.0, low_open=True, high=5.0),
        "S_M1": Number(low=0.0, low_open=True, high=5.0),
        "T_L": Number(low=0.0, low_open=True, high=100.0),
        "R": Number(low=0.0, low_open=True, high=10.0),
        "I_e": Number(low=1.0, high=1.5),
    },
    "analysis": {
        "integrator": Choice(INTEGRATORS),
        "alpha": Number(low=-1 / 3, high=0.0, text="[-1/3, 0]"),
        "dt": Number(low=0.0, low_open=True, high=1.0),
    },
}
"""Section (``""`` for the top level) -> key -> what its value must be (or "a table")."""


def _check_keys(table: dict[str, Any], section: str, path: Path) -> None:
    allowed = sorted(SCHEMA[section])
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        hints = [f"{key!r} (did you mean {close[0]!r}?)" if close else repr(key)
                 for key in unknown
                 for close in [difflib.get_close_matches(key, allowed, n=1)]]
        raise ConfigError(f"{path}: unknown key(s) {', '.join(hints)} in "
                          f"[{section or 'top'}]; allowed: {allowed}.")


def _section(raw: dict[str, Any], section: str, path: Path) -> dict[str, Any]:
    """Check the keys and values of one table (sub-tables are checked on their own)."""
    parent, _, name = section.rpartition(".")
    table = raw.get(name, {})
    if not isinstance(table, dict):
        raise Where(path, parent, name).error(_TABLE, table)
    _check_keys(table, section, path)
    for key, value in table.items():
        spec = SCHEMA[section][key]
        if spec == _TABLE:
            if not isinstance(value, dict):
                raise Where(path, section, key).error(_TABLE, value)
        else:
            spec.check(value, Where(path, section, key))
    return table


def _building(b: dict[str, Any], path: Path) -> None:
    """The building's keys that depend on each other."""
    def where(key: str, section: str = "building") -> Where:
        return Where(path, section, key)

    for key in ("floor_masses", "base_mass"):
        if key not in b:
            raise ConfigError(f"{path}: [building] needs {key!r}.")
    n = len(b["floor_masses"])
    for key in ("storey_stiffnesses", "stiffness_profile"):
        value = b.get(key)
        if isinstance(value, list) and len(value) != n:
            raise ConfigError(f"{where(key)} must hold one value per floor ({n}, as "
                              f"'floor_masses'). Got {_values(len(value))} instead.")
    if "storey_stiffnesses" in b:
        for key in ("fixed_base_period", "stiffness_profile"):
            if key in b:
                where(key).warn("'storey_stiffnesses' gives the stiffnesses")
    elif "fixed_base_period" not in b:
        raise ConfigError(f"{path}: [building] needs 'storey_stiffnesses' or "
                          "'fixed_base_period'.")
    damping = b.get("damping", {})
    kind = damping.get("kind", "rayleigh")
    section = "building.damping"
    if kind == "rayleigh":
        ratios = damping.get("ratios", [0.02, 0.02])
        if not isinstance(ratios, list) or len(ratios) != 2:
            raise where("ratios", section).error(
                "an array of 2 numbers in [0, 1) (-) for kind = \"rayleigh\"", ratios)
        modes = damping.get("modes", [1, 2])
        if modes[0] == modes[1] or max(modes) > n:
            raise where("modes", section).error(
                f"2 distinct mode numbers in [1, {n}] for a {n}-storey building (kind = "
                '"modal" damps a single storey)', modes, "" if "modes" in damping
                else " (the default)")
        if "ratio" in damping:
            where("ratio", section).warn("kind = \"rayleigh\" takes 'ratios' at two 'modes'")
    else:
        if "modes" in damping:
            where("modes", section).warn("kind = \"modal\" damps every mode alike")
        if "ratio" in damping and "ratios" in damping:
            where("ratios", section).warn("'ratio' is given")
        ratio = damping.get("ratio", damping.get("ratios", 0.02))
        if isinstance(ratio, list) and len(ratio) != n:
            key = "ratio" if "ratio" in damping else "ratios"
            raise ConfigError(f"{where(key, section)} must hold one ratio per mode ({n}) for "
                              f"kind = \"modal\". Got {_values(len(ratio))} instead.")


LAMBDA_PARTS = ("ae_max", "ae_min", "test_max", "test_min", "spec_max", "spec_min")
"""The ``[design]`` keys of lambda given by its parts (ASCE 7-16 Eq. 17.2-1, 17.2-2)."""


def _design(table: dict[str, Any], path: Path) -> None:
    """The ``[design]`` keys that depend on each other: lambda_max with lambda_min and not
    with the parts, S_MS with S_M1, T_L only with them."""
    for first, second in (("lambda_max", "lambda_min"), ("S_MS", "S_M1")):
        if (first in table) != (second in table):
            given, missing = (first, second) if first in table else (second, first)
            raise ConfigError(f"{Where(path, 'design', missing)} must be given with "
                              f"{given!r}.")
    parts = [key for key in LAMBDA_PARTS if key in table]
    if "lambda_max" in table and parts:
        raise ConfigError(f"{Where(path, 'design', parts[0])} cannot be given with 'lambda_max' "
                          "and 'lambda_min': give lambda as overall values or as its parts "
                          "(ae_*, test_*, spec_*), not both.")
    if "T_L" in table and "S_MS" not in table:
        raise ConfigError(f"{Where(path, 'design', 'T_L')} needs 'S_MS' and 'S_M1'.")


def check_tables(raw: dict[str, Any], path: Path) -> dict[str, dict[str, Any]]:
    """Check a building file's table against :data:`SCHEMA` and the rules between its keys;
    return ``{section: table}`` for ``""``, ``"building"``, ``"building.damping"``,
    ``"bearing"``, ``"friction"``, ``"analysis"`` and ``"design"`` (absent ones empty), values
    as given.

    Raises
    ------
    ConfigError
        For a key or value the schema refuses (module docstring).

    Warns
    -----
    ConfigWarning
        For a setting that has no effect: ``alpha`` without ``integrator = "hht"``, a stiffness
        period or profile beside ``storey_stiffnesses``, a damping key the damping kind does not
        use.
    """
    tables = {"": _section({"": raw}, "", path)}
    for section in ("building", "building.damping", "bearing", "friction", "analysis",
                    "design"):
        parent = tables[section.rpartition(".")[0]]
        tables[section] = _section(parent, section, path)
    _design(tables["design"], path)
    _building(tables["building"], path)
    for key in ("effective_radius", "slider_diameter"):
        if key not in tables["bearing"]:
            raise ConfigError(f"{path}: [bearing] needs {key!r}.")
    check_bearing_geometry(tables["bearing"], path)
    analysis = tables["analysis"]
    if "alpha" in analysis and analysis.get("integrator", "newmark") != "hht":
        Where(path, "analysis", "alpha").warn(
            'it applies to integrator = "hht" only, and this file runs "newmark"')
    return tables


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
    "load_eccentricity": Pairs(_COORDINATE, "m, the centre the bearings' gravity loads are "
                               "shared from: one pair for every level or one per level, base "
                               "slab first"),
}
"""Key of ``[plan]`` -> what its value must be."""

_PER_STOREY = ("floor_inertias", "storey_stiffnesses_y", "torsional_stiffnesses",
               "storey_heights")


def check_plan(raw: dict[str, Any], n_storeys: int, bearing: dict[str, Any],
               path: Path) -> dict[str, Any] | None:
    """Check the ``[plan]`` table of a building file's table ``raw`` against :data:`PLAN_SCHEMA`
    (None when there is none), for the ``n_storeys`` floors of ``[building]`` and the checked
    ``[bearing]`` table, whose ``count`` must match the coordinates; ``path`` names the file.

    Raises
    ------
    ConfigError
        For an unknown or missing key, a value of the wrong kind or outside its range, a
        per-storey key of another length (module docstring), two bearings at one point (within
        :data:`SAME_POINT` m), or, with ``dimensions``, bearings or centres of mass that no
        a x b slab covers (:func:`_plan_geometry`).
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
    loads = table.get("load_eccentricity", [0.0, 0.0])
    if isinstance(loads[0], list) and len(loads) != n_storeys + 1:
        raise ConfigError(f"{Where(path, 'plan', 'load_eccentricity')} must be one [x, y] pair "
                          f"or one per level, base slab first ({n_storeys + 1}). Got "
                          f"{len(loads)} pairs instead.")
    _plan_geometry(table, path)
    count = len(table["bearing_coordinates"])
    if "count" in bearing and bearing["count"] != count:
        raise ConfigError(f"{Where(path, 'bearing', 'count')} must be the number of "
                          f"[plan] 'bearing_coordinates' ({count}) or left out. Got "
                          f"{bearing['count']} instead.")
    return table


SAME_POINT = 1e-3
"""Two bearings closer than this [m] stand at one point (a bearing is some 0.3 to 1.5 m wide)."""


def _plan_geometry(table: dict[str, Any], path: Path) -> None:
    """The bearings of a checked ``[plan]`` table each at its own point and, when the plan's
    ``dimensions`` (a, b) are given, the bearings and the centres of mass (floors and base slab)
    within one a x b slab: their extent along x at most a, along y at most b, wherever the slab
    lies about the centre of stiffness."""
    xy = np.asarray(table["bearing_coordinates"], dtype=float)
    where = Where(path, "plan", "bearing_coordinates")
    close = _same_point(xy, SAME_POINT)
    if close is not None:
        i, j = close
        gap = float(np.hypot(*(xy[i] - xy[j])))
        raise ConfigError(f"{where} must give each bearing its own point (at least "
                          f"{SAME_POINT * 1e3:g} mm apart). Got bearings {i} and {j} both at "
                          f"{_xy(xy[i])} m ({gap * 1e3:.3g} mm apart) instead; a position "
                          "carries one bearing.")
    if "dimensions" not in table:
        return
    size = np.asarray(table["dimensions"], dtype=float)
    slack = 1e-9 * (1.0 + size)
    for axis, name in ((0, "x"), (1, "y")):
        low, high = int(np.argmin(xy[:, axis])), int(np.argmax(xy[:, axis]))
        span = xy[high, axis] - xy[low, axis]
        if span > size[axis] + slack[axis]:
            raise ConfigError(
                f"{where} must lie within the slab of 'dimensions' {_xy(size)} m. Got bearings "
                f"{low} at {_xy(xy[low])} m and {high} at {_xy(xy[high])} m, {span:g} m apart "
                f"along {name}, more than the plan's {'ab'[axis]} = {size[axis]:g} m, instead.")
    eccentricity = np.asarray(table.get("eccentricity", [0.0, 0.0]), dtype=float).reshape(-1, 2)
    centres = [("eccentricity", f" of floor {k + 1}" if len(eccentricity) > 1 else "", e)
               for k, e in enumerate(eccentricity)]
    centres.append(("base_eccentricity", "",
                    np.asarray(table.get("base_eccentricity", [0.0, 0.0]), dtype=float)))
    for key, which, centre in centres:
        for axis, name in ((0, "x"), (1, "y")):
            low = min(float(xy[:, axis].min()), centre[axis])
            high = max(float(xy[:, axis].max()), centre[axis])
            if high - low > size[axis] + slack[axis]:
                far = int(np.argmax(np.abs(xy[:, axis] - centre[axis])))
                raise ConfigError(
                    f"{Where(path, 'plan', key)} must put the centre of mass within the slab "
                    f"of 'dimensions' {_xy(size)} m that covers the bearings. Got {_xy(centre)} "
                    f"m{which}, {abs(xy[far, axis] - centre[axis]):g} m along {name} from "
                    f"bearing {far} at {_xy(xy[far])} m, more than the plan's "
                    f"{'ab'[axis]} = {size[axis]:g} m, instead.")


def _same_point(xy: np.ndarray, tolerance: float) -> tuple[int, int] | None:
    """The first two of the points ``xy`` (n, 2) [m] closer than ``tolerance`` [m] (lower index
    first), or None: a sweep along x, each point against the next ones within ``tolerance``."""
    order = np.argsort(xy[:, 0], kind="stable")
    ranked = xy[order]
    found = []
    for k in range(1, len(xy)):
        dx = ranked[k:, 0] - ranked[:-k, 0]
        near = dx < tolerance
        if not near.any():
            break
        hit = np.flatnonzero(near & (np.hypot(dx, ranked[k:, 1] - ranked[:-k, 1]) < tolerance))
        found += [tuple(sorted((int(order[h]), int(order[h + k])))) for h in hit[:1]]
    return min(found) if found else None


def _xy(pair: Any) -> str:
    """``(x, y)`` of a pair, short."""
    return f"({float(pair[0]):g}, {float(pair[1]):g})"


MAX_SLOPE = 0.5
"""Largest displacement capacity of a bearing over its effective radius [-]: u / R_eff is the
sine of the plates' slope at the capacity (30 degrees at 0.5; built bearings stay below about
0.2), and the pendulum law F = N u / R_eff is a small-slope one; at 1 the geometry is
impossible."""


def check_bearing_geometry(bearing: dict[str, Any], path: Path) -> None:
    """Check a checked ``[bearing]`` table's geometry: a finite ``effective_radius`` R_eff
    [m] must exceed the ``slider_diameter`` [m] (the slider sits in plates of radius about
    R_eff / 2) and bound the ``displacement_capacity`` [m] (given or the default 0.6 m) to
    :data:`MAX_SLOPE` R_eff.

    Raises
    ------
    ConfigError
        Naming the file, ``[bearing]``, the key, the limit and the value given.
    """
    radius = float(bearing["effective_radius"])
    if math.isinf(radius):
        return
    slider = float(bearing["slider_diameter"])
    if slider >= radius:
        raise ConfigError(f"{Where(path, 'bearing', 'slider_diameter')} must be below the "
                          f"'effective_radius' {radius:g} m (the slider sits in concave plates "
                          f"of radius about R_eff / 2). Got {slider:g} instead.")
    capacity = float(bearing.get("displacement_capacity", 0.6))
    limit = MAX_SLOPE * radius
    if capacity > limit:
        given = "" if "displacement_capacity" in bearing else " (the default)"
        raise ConfigError(
            f"{Where(path, 'bearing', 'displacement_capacity')} must be at most {MAX_SLOPE:g} "
            f"x 'effective_radius' = {limit:g} m: at u / R_eff = {capacity / radius:.3g} the "
            f"plates would slope {math.degrees(math.asin(min(capacity / radius, 1.0))):.0f} "
            f"degrees (more than {math.degrees(math.asin(MAX_SLOPE)):.0f}; impossible at 1). "
            f"Got {capacity:g}{given} instead.")
