"""Linear mixed model with one random intercept (whole plots of a split-plot design, or
random blocks), or several (variance components, nested or crossed), fitted by REML, with
Kenward–Roger tests of the fixed effects.

The model is ``y = X b + Z u + e`` with ``u ~ N(0, s2_g I)`` one effect per group (whole
plot or block) and ``e ~ N(0, s2 I)``, so ``Var(y) = s2 V``, ``V = I + eta Z Z'`` with the
variance ratio ``eta = s2_g / s2``. For a group of ``m`` runs ``V_i = I + eta J`` and
``V_i^{-1/2} = I - (1 - 1/sqrt(1 + eta m)) J / m``: whitening a group subtracts that
fraction of its mean, so generalised least squares is ordinary least squares of the
whitened ``X`` and ``y`` — the regression core (:mod:`rsm_lrg.model.engines.least_squares`)
fits it, and its ``cov_unscaled`` is ``(X' V^-1 X)^-1``.

**REML.** With ``b`` and ``s2`` in closed form at fixed ``eta`` (``s2 = RSS_w / (n - p)``)
the restricted log-likelihood is, up to a constant (Harville 1977; Patterson & Thompson 1971),

    -2 l_R(eta) = (n - p) log RSS_w(eta) + log|V| + log|X' V^-1 X|,

``log|V| = sum_i log(1 + eta m_i)`` and ``log|X'V^-1X|`` from the triangular factor. It is
minimised over ``log eta`` on a grid (bracketing), then the derivative of the profile (in
closed form) is solved by Brent's method inside the bracket; ``eta = 0`` (the boundary: a
whole-plot variance of zero, and then the fit *is* the ordinary least-squares fit) is a
candidate too, and the smallest ``-2 l_R`` wins.

**Kenward–Roger** (Kenward & Roger 1997, Biometrics 53:983; the computation of R's
``pbkrtest``, Halekoh & Højsgaard 2014, J. Stat. Softw. 59(9)): with ``Sigma = s2_g ZZ' + s2 I``
(``G_1 = ZZ'``, ``G_2 = I``), ``Phi = (X' Sigma^-1 X)^-1``, ``P_r = -X' Sigma^-1 G_r Sigma^-1 X``,
``Q_rs = X' Sigma^-1 G_r Sigma^-1 G_s Sigma^-1 X``, the expected information of the variance
parameters ``I_rs = tr(Sigma^-1 G_r Sigma^-1 G_s) - 2 tr(Phi Q_rs) + tr(Phi P_r Phi P_s)`` and
``W = 2 I^-1``, the adjusted covariance is ``Phi_A = Phi + 2 Phi U Phi`` with
``U = sum_rs W_rs (Q_rs - P_r Phi P_s)``; a hypothesis ``L b = 0`` of rank ``q`` is tested by
``F = lambda (L b)'(L Phi_A L')^-1 (L b) / q`` on ``q`` and ``m`` degrees of freedom with
``lambda`` and ``m`` from ``A1``, ``A2`` (Kenward & Roger's Eqs. 5–6 as pbkrtest codes them).
Every product uses the group structure (``Sigma^-1`` acts through group sums), so the cost
is O(n p^2), never an n x n matrix. The den df is never clamped.

**Several random intercepts** (:func:`fit_reml_several`): ``V = I + sum_k eta_k Z_k Z_k'``
is block diagonal over the connected sets of runs and factorised per set (Cholesky,
:class:`_Blocks`); ``-2 l_R`` is the same profile with ``log|V|`` from the factors and is
minimised over ``eta >= 0`` by L-BFGS-B with its analytic gradient
(``d/d eta_k = -(n-p) r'V^-1 Z_kZ_k' V^-1 r / r'V^-1 r + tr(V^-1 Z_kZ_k') - tr(C X'V^-1 Z_kZ_k' V^-1 X)``)
from three starts, then polished by Newton steps; Kenward–Roger is the same computation with
``G_k = Z_k Z_k'`` per effect and ``I`` (pbkrtest's ``vcovAdj`` for an ``lmer`` fit with
``(1|A) + (1|B)``), a component at zero kept.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..contract.prediction import IntervalForm
from ..contract.statistics import fdtrc, stdtrit

if TYPE_CHECKING:
    from .least_squares import Regression

__all__ = ["MixedModel", "KRTest", "VarianceComponent", "RandomEffect", "fit_reml", "fit_reml_several", "group_codes",
           "kr_test", "reml_etas", "whiten",
           "ETA_LOG_RANGE", "CI_METHOD"]

#: A variance ratio (one random effect) or the ratios of several.
Eta = float | np.ndarray

#: The grid of ``log eta`` that brackets the REML optimum: ``eta`` from e^-18 to e^18.
ETA_LOG_RANGE = (-18.0, 18.0)
#: How the variance components' confidence intervals are made (stated in notes and JSON).
CI_METHOD = ("Wald on the log scale: log(s2) ± z·se(log s2), se from the inverse expected (REML) "
             "information of (s2_group, s2), the W of Kenward–Roger")


@dataclass(frozen=True)
class VarianceComponent:
    """One variance component with its confidence interval [response units²].

    ``ci_low``/``ci_high`` are NaN for a component estimated at zero (on the boundary)."""

    name: str
    variance: float
    ci_low: float
    ci_high: float

    def to_dict(self) -> dict:
        return {"variance": self.variance, "std_dev": math.sqrt(self.variance), "ci_low": self.ci_low,
                "ci_high": self.ci_high}


@dataclass(frozen=True)
class KRTest:
    """The Kenward–Roger F test of one model term (all its columns zero)."""

    term: str
    num_df: int
    den_df: float
    f: float
    p: float

    def to_dict(self) -> dict:
        return {"term": self.term, "num_df": self.num_df, "den_df": self.den_df, "f": self.f, "p": self.p}


def group_codes(values: Sequence) -> tuple[np.ndarray, tuple]:
    """``(codes, labels)``: group code 0..G-1 of each run in order of first appearance, and
    the original labels."""
    index: dict = {}
    codes = np.empty(len(values), dtype=int)
    for i, v in enumerate(values):
        codes[i] = index.setdefault(v, len(index))
    return codes, tuple(index)


class _Groups:
    """The group structure: sums and broadcasts by group, and ``V^-1`` at one ``eta``."""

    def __init__(self, codes: np.ndarray) -> None:
        self.codes = np.asarray(codes, dtype=int)
        self.G = int(self.codes.max()) + 1 if self.codes.size else 0
        self.m = np.bincount(self.codes, minlength=self.G).astype(float)

    def sums(self, M: np.ndarray) -> np.ndarray:
        """Group sums of the rows of ``M`` ((n,) or (n, k)) -> (G,) or (G, k)."""
        M = np.asarray(M, dtype=float)
        out = np.zeros((self.G,) + M.shape[1:])
        np.add.at(out, self.codes, M)
        return out

    def spread(self, S: np.ndarray) -> np.ndarray:
        """The group values ``S`` ((G,) or (G, k)) on each run (``Z S``)."""
        return np.asarray(S)[self.codes]

    def vinv(self, M: np.ndarray, eta: Eta) -> np.ndarray:
        """``V^-1 M`` with ``V = I + eta ZZ'``: ``V_i^-1 = I - eta/(1 + eta m_i) J``."""
        d = eta / (1.0 + eta * self.m)
        S = self.sums(M)
        return np.asarray(M, dtype=float) - self.spread((d * S.T).T if S.ndim > 1 else d * S)

    def whiten(self, M: np.ndarray, eta: Eta) -> np.ndarray:
        """``V^-1/2 M``: each group less ``(1 - 1/sqrt(1 + eta m_i))`` times its mean."""
        c = (1.0 - 1.0 / np.sqrt(1.0 + eta * self.m)) / self.m
        S = self.sums(M)
        return np.asarray(M, dtype=float) - self.spread((c * S.T).T if S.ndim > 1 else c * S)

    def logdet(self, eta: Eta) -> float:
        """``log|V| = sum_i log(1 + eta m_i)``."""
        return float(np.sum(np.log1p(eta * self.m)))

    def zzt(self, M: np.ndarray) -> np.ndarray:
        """``ZZ' M``: each run gets its group's sum."""
        return self.spread(self.sums(M))

    def kr_ops(self) -> list[Callable[[np.ndarray], np.ndarray]]:
        """The ``G_r`` of the variance parameters ``(s2_group, s2)``: ``ZZ'`` and ``I``."""
        return [self.zzt, lambda M: M]

    def ktrace(self, eta: Eta, s2: float) -> np.ndarray:
        """``tr(Sigma^-1 G_r Sigma^-1 G_s)`` in closed form: the eigenvalues of ``V_i^-1`` are 1
        (``m_i - 1`` times) and ``1/(1 + eta m_i)``."""
        f = 1.0 / (1.0 + eta * self.m)
        m = self.m
        tr_zz_zz = float(np.sum((m * f) ** 2)) / s2 ** 2
        tr_zz_i = float(np.sum(m * f ** 2)) / s2 ** 2
        tr_i_i = float(np.sum(m - 1.0 + f ** 2)) / s2 ** 2
        return np.array([[tr_zz_zz, tr_zz_i], [tr_zz_i, tr_i_i]])


