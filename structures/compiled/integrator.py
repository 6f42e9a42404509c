"""The compiled engine: a whole time-history run of an isolated building in one numba function.

:func:`integrate` is the time loop of :func:`structures.integrators.integrate` for an
:class:`~structures.isolated_building.IsolatedShearBuilding` (1 DOF per level, x, or 3: x, y,
theta): Newmark / HHT-alpha Newton steps under ``c`` horizontal ground components, with the
storey springs and dampers and the bearings of :mod:`isolator.compiled.element` at their plan
positions (force and tangent times their multiplicity; axial load per trial: gravity times
1 + a_z / g plus the overturning of the storey forces, with its consistent tangent).

It mirrors the reference operation for operation (predictor, residual, force reference,
convergence tests, depth-first halving, trial / commit / revert of every bearing and its heat),
so the two agree to round-off, with one exact rearrangement: the bearings and the overturning
change only the base slab's rows (1 or 3) of the Newton matrix, ``A + E X`` with
``A = c0 M + (1 + alpha)(c1 C + K)`` inverted once per step size and halving depth (LAPACK), so
each iteration solves by the Woodbury formula, O(n^2). The loop allocates nothing, so it is
compiled without reference counting (:func:`isolator.compiled.kernels.jit_unmanaged`);
``integrate.py_func`` is its Python original.
"""

from __future__ import annotations

import math

import numpy as np

from dcfpb.common.units import STANDARD_GRAVITY
from isolator.compiled import element as E
from isolator.compiled.kernels import jit_inner, jit_unmanaged
from isolator.compiled.linking import separately
from structures.compiled import workspace as W
from structures.compiled.lapack import solve
from structures.compiled.linear import add_block, effective_inverse, interpolate, woodbury

__all__ = ["COMMIT_TRIALS", "EFFECTIVE_INVERSE", "INTEGRATE", "SET_TRIALS", "SOLVE", "WOODBURY",
           "integrate", "report_failure", "run", "start"]

# The bearings' trials and commit and the Newton matrix's solves, called as code of their own
# (isolator.compiled.linking): the loop compiles without them (at the same time, in another
# process), and a process binds them before it compiles or loads the loop.
WOODBURY = separately(woodbury, lambda types: types.boolean)
EFFECTIVE_INVERSE = separately(effective_inverse, lambda types: types.none)
SOLVE = separately(solve, lambda types: types.int32)
SET_TRIALS = separately(E.set_trials, lambda types: types.UniTuple(types.int64, 2))
COMMIT_TRIALS = separately(E.commit_trials, lambda types: types.none)


@jit_inner
def start(first, end, mass, influence, ground, mass_influence, p_committed, q_committed,
          load_row, a_committed, work, pivots):
    """The loop's start: M r into ``mass_influence``; from rest (``first <= 1``) the committed
    load and acceleration of the first sample. Returns the first step to take."""
    n, components = mass.shape[0], ground.shape[1]
    for i in range(n):  # M r
        for c in range(components):
            total = 0.0
            for j in range(n):
                total += mass[i, j] * influence[j, c]
            mass_influence[i, c] = total
    if first <= 1:
        first = 1
        for i in range(n):  # from rest: f = 0, q = 0; the load row holds p - q for the solve
            total = 0.0
            for c in range(components):
                total += mass_influence[i, c] * ground[0, c]
            p_committed[i] = -total
            load_row[i] = p_committed[i] - q_committed[i]
        SOLVE(mass, load_row, a_committed, work, pivots)
    return first


