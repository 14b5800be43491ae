"""Dense symmetric linear algebra with a fixed order of floating-point operations.

The reduced thermal network (:mod:`.network`) needs a linear solve ``K x = b`` and the
eigen-decomposition of a symmetric matrix of order ~100.  NumPy's ``linalg.solve`` and
``linalg.eigh`` call BLAS/LAPACK, whose blocking, threading (the number of OpenBLAS/MKL
threads differs between the main process and, say, a Dask worker, which starts with one
thread) and SIMD paths change the order of the additions, so the same matrix gives results
that differ in the last bits (measured: 1.5e-15 relative on the steady rise per watt with 1
thread against 2).  The virtual runs promise bit-identical rows wherever they run, so these
routines use only element-wise NumPy operations (each element one IEEE-754 multiply or
add, the same whatever the array's length, alignment or the number of threads), reductions
in an order fixed by the code (loops) or exactly rounded (:func:`math.fsum`), and plain
Python floats for the scalar iterations.

* :func:`solve_spd` -- Gaussian elimination without pivoting (for a symmetric positive
  definite matrix, where it is backward stable; Golub & Van Loan, *Matrix Computations*,
  4th ed., Section 4.2).
* :func:`symmetric_eigen` -- Householder reduction to tridiagonal form (Golub & Van Loan
  Section 8.3.1) and the implicit QL iteration with Wilkinson shifts (Press et al.,
  *Numerical Recipes*, 3rd ed., Section 11.4, ``tqli``).  It returns the eigenvalues and the
  projections ``V^T x`` of a few vectors on the eigenvectors, which is all the network's
  exact-in-time response needs; :meth:`SymmetricEigen.project` gives more on request.

Both are O(n^3) with O(n^2) NumPy calls: a few tens of milliseconds for n ~ 100.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["solve_spd", "symmetric_eigen", "SymmetricEigen", "dot"]


def dot(x, y) -> float:
    """Exactly rounded dot product (:func:`math.fsum` of the element-wise products, each
    rounded once): independent of the order of the elements.

    >>> dot([1e16, 1.0, -1e16], [1.0, 1.0, 1.0])
    1.0
    """
    return math.fsum((np.asarray(x, float) * np.asarray(y, float)).tolist())


def solve_spd(a, b) -> np.ndarray:
    """Solve ``a x = b`` for a symmetric positive definite ``a`` (n, n) and ``b`` (n,).

    Gaussian elimination without pivoting, row operations as element-wise array
    operations in a fixed order: the result is bit-identical wherever it runs.

    >>> solve_spd([[4.0, 2.0], [2.0, 3.0]], [2.0, 1.0]).tolist()
    [0.5, 0.0]
    """
    a = np.array(a, dtype=float, copy=True)
    x = np.array(b, dtype=float, copy=True)
    n = a.shape[0]
    if a.ndim != 2 or a.shape != (n, n) or x.shape != (n,):
        raise ValueError(f"solve_spd needs a square matrix and a matching vector, got {a.shape} and {x.shape}")
    for k in range(n):
        piv = a[k, k]
        if not (math.isfinite(piv) and piv > 0):
            raise ValueError("solve_spd: the matrix is not positive definite")
        if k + 1 < n:
            f = a[k + 1:, k] / piv
            a[k + 1:, k + 1:] -= f[:, None] * a[k, k + 1:][None, :]
            x[k + 1:] -= f * x[k]
    for k in range(n - 1, -1, -1):
        x[k] = x[k] / a[k, k]
        if k:
            x[:k] -= a[:k, k] * x[k]
    return x


@dataclass(frozen=True)
class SymmetricEigen:
    """Eigenvalues of a symmetric matrix, ascending, with what is needed to project vectors
    on its eigenvectors (``V^T x``) in a fixed order of operations.

    Attributes
    ----------
    values : ndarray (n,)
        Eigenvalues, ascending.
    """

    values: np.ndarray
    _householder: tuple  # ((k, v, beta), ...): Q = H_0 H_1 ... with H = I - beta v v^T on rows k+1:
    _rotations: tuple  # ((i, c, s), ...) of the QL iteration, in the order applied
    _order: tuple  # sorts the QL eigenvalues ascending

    def project(self, *vectors) -> np.ndarray:
        """``V^T x`` for each vector ``x`` (rows of the result, eigenvalue order ascending),
        V the orthonormal eigenvectors: ``x = sum_k (V^T x)_k v_k``."""
        ys = [np.array(x, dtype=float, copy=True) for x in vectors]
        for y in ys:
            for k, v, beta in self._householder:  # Q^T y = H_last ... H_0 y
                y[k + 1:] -= (beta * dot(v, y[k + 1:])) * v
        cols = [y.tolist() for y in ys]
        for i, c, s in self._rotations:  # Z^T y: every rotation of Z's columns i, i+1
            for y in cols:
                f = y[i + 1]
                y[i + 1] = s * y[i] + c * f
                y[i] = c * y[i] - s * f
        return np.array([[y[k] for k in self._order] for y in cols])


def symmetric_eigen(a, *, max_iter: int = 60) -> SymmetricEigen:
    """Eigen-decomposition of the symmetric matrix ``a`` (only its lower triangle is read
    after the first step; it is symmetrised element-wise first), bit-identical wherever it
    runs.

    >>> e = symmetric_eigen([[2.0, 1.0], [1.0, 2.0]])
    >>> e.values.tolist()
    [1.0, 3.0]
    >>> p = e.project([1.0, 1.0])[0]
    >>> [round(abs(float(x)), 12) for x in p]
    [0.0, 1.414213562373]
    """
    a = np.array(a, dtype=float, copy=True)
    n = a.shape[0]
    if a.ndim != 2 or a.shape != (n, n) or n == 0:
        raise ValueError(f"symmetric_eigen needs a square matrix, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError("symmetric_eigen: the matrix has non-finite entries")
    a = 0.5 * (a + a.T)  # a_ij + a_ji == a_ji + a_ij: exactly symmetric
    # ---- Householder reduction to tridiagonal form: T = Q^T A Q -------------------------
    house = []
    for k in range(n - 2):
        x = a[k + 1:, k].copy()
        xn = math.sqrt(dot(x, x))
        if xn == 0.0:
            continue
        alpha = -math.copysign(xn, x[0])
        v = x
        v[0] -= alpha
        vv = dot(v, v)
        if vv == 0.0:
            continue
        beta = 2.0 / vv
        b = a[k + 1:, k + 1:]
        # p = beta * B v, the columns added in a fixed order
        p = b[:, 0] * v[0]
        for j in range(1, v.size):
            p += b[:, j] * v[j]
        p *= beta
        q = p - (0.5 * beta * dot(v, p)) * v
        b -= np.multiply.outer(v, q) + np.multiply.outer(q, v)  # stays exactly symmetric
        a[k + 1:, k] = 0.0
        a[k, k + 1:] = 0.0
        a[k + 1, k] = a[k, k + 1] = alpha
        house.append((k, v, beta))
    d = [float(a[i, i]) for i in range(n)]
    e = [float(a[i + 1, i]) for i in range(n - 1)] + [0.0]
    # ---- implicit QL with Wilkinson shifts (Numerical Recipes tqli), plain floats -------
    rot = []
    eps = np.finfo(float).eps
    for l_ in range(n):
        it = 0
        while True:
            m = l_
            while m < n - 1:
                dd = abs(d[m]) + abs(d[m + 1])
                if abs(e[m]) <= eps * dd:
                    break
                m += 1
            if m == l_:
                break
            it += 1
            if it > max_iter:
                raise ValueError("symmetric_eigen: the QL iteration did not converge")
            g = (d[l_ + 1] - d[l_]) / (2.0 * e[l_])
            r = math.hypot(g, 1.0)
            g = d[m] - d[l_] + e[l_] / (g + math.copysign(r, g))
            s = c = 1.0
            p = 0.0
            i = m - 1
            early = False
            while i >= l_:
                f = s * e[i]
                bb = c * e[i]
                r = math.hypot(f, g)
                e[i + 1] = r
                if r == 0.0:  # underflow: the matrix splits here
                    d[i + 1] -= p
                    e[m] = 0.0
                    early = True
                    break
                s = f / r
                c = g / r
                g = d[i + 1] - p
                r = (d[i] - g) * s + 2.0 * c * bb
                p = s * r
                d[i + 1] = g + p
                g = c * r - bb
                rot.append((i, c, s))
                i -= 1
            if early:
                continue
            d[l_] -= p
            e[l_] = g
            e[m] = 0.0
    order = tuple(sorted(range(n), key=lambda k: (d[k], k)))
    values = np.array([d[k] for k in order])
    values.setflags(write=False)
    return SymmetricEigen(values, tuple(house), tuple(rot), order)
