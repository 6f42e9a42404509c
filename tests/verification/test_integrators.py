"""Newmark and HHT-alpha against closed-form answers: period, order, spectral radius, energy."""

from __future__ import annotations

import math

import numpy as np
import pytest

from structures.integrators import HHT, METHODS, Newmark, integrate
from structures.model import LinearModel, RestoringForce
from structures.shear_building import ModalDamping, RayleighDamping, ShearBuilding


def sdof(period: float, mass: float = 1.0, ratio: float = 0.0) -> LinearModel:
    """A linear single-degree-of-freedom oscillator of the given period [s] and damping ratio."""
    omega = 2.0 * np.pi / period
    return LinearModel([[mass]], [[2.0 * ratio * omega * mass]], [[mass * omega**2]], [1.0])


class ElasticPerfectlyPlastic:
    """A mass on an elastic-perfectly-plastic spring: the OpenSees ElasticPP return map.

    The trial is a pure function of the committed plastic displacement and the trial
    displacement; ``commit`` moves the plastic displacement and adds up the plastic slip [m].
    """

    def __init__(self, mass: float, stiffness: float, yield_force: float, damping: float = 0.0):
        self.stiffness, self.yield_force = stiffness, yield_force
        self.mass_matrix = np.array([[mass]])
        self.damping_matrix = np.array([[damping]])
        self.influence = np.ones(1)
        self.plastic = self._trial_plastic = 0.0
        self.slip = 0.0
        self.commits = 0

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        trial = self.stiffness * (u[0] - self.plastic)
        if abs(trial) <= self.yield_force:
            force, tangent, self._trial_plastic = trial, self.stiffness, self.plastic
        else:
            force, tangent = math.copysign(self.yield_force, trial), 0.0
            self._trial_plastic = u[0] - force / self.stiffness
        return RestoringForce(np.array([force]), np.array([[tangent]]), np.zeros((1, 1)))

    def commit(self) -> None:
        self.slip += abs(self._trial_plastic - self.plastic)
        self.plastic = self._trial_plastic
        self.commits += 1

    def revert(self) -> None:
        self._trial_plastic = self.plastic


def trapezoid(y: np.ndarray, x: np.ndarray) -> float:
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))


def _isolated_building():
    from isolator.bearing import DCFPBearing
    from isolator.friction import ConstantFriction
    from structures.isolated_building import IsolatedShearBuilding

    building = ShearBuilding.from_period(np.full(3, 4.0e5), 0.5, base_mass=5.0e5)
    return IsolatedShearBuilding(building, DCFPBearing(4.0, 0.3, None, ConstantFriction(0.04)),
                                 n_bearings=4)


@pytest.mark.parametrize("make", [lambda: sdof(1.0, 2.0, 0.05),
                                  lambda: ElasticPerfectlyPlastic(1.0, 100.0, 0.5),
                                  _isolated_building], ids=["sdof", "epp", "isolated"])
def test_the_models_keep_the_element_contract(make):
    """What integrate() relies on, called and checked (not just the method names): square
    matrices of one size; a trial that is a pure function of the committed state (repeatable,
    undone by revert); a commit that moves the history on; a tangent that matches the force."""
    model = make()
    n = model.mass_matrix.shape[0]
    assert model.mass_matrix.shape == model.damping_matrix.shape == (n, n)
    assert model.influence.shape == (n,)
    far = np.full(n, 0.02)  # beyond yield for both hysteretic models
    velocity = np.full(n, 0.3)
    first = model.restoring_force(far, velocity, 0.01)
    assert first.force.shape == (n,) and first.stiffness.shape == first.damping.shape == (n, n)
    model.restoring_force(-far, -velocity, 0.01)  # another trial in between
    again = model.restoring_force(far, velocity, 0.01)
    np.testing.assert_array_equal(again.force, first.force)
    model.revert()
    np.testing.assert_array_equal(model.restoring_force(far, velocity, 0.01).force, first.force)
    origin = model.restoring_force(np.zeros(n), np.zeros(n), 0.01).force
    model.restoring_force(far, velocity, 0.01)
    model.commit()
    after = model.restoring_force(np.zeros(n), np.zeros(n), 0.02).force
    if isinstance(model, LinearModel):
        np.testing.assert_array_equal(after, origin)  # no history in a linear spring
    else:
        assert not np.allclose(after, origin)  # the committed slip is remembered
    small = np.full(n, 1e-9)  # on the current branch: the tangent predicts the force change
    base = model.restoring_force(far, velocity, 0.03)
    step = model.restoring_force(far + small, velocity, 0.03)
    np.testing.assert_allclose(step.force - base.force, base.stiffness @ small,
                               rtol=1e-5, atol=1e-9 * np.abs(base.force).max())


