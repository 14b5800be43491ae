"""Compiled loops of the Gaussian-process engine (numba), for fits and predictions on
thousands of runs: the kernel's correlation matrix, the kriging mean at new settings with the
cross-correlations accumulated on the fly (never stored), and the trace sums of the
likelihood's analytic gradient.

The correlation matrices (the runs', :func:`symmetric`, and the predictions', :func:`cross`,
:func:`mean`) are computed by loops written for the vector units (:func:`_tile`): the runs laid
out contiguously per factor (:func:`prediction_layout`), three factors per pass over a tile of
runs with no branch per pair, Matérn 5/2's polynomial as ``(a + 3/2)^2 + 3/4``, a vectorised
exponential (:func:`_exp_row`, fdlibm's algorithm, within one unit in the last place of the C
library's) and fused multiply-adds; each point's mean sums its terms in :data:`LANES` partial
sums. Each correlation is then within ``2 (1 + t)`` units of ``eps`` (relative) of the exact
value, ``t`` the pair's exponent, as the NumPy code's in
:mod:`rsm_lrg.model.engines.gp_kernels` is (``tests/model/engines/test_gp_compiled.py``). The
gradient's sums (:func:`gradient_sums`) do, pair by pair, the NumPy code's arithmetic. The
functions below are plain Python until :func:`kernels` compiles them (once per process; numba
keeps the machine code on disk). Settings are passed transposed, ``(k, n)``, so that the loop
over runs reads memory in order.

Threads: numba's parallel layers are not safe here (GNU OpenMP ends a child forked after the
parent used it, so a GP predicted before ``--workers`` forks its pool would end its workers;
the workqueue layer aborts when two threads call in at once, as Dask's threads may). Instead
the loops are compiled ``nogil`` and :func:`run_split` runs blocks of rows on a few plain
Python threads (:func:`threads`: the usable cores, at most :data:`MAX_THREADS`), joined before
it returns, so no thread outlives a call and a later fork is safe. Every number is computed
by one thread in a fixed order (a point's sum, or a block's partial sums added in block order),
so the results are the same on any number of threads.

Kernel codes: 0 ``gauss``, 1 ``matern52``, 2 ``matern32``.
"""

from __future__ import annotations

import math
import os
import threading
from collections.abc import Callable, Sequence
from functools import lru_cache
from typing import Any

import numpy as np

__all__ = ["KERNEL_CODES", "MAX_THREADS", "PAIRS_PER_THREAD", "GRADIENT_BLOCK_ROWS", "EXP_CLAMP", "TILE", "LANES",
           "kernels", "scales", "prediction_layout", "cores", "threads", "run_split", "cross", "symmetric", "mean",
           "gradient_sums"]

#: The kernels' codes in the compiled loops.
KERNEL_CODES = {"gauss": 0, "matern52": 1, "matern32": 2}
_ROOT = {1: math.sqrt(5.0), 2: math.sqrt(3.0)}
#: At most this many threads per compiled pass (fewer where the process may use fewer cores).
MAX_THREADS = 8
#: A compiled pass takes one thread per this many pairs of settings (below, one thread).
PAIRS_PER_THREAD = 1 << 18
#: Rows of a block of the gradient's sums (the blocks, and so the numbers, do not depend on
#: the thread count).
GRADIENT_BLOCK_ROWS = 64
#: Runs per tile of the predictions' loops (their five scratch rows fit the first-level cache).
TILE = 512
#: Beyond this argument ``exp(-t)`` leaves the normal numbers; the vectorised exponential
#: hands such pairs to the C library.
EXP_CLAMP = 708.0
# fdlibm e_exp.c: ln 2 in two parts (k ln2_hi exact for |k| < 2^20), the rational
# approximation's coefficients; 1.5 * 2^52 rounds to an integer; the exponent bias
_INVLN2 = 1.44269504088896338700e+00
_LN2HI = 6.93147180369123816490e-01
_LN2LO = 1.90821492927058770002e-10
_P1 = 1.66666666666666019037e-01
_P2 = -2.77777777770155933842e-03
_P3 = 6.61375632143793436117e-05
_P4 = -1.65339022054652515390e-06
_P5 = 4.13813679705723846039e-08
_SHIFT = 6755399441055744.0
_BIAS = 1023 << 52
_EXP_CLAMP = EXP_CLAMP
_THIRD = 1.0 / 3.0
_TILE = TILE
_MIRROR = 64  # side of the blocks the runs' matrix is mirrored by
#: Partial sums of each point's kriging mean (the terms dealt by run index modulo this).
LANES = 8
_LANES = LANES


