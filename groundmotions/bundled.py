"""Records shipped with the package (`load_bundled`, `bundled_names`), read without any data
folder of the project."""

from __future__ import annotations

from importlib import resources
from typing import Any

from dcfpb.common.validation import check_choice
from groundmotions.peer import read_peer_at2
from groundmotions.records import GroundMotion

__all__ = ["bundled_names", "load_bundled"]

_BUNDLED: dict[str, tuple[str, dict[str, Any]]] = {
    "elcentro": (
        "elcentro_1940_ns.at2",
        {
            "title": "El Centro 1940 N-S",
            "event": "Imperial Valley 1940",
            "date": "1940-05-19",  # UTC; the evening of 18 May 1940 local time
            "station": "El Centro Array #9 (Imperial Valley Irrigation District substation)",
            "component": "NS",
            "agency": "US Coast and Geodetic Survey (its strong-motion work is now USGS's)",
            "licence": "public domain (US government recording)",
            "origin": "OpenSees EXAMPLES/ExampleScripts/elCentro.AT2 (Peknold version)",
        },
    ),
}


def bundled_names() -> tuple[str, ...]:
    """Names of the records in ``groundmotions/data``, for `load_bundled`."""
    return tuple(sorted(_BUNDLED))


def load_bundled(name: str = "elcentro") -> GroundMotion:
    """The record ``name`` shipped with the package, one of `bundled_names()`: acceleration
    [m/s^2], named by the record's title, with the file's metadata and the recording's event,
    station, licence and origin. ``"elcentro"`` is El Centro 1940 N-S (1559 samples at 0.02 s,
    PGA 0.319 g)."""
    check_choice(name, "name", "load_bundled", bundled_names())
    file_name, extra = _BUNDLED[name]
    resource = resources.files("groundmotions").joinpath("data", file_name)
    with resources.as_file(resource) as path:
        motion = read_peer_at2(path, name=name)
    return GroundMotion(motion.acceleration, motion.dt, extra.get("title", name),
                        {**motion.metadata, **extra}, motion.processing)