# --- linear SDOF, average acceleration: no amplitude decay, exact period elongation --------------


@pytest.mark.parametrize("step_ratio", [0.02, 0.1, 0.3])
def test_average_acceleration_conserves_energy_and_elongates_period(step_ratio):
    period, mass, u0 = 0.8, 2.5, 0.01
    omega, dt = 2.0 * np.pi / period, step_ratio * period
    n_steps = round(100 / step_ratio)  # 100 periods
    result = integrate(sdof(period, mass), np.zeros(n_steps + 1), dt, initial_displacement=[u0])
    u, v = result.displacement[:, 0], result.velocity[:, 0]

    energy = 0.5 * mass * omega**2 * u**2 + 0.5 * mass * v**2
    assert np.max(np.abs(energy / energy[0] - 1.0)) < 1e-11

    phase = np.unwrap(np.angle(u - 1j * v / omega))
    measured = 2.0 * np.pi * dt / np.polyfit(np.arange(n_steps + 1), phase, 1)[0]
    big_omega = omega * dt
    expected = period * big_omega / (2.0 * np.arctan(big_omega / 2.0))  # trapezoidal rule
    assert measured == pytest.approx(expected, rel=1e-6)
    assert measured > period


# --- linear SDOF, harmonic ground motion, 5 % damping: second-order convergence ------------------


def harmonic_response(t, period, ratio, amplitude, forcing_period):
    """Exact relative displacement of an SDOF at rest under a_g = amplitude sin(w_g t) [m]."""
    w, wg = 2.0 * np.pi / period, 2.0 * np.pi / forcing_period
    wd = w * np.sqrt(1.0 - ratio**2)
    g = -amplitude / (w**2 - wg**2 + 2j * ratio * w * wg)  # u_p = Im(g exp(i wg t))
    d1 = -g.imag
    d2 = (ratio * w * d1 - (g * 1j * wg).imag) / wd
    transient = np.exp(-ratio * w * t) * (d1 * np.cos(wd * t) + d2 * np.sin(wd * t))
    return (g * np.exp(1j * wg * t)).imag + transient


@pytest.mark.parametrize(
    "method", [Newmark(), Newmark(0.5, 1.0 / 6.0), HHT(-0.1)], ids=["average", "linear", "hht"]
)
def test_forced_vibration_converges_at_second_order(method):
    period, ratio, amplitude, forcing_period, duration = 1.0, 0.05, 3.0, 0.7, 4.0
    errors = []
    for dt in (0.02, 0.01, 0.005, 0.0025):
        t = dt * np.arange(round(duration / dt) + 1)
        ground = amplitude * np.sin(2.0 * np.pi / forcing_period * t)
        result = integrate(sdof(period, 3.0, ratio), ground, dt, method)
        exact = harmonic_response(t, period, ratio, amplitude, forcing_period)
        errors.append(np.max(np.abs(result.displacement[:, 0] - exact)) / np.max(np.abs(exact)))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 2.0) < 0.1), (errors, orders)
    assert errors[-1] < 5e-4


