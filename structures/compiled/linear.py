"""The engine's small compiled pieces: one-point linear interpolation of a record, and the
Newton matrix: the bearings' blocks on the base slab (:func:`add_block`), the inverse without
them for a step size (:func:`effective_inverse`), the Woodbury solve with them (:func:`woodbury`;
Sherman-Morrison with one DOF on the base slab)."""

from __future__ import annotations

import math

from isolator.compiled.kernels import jit_inner, jit_unmanaged
from structures.compiled.lapack import invert

__all__ = ["add_block", "effective_inverse", "interpolate", "woodbury"]


@jit_unmanaged
def interpolate(x, xp, fp):
    """``numpy.interp(x, xp, fp)`` for one ``x`` (held at the ends), as numpy computes it."""
    size = xp.shape[0]
    if x < xp[0]:
        return fp[0]
    if x >= xp[size - 1]:
        return fp[size - 1]
    lo, hi = 0, size - 1  # xp[lo] <= x < xp[hi]
    while hi - lo > 1:
        middle = (lo + hi) // 2
        if xp[middle] <= x:
            lo = middle
        else:
            hi = middle
    if xp[lo] == x:
        return fp[lo]
    slope = (fp[lo + 1] - fp[lo]) / (xp[lo + 1] - xp[lo])
    return slope * (x - xp[lo]) + fp[lo]


@jit_unmanaged
def add_block(top, kxx, kxy, kyx, kyy, x, y):
    """top[:3, :3] += T^T k T with T = [[1, 0, -y], [0, 1, x]]: a bearing at (x, y) [m]
    with the 2x2 tangent k on the base slab's (u_x, u_y, theta)."""
    rx = -y * kxx + x * kyx  # row 2 of T^T k
    ry = -y * kxy + x * kyy
    top[0, 0] += kxx
    top[0, 1] += kxy
    top[0, 2] += kxx * -y + kxy * x
    top[1, 0] += kyx
    top[1, 1] += kyy
    top[1, 2] += kyx * -y + kyy * x
    top[2, 0] += rx
    top[2, 1] += ry
    top[2, 2] += rx * -y + ry * x


@jit_inner
def effective_inverse(h, mass, damping, stiffness, gamma, beta, alpha, inverse, matrix, work,
                      pivots):
    """inverse <- (c0 M + (1 + alpha)(c1 C + K))^-1 for a step ``h`` [s]: the Newton matrix
    without the bearings and the overturning; ``matrix``, ``work`` (n, n) and ``pivots``
    (int32, n) are work arrays."""
    c0, c1 = 1.0 / (beta * h * h), gamma / (beta * h)
    weight = 1.0 + alpha
    n = matrix.shape[0]
    for i in range(n):
        for j in range(n):
            matrix[i, j] = c0 * mass[i, j] + weight * (c1 * damping[i, j] + stiffness[i, j])
    invert(matrix, inverse, work, pivots)


@jit_inner
def woodbury(inverse, top_k, top_c, columns, weight, c1, residual, du, update):
    """du <- (A + E X)^-1 residual, A^-1 = ``inverse``, E the first ``columns`` (1 or 3) unit
    columns, X = (1 + alpha)(c1 top_c + top_k) the base slab's rows the bearings add, by
    y - A^-1 E (I + X A^-1 E)^-1 X y, y = A^-1 r. ``update`` is a (3, n) work array. False when
    I + X A^-1 E is singular (the reference's singular Newton matrix)."""
    n = inverse.shape[0]
    for j in range(n):
        update[0, j] = weight * (c1 * top_c[0, j] + top_k[0, j])
        if columns == 3:
            update[1, j] = weight * (c1 * top_c[1, j] + top_k[1, j])
            update[2, j] = weight * (c1 * top_c[2, j] + top_k[2, j])
    for i in range(n):
        total = 0.0
        for j in range(n):
            total += inverse[i, j] * residual[j]
        du[i] = total
    if columns == 1:
        s00 = r0 = 0.0
        for j in range(n):
            s00 += update[0, j] * inverse[j, 0]
            r0 += update[0, j] * du[j]
        s00 += 1.0
        if s00 == 0.0 or not math.isfinite(s00):
            return False
        z0 = r0 / s00
        for i in range(n):
            du[i] -= inverse[i, 0] * z0
        return True
    s00 = s01 = s02 = s10 = s11 = s12 = s20 = s21 = s22 = 0.0
    r0 = r1 = r2 = 0.0
    for j in range(n):
        x0, x1, x2 = update[0, j], update[1, j], update[2, j]
        g0, g1, g2 = inverse[j, 0], inverse[j, 1], inverse[j, 2]
        s00 += x0 * g0
        s01 += x0 * g1
        s02 += x0 * g2
        s10 += x1 * g0
        s11 += x1 * g1
        s12 += x1 * g2
        s20 += x2 * g0
        s21 += x2 * g1
        s22 += x2 * g2
        r0 += x0 * du[j]
        r1 += x1 * du[j]
        r2 += x2 * du[j]
    s00 += 1.0
    s11 += 1.0
    s22 += 1.0
    c00, c01, c02 = s11 * s22 - s12 * s21, s02 * s21 - s01 * s22, s01 * s12 - s02 * s11
    c10, c11, c12 = s12 * s20 - s10 * s22, s00 * s22 - s02 * s20, s02 * s10 - s00 * s12
    c20, c21, c22 = s10 * s21 - s11 * s20, s01 * s20 - s00 * s21, s00 * s11 - s01 * s10
    determinant = s00 * c00 + s01 * c10 + s02 * c20
    if determinant == 0.0 or not math.isfinite(determinant):
        return False
    z0 = (c00 * r0 + c01 * r1 + c02 * r2) / determinant
    z1 = (c10 * r0 + c11 * r1 + c12 * r2) / determinant
    z2 = (c20 * r0 + c21 * r1 + c22 * r2) / determinant
    for i in range(n):
        du[i] -= inverse[i, 0] * z0 + inverse[i, 1] * z1 + inverse[i, 2] * z2
    return True
