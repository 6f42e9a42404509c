"""The two dense solves of the compiled engine, as direct LAPACK calls.

:func:`invert` and :func:`solve` are what ``np.linalg.inv`` and ``np.linalg.solve`` do inside
numba (``dgetrf`` then ``dgetri``; ``dgesv``), through the same LAPACK entry points numba's own
implementations call, so the results are the same bits. What they leave out is numba's
generic front end (layout dispatch, finiteness checks, error strings), which cost about 5 s of
the engine's one-off compilation and gave nothing the engine needs: its matrices are square,
C-ordered, finite and small. The caller supplies the work arrays, so nothing is allocated.

Without numba (or with ``DCFPB_DISABLE_NUMBA=1``) both fall back to ``numpy.linalg``, as the
engine did before; that path agrees to round-off, not bit for bit (numpy's inverse is a
``dgesv`` against the identity).
"""

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
        """``inverse <- matrix^-1`` by LU factorisation (LAPACK ``dgetrf``, ``dgetri``).

        Parameters
        ----------
        matrix : ndarray, shape (n, n)
            A non-singular matrix (not changed).
        inverse : ndarray, shape (n, n)
            Output.
        work : ndarray, shape (n, n)
            Work array (holds the matrix in Fortran order).
        pivots : ndarray of int32, shape (n,)
            Work array for the row interchanges.

        Returns
        -------
        int
            LAPACK's ``info``: 0 on success, > 0 for an exactly singular matrix.
        """
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
        """``solution <- matrix^-1 rhs`` by LU factorisation (LAPACK ``dgesv``).

        Parameters
        ----------
        matrix : ndarray, shape (n, n)
            A non-singular matrix (not changed).
        rhs : ndarray, shape (n,)
            Right-hand side (not changed).
        solution : ndarray, shape (n,)
            Output.
        work, pivots : ndarray, shape (n, n) and int32 (n,)
            Work arrays, as for :func:`invert`.

        Returns
        -------
        int
            LAPACK's ``info``.
        """
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