def scales(theta: np.ndarray, kernel: str) -> np.ndarray:
    """Per-factor multipliers of ``|h|`` in the loops: ``sqrt(5) / theta`` (Matérn 5/2),
    ``sqrt(3) / theta`` (Matérn 3/2); for ``gauss`` the length-scales themselves (the loop
    divides, as the NumPy code does).

    Parameters
    ----------
    theta : (k,) ndarray
        Length-scales [coded units].
    kernel : str
        One of the keys of :data:`KERNEL_CODES`.

    Returns
    -------
    (k,) ndarray
    """
    code = KERNEL_CODES[kernel]
    if code == 0:
        return np.ascontiguousarray(theta, dtype=float)
    return np.array([_ROOT[code] / float(t) for t in theta])


def _exp_row(m: int, buf: Any, bufi: Any) -> int:
    """``buf[2, l] * buf[4, l] = exp(-min(buf[0, l], EXP_CLAMP))`` for ``l < m``, in loops the
    compiler vectorises: Cody & Waite's reduction ``x = k ln 2 + r`` and the rational
    approximation of ``exp(r)`` of fdlibm's ``e_exp.c`` (Sun Microsystems 1993; error below
    one unit in the last place, as the C library's), the scale ``2^k`` built from its bits.
    ``buf[2]`` receives ``exp(r)``, ``buf[3]`` the shifted ``k`` (read as integers through
    ``bufi``), ``buf[4]`` the scale (written as integers through ``bufi``). Returns how many
    arguments were beyond :data:`EXP_CLAMP` (counted in the same vectorised loop)."""
    t = buf[0]
    y = buf[2]
    kd = buf[3]
    beyond = 0
    for l in range(m):
        tl = t[l]
        beyond += tl > _EXP_CLAMP
        x = -min(tl, _EXP_CLAMP)
        k = x * _INVLN2 + _SHIFT  # k rounded to the nearest integer, in the low bits
        kf = k - _SHIFT
        hi = x - kf * _LN2HI
        lo = kf * _LN2LO
        r = hi - lo
        rr = r * r
        cc = r - rr * (_P1 + rr * (_P2 + rr * (_P3 + rr * (_P4 + rr * _P5))))
        y[l] = 1.0 - ((lo - (r * cc) / (2.0 - cc)) - hi)
        kd[l] = k
    ki = bufi[3]
    sb = bufi[4]
    for l in range(m):
        sb[l] = (ki[l] << 52) + _BIAS  # 2^k: the exponent field k + 1023 (k >= -1022)
    return beyond


