"""Compiled stick-slip integrator of the RFCMS, one row at a time (:func:`.dynamics.cycle_metrics`).

The frame of the rigid-flexible stage obeys (:mod:`.dynamics`)

    m_f·ẍ_rf = F_h(x_ws − x_rf) + C_n·(ẋ_ws − ẋ_rf) − σ·µ_k·F_z − c_v·ẋ_rf     (sliding, σ = sign ẋ_rf)

with the hinge force F_h of the small-deflection hinge (n·K_n·z, Eq. 1) or of leaves with held
ends (exact beam-column law, ``n·K_n·y·ψ(z/y)``, :func:`.hinge.leaf_force_table`), and stays
put while stuck until ``|F_h + C_n·ẋ_ws| > µ_s·F_z`` (Eq. 2). The stage's profile is cut at
its kinks into segments on which the stage moves on a polynomial (constant acceleration for
the trapezoid, constant jerk for S-curve strokes), so the right-hand side is smooth inside a
segment. Each segment is crossed in equal steps of the explicit Runge-Kutta method of order 8
of Dormand & Prince (DOP853's tableau, taken from :class:`scipy.integrate.DOP853`) with
``ω·Δt ≤ h``, ω the hinge's tangent angular frequency at a bound of the deflection; a stop
(ẋ_rf reaching 0) is located inside a step by the Illinois variant of regula falsi on the
Runge-Kutta step's own length, and a breakaway (``|F_h + C_n·ẋ_ws| = µ_s·F_z``, the frame at
rest, the stage on its polynomial) by bisection to machine precision. Each row is integrated
alone in compiled code (numba): its result does not depend on the rows of its batch or on the
number of worker processes, and there is no per-step Python overhead.

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


@lru_cache(maxsize=1)
def _kernel() -> Any:
    """Compile (once per process; numba caches the machine code on disk) and return the kernel."""
    import numba
    from scipy.integrate import DOP853

    A = np.ascontiguousarray(DOP853.A[:12, :12], dtype=float)
    B = np.ascontiguousarray(DOP853.B[:12], dtype=float)
    C = np.ascontiguousarray(DOP853.C[:12], dtype=float)
    jit = numba.njit(cache=True, fastmath=False, error_model="numpy")

    @jit
    def hinge_f(z: float, k: float, y: float, tab: np.ndarray, step: float, rmax: float) -> float:
        if y <= 0.0:
            return k * z
        r = abs(z) / y
        if r >= rmax:
            return np.nan
        i = int(r / step)
        t = r - i * step
        psi = tab[i, 0] + t * (tab[i, 1] + t * (tab[i, 2] + t * tab[i, 3]))
        return k * y * psi if z >= 0.0 else -k * y * psi

    @jit
    def herm_max(z0: float, d0: float, z1: float, d1: float, dt: float) -> float:
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
                h00 = (1.0 + 2.0 * r) * (1.0 - r) ** 2
                h10 = r * (1.0 - r) ** 2
                h01 = r * r * (3.0 - 2.0 * r)
                h11 = r * r * (r - 1.0)
                p = h00 * z0 + h10 * dt * d0 + h01 * z1 + h11 * dt * d1
                if abs(p) > best:
                    best = abs(p)
        return best

    @jit
    def rk_step(t: float, X: np.ndarray, tau: float, sig: float, sx: float, sv: float, sa: float, sj: float,
                k: float, y: float, c: float, m: float, fk: float, cv: float, tab: np.ndarray, step: float,
                rmax: float, K: np.ndarray, out: np.ndarray) -> None:
        # state X = (x_rf, u, viscous work); t is the time since the segment's start
        for i in range(12):
            ti = t + C[i] * tau
            x = X[0]
            u = X[1]
            for j in range(i):
                aij = A[i, j]
                if aij != 0.0:
                    x += tau * aij * K[j, 0]
                    u += tau * aij * K[j, 1]
            xs = sx + ti * (sv + ti * (0.5 * sa + ti * sj / 6.0))
            vs = sv + ti * (sa + 0.5 * sj * ti)
            fh = hinge_f(xs - x, k, y, tab, step, rmax)
            K[i, 0] = u
            K[i, 1] = (fh + c * (vs - u) - sig * fk - cv * u) / m
            K[i, 2] = cv * u * u
        for q in range(3):
            acc = 0.0
            for i in range(12):
                acc += B[i] * K[i, q]
            out[q] = X[q] + tau * acc

    @jit
    def brk(t: float, xf: float, sx: float, sv: float, sa: float, sj: float, k: float, y: float, c: float,
            tab: np.ndarray, step: float, rmax: float) -> float:
        xs = sx + t * (sv + t * (0.5 * sa + t * sj / 6.0))
        vs = sv + t * (sa + 0.5 * sj * t)
        return hinge_f(xs - xf, k, y, tab, step, rmax) + c * vs

    @jit
    def run(s: np.ndarray, dw: np.ndarray, k: np.ndarray, c: np.ndarray, m: np.ndarray, fs: np.ndarray,
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
                                fb = brk(tb, X[0], sx, sv, sa, sj, kk, yr, cc, tab, step, rmax)
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
                                    if sg * brk(mid, X[0], sx, sv, sa, sj, kk, yr, cc, tab, step, rmax) > fsr:
                                        hi = mid
                                    else:
                                        lo = mid
                                t = hi
                                mode = sg
                                continue
                            # sliding from t towards tb
                            tau = tb - t
                            rk_step(t, X, tau, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, step, rmax,
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
                                tc = (a_ * fb2 - b_ * fa) / (fb2 - fa)
                                if not (tc > a_ and tc < b_):
                                    tc = 0.5 * (a_ + b_)
                                rk_step(t, X, tc, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, step, rmax,
                                        K, Y)
                                fc = mode * Y[1]
                                if fc > 0.0:
                                    a_ = tc
                                    fa = fc
                                    if side == -1:
                                        fb2 *= 0.5
                                    side = -1
                                else:
                                    b_ = tc
                                    fb2 = fc
                                    if side == 1:
                                        fa *= 0.5
                                    side = 1
                                if b_ - a_ <= 1e-15 * (t + tau) or abs(fc) < 1e-15:
                                    break
                            rk_step(t, X, b_, mode, sx, sv, sa, sj, kk, yr, cc, mm, fkr, cvr, tab, step, rmax,
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
                            fh = brk(t, X[0], sx, sv, sa, sj, kk, yr, cc, tab, step, rmax)
                            if abs(fh) > fsr * (1.0 + 1e-12):
                                mode = 1.0 if fh > 0.0 else -1.0
                        zb = sx + tb * (sv + tb * (0.5 * sa + tb * sj / 6.0)) - X[0]
                        zdb = sv + tb * (sa + 0.5 * sj * tb) - X[1]
                        dz = herm_max(za, zda, zb, zdb, tb - ta_)
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
                err = abs(this - prev)
                if cyc >= n_cycles and (err <= rtol * max(this, 1e-300) or cyc >= max_cycles):
                    break
                prev = this
                vprev = vthis
            out[row, 0] = 0.5 * (this + prev)
            out[row, 1] = peak
            out[row, 2] = abs(this - prev)
            out[row, 3] = 0.5 * (vthis + vprev)
            out[row, 4] = bad

    return run


def integrate_rows(s: np.ndarray, v: np.ndarray, a: np.ndarray, dw: np.ndarray, tj: np.ndarray, k: np.ndarray,
                   c: np.ndarray, m: np.ndarray, fs: np.ndarray, fk: np.ndarray, cv: np.ndarray, y: np.ndarray,
                   omega: np.ndarray, *, h: float = 0.6, n_cycles: int = 3, max_cycles: int = 12,
                   rtol: float = 1e-5) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Integrate rows (1-D float arrays) to their periodic steady state with the compiled kernel.

    ``k`` n·K_n [N/m], ``c`` C_n [N·s/m], ``m`` m_f [kg], ``fs``/``fk`` µ_s·F_z/µ_k·F_z [N],
    ``cv`` c_v [N·s/m], ``y`` the thickness of leaves with held ends [m] (0: the linear hinge of
    Eq. 1), ``omega`` the angular frequency that sets the steps [rad/s] (``ω·Δt ≤ h``).
    Returns, per row: mean sliding of the last two cycles [m], peak |x_ws − x_rf| of the last
    cycle [m], |difference of the last two cycles' sliding| [m], mean viscous work of the last
    two cycles [J]. Raises ``ValueError`` where a leaf deflects beyond the tabulated law
    (:data:`.hinge.LEAF_TABLE_MAX_RATIO` thicknesses) or the result is not finite.
    """
    f64 = [np.ascontiguousarray(q, dtype=float) for q in (s, v, a, dw, tj, k, c, m, fs, fk, cv, y, omega)]
    s, v, a, dw, tj, k, c, m, fs, fk, cv, y, omega = f64
    segs = stage_segments(s, v, a, dw, tj)
    tab, step = _table()
    out = np.zeros((len(s), 5))
    _kernel()(s, dw, k, c, m, fs, fk, cv, y, omega, *segs, tab, step, LEAF_TABLE_MAX_RATIO * (1 - 1e-12),
              float(h), int(n_cycles), int(max_cycles), float(rtol), out)
    if np.any(out[:, 4] != 0) or not np.all(np.isfinite(out[:, :4])):
        i = int(np.flatnonzero((out[:, 4] != 0) | ~np.all(np.isfinite(out[:, :4]), axis=1))[0])
        raise ValueError(f"the stage dynamics leave the leaf model at stroke {s[i]:.3g} m, velocity {v[i]:.3g} m/s, "
                         f"acceleration {a[i]:.3g} m/s^2: a leaf deflects by more than "
                         f"{LEAF_TABLE_MAX_RATIO:g} thicknesses")
    return out[:, 0].copy(), out[:, 1].copy(), out[:, 2].copy(), out[:, 3].copy()
