"""Which engine runs a building: the compiled one when it can, else the readable reference.

:func:`choose_engine` turns the ``engine`` argument (:data:`ENGINES`) and the reason the
compiled engine cannot run a model (None when it can) into ``"compiled"`` or
``"reference"``; :func:`unsupported` gives that reason for the planar building
(:func:`select_engine`); the building in plan has its own
(:func:`structures.compiled.plan.engine.plan_unsupported`).
"""

from __future__ import annotations

from dcfpb.common.validation import check_choice
from isolator.bearing import AxialLoadHistory
from isolator.compiled import kernels
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine
from structures.integrators import HHT, Newmark
from structures.isolated_building import IsolatedShearBuilding

__all__ = ["ENGINES", "choose_engine", "select_engine", "unsupported"]

ENGINES = ("auto", "compiled", "reference")
"""The values of an ``engine`` argument."""


def unsupported(model: object, method: object) -> str | None:
    """Why the compiled engine cannot run ``model`` with ``method``, or None when it can."""
    if type(model) is not IsolatedShearBuilding:
        return f"the model is a {type(model).__name__}, not an IsolatedShearBuilding"
    if not isinstance(method, Newmark | HHT):
        return f"the method {method!r} is not a Newmark or HHT instance"
    bearing = model.bearing
    if isinstance(bearing.axial_load, AxialLoadHistory):
        return "the axial load varies in time"
    if bearing.restoring not in ("linear", "spherical"):
        return f"the restoring law {bearing.restoring!r} is unknown to it"
    friction = bearing.friction
    if type(friction) is ConstantFriction:
        return None
    if type(friction) is not PTVFriction:
        return f"the friction model {type(friction).__name__} is unknown to it"
    if friction.heating is not None and type(friction.heating) not in (MonitorLine, CentrePoint):
        return f"the heating layout {type(friction.heating).__name__} is unknown to it"
    return None


def choose_engine(engine: str, reason: str | None, owner: str) -> str:
    """``"compiled"`` or ``"reference"``: the ``engine`` asked of ``owner`` (one of
    :data:`ENGINES`), given why the compiled one cannot run (``reason``; None when it can).

    Raises
    ------
    ValueError
        For an unknown ``engine``, or ``"compiled"`` with a ``reason``.
    """
    check_choice(engine, "engine", owner, ENGINES)
    if engine == "compiled" and reason is not None:
        raise ValueError(f"The 'engine' parameter of {owner} is 'compiled' but {reason}; use "
                         "engine='reference' or 'auto'.")
    if engine == "auto":
        return "compiled" if reason is None and kernels.COMPILED else "reference"
    return engine


def select_engine(engine: str, model: object, method: object) -> str:
    """The engine of :func:`structures.analysis.run`: :func:`choose_engine` on
    :func:`unsupported`."""
    return choose_engine(engine, unsupported(model, method), "run")
