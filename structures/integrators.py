"""Implicit time integration of ``M a + C v + f(u, v) = -M r a_g(t)``: Newmark and HHT-alpha.

The influence ``r`` has shape (n,) for a scalar ground acceleration, or (n, k) for k components
(e.g. x and y in plan). A method (:class:`Newmark`, :class:`HHT`, re-exported from
:mod:`structures.integration_methods`) runs on the one Newton step of :class:`NewmarkStepper`.
Misuse raises; a numerical failure or a :class:`dcfpb.common.errors.RunFailure` ends the run with
``success=False``, keeping the steps already taken.

The step from ``t_n`` to ``t_{n+1} = t_n + h`` (Hilber, Hughes & Taylor 1977; ``alpha = 0`` is
Newmark)::

    M a_{n+1} + (1 + alpha) [C v_{n+1} + f_{n+1}] - alpha [C v_n + f_n]
        = (1 + alpha) p_{n+1} - alpha p_n
    u_{n+1} = u_n + h v_n + h^2 [(1/2 - beta) a_n + beta a_{n+1}]
    v_{n+1} = v_n + h [(1 - gamma) a_n + gamma a_{n+1}]

is solved by Newton on ``K_eff = c0 M + (1 + alpha) [c1 (C + df/dv) + df/du]``,
``c0 = 1/(beta h^2)``, ``c1 = gamma/(beta h)``, from ``a_{n+1} = a_n``. With the residual ``R``
and ``du = K_eff^-1 R``, an iterate is accepted when ``|R| <= tolerance * F_ref`` [N] and
``|du| <= tolerance * max(|u_{n+1}|, |u_n|)`` [m] (Euclidean norms), ``F_ref`` the largest of
``|M a_{n+1}|``, ``|C v_{n+1} + f_{n+1}|``, ``|p_{n+1}|``, ``|C v_n + f_n|`` and ``|p_n|``; one
iteration is one restoring-force evaluation (a linear model takes two). A step that does not
converge in ``max_iterations`` is reverted and solved as two half steps (the ground acceleration
interpolated linearly), down to ``max_subdivisions`` halvings, committing after each sub-step.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from dcfpb.common.errors import InputError, RunFailure
from dcfpb.common.validation import check_array, check_int, check_real
from structures.integration_methods import HHT, METHODS, Newmark, as_method
from structures.model import DynamicModel

__all__ = [
    "HHT", "METHODS", "IntegrationResult", "Newmark", "NewmarkStepper", "as_method", "integrate",
]


@dataclass(frozen=True, eq=False)
class IntegrationResult:
    """A time history relative to the ground, up to the last committed step: ``time`` (nt,)
    [s]; ``displacement``, ``velocity``, ``acceleration`` (nt, n) [m], [m/s], [m/s^2] and
    ``absolute_acceleration = acceleration + r a_g`` [m/s^2]; ``success`` (the whole record
    integrated) and ``message`` (why the run ended); ``iterations`` (Newton, failed attempts
    included) and ``subdivisions`` (halvings) of each committed step, (nt-1,); the ``method``;
    ``failure`` (``""``, ``"convergence"`` or the ``kind`` of the
    :class:`dcfpb.common.errors.RunFailure` that ended the run) and ``failed_at`` [s] (None)."""

    time: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    absolute_acceleration: np.ndarray
    success: bool
    message: str
    iterations: np.ndarray
    subdivisions: np.ndarray
    method: Newmark | HHT
    failure: str = ""
    failed_at: float | None = None


def _matrix(value: object, name: str, shape: tuple[int, ...]) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if arr.shape != shape or not np.all(np.isfinite(arr)):
        raise InputError(
            f"The model's {name!r} must be a finite array of shape {shape}. "
            f"Got shape {arr.shape} instead."
        )
    return arr


class NewmarkStepper:
    """The shared Newton step of the Newmark family, with step subdivision (module docstring).

    It holds the committed state ``(t, u, v, a)``, the ground acceleration ``ag``, and the
    committed internal force ``q = C v + f`` and load ``p`` of the HHT balance; arrays handed to
    the model are never modified afterwards (it may keep references). The initial ``time`` [s],
    ``ground_acceleration`` [m/s^2] (a float, or shape (k,)), ``displacement`` [m] and
    ``velocity`` [m/s] (n,) must match the model's committed state; the rest is as
    :func:`integrate`.
    """

    def __init__(
        self,
        model: DynamicModel,
        method: Newmark | HHT,
        time: float,
        ground_acceleration: float | np.ndarray,
        displacement: np.ndarray,
        velocity: np.ndarray,
        *,
        tolerance: float,
        max_iterations: int,
        max_subdivisions: int,
    ) -> None:
        self.model = model
        self.gamma, self.beta, self.alpha = method.gamma, method.beta, method.alpha
        self.tolerance, self.max_iterations = tolerance, max_iterations
        self.max_subdivisions = max_subdivisions
        n = displacement.shape[0]
        self.mass = _matrix(model.mass_matrix, "mass_matrix", (n, n))
        self.damping = _matrix(model.damping_matrix, "damping_matrix", (n, n))
        influence = np.asarray(model.influence, dtype=float)
        shape = (n,) if influence.ndim < 2 else (n, influence.shape[1])
        self.mass_influence = self.mass @ _matrix(influence, "influence", shape)
        self.components = 0 if influence.ndim < 2 else influence.shape[1]  # 0: scalar a_g
        self.t, self.u, self.v = float(time), displacement.copy(), velocity.copy()
        trial = model.restoring_force(self.u, self.v, self.t)
        for name, value, shape in zip(trial._fields, trial, ((n,), (n, n), (n, n)), strict=True):
            _matrix(value, f"restoring_force(...).{name}", shape)
        model.revert()  # the integrator never changes the history before the first step
        self.ag = self._ground(ground_acceleration)
        self.p = self._load(self.ag)
        self.q = self.damping @ self.v + trial.force
        self.a = np.linalg.solve(self.mass, self.p - self.q)
        self.step_iterations = self.step_subdivisions = 0
        self.message = ""

    def _ground(self, ground_acceleration: float | np.ndarray) -> float | np.ndarray:
        """The ground acceleration of one step as the model's influence takes it."""
        if not self.components:
            return float(ground_acceleration)
        return _matrix(ground_acceleration, "ground acceleration of a step", (self.components,))

    def _load(self, ground_acceleration: float | np.ndarray) -> np.ndarray:
        """``p = -M r a_g`` [N]."""
        if not self.components:
            return -self.mass_influence * ground_acceleration
        return -(self.mass_influence @ ground_acceleration)

    def step(self, time: float, ground_acceleration: float | np.ndarray) -> bool:
        """Advance and commit to ``time`` [s]; return False (see :attr:`message`) on failure."""
        self.step_iterations = self.step_subdivisions = 0
        self._start, self._end, self._span = self.t, float(time), float(time) - self.t
        self._ag_start, self._ag_end = self.ag, self._ground(ground_acceleration)
        return self._advance(0.0, 1.0, 0)

    def _advance(self, s0: float, s1: float, depth: int) -> bool:
        """Solve the fraction ``[s0, s1]`` of the step, halving it on failure."""
        if s1 == 1.0:
            t_end, ag_end = self._end, self._ag_end
        else:
            t_end = self._start + s1 * self._span
            ag_end = self._ag_start + s1 * (self._ag_end - self._ag_start)
        converged, iterations, residual, reference = self._solve(
            (s1 - s0) * self._span, t_end, ag_end
        )
        self.step_iterations += iterations
        if converged:
            self.model.commit()
            return True
        self.model.revert()
        if depth >= self.max_subdivisions:
            relative = residual / reference if reference > 0.0 else np.inf
            self.message = (
                f"Newton iteration did not converge in the step to t = {t_end:.6g} s (sub-step "
                f"of {(s1 - s0) * self._span:.3g} s after {depth} halvings): after {iterations} "
                f"iterations the residual norm was {residual:.3e} N ({relative:.3e} of the force "
                f"reference {reference:.3e} N; tolerance {self.tolerance:g})."
            )
            return False
        self.step_subdivisions += 1
        middle = 0.5 * (s0 + s1)
        return self._advance(s0, middle, depth + 1) and self._advance(middle, s1, depth + 1)

    def _solve(
        self, h: float, time: float, ground_acceleration: float | np.ndarray
    ) -> tuple[bool, int, float, float]:
        """One Newton attempt (moving the committed state to ``time`` on success): ``(converged,
        iterations, residual norm [N], force reference [N])``."""
        alpha, weight = self.alpha, 1.0 + self.alpha
        c0, c1 = 1.0 / (self.beta * h * h), self.gamma / (self.beta * h)
        p = self._load(ground_acceleration)
        load = weight * p - alpha * self.p + alpha * self.q
        a = self.a
        u = self.u + h * self.v + (0.5 * h * h) * a
        v = self.v + h * a
        previous = max(np.linalg.norm(self.p), np.linalg.norm(self.q))
        u_norm = np.linalg.norm(self.u)
        r_norm = reference = np.inf
        for iteration in range(1, self.max_iterations + 1):
            trial = self.model.restoring_force(u, v, time)
            q = self.damping @ v + trial.force
            inertia = self.mass @ a
            residual = load - inertia - weight * q
            tangent = c0 * self.mass + weight * (
                c1 * (self.damping + trial.damping) + trial.stiffness
            )
            r_norm = float(np.linalg.norm(residual))
            reference = max(previous, np.linalg.norm(inertia), np.linalg.norm(q), np.linalg.norm(p))
            try:
                du = np.linalg.solve(tangent, residual)
            except np.linalg.LinAlgError:
                return False, iteration, r_norm, reference
            if not np.all(np.isfinite(du)):
                return False, iteration, r_norm, reference
            if r_norm <= self.tolerance * reference and np.linalg.norm(du) <= self.tolerance * max(
                np.linalg.norm(u), u_norm
            ):
                self.t, self.u, self.v, self.a = time, u, v, a
                self.ag, self.p, self.q = ground_acceleration, p, q
                return True, iteration, r_norm, reference
            u, v, a = u + du, v + c1 * du, a + c0 * du
        return False, self.max_iterations, r_norm, reference