@jit_inner
def report_failure(info, trial, status, k, t_end, h, depth, spent, r_norm, reference):
    """Write a failed (sub-)step into ``info``: the trial's failure (``status`` not SUCCESS)
    or Newton's, at step ``k``."""
    info[W.STATUS], info[W.LAST_STEP] = E.NOT_CONVERGED, k - 1
    if status != E.SUCCESS:
        b = int(info[W.FAIL_BEARING])
        info[W.STATUS] = status
        info[W.FAIL_VALUE] = trial[b, E.PENDING_DT]
        info[W.FAIL_UX], info[W.FAIL_UY] = trial[b, E.UX], trial[b, E.UY]
        info[W.FAIL_E1X], info[W.FAIL_E1Y] = trial[b, E.AXIS_X], trial[b, E.AXIS_Y]
    info[W.FAIL_TIME], info[W.FAIL_SUBSTEP], info[W.FAIL_DEPTH] = t_end, h, depth
    info[W.FAIL_ITERATIONS], info[W.FAIL_RESIDUAL] = spent, r_norm
    info[W.FAIL_REFERENCE] = reference


START = separately(start, lambda types: types.int64)
REPORT_FAILURE = separately(report_failure, lambda types: types.none)


@jit_inner
def integrate(model, motion, settings, state, outputs, steps):
    """Integrate the isolated building through the record, from rest; fill the outputs.

    The groups are the NamedTuples of :mod:`structures.compiled.workspace`; the committed
    bearing states must hold the elements at rest before the first call. ``steps`` (int64,
    (2,)) = (first, end) takes the steps ``first .. end - 1``: (1, nt) is the whole run; a call
    with ``first > 1`` resumes from ``state`` where the call ending at ``first - 1`` stopped,
    with the same arithmetic as one call. Each (sub-)step is ``NewmarkStepper._solve``.
    """
    heat, ws = state.heat, state.workspace  # every array out of its group, once
    method, parameters, ptv, flags = settings.method, settings.parameters, settings.ptv, \
        settings.flags
    info, iterations, subdivisions = outputs.info, outputs.iterations, outputs.subdivisions
    displacement, velocity, acceleration = outputs.displacement, outputs.velocity, \
        outputs.acceleration
    record, restoring = outputs.record, outputs.restoring
    ground, time = motion.ground, motion.time
    mass, damping, stiffness = model.mass, model.damping, model.stiffness
    influence, vertical_time, vertical_acceleration = model.influence, model.vertical_time, \
        model.vertical_acceleration
    overturning_matrix, load_du, load_dv = model.overturning, model.load_du, model.load_dv
    rates, weights, states, stamps = heat.rates, heat.weights, heat.states, heat.stamps
    marks, pending, accumulators, offsets = heat.marks, heat.pending, heat.accumulators, \
        heat.offsets
    cache_keys, cache_values, cache_state = heat.cache_keys, heat.cache_values, heat.cache_state
    scalars, factors, decays, slots = heat.scalars, heat.factors, heat.decays, heat.slots
    table, windows = heat.table, heat.windows
    tangent, work, pivots = ws[W.TANGENT], ws[W.LAPACK_WORK], ws[W.PIVOTS]
    dofs = ws[W.DOFS]  # its rows, one by one
    u_committed, v_committed, a_committed = dofs[W.U_C], dofs[W.V_C], dofs[W.A_C]
    p_committed, q_committed = dofs[W.P_C], dofs[W.Q_C]
    u_trial, v_trial, a_trial, p_trial, q_trial = dofs[W.U], dofs[W.V], dofs[W.A], dofs[W.P], \
        dofs[W.Q]
    load_row, residual_row, du_row = dofs[W.LOAD], dofs[W.RESIDUAL], dofs[W.DU]
    force_row, viscous_row, storey_row = dofs[W.FORCE], dofs[W.VISCOUS], dofs[W.STOREY]
    committed, trial = ws[W.COMMITTED], ws[W.TRIAL]
    inverses, inverse_steps = ws[W.INVERSES], ws[W.INVERSE_STEPS]
    stack_start, stack_end, stack_depth = ws[W.STACK_START], ws[W.STACK_END], ws[W.STACK_DEPTH]
    top_k, top_c, mass_influence = ws[W.TOP_STIFFNESS], ws[W.TOP_DAMPING], ws[W.MASS_INFLUENCE]
    motion_rows, rows, update = ws[W.MOTION], ws[W.GROUND], ws[W.UPDATE]
    ground_committed, ground_start = rows[W.GROUND_COMMITTED], rows[W.GROUND_START]
    ground_end, ground_now = rows[W.GROUND_END], rows[W.GROUND_NOW]
    gamma, beta, alpha = method[W.GAMMA], method[W.BETA], method[W.ALPHA]
    tolerance = method[W.TOLERANCE]
    max_iterations = int(method[W.MAX_ITERATIONS])
    max_subdivisions = int(method[W.MAX_SUBDIVISIONS])
    columns = int(flags[W.LEVEL_DOFS])
    overturning = flags[W.OVERTURNING] != 0.0
    vertical = flags[W.VERTICAL] != 0.0
    weight = 1.0 + alpha
    n, n_bearings, nt = mass.shape[0], committed.shape[0], ground.shape[0]
    components = ground.shape[1]
    first, end = START(steps[0], steps[1], mass, influence, ground, mass_influence, p_committed,
                       q_committed, load_row, a_committed, work, pivots), steps[1]
    end = min(end, nt)
    info[W.STATUS], info[W.LAST_STEP] = E.SUCCESS, end - 1
    t_committed = time[first - 1]
    for c in range(components):
        ground_committed[c] = ground[first - 1, c]
    for k in range(first - 1, end):
        if k >= first:  # the step to time[k]; k = first - 1 only records the state at rest
            start, stop = t_committed, time[k]
            span = stop - start
            for c in range(components):
                ground_start[c] = ground_committed[c]
                ground_end[c] = ground[k, c]
            step_iterations = step_subdivisions = 0
            top = 0
            stack_start[0], stack_end[0], stack_depth[0] = 0.0, 1.0, 0
            while top >= 0:
                s0, s1, depth = stack_start[top], stack_end[top], stack_depth[top]
                top -= 1
                if s1 == 1.0:
                    t_end = stop
                    for c in range(components):
                        ground_now[c] = ground_end[c]
                else:
                    t_end = start + s1 * span
                    for c in range(components):
                        g0 = ground_start[c]
                        ground_now[c] = g0 + s1 * (ground_end[c] - g0)
                h = (s1 - s0) * span
                inverse = inverses[depth]
                if abs(h - inverse_steps[depth]) > 1e-9 * h:
                    EFFECTIVE_INVERSE(h, mass, damping, stiffness, gamma, beta, alpha, inverse,
                                      tangent, work, pivots)
                    inverse_steps[depth] = h
                # the predictor and the norms of the committed state
                c0, c1 = 1.0 / (beta * h * h), gamma / (beta * h)
                half_h2 = 0.5 * h * h
                p_squared = previous_p = previous_q = u_squared = 0.0
                for i in range(n):
                    total = 0.0
                    for c in range(components):
                        total += mass_influence[i, c] * ground_now[c]
                    p_trial[i] = -total
                    load_row[i] = (weight * p_trial[i] - alpha * p_committed[i]
                                       + alpha * q_committed[i])
                    a_trial[i] = a_committed[i]
                    u_trial[i] = u_committed[i] + h * v_committed[i] + half_h2 * a_trial[i]
                    v_trial[i] = v_committed[i] + h * a_trial[i]
                    p_squared += p_trial[i] * p_trial[i]
                    previous_p += p_committed[i] * p_committed[i]
                    previous_q += q_committed[i] * q_committed[i]
                    u_squared += u_committed[i] * u_committed[i]
                previous = max(math.sqrt(previous_p), math.sqrt(previous_q))
                u_norm, p_norm = math.sqrt(u_squared), math.sqrt(p_squared)
                factor = 1.0
                if vertical:
                    factor = 1.0 + interpolate(t_end, vertical_time,
                                               vertical_acceleration) / STANDARD_GRAVITY
                r_norm = reference = np.inf
                converged, status, spent = False, E.SUCCESS, max_iterations
                for iteration in range(1, max_iterations + 1):
                    # the restoring force: storey springs and dampers, then the bearings
                    for i in range(n):
                        spring = 0.0
                        viscous = 0.0
                        for j in range(n):
                            spring += stiffness[i, j] * u_trial[j]
                            viscous += damping[i, j] * v_trial[j]
                        force_row[i] = spring
                        viscous_row[i] = viscous
                        storey_row[i] = spring + viscous
                    for r in range(columns):
                        for j in range(n):
                            top_k[r, j] = 0.0
                            top_c[r, j] = 0.0
                    ux, vx = u_trial[0], v_trial[0]
                    uy = vy = theta = omega = 0.0  # one DOF per level: the bearings move on x
                    if columns == 3:
                        uy, theta, vy, omega = u_trial[1], u_trial[2], v_trial[1], \
                            v_trial[2]
                    for b in range(n_bearings):  # each row's trial motion and axial load
                        x, y = parameters[b, E.X], parameters[b, E.Y]
                        row = motion_rows[b]
                        # u_i = T_i q_b = (u_x - theta y_i, u_y + theta x_i)
                        row[E.MOTION_UX], row[E.MOTION_UY] = ux - y * theta, uy + x * theta
                        row[E.MOTION_VX], row[E.MOTION_VY] = vx - y * omega, vy + x * omega
                        load = parameters[b, E.GRAVITY] * factor
                        if overturning:
                            extra = 0.0
                            for j in range(n):
                                extra += overturning_matrix[b, j] * storey_row[j]
                            load = load + extra
                        row[E.MOTION_LOAD] = load
                    status, failed = SET_TRIALS(
                        t_end, motion_rows, parameters, ptv, committed, trial, rates, weights,
                        states, stamps, marks, pending, accumulators, offsets, cache_keys,
                        cache_values, cache_state, scalars, factors, decays, slots, table,
                        windows)
                    if status != E.SUCCESS:
                        info[W.FAIL_BEARING] = failed
                        spent = iteration
                        break
                    for b in range(n_bearings):
                        x, y, m = parameters[b, E.X], parameters[b, E.Y], \
                            parameters[b, E.MULTIPLICITY]
                        load = motion_rows[b, E.MOTION_LOAD]
                        t = trial[b]
                        fx, fy = m * t[E.FX], m * t[E.FY]
                        force_row[0] += fx
                        if columns == 1:
                            top_k[0, 0] += m * t[E.KXX]
                            top_c[0, 0] += m * t[E.CXX]
                            continue
                        force_row[1] += fy
                        force_row[2] += -y * fx + x * fy
                        add_block(top_k, m * t[E.KXX], m * t[E.KXY], m * t[E.KYX], m * t[E.KYY],
                                  x, y)
                        add_block(top_c, m * t[E.CXX], m * t[E.CXY], m * t[E.CYX], m * t[E.CYY],
                                  x, y)
                        if overturning and load > 0.0:  # d(T^T F) / dN times dN / du, dv
                            px, py = fx / load, fy / load
                            per_load_2 = -y * px + x * py
                            for j in range(n):
                                du, dv = load_du[b, j], load_dv[b, j]
                                top_k[0, j] += px * du
                                top_k[1, j] += py * du
                                top_k[2, j] += per_load_2 * du
                                top_c[0, j] += px * dv
                                top_c[1, j] += py * dv
                                top_c[2, j] += per_load_2 * dv
                    # the residual and its norms, then the correction
                    inertia_squared = q_squared = r_squared = 0.0
                    for i in range(n):
                        inertia = 0.0
                        for j in range(n):
                            inertia += mass[i, j] * a_trial[j]
                        q = viscous_row[i] + force_row[i]
                        q_trial[i] = q
                        residual = load_row[i] - inertia - weight * q
                        residual_row[i] = residual
                        inertia_squared += inertia * inertia
                        q_squared += q * q
                        r_squared += residual * residual
                    r_norm = math.sqrt(r_squared)
                    reference = max(previous, math.sqrt(inertia_squared),
                                    math.sqrt(q_squared), p_norm)
                    spent = iteration
                    if not WOODBURY(inverse, top_k, top_c, columns, weight, c1,
                                    residual_row, du_row, update):
                        break
                    du_squared = u_squared = 0.0
                    finite = True
                    for i in range(n):
                        du = du_row[i]
                        finite = finite and math.isfinite(du)
                        du_squared += du * du
                        u_squared += u_trial[i] * u_trial[i]
                    if not finite:
                        break
                    if r_norm <= tolerance * reference and math.sqrt(du_squared) <= \
                            tolerance * max(math.sqrt(u_squared), u_norm):
                        for i in range(n):
                            u_committed[i], v_committed[i] = u_trial[i], v_trial[i]
                            a_committed[i] = a_trial[i]
                            p_committed[i], q_committed[i] = p_trial[i], q_trial[i]
                        converged = True
                        break
                    for i in range(n):
                        u_trial[i] += du_row[i]
                        v_trial[i] += c1 * du_row[i]
                        a_trial[i] += c0 * du_row[i]
                step_iterations += spent
                if converged:
                    COMMIT_TRIALS(parameters, committed, trial, rates, weights, states, stamps,
                                    marks, pending, accumulators, offsets, cache_keys,
                                    cache_values, cache_state, scalars, factors, decays, slots,
                                    table, windows)
                    t_committed = t_end
                    for c in range(components):
                        ground_committed[c] = ground_now[c]
                    continue
                for b in range(n_bearings):  # revert: drop the trials and their heat
                    trial[b, E.PENDING] = 0.0
                if status != E.SUCCESS or depth >= max_subdivisions:
                    REPORT_FAILURE(info, trial, status, k, t_end, h, depth, spent, r_norm,
                                   reference)
                    iterations[k - 1] = step_iterations
                    subdivisions[k - 1] = step_subdivisions
                    return
                step_subdivisions += 1
                middle = 0.5 * (s0 + s1)
                top += 1
                stack_start[top], stack_end[top], stack_depth[top] = middle, s1, depth + 1
                top += 1
                stack_start[top], stack_end[top], stack_depth[top] = s0, middle, depth + 1
            iterations[k - 1] = step_iterations
            subdivisions[k - 1] = step_subdivisions
        # the step's record: the committed rows and every bearing's committed state
        for i in range(n):
            displacement[k, i] = u_committed[i]
            velocity[k, i] = v_committed[i]
            acceleration[k, i] = a_committed[i]
            total = 0.0
            for j in range(n):
                total += stiffness[i, j] * u_committed[j]
            restoring[k, i] = total
        sx = sy = sz = 0.0
        for b in range(n_bearings):
            m = parameters[b, E.MULTIPLICITY]
            fx, fy = m * committed[b, E.FX], m * committed[b, E.FY]
            sx += fx
            sy += fy
            sz += -parameters[b, E.Y] * fx + parameters[b, E.X] * fy
            for c in range(E.RECORD_SIZE):
                record[k, b, c] = committed[b, E.RECORD_COLUMNS[c]]
        restoring[k, 0] += sx
        if columns == 3:
            restoring[k, 1] += sy
            restoring[k, 2] += sz


INTEGRATE = separately(integrate, lambda types: types.none)


@jit_unmanaged
def run(model, motion, settings, state, outputs, steps):
    """:func:`integrate`, called from Python: the loop itself is compiled without the wrapper
    that unboxes its arguments from Python objects, which this function has (and compiles
    apart from the loop); a process binds the loop before it compiles or loads this."""
    INTEGRATE(model, motion, settings, state, outputs, steps)
