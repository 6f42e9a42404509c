"""Ready-made bearings for the paper's test set-up: the model names ``precise``, ``simplified``
and ``constant`` mapped onto friction models and a bearing, in one place."""

from __future__ import annotations

import math

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_choice, check_real
from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine, ThermalProperties

MODELS = ("precise", "simplified", "constant")


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
    refinement: float = 0.5,
    mu0: float | None = None,
    mu_t0: float = 0.075,
    initial_temperature: float = 20.0,
    displacement_capacity: float = 0.6,
) -> DCFPBearing:
    """A DCFPB for a bearing test, loaded by a contact ``pressure`` [Pa] or an ``axial_load`` [N].

    The default load is 60 N/mm^2 on the slider. See :func:`friction_model` for the rest.
    """
    owner = "protocol_bearing"
    check_real(slider_diameter, "slider_diameter", owner, low=0.0, low_open=True, high=10.0)
    area = math.pi * (0.5 * slider_diameter) ** 2
    if pressure is not None and axial_load is not None:
        raise InputError(f"{owner}: give either 'pressure' or 'axial_load', not both.")
    if axial_load is None:
        pressure = 60.0e6 if pressure is None else pressure
        check_real(pressure, "pressure", owner, low=0.0, low_open=True, high=1e9)
        axial_load = pressure * area
    check_real(axial_load, "axial_load", owner, low=0.0, low_open=True)
    friction = friction_model(
        model, slider_diameter=slider_diameter, design_pressure=axial_load / area,
        design_velocity=design_velocity, refinement=refinement, mu0=mu0, mu_t0=mu_t0,
        initial_temperature=initial_temperature,
    )
    return DCFPBearing(effective_radius, slider_diameter, axial_load, friction,
                       displacement_capacity=displacement_capacity)
