"""The one reader of units as written in headers (`groundmotions.units.read_unit`): quantity,
canonical name and factor to SI over many spellings, and its invariance to case, blanks and
brackets (hypothesis)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dcfpb.common.units import M_PER_FOOT, M_PER_INCH, STANDARD_GRAVITY
from groundmotions.units import (
    TO_M_PER_S2,
    TO_SECONDS,
    Unit,
    check_units,
    parse_time_unit,
    read_unit,
)

SPELLINGS: dict[str, tuple[str, str, float]] = {
    # acceleration
    "g": ("acceleration", "g", STANDARD_GRAVITY),
    "G": ("acceleration", "g", STANDARD_GRAVITY),
    "g's": ("acceleration", "g", STANDARD_GRAVITY),
    "mg": ("acceleration", "mg", STANDARD_GRAVITY / 1000),
    "MG": ("acceleration", "mg", STANDARD_GRAVITY / 1000),
    "milli-g": ("acceleration", "mg", STANDARD_GRAVITY / 1000),
    "milli g": ("acceleration", "mg", STANDARD_GRAVITY / 1000),
    "gal": ("acceleration", "cm/s^2", 0.01),
    "GALS": ("acceleration", "cm/s^2", 0.01),
    "CM/S/S": ("acceleration", "cm/s^2", 0.01),
    "CM/SEC/SEC": ("acceleration", "cm/s^2", 0.01),
    "cm/s2": ("acceleration", "cm/s^2", 0.01),
    "cm/s**2": ("acceleration", "cm/s^2", 0.01),
    "cm/s²": ("acceleration", "cm/s^2", 0.01),
    "cm s^-2": ("acceleration", "cm/s^2", 0.01),
    "m/s^2": ("acceleration", "m/s^2", 1.0),
    "M/S/S": ("acceleration", "m/s^2", 1.0),
    "m/sec2": ("acceleration", "m/s^2", 1.0),
    "mm/s2": ("acceleration", "mm/s^2", 0.001),
    "MM/SEC/SEC": ("acceleration", "mm/s^2", 0.001),
    "in/s2": ("acceleration", "in/s^2", M_PER_INCH),
    "IN/S/S": ("acceleration", "in/s^2", M_PER_INCH),
    "inch/s^2": ("acceleration", "in/s^2", M_PER_INCH),
    "ft/s2": ("acceleration", "ft/s^2", M_PER_FOOT),
    "FT/SEC/SEC": ("acceleration", "ft/s^2", M_PER_FOOT),
    "feet/s^2": ("acceleration", "ft/s^2", M_PER_FOOT),
    # velocity
    "cm/s": ("velocity", "cm/s", 0.01),
    "CM/SEC": ("velocity", "cm/s", 0.01),
    "m/s": ("velocity", "m/s", 1.0),
    "mm/sec": ("velocity", "mm/s", 0.001),
    "in/s": ("velocity", "in/s", M_PER_INCH),
    "IN/SEC": ("velocity", "in/s", M_PER_INCH),
    "ft/s": ("velocity", "ft/s", M_PER_FOOT),
    "cm s^-1": ("velocity", "cm/s", 0.01),
    # displacement
    "cm": ("displacement", "cm", 0.01),
    "CM": ("displacement", "cm", 0.01),
    "m": ("displacement", "m", 1.0),
    "metres": ("displacement", "m", 1.0),
    "mm": ("displacement", "mm", 0.001),
    "millimeters": ("displacement", "mm", 0.001),
    "in": ("displacement", "in", M_PER_INCH),
    "inches": ("displacement", "in", M_PER_INCH),
    "ft": ("displacement", "ft", M_PER_FOOT),
    # time
    "s": ("time", "s", 1.0),
    "SEC": ("time", "s", 1.0),
    "secs": ("time", "s", 1.0),
    "seconds": ("time", "s", 1.0),
    "ms": ("time", "ms", 1e-3),
    "MSEC": ("time", "ms", 1e-3),
    "msecs": ("time", "ms", 1e-3),
    "milliseconds": ("time", "ms", 1e-3),
    "Millisecond": ("time", "ms", 1e-3),
}
NOT_UNITS = ["furlong", "km/s/s", "bananas", "", "   ", "min", "Hz", "us", "g/s", "kg", "N",
             "mgal", "cm/min", "1", "s/s"]


@pytest.mark.parametrize("written", sorted(SPELLINGS))
def test_every_spelling_reads_as_its_quantity_unit_and_factor(written):
    quantity, name, factor = SPELLINGS[written]
    found = read_unit(written)
    assert found == Unit(quantity, name, pytest.approx(factor, rel=1e-15))


@pytest.mark.parametrize("written", NOT_UNITS)
def test_what_is_no_known_unit_reads_as_none(written):
    assert read_unit(written) is None


def test_acceleration_factors_are_the_readers_and_time_factors_seconds():
    for name, factor in TO_M_PER_S2.items():
        assert read_unit(name) == Unit("acceleration", name, factor)
    assert TO_SECONDS == {"s": 1.0, "ms": 1e-3}
    assert check_units("mg", "test") == "mg"  # --units mg is a choice too


def _case_variants(text: str) -> st.SearchStrategy[str]:
    return st.lists(st.booleans(), min_size=len(text), max_size=len(text)).map(
        lambda flags: "".join(c.upper() if f else c.lower() for c, f in zip(text, flags,
                                                                             strict=True)))


@settings(max_examples=300, deadline=None)
@given(data=st.data(), written=st.sampled_from(sorted(SPELLINGS)))
def test_case_blanks_and_brackets_do_not_change_the_unit(data, written):
    variant = data.draw(_case_variants(written))
    left, right = data.draw(st.sampled_from([("", ""), ("(", ")"), ("[", "]"), (" ", "  ")]))
    expected = read_unit(written)
    assert read_unit(f"{left}{variant}{right}") == expected


@settings(max_examples=200, deadline=None)
@given(text=st.text(max_size=12))
def test_any_text_reads_as_a_unit_or_none_never_raises(text):
    found = read_unit(text)
    assert found is None or (found.quantity in {"acceleration", "velocity", "displacement",
                                                "time"} and found.factor > 0)
    time = parse_time_unit(text)
    assert time is None or found == Unit("time", time, TO_SECONDS[time])
