"""Properties of the integrators: linearity in the ground motion, revert-then-redo determinism."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from structures.integrators import HHT, Newmark, integrate
from structures.model import RestoringForce
from structures.shear_building import RayleighDamping, ShearBuilding
from tests.verification.test_integrators import ElasticPerfectlyPlastic

DT = 0.01
BUILDING = ShearBuilding([2.0e5, 1.6e5], [3.0e8, 2.0e8], 2.5e5, RayleighDamping((0.05, 0.05)))

# Ground accelerations of physical size: 0, or 1e-6 to 15 m/s^2 in magnitude (the readers refuse
# a record whose PGA is below 1e-4 g). Far smaller values (hypothesis found 6e-167) make the
# squares inside the Euclidean norms of the convergence test underflow, which says nothing
# about the integrator.
records = arrays(
    float,
    st.integers(min_value=2, max_value=60),
    elements=st.floats(min_value=-15.0, max_value=15.0, allow_nan=False,
                       allow_subnormal=False).filter(lambda x: x == 0.0 or abs(x) >= 1e-6),
)
methods = st.sampled_from([Newmark(), Newmark(0.5, 1.0 / 6.0), HHT(-0.1), HHT(-1.0 / 3.0)])
models = st.sampled_from(
    [BUILDING.fixed_base_model(), BUILDING.isolated_linear_model(0.05 * BUILDING.weight)]
)


@settings(max_examples=40, deadline=None)
@given(ground=records, method=methods, model=models)
def test_negated_ground_motion_negates_the_response(ground, method, model):
    forward = integrate(model, ground, DT, method)
    backward = integrate(model, -ground, DT, method)
    assert forward.success and backward.success
    for name in ("displacement", "velocity", "acceleration", "absolute_acceleration"):
        np.testing.assert_array_equal(getattr(backward, name), -getattr(forward, name))


@settings(max_examples=40, deadline=None)
@given(
    ground=records,
    scale=st.floats(min_value=1e-3, max_value=1e3) | st.floats(min_value=-1e3, max_value=-1e-3),
    method=methods,
    model=models,
)
def test_scaling_the_ground_motion_scales_a_linear_response(ground, scale, method, model):
    unit = integrate(model, ground, DT, method)
    scaled = integrate(model, scale * ground, DT, method)
    for name in ("displacement", "velocity", "acceleration"):
        expected = scale * getattr(unit, name)
        size = np.max(np.abs(expected), initial=0.0)
        np.testing.assert_allclose(getattr(scaled, name), expected, rtol=0, atol=1e-9 * size)


class Meddler:
    """Wraps a model and probes a junk trial, then reverts, before every real trial."""

    def __init__(self, model: ElasticPerfectlyPlastic, seed: int):
        self.model, self.rng = model, np.random.default_rng(seed)
        self.mass_matrix, self.damping_matrix = model.mass_matrix, model.damping_matrix
        self.influence = model.influence

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        self.model.restoring_force(self.rng.normal(0.0, 0.1, 1), self.rng.normal(0.0, 1.0, 1), time)
        self.model.revert()
        return self.model.restoring_force(u, v, time)

    def commit(self) -> None:
        self.model.commit()

    def revert(self) -> None:
        self.model.revert()


def elastoplastic() -> ElasticPerfectlyPlastic:
    return ElasticPerfectlyPlastic(1.0e3, 1.0e3 * (2.0 * np.pi / 0.5) ** 2, 1.5e3)


@settings(max_examples=25, deadline=None)
@given(ground=records, method=methods, seed=st.integers(0, 2**32 - 1))
def test_junk_trials_reverted_leave_the_response_unchanged(ground, method, seed):
    plain_model, meddled_model = elastoplastic(), elastoplastic()
    plain = integrate(plain_model, 2.0 * ground, DT, method)
    meddled = integrate(Meddler(meddled_model, seed), 2.0 * ground, DT, method)
    assert plain.success and meddled.success
    np.testing.assert_array_equal(meddled.displacement, plain.displacement)
    np.testing.assert_array_equal(meddled.iterations, plain.iterations)
    assert meddled_model.slip == plain_model.slip and meddled_model.plastic == plain_model.plastic


@settings(max_examples=50, deadline=None)
@given(
    path=st.lists(st.floats(-0.1, 0.1), min_size=1, max_size=10),
    junk=st.lists(st.floats(-0.1, 0.1), min_size=1, max_size=5),
    target=st.floats(-0.1, 0.1),
)
def test_revert_then_redo_equals_a_fresh_trial(path, junk, target):
    probed, fresh = elastoplastic(), elastoplastic()
    for model in (probed, fresh):
        for u in path:
            model.restoring_force(np.array([u]), np.zeros(1), 0.0)
            model.commit()
    for u in junk:
        probed.restoring_force(np.array([u]), np.zeros(1), 0.0)
    probed.revert()
    redo = probed.restoring_force(np.array([target]), np.zeros(1), 0.0)
    once = fresh.restoring_force(np.array([target]), np.zeros(1), 0.0)
    assert redo.force[0] == once.force[0] and redo.stiffness[0, 0] == once.stiffness[0, 0]


class RejectsLongSteps:
    """Wraps a model whose trials more than ``max_step`` after the last commit give NaN forces."""

    def __init__(self, model: ElasticPerfectlyPlastic, max_step: float):
        self.model, self.max_step = model, max_step
        self.mass_matrix, self.damping_matrix = model.mass_matrix, model.damping_matrix
        self.influence = model.influence
        self.committed_time = self.trial_time = 0.0

    def restoring_force(self, u: np.ndarray, v: np.ndarray, time: float) -> RestoringForce:
        self.trial_time = time
        trial = self.model.restoring_force(u, v, time)
        if time - self.committed_time > self.max_step:
            return trial._replace(force=np.full_like(trial.force, np.nan))
        return trial

    def commit(self) -> None:
        self.model.commit()
        self.committed_time = self.trial_time

    def revert(self) -> None:
        self.model.revert()


@settings(max_examples=25, deadline=None)
@given(ground=records, method=methods)
def test_a_reverted_and_halved_step_equals_two_half_steps(ground, method):
    halved = integrate(RejectsLongSteps(elastoplastic(), 0.75 * DT), 2.0 * ground, DT, method)
    fine_ground = np.empty(2 * ground.size - 1)
    fine_ground[::2] = 2.0 * ground
    fine_ground[1::2] = fine_ground[:-1:2] + 0.5 * (fine_ground[2::2] - fine_ground[:-1:2])
    fine = integrate(elastoplastic(), fine_ground, 0.5 * DT, method)
    assert halved.success and fine.success
    assert np.all(halved.subdivisions == 1)
    np.testing.assert_array_equal(
        halved.iterations, 1 + fine.iterations[::2] + fine.iterations[1::2]
    )
    for name in ("displacement", "velocity", "acceleration"):
        expected = getattr(fine, name)[::2]
        size = np.max(np.abs(expected), initial=0.0)
        np.testing.assert_allclose(getattr(halved, name), expected, rtol=0, atol=1e-9 * size)
