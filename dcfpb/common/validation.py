"""Parameter checks with one error template.

A bad parameter raises :class:`dcfpb.common.errors.InputError` (a ``ValueError``), or
:class:`~dcfpb.common.errors.InputTypeError` (also a ``TypeError``) for a wrong kind, with the
message naming the parameter, its owner, the allowed range and the value given:

    The 'mu0' parameter of ConstantFriction must be a float in (0, 1]. Got -0.1 instead.
"""

from __future__ import annotations

import math
import os
from numbers import Integral, Real

import numpy as np

from dcfpb.common.errors import InputError, InputTypeError


def _interval(low: float | None, high: float | None, low_open: bool, high_open: bool) -> str:
    left = "(" if (low is None or low_open) else "["
    right = ")" if (high is None or high_open) else "]"
    lo = "-inf" if low is None else f"{low:g}"
    hi = "inf" if high is None else f"{high:g}"
    return f"{left}{lo}, {hi}{right}"


def _error(kind: type[Exception], name: str, owner: str, must: str, got: str) -> Exception:
    """The one template: ``The 'name' parameter of owner must <must>. Got <got> instead.``"""
    return kind(f"The {name!r} parameter of {owner} must {must}. Got {got} instead.")


def check_real(
    value: object,
    name: str,
    owner: str,
    *,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    high_open: bool = False,
    allow_inf: bool = False,
) -> float:
    """``value`` as a float, checked to lie in the interval given.

    ``name`` and ``owner`` (the class or function) name the parameter in the message; ``low`` and
    ``high`` bound the interval (None: unbounded) and ``low_open``, ``high_open`` exclude the bound
    itself; ``allow_inf`` accepts +inf (e.g. a flat slider's effective radius). A value that is not
    a real number raises ``TypeError``; NaN, infinity (unless allowed) or a value outside the
    interval raises ``ValueError``.
    """
    must = f"be a float in {_interval(low, high, low_open, high_open)}"
    if isinstance(value, bool) or not isinstance(value, Real | np.floating | np.integer):
        raise _error(InputTypeError, name, owner, must, repr(value))
    x = float(value)
    bad = math.isnan(x) or (math.isinf(x) and not allow_inf)
    if low is not None:
        bad = bad or x < low or (low_open and x == low)
    if high is not None and not (allow_inf and x == math.inf):
        bad = bad or x > high or (high_open and x == high)
    if bad:
        raise _error(InputError, name, owner, must, repr(value))
    return x


def check_int(
    value: object, name: str, owner: str, *, low: int | None = None, high: int | None = None
) -> int:
    """``value`` as an int, checked to lie in ``[low, high]`` (errors as :func:`check_real`)."""
    must = f"be an int in {_interval(low, high, False, False)}"
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise _error(InputTypeError, name, owner, must, repr(value))
    x = int(value)
    if (low is not None and x < low) or (high is not None and x > high):
        raise _error(InputError, name, owner, must, repr(value))
    return x


def check_choice(value: object, name: str, owner: str, choices: tuple[str, ...]) -> str:
    """``value``, checked to be one of ``choices`` (an ``InputError`` names them; an
    ``InputTypeError`` when ``value`` is not even a str)."""
    if value not in choices:
        allowed = ", ".join(repr(c) for c in choices)
        raise _error(InputError if isinstance(value, str) else InputTypeError, name, owner,
                     f"be one of {{{allowed}}}", repr(value))
    return str(value)