# --- HHT-alpha: spectral radius and numerical damping from an independent amplification matrix ---


def hht_amplification(big_omega: float, alpha: float) -> np.ndarray:
    """Amplification matrix of ``(u, dt v, dt^2 a)`` in free vibration, ``Omega = omega dt``.

    From ``u1 = u0 + h v0 + h^2((1/2-b) a0 + b a1)``, ``v1 = v0 + h((1-g) a0 + g a1)`` and
    ``a1 + (1+alpha) omega^2 u1 - alpha omega^2 u0 = 0`` (Hilber, Hughes & Taylor 1977), with
    ``g = 1/2 - alpha`` and ``b = (1 - alpha)^2/4``.
    """
    g, b, w2 = 0.5 - alpha, 0.25 * (1.0 - alpha) ** 2, big_omega**2
    new = np.array([[1.0, 0.0, -b], [0.0, 1.0, -g], [(1.0 + alpha) * w2, 0.0, 1.0]])
    old = np.array([[1.0, 1.0, 0.5 - b], [0.0, 1.0, 1.0 - g], [alpha * w2, 0.0, 0.0]])
    return np.linalg.solve(new, old)


def principal_roots(u: np.ndarray) -> np.ndarray:
    """The two roots of ``u[n+2] = p1 u[n+1] + p2 u[n]`` fitted to a sequence (Prony)."""
    u = u / np.max(np.abs(u))
    (p1, p2), *_ = np.linalg.lstsq(np.column_stack([u[1:-1], u[:-2]]), u[2:], rcond=None)
    return np.roots([1.0, -p1, -p2])


def free_vibration_roots(method, step_ratio, skip, fit=100):
    """Run free vibration at dt/T = step_ratio and fit the principal roots after ``skip`` steps."""
    period = 0.5
    result = integrate(
        sdof(period),
        np.zeros(skip + fit + 1),
        step_ratio * period,
        method,
        initial_displacement=[1.0],
    )
    return principal_roots(result.displacement[skip:, 0])


@pytest.mark.parametrize("alpha", [-0.05, -0.1, -0.2, -0.3])
def test_hht_spectral_radius_at_large_steps(alpha):
    big_omega = 2.0 * np.pi * 100.0
    theory = np.max(np.abs(np.linalg.eigvals(hht_amplification(big_omega, alpha))))
    limit = np.max(np.abs(np.linalg.eigvals(hht_amplification(1e5, alpha))))
    assert limit == pytest.approx((1.0 + alpha) / (1.0 - alpha), rel=1e-6)

    measured = np.max(np.abs(free_vibration_roots(HHT(alpha), 100.0, skip=200)))
    assert measured == pytest.approx(theory, rel=1e-6)
    assert measured == pytest.approx((1.0 + alpha) / (1.0 - alpha), rel=1e-3)


@pytest.mark.parametrize("alpha", [-0.05, -0.1, -0.3])
@pytest.mark.parametrize("step_ratio", [0.05, 0.1, 0.2])
def test_hht_numerical_damping_ratio(alpha, step_ratio):
    def damping_ratio(roots):
        root = roots[np.argmax(roots.imag)]
        return -np.log(np.abs(root)) / np.angle(root)

    eigenvalues = np.linalg.eigvals(hht_amplification(2.0 * np.pi * step_ratio, alpha))
    principal = eigenvalues[np.argsort(np.abs(eigenvalues))[1:]]
    theory = damping_ratio(principal)
    measured = damping_ratio(free_vibration_roots(HHT(alpha), step_ratio, skip=30))
    assert measured == pytest.approx(theory, rel=1e-6)
    assert 0.0 < measured < -alpha * 2.0 * np.pi * step_ratio  # positive, below ~ -alpha Omega


def test_average_acceleration_has_no_numerical_damping():
    roots = free_vibration_roots(Newmark(), 0.2, skip=0)
    assert np.abs(roots) == pytest.approx([1.0, 1.0], rel=1e-12)


