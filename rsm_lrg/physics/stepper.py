"""Compiled stick-slip integrator of the RFCMS, one row at a time (:func:`.dynamics.cycle_metrics`).

The frame of the rigid-flexible stage obeys (:mod:`.dynamics`)

    m_f·ẍ_rf = F_h(x_ws − x_rf) + C_n·(ẋ_ws − ẋ_rf) − σ·µ_k·F_z − c_v·ẋ_rf     (sliding, σ = sign ẋ_rf)

with the hinge force F_h of the small-deflection hinge (n·K_n·z, Eq. 1) or of leaves with held
ends (exact beam-column law, ``n·K_n·y·ψ(z/y)``, :func:`.hinge.leaf_force_table`), and stays
put while stuck until ``|F_h + C_n·ẋ_ws| > µ_s·F_z`` (Eq. 2). The stage's profile is cut at
its kinks into segments on which the stage moves on a polynomial (constant acceleration for
the trapezoid, constant jerk for S-curve strokes), so the right-hand side is smooth inside a
segment. Each segment is crossed in equal steps of the explicit Runge-Kutta method of order 8
of Dormand & Prince (DOP853's tableau, :mod:`.dop853`, SciPy's numbers) with
``ω·Δt ≤ h``, ω the hinge's tangent angular frequency at a bound of the deflection; a stop
(ẋ_rf reaching 0) is located inside a step by the Illinois variant of regula falsi on the
Runge-Kutta step's own length, and a breakaway (``|F_h + C_n·ẋ_ws| = µ_s·F_z``, the frame at
rest, the stage on its polynomial) by bisection to machine precision. That is the reference
(``method="fixed"``, :func:`.dynamics.cycle_metrics` with ``integrator="compiled"``).

The default (``method="adaptive"`` of :func:`integrate_rows`, ``integrator="adaptive"`` of
:func:`.dynamics.cycle_metrics`, the default there too) takes the same order-8 steps with their length controlled by
DOP853's embedded error estimate (the 5th- and 3rd-order estimators of Hairer et al., as in
:class:`scipy.integrate.DOP853`; local error per step below ``tol`` times the breakaway
deflection f_µmax/(m_f·ω²) and its speed, ω·Δt ≤ ``h_max``), the last stage reused as the next
step's first (FSAL), a stop located by regula falsi on the step's 7th-order dense output, and
the peak deflection refined on the dense output (Newton on ż = 0) where the step's Hermite
cubic puts a peak near the largest so far. A stuck frame still checks breakaway on the grid
ω·Δt ≤ ``h``; its deflection is a cubic in t there, so the Hermite peak is exact.
Why not the exact propagator of the linear spring-damper between events: the leaves with held
ends are not linear anywhere in the Table 3 box to 1e-6 (at δ/y = 0.01 the force is already
7e-5 above K_n·δ, and the deflections reach 10 thicknesses, where the tangent stiffness is 50
times K_n), so a linear step would need a nonlinear correction integrated as finely as the
whole force. Measured: 730 steps per row at ``tol`` 1e-6 against 1,390 (stop location
included) in equal steps of 0.6, and the peak no longer carries the Hermite error of the
equal steps (1e-4 to 2e-3).

Each row is integrated alone in compiled code (numba): its result does not depend on the rows
of its batch or on the number of worker processes, and there is no per-step Python overhead.
Both kernels are module-level functions compiled on first use and loaded from numba's disk
cache in every later process (pool workers included). The stiction force passed in is the force
a stuck frame holds, ``max(µ_s, µ_k)·F_z`` (:func:`.dynamics.cycle_metrics`): with µ_k > µ_s
the switch model has no slip below µ_k·F_z, and breakaway and stop would chatter.

What limits the accuracy is not the step but the periodic state: a row runs from rest until two
successive cycles' sliding agree within ``rtol`` (at least 3 cycles). With the earlier 1e-5 and at
most 12 cycles, on 2,000 rows of the
Table 3 box (the shipped viscous friction, half of them S-curve strokes;
``python benchmarks/bench_dynamics.py --rows --convergence 2000``) that stops after 4.2 cycles on
average, and against the periodic state itself (cycles within 1e-10, up to 40, at ω·Δt = 0.2;
1,837 rows settle) the sliding is then off by up to 2.4e-3 (956 rows beyond 1e-6) and the peak
by up to 3.8 %: some rows drift slowly for ten cycles or more (a nearly neutral stick-slip phase)
before they settle, and the peak still carries the start-up oscillation. Both kernels stop after
the same cycles, so they agree with each other far better (median 1e-9) than with the periodic
state. ``rtol`` = 1e-8 with up to 40 cycles, the default of :func:`.dynamics.cycle_metrics`
now, comes within 1e-6 in sliding on all but 1 settled row and in viscous work on all but 7, at
8.8 cycles a row, where the adaptive kernel costs what the equal steps cost at 1e-5 (the peak:
207 rows beyond 1e-6, up to 3.6e-3, against the reference's own Hermite peak at ω·Δt = 0.2,
good to about 1e-5).

References
----------
Hairer, E., Nørsett, S.P. & Wanner, G. (1993), *Solving Ordinary Differential Equations I*,
2nd ed., Springer, Section II.10 (DOP853). Karnopp (1985); Leine et al. (1998) (switch model).
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

import numpy as np

from . import motion
from .hinge import LEAF_TABLE_MAX_RATIO, leaf_force_table
from .jit import run_kernel

__all__ = ["integrate_rows", "stage_segments", "leaf_psi", "leaf_dpsi", "MAX_SEGMENTS"]

#: Segments of one cycle: two strokes of at most 7 pieces (S-curve) and two dwells.
MAX_SEGMENTS = 16


@lru_cache(maxsize=1)
def _table() -> tuple[np.ndarray, float]:
    return leaf_force_table()


def leaf_psi(r: Any) -> np.ndarray:
    """ψ(r) = r·φ(r) of the tabulated beam-column law (odd in r), for numpy arrays."""
    tab, step = _table()
    r = np.asarray(r, dtype=float)
    a = np.minimum(np.abs(r), LEAF_TABLE_MAX_RATIO * (1 - 1e-12))
    i = (a / step).astype(np.int64)
    t = a - i * step
    c = tab[i]
    return np.sign(r) * (c[..., 0] + t * (c[..., 1] + t * (c[..., 2] + t * c[..., 3])))


def leaf_dpsi(r: Any) -> np.ndarray:
    """dψ/dr of the tabulated law (the tangent stiffness over n·K_n), for numpy arrays."""
    tab, step = _table()
    a = np.minimum(np.abs(np.asarray(r, dtype=float)), LEAF_TABLE_MAX_RATIO * (1 - 1e-12))
    i = (a / step).astype(np.int64)
    t = a - i * step
    c = tab[i]
    return c[..., 1] + t * (2.0 * c[..., 2] + 3.0 * t * c[..., 3])


def stage_segments(s: np.ndarray, v: np.ndarray, a: np.ndarray, dw: np.ndarray,
                   tj: np.ndarray) -> tuple[np.ndarray, ...]:
    """The cycle of every row cut at the kinks of the stage's profile (rows × MAX_SEGMENTS):
    start time [s], length [s] (0 for unused entries), stage position [m], velocity [m/s],
    acceleration [m/s²] at the start and the jerk [m/s³] of each segment, from the exact
    profile of :func:`.motion.reciprocating_profile`."""
    n = len(s)
    kinks = motion.stroke_kinks(s, v, a, tj)  # (n, 4) or (n, 8)
    if kinks.shape[-1] == 4:
        kinks = np.concatenate([kinks, kinks[:, -1:].repeat(4, axis=1)], axis=1)
    tsj = kinks[:, -1]
    # one stroke: 7 pieces between the kinks, then the dwell; the return stroke the same
    one = np.concatenate([kinks, (tsj + dw)[:, None]], axis=1)  # 9 boundaries
    bounds = np.concatenate([one[:, :-1], tsj[:, None] + dw[:, None] + one], axis=1)  # 17
    t0 = bounds[:, :-1]
    L = np.maximum(bounds[:, 1:] - t0, 0.0)
    T = motion.cycle_time(s, v, a, dw, tj)
    L[:, -1] = np.maximum(T - t0[:, -1], 0.0)  # the last segment ends exactly at T

    def prof(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        b = (s, v, a, dw, tj)
        x, vel, acc = motion.reciprocating_profile(t, *(np.broadcast_to(q[:, None], t.shape) for q in b))
        return x, vel, acc

    x0, v0, _ = prof(np.minimum(t0, T[:, None] * (1 - 1e-15)))
    x0 = np.where(t0 <= 0.0, 0.0, x0)
    _, _, a1 = prof(t0 + 0.25 * L)
    _, _, a3 = prof(t0 + 0.75 * L)
    with np.errstate(divide="ignore", invalid="ignore"):
        jerk = np.where(L > 0, (a3 - a1) / (0.5 * L), 0.0)
    acc0 = a1 - 0.25 * L * jerk
    del n
    return (np.ascontiguousarray(t0), np.ascontiguousarray(L), np.ascontiguousarray(x0),
            np.ascontiguousarray(v0), np.ascontiguousarray(acc0), np.ascontiguousarray(jerk))


# The reference kernel (equal steps): module-level functions compiled by :func:`_kernel` on first
# use, like the adaptive kernel below (a closure calling other compiled closures is not loaded
# from numba's disk cache). DOP853's 12-stage tableau is filled in before the first compilation.
_FK_A = np.zeros((12, 12))
_FK_B = np.zeros(12)
_FK_C = np.zeros(12)


def _settled(cyc: int, this: float, prev: float, n_cycles: int, max_cycles: int, rtol: float) -> bool:
    # at least n_cycles, then until two successive cycles' sliding agree within rtol (or max_cycles)
    return cyc >= n_cycles and (abs(this - prev) <= rtol * max(this, 1e-300) or cyc >= max_cycles)


def _falsi_point(a_: float, fa: float, b_: float, fb: float) -> float:
    # the regula falsi point of the bracket [a_, b_] (fa > 0 >= fb), its midpoint if it falls outside
    tc = (a_ * fb - b_ * fa) / (fb - fa)
    if not (tc > a_ and tc < b_):
        tc = 0.5 * (a_ + b_)
    return tc


def _illinois(a_: float, fa: float, b_: float, fb: float, side: int, tc: float,
              fc: float) -> tuple[float, float, float, float, int]:
    # the bracket after the value fc at tc, halving the value kept twice in a row (Illinois)
    if fc > 0.0:
        a_ = tc
        fa = fc
        if side == -1:
            fb *= 0.5
        side = -1
    else:
        b_ = tc
        fb = fc
        if side == 1:
            fa *= 0.5
        side = 1
    return a_, fa, b_, fb, side


def _put_row(out: np.ndarray, row: int, this: float, prev: float, vthis: float, vprev: float, peak: float,
             bad: float, nsteps: int, cyc: int) -> None:
    # one row's result: mean sliding and viscous work of the last two cycles, the last cycle's peak,
    # the periodicity error, the failure flag, steps and cycles taken
    out[row, 0] = 0.5 * (this + prev)
    out[row, 1] = peak
    out[row, 2] = abs(this - prev)
    out[row, 3] = 0.5 * (vthis + vprev)
    out[row, 4] = bad
    out[row, 5] = nsteps
    out[row, 6] = cyc


def _fk_hinge_f(z: float, k: float, y: float, tab: np.ndarray, step: float, rmax: float) -> float:
    if y <= 0.0:
        return k * z
    r = abs(z) / y
    if r >= rmax:
        return np.nan
    i = int(r / step)
    t = r - i * step
    psi = tab[i, 0] + t * (tab[i, 1] + t * (tab[i, 2] + t * tab[i, 3]))
    return k * y * psi if z >= 0.0 else -k * y * psi


def _fk_herm_max(z0: float, d0: float, z1: float, d1: float, dt: float) -> float:
    # largest |p| of the cubic Hermite interpolant of z over a step (z, ż at both ends)
    best = max(abs(z0), abs(z1))
    qa = 6.0 * z0 + 3.0 * dt * d0 - 6.0 * z1 + 3.0 * dt * d1
    qb = -6.0 * z0 - 4.0 * dt * d0 + 6.0 * z1 - 2.0 * dt * d1
    qc = dt * d0
    roots = np.empty(2)
    nr = 0
    if abs(qa) > 1e-300:
        disc = qb * qb - 4.0 * qa * qc
        if disc >= 0.0:
            sq = math.sqrt(disc)
            roots[0] = (-qb - sq) / (2.0 * qa)
            roots[1] = (-qb + sq) / (2.0 * qa)
            nr = 2
    elif abs(qb) > 1e-300:
        roots[0] = -qc / qb
        nr = 1
    for i in range(nr):
        r = roots[i]
        if 0.0 < r < 1.0:
            w1 = 1.0 - r
            h00 = (1.0 + 2.0 * r) * (w1 * w1)  # (1 - r)**2 as numba computes it: the same in Python
            h10 = r * (w1 * w1)
            h01 = r * r * (3.0 - 2.0 * r)
            h11 = r * r * (r - 1.0)
            p = h00 * z0 + h10 * dt * d0 + h01 * z1 + h11 * dt * d1
            if abs(p) > best:
                best = abs(p)
    return best


def _fk_rk_step(t: float, X: np.ndarray, tau: float, sig: float, sx: float, sv: float, sa: float, sj: float,
            k: float, y: float, c: float, m: float, fk: float, cv: float, tab: np.ndarray, step: float,
            rmax: float, K: np.ndarray, out: np.ndarray) -> None:
    # state X = (x_rf, u, viscous work); t is the time since the segment's start
    for i in range(12):
        ti = t + _FK_C[i] * tau
        x = X[0]
        u = X[1]
        for j in range(i):
            aij = _FK_A[i, j]
            if aij != 0.0:
                x += tau * aij * K[j, 0]
                u += tau * aij * K[j, 1]
        xs = sx + ti * (sv + ti * (0.5 * sa + ti * sj / 6.0))
        vs = sv + ti * (sa + 0.5 * sj * ti)
        fh = _fk_hinge_f(xs - x, k, y, tab, step, rmax)
        K[i, 0] = u
        K[i, 1] = (fh + c * (vs - u) - sig * fk - cv * u) / m
        K[i, 2] = cv * u * u
    for q in range(3):
        acc = 0.0
        for i in range(12):
            acc += _FK_B[i] * K[i, q]
        out[q] = X[q] + tau * acc


def _fk_brk(t: float, xf: float, sx: float, sv: float, sa: float, sj: float, k: float, y: float, c: float,
        tab: np.ndarray, step: float, rmax: float) -> float:
    xs = sx + t * (sv + t * (0.5 * sa + t * sj / 6.0))
    vs = sv + t * (sa + 0.5 * sj * t)
    return _fk_hinge_f(xs - xf, k, y, tab, step, rmax) + c * vs


def _fk_run(s: np.ndarray, dw: np.ndarray, k: np.ndarray, c: np.ndarray, m: np.ndarray, fs: np.ndarray,
        fk: np.ndarray, cv: np.ndarray, y: np.ndarray, w: np.ndarray, seg_t0: np.ndarray, seg_l: np.ndarray,
        seg_x: np.ndarray, seg_v: np.ndarray, seg_a: np.ndarray, seg_j: np.ndarray, tab: np.ndarray,
        step: float, rmax: float, h: float, n_cycles: int, max_cycles: int, rtol: float,
        out: np.ndarray) -> None:
    n = s.shape[0]
    nseg = seg_t0.shape[1]
    K = np.zeros((12, 3))
    X = np.zeros(3)
    Y = np.zeros(3)
    for row in range(n):
        kk, cc, mm, fsr, fkr, cvr, yr = k[row], c[row], m[row], fs[row], fk[row], cv[row], y[row]
        X[0] = 0.0
        X[1] = 0.0
        X[2] = 0.0
        mode = 0.0  # 0 stuck, +1/-1 sliding
        dist = 0.0
        prev = 0.0
        vprev = 0.0
        bad = 0.0
        this = 0.0
        vthis = 0.0
        peak = 0.0
        cyc = 0
        while True:
            d0 = dist
            v0 = X[2]
            peak = 0.0
            for g in range(nseg):
                L = seg_l[row, g]
                if L <= 0.0:
                    continue
                sx, sv, sa, sj = seg_x[row, g], seg_v[row, g], seg_a[row, g], seg_j[row, g]
                ns = max(1, int(math.ceil(w[row] * L / h)))
                dt = L / ns
                t = 0.0
                for q in range(ns):
                    tb = L if q == ns - 1 else (q + 1) * dt
                    ta_ = t
                    za = sx + t * (sv + t * (0.5 * sa + t * sj / 6.0)) - X[0]
                    zda = sv + t * (sa + 0.5 * sj * t) - X[1]
                    guard = 0
                    while t < tb and guard < 16:
                        guard += 1
                        if mode == 0.0:
                            fb = _fk_brk(tb, X[0], sx, sv, sa, sj, kk, yr, cc, tab, step, rmax)
                            if not (abs(fb) > fsr):
                                if fb != fb:
                                    bad = 1.0
                                t = tb
                                break
                            sg = 1.0 if fb > 0.0 else -1.0
                            # breakaway in (t, tb]: bisection on |F_h + C_n·ẋ_ws| = f_µmax
                            lo = t
                            hi = tb
                            for _ in range(64):
                                mid = 0.5 * (lo + hi)
                                if mid <= lo or mid >= hi:
                                    break
                                if sg * _fk_brk(mid, X[0], sx, sv, sa, sj, kk, yr, cc, tab, step, rmax) > fsr:
                                    hi = mid
                                else:
                                    lo = mid
                            t = hi
                            mode = sg
                            continue
                        # sliding from t towards tb
                        tau = tb - t
                        _fk_rk_step(t, X, tau, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, step, rmax,
                                K, Y)
                        if mode * Y[1] > 0.0:
                            dist += abs(Y[0] - X[0])
                            X[0] = Y[0]
                            X[1] = Y[1]
                            X[2] = Y[2]
                            t = tb
                            continue
                        # the frame stops inside: ẋ_rf = 0 at τ*, Illinois regula falsi on τ
                        a_ = 0.0
                        fa = mode * X[1]
                        b_ = tau
                        fb2 = mode * Y[1]
                        side = 0
                        for _ in range(60):
                            tc = _falsi_point(a_, fa, b_, fb2)
                            _fk_rk_step(t, X, tc, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, step, rmax,
                                    K, Y)
                            fc = mode * Y[1]
                            a_, fa, b_, fb2, side = _illinois(a_, fa, b_, fb2, side, tc, fc)
                            if b_ - a_ <= 1e-15 * (t + tau) or abs(fc) < 1e-15:
                                break
                        _fk_rk_step(t, X, b_, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, step, rmax,
                                K, Y)
                        dist += abs(Y[0] - X[0])
                        X[0] = Y[0]
                        X[1] = 0.0
                        X[2] = Y[2]
                        t = t + b_
                        if t > tb:
                            t = tb
                        mode = 0.0
                        # stuck now; a breakaway at once (the other way) is checked by the stuck branch
                        fh = _fk_brk(t, X[0], sx, sv, sa, sj, kk, yr, cc, tab, step, rmax)
                        if abs(fh) > fsr * (1.0 + 1e-12):
                            mode = 1.0 if fh > 0.0 else -1.0
                    zb = sx + tb * (sv + tb * (0.5 * sa + tb * sj / 6.0)) - X[0]
                    zdb = sv + tb * (sa + 0.5 * sj * tb) - X[1]
                    dz = _fk_herm_max(za, zda, zb, zdb, tb - ta_)
                    if dz > peak:
                        peak = dz
                    if X[0] != X[0]:
                        bad = 1.0
                if bad != 0.0:
                    break
            if bad != 0.0:
                break
            this = dist - d0
            vthis = X[2] - v0
            cyc += 1
            if _settled(cyc, this, prev, n_cycles, max_cycles, rtol):
                break
            prev = this
            vprev = vthis
        _put_row(out, row, this, prev, vthis, vprev, peak, bad, 0, cyc)



_FK_NAMES = ("_settled", "_falsi_point", "_illinois", "_put_row", "_fk_hinge_f", "_fk_herm_max", "_fk_rk_step", "_fk_brk", "_fk_run")


@lru_cache(maxsize=1)
def _kernel() -> Any:
    """Compile (once per process; numba caches the machine code on disk) and return the
    equal-step reference kernel."""
    from . import dop853
    from .jit import import_numba

    numba = import_numba()

    g = globals()
    g["_FK_A"] = np.ascontiguousarray(dop853.A[:12, :12], dtype=float)
    g["_FK_B"] = np.ascontiguousarray(dop853.B[:12], dtype=float)
    g["_FK_C"] = np.ascontiguousarray(dop853.C[:12], dtype=float)
    jit = numba.njit(cache=True, fastmath=False, error_model="numpy")
    for name in _FK_NAMES:  # callees first (the shared helpers once, by whichever kernel comes first)
        if not hasattr(g[name], "py_func"):
            g[name] = jit(g[name])
    return g["_fk_run"]


# The step-size-controlled kernel: module-level functions compiled by :func:`_adaptive_kernel`
# on first use (numba imported only then), calling each other through the module's globals:
# numba keys its on-disk cache of a closure by its pickled cells, and a compiled function
# pickles with a per-process id, so a closure calling other compiled closures (as the
# equal-step kernel of :func:`_kernel` does) is compiled anew in every process instead of
# loaded from the cache. The tableau (DOP853's 12 stages, the FSAL stage and the 3 stages of its
# dense output, Hairer et al. II.10, from :mod:`.dop853`) is filled in at
# import (below).
def _extended_tableau() -> tuple[np.ndarray, ...]:
    from . import dop853

    A = np.zeros((16, 16))
    A[:12, :12] = dop853.A[:12, :12]
    A[12, :12] = dop853.B
    A[13:, :] = dop853.A[13:]
    return (np.ascontiguousarray(A), np.ascontiguousarray(dop853.B, dtype=float),
            np.ascontiguousarray(np.concatenate([dop853.C[:12], [1.0], dop853.C[13:]]), dtype=float),
            np.ascontiguousarray(dop853.E3, dtype=float), np.ascontiguousarray(dop853.E5, dtype=float),
            np.ascontiguousarray(dop853.D, dtype=float))


# filled here (not at the first compilation): the kernel also runs uncompiled for a few rows (.jit)
_AK_A, _AK_B, _AK_C, _AK_E3, _AK_E5, _AK_D = _extended_tableau()


def _ak_hinge_f(z: float, k: float, y: float, tab: np.ndarray, inv_step: float, step: float, rmax: float) -> float:
    # y ≤ 0: the linear hinge (k·z); else k·y·ψ(z/y), k here being n·K_n·y and y its inverse 1/y
    if y <= 0.0:
        return k * z
    r = abs(z) * y
    if r >= rmax:
        return np.nan
    i = int(r * inv_step)
    t = r - i * step
    psi = tab[i, 0] + t * (tab[i, 1] + t * (tab[i, 2] + t * tab[i, 3]))
    return k * psi if z >= 0.0 else -k * psi


def _ak_herm(z0: float, d0: float, z1: float, d1: float, dt: float) -> tuple[float, float]:
    # largest |p| of the cubic Hermite interpolant over a step and where (0..1)
    best = abs(z0)
    arg = 0.0
    if abs(z1) > best:
        best = abs(z1)
        arg = 1.0
    qa = 6.0 * z0 + 3.0 * dt * d0 - 6.0 * z1 + 3.0 * dt * d1
    qb = -6.0 * z0 - 4.0 * dt * d0 + 6.0 * z1 - 2.0 * dt * d1
    qc = dt * d0
    r0 = -1.0
    r1 = -1.0
    if abs(qa) > 1e-300:
        disc = qb * qb - 4.0 * qa * qc
        if disc >= 0.0:
            sq = math.sqrt(disc)
            r0 = (-qb - sq) / (2.0 * qa)
            r1 = (-qb + sq) / (2.0 * qa)
    elif abs(qb) > 1e-300:
        r0 = -qc / qb
    for q in range(2):
        r = r0 if q == 0 else r1
        if 0.0 < r < 1.0:
            w1 = 1.0 - r
            h00 = (1.0 + 2.0 * r) * (w1 * w1)  # (1 - r)**2 as numba computes it: the same in Python
            h10 = r * (w1 * w1)
            h01 = r * r * (3.0 - 2.0 * r)
            h11 = r * r * (r - 1.0)
            p = h00 * z0 + h10 * dt * d0 + h01 * z1 + h11 * dt * d1
            if abs(p) > best:
                best = abs(p)
                arg = r
    return best, arg


def _ak_rhs(ti: float, x: float, u: float, sig: float, sx: float, sv: float, sa: float, sj: float, k: float,
        y: float, c: float, m: float, fk: float, cv: float, tab: np.ndarray, inv_step: float, step: float,
        rmax: float, K: np.ndarray, i: int) -> None:
    xs = sx + ti * (sv + ti * (0.5 * sa + ti * sj / 6.0))
    vs = sv + ti * (sa + 0.5 * sj * ti)
    fh = _ak_hinge_f(xs - x, k, y, tab, inv_step, step, rmax)
    K[i, 0] = u
    K[i, 1] = (fh + c * (vs - u) - sig * fk - cv * u) * m
    K[i, 2] = cv * u * u


def _ak_stages(t: float, X: np.ndarray, tau: float, sig: float, sx: float, sv: float, sa: float, sj: float,
           k: float, y: float, c: float, m: float, fk: float, cv: float, tab: np.ndarray, inv_step: float,
           step: float, rmax: float, K: np.ndarray, lo: int, hi: int) -> None:
    # stages lo..hi-1 of the extended tableau from the state X at t (K[0] given)
    for i in range(lo, hi):
        x = X[0]
        u = X[1]
        for j in range(i):
            aij = _AK_A[i, j]
            if aij != 0.0:
                x += tau * aij * K[j, 0]
                u += tau * aij * K[j, 1]
        _ak_rhs(t + _AK_C[i] * tau, x, u, sig, sx, sv, sa, sj, k, y, c, m, fk, cv, tab, inv_step, step, rmax, K, i)


def _ak_dense(X: np.ndarray, Y: np.ndarray, tau: float, K: np.ndarray, F: np.ndarray) -> None:
    # DOP853's dense output (Hairer et al., II.10; scipy's Dop853DenseOutput), K[13:16] computed
    for q in range(3):
        dy = Y[q] - X[q]
        F[0, q] = dy
        F[1, q] = tau * K[0, q] - dy
        F[2, q] = 2.0 * dy - tau * (K[12, q] + K[0, q])
        for r in range(4):
            acc = 0.0
            for j in range(16):
                acc += _AK_D[r, j] * K[j, q]
            F[3 + r, q] = tau * acc


def _ak_dense_at(X: np.ndarray, F: np.ndarray, th: float, q: int) -> float:
    yv = 0.0
    for i in range(7):
        yv += F[6 - i, q]
        if i % 2 == 0:
            yv *= th
        else:
            yv *= 1.0 - th
    return yv + X[q]


def _ak_run(s: np.ndarray, dw: np.ndarray, k: np.ndarray, c: np.ndarray, m: np.ndarray, fs: np.ndarray,
        fk: np.ndarray, cv: np.ndarray, y: np.ndarray, w: np.ndarray, seg_t0: np.ndarray, seg_l: np.ndarray,
        seg_x: np.ndarray, seg_v: np.ndarray, seg_a: np.ndarray, seg_j: np.ndarray, tab: np.ndarray,
        step: float, rmax: float, h_grid: float, h_first: float, h_max: float, tol: float, n_cycles: int,
        max_cycles: int, rtol: float, out: np.ndarray) -> None:
    n = s.shape[0]
    nseg = seg_t0.shape[1]
    inv_step = 1.0 / step
    K = np.zeros((16, 3))
    F = np.zeros((7, 3))
    X = np.zeros(3)
    Y = np.zeros(3)
    for row in range(n):
        cc, fsr, fkr, cvr, wr = c[row], fs[row], fk[row], cv[row], w[row]
        # hinge_f and rhs take n·K_n·y and 1/y (n·K_n and 0 for the linear hinge), and 1/m_f
        yr = 1.0 / y[row] if y[row] > 0.0 else 0.0
        kk = k[row] * y[row] if y[row] > 0.0 else k[row]
        mm = 1.0 / m[row]
        # error scales: the breakaway deflection at the bound's tangent (a lower bound) and its speed
        zsc = fsr * mm / (wr * wr)
        sc0 = tol * zsc
        sc1 = tol * zsc * wr
        tau_max = h_max / wr
        tau_ctrl = h_first / wr
        X[0] = 0.0
        X[1] = 0.0
        X[2] = 0.0
        mode = 0.0
        fsal = False
        dist = 0.0
        prev = 0.0
        vprev = 0.0
        bad = 0.0
        this = 0.0
        vthis = 0.0
        peak = 0.0
        cyc = 0
        nsteps = 0
        while True:
            d0 = dist
            v0 = X[2]
            peak = 0.0
            for g in range(nseg):
                L = seg_l[row, g]
                if L <= 0.0:
                    continue
                sx, sv, sa, sj = seg_x[row, g], seg_v[row, g], seg_a[row, g], seg_j[row, g]
                ng = max(1, int(math.ceil(wr * L / h_grid)))
                dtg = L / ng
                t = 0.0
                guard = 0
                while t < L and guard < 1000000:
                    guard += 1
                    if mode == 0.0:
                        # stuck: the breakaway condition on the grid of ω·Δt = h_grid
                        q = int(t / dtg) + 1
                        tb = L if q >= ng else q * dtg
                        if tb <= t:
                            tb = L if q + 1 >= ng else (q + 1) * dtg
                        xs = sx + tb * (sv + tb * (0.5 * sa + tb * sj / 6.0))
                        vs = sv + tb * (sa + 0.5 * sj * tb)
                        fb = _ak_hinge_f(xs - X[0], kk, yr, tab, inv_step, step, rmax) + cc * vs
                        if not (abs(fb) > fsr):
                            if fb != fb:
                                bad = 1.0
                            te = tb
                        else:
                            sg = 1.0 if fb > 0.0 else -1.0
                            lo = t
                            hi = tb
                            for _ in range(64):
                                mid = 0.5 * (lo + hi)
                                if mid <= lo or mid >= hi:
                                    break
                                xs = sx + mid * (sv + mid * (0.5 * sa + mid * sj / 6.0))
                                vs = sv + mid * (sa + 0.5 * sj * mid)
                                if sg * (_ak_hinge_f(xs - X[0], kk, yr, tab, inv_step, step, rmax) + cc * vs) > fsr:
                                    hi = mid
                                else:
                                    lo = mid
                            te = hi
                            mode = sg
                            fsal = False
                            if tau_ctrl > h_first / wr:
                                tau_ctrl = h_first / wr
                        # the deflection of a stuck frame is a cubic in t: Hermite is exact
                        za = sx + t * (sv + t * (0.5 * sa + t * sj / 6.0)) - X[0]
                        zda = sv + t * (sa + 0.5 * sj * t)
                        zb = sx + te * (sv + te * (0.5 * sa + te * sj / 6.0)) - X[0]
                        zdb = sv + te * (sa + 0.5 * sj * te)
                        pz, _ = _ak_herm(za, zda, zb, zdb, te - t)
                        if pz > peak:
                            peak = pz
                        t = te
                        if bad != 0.0:
                            break
                        continue
                    # sliding: one DOP853 step of controlled length
                    tau = tau_ctrl
                    if tau > tau_max:
                        tau = tau_max
                    last = False
                    if t + tau >= L * (1.0 - 1e-13):
                        tau = L - t
                        last = True
                    if not fsal:
                        _ak_rhs(t, X[0], X[1], mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, inv_step, step,
                            rmax, K, 0)
                    _ak_stages(t, X, tau, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, inv_step, step, rmax,
                           K, 1, 12)
                    for q in range(3):
                        acc = 0.0
                        for i in range(12):
                            acc += _AK_B[i] * K[i, q]
                        Y[q] = X[q] + tau * acc
                    _ak_rhs(t + tau, Y[0], Y[1], mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, inv_step, step,
                        rmax, K, 12)
                    nsteps += 1
                    e5a = 0.0
                    e5b = 0.0
                    e3a = 0.0
                    e3b = 0.0
                    for i in range(13):
                        e5a += _AK_E5[i] * K[i, 0]
                        e5b += _AK_E5[i] * K[i, 1]
                        e3a += _AK_E3[i] * K[i, 0]
                        e3b += _AK_E3[i] * K[i, 1]
                    q5a, q5b, q3a, q3b = e5a / sc0, e5b / sc1, e3a / sc0, e3b / sc1
                    e5 = q5a * q5a + q5b * q5b  # x**2 as numba computes it (x*x): the same in Python
                    e3 = q3a * q3a + q3b * q3b
                    err = 0.0
                    if e5 > 0.0 or e3 > 0.0:
                        err = tau * e5 / math.sqrt((e5 + 0.01 * e3) * 2.0)
                    if not (err <= 1.0):
                        if err != err or Y[0] != Y[0]:
                            bad = 1.0
                            break
                        fac = 0.9 * err ** (-0.125)
                        tau_ctrl = tau * (fac if fac > 0.2 else 0.2)
                        fsal = True  # K[0] still belongs to (t, X)
                        continue
                    fac = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-0.125))
                    if last:
                        if tau * fac > tau_ctrl:
                            tau_ctrl = tau * fac
                    else:
                        tau_ctrl = tau * fac
                    # a stop inside the step? also where the frame's speed dips through 0 between stages
                    stop = not (mode * Y[1] > 0.0)
                    dip = False
                    if not stop:
                        for i in range(1, 12):
                            if mode * K[i, 0] <= 0.0:
                                dip = True
                    have_dense = False
                    th_hi = 1.0
                    if stop or dip:
                        _ak_stages(t, X, tau, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, inv_step, step,
                               rmax, K, 13, 16)
                        _ak_dense(X, Y, tau, K, F)
                        have_dense = True
                        if dip:  # sample the dense speed for a sign change
                            for i in range(1, 33):
                                th = i / 32.0
                                if mode * _ak_dense_at(X, F, th, 1) <= 0.0:
                                    stop = True
                                    th_hi = th
                                    break
                    if stop:
                        # ẋ_rf = 0 at θ*: Illinois regula falsi on the dense output
                        a_ = 0.0
                        fa = mode * X[1]
                        b_ = th_hi
                        fb2 = mode * (_ak_dense_at(X, F, b_, 1) if th_hi < 1.0 else Y[1])
                        side = 0
                        for _ in range(80):
                            tc = _falsi_point(a_, fa, b_, fb2)
                            fc = mode * _ak_dense_at(X, F, tc, 1)
                            a_, fa, b_, fb2, side = _illinois(a_, fa, b_, fb2, side, tc, fc)
                            if b_ - a_ <= 1e-15 or fc == 0.0:
                                break
                        th_end = b_
                        Y[0] = _ak_dense_at(X, F, th_end, 0)
                        Y[2] = _ak_dense_at(X, F, th_end, 2)
                        Y[1] = 0.0
                    else:
                        th_end = 1.0
                    te = t + th_end * tau if th_end < 1.0 else (L if last else t + tau)
                    if te > L:
                        te = L
                    # peak of |x_ws − x_rf| over the step: Hermite, refined on the dense output near a peak
                    za = sx + t * (sv + t * (0.5 * sa + t * sj / 6.0)) - X[0]
                    zda = sv + t * (sa + 0.5 * sj * t) - X[1]
                    zb = sx + te * (sv + te * (0.5 * sa + te * sj / 6.0)) - Y[0]
                    zdb = sv + te * (sa + 0.5 * sj * te) - Y[1]
                    pz, arg = _ak_herm(za, zda, zb, zdb, te - t)
                    if pz > peak:
                        peak = pz
                    if 0.0 < arg < 1.0 and pz >= 0.98 * peak:
                        if not have_dense:
                            _ak_stages(t, X, tau, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, inv_step, step,
                                   rmax, K, 13, 16)
                            _ak_dense(X, Y, tau, K, F)
                            have_dense = True
                        # Newton on ż = ẋ_ws − ẋ_rf = 0 in θ of the dense output
                        th = arg * (te - t) / tau
                        for _ in range(6):
                            tt = t + th * tau
                            xf = _ak_dense_at(X, F, th, 0)
                            uf = _ak_dense_at(X, F, th, 1)
                            xs = sx + tt * (sv + tt * (0.5 * sa + tt * sj / 6.0))
                            vs = sv + tt * (sa + 0.5 * sj * tt)
                            as_ = sa + sj * tt
                            fh = _ak_hinge_f(xs - xf, kk, yr, tab, inv_step, step, rmax)
                            zz = abs(xs - xf)
                            if zz > peak:
                                peak = zz
                            gd = as_ - (fh + cc * (vs - uf) - mode * fkr - cvr * uf) * mm
                            if gd == 0.0:
                                break
                            dth = -(vs - uf) / gd / tau
                            th2 = th + dth
                            if th2 < 0.0:
                                th2 = 0.0
                            if th2 > th_end:
                                th2 = th_end
                            if abs(th2 - th) < 1e-14:
                                break
                            th = th2
                    dist += abs(Y[0] - X[0])
                    X[0] = Y[0]
                    X[1] = Y[1]
                    X[2] = Y[2]
                    t = te
                    if stop:
                        mode = 0.0
                        fsal = False
                        xs = sx + t * (sv + t * (0.5 * sa + t * sj / 6.0))
                        vs = sv + t * (sa + 0.5 * sj * t)
                        fh = _ak_hinge_f(xs - X[0], kk, yr, tab, inv_step, step, rmax) + cc * vs
                        if abs(fh) > fsr * (1.0 + 1e-12):
                            mode = 1.0 if fh > 0.0 else -1.0
                    else:
                        # FSAL: the last stage is the next step's first (the right-hand side depends on the
                        # stage's position and speed only, continuous across the kinks)
                        for q in range(3):
                            K[0, q] = K[12, q]
                        fsal = True
                    if X[0] != X[0]:
                        bad = 1.0
                        break
                if bad != 0.0:
                    break
            if bad != 0.0:
                break
            this = dist - d0
            vthis = X[2] - v0
            cyc += 1
            if _settled(cyc, this, prev, n_cycles, max_cycles, rtol):
                break
            prev = this
            vprev = vthis
        _put_row(out, row, this, prev, vthis, vprev, peak, bad, nsteps, cyc)


_AK_NAMES = ("_settled", "_falsi_point", "_illinois", "_put_row", "_ak_hinge_f", "_ak_herm", "_ak_rhs", "_ak_stages", "_ak_dense", "_ak_dense_at", "_ak_run")


@lru_cache(maxsize=1)
def _adaptive_kernel() -> Any:
    """Compile (once per process; numba caches the machine code on disk) and return the kernel."""
    from .jit import import_numba

    numba = import_numba()

    g = globals()
    jit = numba.njit(cache=True, fastmath=False, error_model="numpy")
    for name in _AK_NAMES:  # callees first (the shared helpers once, by whichever kernel comes first)
        if not hasattr(g[name], "py_func"):
            g[name] = jit(g[name])
    return g["_ak_run"]


def integrate_rows(s: np.ndarray, v: np.ndarray, a: np.ndarray, dw: np.ndarray, tj: np.ndarray, k: np.ndarray,
                   c: np.ndarray, m: np.ndarray, fs: np.ndarray, fk: np.ndarray, cv: np.ndarray, y: np.ndarray,
                   omega: np.ndarray, *, h: float = 0.6, n_cycles: int = 3, max_cycles: int = 12,
                   rtol: float = 1e-5, method: str = "adaptive", tol: float = 1e-6, h_max: float = 2.0,
                   info: dict[str, np.ndarray] | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Integrate rows (1-D float arrays) to their periodic steady state with the compiled kernel.

    ``k`` n·K_n [N/m], ``c`` C_n [N·s/m], ``m`` m_f [kg], ``fs``/``fk`` µ_s·F_z/µ_k·F_z [N],
    ``cv`` c_v [N·s/m], ``y`` the thickness of leaves with held ends [m] (0: the linear hinge of
    Eq. 1), ``omega`` the angular frequency that sets the steps [rad/s] (``ω·Δt ≤ h``).
    ``method``: ``"adaptive"`` (default; error-controlled steps, local error below ``tol``
    relative to the breakaway deflection, ω·Δt ≤ ``h_max``, breakaway checked every ω·Δt = ``h``)
    or ``"fixed"`` (the reference: equal steps ω·Δt ≤ ``h``).
    Returns, per row: mean sliding of the last two cycles [m], peak |x_ws − x_rf| of the last
    cycle [m], |difference of the last two cycles' sliding| [m], mean viscous work of the last
    two cycles [J]. ``info``, a dict, receives per row the cycles integrated (``"cycles"``) and the
    Runge-Kutta steps taken while sliding (``"steps"``, adaptive only). Raises ``ValueError`` where a leaf deflects beyond the tabulated law
    (:data:`.hinge.LEAF_TABLE_MAX_RATIO` thicknesses) or the result is not finite.
    """
    f64 = [np.ascontiguousarray(q, dtype=float) for q in (s, v, a, dw, tj, k, c, m, fs, fk, cv, y, omega)]
    s, v, a, dw, tj, k, c, m, fs, fk, cv, y, omega = f64
    segs = stage_segments(s, v, a, dw, tj)
    tab, step = _table()
    out = np.zeros((len(s), 7))  # 5: steps (adaptive), 6: cycles integrated
    rmax = LEAF_TABLE_MAX_RATIO * (1 - 1e-12)
    if method == "adaptive":  # uncompiled for a few rows while numba is not loaded (.jit: the same numbers)
        run_kernel(getattr(_ak_run, "py_func", _ak_run), _adaptive_kernel, s, dw, k, c, m, fs, fk, cv, y, omega,
                   *segs, tab, step, rmax, float(h), 1.0, float(h_max), float(tol), int(n_cycles), int(max_cycles),
                   float(rtol), out)
    elif method == "fixed":
        _kernel()(s, dw, k, c, m, fs, fk, cv, y, omega, *segs, tab, step, rmax, float(h), int(n_cycles),
                  int(max_cycles), float(rtol), out)
    else:
        raise ValueError(f"method must be 'adaptive' or 'fixed', not {method!r}")
    if info is not None:
        info["cycles"] = out[:, 6].astype(np.int64)
        info["steps"] = out[:, 5].astype(np.int64)
    if np.any(out[:, 4] != 0) or not np.all(np.isfinite(out[:, :4])):
        i = int(np.flatnonzero((out[:, 4] != 0) | ~np.all(np.isfinite(out[:, :4]), axis=1))[0])
        raise ValueError(f"the stage dynamics leave the leaf model at stroke {s[i]:.3g} m, velocity {v[i]:.3g} m/s, "
                         f"acceleration {a[i]:.3g} m/s^2: a leaf deflects by more than "
                         f"{LEAF_TABLE_MAX_RATIO:g} thicknesses")
    return out[:, 0].copy(), out[:, 1].copy(), out[:, 2].copy(), out[:, 3].copy()
