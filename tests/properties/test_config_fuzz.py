"""Fuzzing the building-file loader: whatever the file holds, :func:`structures.config.load_config`
either loads it or raises :class:`dcfpb.common.errors.InputError` (a message naming the file), never
another exception.

Two sources of files: the example building (``examples/five_storey.toml``) with some of its
values replaced by random TOML values of random types (numbers of every size and sign, inf and
nan, booleans, strings, dates, arrays, nested arrays, tables), and random bytes (with and
without a UTF-8 byte-order mark, and the example's text with bytes spliced in). Warnings (a
setting without effect) are allowed and recorded, not raised.
"""

from __future__ import annotations

import datetime as dt
import tomllib
import warnings
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dcfpb.common.errors import InputError
from structures.config import BuildingConfig, load_config

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
BASE = tomllib.loads(EXAMPLE.read_text(encoding="utf-8"))
PATHS = [(section, key) for section, table in BASE.items() if isinstance(table, dict)
         for key in table if not isinstance(table[key], dict)]
PATHS += [("building.damping", key) for key in BASE["building"]["damping"]]
PATHS += [("", "name"), ("bearing", "mu0"), ("analysis", "alpha"), ("building", "ratio"),
          ("building.damping", "ratio"), ("building", "storey_stiffnesses")]
FUZZ = settings(max_examples=150, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
"""Deterministic (the same examples on every run) and a few seconds each; the changed example
takes more examples, having more to explore."""

positive = st.one_of(  # values inside many ranges, to reach the objects built from them
    st.floats(min_value=0.0, max_value=1e308, exclude_min=True),
    st.sampled_from([1e-320, 1e-9, 0.01, 0.3, 0.5, 1.0, 2.0, 4.5, 1e9, 1e300]),
    st.integers(min_value=1, max_value=12),
)
scalars = st.one_of(
    positive,
    st.integers(min_value=-(2**63), max_value=2**63 - 1),
    st.sampled_from([0, 1, 2, -1, 6, 1000, 10001]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-320, 1e300, 0.5, 2.7, 1e-9]),
    st.booleans(),
    st.text(st.characters(blacklist_categories=("Cs",)), max_size=12),
    st.sampled_from(["precise", "hht", "modal", "rayleigh", "uniform", "6"]),
    st.datetimes(min_value=dt.datetime(1900, 1, 1), max_value=dt.datetime(2100, 1, 1)),
    st.dates(min_value=dt.date(1900, 1, 1), max_value=dt.date(2100, 1, 1)),
)
values = st.recursive(
    scalars,
    lambda inner: st.one_of(st.lists(inner, max_size=7), st.lists(positive, max_size=7),
                            st.dictionaries(st.sampled_from(["a", "kind", "ratio"]), inner,
                                            max_size=2)),
    max_leaves=12,
)


def _toml(value: object) -> str:
    """``value`` written as a TOML value (tomllib reads, it does not write)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if value != value:
            return "nan"
        if value in (float("inf"), float("-inf")):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return '"' + "".join(c if c.isprintable() and c not in '"\\' else f"\\u{ord(c):04x}"
                             for c in value) + '"'
    if isinstance(value, dt.date):
        return value.isoformat()
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return "{" + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + "}"


def _document(tables: dict) -> str:
    top = [f"{k} = {_toml(v)}" for k, v in tables.items() if not isinstance(v, dict)]
    lines = top[:]
    for section, table in tables.items():
        if not isinstance(table, dict):
            continue
        lines.append(f"[{section}]")
        lines += [f"{k} = {_toml(v)}" for k, v in table.items() if not isinstance(v, dict)]
        for sub, inner in table.items():
            if isinstance(inner, dict):
                lines.append(f"[{section}.{sub}]")
                lines += [f"{k} = {_toml(v)}" for k, v in inner.items()]
    return "\n".join(lines) + "\n"


def _loads_or_refuses(path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # a setting without effect: said so
        warnings.simplefilter("error", RuntimeWarning)  # no overflow on the way to a verdict
        try:
            config = load_config(path)
        except InputError as error:
            assert str(path) in str(error)
            return
    assert isinstance(config, BuildingConfig)
    config.bearing()


def _table(tables: dict, section: str) -> dict:
    table = tables
    for part in filter(None, section.split(".")):
        table = table.setdefault(part, {}) if isinstance(table.get(part, {}), dict) else {}
    return table


@settings(FUZZ, max_examples=500)
@given(changes=st.lists(st.tuples(st.sampled_from(PATHS), values), min_size=1, max_size=4),
       drop=st.lists(st.sampled_from(PATHS), max_size=2))
def test_example_with_random_values_loads_or_is_refused(tmp_path_factory, changes, drop):
    import copy

    tables = copy.deepcopy(BASE)
    for section, key in drop:
        _table(tables, section).pop(key, None)
    for (section, key), value in changes:
        _table(tables, section)[key] = value
    path = tmp_path_factory.mktemp("fuzz") / "building.toml"
    path.write_text(_document(tables), encoding="utf-8")
    _loads_or_refuses(path)


@FUZZ
@given(data=st.binary(max_size=300), bom=st.booleans())
def test_random_bytes_load_or_are_refused(tmp_path_factory, data, bom):
    path = tmp_path_factory.mktemp("fuzz") / "bytes.toml"
    path.write_bytes((b"\xef\xbb\xbf" if bom else b"") + data)
    _loads_or_refuses(path)


@FUZZ
@given(at=st.integers(min_value=0, max_value=len(EXAMPLE.read_bytes())),
       data=st.binary(min_size=1, max_size=8))
def test_example_with_bytes_spliced_in_loads_or_is_refused(tmp_path_factory, at, data):
    text = EXAMPLE.read_bytes()
    path = tmp_path_factory.mktemp("fuzz") / "spliced.toml"
    path.write_bytes(text[:at] + data + text[at:])
    _loads_or_refuses(path)