# --- fixed-base building: modal periods ----------------------------------------------------------


@pytest.mark.parametrize("mode", [0, 1, 2])
def test_fixed_base_building_vibrates_at_its_modal_periods(mode):
    building = ShearBuilding([3.0e5, 2.8e5, 2.2e5], [4.0e8, 3.0e8, 2.0e8], 3.0e5, ModalDamping(0.0))
    periods, shapes = building.fixed_base_modes()
    period, shape = periods[mode], shapes[:, mode]
    dt = period / 100.0
    result = integrate(
        building.fixed_base_model(), np.zeros(2001), dt, initial_displacement=0.01 * shape
    )
    u = result.displacement

    mass = building.fixed_base_mass_matrix
    modal = u @ mass @ shape
    assert np.max(np.abs(u - np.outer(modal, shape))) < 1e-10 * np.max(np.abs(u))

    roof = u[:, -1]
    i = np.flatnonzero(np.sign(roof[1:]) != np.sign(roof[:-1]))
    crossings = result.time[i] - roof[i] * dt / (roof[i + 1] - roof[i])
    measured = 2.0 * np.mean(np.diff(crossings))
    big_omega = 2.0 * np.pi * dt / period
    assert measured == pytest.approx(period * big_omega / (2 * np.arctan(big_omega / 2)), rel=1e-5)
    assert measured == pytest.approx(period, rel=1e-3)


def test_fixed_base_building_decays_at_its_rayleigh_ratio():
    building = ShearBuilding(
        [3.0e5, 2.8e5, 2.2e5], [4.0e8, 3.0e8, 2.0e8], 3.0e5, RayleighDamping((0.05, 0.05))
    )
    periods, shapes = building.fixed_base_modes()
    dt = periods[0] / 200.0
    result = integrate(
        building.fixed_base_model(), np.zeros(1201), dt, initial_displacement=0.01 * shapes[:, 0]
    )
    roof = result.displacement[:, -1]
    peaks = np.flatnonzero((roof[1:-1] > roof[:-2]) & (roof[1:-1] > roof[2:])) + 1
    decrement = np.log(roof[0] / roof[peaks[4]]) / 5.0
    assert decrement / np.hypot(2.0 * np.pi, decrement) == pytest.approx(0.05, rel=1e-2)


# --- nonlinear: elastic-perfectly-plastic spring -------------------------------------------------


@pytest.mark.parametrize("method", [Newmark(), HHT(-0.1)], ids=["average", "hht"])
def test_elastoplastic_oscillator_converges_and_dissipates_its_loop_area(method):
    mass, period, yield_displacement = 1.0e3, 0.5, 0.01
    stiffness = mass * (2.0 * np.pi / period) ** 2
    model = ElasticPerfectlyPlastic(mass, stiffness, stiffness * yield_displacement)
    dt = 0.005
    t = dt * np.arange(1201)
    ground = 2.0 * np.sin(2.0 * np.pi / 0.6 * t) * np.exp(-0.3 * t)
    force, steps = [0.0], []  # the spring force as committed, recorded through on_commit

    def record(k, time, u, v, a):
        steps.append(k)
        force.append(stiffness * (u[0] - model.plastic))

    result = integrate(model, ground, dt, method, on_commit=record)

    assert result.success, result.message
    assert steps == list(range(1, t.size))
    assert result.iterations.max() <= 4 and result.iterations.mean() < 2.1
    u, v = result.displacement[:, 0], result.velocity[:, 0]
    assert np.min(u) < -2.0 * yield_displacement and np.max(u) > 2.0 * yield_displacement
    assert model.slip > 10.0 * yield_displacement

    force = np.array(force)
    hysteretic = trapezoid(force, u)  # work done on the spring
    stored = force[-1] ** 2 / (2.0 * stiffness)
    assert hysteretic == pytest.approx(model.yield_force * model.slip + stored, rel=2e-3)
    if method == Newmark():  # average acceleration: the discrete energy balance closes exactly
        kinetic = 0.5 * mass * (v[-1] ** 2 - v[0] ** 2)
        input_energy = trapezoid(-mass * ground, u)
        assert kinetic + hysteretic == pytest.approx(input_energy, rel=1e-7)