def _tile(x1s: Any, i: int, x2s: Any, l0: int, l1: int, c: Any, code: int, buf: Any, bufi: Any) -> int:
    """The parts of ``k(x1[i], x2[l]) / post`` for the runs ``l0 <= l < l1`` (a tile of at
    most :data:`TILE` runs, so that the scratch rows stay in the first-level cache), from the
    layout of :func:`prediction_layout` (``x1s``, ``x2s``: transposed settings, factors padded
    with zeros to a multiple of three; ``c`` their scales). Three factors per pass over the
    runs (contiguous, no branch per pair), then one vectorised exponential (:func:`_exp_row`;
    the C library's where the argument is beyond :data:`EXP_CLAMP`). Per factor ``d`` the
    scaled difference ``(x1_j - x2_j) c_j``: ``gauss`` adds ``d^2`` to the exponent; Matérn 3/2 adds
    ``a = |d|`` and multiplies the factor ``1 + a``; Matérn 5/2 adds ``a`` and multiplies
    ``(a + 3/2)^2 + 3/4 = 3 (1 + a + a^2/3)``, each pass's product times ``2^-5`` (exact; the
    products stay within ``27/32`` of ``prod (1 + a + a^2/3)``, so they overflow no sooner) and
    ``post = 32^(kp/3) / 3^kp`` restoring the scale; a padded factor adds 0 and multiplies
    exactly 1, or 3). Returns how many exponents are beyond
    :data:`EXP_CLAMP`; :func:`_finish` puts the correlations in ``buf[2]``."""
    kp = x1s.shape[0]
    m = l1 - l0
    total = buf[0]
    poly = buf[1]
    for j in range(0, kp, 3):
        x0 = x1s[j, i]
        x1 = x1s[j + 1, i]
        x2 = x1s[j + 2, i]
        r0 = x2s[j, l0:l1]
        r1 = x2s[j + 1, l0:l1]
        r2 = x2s[j + 2, l0:l1]
        c0 = c[j]
        c1 = c[j + 1]
        c2 = c[j + 2]
        if code == 0:
            if j == 0:
                for l in range(m):
                    d0 = (x0 - r0[l]) * c0
                    d1 = (x1 - r1[l]) * c1
                    d2 = (x2 - r2[l]) * c2
                    total[l] = d0 * d0 + d1 * d1 + d2 * d2
            else:
                for l in range(m):
                    d0 = (x0 - r0[l]) * c0
                    d1 = (x1 - r1[l]) * c1
                    d2 = (x2 - r2[l]) * c2
                    total[l] = total[l] + d0 * d0 + d1 * d1 + d2 * d2
        elif code == 1:
            if j == 0:
                for l in range(m):
                    a0 = abs(x0 - r0[l]) * c0
                    a1 = abs(x1 - r1[l]) * c1
                    a2 = abs(x2 - r2[l]) * c2
                    u0 = a0 + 1.5
                    u1 = a1 + 1.5
                    u2 = a2 + 1.5
                    total[l] = a0 + a1 + a2
                    poly[l] = ((u0 * u0 + 0.75) * (u1 * u1 + 0.75) * (u2 * u2 + 0.75)) * 0.03125
            else:
                for l in range(m):
                    a0 = abs(x0 - r0[l]) * c0
                    a1 = abs(x1 - r1[l]) * c1
                    a2 = abs(x2 - r2[l]) * c2
                    u0 = a0 + 1.5
                    u1 = a1 + 1.5
                    u2 = a2 + 1.5
                    total[l] = total[l] + a0 + a1 + a2
                    poly[l] = poly[l] * (((u0 * u0 + 0.75) * (u1 * u1 + 0.75) * (u2 * u2 + 0.75)) * 0.03125)
        else:
            if j == 0:
                for l in range(m):
                    a0 = abs(x0 - r0[l]) * c0
                    a1 = abs(x1 - r1[l]) * c1
                    a2 = abs(x2 - r2[l]) * c2
                    total[l] = a0 + a1 + a2
                    poly[l] = (1.0 + a0) * (1.0 + a1) * (1.0 + a2)
            else:
                for l in range(m):
                    a0 = abs(x0 - r0[l]) * c0
                    a1 = abs(x1 - r1[l]) * c1
                    a2 = abs(x2 - r2[l]) * c2
                    total[l] = total[l] + a0 + a1 + a2
                    poly[l] = poly[l] * ((1.0 + a0) * (1.0 + a1) * (1.0 + a2))
    return _exp_row(m, buf, bufi)


def _finish(m: int, code: int, beyond: int, buf: Any) -> None:
    """``buf[2, l] = k`` of the pairs of a tile from :func:`_tile`'s parts (the exponential's
    ``exp(r)`` and ``2^k``, the product of the factors' polynomials), the C library's
    exponential where the exponent is beyond :data:`EXP_CLAMP` (``beyond`` of them, from
    :func:`_tile`)."""
    total = buf[0]
    poly = buf[1]
    y = buf[2]
    scale = buf[4]
    if code == 0:
        for l in range(m):
            y[l] = y[l] * scale[l]
    else:
        for l in range(m):
            y[l] = (y[l] * scale[l]) * poly[l]
    if beyond:  # beyond the normal numbers: the C library's
        for l in range(m):
            if total[l] > _EXP_CLAMP:
                y[l] = math.exp(-total[l]) * (1.0 if code == 0 else poly[l])


def _cross_rows(x1s: Any, x2s: Any, c: Any, code: int, post: float, out: Any, start: int, stop: int, buf: Any,
                bufi: Any) -> None:
    """Rows ``start:stop`` of ``out[i, l] = k(x1[i], x2[l])`` (:func:`_tile`)."""
    n = x2s.shape[1]
    for i in range(start, stop):
        for l0 in range(0, n, _TILE):
            l1 = min(n, l0 + _TILE)
            _finish(l1 - l0, code, _tile(x1s, i, x2s, l0, l1, c, code, buf, bufi), buf)
            y = buf[2]
            for l in range(l1 - l0):
                out[i, l0 + l] = y[l] * post


