"""Compiled loops of the Gaussian-process engine (numba), for fits and predictions on
thousands of runs: the kernel's correlation matrix, the kriging mean at new settings with the
cross-correlations accumulated on the fly (never stored), and the trace sums of the
likelihood's analytic gradient.

Each loop does, pair by pair, the arithmetic of the NumPy code in
:mod:`rsm_lrg.model.engines.gp_kernels` (the same operations in the same order per pair, the
exponential from the C library), so the two agree to a few units in the last place
(``tests/model/engines/test_gp_compiled.py``). The functions below are plain Python until
:func:`kernels` compiles them (once per process; numba keeps the machine code on disk).
Settings are passed transposed, ``(k, n)``, so that the loop over runs reads memory in order.
The loops run on one thread: numba's parallel layers are not safe here (GNU OpenMP ends a
child forked after the parent used it, so a GP predicted before ``--workers`` forks its pool
would end its workers; the workqueue layer aborts when two threads call in at once, as Dask's
threads may), and CPU time, not wall time, is what a busy two-core machine has to spare.

Kernel codes: 0 ``gauss``, 1 ``matern52``, 2 ``matern32``.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

import numpy as np

__all__ = ["KERNEL_CODES", "kernels", "scales"]

#: The kernels' codes in the compiled loops.
KERNEL_CODES = {"gauss": 0, "matern52": 1, "matern32": 2}
_ROOT = {1: math.sqrt(5.0), 2: math.sqrt(3.0)}


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


def _pair(x1t: Any, i: int, x2t: Any, l: int, c: Any, code: int) -> float:
    """The correlation of ``x1[i]`` and ``x2[l]``."""
    k = x1t.shape[0]
    total = 0.0
    if code == 0:
        for j in range(k):
            h = (x1t[j, i] - x2t[j, l]) / c[j]
            total += h * h
        return math.exp(total * -0.5)
    poly = 1.0
    for j in range(k):
        a = abs(x1t[j, i] - x2t[j, l]) * c[j]
        total += a
        if code == 1:
            poly *= 1.0 + a * (1.0 + a / 3.0)
        else:
            poly *= 1.0 + a
    return math.exp(-total) * poly


def _cross(x1t: Any, x2t: Any, c: Any, code: int, out: Any) -> None:
    """``out[i, l] = k(x1[i], x2[l])``."""
    m = x1t.shape[1]
    n = x2t.shape[1]
    for i in range(m):
        for l in range(n):
            out[i, l] = _pair(x1t, i, x2t, l, c, code)


def _symmetric(xt: Any, c: Any, code: int, out: Any) -> None:
    """``out[i, l] = k(x[i], x[l])``: the lower triangle computed, the upper mirrored, ones on
    the diagonal."""
    n = xt.shape[1]
    for i in range(n):
        for l in range(i):
            out[i, l] = _pair(xt, i, xt, l, c, code)
        out[i, i] = 1.0
    for i in range(n):
        for l in range(i):
            out[l, i] = out[i, l]


def _mean(x1t: Any, x2t: Any, c: Any, code: int, weights: Any, out: Any) -> None:
    """``out[i] = sum_l k(x1[i], x2[l]) weights[l]``, in the order of ``l``."""
    m = x1t.shape[1]
    n = x2t.shape[1]
    for i in range(m):
        acc = 0.0
        for l in range(n):
            acc += _pair(x1t, i, x2t, l, c, code) * weights[l]
        out[i] = acc


def _gradient_sums(xt: Any, c: Any, code: int, R: Any, minv: Any, w: Any, kappa: float, out: Any) -> float:
    """Over the pairs ``i > l``: ``out[j] = sum g_il R_il dlogR_il/dlog theta_j`` with
    ``g = kappa w_i w_l - minv_il`` (``minv``'s lower triangle read); returns
    ``sum g_il R_il`` over the same pairs."""
    k = xt.shape[0]
    n = xt.shape[1]
    for j in range(k):
        out[j] = 0.0
    total = 0.0
    for i in range(n):
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
    return total


_LOOPS = ("_pair", "_symmetric", "_gradient_sums", "_cross", "_mean")  # the callee first


@lru_cache(maxsize=1)
def kernels() -> dict[str, Any]:
    """Compile the loops (once per process; numba caches the machine code on disk).

    Returns
    -------
    dict
        ``{"cross", "symmetric", "mean", "gradient_sums"}`` to the compiled functions; their
        arguments are those of the functions of the same names with a leading underscore.
    """
    import numba

    g = globals()
    jit = numba.njit(cache=True, fastmath=False, error_model="numpy")
    for name in _LOOPS:
        g[name] = jit(g[name])
    return {name.lstrip("_"): g[name] for name in _LOOPS if name != "_pair"}
