"""The two dense solves of the compiled engine, as direct LAPACK calls: :func:`invert` and
:func:`solve` call the routines behind numba's ``np.linalg.inv`` and ``np.linalg.solve``
(``dgetrf``, ``dgetri``; ``dgesv``), to the same bits, without numba's generic front end (its
checks cost compile time; the engine's matrices are small, square, C-ordered and finite). The
caller supplies the work arrays. Without numba: ``numpy.linalg``, equal to round-off only."""

from __future__ import annotations

import numpy as np

from isolator.compiled import kernels
from isolator.compiled.kernels import jit_unmanaged

__all__ = ["invert", "solve"]

_LAPACK_CALLS = False
if kernels.COMPILED:  # pragma: no cover - depends on the environment
    try:
        from numba import types
        from numba.np.linalg import _LAPACK

        _lapack = _LAPACK()  # checks that scipy's LAPACK is there
        _getrf = _lapack.numba_xxgetrf(types.float64)
        _getri = _lapack.numba_ez_xxgetri(types.float64)
        _gesv = _lapack.numba_xgesv(types.float64)
        _LAPACK_CALLS = True
    except (ImportError, AttributeError):  # a numba without these entry points
        pass

_DOUBLE = ord("d")  # LAPACK's kind code of float64

if _LAPACK_CALLS:  # pragma: no cover - depends on the environment

    @jit_unmanaged
    def invert(matrix, inverse, work, pivots):
        """``inverse <- matrix^-1``, both (n, n), by LU factorisation (LAPACK ``dgetrf``,
        ``dgetri``); ``matrix`` is not changed, ``work`` (n, n) and ``pivots`` (int32, (n,)) are
        work arrays. Returns LAPACK's ``info``: 0 on success, > 0 for a singular matrix."""
        n = matrix.shape[0]
        for i in range(n):
            for j in range(n):
                work[j, i] = matrix[i, j]  # work is the Fortran-ordered copy
        status = _getrf(_DOUBLE, n, n, work.ctypes, n, pivots.ctypes)
        if status == 0:
            status = _getri(_DOUBLE, n, work.ctypes, n, pivots.ctypes)
        for i in range(n):
            for j in range(n):
                inverse[i, j] = work[j, i]
        return status

    @jit_unmanaged
    def solve(matrix, rhs, solution, work, pivots):
        """``solution <- matrix^-1 rhs``, both (n,), by LU factorisation (LAPACK ``dgesv``);
        ``matrix`` and ``rhs`` are not changed, ``work`` and ``pivots`` as for :func:`invert`.
        Returns LAPACK's ``info``."""
        n = matrix.shape[0]
        for i in range(n):
            solution[i] = rhs[i]
            for j in range(n):
                work[j, i] = matrix[i, j]
        return _gesv(_DOUBLE, n, 1, work.ctypes, n, pivots.ctypes, solution.ctypes, n)

else:

    @jit_unmanaged
    def invert(matrix, inverse, work, pivots):
        """``inverse <- matrix^-1`` (``numpy.linalg.inv``); the work arrays are unused."""
        inverse[:, :] = np.linalg.inv(matrix)
        return 0

    @jit_unmanaged
    def solve(matrix, rhs, solution, work, pivots):
        """``solution <- matrix^-1 rhs`` (``numpy.linalg.solve``); the work arrays are unused."""
        solution[:] = np.linalg.solve(matrix, rhs)
        return 0
