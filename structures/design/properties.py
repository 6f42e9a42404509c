"""Property modification factors of ASCE/SEI 7-16 Sec. 17.2.8.4: lambda_max and lambda_min
assembled from their parts (or given as overall values) and applied to the friction of any
friction model.

Eq. 17.2-1 and 17.2-2 (as read in the literature; :mod:`structures.design.limits` says what was
verified)::

    lambda_max = (1 + 0.75 (lambda_ae,max - 1)) lambda_test,max lambda_spec,max
    lambda_min = (1 - 0.75 (1 - lambda_ae,min)) lambda_test,min lambda_spec,min

lambda_ae is aging and environment, lambda_test the variation seen in prototype tests (heating,
rate of loading, scragging, the cycles' spread: :func:`structures.design.prototype.prototype_test`),
lambda_spec the manufacturing tolerance. A friction model is scaled through its own
``scaled(factor)`` (``mu0`` of the constant model, ``mu_t0`` of the precise and simplified
ones), as the suites' property modifiers are.

The precise and simplified models compute the contact temperature and its effect on mu in the
simulation. A lambda_test taken from tests includes the drop of mu with heating over the cycles;
applied to those models it counts heating twice. With a named heating component
(``test_heating_max``, ``test_heating_min``) :meth:`PropertyModification.factor_for` divides it
out for a model that heats and says so (an ``InputWarning``); with only the flag
``test_includes_heating`` it keeps the factor and warns of the double count.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

from dcfpb.common.errors import InputError, InputWarning
from dcfpb.common.validation import check_choice, check_real
from isolator.friction import FrictionModel
from structures.design.limits import LIMITS, limit

__all__ = ["BOUNDS", "PropertyModification", "model_heats"]

BOUNDS = ("upper", "lower")
"""The two bounds of the properties: ``"upper"`` (lambda_max) and ``"lower"`` (lambda_min)."""

_OWNER = "PropertyModification"


def model_heats(friction: FrictionModel) -> bool:
    """Whether a friction model computes its own heating (``heats`` True: the precise and the
    simplified models)."""
    return bool(getattr(friction, "heats", False))


def _max_factor(value: object, name: str) -> float:
    return check_real(value, name, _OWNER, low=1.0, high=10.0)


def _min_factor(value: object, name: str) -> float:
    return check_real(value, name, _OWNER, low=0.0, high=1.0, low_open=True)


@dataclass(frozen=True)
class PropertyModification:
    """The property modification factors of Sec. 17.2.8.4 [-].

    Give the parts (the defaults are 1: no modification) or ``overall_max`` and ``overall_min``
    (:meth:`overall`), not both.

    Parameters
    ----------
    ae_max, ae_min : float
        Aging and environmental factors lambda_ae,max >= 1 and lambda_ae,min in (0, 1].
    test_max, test_min : float
        Test factors lambda_test,max >= 1 and lambda_test,min in (0, 1].
    spec_max, spec_min : float
        Specification (manufacturing) factors, >= 1 and in (0, 1].
    overall_max, overall_min : float or None
        lambda_max >= 1 and lambda_min in (0, 1] given as a whole.
    test_includes_heating : bool
        The test factors include the effect of heating on friction (as factors from cyclic
        tests do).
    test_heating_max, test_heating_min : float or None
        The heating part of lambda_test,max (>= 1) and lambda_test,min (in (0, 1]), divided out
        for a model that computes heating; giving one implies ``test_includes_heating``.
    adjustment : float
        The 0.75 of Eq. 17.2-1/2 (``LIMITS["lambda_ae_adjustment"]``), in [0, 1].

    Raises
    ------
    InputError
        A factor outside its range (named), parts and overall values together, only one of the
        overall values, lambda_min > 1 or lambda_max < 1.

    Notes
    -----
    :meth:`limit_notes` names lambda_max below 1.8 or lambda_min above 0.60 (Sec. 17.2.8.4 as
    read, not verified: :mod:`structures.design.limits`); :func:`structures.design.elf` warns
    with them.
    """

    ae_max: float = 1.0
    ae_min: float = 1.0
    test_max: float = 1.0
    test_min: float = 1.0
    spec_max: float = 1.0
    spec_min: float = 1.0
    overall_max: float | None = None
    overall_min: float | None = None
    test_includes_heating: bool = False
    test_heating_max: float | None = None
    test_heating_min: float | None = None
    adjustment: float = limit("lambda_ae_adjustment")

    def __post_init__(self) -> None:
        for name in ("ae_max", "test_max", "spec_max"):
            object.__setattr__(self, name, _max_factor(getattr(self, name), name))
        for name in ("ae_min", "test_min", "spec_min"):
            object.__setattr__(self, name, _min_factor(getattr(self, name), name))
        check_real(self.adjustment, "adjustment", _OWNER, low=0.0, high=1.0)
        if not isinstance(self.test_includes_heating, bool):
            raise InputError(f"The 'test_includes_heating' parameter of {_OWNER} must be True "
                             f"or False. Got {self.test_includes_heating!r} instead.")
        if self.test_heating_max is not None:
            _max_factor(self.test_heating_max, "test_heating_max")
            if self.test_heating_max > self.test_max:
                raise InputError(f"The 'test_heating_max' parameter of {_OWNER} must be in "
                                 f"[1, test_max = {self.test_max:g}] (a part of lambda_test,max)."
                                 f" Got {self.test_heating_max!r} instead.")
        if self.test_heating_min is not None:
            _min_factor(self.test_heating_min, "test_heating_min")
            if self.test_heating_min < self.test_min:
                raise InputError(f"The 'test_heating_min' parameter of {_OWNER} must be in "
                                 f"[test_min = {self.test_min:g}, 1] (a part of "
                                 f"lambda_test,min). Got {self.test_heating_min!r} instead.")
        overall = (self.overall_max, self.overall_min)
        if any(v is not None for v in overall):
            if any(v is None for v in overall):
                missing = "overall_min" if self.overall_min is None else "overall_max"
                raise InputError(f"The {missing!r} parameter of {_OWNER} must be given with the "
                                 "other overall value. Got None instead.")
            parts = ("ae_max", "ae_min", "test_max", "test_min", "spec_max", "spec_min")
            given = [name for name in parts if getattr(self, name) != 1.0]
            if given:
                raise InputError(f"The {given[0]!r} parameter of {_OWNER} must be 1 when "
                                 "overall_max and overall_min are given (parts or overall "
                                 f"values, not both). Got {getattr(self, given[0])!r} instead.")
            object.__setattr__(self, "overall_max", check_real(
                self.overall_max, "overall_max", _OWNER, low=1.0, high=10.0))
            object.__setattr__(self, "overall_min", check_real(
                self.overall_min, "overall_min", _OWNER, low=0.0, high=1.0, low_open=True))

    @classmethod
    def overall(cls, lambda_max: float, lambda_min: float, **kwargs: object
                ) -> PropertyModification:
        """lambda_max and lambda_min given as a whole (``kwargs``: the heating arguments)."""
        return cls(overall_max=lambda_max, overall_min=lambda_min, **kwargs)

    @property
    def includes_heating(self) -> bool:
        """Whether the test factors include the effect of heating."""
        return (self.test_includes_heating or self.test_heating_max is not None
                or self.test_heating_min is not None)

    @property
    def lambda_max(self) -> float:
        """lambda_max, Eq. 17.2-1 (or the overall value) [-]."""
        if self.overall_max is not None:
            return float(self.overall_max)
        ae = 1.0 + self.adjustment * (self.ae_max - 1.0)
        return ae * self.test_max * self.spec_max

    @property
    def lambda_min(self) -> float:
        """lambda_min, Eq. 17.2-2 (or the overall value) [-]."""
        if self.overall_min is not None:
            return float(self.overall_min)
        ae = 1.0 - self.adjustment * (1.0 - self.ae_min)
        return ae * self.test_min * self.spec_min

    def factor(self, bound: str) -> float:
        """lambda of the ``bound`` ``"upper"`` (lambda_max) or ``"lower"`` (lambda_min) [-]."""
        bound = check_choice(bound, "bound", f"{_OWNER}.factor", BOUNDS)
        return self.lambda_max if bound == "upper" else self.lambda_min

    def factor_for(self, friction: FrictionModel, bound: str) -> float:
        """lambda of ``bound`` as applied to ``friction`` [-]: on a model that computes heating
        the named heating part of lambda_test is divided out.

        Warns
        -----
        InputWarning
            On a model that heats where the factors include heating: what was divided out, or,
            without a named part, that heating is counted twice.
        """
        value = self.factor(bound)
        if not (model_heats(friction) and self.includes_heating):
            return value
        part = self.test_heating_max if bound == "upper" else self.test_heating_min
        name = getattr(friction, "name", type(friction).__name__)
        if part is not None:
            warnings.warn(InputWarning(
                f"The {name} model computes the heating of the sliding surfaces: the heating "
                f"part {part:g} of lambda_test ({bound} bound) is left to the simulation, so "
                f"lambda = {value:.4g} / {part:g} = {value / part:.4g} is applied."),
                stacklevel=2)
            return value / part
        warnings.warn(InputWarning(
            f"The {name} model computes the heating of the sliding surfaces, and lambda_test "
            f"includes heating (test_includes_heating): lambda = {value:.4g} ({bound} bound) "
            "counts heating twice. Give its heating part as test_heating_max/test_heating_min "
            "to leave it to the simulation, or use the constant model."), stacklevel=2)
        return value

    def apply(self, friction: FrictionModel, bound: str) -> FrictionModel:
        """``friction`` with its friction coefficient times lambda of ``bound``
        (:meth:`factor_for`, through the model's ``scaled``).

        Raises
        ------
        InputError
            A scaled reference coefficient outside (0, 1] (named by the model).
        """
        return friction.scaled(self.factor_for(friction, bound))

    def limit_notes(self) -> list[str]:
        """What falls outside the lambda limits of Sec. 17.2.8.4 as read (empty: nothing)."""
        notes = []
        for key, value, word, outside in (
                ("lambda_max_floor", self.lambda_max, "below", self.lambda_max < limit(
                    "lambda_max_floor")),
                ("lambda_min_ceiling", self.lambda_min, "above", self.lambda_min > limit(
                    "lambda_min_ceiling"))):
            if outside:
                entry = LIMITS[key]
                notes.append(f"lambda_{key[7:10]} = {value:.4g} is {word} {entry.value:g} "
                             f"({entry.clause}; {entry.note}).")
        return notes

    def to_dict(self) -> dict[str, object]:
        """The factors and lambda_max, lambda_min (for JSON)."""
        names = ("ae_max", "ae_min", "test_max", "test_min", "spec_max", "spec_min",
                 "overall_max", "overall_min", "test_includes_heating", "test_heating_max",
                 "test_heating_min", "adjustment")
        return {**{n: getattr(self, n) for n in names},
                "lambda_max": self.lambda_max, "lambda_min": self.lambda_min}