def _initial_state(value: object, name: str, n: int) -> np.ndarray:
    if value is None:
        return np.zeros(n)
    state = check_array(value, name, "integrate")
    if state.shape != (n,):
        raise InputError(
            f"The {name!r} parameter of integrate must have shape ({n},). "
            f"Got {state.shape} instead."
        )
    return state


def integrate(
    model: DynamicModel,
    ground_acceleration: object,
    dt: float,
    method: str | Newmark | HHT = "newmark",
    *,
    initial_displacement: object = None,
    initial_velocity: object = None,
    tolerance: float = 1e-8,
    max_iterations: int = 25,
    max_subdivisions: int = 4,
    on_commit: Callable[[int, float, np.ndarray, np.ndarray, np.ndarray], None] | None = None,
) -> IntegrationResult:
    """Integrate a model through a ground-acceleration record (module docstring).

    Parameters
    ----------
    model : DynamicModel
        The structure; its committed state must be that of the initial conditions.
    ground_acceleration : array_like
        Ground acceleration sampled every ``dt`` from ``t = 0`` [m/s^2], shape (nt,), or (nt, k)
        for a model whose influence has shape (n, k).
    dt : float
        Time step of the record and of the integration [s].
    method : {"newmark", "hht"} or Newmark or HHT
        A name from :data:`METHODS` (default parameters) or a configured instance.
    initial_displacement, initial_velocity : array_like, optional
        Initial state relative to the ground, shape (n,) [m], [m/s]; zeros by default.
    tolerance : float
        Relative tolerance of the force-residual and displacement-increment tests, in (0, 1).
    max_iterations, max_subdivisions : int
        Newton iterations per attempt (>= 1) and nested halvings of a step that does not converge
        (>= 0).
    on_commit : callable, optional
        ``on_commit(step_index, time, u, v, a)`` after each committed full step (index >= 1);
        the arrays are rows of the result, not to be modified. Raising
        :class:`dcfpb.common.errors.RunFailure` ends the run, that step kept.

    Returns
    -------
    IntegrationResult
        The history up to the last committed step, with ``success`` and ``message``.
    """
    owner = "integrate"
    chosen = as_method(method)
    influence = np.asarray(model.influence, dtype=float)
    record = check_array(ground_acceleration, "ground_acceleration", owner, min_length=2,
                         ndim=max(influence.ndim, 1))
    if influence.ndim == 2 and record.shape[1] != influence.shape[1]:
        raise InputError(
            f"The 'ground_acceleration' parameter of integrate must have one column per column "
            f"of the model's influence ({influence.shape[1]}). Got shape {record.shape} instead."
        )
    step = check_real(dt, "dt", owner, low=0.0, low_open=True)
    tol = check_real(tolerance, "tolerance", owner, low=0, high=1, low_open=True, high_open=True)
    iterations_max = check_int(max_iterations, "max_iterations", owner, low=1)
    subdivisions_max = check_int(max_subdivisions, "max_subdivisions", owner, low=0)
    n = np.asarray(model.mass_matrix).shape[0]
    u0 = _initial_state(initial_displacement, "initial_displacement", n)
    v0 = _initial_state(initial_velocity, "initial_velocity", n)

    nt = record.shape[0]
    time = step * np.arange(nt)
    displacement, velocity, acceleration = np.empty((nt, n)), np.empty((nt, n)), np.empty((nt, n))
    iterations, subdivisions = np.zeros(nt - 1, dtype=int), np.zeros(nt - 1, dtype=int)
    limits = {"max_iterations": iterations_max, "max_subdivisions": subdivisions_max}
    stepper = NewmarkStepper(model, chosen, time[0], record[0], u0, v0, tolerance=tol, **limits)
    displacement[0], velocity[0], acceleration[0] = stepper.u, stepper.v, stepper.a
    last, success, failure, failed_at = nt - 1, True, "", None
    message = "The integration reached the end of the record."
    for k in range(1, nt):
        try:
            success = stepper.step(time[k], record[k])
        except RunFailure as error:  # the model cannot go on: the run ends at step k - 1
            model.revert()
            success, failure, stepper.message = False, error.kind, str(error)
        iterations[k - 1], subdivisions[k - 1] = stepper.step_iterations, stepper.step_subdivisions
        if not success:
            last, message, failed_at = k - 1, f"Step {k}: {stepper.message}", float(time[k])
            failure = failure or "convergence"
            break
        displacement[k], velocity[k], acceleration[k] = stepper.u, stepper.v, stepper.a
        try:
            if on_commit is not None:
                on_commit(k, time[k], displacement[k], velocity[k], acceleration[k])
        except RunFailure as error:  # e.g. a time limit: step k is kept
            last, success, failure, failed_at = k, False, error.kind, float(time[k])
            message = f"Step {k}: {error}"
            break

    kept = slice(0, last + 1)
    if influence.ndim == 2:
        absolute = acceleration[kept] + record[kept] @ influence.T
    else:
        absolute = acceleration[kept] + record[kept, None] * influence
    arrays = [time[kept], displacement[kept], velocity[kept], acceleration[kept], absolute]
    arrays += [iterations[:last], subdivisions[:last]]
    for array in arrays:
        array.setflags(write=False)
    return IntegrationResult(*arrays[:5], success, message, *arrays[5:], method=chosen,
                             failure=failure, failed_at=failed_at)