def _symmetric_rows(xs: Any, c: Any, code: int, post: float, out: Any, start: int, stop: int, buf: Any,
                    bufi: Any) -> None:
    """Rows ``start:stop`` of ``out[i, l] = k(x[i], x[l])`` (:func:`_tile` against the runs
    before ``i``): the lower triangle computed, the upper mirrored in square blocks of
    :data:`_MIRROR` (rows ``start:stop`` fill columns ``start:stop`` above the diagonal, which
    no other block of rows writes), one on the diagonal."""
    for i in range(start, stop):
        for l0 in range(0, i, _TILE):
            l1 = min(i, l0 + _TILE)
            _finish(l1 - l0, code, _tile(xs, i, xs, l0, l1, c, code, buf, bufi), buf)
            y = buf[2]
            for l in range(l1 - l0):
                out[i, l0 + l] = y[l] * post
        out[i, i] = 1.0
    for i0 in range(start, stop, _MIRROR):  # the mirror by square blocks (in cache both ways)
        i1 = min(stop, i0 + _MIRROR)
        for l0 in range(0, i1, _MIRROR):
            for i in range(i0, i1):
                for l in range(l0, min(l0 + _MIRROR, i)):
                    out[l, i] = out[i, l]


def _mean_rows(x1s: Any, x2s: Any, c: Any, code: int, post: float, weights: Any, out: Any, start: int, stop: int,
               buf: Any, bufi: Any) -> None:
    """``out[i] = sum_l k(x1[i], x2[l]) weights[l]`` for ``i`` in ``start:stop`` (:func:`_tile`):
    the terms dealt to :data:`LANES` partial sums by ``l mod LANES`` (a vectorised loop), the
    lanes then added in order; a fixed order, whatever the threads."""
    n = x2s.shape[1]
    acc = np.empty(_LANES)
    poly = buf[1]
    y = buf[2]
    scale = buf[4]
    for i in range(start, stop):
        for q in range(_LANES):
            acc[q] = 0.0
        for l0 in range(0, n, _TILE):
            l1 = min(n, l0 + _TILE)
            m = l1 - l0
            w = weights[l0:l1]
            whole = m // _LANES
            beyond = _tile(x1s, i, x2s, l0, l1, c, code, buf, bufi)
            if beyond or code == 0:
                _finish(m, code, beyond, buf)
                for b in range(whole):
                    for q in range(_LANES):
                        acc[q] += y[b * _LANES + q] * w[b * _LANES + q]
                for l in range(whole * _LANES, m):
                    acc[l - whole * _LANES] += y[l] * w[l]
            else:  # the same operations, _finish's product taken in the loop
                for b in range(whole):
                    for q in range(_LANES):
                        l = b * _LANES + q
                        acc[q] += ((y[l] * scale[l]) * poly[l]) * w[l]
                for l in range(whole * _LANES, m):
                    acc[l - whole * _LANES] += ((y[l] * scale[l]) * poly[l]) * w[l]
        total = 0.0
        for q in range(_LANES):
            total += acc[q]
        out[i] = total * post


def _gradient_block(xt: Any, c: Any, code: int, R: Any, minv: Any, w: Any, kappa: float, start: int, stop: int,
                    out: Any) -> None:
    """Over the pairs ``i > l`` with ``start <= i < stop``: ``out[j] = sum g_il R_il
    dlogR_il/dlog theta_j`` for ``j < k`` and ``out[k] = sum g_il R_il``, with ``g = kappa
    w_i w_l - minv_il`` (``minv``'s lower triangle read)."""
    k = xt.shape[0]
    for j in range(k + 1):
        out[j] = 0.0
    total = 0.0
    for i in range(start, stop):
        wi = kappa * w[i]
        for l in range(i):
            g = (wi * w[l] - minv[i, l]) * R[i, l]
            total += g
            for j in range(k):
                if code == 0:
                    h = (xt[j, i] - xt[j, l]) / c[j]
                    out[j] += g * (h * h)
                else:
                    a = abs(xt[j, i] - xt[j, l]) * c[j]
                    if code == 1:
                        out[j] += g * (a * a * (1.0 + a) / (3.0 * (1.0 + a + a * a / 3.0)))
                    else:
                        out[j] += g * (a * a / (1.0 + a))
    out[k] = total


