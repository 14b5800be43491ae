"""Element-wise kernels of the beam-column leaf (:mod:`.hinge`), compiled with numba.

Every element is computed alone with the C library's scalar ``tanh``/``cosh``, so a value does
not depend on where it sits in an array: NumPy's vectorised transcendental functions may round
the elements of a SIMD block and those of its tail differently (one ulp), which would make a
row's result depend on its batch. The formulas are those of :mod:`.hinge` (comment before
``_S_SERIES``): ``S(u) = 3·(u − tanh u)/u³``, ``D(u)/u⁴`` with
``D = 1 + ½·sech²u − 3·tanh u/(2u)`` and ``tanh(u)/u``, by their Taylor series below u = 0.2.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

import numpy as np

__all__ = ["leaf_parts", "tension_parameter", "parameter_for_load"]

_S = (1.0, -2.0 / 5, 17.0 / 105, -62.0 / 945, 1382.0 / 51975, -21844.0 / 2027025, 929569.0 / 212837625)
_D = (2.0 / 15, -34.0 / 315, 62.0 / 945, -5528.0 / 155925, 21844.0 / 1216215, -1859138.0 / 212837625,
      6404582.0 / 1550674125)
_T = (1.0, -1.0 / 3, 2.0 / 15, -17.0 / 315, 62.0 / 2835, -1382.0 / 155925)
_S_ARR = np.array(_S)
_D_ARR = np.array(_D)
_T_ARR = np.array(_T)

# The kernels are module-level functions, compiled by :func:`_kernels` on first use (numba is
# imported only then). They call each other through the module's globals, not through a
# closure: numba keys its on-disk cache of a closure by its pickled cells, and a compiled
# function pickles with a per-process id, so closures calling closures were compiled anew in
# every process (4 s here) instead of loaded from the cache.


def _lc_poly(c: np.ndarray, x: float) -> float:
    out = c[c.shape[0] - 1]
    for i in range(c.shape[0] - 2, -1, -1):
        out = out * x + c[i]
    return out


def _lc_parts(u: float) -> tuple[float, float, float]:
    if u < 0.2:
        u2 = u * u
        return _lc_poly(_S_ARR, u2), _lc_poly(_D_ARR, u2), _lc_poly(_T_ARR, u2)
    th = math.tanh(u)
    ch = math.cosh(min(u, 350.0))
    return 3.0 * (u - th) / u ** 3, (1.0 + 0.5 / (ch * ch) - 1.5 * th / u) / u ** 4, th / u


def _lc_ratio(u: float) -> float:
    s, dq, _ = _lc_parts(u)
    return u * s * math.sqrt(2.0 / (27.0 * dq))


def _lc_psi(u: float) -> float:
    s, dq, _ = _lc_parts(u)
    return u * math.sqrt(2.0 / (27.0 * dq))  # ratio·φ = ratio/S


def _lc_solve(target: np.ndarray, which: int) -> np.ndarray:
    out = np.empty(target.shape[0])
    for k in range(target.shape[0]):
        t = target[k]
        lo = 0.0
        hi = 1.5 * t + 1e-300
        for _ in range(200):
            f = _lc_ratio(hi) if which == 0 else _lc_psi(hi)
            if not f < t:
                break
            hi = 2.0 * hi + 1.0
        if not t > 0.0:
            for _ in range(90):
                mid = 0.5 * (lo + hi)
                f = _lc_ratio(mid) if which == 0 else _lc_psi(mid)
                if f < t:
                    lo = mid
                else:
                    hi = mid
            out[k] = 0.5 * (lo + hi)
            continue
        # Illinois regula falsi in the bracket (both functions increase from 0): superlinear,
        # to the last bits in about ten evaluations where bisection took 90
        flo = -t
        fhi = (_lc_ratio(hi) if which == 0 else _lc_psi(hi)) - t
        side = 0
        res = 0.5 * (lo + hi)
        for _ in range(200):
            if fhi == 0.0:
                res = hi
                break
            mid = (lo * fhi - hi * flo) / (fhi - flo)
            if not (mid > lo and mid < hi):
                mid = 0.5 * (lo + hi)
                if not (mid > lo and mid < hi):
                    res = mid
                    break
            fm = (_lc_ratio(mid) if which == 0 else _lc_psi(mid)) - t
            if fm == 0.0:
                res = mid
                break
            if fm < 0.0:
                lo = mid
                flo = fm
                if side == -1:
                    fhi *= 0.5
                side = -1
            else:
                hi = mid
                fhi = fm
                if side == 1:
                    flo *= 0.5
                side = 1
            res = 0.5 * (lo + hi)
            if hi - lo <= 4e-16 * hi:
                break
        out[k] = res
    return out


def _lc_parts_arr(u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    a = np.empty(u.shape[0])
    b = np.empty(u.shape[0])
    c = np.empty(u.shape[0])
    for k in range(u.shape[0]):
        a[k], b[k], c[k] = _lc_parts(u[k])
    return a, b, c


_KERNEL_NAMES = ("_lc_poly", "_lc_parts", "_lc_ratio", "_lc_psi", "_lc_solve", "_lc_parts_arr")


@lru_cache(maxsize=1)
def _kernels() -> Any:
    from .jit import import_numba

    numba = import_numba()

    jit = numba.njit(cache=True, error_model="numpy")
    g = globals()
    for name in _KERNEL_NAMES:  # callees first: a caller is typed against its callees' dispatchers
        g[name] = jit(g[name])
    return g["_lc_solve"], g["_lc_parts_arr"]


# The same computations in NumPy, for a few rows without numba (:mod:`.jit`): every element takes
# the compiled kernel's operations in its order (``u ** 3`` is numba's ``u * (u * u)``, ``u ** 4``
# its ``(u * u) * (u * u)``; ``tanh`` and ``cosh`` the C library's, element by element, as in the
# kernel: NumPy's own may differ in the last bit), so the results are the compiled ones bit for bit.
_TANH = np.frompyfunc(math.tanh, 1, 1)
_COSH = np.frompyfunc(math.cosh, 1, 1)


def _np_poly(c: tuple[float, ...], x: np.ndarray) -> np.ndarray:
    out = np.full(x.shape, c[-1])
    for i in range(len(c) - 2, -1, -1):
        out = out * x + c[i]
    return out


def _np_parts(u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    s, d, t = np.empty(u.shape), np.empty(u.shape), np.empty(u.shape)
    small = u < 0.2
    us = u[small]
    u2 = us * us
    s[small], d[small], t[small] = _np_poly(_S, u2), _np_poly(_D, u2), _np_poly(_T, u2)
    big = ~small
    ub = u[big]
    th = _TANH(ub).astype(float)
    ch = _COSH(np.minimum(ub, 350.0)).astype(float)
    u2 = ub * ub
    s[big] = 3.0 * (ub - th) / (ub * u2)
    d[big] = (1.0 + 0.5 / (ch * ch) - 1.5 * th / ub) / (u2 * u2)
    t[big] = th / ub
    return s, d, t


def _np_value(u: np.ndarray, which: int) -> np.ndarray:
    s, dq, _ = _np_parts(u)
    root = np.sqrt(2.0 / (27.0 * dq))
    return u * s * root if which == 0 else u * root


def _np_solve(target: np.ndarray, which: int) -> np.ndarray:
    # _lc_solve on every element at once: the elements still searching are carried along
    t = target
    n = t.shape[0]
    out = np.empty(n)
    lo = np.zeros(n)
    hi = 1.5 * t + 1e-300
    grow = np.arange(n)
    for _ in range(200):
        if grow.size == 0:
            break
        grow = grow[_np_value(hi[grow], which) < t[grow]]
        hi[grow] = 2.0 * hi[grow] + 1.0
    zero = np.flatnonzero(~(t > 0.0))
    if zero.size:  # bisection
        lz, hz = lo[zero], hi[zero]
        for _ in range(90):
            mid = 0.5 * (lz + hz)
            below = _np_value(mid, which) < t[zero]
            lz, hz = np.where(below, mid, lz), np.where(below, hz, mid)
        out[zero] = 0.5 * (lz + hz)
    idx = np.flatnonzero(t > 0.0)
    tt = t[idx]
    lo, hi = lo[idx], hi[idx]
    flo = -tt
    fhi = _np_value(hi, which) - tt
    side = np.zeros(idx.size, dtype=np.int64)
    res = 0.5 * (lo + hi)
    live = np.arange(idx.size)
    for _ in range(200):  # Illinois regula falsi
        if live.size == 0:
            break
        a, b, fa, fb = lo[live], hi[live], flo[live], fhi[live]
        hit = fb == 0.0
        res[live[hit]] = b[hit]
        keep = ~hit
        live, a, b, fa, fb = live[keep], a[keep], b[keep], fa[keep], fb[keep]
        mid = (a * fb - b * fa) / (fb - fa)
        outside = ~((mid > a) & (mid < b))
        mid = np.where(outside, 0.5 * (a + b), mid)
        stuck = outside & ~((mid > a) & (mid < b))
        res[live[stuck]] = mid[stuck]
        keep = ~stuck
        live, a, b, fa, fb, mid = live[keep], a[keep], b[keep], fa[keep], fb[keep], mid[keep]
        fm = _np_value(mid, which) - tt[live]
        hit = fm == 0.0
        res[live[hit]] = mid[hit]
        keep = ~hit
        live, a, b, fa, fb, mid, fm = live[keep], a[keep], b[keep], fa[keep], fb[keep], mid[keep], fm[keep]
        sd = side[live]
        neg = fm < 0.0
        fb = np.where(neg & (sd == -1), fb * 0.5, fb)
        fa = np.where(~neg & (sd == 1), fa * 0.5, fa)
        a, fa = np.where(neg, mid, a), np.where(neg, fm, fa)
        b, fb = np.where(neg, b, mid), np.where(neg, fb, fm)
        side[live] = np.where(neg, -1, 1)
        lo[live], hi[live], flo[live], fhi[live] = a, b, fa, fb
        res[live] = 0.5 * (a + b)
        live = live[~(b - a <= 4e-16 * b)]
    out[idx] = res
    return out


def _solve(a: np.ndarray, which: int) -> np.ndarray:
    from .jit import interpreted

    flat = np.ascontiguousarray(a.ravel())
    if interpreted():
        with np.errstate(all="ignore"):
            return _np_solve(flat, which).reshape(a.shape)
    return _kernels()[0](flat, which).reshape(a.shape)


def leaf_parts(u: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """S(u), D(u)/u⁴ and tanh(u)/u for u ≥ 0 (arrays of u's shape)."""
    from .jit import interpreted

    a = np.asarray(u, dtype=float)
    flat = np.ascontiguousarray(a.ravel())
    if interpreted():
        with np.errstate(all="ignore"):
            s, d, t = _np_parts(flat)
    else:
        s, d, t = _kernels()[1](flat)
    return s.reshape(a.shape), d.reshape(a.shape), t.reshape(a.shape)


def tension_parameter(ratio: Any) -> np.ndarray:
    """u ≥ 0 with δ/y = ``ratio`` (bracketed Illinois regula falsi to machine precision, element by
    element)."""
    return _solve(np.abs(np.asarray(ratio, dtype=float)), 0)


def parameter_for_load(q: Any) -> np.ndarray:
    """u ≥ 0 with (δ/y)·φ = ``q`` = F/(K·y) (bracketed Illinois regula falsi, element by element)."""
    return _solve(np.abs(np.asarray(q, dtype=float)), 1)