class _Blocks:
    """Several random intercepts: ``V = I + sum_k eta_k Z_k Z_k'``.

    ``V`` is block diagonal over the connected sets of runs (runs that share a level of some
    effect, directly or through other runs: a replicate with its whole plots, or the whole
    grid of a strip-plot); each set is factorised densely (Cholesky; sets of one size
    together, as a stack), so the cost is ``sum_c n_c^3`` per variance ratio, never an
    n x n matrix unless every run is connected."""

    def __init__(self, codes: Sequence[np.ndarray]) -> None:
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        self.groups = [_Groups(c) for c in codes]
        self.K = len(self.groups)
        n = self.groups[0].codes.size
        offs = np.cumsum([0] + [g.G for g in self.groups])
        rows = np.concatenate([np.arange(n)] * self.K)
        cols = n + np.concatenate([g.codes + o for g, o in zip(self.groups, offs)])
        N = n + int(offs[-1])
        graph = coo_matrix((np.ones(rows.size), (rows, cols)), shape=(N, N))
        _, lab = connected_components(graph, directed=False)
        lab = lab[:n]
        sets = [np.flatnonzero(lab == c) for c in np.unique(lab)]
        by_size: dict[int, list[np.ndarray]] = {}
        for ix in sets:
            by_size.setdefault(ix.size, []).append(ix)
        #: (rows (b, m), Z_kZ_k' (K, b, m, m)) per size m of the connected sets
        self.stacks = []
        for _size, ixs in sorted(by_size.items()):
            R = np.stack(ixs)
            zz = np.stack([(g.codes[R][:, :, None] == g.codes[R][:, None, :]).astype(float) for g in self.groups])
            self.stacks.append((R, zz))
        self._key: tuple | None = None
        self._fac: list[tuple[np.ndarray, np.ndarray, float]] = []

    def _factor(self, eta: Eta) -> list[tuple[np.ndarray, np.ndarray, float]]:
        """Per stack ``(L^-1, V^-1, log|V|)`` at ``eta``."""
        e = np.asarray(eta, dtype=float)
        key = tuple(float(v) for v in e)
        if key != self._key:
            fac = []
            for R, zz in self.stacks:
                V = np.eye(R.shape[1]) + np.einsum("k,kbij->bij", e, zz)
                L = np.linalg.cholesky(V)
                Li = np.linalg.inv(L)
                Li = np.tril(Li)
                Vi = np.swapaxes(Li, 1, 2) @ Li
                fac.append((Li, Vi, float(2.0 * np.sum(np.log(np.diagonal(L, axis1=1, axis2=2))))))
            self._fac = fac
            self._key = key
        return self._fac

    def _apply(self, M: np.ndarray, eta: Eta, which: int) -> np.ndarray:
        M = np.asarray(M, dtype=float)
        vec = M.ndim == 1
        M2 = M[:, None] if vec else M
        out = np.empty_like(M2)
        for (R, _), f in zip(self.stacks, self._factor(eta)):
            out[R] = f[which] @ M2[R]
        return out[:, 0] if vec else out

    def whiten(self, M: np.ndarray, eta: Eta) -> np.ndarray:
        """``L^-1 M`` with ``V = L L'`` (``(L^-1 X)'(L^-1 X) = X' V^-1 X``)."""
        return self._apply(M, eta, 0)

    def vinv(self, M: np.ndarray, eta: Eta) -> np.ndarray:
        """``V^-1 M``."""
        return self._apply(M, eta, 1)

    def logdet(self, eta: Eta) -> float:
        return float(sum(f[2] for f in self._factor(eta)))

    def tr_vinv_zz(self, eta: Eta) -> np.ndarray:
        """``tr(V^-1 Z_k Z_k')`` for every effect."""
        return np.array([sum(float(np.sum(f[1] * zz[k])) for (_, zz), f in zip(self.stacks, self._factor(eta)))
                         for k in range(self.K)])

    def kr_ops(self) -> list[Callable[[np.ndarray], np.ndarray]]:
        """The ``G_r`` of the variance parameters ``(s2_1, ..., s2_K, s2)``: ``Z_k Z_k'`` and ``I``."""
        return [g.zzt for g in self.groups] + [lambda M: M]

    def ktrace(self, eta: Eta, s2: float) -> np.ndarray:
        """``tr(Sigma^-1 G_r Sigma^-1 G_s)`` summed over the connected sets (``tr(H_r H_s)``,
        ``H_r = G_r Sigma^-1``, as pbkrtest's ``Ktrace``)."""
        k = self.K + 1
        out = np.zeros((k, k))
        for (_, zz), f in zip(self.stacks, self._factor(eta)):
            Vi = f[1]
            H = [zz[j] @ Vi for j in range(self.K)] + [Vi]
            for r in range(k):
                for s in range(r, k):
                    out[r, s] += float(np.sum(np.swapaxes(H[r], 1, 2) * H[s]))
        out = np.triu(out) + np.triu(out, 1).T
        return out / s2 ** 2