_LOOPS = ("_gradient_block", "_exp_row", "_tile", "_finish", "_symmetric_rows", "_cross_rows",
          "_mean_rows")  # the callees first
#: The correlation loops, compiled with fused multiply-adds (``a * b + c`` rounded once; the
#: gradient's sums keep NumPy's separate roundings).
_FUSED = ("_exp_row", "_tile", "_finish", "_symmetric_rows", "_cross_rows", "_mean_rows")


_COMPILING = threading.Lock()


def kernels() -> dict[str, Any]:
    """Compile the loops (once per process, under a lock: two threads asking first, as Dask's
    threads may, compile once; numba caches the machine code on disk). They hold no lock and
    no Python object (``nogil``), so that several Python threads run them at once.

    Returns
    -------
    dict
        ``{"symmetric_rows", "gradient_block", "cross_rows", "mean_rows", "exp_row"}`` to the
        compiled functions; their arguments are those of the functions of the same names with
        a leading underscore.
    """
    with _COMPILING:
        return _compiled()


@lru_cache(maxsize=1)
def _compiled() -> dict[str, Any]:
    import numba

    g = globals()
    jit = numba.njit(cache=True, fastmath=False, error_model="numpy", nogil=True)
    fused = numba.njit(cache=True, fastmath={"contract"}, error_model="numpy", nogil=True)
    for name in _LOOPS:
        g[name] = (fused if name in _FUSED else jit)(g[name])
    return {name.lstrip("_"): g[name] for name in _LOOPS if name not in ("_tile", "_finish")}


