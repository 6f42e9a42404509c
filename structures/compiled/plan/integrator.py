"""The compiled engine of the building in plan: a whole run of ``run_spatial`` in one numba
function.

:func:`integrate_plan` is the time loop of :func:`structures.spatial.analysis.run_spatial`:
the Newmark / HHT-alpha Newton step of :mod:`structures.integrators` with a ground acceleration
of two components, the model of :class:`~structures.spatial.isolated.SpatialIsolatedBuilding`
(storey springs and dampers, every bearing at its plan position with its axial load per trial
from the gravity share, the vertical record and the overturning of the storey forces, and
their consistent tangent) and the bidirectional elements of
:mod:`isolator.compiled.bidirectional.bearing`. It
mirrors the reference operation for operation, so the two agree to round-off: the same
predictor, residual, force reference and convergence tests, the same depth-first halving with
the ground accelerations interpolated linearly and the bearings committed after each sub-step,
the same trial / commit semantics of every bearing and its heat.

One thing is done differently, an exact rearrangement: the Newton matrix is the reference's
``c0 M + (1 + alpha)(c1 (C + C_t) + K_t)``, and the bearings and the overturning change only
the base slab's three rows of it, so it is ``A + E X`` with ``A = c0 M + (1 + alpha)(c1 C + K)``
constant for a step size (its inverse formed once per step size and halving depth by LAPACK,
:mod:`structures.compiled.lapack`) and ``E`` the first three unit columns: each iteration
solves with the Woodbury formula, a 3 x 3 system and O(n^2), instead of factorising the
matrix.

It is a numba function of its own, apart from the planar engine
(:mod:`structures.compiled.integrator`), so that compiling one never compiles the other; the
kernels they share (friction, step factors, LAPACK) are compiled once and cached. Without
numba, or with ``DCFPB_DISABLE_NUMBA=1``, the same source runs as plain Python;
``integrate_plan.py_func`` is the Python original. The adapter is
:mod:`structures.compiled.plan.engine`.
"""

from __future__ import annotations

import math

import numpy as np

from dcfpb.common.units import STANDARD_GRAVITY
from isolator.compiled.bidirectional import bearing as E
from isolator.compiled.bidirectional.bearing import inlined
from isolator.compiled.kernels import jit
from structures.compiled.lapack import solve
from structures.compiled.plan import workspace as W
from structures.compiled.plan.linear import (
    add_block,
    effective_inverse,
    interpolate,
    norm,
    woodbury,
)
from structures.compiled.plan.unmanaged import unmanaged
from structures.compiled.workspace import (
    ALPHA,
    BETA,
    FAIL_DEPTH,
    FAIL_ITERATIONS,
    FAIL_REFERENCE,
    FAIL_RESIDUAL,
    FAIL_SUBSTEP,
    FAIL_TIME,
    FAIL_VALUE,
    GAMMA,
    LAST_STEP,
    MAX_ITERATIONS,
    MAX_SUBDIVISIONS,
    STATUS,
    TOLERANCE,
)

__all__ = ["integrate_plan"]


