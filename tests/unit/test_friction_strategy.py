"""A friction law the package does not know, added through the strategy interface only.

The element asks its friction model for mu and its derivative (:class:`isolator.friction.
FrictionModel`, as OpenSees' ``FrictionModel`` serves its bearings): a new law is a class with
``name``, ``initial_temperature``, ``scaled`` and ``bind``, and every workflow runs it without
a line changed in the element, the test rig, the building or the engines (the compiled engine
has no form of it, so ``engine="auto"`` takes the reference engine). The law here is a
velocity-dependent Coulomb friction (OpenSees' ``VelDependent``): mu = mu_fast - (mu_fast -
mu_slow) exp(-rate |v|).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
import pytest

from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction, Friction
from isolator.orbits import circle
from isolator.protocols import sine
from isolator.testrig import run_orbit, run_test
from structures.analysis import run
from structures.plan import Plan
from structures.shear_building import ShearBuilding

N = 60e6 * math.pi * 0.15**2  # [N]


class _VelocityDependentState:
    def __init__(self, law: VelocityDependent) -> None:
        self.law = law

    def trial(self, position, velocity, pressure, dt) -> Friction:
        speed = math.hypot(*velocity)
        decay = math.exp(-self.law.rate * speed)
        drop = self.law.mu_fast - self.law.mu_slow
        return Friction(self.law.mu_fast - drop * decay, drop * self.law.rate * decay,
                        self.law.initial_temperature, 0.0)

    def lifted(self, position, dt) -> Friction:
        return Friction(0.0, 0.0, self.law.initial_temperature, 0.0)

    def commit(self) -> None:
        pass

    def revert(self) -> None:
        pass

    def temperature_field(self) -> None:
        return None


@dataclass(frozen=True)
class VelocityDependent:
    """mu = mu_fast - (mu_fast - mu_slow) exp(-rate |v|); no heating."""

    mu_slow: float = 0.02
    mu_fast: float = 0.06
    rate: float = 20.0  # [s/m]
    initial_temperature: float = 20.0

    @property
    def name(self) -> str:
        return "velocity-dependent"

    def scaled(self, factor: float) -> VelocityDependent:
        return dataclasses.replace(self, mu_slow=self.mu_slow * factor,
                                   mu_fast=self.mu_fast * factor)

    def bind(self, contact_radius, travel, dimension=1, orientation=None):
        return _VelocityDependentState(self)

    def mu(self, speed: np.ndarray) -> np.ndarray:
        return self.mu_fast - (self.mu_fast - self.mu_slow) * np.exp(-self.rate * speed)


def test_the_bearing_test_slides_at_the_laws_mu():
    law = VelocityDependent()
    bearing = DCFPBearing(4.5, 0.3, N, law)
    history = sine(0.2, 3.0, 2, 0.005)
    result = run_test(bearing, history.time, history.displacement, history.velocity)
    sliding = np.abs(result.z) == 1.0
    assert sliding.mean() > 0.9
    expected = law.mu(np.abs(result.velocity)) * N * result.z
    np.testing.assert_allclose(result.mu[sliding], law.mu(np.abs(result.velocity))[sliding],
                               rtol=1e-14)  # numpy's exp against math's
    np.testing.assert_allclose(result.friction_force[sliding], expected[sliding], rtol=1e-14)


def test_an_orbit_slides_at_the_laws_mu_of_the_speed():
    law = VelocityDependent()
    path = circle(0.15, 3.0, 2, 0.005)
    result = run_orbit(DCFPBearing(4.5, 0.3, N, law), path)
    speed = np.hypot(*path.velocity.T)
    late = slice(len(speed) // 2, None)  # on the circle: sliding, |z| = 1
    magnitude = np.hypot(*result.friction_force[late].T)
    np.testing.assert_allclose(magnitude, law.mu(speed[late]) * N, rtol=1e-9)


@pytest.fixture(scope="module")
def building() -> ShearBuilding:
    return ShearBuilding.from_period([4e5, 4e5], 0.4, base_mass=5e5)


def test_a_building_runs_on_it_with_the_reference_engine(building):
    from groundmotions.synthetic import kanai_tajimi

    motion = kanai_tajimi(4.0, 0.01, seed=3, target_pga=3.0, ground_frequency=15.0,
                          ground_damping=0.6)
    result = run(building, DCFPBearing(2.5, 0.3, friction=VelocityDependent()), motion,
                 n_bearings=4, dt=0.01)
    assert result.attrs["success"] and result.attrs["engine"] == "reference"
    assert result.attrs["friction_model"] == "velocity-dependent"
    assert result.attrs["energy_balance_error"] < 1e-8
    # a law that does not depend on the speed is the constant model, to the last bit
    constant = ConstantFriction(mu0=0.04)
    flat = VelocityDependent(mu_slow=constant.mu, mu_fast=constant.mu)
    ours = run(building, DCFPBearing(2.5, 0.3, friction=flat), motion, n_bearings=4, dt=0.01,
               engine="reference")
    theirs = run(building, DCFPBearing(2.5, 0.3, friction=constant), motion, n_bearings=4,
                 dt=0.01, engine="reference")
    for name in ("displacement", "base_shear", "bearing_friction_force", "energy_error"):
        assert np.array_equal(ours[name], theirs[name]), name


def test_a_building_in_plan_runs_on_it(building):
    from groundmotions.synthetic import synthetic_pair

    plan = Plan([[-5.0, -4.0], [5.0, -4.0], [5.0, 4.0], [-5.0, 4.0]], eccentricity=(0.8, 0.4),
                dimensions=(10.0, 8.0), storey_heights=3.0)
    pair = synthetic_pair("kanai-tajimi", 5, duration=3.0, dt=0.01, target_pga=3.0,
                          ground_frequency=15.0, ground_damping=0.6)
    result = run(dataclasses.replace(building, plan=plan),
                 DCFPBearing(2.5, 0.3, friction=VelocityDependent()), pair, dt=0.01)
    assert result.attrs["success"] and result.attrs["engine"] == "reference"
    sliding = np.hypot(*result["bearing_friction_force"].values.T) > 0.0
    mu = result["mu"].values.T
    assert np.all((mu[sliding] >= 0.02) & (mu[sliding] <= 0.06))
    assert result.attrs["energy_balance_error"] < 1e-8