def threads(pairs: int) -> int:
    """The Python threads a compiled pass over ``pairs`` pairs of settings runs on: the
    cores this process may use (``os.sched_getaffinity``), at most :data:`MAX_THREADS` (or
    the environment's ``RSM_LRG_GP_THREADS``), and one per :data:`PAIRS_PER_THREAD` pairs;
    one inside a task of :func:`run_split` (no threads within threads).

    Parameters
    ----------
    pairs : int
        Pairs of settings the pass computes.

    Returns
    -------
    int
        At least 1.
    """
    return max(1, min(cores(), pairs // PAIRS_PER_THREAD))


def cores() -> int:
    """The threads a parallel step of the GP engine may use: the cores this process may use
    (``os.sched_getaffinity``), at most :data:`MAX_THREADS` or the environment's
    ``RSM_LRG_GP_THREADS``; 1 inside a task of :func:`run_split` (no threads within threads).

    Returns
    -------
    int
        At least 1.
    """
    if getattr(_INSIDE, "split", False):  # already on one of run_split's threads
        return 1
    try:
        usable = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # not on Linux
        usable = os.cpu_count() or 1
    cap = MAX_THREADS
    given = os.environ.get("RSM_LRG_GP_THREADS", "").strip()
    if given.isdigit() and int(given) > 0:
        cap = int(given)
    return max(1, min(usable, cap))


_INSIDE = threading.local()


def run_split(task: Callable[[int, int], None], bounds: Sequence[int], count: int) -> None:
    """Run ``task(bounds[b], bounds[b + 1])`` for every block ``b``, the blocks dealt in
    ``count`` contiguous groups to as many threads (the caller's thread takes the first).
    Every thread has ended when this returns (so a later ``fork`` copies none), and an
    exception in one is raised here.

    Parameters
    ----------
    task : callable
        ``task(start, stop)``, a compiled ``nogil`` loop over rows ``start:stop``.
    bounds : sequence of int
        Block boundaries, increasing; the blocks do not depend on ``count``.
    count : int
        Threads to use.
    """
    blocks = len(bounds) - 1
    count = max(1, min(int(count), blocks))
    cuts = [round(t * blocks / count) for t in range(count + 1)]
    errors: list[BaseException] = []

    def group(t: int) -> None:
        outer = getattr(_INSIDE, "split", False)
        _INSIDE.split = True
        try:
            for b in range(cuts[t], cuts[t + 1]):
                task(bounds[b], bounds[b + 1])
        except BaseException as exc:
            errors.append(exc)
        finally:
            _INSIDE.split = outer

    others = [threading.Thread(target=group, args=(t,), daemon=True) for t in range(1, count)]
    for th in others:
        th.start()
    group(0)
    for th in others:
        th.join()
    if errors:
        raise errors[0]


def _row_blocks(m: int, count: int) -> list[int]:
    """``count`` nearly equal blocks of rows ``0:m``."""
    return [round(t * m / count) for t in range(count + 1)]


def _scratch() -> tuple[np.ndarray, np.ndarray]:
    buf = np.empty((5, TILE))
    return buf, buf.view(np.int64)


def cross(x1: np.ndarray, x2: np.ndarray, theta: np.ndarray, kernel: str) -> np.ndarray:
    """The correlation matrix ``R[i, l] = k(x1[i], x2[l])``, rows computed on :func:`threads`
    threads (each entry by one thread; the same numbers on any number of threads).

    Parameters
    ----------
    x1, x2 : (m, k) and (n, k) ndarray
        Settings [coded units].
    theta : (k,) ndarray
        Length-scales [coded units].
    kernel : str
        One of the keys of :data:`KERNEL_CODES`.

    Returns
    -------
    (m, n) ndarray
    """
    return _tiled_rows("cross_rows", x1, x2, theta, kernel, np.empty((x1.shape[0], x2.shape[0])))


def prediction_layout(x: np.ndarray, theta: np.ndarray, kernel: str) -> tuple[np.ndarray, np.ndarray, float]:
    """Settings as the predictions' loops read them: transposed, ``(kp, n)``, padded with rows
    of zeros to ``kp``, a multiple of three factors; the factors' scales (``sqrt(5) / theta``
    for Matérn 5/2, ``sqrt(3) / theta`` for Matérn 3/2, ``1 / (sqrt(2) theta)`` for ``gauss``,
    1 for a padded factor), so that a pair's exponent is a sum of ``|d|`` or ``d^2`` over the
    scaled differences ``d = (x_j - x'_j) c_j``; and the factor ``post`` that the loops'
    products carry (``32^(kp/3) / 3^kp`` for Matérn 5/2, else 1). The differences are taken before the
    scaling, so that each exponent's rounding stays relative to the exponent.

    Parameters
    ----------
    x : (n, k) ndarray
        Settings [coded units].
    theta : (k,) ndarray
        Length-scales [coded units].
    kernel : str
        One of the keys of :data:`KERNEL_CODES`.

    Returns
    -------
    xs : (kp, n) ndarray
        Transposed, padded settings [coded units], C order.
    c : (kp,) ndarray
        Scale of each factor [1/coded unit].
    post : float
        Multiplier of the loops' correlations [-].
    """
    code = KERNEL_CODES[kernel]
    theta = np.asarray(theta, dtype=float)
    k = theta.size
    kp = 3 * max(1, -(-k // 3))
    xs = np.zeros((kp, x.shape[0]))
    xs[:k] = np.asarray(x, dtype=float).T
    c = np.ones(kp)
    c[:k] = 1.0 / (math.sqrt(2.0) * theta) if code == 0 else _ROOT[code] / theta
    return xs, c, (2.0 ** (5 * (kp // 3)) / 3.0 ** kp if code == 1 else 1.0)


def _tiled_rows(name: str, x1: np.ndarray, x2: np.ndarray, theta: np.ndarray, kernel: str, out: np.ndarray,
                *inputs: np.ndarray) -> np.ndarray:
    """Run the compiled tile loop ``name`` (``fn(x1s, x2s, c, code, post, *inputs, out, start, stop,
    scratch...)``, :func:`prediction_layout`) over the rows of ``x1`` against every row of ``x2``,
    in nearly equal blocks of rows on :func:`threads` threads, each thread with its own scratch;
    ``out`` filled and returned."""
    fn = kernels()[name]
    m = x1.shape[0]
    x1s, c, post = prediction_layout(x1, theta, kernel)
    x2s, _, _ = prediction_layout(x2, theta, kernel)
    count = threads(m * x2.shape[0])
    _on_threads(fn, (x1s, x2s, c, KERNEL_CODES[kernel], post, *inputs, out), _row_blocks(m, count), count)
    return out


def _on_threads(fn: Any, args: tuple, blocks: list[int], count: int) -> None:
    """``fn(*args, start, stop, scratch...)`` for each block ``blocks[t]:blocks[t + 1]`` of rows,
    on ``count`` threads (:func:`run_split`), each thread with its own scratch."""

    def task(start: int, stop: int) -> None:
        buf, bufi = _scratch()
        fn(*args, start, stop, buf, bufi)

    run_split(task, blocks, count)


def symmetric(x: np.ndarray, theta: np.ndarray, kernel: str) -> np.ndarray:
    """The correlation matrix ``R[i, l] = k(x[i], x[l])`` (the lower triangle computed by the
    predictions' tiles, the upper mirrored, ones on the diagonal), rows on :func:`threads`
    threads in blocks of nearly equal pairs.

    Parameters
    ----------
    x : (n, k) ndarray
        Settings [coded units].
    theta : (k,) ndarray
        Length-scales [coded units].
    kernel : str
        One of the keys of :data:`KERNEL_CODES`.

    Returns
    -------
    (n, n) ndarray
    """
    fn = kernels()["symmetric_rows"]
    n = x.shape[0]
    out = np.empty((n, n))
    xs, c, post = prediction_layout(x, theta, kernel)
    count = threads(n * n // 2)
    _on_threads(fn, (xs, c, KERNEL_CODES[kernel], post, out), _triangle_blocks(n, count), count)
    return out


def _triangle_blocks(n: int, count: int) -> list[int]:
    """``count`` blocks of the rows of a lower triangle with nearly equal pairs each."""
    return [int(round(n * math.sqrt(t / count))) for t in range(count + 1)]


def mean(points: np.ndarray, runs: np.ndarray, theta: np.ndarray, kernel: str, weights: np.ndarray) -> np.ndarray:
    """``sum_l k(points[i], runs[l]) weights[l]`` for every point, the cross-correlations
    never stored; points on :func:`threads` threads, each point's sum by one thread in the
    order of ``l`` (the same numbers on any number of threads).

    Parameters
    ----------
    points : (m, k) ndarray
        Settings [coded units].
    runs : (n, k) ndarray
        The runs' settings [coded units].
    theta : (k,) ndarray
        Length-scales [coded units].
    kernel : str
        One of the keys of :data:`KERNEL_CODES`.
    weights : (n,) ndarray
        Weight of each run.

    Returns
    -------
    (m,) ndarray
    """
    return _tiled_rows("mean_rows", points, runs, theta, kernel, np.empty(points.shape[0]),
                       np.ascontiguousarray(weights, dtype=float))


def gradient_sums(x: np.ndarray, theta: np.ndarray, kernel: str, R: np.ndarray, minv: np.ndarray, w: np.ndarray,
                  kappa: float, out: np.ndarray) -> float:
    """The likelihood gradient's sums over the pairs of runs ``i > l``: ``out[j] = sum g_il
    R_il d log R_il / d log theta_j``, ``g = kappa w_i w_l - minv_il``. The rows are cut into
    blocks of :data:`GRADIENT_BLOCK_ROWS` whatever the thread count, each block's partial sums
    are kept and added in block order: the same numbers on any number of threads.

    Parameters
    ----------
    x : (n, k) ndarray
        Coded settings.
    theta : (k,) ndarray
        Length-scales [coded units].
    kernel : str
        One of the keys of :data:`KERNEL_CODES`.
    R : (n, n) ndarray
        Correlation matrix.
    minv : (n, n) ndarray
        Lower triangle of the covariance's inverse.
    w : (n,) ndarray
        ``M^-1 z``.
    kappa : float
        Weight of ``w w'``.
    out : (k,) ndarray
        Receives the sums per factor.

    Returns
    -------
    float
        ``sum g_il R_il`` over the same pairs.
    """
    fn = kernels()["gradient_block"]
    n, k = x.shape
    xt = np.ascontiguousarray(x.T, dtype=float)
    c, code = scales(theta, kernel), KERNEL_CODES[kernel]
    minv = np.ascontiguousarray(minv)
    bounds = list(range(0, n, GRADIENT_BLOCK_ROWS)) + [n]
    parts = np.zeros((len(bounds) - 1, k + 1))
    first = {b: i for i, b in enumerate(bounds[:-1])}
    kap = float(kappa)
    run_split(lambda start, stop: fn(xt, c, code, R, minv, w, kap, start, stop, parts[first[start]]), bounds,
              threads(n * n // 2))
    total = np.zeros(k + 1)
    for part in parts:  # in block order
        total += part
    out[:] = total[:k]
    return float(total[k])