@inlined
def _restoring(time, model, settings, ws, heat):
    """SpatialIsolatedBuilding.restoring_force at the trial rows U, V of ``dofs``: the force
    row FORCE, C v (VISCOUS), the storey forces STOREY, and what the bearings and the
    overturning add to the tangent's rows of the base slab (TOP_STIFFNESS, TOP_DAMPING);
    returns (status, failing bearing)."""
    stiffness, damping = model.stiffness, model.damping
    bearings, ptv, flags = settings.bearings, settings.ptv, settings.flags
    dofs, loads = ws[W.DOFS], ws[W.LOADS]
    top_k, top_c = ws[W.TOP_STIFFNESS], ws[W.TOP_DAMPING]
    committed, trial = ws[W.COMMITTED], ws[W.TRIAL]
    n = stiffness.shape[0]
    overturning = flags[W.OVERTURNING] != 0.0
    for i in range(n):
        spring = 0.0
        viscous = 0.0
        for j in range(n):
            spring += stiffness[i, j] * dofs[W.U, j]
            viscous += damping[i, j] * dofs[W.V, j]
        dofs[W.FORCE, i] = spring
        dofs[W.VISCOUS, i] = viscous
        dofs[W.STOREY, i] = spring + viscous
    for r in range(3):
        for j in range(n):
            top_k[r, j] = 0.0
            top_c[r, j] = 0.0
    vertical = 0.0
    if flags[W.VERTICAL] != 0.0:
        vertical = interpolate(time, model.vertical_time, model.vertical_acceleration)
    factor = 1.0 + vertical / STANDARD_GRAVITY
    for b in range(loads.shape[0]):
        load = bearings[b, E.GRAVITY] * factor
        if overturning:
            extra = 0.0
            for j in range(n):
                extra += model.overturning[b, j] * dofs[W.STOREY, j]
            load = load + extra
        loads[b] = load
    ux, uy, theta = dofs[W.U, 0], dofs[W.U, 1], dofs[W.U, 2]
    vx, vy, omega = dofs[W.V, 0], dofs[W.V, 1], dofs[W.V, 2]
    for b in range(loads.shape[0]):
        x, y = bearings[b, E.X], bearings[b, E.Y]
        status = E.plate_trial(b, ux - y * theta, uy + x * theta, vx - y * omega,
                               vy + x * omega, time, loads[b], bearings, ptv, committed, trial,
                               heat)
        if status != E.SUCCESS:
            return status, b
        t = trial[b]
        fx, fy = t[E.FX], t[E.FY]
        dofs[W.FORCE, 0] += fx
        dofs[W.FORCE, 1] += fy
        dofs[W.FORCE, 2] += -y * fx + x * fy
        add_block(top_k, t[E.KXX], t[E.KXY], t[E.KYX], t[E.KYY], x, y)
        add_block(top_c, t[E.CXX], t[E.CXY], t[E.CYX], t[E.CYY], x, y)
        if overturning and loads[b] > 0.0:  # d(T^T F) / dN times dN / du, dN / dv
            px, py = fx / loads[b], fy / loads[b]
            per_load_2 = -y * px + x * py
            for j in range(n):
                du, dv = model.load_du[b, j], model.load_dv[b, j]
                top_k[0, j] += px * du
                top_k[1, j] += py * du
                top_k[2, j] += per_load_2 * du
                top_c[0, j] += px * dv
                top_c[1, j] += py * dv
                top_c[2, j] += per_load_2 * dv
    return E.SUCCESS, -1


@inlined
def _newton(h, time, ground_x, ground_y, depth, model, settings, ws, heat, info):
    """NewmarkStepper._solve on a (sub-)step of ``h`` [s] to ``time``; on success the
    committed rows move to the new state (the bearings are committed by the caller).

    Returns converged, iterations, residual norm [N], force reference [N], status.
    """
    method = settings.method
    mass = model.mass
    dofs, inverse = ws[W.DOFS], ws[W.INVERSES][depth]
    top_k, top_c, mass_influence = ws[W.TOP_STIFFNESS], ws[W.TOP_DAMPING], ws[W.MASS_INFLUENCE]
    gamma, beta, alpha = method[GAMMA], method[BETA], method[ALPHA]
    tolerance = method[TOLERANCE]
    weight = 1.0 + alpha
    c0, c1 = 1.0 / (beta * h * h), gamma / (beta * h)
    n = mass.shape[0]
    half_h2 = 0.5 * h * h
    for i in range(n):
        dofs[W.P, i] = -(mass_influence[i, 0] * ground_x + mass_influence[i, 1] * ground_y)
        dofs[W.LOAD, i] = weight * dofs[W.P, i] - alpha * dofs[W.P_C, i] + alpha * dofs[W.Q_C, i]
        dofs[W.A, i] = dofs[W.A_C, i]
        dofs[W.U, i] = dofs[W.U_C, i] + h * dofs[W.V_C, i] + half_h2 * dofs[W.A, i]
        dofs[W.V, i] = dofs[W.V_C, i] + h * dofs[W.A, i]
    previous = max(norm(dofs[W.P_C]), norm(dofs[W.Q_C]))
    u_norm = norm(dofs[W.U_C])
    p_norm = norm(dofs[W.P])
    r_norm = reference = np.inf
    max_iterations = int(method[MAX_ITERATIONS])
    for iteration in range(1, max_iterations + 1):
        status, bearing = _restoring(time, model, settings, ws, heat)
        if status != E.SUCCESS:
            info[W.FAIL_BEARING] = bearing
            return False, iteration, r_norm, reference, status
        inertia_squared = q_squared = r_squared = 0.0
        for i in range(n):
            inertia = 0.0
            for j in range(n):
                inertia += mass[i, j] * dofs[W.A, j]
            q = dofs[W.VISCOUS, i] + dofs[W.FORCE, i]
            dofs[W.Q, i] = q
            residual = dofs[W.LOAD, i] - inertia - weight * q
            dofs[W.RESIDUAL, i] = residual
            inertia_squared += inertia * inertia
            q_squared += q * q
            r_squared += residual * residual
        r_norm = math.sqrt(r_squared)
        reference = max(previous, math.sqrt(inertia_squared), math.sqrt(q_squared), p_norm)
        if not woodbury(inverse, top_k, top_c, weight, c1, dofs[W.RESIDUAL], dofs[W.DU],
                         ws[W.UPDATE]):
            return False, iteration, r_norm, reference, E.SUCCESS
        du_squared = u_squared = 0.0
        finite = True
        for i in range(n):
            du = dofs[W.DU, i]
            finite = finite and math.isfinite(du)
            du_squared += du * du
            u_squared += dofs[W.U, i] * dofs[W.U, i]
        if not finite:
            return False, iteration, r_norm, reference, E.SUCCESS
        if r_norm <= tolerance * reference and math.sqrt(du_squared) <= tolerance * max(
                math.sqrt(u_squared), u_norm):
            for i in range(n):
                dofs[W.U_C, i], dofs[W.V_C, i], dofs[W.A_C, i] = dofs[W.U, i], dofs[W.V, i], \
                    dofs[W.A, i]
                dofs[W.P_C, i], dofs[W.Q_C, i] = dofs[W.P, i], dofs[W.Q, i]
            return True, iteration, r_norm, reference, E.SUCCESS
        for i in range(n):
            dofs[W.U, i] += dofs[W.DU, i]
            dofs[W.V, i] += c1 * dofs[W.DU, i]
            dofs[W.A, i] += c0 * dofs[W.DU, i]
    return False, max_iterations, r_norm, reference, E.SUCCESS


