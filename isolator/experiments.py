"""Ready-made bearings for the paper's test set-up: the model names ``precise``, ``simplified``
and ``constant`` mapped onto friction models and a bearing, in one place."""

from __future__ import annotations

import warnings

from dcfpb.common.errors import InputError, InputWarning
from dcfpb.common.validation import check_choice, check_real
from isolator.bearing import DCFPBearing, slider_contact_area
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine, ThermalProperties

MODELS = ("precise", "simplified", "constant")

PRESSURE_RANGE = (1.0e6, 200.0e6)
"""Contact pressures a bearing test may impose [Pa]: 1 to 200 MPa (the paper's tests run at
20 to 60 MPa); a value below 1 MPa is almost surely one meant in MPa."""
MIN_AXIAL_LOAD = 1.0e4
"""Smallest axial load a bearing test may impose [N]: 10 kN (a value below is almost surely one
meant in kN)."""

PARAMETER_MODELS = {"mu0": ("constant",), "refinement": ("simplified",),
                    "mu_t0": ("precise", "simplified")}
"""The friction parameters of a bearing test and the models that use them."""


def check_test_load(pressure: object, axial_load: object, owner: str, *,
                    names: tuple[str, str] = ("pressure", "axial_load")) -> None:
    """Check the load of a bearing test: a contact ``pressure`` [Pa] in :data:`PRESSURE_RANGE`
    or an ``axial_load`` [N] of at least :data:`MIN_AXIAL_LOAD` (None: not given).

    Parameters
    ----------
    pressure, axial_load : float or None
        Contact pressure [Pa] and axial load [N] as given.
    owner : str
        The function or command, for the message.
    names : (str, str)
        How the two are called there (e.g. ``("--pressure", "--axial-load")``).

    Raises
    ------
    InputError
        Naming the parameter, its unit, the allowed range and the value given; a bare number
        below the range gets the reading in MPa (kN) it most likely meant.
    """
    low, high = PRESSURE_RANGE
    for value, name, bounds, unit, big, big_unit in (
            (pressure, names[0], (low, high), "Pa", 1e6, "MPa"),
            (axial_load, names[1], (MIN_AXIAL_LOAD, None), "N", 1e3, "kN")):
        if value is None:
            continue
        try:
            check_real(value, name, owner, low=bounds[0], high=bounds[1])
        except InputError as error:
            span = (f"{low / 1e6:g} to {high / 1e6:g} MPa" if unit == "Pa"
                    else f"at least {MIN_AXIAL_LOAD / 1e3:g} kN")
            hint = f" The unit of {name!r} is {unit} ({span})."
            x = value if isinstance(value, int | float) and not isinstance(value, bool) else None
            if x is not None and 0.0 < x < bounds[0]:
                hint += (f" {x:g} {unit} is {x / big:g} {big_unit}; if {x:g} {big_unit} was "
                         f"meant, give {x * big:g}.")
            raise type(error)(f"{error}{hint}") from None


def friction_model(
    model: str,
    *,
    slider_diameter: float,
    design_pressure: float,
    design_velocity: float,
    refinement: float = 0.5,
    mu0: float | None = None,
    mu_t0: float = 0.075,
    initial_temperature: float = 20.0,
) -> ConstantFriction | PTVFriction:
    """The friction model called ``model`` with the paper's defaults.

    Parameters
    ----------
    model : {"precise", "simplified", "constant"}
        Eq. 7 with a monitor line, Eq. 7 with one centre point of refinement lambda, or Eq. 8.
    slider_diameter : float
        Slider diameter [m]; it selects the constant model's mu_0 (0.041 for 300 mm, 0.038 for
        400 mm) unless ``mu0`` is given.
    design_pressure, design_velocity : float
        sigma_d [Pa] and v_d [m/s] of the constant model (Eq. 8).
    refinement : float
        lambda of the simplified model [-].
    mu0, mu_t0 : float
        Reference friction coefficients of the constant model and of the others [-].
    initial_temperature : float
        T_0 [degC].
    """
    check_choice(model, "model", "friction_model", MODELS)
    if mu0 is not None:  # checked even where the model does not use it: no silent ignoring
        check_real(mu0, "mu0", "friction_model", low=0.0, high=1.0, low_open=True)
    if model == "constant":
        kwargs = {"design_pressure": design_pressure, "design_velocity": design_velocity,
                  "initial_temperature": initial_temperature}
        if mu0 is not None:
            return ConstantFriction(mu0=mu0, **kwargs)
        return ConstantFriction.for_slider(slider_diameter, **kwargs)
    heating = MonitorLine() if model == "precise" else CentrePoint(refinement=refinement)
    thermal = ThermalProperties(initial_temperature=initial_temperature)
    return PTVFriction(mu_t0=mu_t0, heating=heating, thermal=thermal)


def protocol_bearing(
    model: str,
    *,
    slider_diameter: float = 0.3,
    effective_radius: float = 4.5,
    pressure: float | None = None,
    axial_load: float | None = None,
    design_velocity: float = 0.4,
    refinement: float | None = None,
    mu0: float | None = None,
    mu_t0: float | None = None,
    initial_temperature: float = 20.0,
    displacement_capacity: float = 0.6,
) -> DCFPBearing:
    """A DCFPB for a bearing test, loaded by a contact ``pressure`` [Pa] or an ``axial_load`` [N].

    The default load is 60 N/mm^2 on the slider; a pressure must lie in 1 to 200 MPa
    (:data:`PRESSURE_RANGE`, given in Pa) and an axial load be at least 10 kN
    (:data:`MIN_AXIAL_LOAD`, given in N). ``refinement`` (default 0.5), ``mu0`` and ``mu_t0``
    (default 0.075) are those of :func:`friction_model`; one given to a model that does not use
    it (``mu0`` but to ``"constant"``, ``refinement`` but to ``"simplified"``, ``mu_t0`` to
    ``"constant"``) is checked, then has no effect, with an :class:`InputWarning`.
    """
    owner = "protocol_bearing"
    check_real(slider_diameter, "slider_diameter", owner, low=0.0, low_open=True, high=10.0)
    area = slider_contact_area(slider_diameter)
    if pressure is not None and axial_load is not None:
        raise InputError(f"{owner}: give either 'pressure' or 'axial_load', not both.")
    check_test_load(pressure, axial_load, owner)
    if axial_load is None:
        axial_load = (60.0e6 if pressure is None else pressure) * area
    check_choice(model, "model", owner, MODELS)
    for name, value, high in (("refinement", refinement, 2.0), ("mu0", mu0, 1.0),
                              ("mu_t0", mu_t0, 1.0)):
        if value is None:
            continue
        check_real(value, name, owner, low=0.0, low_open=True, high=high)
        models = PARAMETER_MODELS[name]
        if model not in models:
            warnings.warn(f"The {name!r} parameter of {owner} applies to the "
                          f"{' and '.join(models)} model{'s' * (len(models) > 1)} "
                          f"only; it has no effect with the {model} model.", InputWarning,
                          stacklevel=2)
    friction = friction_model(
        model, slider_diameter=slider_diameter, design_pressure=axial_load / area,
        design_velocity=design_velocity, refinement=0.5 if refinement is None else refinement,
        mu0=mu0, mu_t0=0.075 if mu_t0 is None else mu_t0,
        initial_temperature=initial_temperature,
    )
    return DCFPBearing(effective_radius, slider_diameter, axial_load, friction,
                       displacement_capacity=displacement_capacity)