def check_array(
    values: object,
    name: str,
    owner: str,
    *,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    ndim: int = 1,
    min_length: int = 1,
    increasing: bool = False,
    length_of: tuple[str, int] | None = None,
) -> np.ndarray:
    """``values`` as a float array, checked for ``ndim``, ``min_length``, finiteness, bounds,
    with ``increasing`` to increase strictly along its first axis and with ``length_of``, a
    (name, length) of another array, to have its length; a ``ValueError`` names the array, the
    first offending index and its value."""
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as error:
        raise InputTypeError(f"The {name!r} parameter of {owner} must be a {ndim}-d array of "
                             f"floats. Got {_shown(values)} instead ({error}).") from None
    if arr.ndim != ndim:
        raise _error(InputError, name, owner, f"be a {ndim}-d array", f"shape {arr.shape}")
    if arr.shape[0] < min_length:
        raise _error(InputError, name, owner, f"have at least {min_length} values",
                     str(arr.shape[0]))
    bad = ~np.isfinite(arr)
    if low is not None:
        bad |= (arr < low) | ((arr == low) if low_open else False)
    if high is not None:
        bad |= arr > high
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        where = index[0] if len(index) == 1 else index
        raise _error(InputError, name, owner, "hold finite floats in "
                     + _interval(low, high, low_open, False), f"{arr[index]!r} at index {where}")
    if increasing and np.any(np.diff(arr, axis=0) <= 0.0):
        i = int(np.argmax(np.diff(arr, axis=0) <= 0.0)) + 1
        raise _error(InputError, name, owner, "be strictly increasing",
                     f"{arr[i]!r} after {arr[i - 1]!r} at index {i}")
    if length_of is not None and arr.shape[0] != length_of[1]:
        raise _error(InputError, name, owner, f"have the length of {length_of[0]!r} "
                     f"({length_of[1]})", str(arr.shape[0]))
    return arr


def parse_floats(
    text: object, flag: str, form: str = "", *, count: int | None = None
) -> tuple[float, ...]:
    """The finite numbers of a comma-separated command-line value such as ``--scales 1,1.5``
    (blank items skipped).

    ``flag`` and ``form`` (e.g. ``"MAX,MIN"``) name the value in the message; ``count`` is the
    number of values required (None: any, at least one). Anything else raises
    :class:`~dcfpb.common.errors.InputError`:

        --lambda-test must be MAX,MIN, two numbers separated by a comma. Got '1.2'.
    """
    try:
        values = tuple(float(x) for x in str(text).split(",") if x.strip())
    except ValueError:
        values = None
    if values == () and count is None:
        raise InputError(f"{flag} needs at least one value. Got {text!r}.")
    if values is None or (count is not None and len(values) != count) or not all(
            math.isfinite(v) for v in values):
        numbers = ("two numbers separated by a comma" if count == 2
                   else "numbers separated by commas")
        raise InputError(f"{flag} must be {form + ', ' if form else ''}{numbers}. Got {text!r}.")
    return values


def _shown(value: object, limit: int = 80) -> str:
    """``repr(value)``, cut to ``limit`` characters."""
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def check_path(value: object, name: str, owner: str) -> str | os.PathLike:
    """``value``, checked to be a path: a ``str`` or an ``os.PathLike`` (not bytes, a number or
    a list); an :class:`~dcfpb.common.errors.InputTypeError` names the parameter otherwise."""
    if isinstance(value, str) or (isinstance(value, os.PathLike)
                                  and isinstance(os.fspath(value), str)):
        return value
    raise _error(InputTypeError, name, owner, "be a path (a str or pathlib.Path)", _shown(value))


def check_instance(value: object, name: str, owner: str, kinds: type | tuple[type, ...],
                   what: str) -> object:
    """``value``, checked to be an instance of ``kinds``; an
    :class:`~dcfpb.common.errors.InputTypeError` names the parameter and ``what`` it must be
    (e.g. ``"a GroundMotion"``) otherwise."""
    if isinstance(value, kinds):
        return value
    raise _error(InputTypeError, name, owner, f"be {what}", _shown(value))


def check_dataset(value: object, name: str, owner: str) -> object:
    """``value``, checked to be a run's result (an ``xarray.Dataset``; checked by its
    attributes, so that xarray is not imported here)."""
    if all(hasattr(value, attribute) for attribute in ("data_vars", "attrs", "sizes")):
        return value
    raise _error(InputTypeError, name, owner, "be a run's result (an xarray.Dataset)",
                 _shown(value))