@inlined
def _record(k, model, settings, ws, outputs):
    """Step ``k`` of the outputs: the committed rows and every bearing's committed state."""
    dofs, committed = ws[W.DOFS], ws[W.COMMITTED]
    stiffness, bearings = model.stiffness, settings.bearings
    n = stiffness.shape[0]
    for i in range(n):
        outputs.displacement[k, i] = dofs[W.U_C, i]
        outputs.velocity[k, i] = dofs[W.V_C, i]
        outputs.acceleration[k, i] = dofs[W.A_C, i]
        total = 0.0
        for j in range(n):
            total += stiffness[i, j] * dofs[W.U_C, j]
        outputs.restoring[k, i] = total
    sx = sy = sz = 0.0
    for b in range(committed.shape[0]):
        fx, fy = committed[b, E.FX], committed[b, E.FY]
        sx += fx
        sy += fy
        sz += -bearings[b, E.Y] * fx + bearings[b, E.X] * fy
        for c in range(committed.shape[1]):
            outputs.record[k, b, c] = committed[b, c]
    outputs.restoring[k, 0] += sx
    outputs.restoring[k, 1] += sy
    outputs.restoring[k, 2] += sz


@jit
def integrate_plan(model, motion, settings, state, outputs, steps):
    """Integrate the building in plan through the pair, from rest; fill the outputs.

    ``steps`` = (first, end) takes the steps ``first .. end - 1``; (1, nt) is the whole run,
    and a call with ``first > 1`` resumes from the state the previous call left (as the
    planar :func:`~structures.compiled.integrator.integrate_building`). The groups are the
    NamedTuples of :mod:`structures.compiled.plan.workspace`; the committed bearing states
    must hold the elements at rest before the first call.
    """
    # the groups without numba's reference counts (half the engine's time otherwise)
    model, motion, settings = unmanaged(model), unmanaged(motion), unmanaged(settings)
    heat, ws, outputs = unmanaged(state.heat), unmanaged(state.workspace), unmanaged(outputs)
    method, info = settings.method, outputs.info
    ground, time = motion.ground, motion.time
    dofs, committed, trial = ws[W.DOFS], ws[W.COMMITTED], ws[W.TRIAL]
    inverse_steps = ws[W.INVERSE_STEPS]
    stack_start, stack_end, stack_depth = ws[W.STACK_START], ws[W.STACK_END], ws[W.STACK_DEPTH]
    mass, influence, mass_influence = model.mass, model.influence, ws[W.MASS_INFLUENCE]
    n, n_bearings, nt = mass.shape[0], committed.shape[0], ground.shape[0]
    max_subdivisions = int(method[MAX_SUBDIVISIONS])
    for i in range(n):  # M r
        for c in range(2):
            total = 0.0
            for j in range(n):
                total += mass[i, j] * influence[j, c]
            mass_influence[i, c] = total
    first, end = steps[0], steps[1]
    if first <= 1:
        first = 1
        for i in range(n):  # from rest: f = 0, q = 0
            dofs[W.P_C, i] = -(mass_influence[i, 0] * ground[0, 0]
                               + mass_influence[i, 1] * ground[0, 1])
            dofs[W.LOAD, i] = dofs[W.P_C, i] - dofs[W.Q_C, i]
        solve(mass, dofs[W.LOAD], dofs[W.A_C], ws[W.LAPACK_WORK], ws[W.PIVOTS])
        _record(0, model, settings, ws, outputs)
    end = min(end, nt)
    info[STATUS], info[LAST_STEP] = E.SUCCESS, end - 1
    t_committed = time[first - 1]
    gx_committed, gy_committed = ground[first - 1, 0], ground[first - 1, 1]
    for k in range(first, end):
        start, stop = t_committed, time[k]
        span = stop - start
        gx0, gy0, gx1, gy1 = gx_committed, gy_committed, ground[k, 0], ground[k, 1]
        step_iterations = step_subdivisions = 0
        top = 0
        stack_start[0], stack_end[0], stack_depth[0] = 0.0, 1.0, 0
        while top >= 0:
            s0, s1, depth = stack_start[top], stack_end[top], stack_depth[top]
            top -= 1
            if s1 == 1.0:
                t_end, gx, gy = stop, gx1, gy1
            else:
                t_end = start + s1 * span
                gx, gy = gx0 + s1 * (gx1 - gx0), gy0 + s1 * (gy1 - gy0)
            h = (s1 - s0) * span
            if abs(h - inverse_steps[depth]) > 1e-9 * h:
                effective_inverse(h, model, method, ws[W.INVERSES][depth], ws)
                inverse_steps[depth] = h
            converged, spent, r_norm, reference, status = _newton(
                h, t_end, gx, gy, depth, model, settings, ws, heat, info)
            step_iterations += spent
            if converged:
                for b in range(n_bearings):
                    E.plate_commit(b, settings.bearings, settings.ptv, committed, trial, heat)
                t_committed, gx_committed, gy_committed = t_end, gx, gy
                continue
            for b in range(n_bearings):  # revert: drop the trials and their heat
                trial[b, E.PENDING] = 0.0
            if status != E.SUCCESS or depth >= max_subdivisions:
                info[STATUS], info[LAST_STEP] = E.NOT_CONVERGED, k - 1
                if status != E.SUCCESS:
                    b = int(info[W.FAIL_BEARING])
                    info[STATUS] = status
                    info[FAIL_VALUE] = trial[b, E.PENDING_DT]
                    info[W.FAIL_UX], info[W.FAIL_UY] = trial[b, E.UX], trial[b, E.UY]
                    info[W.FAIL_E1X], info[W.FAIL_E1Y] = trial[b, E.AXIS_X], trial[b, E.AXIS_Y]
                info[FAIL_TIME], info[FAIL_SUBSTEP], info[FAIL_DEPTH] = t_end, h, depth
                info[FAIL_ITERATIONS], info[FAIL_RESIDUAL] = spent, r_norm
                info[FAIL_REFERENCE] = reference
                outputs.iterations[k - 1] = step_iterations
                outputs.subdivisions[k - 1] = step_subdivisions
                return
            step_subdivisions += 1
            middle = 0.5 * (s0 + s1)
            top += 1
            stack_start[top], stack_end[top], stack_depth[top] = middle, s1, depth + 1
            top += 1
            stack_start[top], stack_end[top], stack_depth[top] = s0, middle, depth + 1
        outputs.iterations[k - 1], outputs.subdivisions[k - 1] = step_iterations, \
            step_subdivisions
        _record(k, model, settings, ws, outputs)
