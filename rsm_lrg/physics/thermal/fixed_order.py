"""Dense symmetric linear algebra with a fixed order of floating-point operations.

The reduced thermal network (:mod:`.network`) needs a linear solve ``K x = b`` and the
eigen-decomposition of a symmetric matrix of order ~30-100.  NumPy's ``linalg.solve`` and
``linalg.eigh`` call BLAS/LAPACK, whose blocking, threading (the number of OpenBLAS/MKL
threads differs between the main process and, say, a Dask worker, which starts with one
thread) and SIMD paths change the order of the additions, so the same matrix gives results
that differ in the last bits (measured: 1.5e-15 relative on the steady rise per watt with 1
thread against 2).  The virtual runs promise bit-identical rows wherever they run, so these
routines are compiled loops (numba, ``fastmath`` off: every multiply and add one IEEE-754
operation, in the order the code gives, no reassociation) that run the same operations
whatever the process, the number of threads or the other rows of a batch.

* :func:`solve_spd` -- Gaussian elimination without pivoting (for a symmetric positive
  definite matrix, where it is backward stable; Golub & Van Loan, *Matrix Computations*,
  4th ed., Section 4.2).
* :func:`symmetric_eigen` -- Householder reduction to tridiagonal form (Golub & Van Loan
  Section 8.3.1) and the implicit QL iteration with Wilkinson shifts (Press et al.,
  *Numerical Recipes*, 3rd ed., Section 11.4, ``tqli``).  It returns the eigenvalues and the
  projections ``V^T x`` of given vectors on the eigenvectors (the reflections and rotations
  are applied to the vectors as they are made), which is all the network's exact-in-time
  response needs.
* :func:`modal_sum` -- the step response ``sum_k a_k (1 - exp(-mu_k t))`` at given times.
* :func:`chain_network`, :func:`chain_rows` -- many rows whose networks share a core and
  differ in a chain of nodes attached to it (the leaves of each thickness of a design): the
  core is reduced to tridiagonal form once, so a row costs a QL iteration, in one compiled
  loop with no Python per row.
* :func:`patched_rows` -- many rows of a network that differ in a few entries (the two-carriage
  rig of each setting of a design): each row assembled from a shared base and its own entries and
  decomposed with the operations of :func:`network_modes`, in one compiled loop.

The kernels are compiled on first use (numba imported only then) and cached on disk.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

__all__ = ["solve_spd", "symmetric_eigen", "SymmetricEigen", "modal_sum", "network_modes", "chain_network", "chain_rows", "ChainNetwork",
           "patched_rows", "RowError"]


# ----------------------------------------------------------------------------------------
# compiled kernels (module-level functions, compiled by _kernels() on first use; numba keys
# its disk cache of module-level functions by their source, so each process loads them)
# ----------------------------------------------------------------------------------------
def _fo_solve(a: np.ndarray, x: np.ndarray) -> int:
    # a (n, n) overwritten; x (n, m) overwritten by the solution; 1: not positive definite
    n = a.shape[0]
    m = x.shape[1]
    for k in range(n):
        piv = a[k, k]
        if not (piv > 0.0 and piv < np.inf):
            return 1
        rk = a[k, k + 1:]
        for i in range(k + 1, n):
            f = a[i, k] / piv
            ri = a[i, k + 1:]  # views from 0: vector registers, the same operations
            for j in range(n - k - 1):
                ri[j] = ri[j] - f * rk[j]
            for c in range(m):
                x[i, c] -= f * x[k, c]
    for k in range(n - 1, -1, -1):
        for c in range(m):
            x[k, c] = x[k, c] / a[k, k]
        for i in range(k):
            for c in range(m):
                x[i, c] -= a[i, k] * x[k, c]
    return 0


def _fo_hypot(x: float, y: float) -> float:
    # sqrt(x^2 + y^2): the plain formula where neither square can overflow or underflow to a
    # loss of digits (math.hypot's scaling costs tens of ns, called ~1,000 times a matrix)
    ax = abs(x)
    ay = abs(y)
    big = ax if ax > ay else ay
    if 1e-150 < big < 1e150:
        return math.sqrt(x * x + y * y)
    return _fo_hypot_far(x, y)


def _fo_hypot_far(x: float, y: float) -> float:
    # uncompiled (a few rows, rsm_lrg.physics.jit): Python's math.hypot is its own algorithm, not
    # the C library's hypot that the compiled kernel calls, so the kernel is handed back to numba
    # (run_kernel puts its arrays back and runs it compiled); compiled, this is _fo_hypot_c
    raise ArithmeticError("hypot outside [1e-150, 1e150]: run compiled")


def _fo_hypot_c(x: float, y: float) -> float:
    return math.hypot(x, y)


def _fo_tridiag(a: np.ndarray, x: np.ndarray, d: np.ndarray, e: np.ndarray) -> None:
    # a (n, n) symmetric, overwritten: T = Q^T A Q tridiagonal, its diagonal in d (n,) and
    # sub-diagonal in e (e[i] couples i and i+1, e[n-1] = 0); x (n, m) overwritten by Q^T x.
    # Q's reflections act on rows 1.. only: Q e_0 = e_0
    n = a.shape[0]
    m = x.shape[1]
    v = np.empty(n)
    p = np.empty(n)
    # ---- Householder reduction to tridiagonal form: T = Q^T A Q --------------------------
    for k in range(n - 2):
        xn2 = 0.0
        for i in range(k + 1, n):
            xn2 += a[i, k] * a[i, k]
        xn = math.sqrt(xn2)
        if xn == 0.0:
            continue
        alpha = -xn if a[k + 1, k] >= 0.0 else xn
        for i in range(k + 1, n):
            v[i] = a[i, k]
        v[k + 1] -= alpha
        vv = 0.0
        for i in range(k + 1, n):
            vv += v[i] * v[i]
        if vv == 0.0:
            continue
        beta = 2.0 / vv
        # p = beta B v, each p[i] summed over j in ascending order; B is exactly symmetric, so row j of B
        # is its column j and the sweep runs along rows (contiguous, in vector registers: the order of each
        # p[i]'s additions is unchanged)
        # (the loops run over views that start at k + 1 and from 0, where the compiler sees no negative
        # index and uses vector registers: each element's operations are the same, in the same order)
        m_ = n - k - 1
        pt = p[k + 1:]
        vt = v[k + 1:]
        row = a[k + 1, k + 1:]
        vk = vt[0]
        for i in range(m_):
            pt[i] = row[i] * vk
        for j in range(1, m_):
            vj = vt[j]
            row = a[k + 1 + j, k + 1:]
            for i in range(m_):
                pt[i] += row[i] * vj
        for i in range(m_):
            pt[i] = pt[i] * beta
        vp = 0.0
        for i in range(k + 1, n):
            vp += v[i] * p[i]
        half = 0.5 * beta * vp
        for i in range(k + 1, n):
            p[i] = p[i] - half * v[i]  # q
        for i in range(m_):
            vi = vt[i]
            pi = pt[i]
            row = a[k + 1 + i, k + 1:]
            for j in range(m_):
                row[j] = row[j] - (vi * pt[j] + pi * vt[j])  # stays exactly symmetric
        for i in range(k + 1, n):
            a[i, k] = 0.0
            a[k, i] = 0.0
        a[k + 1, k] = alpha
        a[k, k + 1] = alpha
        for c in range(m):  # H x = x - beta v (v^T x)
            acc = 0.0
            for i in range(k + 1, n):
                acc += v[i] * x[i, c]
            f = beta * acc
            for i in range(k + 1, n):
                x[i, c] -= f * v[i]
    for i in range(n):
        d[i] = a[i, i]
        e[i] = a[i + 1, i] if i < n - 1 else 0.0


def _fo_ql(d: np.ndarray, e: np.ndarray, x: np.ndarray, max_iter: int, values: np.ndarray,
           proj: np.ndarray) -> int:
    # the symmetric tridiagonal matrix (d, e), both overwritten; x (n, m) overwritten by Z^T x;
    # values (n,) and proj (n, m) receive the eigenvalues ascending and Z^T x in that order.
    # 1: no convergence
    n = d.shape[0]
    m = x.shape[1]
    # ---- implicit QL with Wilkinson shifts (Numerical Recipes tqli) -----------------------
    eps = 2.220446049250313e-16
    for l_ in range(n):
        it = 0
        while True:
            mm = l_
            while mm < n - 1:
                dd = abs(d[mm]) + abs(d[mm + 1])
                if abs(e[mm]) <= eps * dd:
                    break
                mm += 1
            if mm == l_:
                break
            it += 1
            if it > max_iter:
                return 1
            g = (d[l_ + 1] - d[l_]) / (2.0 * e[l_])
            r = _fo_hypot(g, 1.0)
            g = d[mm] - d[l_] + e[l_] / (g + (r if g >= 0.0 else -r))
            s = 1.0
            c_ = 1.0
            pp = 0.0
            i = mm - 1
            early = False
            while i >= l_:
                f = s * e[i]
                bb = c_ * e[i]
                r = _fo_hypot(f, g)
                e[i + 1] = r
                if r == 0.0:  # underflow: the matrix splits here
                    d[i + 1] -= pp
                    e[mm] = 0.0
                    early = True
                    break
                s = f / r
                c_ = g / r
                g = d[i + 1] - pp
                r = (d[i] - g) * s + 2.0 * c_ * bb
                pp = s * r
                d[i + 1] = g + pp
                g = c_ * r - bb
                for col in range(m):  # the rotation of the columns i, i+1 of Z, on Z^T x
                    fx = x[i + 1, col]
                    x[i + 1, col] = s * x[i, col] + c_ * fx
                    x[i, col] = c_ * x[i, col] - s * fx
                i -= 1
            if early:
                continue
            d[l_] -= pp
            e[l_] = g
            e[mm] = 0.0
    # ---- ascending order (ties by index: insertion sort, stable) --------------------------
    order = np.arange(n)
    for i in range(1, n):
        j = i
        while j > 0 and d[order[j - 1]] > d[order[j]]:
            t = order[j - 1]
            order[j - 1] = order[j]
            order[j] = t
            j -= 1
    for i in range(n):
        values[i] = d[order[i]]
        for col in range(m):
            proj[i, col] = x[order[i], col]
    return 0


def _fo_eigen(a: np.ndarray, x: np.ndarray, max_iter: int, values: np.ndarray, proj: np.ndarray) -> int:
    # a (n, n) symmetric, overwritten; x (n, m) overwritten; values (n,) and proj (n, m)
    # receive the eigenvalues ascending and V^T x in that order. 1: no convergence
    n = a.shape[0]
    d = np.empty(n)
    e = np.empty(n)
    _fo_tridiag(a, x, d, e)
    return _fo_ql(d, e, x, max_iter, values, proj)


def _fo_modal_sum(coef: np.ndarray, mu: np.ndarray, t: np.ndarray, out: np.ndarray) -> None:
    # out[j] = -sum_k coef_k expm1(-mu_k t_j), the modes added in their order
    for j in range(t.shape[0]):
        acc = 0.0
        for k in range(mu.shape[0]):
            acc -= coef[k] * math.expm1(-mu[k] * t[j])
        out[j] = acc


def _fo_scaled(kk: np.ndarray, sc: np.ndarray, a: np.ndarray) -> None:
    # a = diag(sc) K diag(sc), then made exactly symmetric ((x + y) / 2 is the same sum either way)
    n = kk.shape[0]
    for i in range(n):
        for j in range(n):
            a[i, j] = sc[i] * kk[i, j] * sc[j]
    for i in range(n):
        for j in range(i):
            h = 0.5 * (a[i, j] + a[j, i])
            a[i, j] = h
            a[j, i] = h


def _fo_row_responses(mu: np.ndarray, proj: np.ndarray, s_node: float, times: np.ndarray, coef: np.ndarray,
                      out: np.ndarray, resp: np.ndarray) -> int:
    # what the row kernels share once a row is decomposed: the check that no mode is zero to
    # rounding (2: a node set with no loss) and, per source c, the observed node's step response
    # resp[c] (m,) at times (m,) from the modes mu and the projections proj (column 0 the node)
    n = mu.shape[0]
    if not mu[0] > 1e-13 * abs(mu[n - 1]):
        return 2
    for c in range(resp.shape[0]):
        for k in range(n):
            coef[k] = s_node * proj[k, 0] * proj[k, 1 + c] / mu[k]
        _fo_modal_sum(coef, mu, times, out)
        for j in range(times.shape[0]):
            resp[c, j] = out[j]
    return 0


def _fo_network(k_mat: np.ndarray, cap: np.ndarray, src: np.ndarray, node: int, max_iter: int,
                mu: np.ndarray, coef: np.ndarray, steady: np.ndarray) -> int:
    # one network K (overwritten), C: its modes mu (ascending) and, per source (columns of
    # src), the coefficients of node's unit response and its steady rise
    n = k_mat.shape[0]
    ns = src.shape[1]
    s = np.empty(n)
    for i in range(n):
        s[i] = 1.0 / math.sqrt(cap[i])
    a = np.empty((n, n))
    _fo_scaled(k_mat, s, a)
    x = np.zeros((n, 1 + ns))
    x[node, 0] = 1.0
    for c in range(ns):
        for i in range(n):
            x[i, 1 + c] = s[i] * src[i, c]
    proj = np.empty((n, 1 + ns))
    if _fo_eigen(a, x, max_iter, mu, proj) != 0:
        return 1
    if not mu[0] > 1e-13 * abs(mu[n - 1]):  # zero to rounding: a node set with no loss
        return 2
    for c in range(ns):
        for k in range(n):
            coef[k, c] = s[node] * proj[k, 0] * proj[k, 1 + c] / mu[k]
    b = src.copy()
    if _fo_solve(k_mat, b) != 0:
        return 3
    for c in range(ns):
        steady[c] = b[node, c]
    return 0


def _fo_tri_solve(d: np.ndarray, e: np.ndarray, y: np.ndarray) -> int:
    # the symmetric positive definite tridiagonal (d, e) (not overwritten): y overwritten by
    # T^-1 y (elimination without pivoting); 1: not positive definite
    n = d.shape[0]
    w = np.empty(n)
    w[0] = d[0]
    if not w[0] > 0.0:
        return 1
    for i in range(1, n):
        f = e[i - 1] / w[i - 1]
        w[i] = d[i] - f * e[i - 1]
        if not w[i] > 0.0:
            return 1
        y[i] -= f * y[i - 1]
    y[n - 1] = y[n - 1] / w[n - 1]
    for i in range(n - 2, -1, -1):
        y[i] = (y[i] - e[i] * y[i + 1]) / w[i]
    return 0


def _fo_chain_rows(core_d: np.ndarray, core_e: np.ndarray, core_x: np.ndarray, s_hub: float, kd: np.ndarray,
                   ko: np.ndarray, cc: np.ndarray, chain_src: np.ndarray, times: np.ndarray, max_iter: int,
                   resp: np.ndarray, steady: np.ndarray, status: np.ndarray) -> None:
    # rows of a network made of a fixed core, already tridiagonal (core_d, core_e; its sources
    # Q^T C^-1/2 b in core_x (nc, ns_core); the hub, node 0 of the core, observed) and a chain
    # of m nodes that changes row by row: K's diagonal kd[r] (m,), its links ko[r] (m,) (i to
    # i + 1, the last to the hub), capacities cc[r] (m,), sources chain_src (m, ns_chain)
    nc = core_d.shape[0]
    m = kd.shape[1]
    n = m + nc
    ns_core = core_x.shape[1]
    ns = ns_core + chain_src.shape[1]
    d = np.empty(n)
    e = np.empty(n)
    d0 = np.empty(n)
    e0 = np.empty(n)
    x = np.zeros((n, 1 + ns))
    x0 = np.empty((n, 1 + ns))
    mu = np.empty(n)
    proj = np.empty((n, 1 + ns))
    y = np.empty(n)
    coef = np.empty(n)
    out = np.empty(times.shape[1])
    sc = np.empty(m + 1)
    for r in range(times.shape[0]):
        for i in range(m):
            sc[i] = 1.0 / math.sqrt(cc[r, i])
        sc[m] = s_hub
        for i in range(m):
            d[i] = sc[i] * kd[r, i] * sc[i]
            e[i] = sc[i] * ko[r, i] * sc[i + 1]
        for j in range(nc):
            d[m + j] = core_d[j]
            e[m + j] = core_e[j]
        for i in range(n):
            for c in range(1 + ns):
                x[i, c] = 0.0
        x[m, 0] = 1.0
        for c in range(ns_core):
            for j in range(nc):
                x[m + j, 1 + c] = core_x[j, c]
        for c in range(ns - ns_core):
            for i in range(m):
                x[i, 1 + ns_core + c] = sc[i] * chain_src[i, c]
        for i in range(n):
            d0[i] = d[i]
            e0[i] = e[i]
            for c in range(1 + ns):
                x0[i, c] = x[i, c]
        if _fo_ql(d, e, x, max_iter, mu, proj) != 0:
            status[r] = 1
            continue
        status[r] = _fo_row_responses(mu, proj, s_hub, times[r], coef, out, resp[r])
        if status[r] != 0:
            continue
        for c in range(ns):
            for i in range(n):
                y[i] = x0[i, 1 + c]
            if _fo_tri_solve(d0, e0, y) != 0:
                status[r] = 3
                break
            steady[r, c] = s_hub * y[m]


def _fo_patched_rows(k_base: np.ndarray, c_base: np.ndarray, src_base: np.ndarray, k_pos: np.ndarray,
                     k_add: np.ndarray, c_pos: np.ndarray, c_add: np.ndarray, s_pos: np.ndarray, s_add: np.ndarray,
                     node: np.ndarray, times: np.ndarray, max_iter: int, resp: np.ndarray, steady: np.ndarray,
                     status: np.ndarray) -> None:
    # rows of a network K = k_base + the row's patches (k_add[r, p] added at (k_pos[p, 0], k_pos[p, 1]) and,
    # off the diagonal, at its mirror; the patches added in their order), C = c_base + c_add[r] at c_pos,
    # sources src_base + s_add[r] at (s_pos[p, 0] node, s_pos[p, 1] column): each row assembled and
    # decomposed (Householder, QL) on its own, its observed node node[r], with the operations of
    # _fo_network; resp (rows, ns, m) at times (rows, m), steady (rows, ns); status as _fo_network
    n = k_base.shape[0]
    ns = src_base.shape[1]
    a = np.empty((n, n))
    kk = np.empty((n, n))
    cap = np.empty(n)
    sc = np.empty(n)
    x = np.empty((n, 1 + ns))
    b = np.empty((n, ns))
    mu = np.empty(n)
    proj = np.empty((n, 1 + ns))
    coef = np.empty(n)
    out = np.empty(times.shape[1])
    for r in range(times.shape[0]):
        for i in range(n):
            cap[i] = c_base[i]
            for j in range(n):
                kk[i, j] = k_base[i, j]
            for c in range(ns):
                x[i, 1 + c] = src_base[i, c]
            x[i, 0] = 0.0
        for p in range(k_pos.shape[0]):
            i = k_pos[p, 0]
            j = k_pos[p, 1]
            kk[i, j] += k_add[r, p]
            if i != j:
                kk[j, i] += k_add[r, p]
        for p in range(c_pos.shape[0]):
            cap[c_pos[p]] += c_add[r, p]
        for p in range(s_pos.shape[0]):
            x[s_pos[p, 0], 1 + s_pos[p, 1]] += s_add[r, p]
        bad = False
        for i in range(n):
            if not (cap[i] > 0.0 and cap[i] < np.inf):
                bad = True
        if bad:
            status[r] = 4
            continue
        for i in range(n):
            sc[i] = 1.0 / math.sqrt(cap[i])
        _fo_scaled(kk, sc, a)
        nd = node[r]
        x[nd, 0] = 1.0
        for i in range(n):
            for c in range(ns):
                b[i, c] = x[i, 1 + c]
                x[i, 1 + c] = sc[i] * x[i, 1 + c]
        if _fo_eigen(a, x, max_iter, mu, proj) != 0:
            status[r] = 1
            continue
        status[r] = _fo_row_responses(mu, proj, sc[nd], times[r], coef, out, resp[r])
        if status[r] != 0:
            continue
        if _fo_solve(kk, b) != 0:  # the steady state K^-1 b, as network_modes and solve_spd solve it
            status[r] = 3
            continue
        for c in range(ns):
            steady[r, c] = b[nd, c]


_FO_NAMES = ("_fo_solve", "_fo_hypot", "_fo_tridiag", "_fo_ql", "_fo_eigen", "_fo_modal_sum", "_fo_scaled", "_fo_row_responses",
             "_fo_network", "_fo_tri_solve", "_fo_chain_rows",
             "_fo_patched_rows")


@lru_cache(maxsize=1)
def _kernels() -> dict[str, Any]:
    """Compile the kernels (once per process; numba caches the machine code on disk)."""
    from ..jit import import_numba

    numba = import_numba()

    g = globals()
    jit = numba.njit(cache=True, fastmath=False, error_model="numpy")
    g["_fo_hypot_far"] = jit(_fo_hypot_c)  # the C library's hypot, as math.hypot compiles
    for name in _FO_NAMES:  # callees first
        g[name] = jit(g[name])
    return {name: g[name] for name in _FO_NAMES}


def _run(name: str, *args: Any) -> Any:
    """Call the kernel ``name``: compiled, or as Python for a few rows while numba is not loaded
    (:mod:`rsm_lrg.physics.jit`; the same numbers)."""
    from ..jit import run_kernel

    f = globals()[name]
    return run_kernel(getattr(f, "py_func", f), lambda: _kernels()[name], *args)


_MESSAGES = {1: "the QL iteration did not converge", 2: "the network has no path to ambient (all h = 0): "
             "no steady state.", 3: "the matrix is not positive definite", 4: "a heat capacity is not positive"}


def _square(a: Any, what: str) -> np.ndarray:
    a = np.array(a, dtype=float, copy=True)
    n = a.shape[0] if a.ndim else 0
    if a.ndim != 2 or a.shape != (n, n) or n == 0:
        raise ValueError(f"{what} needs a square matrix, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{what}: the matrix has non-finite entries")
    return np.ascontiguousarray(a)


def solve_spd(a, b) -> np.ndarray:
    """Solve ``a x = b`` for a symmetric positive definite ``a`` (n, n) and ``b`` (n,).

    Gaussian elimination without pivoting, in a fixed order of operations: the result is
    bit-identical wherever it runs.

    >>> solve_spd([[4.0, 2.0], [2.0, 3.0]], [2.0, 1.0]).tolist()
    [0.5, 0.0]
    """
    a = _square(a, "solve_spd")
    x = np.array(b, dtype=float, copy=True)
    if x.shape != (a.shape[0],):
        raise ValueError(f"solve_spd needs a square matrix and a matching vector, got {a.shape} and {x.shape}")
    x2 = np.ascontiguousarray(x[:, None])
    if _run("_fo_solve", a, x2) != 0:
        raise ValueError("solve_spd: " + _MESSAGES[3])
    return x2[:, 0].copy()


@dataclass(frozen=True)
class SymmetricEigen:
    """Eigenvalues of a symmetric matrix, ascending, with the projections of vectors on its
    eigenvectors (``V^T x``) in a fixed order of operations.

    Attributes
    ----------
    values : ndarray (n,)
        Eigenvalues, ascending.
    """

    values: np.ndarray
    _matrix: np.ndarray  # the symmetrised matrix: project() decomposes it again with the vectors
    max_iter: int = 60

    def project(self, *vectors) -> np.ndarray:
        """``V^T x`` for each vector ``x`` (rows of the result, eigenvalue order ascending),
        V the orthonormal eigenvectors: ``x = sum_k (V^T x)_k v_k``. The reflections and
        rotations of the decomposition are applied to the vectors (each on its own: a
        vector's projection does not depend on the others asked for with it)."""
        _, p = _decompose(self._matrix, np.array(vectors, dtype=float).T, self.max_iter)
        return np.ascontiguousarray(p.T)


def _decompose(a: np.ndarray, x: np.ndarray, max_iter: int) -> tuple[np.ndarray, np.ndarray]:
    n = a.shape[0]
    values = np.empty(n)
    proj = np.empty((n, x.shape[1]))
    if _run("_fo_eigen", a.copy(), np.ascontiguousarray(x, dtype=float).copy(), int(max_iter), values,
                               proj) != 0:
        raise ValueError("symmetric_eigen: " + _MESSAGES[1])
    return values, proj


def symmetric_eigen(a, *, max_iter: int = 60) -> SymmetricEigen:
    """Eigen-decomposition of the symmetric matrix ``a`` (symmetrised element-wise first),
    bit-identical wherever it runs.

    >>> e = symmetric_eigen([[2.0, 1.0], [1.0, 2.0]])
    >>> e.values.tolist()
    [1.0, 3.0]
    >>> p = e.project([1.0, 1.0])[0]
    >>> [round(abs(float(x)), 12) for x in p]
    [0.0, 1.414213562373]
    """
    a = _square(a, "symmetric_eigen")
    a = np.ascontiguousarray(0.5 * (a + a.T))  # a_ij + a_ji == a_ji + a_ij: exactly symmetric
    values, _ = _decompose(a, np.zeros((a.shape[0], 0)), max_iter)
    values.setflags(write=False)
    return SymmetricEigen(values, a, int(max_iter))


def modal_sum(coef, mu, times_s) -> np.ndarray:
    """``sum_k coef_k (1 - exp(-mu_k t))`` at each time ``t`` [s] (``expm1``, the modes added
    in their order): a step response from its modal coefficients ``coef`` and rates ``mu``
    [1/s]. Each time's value does not depend on the other times asked for.

    >>> modal_sum([1.0, 2.0], [1.0, 0.5], [0.0, 1e9]).tolist()
    [0.0, 3.0]
    """
    t = np.asarray(times_s, dtype=float)
    out = np.empty(t.size)
    _run("_fo_modal_sum", np.ascontiguousarray(coef, dtype=float), np.ascontiguousarray(mu, dtype=float),
                                np.ascontiguousarray(t.reshape(-1)), out)
    return out.reshape(t.shape)


def network_modes(k_mat, capacity, sources, node: int = 0, *, max_iter: int = 60
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The modes of the network ``C θ' = -K θ + b`` (``K`` (n, n) symmetric positive definite
    [W/K], ``C`` (n,) [J/K]): rates ``mu`` [1/s] ascending, and for each source (columns of
    ``sources`` (n, m) [1]) the coefficients ``a_k`` [K/W] of ``node``'s unit response
    ``sum_k a_k (1 - exp(-mu_k t))`` (:func:`modal_sum`) and its steady rise [K/W] (a solve of
    ``K x = b``), from the decomposition of ``C^(-1/2) K C^(-1/2)``."""
    k_mat = _square(k_mat, "network_modes")
    cap = np.ascontiguousarray(capacity, dtype=float)
    src = np.ascontiguousarray(sources, dtype=float)
    n = k_mat.shape[0]
    if cap.shape != (n,) or src.ndim != 2 or src.shape[0] != n or not np.all(cap > 0):
        raise ValueError("network_modes needs positive capacities and sources of the matrix's order")
    mu, coef, steady = np.empty(n), np.empty((n, src.shape[1])), np.empty(src.shape[1])
    status = _run("_fo_network", k_mat, cap, src, int(node), int(max_iter), mu, coef, steady)
    if status:
        raise ValueError(_MESSAGES[status])
    return mu, coef, steady


@dataclass(frozen=True)
class ChainNetwork:
    """A network split into a fixed core, reduced once to tridiagonal form, and a chain of
    nodes that changes from row to row (:func:`chain_network`, :func:`chain_rows`).

    Attributes
    ----------
    core_d, core_e : ndarray (nc,)
        The core's ``C^(-1/2) K C^(-1/2)`` reduced to tridiagonal form ``Q^T A Q`` (Q fixes the
        hub, the core's first node).
    core_x : ndarray (nc, ns)
        ``Q^T C^(-1/2) b`` of the core's sources.
    s_hub : float
        ``C^(-1/2)`` of the hub [K^(1/2) J^(-1/2)].
    """

    core_d: np.ndarray
    core_e: np.ndarray
    core_x: np.ndarray
    s_hub: float


def chain_network(k_core, c_core, core_sources) -> ChainNetwork:
    """Reduce the core of a network (``K`` (nc, nc) [W/K] among the core's nodes, every link
    to the chain included on the diagonal; capacities (nc,) [J/K]; sources (nc, ns)) once,
    by Householder reflections that leave its first node, the hub, in place."""
    k_core = _square(k_core, "chain_network")
    cap = np.ascontiguousarray(c_core, dtype=float)
    src = np.ascontiguousarray(core_sources, dtype=float)
    nc = k_core.shape[0]
    if cap.shape != (nc,) or not np.all(cap > 0) or src.ndim != 2 or src.shape[0] != nc:
        raise ValueError("chain_network needs positive capacities and sources of the core's order")
    s = 1.0 / np.sqrt(cap)
    a = s[:, None] * k_core * s[None, :]
    a = np.ascontiguousarray(0.5 * (a + a.T))
    x = np.ascontiguousarray(s[:, None] * src)
    d, e = np.empty(nc), np.empty(nc)
    _run("_fo_tridiag", a, x, d, e)
    return ChainNetwork(d, e, x, float(s[0]))


def chain_rows(core: ChainNetwork, k_diag, k_link, capacity, chain_sources, times_s, *, max_iter: int = 60
               ) -> tuple[np.ndarray, np.ndarray]:
    """Unit responses of the hub for many rows of a network made of the fixed ``core``
    (:func:`chain_network`) and a chain of m nodes attached to the hub, which changes row by
    row: ``k_diag`` (rows, m) the chain's diagonal of K [W/K], ``k_link`` (rows, m) its links
    (node i to i + 1; the last, to the hub) [W/K], ``capacity`` (rows, m) [J/K];
    ``chain_sources`` (m, ns_chain) the chain's sources.

    The row's matrix ``C^(-1/2) K C^(-1/2)`` is tridiagonal in the basis (chain, ``Q`` core), so
    each row costs one QL iteration (:func:`symmetric_eigen`'s second half) and a tridiagonal
    solve, O(n^2), instead of a dense decomposition, O(n^3). The eigenvalues and the hub's
    response are those of the dense matrix (an orthogonal change of basis), to rounding.

    Returns ``resp`` (rows, ns_core + ns_chain, times) [K/W] at ``times_s`` (rows, times) [s]
    (sources: the core's, then the chain's) and the steady rises ``(rows, sources)`` [K/W].
    Raises :class:`RowError` (a ``ValueError``) naming the first row (from 0) that fails.
    """
    t = np.ascontiguousarray(times_s, dtype=float)
    rows = t.shape[0]
    kd, ko, cc = (np.ascontiguousarray(np.broadcast_to(np.asarray(q, float), (rows, np.shape(q)[-1])))
                  for q in (k_diag, k_link, capacity))
    src = np.ascontiguousarray(chain_sources, dtype=float)
    ns = core.core_x.shape[1] + src.shape[1]
    resp = np.zeros((rows, ns, t.shape[1]))
    steady = np.zeros((rows, ns))
    status = np.zeros(rows, dtype=np.int64)
    bad_cap = np.flatnonzero(~np.all(cc > 0, axis=1))
    if bad_cap.size:
        raise RowError(int(bad_cap[0]), "a heat capacity is not positive")
    _run("_fo_chain_rows", core.core_d, core.core_e, core.core_x, core.s_hub, kd, ko, cc, src, t,
                                 int(max_iter), resp, steady, status)
    bad = np.flatnonzero(status)
    if bad.size:
        raise RowError(int(bad[0]), _MESSAGES[int(status[bad[0]])])
    return resp, steady


def patched_rows(k_base, c_base, src_base, k_pos, k_add, c_pos, c_add, s_pos, s_add, node, times_s, *,
                 max_iter: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """Unit responses of many rows of a network that differs from row to row in a few entries, each
    row assembled and decomposed on its own in one compiled loop (no Python object per row).

    Row ``r``'s network is ``K = k_base`` with ``k_add[r, p]`` added at ``k_pos[p]`` (and at its
    mirror off the diagonal), ``C = c_base`` with ``c_add[r, p]`` added at node ``c_pos[p]``, and
    the sources ``src_base`` (n, ns) with ``s_add[r, p]`` added at ``s_pos[p]`` (node, source); the
    patches are added in their order. Then the row runs the operations of :func:`network_modes`:
    its ``C^(-1/2) K C^(-1/2)`` decomposed (Householder, then QL with the projections carried
    along), the response of node ``node[r]`` summed at ``times_s[r]`` (:func:`modal_sum`) and its
    steady rise solved from ``K`` (:func:`solve_spd`), so a row equal to a network gives that
    network's numbers to the last bit. A row's numbers do not depend on the other rows.

    Parameters
    ----------
    k_base : array (n, n)
        The conductances common to every row [W/K] (symmetric).
    c_base : array (n,)
        The heat capacities common to every row [J/K].
    src_base : array (n, ns)
        Where each watt of each source enters, common part [1].
    k_pos, c_pos, s_pos : int arrays (pk, 2), (pc,), (ps, 2)
        Where the rows' patches go.
    k_add, c_add, s_add : arrays (rows, pk), (rows, pc), (rows, ps)
        The patches of each row [W/K], [J/K], [1].
    node : int array (rows,)
        The node observed in each row.
    times_s : array (rows, m)
        Times after the heat step [s].
    max_iter : int
        Most QL iterations per eigenvalue.

    Returns
    -------
    resp : ndarray (rows, ns, m)
        Rise per watt [K/W] of ``node[r]`` at ``times_s[r]`` for each source.
    steady : ndarray (rows, ns)
        The steady rises per watt [K/W].

    Raises :class:`RowError` naming the first row (from 0) that fails.

    Examples
    --------
    >>> k = np.array([[2.0, -1.0], [-1.0, 2.0]])
    >>> resp, steady = patched_rows(k, [1.0, 1.0], [[1.0], [0.0]], [[0, 0]], [[0.0], [1.0]], np.zeros(0, int),
    ...                             np.zeros((2, 0)), np.zeros((0, 2), int), np.zeros((2, 0)), [0, 0], [[1e9], [1e9]])
    >>> [round(float(x), 12) for x in steady[:, 0]]  # (K^-1 e_0)_0: row 0 K as given, row 1 K[0, 0] + 1
    [0.666666666667, 0.4]
    """
    kb = _square(k_base, "patched_rows")
    n = kb.shape[0]
    cb = np.ascontiguousarray(c_base, dtype=float)
    sb = np.ascontiguousarray(src_base, dtype=float)
    t = np.ascontiguousarray(np.atleast_2d(np.asarray(times_s, dtype=float)))
    rows = t.shape[0]
    kp = np.ascontiguousarray(np.asarray(k_pos, dtype=np.int64).reshape(-1, 2))
    cp = np.ascontiguousarray(np.asarray(c_pos, dtype=np.int64).reshape(-1))
    sp = np.ascontiguousarray(np.asarray(s_pos, dtype=np.int64).reshape(-1, 2))
    ka, ca, sa = (np.ascontiguousarray(np.asarray(q, dtype=float).reshape(rows, -1) if np.size(q) else
                                       np.zeros((rows, len(pos)))) for q, pos in ((k_add, kp), (c_add, cp), (s_add, sp)))
    nd = np.ascontiguousarray(np.broadcast_to(np.asarray(node, dtype=np.int64), (rows,)))
    if (cb.shape != (n,) or sb.ndim != 2 or sb.shape[0] != n or ka.shape[1] != len(kp) or ca.shape[1] != len(cp)
            or sa.shape[1] != len(sp)):
        raise ValueError("patched_rows: the base network, the patches and their positions do not match")
    if (kp.size and not (0 <= kp.min() and kp.max() < n)) or (cp.size and not (0 <= cp.min() and cp.max() < n)) or (
            sp.size and not (0 <= sp[:, 0].min() and sp[:, 0].max() < n and 0 <= sp[:, 1].min()
                             and sp[:, 1].max() < sb.shape[1])) or (nd.size and not (0 <= nd.min() and nd.max() < n)):
        raise ValueError("patched_rows: a position is outside the network")
    if np.any(t < 0) or not np.all(np.isfinite(t)):
        raise ValueError("times_s must be finite and >= 0 [s].")
    for what, q in (("k_base", kb), ("c_base", cb), ("src_base", sb), ("k_add", ka), ("c_add", ca), ("s_add", sa)):
        if not np.all(np.isfinite(q)):
            raise ValueError(f"patched_rows: {what} has non-finite entries")
    ns = sb.shape[1]
    resp = np.zeros((rows, ns, t.shape[1]))
    steady = np.zeros((rows, ns))
    status = np.zeros(rows, dtype=np.int64)
    _run("_fo_patched_rows", kb, cb, sb, kp, ka, cp, ca, sp, sa, nd, t, int(max_iter), resp, steady, status)
    bad = np.flatnonzero(status)
    if bad.size:
        raise RowError(int(bad[0]), _MESSAGES[int(status[bad[0]])])
    return resp, steady


class RowError(ValueError):
    """A row of :func:`rig_rows` whose network fails: ``row`` (from 0) and the reason."""

    def __init__(self, row: int, reason: str):
        super().__init__(f"row {row}: {reason}")
        self.row = row
        self.reason = reason