def whiten(X: np.ndarray, y: np.ndarray, codes: np.ndarray, eta: float) -> tuple[np.ndarray, np.ndarray]:
    """``(V^-1/2 X, V^-1/2 y)`` for ``V = I + eta ZZ'`` (one random intercept per group ``codes``)."""
    g = _Groups(codes)
    return g.whiten(X, eta), g.whiten(y, eta)


@dataclass(frozen=True)
class _Profile:
    """The regression core at one ``eta`` and the profiled ``-2 l_R``."""

    eta: Eta
    m2l: float
    reg: Regression


def _profile_at(eta: Eta, X: np.ndarray, y: np.ndarray, groups: _Groups | _Blocks,
                names: Sequence[str]) -> _Profile:
    from .least_squares import CHUNK_ROWS, factorise

    Xw, yw = groups.whiten(X, eta), groups.whiten(y, eta)
    n, p = X.shape
    reg = factorise(lambda: ((Xw[s:s + CHUNK_ROWS], yw[s:s + CHUNK_ROWS]) for s in range(0, n, CHUNK_ROWS)), p,
                    names, shift=0.0)
    d = np.abs(np.diag(reg.R))
    if not reg.full_rank or not np.all(d > 0):
        return _Profile(eta, math.inf, reg)
    logdet_xvx = 2.0 * float(np.sum(np.log(d)) + np.sum(np.log(reg.scale)))
    rss = reg.rho ** 2
    m2l = (n - p) * math.log(rss) + groups.logdet(eta) + logdet_xvx if rss > 0 else -math.inf
    return _Profile(eta, m2l, reg)


def _dprofile(eta: float, X: np.ndarray, y: np.ndarray, groups: _Groups) -> float:
    """``d(-2 l_R)/d eta`` in closed form:
    ``-(n-p) r'V^-1ZZ'V^-1 r / r'V^-1 r + tr(V^-1 ZZ') - tr(C X'V^-1ZZ'V^-1X)``, ``C = (X'V^-1X)^-1``."""
    n, p = X.shape
    Xw, yw = groups.whiten(X, eta), groups.whiten(y, eta)
    C = np.linalg.inv(Xw.T @ Xw)
    b = C @ (Xw.T @ yw)
    r = y - X @ b
    f = 1.0 / (1.0 + eta * groups.m)
    a = groups.sums(r) * f  # Z'V^-1 r
    rvr = float(np.sum(groups.whiten(r, eta) ** 2))
    A = groups.sums(X) * f[:, None]  # Z'V^-1 X (G x p)
    return float(-(n - p) * np.sum(a * a) / rvr + np.sum(groups.m * f) - np.einsum("gi,ij,gj->", A, C, A))


