"""The compiled engine: a whole time-history run of a shear building on DCFPB isolators.

:func:`integrate_building` is the time loop of :func:`structures.analysis.run` in one numba
function, with no Python object touched per step: the Newmark / HHT-alpha Newton step of
:mod:`structures.integrators`, the bearing of :mod:`isolator.bearing` (elastic-plastic return
map, linear or spherical restoring law) and its friction (constant, or Eq. 7 with or without
heating), through the kernels the element calls: ``cold_friction``, ``solve_friction``,
``heated_window`` and ``ptv_friction`` of :mod:`isolator.compiled.kernels` (``ptv_trial`` is
``heated_window``, ``contact_history`` and ``ptv_friction``) and ``step_factors`` of
:mod:`isolator.heating`. It mirrors the reference operation for operation, so the two agree
to round-off:

- the same predictor, residual, force reference and the two convergence tests (the force
  residual and the Newton correction, both relative to ``tolerance``);
- the same depth-first step halving (an explicit stack instead of recursion), with the ground
  acceleration interpolated linearly and the model committed after each sub-step;
- the same trial / commit / revert semantics of the bearing and its heat history, with step
  factors exact for every step size (the few distinct sizes of a run, t_n - t_(n-1) rounded,
  are kept in a table of ``FACTOR_SLOTS``).

Two things are done differently, both exact rearrangements:

- The superstructure is linear and the isolators act on the base slab (DOF 0) only, so the
  Newton matrix is ``A + d e0 e0^T`` with ``A = c0 M + (1 + alpha)(c1 C + K)`` constant for a
  step size and ``d`` the isolators' tangent: ``A^-1`` is computed once per step size (and per
  halving depth) and each iteration solves with the Sherman-Morrison formula in O(n^2).
- The monitor points under the slider take the same flux, so their heat history is held as a
  group (:mod:`isolator.contact_window`): O(K) per step and per trial instead of advancing
  every point ever heated (``advance_states``, O(points x K)) and re-summing the window for
  every trial (``contact_history``, O(window x K)).

What it costs to compile on a cold cache (``benchmarks/COLD_START.md``) is kept down by
writing the loop in plain scalar arithmetic: the work arrays come from Python
(:func:`structures.compiled.workspace.new_workspace`), the two dense solves are direct LAPACK calls
(:mod:`structures.compiled.lapack`), and nothing is allocated, broadcast or multiplied as a
matrix inside, since numba compiles each such numpy construct as a function of its own. The
helpers are ordinary compiled functions, which LLVM inlines; numba's own IR inlining
(``inline="always"``) cost more compile time than it saved.

Without numba, or with ``DCFPB_DISABLE_NUMBA=1``, the same source runs as plain Python (slow,
meant for tests); ``integrate_building.py_func`` is the Python original of the top level.
The bearing, its friction and heat history in array form are
:mod:`isolator.compiled.bearing`; the Python side of the engine (packing the model, the
messages, the result) is :mod:`structures.compiled.engine`.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.compiled.bearing import DISPLACEMENT as BEARING_DISPLACEMENT
from isolator.compiled.bearing import (
    FORCE,
    INITIAL_MU,
    INITIAL_TEMPERATURE,
    MU,
    N_BEARINGS,
    NOT_CONVERGED,
    PENDING,
    PENDING_DT,
    STATE_SIZE,
    STEP_BELOW_MIN_LAG,
    SUCCESS,
    TEMPERATURE,
    bearing_commit,
    bearing_trial,
    record_state,
)
from isolator.compiled.kernels import jit
from structures.compiled.lapack import invert, solve
from structures.compiled.workspace import (
    A_C,
    ALPHA,
    BETA,
    COMMITTED,
    DOFS,
    DU,
    FAIL_DEPTH,
    FAIL_ITERATIONS,
    FAIL_REFERENCE,
    FAIL_RESIDUAL,
    FAIL_SUBSTEP,
    FAIL_TIME,
    FAIL_VALUE,
    GAMMA,
    INVERSE_STEPS,
    INVERSES,
    LAPACK_WORK,
    LAST_STEP,
    LOAD,
    MASS_INFLUENCE,
    MATRIX,
    MAX_ITERATIONS,
    MAX_SUBDIVISIONS,
    P_C,
    PIVOTS,
    Q_C,
    RESIDUAL,
    STACK_DEPTH,
    STACK_END,
    STACK_START,
    STATUS,
    TOLERANCE,
    TRIAL,
    U_C,
    V_C,
    A,
    P,
    Q,
    U,
    V,
)

__all__ = ["integrate_building"]

@jit
def _effective_inverse(h, mass, damping, stiffness, gamma, beta, alpha, inverse, matrix, work,
                       pivots):
    """inverse <- (c0 M + (1 + alpha)(c1 C + K))^-1 for a step ``h`` [s]; ``matrix``,
    ``work`` and ``pivots`` are work arrays (n, n), (n, n) and int32 (n,)."""
    c0, c1 = 1.0 / (beta * h * h), gamma / (beta * h)
    n = mass.shape[0]
    for i in range(n):  # element by element, as numpy's expression would
        for j in range(n):
            matrix[i, j] = c0 * mass[i, j] + (1.0 + alpha) * (c1 * damping[i, j]
                                                                + stiffness[i, j])
    invert(matrix, inverse, work, pivots)


@jit
def _newton(h, time, ground, mass, damping, stiffness, mass_influence, inverses, depth, method,
            bearing, ptv, dofs, committed, trial, heating):
    """NewmarkStepper._solve: one Newton attempt on a (sub-)step of ``h`` [s] to ``time``.

    ``dofs`` rows (U_C ... DU): the committed u, v, a, p, q; the trial u, v, a, p, q; work
    (load, residual, correction). ``inverses[depth]`` is ``A^-1`` for this step size. On
    success the committed rows move to the new state (the bearing is committed by the caller).

    Returns
    -------
    converged, iterations, residual norm [N], force reference [N], status
    """
    gamma, beta, alpha = method[GAMMA], method[BETA], method[ALPHA]
    tolerance = method[TOLERANCE]
    weight = 1.0 + alpha
    c0, c1 = 1.0 / (beta * h * h), gamma / (beta * h)
    n_bearings = bearing[N_BEARINGS]
    n = mass.shape[0]
    half_h2 = 0.5 * h * h
    p_squared = previous_p = previous_q = u_norm = 0.0
    for i in range(n):
        dofs[P, i] = -mass_influence[i] * ground
        dofs[LOAD, i] = weight * dofs[P, i] - alpha * dofs[P_C, i] + alpha * dofs[Q_C, i]
        dofs[A, i] = dofs[A_C, i]
        dofs[U, i] = dofs[U_C, i] + h * dofs[V_C, i] + half_h2 * dofs[A, i]
        dofs[V, i] = dofs[V_C, i] + h * dofs[A, i]
        p_squared += dofs[P, i] * dofs[P, i]
        previous_p += dofs[P_C, i] * dofs[P_C, i]
        previous_q += dofs[Q_C, i] * dofs[Q_C, i]
        u_norm += dofs[U_C, i] * dofs[U_C, i]
    previous = max(math.sqrt(previous_p), math.sqrt(previous_q))
    u_norm = math.sqrt(u_norm)
    p_norm = math.sqrt(p_squared)
    r_norm = reference = np.inf
    g00 = inverses[depth, 0, 0]
    max_iterations = int(method[MAX_ITERATIONS])
    for iteration in range(1, max_iterations + 1):
        force, k_bearing, c_bearing, status = bearing_trial(
            dofs[U, 0], dofs[V, 0], time, bearing, ptv, committed, trial, heating)
        if status != SUCCESS:
            return False, iteration, r_norm, reference, status
        inertia_squared = q_squared = r_squared = 0.0
        for i in range(n):  # q = C v + f(u), f = K u + isolators on DOF 0; the residual
            spring = 0.0
            viscous = 0.0
            inertia = 0.0
            for j in range(n):
                spring += stiffness[i, j] * dofs[U, j]
                viscous += damping[i, j] * dofs[V, j]
                inertia += mass[i, j] * dofs[A, j]
            if i == 0:
                spring += n_bearings * force
            q = viscous + spring
            dofs[Q, i] = q
            residual = dofs[LOAD, i] - inertia - weight * q
            dofs[RESIDUAL, i] = residual
            inertia_squared += inertia * inertia
            q_squared += q * q
            r_squared += residual * residual
        r_norm = math.sqrt(r_squared)
        reference = max(previous, math.sqrt(inertia_squared), math.sqrt(q_squared), p_norm)
        # Sherman-Morrison: (A + d e0 e0^T)^-1 r = y - d y0 / (1 + d g00) A^-1 e0, y = A^-1 r
        d = weight * (c1 * n_bearings * c_bearing + n_bearings * k_bearing)
        denominator = 1.0 + d * g00
        if denominator == 0.0 or not math.isfinite(denominator):
            return False, iteration, r_norm, reference, SUCCESS
        y0 = 0.0
        for j in range(n):
            y0 += inverses[depth, 0, j] * dofs[RESIDUAL, j]
        factor = d * y0 / denominator
        du_squared = u_squared = 0.0
        finite = True
        for i in range(n):
            if i == 0:
                du = y0 / denominator
            else:
                total = 0.0
                for j in range(n):
                    total += inverses[depth, i, j] * dofs[RESIDUAL, j]
                du = total - factor * inverses[depth, i, 0]
            dofs[DU, i] = du
            finite = finite and math.isfinite(du)
            du_squared += du * du
            u_squared += dofs[U, i] * dofs[U, i]
        if not finite:
            return False, iteration, r_norm, reference, SUCCESS
        if r_norm <= tolerance * reference and math.sqrt(du_squared) <= tolerance * max(
                math.sqrt(u_squared), u_norm):
            for i in range(n):
                dofs[U_C, i], dofs[V_C, i], dofs[A_C, i] = dofs[U, i], dofs[V, i], dofs[A, i]
                dofs[P_C, i], dofs[Q_C, i] = dofs[P, i], dofs[Q, i]
            return True, iteration, r_norm, reference, SUCCESS
        for i in range(n):
            dofs[U, i] += dofs[DU, i]
            dofs[V, i] += c1 * dofs[DU, i]
            dofs[A, i] += c0 * dofs[DU, i]
    return False, max_iterations, r_norm, reference, SUCCESS


@jit
def integrate_building(model, motion, settings, state, outputs, steps):
    """Integrate the isolated building through a ground motion, from rest; fill the outputs.

    ``steps`` = (first, end) takes the steps ``first .. end - 1``: (1, nt) is the whole run.
    A call with ``first > 1`` resumes where the call that ended at ``first - 1`` stopped,
    from the state it left in ``state`` (the same arithmetic as one call: the committed time
    and ground acceleration are then ``time[first - 1]`` and ``ground[first - 1]``, exactly
    what the step to ``first - 1`` committed).

    Parameters
    ----------
    model : Model
        mass, damping, stiffness (n, n) and influence (n,).
    motion : Motion
        ground acceleration and time (nt,).
    settings : Settings
        method, bearing and ptv: the integration method and the bearing's constants.
    state : State
        heating and workspace, zero at the start; changed in place.
    outputs : Outputs
        displacement, velocity, acceleration, record, restoring, iterations, subdivisions
        and info: filled for the steps taken.
    steps : ndarray of int64, shape (2,)
        The steps to take, ``[first, end)`` (see above).

    The groups are named tuples (:class:`Model` ... :class:`Outputs`, whose fields say the
    shapes and units), which numba types as tuples; the first lines take their arrays out by
    name, once, and the helpers take arrays as before. (Compiling this function costs about
    1 % more than with the 20 arrays as parameters, ~0.03 s; taking them out by attribute was
    the cheapest of the ways tried: ``benchmarks/COLD_START.md``.)
    """
    mass, damping, stiffness = model.mass, model.damping, model.stiffness
    influence = model.influence
    ground, time = motion.ground, motion.time
    method, bearing, ptv = settings.method, settings.bearing, settings.ptv
    heating, workspace = state.heating, state.workspace
    displacement, velocity = outputs.displacement, outputs.velocity
    acceleration, record, restoring = outputs.acceleration, outputs.record, outputs.restoring
    iterations, subdivisions, info = outputs.iterations, outputs.subdivisions, outputs.info
    n = mass.shape[0]
    nt = ground.shape[0]
    max_subdivisions = int(method[MAX_SUBDIVISIONS])
    n_bearings = bearing[N_BEARINGS]
    committed, trial = workspace[COMMITTED], workspace[TRIAL]
    inverses, inverse_steps = workspace[INVERSES], workspace[INVERSE_STEPS]
    stack_start, stack_end = workspace[STACK_START], workspace[STACK_END]
    stack_depth, dofs, matrix = workspace[STACK_DEPTH], workspace[DOFS], workspace[MATRIX]
    work, pivots = workspace[LAPACK_WORK], workspace[PIVOTS]
    mass_influence = workspace[MASS_INFLUENCE]
    for i in range(n):  # M r
        total = 0.0
        for j in range(n):
            total += mass[i, j] * influence[j]
        mass_influence[i] = total
    first, end = steps[0], steps[1]
    if first <= 1:
        first = 1
        committed[TEMPERATURE] = bearing[INITIAL_TEMPERATURE]
        committed[MU] = bearing[INITIAL_MU]
        for i in range(STATE_SIZE):
            trial[i] = committed[i]

        # from rest: u = v = 0, so f = 0 and q = 0; the load row holds p - q for the solve
        for i in range(n):
            dofs[P_C, i] = -mass_influence[i] * ground[0]
            dofs[LOAD, i] = dofs[P_C, i] - dofs[Q_C, i]
        solve(mass, dofs[LOAD], dofs[A_C], work, pivots)
        for i in range(n):
            displacement[0, i], velocity[0, i] = dofs[U_C, i], dofs[V_C, i]
            acceleration[0, i], restoring[0, i] = dofs[A_C, i], 0.0
        record_state(record[:, 0], committed)
    end = min(end, nt)
    info[STATUS], info[LAST_STEP] = SUCCESS, end - 1

    t_committed = time[first - 1]
    ground_committed = ground[first - 1]
    for k in range(first, end):
        start, end = t_committed, time[k]
        span = end - start
        ground_start, ground_end = ground_committed, ground[k]
        step_iterations = 0
        step_subdivisions = 0
        top = 0
        stack_start[0], stack_end[0], stack_depth[0] = 0.0, 1.0, 0
        while top >= 0:
            s0, s1, depth = stack_start[top], stack_end[top], stack_depth[top]
            top -= 1
            if s1 == 1.0:
                t_end, ground_now = end, ground_end
            else:
                t_end = start + s1 * span
                ground_now = ground_start + s1 * (ground_end - ground_start)
            h = (s1 - s0) * span
            if abs(h - inverse_steps[depth]) > 1e-9 * h:
                _effective_inverse(h, mass, damping, stiffness, method[GAMMA], method[BETA],
                                   method[ALPHA], inverses[depth], matrix, work, pivots)
                inverse_steps[depth] = h
            converged, spent, r_norm, reference, status = _newton(
                h, t_end, ground_now, mass, damping, stiffness, mass_influence, inverses, depth,
                method, bearing, ptv, dofs, committed, trial, heating)
            step_iterations += spent
            if converged:
                bearing_commit(bearing, committed, trial, heating)
                t_committed, ground_committed = t_end, ground_now
                continue
            trial[PENDING] = 0.0  # revert: drop the trial and its heat
            if status != SUCCESS or depth >= max_subdivisions:
                info[STATUS], info[LAST_STEP] = NOT_CONVERGED, k - 1
                if status != SUCCESS:
                    info[STATUS] = status
                    info[FAIL_VALUE] = trial[
                        PENDING_DT] if status == STEP_BELOW_MIN_LAG else trial[BEARING_DISPLACEMENT]
                info[FAIL_TIME], info[FAIL_SUBSTEP], info[FAIL_DEPTH] = t_end, h, depth
                info[FAIL_ITERATIONS], info[FAIL_RESIDUAL] = spent, r_norm
                info[FAIL_REFERENCE] = reference
                iterations[k - 1], subdivisions[k - 1] = step_iterations, step_subdivisions
                return
            step_subdivisions += 1
            middle = 0.5 * (s0 + s1)
            top += 1
            stack_start[top], stack_end[top], stack_depth[top] = middle, s1, depth + 1
            top += 1
            stack_start[top], stack_end[top], stack_depth[top] = s0, middle, depth + 1
        iterations[k - 1], subdivisions[k - 1] = step_iterations, step_subdivisions
        for i in range(n):
            displacement[k, i] = dofs[U_C, i]
            velocity[k, i] = dofs[V_C, i]
            acceleration[k, i] = dofs[A_C, i]
            total = 0.0
            for j in range(n):
                total += stiffness[i, j] * dofs[U_C, j]
            restoring[k, i] = total
        restoring[k, 0] += n_bearings * committed[FORCE]
        record_state(record[:, k], committed)
