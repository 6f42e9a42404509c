"""Units of ground acceleration in record files: factors to [m/s^2], spellings, plausibility.

Every reader converts a file's values to [m/s^2] with :data:`TO_M_PER_S2`, whose factors come
from `dcfpb.common.units` (``STANDARD_GRAVITY`` = 9.80665 m/s^2; the inch 0.0254 m and the foot
0.3048 m exactly).

=========  ===================  ================================================================
name       factor to m/s^2      spellings recognised (any case, blanks around ``/ ^ *`` ignored)
=========  ===================  ================================================================
g          9.80665              ``g``, ``G``, ``g's``, ``gs``
mg         0.00980665           ``mg``, ``MG``, ``milli-g``, ``milli g`` (a thousandth of g)
cm/s^2     0.01                 ``gal``, ``gals``, ``CM/S/S``, ``CM/SEC/SEC``, ``cm/s2``,
                                ``cm/s**2``, ``CM/SEC**2``, ``cm/s²``, ``cm s^-2``, ``cm/sec^2``
m/s^2      1                    ``M/S/S``, ``M/SEC/SEC``, ``m/s2``, ``m/s**2``, ``m s^-2`` ...
mm/s^2     0.001                ``MM/S/S``, ``mm/sec/sec``, ``mm/s2`` ...
in/s^2     0.0254               ``IN/S/S``, ``IN/SEC/SEC``, ``in/s2``, ``inch/s^2`` ...
ft/s^2     0.3048               ``FT/S/S``, ``ft/sec/sec``, ``ft/s2``, ``feet/s^2`` ...
=========  ===================  ================================================================

Velocity units (``cm/s``, ``m/sec`` ...) and lengths (``cm``, ``in`` ...) are recognised as
such, so that a velocity or displacement record is refused, not read as an acceleration.

Time steps are read in seconds (``s``, ``sec``, ``secs``, ``second(s)``) or milliseconds
(``ms``, ``msec``, ``msecs``, ``millisecond(s)``) by :func:`parse_time_unit`. :func:`read_unit`
is the one reader of a unit as written in any header (records and bearing-test files): it tells
the quantity (acceleration, velocity, displacement or time), the canonical name and the factor to
SI (m/s^2, m/s, m, s).

A record read from a file must also be plausible: PGA within :data:`PGA_LIMITS_G` (at most
:data:`UNSTATED_MAX_PGA_G` when its units are not stated but taken as g), time step
within :data:`DT_LIMITS_S` and duration at most :data:`MAX_DURATION_S`
(:func:`groundmotions.filetext.check_record_plausible`).
"""

from __future__ import annotations

import math
import re
from typing import NamedTuple

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.units import M_PER_FOOT, M_PER_INCH, STANDARD_GRAVITY

__all__ = [
    "DEFAULT_UNITS",
    "DT_LIMITS_S",
    "MAX_DURATION_S",
    "PGA_LIMITS_G",
    "TO_M_PER_S2",
    "TO_SECONDS",
    "TYPICAL_PGA_G",
    "UNIT_NAMES",
    "UNSTATED_MAX_PGA_G",
    "Unit",
    "check_units",
    "describe_units",
    "likely_units",
    "parse_time_unit",
    "parse_units",
    "quantity_of",
    "read_unit",
]

TO_M_PER_S2: dict[str, float] = {
    "g": STANDARD_GRAVITY,
    "mg": STANDARD_GRAVITY / 1000.0,
    "cm/s^2": 0.01,
    "m/s^2": 1.0,
    "mm/s^2": 0.001,
    "in/s^2": M_PER_INCH,
    "ft/s^2": M_PER_FOOT,
}
"""Canonical unit name -> factor from the unit to [m/s^2]; ``gal`` is ``cm/s^2``."""

UNIT_NAMES: tuple[str, ...] = ("g", "mg", "gal", "cm/s^2", "m/s^2", "mm/s^2", "in/s^2", "ft/s^2")
"""The names a caller may give (the ``--units`` choices); other spellings are accepted too."""

DEFAULT_UNITS = "g"
"""Units of a file whose header states none and whose caller gives none (the PEER convention)."""

PGA_LIMITS_G = (1e-4, 5.0)
"""A record whose PGA falls outside this range [g] is refused as implausible."""

TYPICAL_PGA_G = (0.01, 2.0)
"""The range of PGA [g] a unit must bring a refused record into to be suggested for it."""

