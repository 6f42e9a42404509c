"""Units of ground acceleration in record files: factors to [m/s^2], spellings, plausibility.

Every reader converts a file's values to [m/s^2] with :data:`TO_M_PER_S2`, whose factors come
from `dcfpb.common.units` (``STANDARD_GRAVITY`` = 9.80665 m/s^2; the inch 0.0254 m and the foot
0.3048 m exactly).

=========  ===================  ================================================================
name       factor to m/s^2      spellings recognised (any case, blanks around ``/ ^ *`` ignored)
=========  ===================  ================================================================
g          9.80665              ``g``, ``G``, ``g's``, ``gs``
cm/s^2     0.01                 ``gal``, ``gals``, ``CM/S/S``, ``CM/SEC/SEC``, ``cm/s2``,
                                ``cm/s**2``, ``CM/SEC**2``, ``cm/s²``, ``cm s^-2``, ``cm/sec^2``
m/s^2      1                    ``M/S/S``, ``M/SEC/SEC``, ``m/s2``, ``m/s**2``, ``m s^-2`` ...
mm/s^2     0.001                ``MM/S/S``, ``mm/sec/sec``, ``mm/s2`` ...
in/s^2     0.0254               ``IN/S/S``, ``IN/SEC/SEC``, ``in/s2``, ``inch/s^2`` ...
ft/s^2     0.3048               ``FT/S/S``, ``ft/sec/sec``, ``ft/s2``, ``feet/s^2`` ...
=========  ===================  ================================================================

Velocity units (``cm/s``, ``m/sec`` ...) and lengths (``cm``, ``in`` ...) are recognised as
such, so that a velocity or displacement record is refused, not read as an acceleration.
"""

from __future__ import annotations

import math
import re

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.units import M_PER_FOOT, M_PER_INCH, STANDARD_GRAVITY

__all__ = [
    "DEFAULT_UNITS",
    "PGA_LIMITS_G",
    "TO_M_PER_S2",
    "TYPICAL_PGA_G",
    "UNIT_NAMES",
    "check_units",
    "describe_units",
    "likely_units",
    "parse_units",
    "quantity_of",
]

TO_M_PER_S2: dict[str, float] = {
    "g": STANDARD_GRAVITY,
    "cm/s^2": 0.01,
    "m/s^2": 1.0,
    "mm/s^2": 0.001,
    "in/s^2": M_PER_INCH,
    "ft/s^2": M_PER_FOOT,
}
"""Canonical unit name -> factor from the unit to [m/s^2]; ``gal`` is ``cm/s^2``."""

UNIT_NAMES: tuple[str, ...] = ("g", "gal", "cm/s^2", "m/s^2", "mm/s^2", "in/s^2", "ft/s^2")
"""The names a caller may give (the ``--units`` choices); other spellings are accepted too."""

DEFAULT_UNITS = "g"
"""Units of a file whose header states none and whose caller gives none (the PEER convention)."""

PGA_LIMITS_G = (1e-4, 5.0)
"""A record whose PGA falls outside this range [g] is refused as implausible."""

TYPICAL_PGA_G = (0.01, 2.0)
"""The range of PGA [g] a unit must bring a refused record into to be suggested for it."""

_LENGTHS = {
    "cm": "cm", "centimeter": "cm", "centimetre": "cm", "centimeters": "cm", "centimetres": "cm",
    "mm": "mm", "millimeter": "mm", "millimetre": "mm", "millimeters": "mm", "millimetres": "mm",
    "m": "m", "meter": "m", "metre": "m", "meters": "m", "metres": "m",
    "in": "in", "inch": "in", "inches": "in", "ins": "in",
    "ft": "ft", "foot": "ft", "feet": "ft",
}  # fmt: skip
_G = {"g", "gs", "g's", "gees"}
_GAL = {"gal", "gals", "galileo", "galileos"}
_PER_SECOND_SQUARED = re.compile(r"^(?P<length>[a-z]+)(?:/s/s|/s\^?2|/\(s\^?2\)|[*.·]?s\^?-2)$")
_PER_SECOND = re.compile(r"^(?P<length>[a-z]+)(?:/s|[*.·]?s\^?-1)$")


def _normalised(text: str) -> str:
    """Lower case, no blanks, ``sec``/``second(s)`` as ``s``, ``**`` and ``²`` as ``^2``."""
    s = text.strip().lower().replace("²", "^2").replace("⁻", "-").replace("**", "^")
    s = re.sub(r"\s+", "", s).strip(".,;:'\"")
    if s.startswith(("(", "[")) and s.endswith((")", "]")):
        s = s[1:-1]
    return re.sub(r"sec(?:ond)?s?", "s", s)


def quantity_of(text: str) -> tuple[str, str] | None:
    """``(quantity, canonical name)`` of a unit as written, or None when it is not one:
    ``"acceleration"`` (a key of :data:`TO_M_PER_S2`), ``"velocity"`` or ``"displacement"``."""
    s = _normalised(text)
    if s in _G:
        return "acceleration", "g"
    if s in _GAL:
        return "acceleration", "cm/s^2"
    match = _PER_SECOND_SQUARED.match(s)
    if match and match["length"] in _LENGTHS:
        return "acceleration", f"{_LENGTHS[match['length']]}/s^2"
    match = _PER_SECOND.match(s)
    if match and match["length"] in _LENGTHS:
        return "velocity", f"{_LENGTHS[match['length']]}/s"
    if s in _LENGTHS:
        return "displacement", _LENGTHS[s]
    return None


def parse_units(text: str) -> str | None:
    """The canonical name (a key of :data:`TO_M_PER_S2`) of an acceleration unit as written,
    or None when ``text`` is not an acceleration unit the readers know."""
    if not isinstance(text, str):
        raise InputTypeError(f"The 'text' parameter of parse_units must be a str. Got "
                             f"{text!r:.80} instead.")
    found = quantity_of(text)
    return found[1] if found and found[0] == "acceleration" else None


def describe_units(name: str) -> str:
    """A unit's name for messages: ``"cm/s^2 (gal)"`` for cm/s^2, the name otherwise."""
    return "cm/s^2 (gal)" if name == "cm/s^2" else name


def check_units(units: object, owner: str) -> str:
    """The canonical name of a unit a caller gives (``units=``, ``--units``): one of
    :data:`UNIT_NAMES` or another spelling (``"m/s2"``, ``"CM/S/S"`` ...). Any other value raises
    `InputError` naming ``owner`` (the function or option), the value and the known units."""
    name = parse_units(units) if isinstance(units, str) else None
    if name is None:
        raise InputError(
            f"The 'units' parameter of {owner} must be an acceleration unit, one of "
            f"{', '.join(UNIT_NAMES)}. Got {units!r} instead."
        )
    return name


def likely_units(peak: float, current: str) -> list[tuple[str, float]]:
    """The known units, other than ``current``, that bring a record's ``peak`` (max |value| in
    the file's units) into :data:`TYPICAL_PGA_G`, as (canonical unit, PGA [g]) pairs, likeliest
    (nearest the geometric middle of the range) first."""
    low, high = TYPICAL_PGA_G
    middle = math.log10(math.sqrt(low * high))
    found = []
    for name, factor in TO_M_PER_S2.items():
        pga = peak * (factor / STANDARD_GRAVITY)
        if name != current and low <= pga <= high:
            found.append((abs(math.log10(pga) - middle), name, pga))
    return [(name, pga) for _, name, pga in sorted(found)]