def _brent_root(f: Callable[[float], float], a: float, b: float, fa: float, fb: float, tol: float = 1e-15,
                maxiter: int = 200) -> float:
    """A root of ``f`` in ``[a, b]`` with ``f(a) f(b) <= 0`` (Brent 1973, *Algorithms for
    Minimization without Derivatives*, ch. 4: bisection, secant and inverse quadratic steps)."""
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    c, fc, d = a, fa, b - a
    e = d
    for _ in range(maxiter):
        if fb * fc > 0:
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol1 = 2.0 * 2.2e-16 * abs(b) + 0.5 * tol
        xm = 0.5 * (c - b)
        if abs(xm) <= tol1 or fb == 0.0:
            return b
        if abs(e) >= tol1 and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:
                p, q = 2.0 * xm * s, 1.0 - s
            else:
                q, r = fa / fc, fb / fc
                p = s * (2.0 * xm * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0:
                q = -q
            p = abs(p)
            if 2.0 * p < min(3.0 * xm * q - abs(tol1 * q), abs(e * q)):
                e, d = d, p / q
            else:
                d = e = xm
        else:
            d = e = xm
        a, fa = b, fb
        b += d if abs(d) > tol1 else math.copysign(tol1, xm)
        fb = f(b)
    return b


def reml_eta(X: np.ndarray, y: np.ndarray, codes: np.ndarray, names: Sequence[str]) -> tuple[float, float]:
    """``(eta, -2 l_R)`` at the REML optimum of the variance ratio ``eta = s2_g / s2`` (see the
    module docstring): a grid on ``log eta`` brackets the minima, Brent's method solves the
    profile's derivative inside each bracket, ``eta = 0`` is a candidate; the least wins."""
    groups = _Groups(codes)
    grid = np.arange(ETA_LOG_RANGE[0], ETA_LOG_RANGE[1] + 0.5, 1.0)
    vals = [_profile_at(math.exp(t), X, y, groups, names).m2l for t in grid]
    best = (0.0, _profile_at(0.0, X, y, groups, names).m2l)

    def g(t: float) -> float:  # derivative with respect to log eta
        e = math.exp(t)
        return e * _dprofile(e, X, y, groups)

    for i in range(len(grid)):  # every local minimum of the grid (interior or at an end)
        lo, hi = max(i - 1, 0), min(i + 1, len(grid) - 1)
        if not (vals[i] <= vals[lo] and vals[i] <= vals[hi]) or not math.isfinite(vals[i]):
            continue
        a, b = float(grid[lo]), float(grid[hi])
        ga, gb = g(a), g(b)
        if ga <= 0.0 <= gb:
            t = _brent_root(g, a, b, ga, gb)
        else:
            t = float(grid[i])
        cand = _profile_at(math.exp(t), X, y, groups, names).m2l
        if cand < best[1]:
            best = (math.exp(t), cand)
    return best


def _dprofile_several(eta: np.ndarray, X: np.ndarray, y: np.ndarray, blocks: _Blocks) -> np.ndarray:
    """``d(-2 l_R)/d eta_k`` for every effect, in closed form:
    ``-(n-p) r'V^-1 Z_kZ_k' V^-1 r / r'V^-1 r + tr(V^-1 Z_kZ_k') - tr(C X'V^-1 Z_kZ_k' V^-1 X)``."""
    n, p = X.shape
    Xw, yw = blocks.whiten(X, eta), blocks.whiten(y, eta)
    C = np.linalg.inv(Xw.T @ Xw)
    b = C @ (Xw.T @ yw)
    r = y - X @ b
    Vr = blocks.vinv(r, eta)
    VX = blocks.vinv(X, eta)
    rvr = float(r @ Vr)
    tr_vz = blocks.tr_vinv_zz(eta)
    out = np.empty(blocks.K)
    for k, g in enumerate(blocks.groups):
        a = g.sums(Vr)
        A = g.sums(VX)
        out[k] = -(n - p) * float(np.sum(a * a)) / rvr + tr_vz[k] - float(np.einsum("gi,ij,gj->", A, C, A))
    return out


def reml_etas(X: np.ndarray, y: np.ndarray, codes: Sequence[np.ndarray], names: Sequence[str]) -> tuple[np.ndarray, float]:
    """``(eta, -2 l_R)`` at the REML optimum of the variance ratios ``eta_k = s2_k / s2`` of
    several random intercepts: L-BFGS-B on ``eta`` (bounds at 0, the analytic gradient) from
    up to three starts (each effect's own one-effect REML ratio over K, all 1, all 0.1; the
    third only when the first two disagree), the best polished
    by Newton steps on the components inside the bounds (Hessian by central differences of
    the analytic gradient); a component at its bound stays exactly 0."""
    from scipy.optimize import minimize

    blocks = _Blocks(codes)
    K = blocks.K

    def m2l(e: np.ndarray) -> float:
        return _profile_at(np.asarray(e, dtype=float), X, y, blocks, names).m2l

    def fg(e: np.ndarray) -> tuple[float, np.ndarray]:
        e = np.maximum(np.asarray(e, dtype=float), 0.0)
        v = m2l(e)
        if not math.isfinite(v):
            return 1e300, np.zeros(K)
        return v, _dprofile_several(e, X, y, blocks)

    single = []
    for c in codes:
        e1, _ = reml_eta(X, y, c, names)
        single.append(min(max(e1, 1e-3), 1e6))
    starts = [np.array(single) / K, np.ones(K), np.full(K, 0.1)]
    best: tuple[np.ndarray, float] | None = None
    found = []
    for x0 in starts:
        res = minimize(fg, x0, jac=True, method="L-BFGS-B", bounds=[(0.0, None)] * K,
                       options={"ftol": 1e-15, "gtol": 1e-11, "maxiter": 2000, "maxcor": 20})
        e = np.maximum(np.asarray(res.x, dtype=float), 0.0)
        v = m2l(e)
        found.append(v)
        if best is None or v < best[1]:
            best = (e, v)
        if len(found) == 2 and abs(found[0] - found[1]) <= 1e-9 * max(1.0, abs(found[0])):
            break  # two starts reach one optimum: the third is not needed
    assert best is not None
    eta, val = best
    # Newton polish of the components inside the bounds
    for _ in range(30):
        free = np.flatnonzero(eta > 0)
        if free.size == 0:
            break
        g = _dprofile_several(eta, X, y, blocks)[free]
        H = np.empty((free.size, free.size))
        for j, i in enumerate(free):
            h = 1e-5 * eta[i]
            ep, em = eta.copy(), eta.copy()
            ep[i] += h
            em[i] -= h
            H[:, j] = (_dprofile_several(ep, X, y, blocks)[free] - _dprofile_several(em, X, y, blocks)[free]) / (2 * h)
        H = 0.5 * (H + H.T)
        try:
            step = np.linalg.solve(H, g)
        except np.linalg.LinAlgError:
            break
        trial = eta.copy()
        trial[free] -= step
        if np.any(trial[free] <= 0) or not np.all(np.linalg.eigvalsh(H) > 0):
            break
        v = m2l(trial)
        if not v <= val + 1e-12 * abs(val):
            break
        eta, val = trial, min(v, val)
        if np.all(np.abs(step) <= 1e-13 * eta[free]):
            break
    return eta, float(val)


# ----------------------------------------------------------------------------------------
# Kenward-Roger
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _KRParts:
    """``Phi``, ``Phi_A``, the ``P_r`` and ``W`` at the REML optimum (pbkrtest's ``vcovAdj``)."""

    phi: np.ndarray
    phi_a: np.ndarray
    P_std: tuple
    W_std: np.ndarray
    information_std: np.ndarray
    #: The variance unit ``u`` (the response's scale squared) the parts are computed in:
    #: ``phi`` and ``phi_a`` are in response units² (``u`` times their standardised values),
    #: ``P_std``, ``W_std`` and ``information_std`` are those of the standardised response
    #: ``y / sqrt(u)``. Every test and interval is computed from these, free of ``u``.
    unit: float = 1.0

    @property
    def W(self) -> np.ndarray:
        """``W`` in response units⁴ (``u² W_std``; infinite or 0 where that leaves the floats)."""
        with np.errstate(over="ignore", under="ignore"):
            return self.W_std * self.unit * self.unit

    @property
    def P(self) -> tuple:
        """The ``P_r`` in response units⁻⁴ (``P_std / u²``)."""
        with np.errstate(over="ignore", under="ignore"):
            return tuple(Pr / self.unit / self.unit for Pr in self.P_std)

    @property
    def information(self) -> np.ndarray:
        """The expected information of the variance parameters in response units⁻⁴."""
        with np.errstate(over="ignore", under="ignore"):
            return self.information_std / self.unit / self.unit


def _kr_parts(X: np.ndarray, groups: _Groups | _Blocks, s2g: float | np.ndarray, s2: float,
              unit: float = 1.0) -> _KRParts:
    """pbkrtest's ``vcovAdj`` with ``Sigma = sum_k s2g_k Z_k Z_k' + s2 I`` (``s2g`` one variance
    per random effect: a float for one, an array for several), at the variance components of the
    response standardised by ``sqrt(unit)`` (see :class:`_KRParts`)."""
    eta = s2g / s2

    def sinv(M: np.ndarray) -> np.ndarray:  # Sigma^-1 M
        return groups.vinv(M, eta) / s2

    SX = sinv(X)
    phi = np.linalg.inv(X.T @ SX)
    phi = 0.5 * (phi + phi.T)
    # a random-effect component stays in the computation when it is estimated at zero (the
    # boundary), as pbkrtest and lmerTest keep it: Sigma lacks it there, but the information
    # about it, and so W, Phi_A and the den df, still count it
    G = groups.kr_ops()
    # O_r = G_r Sigma^-1 X ; P_r = -O_r' Sigma^-1 X ; Q_rs = O_r' Sigma^-1 O_s
    O = [gr(SX) for gr in G]
    P = [-(o.T @ SX) for o in O]
    P = [0.5 * (pr + pr.T) for pr in P]
    k = len(G)
    Q = [[O[r].T @ sinv(O[s]) for s in range(k)] for r in range(k)]
    # tr(Sigma^-1 G_r Sigma^-1 G_s)
    K = groups.ktrace(eta, s2)
    info = np.empty((k, k))
    for r in range(k):
        for s in range(k):
            info[r, s] = K[r, s] - 2.0 * float(np.sum(phi * Q[r][s])) + float(np.sum((phi @ P[r]) * (P[s] @ phi)))
    info = 0.5 * (info + info.T)
    ev = np.linalg.eigvalsh(info)
    W = 2.0 * (np.linalg.inv(info) if np.min(np.abs(ev)) > 1e-10 else np.linalg.pinv(info))
    U = np.zeros_like(phi)
    for r in range(k):
        for s in range(k):
            U += W[r, s] * (Q[r][s] - P[r] @ phi @ P[s])
    phi_a = phi + 2.0 * phi @ U @ phi
    return _KRParts(phi=phi * unit, phi_a=0.5 * (phi_a + phi_a.T) * unit, P_std=tuple(P), W_std=W,
                    information_std=info, unit=unit)


def _div_zero(x: float, y: float, tol: float = 1e-14) -> float:
    return 1.0 if (abs(x) < tol and abs(y) < tol) else x / y


def kr_test(parts: _KRParts, L: np.ndarray, beta: np.ndarray) -> tuple[float, float, float, int]:
    """``(F, den_df, p, q)`` of the Kenward–Roger test of ``L b = 0`` (pbkrtest's
    ``.KR_adjust``: ``F`` scaled by ``lambda``; ``den_df`` not clamped; ``p`` NaN when the
    den df is not positive)."""
    L = np.atleast_2d(np.asarray(L, dtype=float))
    phi, W = parts.phi / parts.unit, parts.W_std  # standardised (the statistics are free of the unit)
    q = int(np.linalg.matrix_rank(L))
    LPL = L @ phi @ L.T
    Theta = L.T @ np.linalg.solve(LPL, L)
    TP = Theta @ phi
    k = len(parts.P_std)
    A1 = A2 = 0.0
    us = [TP @ parts.P_std[i] @ phi for i in range(k)]
    for i in range(k):
        for j in range(i, k):
            e = 1.0 if i == j else 2.0
            A1 += e * W[i, j] * float(np.trace(us[i])) * float(np.trace(us[j]))
            A2 += e * W[i, j] * float(np.sum(us[i] * us[j].T))
    if q == 1:
        # one df: A1 = A2 = A (u is of rank one), so g = -1, c1 = -1/7, c2 = 2/7, c3 = 4/7,
        # V1 = 1 - A = 1 - A2/q and pbkrtest's formulas reduce exactly to den df = 2/A and
        # F scaling 1; written so, since (1 - A2/q)/V1 is 0/0 in rounding when A is near 1
        # (den df near 2, e.g. a balanced split-plot with 2 whole-plot error df)
        df2 = 2.0 / A2 if A2 > 0 else math.inf
        scale = 1.0
    else:
        B = (A1 + 6.0 * A2) / (2.0 * q)
        g = ((q + 1) * A1 - (q + 4) * A2) / ((q + 2) * A2)
        den = 3.0 * q + 2.0 * (1.0 - g)
        c1, c2, c3 = g / den, (q - g) / den, (q + 2 - g) / den
        V0, V1, V2 = 1.0 + c1 * B, 1.0 - c2 * B, 1.0 - c3 * B
        V0 = 0.0 if abs(V0) < 1e-10 else V0
        rho = (1.0 / q) * _div_zero(1.0 - A2 / q, V1) ** 2 * V0 / V2
        df2 = 4.0 + (q + 2.0) / (q * rho - 1.0)
        scale = 1.0 if abs(df2 - 2.0) < 1e-2 else df2 * (1.0 - A2 / q) / (df2 - 2.0)
    Lb = L @ beta / math.sqrt(parts.unit)
    wald = float(Lb @ np.linalg.solve(L @ (parts.phi_a / parts.unit) @ L.T, Lb))
    F = float(scale * wald / q)
    p = float(fdtrc(q, df2, F)) if df2 > 0 and math.isfinite(df2) and F >= 0 else math.nan
    return F, float(df2), p, q


# ----------------------------------------------------------------------------------------
# the fitted mixed model
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class RandomEffect:
    """One random intercept of a model with several: its grouping column, the level of each run
    (codes 0..G-1 in order of first appearance) and the levels' labels."""

    column: str
    codes: np.ndarray = field(repr=False)
    labels: tuple = field(repr=False)

    @property
    def n_levels(self) -> int:
        return len(self.labels)


@dataclass(frozen=True)
class MixedModel:
    """The mixed-model part of a REML fit (:attr:`rsm_lrg.model.results.result.FitResult.mixed`).

    With one random intercept (``kind`` ``"whole_plot"``, ``"block"`` or ``"effect"``) the
    attributes below describe it; with several (``kind == "several"``, ``effects`` holds them)
    ``column``, ``codes`` and ``labels`` are the first effect's, ``eta`` and ``sigma2_group``
    the sums over the effects (``etas`` and :attr:`variance_components` give each).

    Attributes
    ----------
    column : str
        The group column (whole plot or random block).
    kind : {"whole_plot", "block", "effect", "several"}
        What the random intercept is (names the variance component: ``"whole_plot"``,
        ``"block"``, or the column for ``"effect"`` and ``"several"``).
    codes : (n,) ndarray of int
        Group of each run (0..G-1, in order of first appearance); ``labels`` the original values.
    eta : float
        REML variance ratio ``s2_group / s2`` (0 on the boundary) [-].
    sigma2, sigma2_group : float
        Residual and group variance components [response units²]; with several random
        effects ``sigma2_group`` is their sum, the variance of a new run's random part.
    m2loglik : float
        ``-2 l_R`` at the optimum (profiled, without the constant ``(n - p)(1 + log 2 pi - log(n - p))``).
    beta : (p,) ndarray
        GLS coefficients of the model matrix ``X`` (coded units).
    X : (n, p) ndarray
        The model matrix (unwhitened); ``y`` the response on the model's scale.
    """

    column: str
    kind: str
    codes: np.ndarray = field(repr=False)
    labels: tuple = field(repr=False)
    eta: float
    sigma2: float
    sigma2_group: float
    m2loglik: float
    beta: np.ndarray = field(repr=False)
    X: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    parts: _KRParts = field(repr=False)
    effects: tuple = field(default=(), repr=False)
    etas: np.ndarray | None = field(default=None, repr=False)
    structure: _Blocks | None = field(default=None, repr=False)

    @property
    def several(self) -> bool:
        """Whether the model has more than one random intercept."""
        return self.kind == "several"

    @property
    def n_groups(self) -> int:
        return len(self.labels)

    @property
    def columns(self) -> tuple:
        """The grouping columns of the random intercepts."""
        return tuple(e.column for e in self.effects) if self.several else (self.column,)

    @property
    def component_names(self) -> tuple:
        """The names of the random-effect variance components (without ``"residual"``)."""
        if self.several or self.kind == "effect":
            return self.columns
        return (self.kind,)

    @property
    def component_variances(self) -> tuple:
        """The random-effect variance components [response units²], as :attr:`component_names`."""
        if self.several:
            assert self.etas is not None
            return tuple(float(e) * self.sigma2 for e in self.etas)
        return (self.sigma2_group,)

    @property
    def boundary(self) -> bool:
        """A random-effect variance is estimated at zero (with one effect the fit is then the
        OLS fit)."""
        if self.several:
            assert self.etas is not None
            return bool(np.any(self.etas == 0.0))
        return self.eta == 0.0

    def describe(self) -> str:
        """``"a random intercept per whole plot ('wp', 8 whole plots)"`` or, with several,
        ``"random intercepts per level of 'replicate' (15) and of 'replicate:recipe' (45)"``."""
        if self.several:
            parts = [f"{e.column!r} ({e.n_levels})" for e in self.effects]
            return "random intercepts per level of " + ", of ".join(parts[:-1]) + " and of " + parts[-1]
        if self.kind == "effect":
            return f"a random intercept per level of {self.column!r} ({self.n_groups} levels)"
        what = "whole plot" if self.kind == "whole_plot" else "block"
        return f"a random intercept per {what} ({self.column!r}, {self.n_groups} {what}s)"

    @property
    def cov(self) -> np.ndarray:
        """``Phi = (X' Sigma^-1 X)^-1``, the GLS covariance of the coefficients [units²]."""
        return self.parts.phi

    @property
    def cov_adjusted(self) -> np.ndarray:
        """Kenward–Roger's adjusted covariance ``Phi_A`` [units²]."""
        return self.parts.phi_a

    def test(self, L: np.ndarray) -> tuple[float, float, float, int]:
        """``(F, den_df, p, num_df)`` of the Kenward–Roger test of ``L b = 0``."""
        return kr_test(self.parts, L, self.beta)

    def tests(self, names: Sequence[str], groups: Sequence[Sequence[int]]) -> list[KRTest]:
        """One Kenward–Roger test per term: its columns ``groups[i]`` all zero."""
        out = []
        p = self.beta.size
        for name, cols in zip(names, groups):
            L = np.zeros((len(cols), p))
            L[np.arange(len(cols)), list(cols)] = 1.0
            F, df2, pv, q = self.test(L)
            out.append(KRTest(term=str(name), num_df=q, den_df=df2, f=F, p=pv))
        return out

    def contrast_tests(self, hypotheses: Sequence[tuple[str, np.ndarray]]) -> list[KRTest]:
        """One Kenward–Roger test per ``(name, L)``: the hypothesis ``L b = 0``.

        Parameters
        ----------
        hypotheses : sequence of (str, numpy.ndarray)
            The name of each test and its L (rows over every model column).

        Returns
        -------
        list of KRTest
        """
        out = []
        for name, L in hypotheses:
            F, df2, pv, q = self.test(L)
            out.append(KRTest(term=str(name), num_df=q, den_df=df2, f=F, p=pv))
        return out

    def interval_form(self, columns: np.ndarray) -> IntervalForm:
        """The prediction contract's :class:`~rsm_lrg.model.contract.prediction.IntervalForm` of the
        model columns ``columns``: ``Φ`` for ``se_fit``, ``Φ_A`` for the mean, a new run in a
        new group (``σ²_g + σ²``), and the Kenward–Roger den df per point from ``Φ P_r Φ``
        and ``W``."""
        ix = np.ix_(columns, columns)
        u = self.parts.unit
        phi = self.parts.phi
        phi_s = phi / u  # Phi P_r Phi is free of the unit; W is given in the unit (kr_unit)
        return IntervalForm(cov_se=phi[ix], cov_mean=self.parts.phi_a[ix], s2_residual=self.sigma2,
                            s2_group=float(sum(self.component_variances)), df=math.nan,
                            kr_phi_p_phi=tuple((phi_s @ P @ phi_s)[ix] for P in self.parts.P_std),
                            kr_w=self.parts.W_std, kr_unit=u)

    @property
    def variance_components(self) -> dict:
        """``{kind: VarianceComponent, "residual": VarianceComponent}`` (with several random
        effects, or ``random_effects=[COL]``, one entry per grouping column, named as the
        column) with Wald intervals on the log scale (:data:`CI_METHOD`; none for a component at
        zero)."""
        z = float(stdtrit(math.inf, 0.975))
        W, u = self.parts.W_std, self.parts.unit  # W of the standardised response: se(log s2) is free of the unit
        out = {}
        names = list(self.component_names) + ["residual"]
        values = list(self.component_variances) + [self.sigma2]
        for i, (nm, v) in enumerate(zip(names, values)):
            se_log = math.sqrt(W[i, i]) / (v / u) if W[i, i] > 0 and v > 0 else math.nan
            lo, hi = (v * math.exp(-z * se_log), v * math.exp(z * se_log)) if math.isfinite(se_log) else (math.nan,) * 2
            out[nm] = VarianceComponent(nm, float(v), float(lo), float(hi))
        return out

    @property
    def fitted(self) -> np.ndarray:
        """The fitted values a REML fit reports: the conditional ``X b + Z u`` (nlme's default)."""
        return self.conditional_fitted

    @property
    def residuals(self) -> np.ndarray:
        """The residuals a REML fit reports: the conditional ``y - X b - Z u``."""
        return self.conditional_residuals

    @property
    def random_effect(self) -> dict:
        """``{"whole_plot": COL}``, ``{"random_block": COL}`` or ``{"random_effects": [COL, ...]}``:
        the keyword :func:`rsm_lrg.fit` takes to refit the model."""
        if self.several or self.kind == "effect":
            return {"random_effects": list(self.columns)}
        return {"whole_plot" if self.kind == "whole_plot" else "random_block": self.column}

    @property
    def marginal_fitted(self) -> np.ndarray:
        """``X b`` (the population prediction, group effect 0) [response units]."""
        return self.X @ self.beta

    @property
    def blups(self) -> np.ndarray:
        """Predicted group effects ``u_i = eta sum_i(r) / (1 + eta m_i)`` (BLUPs), one per group
        (with several random effects: the first effect's, see :attr:`effect_blups`)."""
        if self.several:
            return self.effect_blups[0]
        g = _Groups(self.codes)
        r = self.y - self.marginal_fitted
        return self.eta * g.sums(r) / (1.0 + self.eta * g.m)

    @property
    def effect_blups(self) -> tuple:
        """The BLUPs of every random effect, ``u_k = eta_k Z_k' V^-1 (y - X b)``, one array per
        effect (levels as its ``labels``)."""
        if not self.several:
            return (self.blups,)
        assert self.structure is not None and self.etas is not None
        Vr = self.structure.vinv(self.y - self.marginal_fitted, self.etas)
        return tuple(float(e) * g.sums(Vr) for e, g in zip(self.etas, self.structure.groups))

    @property
    def random_effects_table(self) -> dict:
        """``{label: BLUP}`` (one effect) or ``{column: {label: BLUP}}`` (several)."""
        if not self.several:
            return {str(lab): float(u) for lab, u in zip(self.labels, self.blups)}
        return {e.column: {str(lab): float(u) for lab, u in zip(e.labels, b)}
                for e, b in zip(self.effects, self.effect_blups)}

    @property
    def marginal_residuals(self) -> np.ndarray:
        """``y - X b`` [response units]."""
        return self.y - self.marginal_fitted

    @property
    def conditional_fitted(self) -> np.ndarray:
        """``X b + Z u`` [response units]."""
        if self.several:
            return self.marginal_fitted + sum(b[e.codes] for e, b in zip(self.effects, self.effect_blups))
        return self.marginal_fitted + self.blups[self.codes]

    @property
    def conditional_residuals(self) -> np.ndarray:
        """``y - X b - Z u``: the estimated within-group errors [response units]."""
        return self.y - self.conditional_fitted


def _standardised(X: Any, y: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, float, bool]:
    """``(X, y, ys, c, k, ones)``: the response centred on its mean ``c`` when the model has an
    intercept column, and standardised, ``ys = (y - c) / k`` with ``k`` its largest centred
    value. The variance ratios, the profile and the Kenward–Roger parts are computed on ``ys``,
    free of the response's unit, so a response in 1e-95 or 1e80 units fits as well as one in
    units near 1 (the variances, y's scale squared, and their products would leave the floats
    otherwise)."""
    X = np.asarray(X, dtype=float)
    y = np.asarray(y, dtype=float)
    n, p = X.shape
    ones = bool(np.all(X[:, 0] == 1.0)) if p else False
    c = math.fsum(y) / n if ones else 0.0  # added back to the intercept
    yc = y - c
    k = float(np.max(np.abs(yc))) if n else 0.0
    k = k if math.isfinite(k) and k > 0.0 else 1.0
    return X, y, yc / k, c, k, ones


def _gls_in_unit(eta: Any, X: np.ndarray, ys: np.ndarray, structure: Any, names: Sequence[str], c: float, k: float,
                 ones: bool, exact: str) -> tuple[Regression, float]:
    """The GLS core at the variance ratios ``eta`` (one whitening, a second pass over row
    chunks), back in the response's unit: ``(Regression, s2s)`` with ``s2s`` the residual
    variance of the standardised response. Raises ``ValueError(exact)`` when the model leaves
    no residual variance (the residual RMS at round-off of the spread)."""
    from dataclasses import replace

    from .least_squares import CHUNK_ROWS

    n, p = X.shape
    prof = _profile_at(eta, X, ys, structure, names)
    Xw, yw = structure.whiten(X, eta), structure.whiten(ys, eta)
    reg = prof.reg.second_pass(lambda: ((Xw[s:s + CHUNK_ROWS], yw[s:s + CHUNK_ROWS]) for s in range(0, n, CHUNK_ROWS)))
    s2s = float(reg.sigma2)
    spread = float(np.sum((ys - np.mean(ys)) ** 2))
    if not (math.isfinite(s2s) and s2s * (n - p) > 1e-20 * spread):
        raise ValueError(exact)
    reg = reg.rescaled(k)  # back to the response's unit
    # params: b[0] + c (the whitened intercept column fits y - c)
    return replace(reg, shift=c, intercept=ones), s2s


def fit_reml(X: np.ndarray, y: np.ndarray, codes: np.ndarray, labels: Sequence, names: Sequence[str], *,
             column: str, kind: str = "whole_plot") -> tuple[MixedModel, Regression]:
    """REML fit of ``y = X b + Z u + e`` (one random intercept per group ``codes``).

    Returns
    -------
    (MixedModel, Regression)
        The mixed-model part and the regression core of the whitened data at the optimum
        (its ``params``, ``cov_unscaled`` and ``sigma2`` are the GLS coefficients,
        ``(X' V^-1 X)^-1`` and the REML residual variance; its residuals and leverages are
        those of the whitened model).
    """
    X, y, ys, c, k, ones = _standardised(X, y)
    n, p = X.shape
    eta, m2l = reml_eta(X, ys, codes, names)
    m2l += (n - p) * 2.0 * math.log(k)  # -2 l_R of the response in its own unit
    groups = _Groups(codes)
    within = "whole plot" if kind == "whole_plot" else "block"
    reg, s2s = _gls_in_unit(eta, X, ys, groups, names, c, k, ones,
                            f"the model fits the data exactly within every {within} (no residual variance): "
                            "REML has nothing to estimate the variance components from")
    s2 = float(reg.sigma2)
    beta = np.asarray(reg.params, dtype=float)
    parts = _kr_parts(X, groups, eta * s2s, s2s, unit=k * k)
    mm = MixedModel(column=column, kind=kind, codes=np.asarray(codes, dtype=int), labels=tuple(labels), eta=float(eta),
                    sigma2=s2, sigma2_group=float(eta * s2), m2loglik=float(m2l), beta=beta, X=X, y=y, parts=parts)
    return mm, reg


def fit_reml_several(X: np.ndarray, y: np.ndarray, effects: Sequence[RandomEffect],
                     names: Sequence[str]) -> tuple[MixedModel, Regression]:
    """REML fit of ``y = X b + sum_k Z_k u_k + e`` with several random intercepts (nested or
    crossed as the codes say), ``u_k ~ N(0, s2_k I)``: the variance ratios by :func:`reml_etas`,
    then the same GLS core and Kenward–Roger parts as :func:`fit_reml` (pbkrtest's ``vcovAdj``
    with one ``G_k = Z_k Z_k'`` per effect and ``I``)."""
    X, y, ys, c, k, ones = _standardised(X, y)
    n, p = X.shape
    codes = [np.asarray(e.codes, dtype=int) for e in effects]
    etas, m2l = reml_etas(X, ys, codes, names)
    m2l += (n - p) * 2.0 * math.log(k)  # -2 l_R of the response in its own unit
    blocks = _Blocks(codes)
    reg, s2s = _gls_in_unit(etas, X, ys, blocks, names, c, k, ones,
                            "the model fits the data exactly within the random-effect levels (no residual variance): "
                            "REML has nothing to estimate the variance components from")
    s2 = float(reg.sigma2)
    beta = np.asarray(reg.params, dtype=float)
    parts = _kr_parts(X, blocks, etas * s2s, s2s, unit=k * k)
    first = effects[0]
    mm = MixedModel(column=first.column, kind="several", codes=np.asarray(first.codes, dtype=int),
                    labels=tuple(first.labels), eta=float(np.sum(etas)), sigma2=s2,
                    sigma2_group=float(np.sum(etas) * s2), m2loglik=float(m2l), beta=beta, X=X, y=y, parts=parts,
                    effects=tuple(effects), etas=np.asarray(etas, dtype=float), structure=blocks)
    return mm, reg