UNSTATED_MAX_PGA_G = 2.0
"""The most PGA [g] of a record whose units are neither stated in its header nor given (read
as g by default): values of m/s^2 read as g land between 2 and 10 g for PGA of 0.2 to 1 g, so
such a record must state its units (``UNITS OF G``, ``--units g``) to be read."""

DT_LIMITS_S = (1e-5, 0.1)
"""A record whose time step [s] falls outside this range is refused as implausible: 0.1 s
(10 samples a second) is coarser than any accelerograph; a step above it is most often one in
milliseconds read as seconds, below 1e-5 s (100 kHz) one in seconds read as something smaller."""

MAX_DURATION_S = 1800.0
"""A record longer than this [s] (half an hour; the longest strong-motion records last minutes)
is refused as implausible: most often a time step in the wrong unit."""

TO_SECONDS: dict[str, float] = {"s": 1.0, "ms": 1e-3}
"""Canonical time unit -> factor to [s]."""

_TIMES = {
    "s": "s", "sec": "s", "secs": "s", "second": "s", "seconds": "s",
    "ms": "ms", "msec": "ms", "msecs": "ms", "millisec": "ms", "millisecs": "ms",
    "millisecond": "ms", "milliseconds": "ms", "milli-s": "ms", "milli-sec": "ms",
    "milli-second": "ms", "milli-seconds": "ms",
}  # fmt: skip
_MILLI_G = {"mg", "milli-g", "millig", "milli-gs", "milli-g's"}
_LENGTH_TO_M = {"cm": 0.01, "mm": 0.001, "m": 1.0, "in": M_PER_INCH, "ft": M_PER_FOOT}

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
    if s in _MILLI_G:
        return "acceleration", "mg"
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


def parse_time_unit(text: str) -> str | None:
    """The canonical name (a key of :data:`TO_SECONDS`: ``"s"`` or ``"ms"``) of a time unit as
    written (``SEC``, ``secs``, ``MSEC``, ``milliseconds``, ``(s)``, ``[ms]`` ...), or None."""
    s = text.strip().lower().strip(".,;:'\"")
    if s.startswith(("(", "[")) and s.endswith((")", "]")):
        s = s[1:-1].strip()
    return _TIMES.get(re.sub(r"\s+", "", s))


class Unit(NamedTuple):
    """A unit as read by :func:`read_unit`."""

    quantity: str
    """``"acceleration"``, ``"velocity"``, ``"displacement"`` or ``"time"``."""
    name: str
    """Canonical name: ``"g"``, ``"cm/s^2"``, ``"cm/s"``, ``"cm"``, ``"ms"`` ..."""
    factor: float
    """Factor to SI: [m/s^2], [m/s], [m] or [s]."""


def read_unit(text: str) -> Unit | None:
    """The quantity, canonical name and factor to SI of a unit as written in a header (the one
    reader of units for records and bearing-test files), or None when ``text`` is no unit known.

    Parameters
    ----------
    text : str
        The unit as written: ``"G"``, ``"mg"``, ``"CM/SEC/SEC"``, ``"gal"``, ``"cm/s"``,
        ``"IN"``, ``"MSEC"``, ``"(s)"`` ...

    Returns
    -------
    Unit or None
        E.g. ``Unit("acceleration", "cm/s^2", 0.01)``, ``Unit("velocity", "in/s", 0.0254)``,
        ``Unit("time", "ms", 0.001)``.
    """
    time = parse_time_unit(text)
    if time is not None:
        return Unit("time", time, TO_SECONDS[time])
    found = quantity_of(text)
    if found is None:
        return None
    quantity, name = found
    if quantity == "acceleration":
        return Unit(quantity, name, TO_M_PER_S2[name])
    return Unit(quantity, name, _LENGTH_TO_M[name.split("/")[0]])


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
    """The known units (but mg, 2 % off gal), other than ``current``, that bring a record's
    ``peak`` (max |value| in the file's units) into :data:`TYPICAL_PGA_G`, as (canonical unit,
    PGA [g]) pairs, likeliest (nearest the geometric middle of the range) first."""
    low, high = TYPICAL_PGA_G
    middle = math.log10(math.sqrt(low * high))
    found = []
    for name, factor in TO_M_PER_S2.items():
        if name == "mg":  # within 2 % of gal, and far rarer: gal is the one suggested
            continue
        pga = peak * (factor / STANDARD_GRAVITY)
        if name != current and low <= pga <= high:
            found.append((abs(math.log10(pga) - middle), name, pga))
    return [(name, pga) for _, name, pga in sorted(found)]
