"""Every parameter is validated: the error names it, its allowed range and the value given."""

from __future__ import annotations

import math

import pytest

from isolator.bearing import DCFPBearing
from isolator.experiments import friction_model, protocol_bearing
from isolator.factors import KumarFactors, factor_set
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine, ThermalProperties, sum_of_exponentials

N = 4.0e6

CASES = [
    (lambda: ConstantFriction(mu0=-0.1), "mu0", "(0, 1]", "-0.1"),
    (lambda: ConstantFriction(mu0=1.5), "mu0", "(0, 1]", "1.5"),
    (lambda: ConstantFriction(design_pressure=0.0), "design_pressure", "(0, inf)", "0.0"),
    (lambda: ConstantFriction(design_velocity=-1.0), "design_velocity", "[0, inf)", "-1.0"),
    (lambda: ConstantFriction(factors="mine"), "factors", "'paper', 'kumar'", "'mine'"),
    (lambda: PTVFriction(mu_t0=0.0), "mu_t0", "(0, 1]", "0.0"),
    (lambda: PTVFriction(surfaces=3), "surfaces", "[1, 2]", "3"),
    (lambda: PTVFriction(dependencies=("pressure", "wear")), "dependencies", "'temperature'",
     "'wear'"),
    (lambda: PTVFriction(kernel_min_lag=1.0), "kernel_min_lag", "[1e-09, 0.01]", "1.0"),
    (lambda: CentrePoint(refinement=0.0), "refinement", "(0, 2]", "0.0"),
    (lambda: MonitorLine(spacing=0.0), "spacing", "[1e-05, 0.1]", "0.0"),
    (lambda: ThermalProperties(conductivity=-16.0), "conductivity", "(0, inf)", "-16.0"),
    (lambda: ThermalProperties(diffusivity=float("nan")), "diffusivity", "(0, inf)", "nan"),
    (lambda: KumarFactors(rate_parameter=0.0), "rate_parameter", "(0, inf)", "0.0"),
    (lambda: factor_set("other"), "name", "'paper', 'kumar'", "'other'"),
    (lambda: DCFPBearing(-1.0, 0.3, N, ConstantFriction()), "effective_radius", "(0, inf)",
     "-1.0"),
    (lambda: DCFPBearing(4.5, 0.0, N, ConstantFriction()), "slider_diameter", "(0, 10]", "0.0"),
    (lambda: DCFPBearing(4.5, 0.3, -N, ConstantFriction()), "axial_load", "(0, inf)", "-4"),
    (lambda: DCFPBearing(4.5, 0.3, N, ConstantFriction(), yield_displacement=0.0),
     "yield_displacement", "(0, 0.1]", "0.0"),
    (lambda: DCFPBearing(4.5, 0.3, N, ConstantFriction(), displacement_capacity=0.0),
     "displacement_capacity", "(0, 10]", "0.0"),
    (lambda: DCFPBearing(4.5, 0.3, N, ConstantFriction(), restoring="cubic"), "restoring",
     "'linear', 'spherical'", "'cubic'"),
    (lambda: friction_model("exact", slider_diameter=0.3, design_pressure=6e7,
                            design_velocity=0.4), "model", "'precise'", "'exact'"),
    (lambda: protocol_bearing("precise", pressure=-5.0), "pressure", "[1e+06, 2e+08]", "-5.0"),
    (lambda: sum_of_exponentials(1e-6, 1e4, 0.5), "tolerance", "[1e-13, 0.01]", "0.5"),
]


@pytest.mark.parametrize(("make", "name", "allowed", "given"), CASES,
                         ids=[c[1] + str(i) for i, c in enumerate(CASES)])
def test_bad_parameter_names_itself_its_range_and_the_value(make, name, allowed, given):
    with pytest.raises(ValueError) as info:
        make()
    message = str(info.value)
    assert f"'{name}'" in message
    assert allowed in message
    assert given in message


def test_wrong_kinds_raise_type_errors():
    with pytest.raises(TypeError, match="'friction' parameter of DCFPBearing"):
        DCFPBearing(4.5, 0.3, N, friction=0.04)
    with pytest.raises(TypeError, match="'mu0' parameter of ConstantFriction must be a float"):
        ConstantFriction(mu0="0.04")
    with pytest.raises(TypeError, match="'heating' parameter of PTVFriction"):
        PTVFriction(heating="line")


def test_flat_slider_accepts_infinite_radius():
    bearing = DCFPBearing(math.inf, 0.3, N, ConstantFriction())
    assert bearing.pendulum_stiffness == 0.0