class DivergesAfter(LinearModel):
    """A linear SDOF whose force jumps back and forth at every call once time >= ``onset``."""

    def __init__(self, onset: float):
        model = sdof(1.0, 1.0, 0.02)
        super().__init__(model.mass_matrix, model.damping_matrix, model.stiffness_matrix, [1.0])
        self.onset, self.calls, self.times = onset, 0, []

    def restoring_force(self, u, v, time):
        self.times.append(time)
        trial = super().restoring_force(u, v, time)
        if time < self.onset:
            return trial
        self.calls += 1
        return trial._replace(force=trial.force + (-1.0) ** self.calls * 10.0)


def test_non_convergence_subdivides_then_reports_and_keeps_earlier_steps():
    dt, onset = 0.01, 0.5031
    ground = 2.0 * np.sin(2.0 * np.pi * dt * np.arange(101))
    model = DivergesAfter(onset)
    result = integrate(model, ground, dt, max_iterations=8, max_subdivisions=3)

    assert not result.success
    assert result.time.size == 51 and result.time[-1] == pytest.approx(0.5)
    assert "after 8 iterations" in result.message
    assert "residual norm" in result.message and "3 halvings" in result.message
    # 0.51 fails; to 0.505 fails; to 0.5025 is committed; to 0.505 fails; to 0.50375 fails at
    # the third halving: the run stops there
    tried = sorted({round(t, 9) for t in model.times if t > 0.5})
    assert tried == [0.5025, 0.50375, 0.505, 0.51] and "t = 0.50375 s" in result.message
    reference = integrate(sdof(1.0, 1.0, 0.02), ground[:51], dt)
    np.testing.assert_array_equal(result.displacement, reference.displacement)
    assert result.iterations.shape == (50,) and np.all(result.iterations == 2)


# --- misuse raises with the house template -------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        (
            {"dt": 0.0},
            ValueError,
            "The 'dt' parameter of integrate must be a float in \\(0, inf\\)",
        ),
        ({"dt": float("nan")}, ValueError, "'dt' parameter"),
        ({"method": "rk45"}, ValueError, "The 'method' parameter of integrate must be one of"),
        ({"method": 3}, TypeError, "'method' parameter"),
        ({"ground_acceleration": np.zeros((3, 2))}, ValueError, "'ground_acceleration'"),
        ({"initial_displacement": [0.0, 1.0]}, ValueError, "'initial_displacement'"),
        ({"tolerance": 1.0}, ValueError, "'tolerance'"),
        ({"max_subdivisions": -1}, ValueError, "'max_subdivisions'"),
    ],
)
def test_misuse_raises(kwargs, error, match):
    arguments = {"ground_acceleration": np.zeros(5), "dt": 0.01} | kwargs
    with pytest.raises(error, match=match):
        integrate(sdof(1.0), **arguments)


def test_method_parameters_are_validated_and_registered():
    assert set(METHODS) == {"newmark", "hht"}
    assert HHT(-1.0 / 3.0).beta == pytest.approx(4.0 / 9.0) and HHT(-0.1).gamma == pytest.approx(
        0.6
    )
    assert Newmark(0.5, 1.0 / 6.0).stability_limit == pytest.approx(np.sqrt(12.0))
    with pytest.raises(ValueError, match="The 'gamma' parameter of Newmark must be a float in"):
        Newmark(gamma=0.4)
    with pytest.raises(ValueError, match="The 'alpha' parameter of HHT must be a float in"):
        HHT(alpha=-0.5)
