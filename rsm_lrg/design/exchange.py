"""The exchange step of optimal designs, shared by :func:`rsm_lrg.design.optimal.optimal` and
:mod:`rsm_lrg.design.augment`: the criteria (D, I, A) and their values, the region's moment
matrix, the feasible candidate pool and the coordinate/row exchange of Meyer & Nachtsheim
(1995) (:class:`ExchangeProblem`).

Meyer, R. K. & Nachtsheim, C. J. (1995). The coordinate-exchange algorithm for
constructing exact optimal experimental designs. *Technometrics* 37(1), 60-69.

See :mod:`rsm_lrg.design.optimal` for the criteria's definitions and the search.
"""

from __future__ import annotations

import math
from typing import Any, cast

import numpy as np

from ..terms import design_matrix, n_columns

__all__ = ["CRITERIA", "GRID", "MAX_RUNS", "MAX_COLUMNS", "MAX_STARTS", "check_criterion", "check_columns",
           "information", "moment_matrix", "thin_region_error", "criterion_value", "reported_value",
           "information_criterion", "is_gain", "ExchangeProblem",
           "candidate_pool", "at_every_level", "halton"]

#: Criteria accepted by :func:`optimal`.
CRITERIA = ("D", "I", "A")

#: Levels tried for a numeric coordinate (coded).
GRID = np.linspace(-1.0, 1.0, 21)
_COARSE = np.array([-1.0, 0.0, 1.0])

#: Largest design :func:`optimal` builds [runs].
MAX_RUNS = 2000

#: Largest model (columns) :func:`optimal` and augmentation search for (the exchange grows
#: as columns^3 per move: beyond this a run would take hours).
MAX_COLUMNS = 120

#: Most random starts accepted.
MAX_STARTS = 1000

def check_criterion(c: Any) -> str:
    """``c`` as one of :data:`CRITERIA` (upper case), or a ValueError."""
    if not isinstance(c, str) or c.strip().upper() not in CRITERIA:
        raise ValueError(f"criterion must be one of {', '.join(CRITERIA)} (got {c!r})")
    return c.strip().upper()


def check_columns(p: int, model: str, k: int) -> None:
    """ValueError when the model is beyond :data:`MAX_COLUMNS` columns."""
    if p > MAX_COLUMNS:
        raise ValueError(f"the {model} model in {k} factors has {p} coefficients, beyond the {MAX_COLUMNS} an optimal "
                         "design is searched for here; choose a smaller model (e.g. 2fi or quadratic)")


def information(coded: np.ndarray, terms) -> np.ndarray:
    """``X'X`` of coded runs for ``terms``."""
    X = design_matrix(np.asarray(coded, dtype=float), terms)
    return X.T @ X


def moment_matrix(space, terms, constraints=None, n_sample: int = 2 ** 14, seed: int = 12345) -> np.ndarray:
    """Region moment matrix ``W = E[f(x) f(x)']`` (p x p) of the I criterion.

    Numeric factors uniform on the coded cube [-1, 1] (exact moments: ``E[x^m]`` is
    ``1/(m+1)`` for even m, 0 for odd), categoric levels equally weighted, independent; with
    ``constraints`` (a :class:`~rsm_lrg.design.constraints.Constraints`) the mean over the
    feasible points of a scrambled Sobol' sample of the cube.
    """
    import itertools

    if any(t.diff for t in terms):
        raise ValueError("moment_matrix: the full-cubic terms AB(A-B) are not monomials (a mixture design's "
                         "moments are taken over its simplex)")
    k = len(space)
    num = space.numeric_index
    cats = [(i, f.n_levels) for i, f in enumerate(space.factors) if f.kind == "categoric"]
    combos = list(itertools.product(*[range(L) for _, L in cats])) or [()]
    # categoric part of every column at each combination (numeric factors at 1)
    probe = np.ones((len(combos), k))
    for r, c in enumerate(combos):
        for (i, _), lv in zip(cats, c):
            probe[r, i] = lv
    Z = design_matrix(probe, terms)
    C = Z.T @ Z / len(combos)
    powers = []
    for t in terms:
        powers += [np.array(t.numeric_powers)[num]] * t.df
    P = np.array(powers, dtype=int).reshape(len(powers), len(num))
    if constraints is None or not constraints:
        S = P[:, None, :] + P[None, :, :]
        mom = np.where(S % 2 == 0, 1.0 / (S + 1.0), 0.0)
        return np.prod(mom, axis=2) * C
    from scipy.stats import qmc

    pts = qmc.Sobol(len(num), scramble=True, seed=seed).random(n_sample) * 2.0 - 1.0
    full = np.zeros((n_sample, k))
    full[:, num] = pts
    ok = constraints.feasible_coded(full)
    if not ok.any():
        raise thin_region_error(constraints)
    pts = pts[ok]
    G = np.prod(pts[:, None, :] ** P[None, :, :], axis=2)  # numeric monomial of every column
    return (G.T @ G / G.shape[0]) * C


def thin_region_error(constraints) -> ValueError:
    """The error for a constrained region that holds no point of the search (empty, or too
    thin to design in: ``x + y <= 0`` on ``x, y >= 0`` is one corner)."""
    texts = "; ".join(repr(c.text) for c in getattr(constraints, "items", ()))
    return ValueError(f"constraints {texts}: no point of the search satisfies them (the constrained region is "
                      "empty or too thin to design in, e.g. a single point or a line)")


def information_criterion(M: np.ndarray, crit: str, W: np.ndarray | None) -> Any:
    """Criterion to minimise (``-log det`` for D), batched over leading axes; inf if singular."""
    if crit == "D":
        sign, logdet = np.linalg.slogdet(M)
        return np.where(sign > 0, -logdet, np.inf)
    try:
        if crit == "A":
            inv = np.linalg.inv(M)
            v = np.trace(inv, axis1=-2, axis2=-1)
        else:
            v = np.trace(np.linalg.solve(M, np.broadcast_to(cast(np.ndarray, W), M.shape)), axis1=-2, axis2=-1)
    except np.linalg.LinAlgError:
        return np.full(M.shape[:-2], np.inf) if M.ndim > 2 else np.inf
    return np.where(np.isfinite(v) & (v > 0), v, np.inf)


def criterion_value(coded: np.ndarray, terms, criterion: str = "D", W: np.ndarray | None = None) -> float:
    """The criterion of coded runs as reported: D ``det(X'X)^(1/p) / n``; A
    ``trace((X'X)^-1)``; I ``trace((X'X)^-1 W)`` (``W`` from :func:`moment_matrix`). A
    singular design gives 0 (D) or inf (A, I)."""
    coded = np.asarray(coded, dtype=float)
    return reported_value(information(coded, terms), coded.shape[0], criterion, W)


def reported_value(M: np.ndarray, n: int, criterion: str = "D", W: np.ndarray | None = None) -> float:
    """The criterion as reported, from an information matrix ``M`` (p x p) of ``n`` runs:
    D ``det(M)^(1/p) / n``; A ``trace(M^-1)``; I ``trace(M^-1 W)``. A singular ``M`` gives
    0 (D) or inf (A, I). With ``M = X'X`` this is :func:`criterion_value`; the split-plot
    designs pass the GLS information ``X' V^-1 X`` (:mod:`rsm_lrg.design.split_plot`)."""
    crit = check_criterion(criterion)
    p = M.shape[0]
    if crit == "D":
        sign, logdet = np.linalg.slogdet(M)
        if sign <= 0 or np.linalg.cond(M) > 1e12:
            return 0.0
        return float(math.exp(logdet / p) / n)
    if np.linalg.cond(M) > 1e12:
        return math.inf
    return float(information_criterion(M, crit, W))


def is_gain(v: float, cur: float) -> bool:
    """Whether criterion value ``v`` (to minimise) is a real gain on ``cur`` (more than a
    relative 1e-10, so that rounding never cycles an exchange)."""
    return v < cur - 1e-10 * max(1.0, abs(cur))


class ExchangeProblem:
    """One exchange search: the factor space, the model terms, the criterion (``W`` for I),
    the constraints and the feasible candidate pool; :meth:`improve` runs coordinate and row
    exchange on a start (:meth:`greedy_start`, :meth:`random_start`), rows before ``fixed``
    held (the runs an augmentation keeps)."""

    def __init__(self, space, terms, crit, W, constraints, pool):
        self.space, self.terms, self.crit, self.W, self.cons = space, terms, crit, W, constraints
        self.k = len(space)
        self.p = n_columns(terms)
        self.pool = pool
        cands = at_every_level(pool, space)
        self._P = None
        if not space.has_categoric and not any(t.diff for t in terms):  # monomials: products of powers (fast path)
            self._P = np.array([t.powers for t in terms], dtype=int)
            self._factor_index = np.arange(self.k)[None, :]
        self.candidates = cands
        self.cand_rows = self.rows(cands)
        self._cache_key = None
        self.values = []
        for f in space.factors:
            self.values.append(GRID if f.kind == "numeric" else np.arange(f.n_levels, dtype=float))

    def rows(self, coded: np.ndarray) -> np.ndarray:
        """Model rows of coded points (:func:`rsm_lrg.terms.design_matrix`); all-numeric
        factors: each monomial as a product of gathered powers (no ``**`` per entry)."""
        if self._P is not None:
            P = self._P
            powers = np.ones((int(P.max()) + 1,) + coded.shape)
            for d in range(1, powers.shape[0]):
                powers[d] = powers[d - 1] * coded
            # powers[P[t, f], :, f] for every term t and factor f, multiplied over f
            return np.prod(powers[P, :, self._factor_index], axis=1).T
        return design_matrix(coded, self.terms)

    def _prepared(self, M: np.ndarray):
        """``(A, K, base)`` for ``M`` (cached while ``M`` is the same array), or None when
        ``M`` is badly conditioned."""
        if self._cache_key is not None and self._cache_key[0] is M:
            return self._cache_key[1]
        out: tuple | None = None
        if np.linalg.cond(M) < 1e8:
            A = np.linalg.inv(M)
            if self.crit == "D":
                out = (A, None, np.linalg.slogdet(M)[1])
            elif self.crit == "I":
                out = (A, A @ self.W @ A, float(np.trace(A @ self.W)))
            else:
                out = (A, A @ A, float(np.trace(A)))
        self._cache_key = (M, out)
        return out

    def batch(self, M: np.ndarray, f: np.ndarray | None, G: np.ndarray) -> np.ndarray:
        """Criterion (to minimise) of ``M - f f' + g g'`` for every row g of ``G`` (``f``
        None: nothing removed). With ``A = M^-1`` the updates cost ``O(p^2)`` per candidate:
        ``det`` times ``(1 + g'Ag)(1 - f'Af) + (f'Ag)^2`` (Meyer & Nachtsheim 1995) and the
        rank-two Woodbury identity for the traces of A and I; a badly conditioned ``M`` falls
        back to exact factorisations."""
        if f is None:
            f = np.zeros(M.shape[0])
        # one run f against every candidate: the pairs of batch_pairs with a single run
        return self.batch_pairs(M, f[None, :], np.zeros(len(G), dtype=int), G)

    def batch_pairs(self, M: np.ndarray, F: np.ndarray, own: np.ndarray, G: np.ndarray) -> np.ndarray:
        """Criterion (to minimise) of ``M - f f' + g g'`` for every pair ``(f, g) = (F[own[m]],
        G[m])``: the exchange of any run for any point, ranked in one vectorised step by the
        same rank-two updates as :meth:`batch` (``O(p^2)`` per point, the runs' terms once)."""
        prep = self._prepared(M)
        if prep is None:
            Fr = F[own]
            stack = M[None, :, :] - Fr[:, :, None] * Fr[:, None, :] + G[:, :, None] * G[:, None, :]
            return information_criterion(stack, self.crit, self.W)
        A, K, base = prep
        FA = F @ A
        gAg = np.einsum("ij,ij->i", G @ A, G)
        fAg = np.einsum("ij,ij->i", FA[own], G)
        fAf = np.einsum("ij,ij->i", FA, F)[own]
        with np.errstate(all="ignore"):
            if self.crit == "D":
                r = (1.0 + gAg) * (1.0 - fAf) + fAg ** 2
                v = -(base + np.log(r))
                ok = r > 0
            else:
                FK = F @ K
                t11 = np.einsum("ij,ij->i", G @ K, G)
                t12 = np.einsum("ij,ij->i", FK[own], G)
                t22 = np.einsum("ij,ij->i", FK, F)[own]
                s11, s12, s22 = 1.0 + gAg, fAg, fAf - 1.0
                det = s11 * s22 - s12 ** 2
                v = base - (s22 * t11 - 2.0 * s12 * t12 + s11 * t22) / det
                ok = np.abs(det) > 1e-12
        return np.where(ok & np.isfinite(v), v, np.inf)

    def _moves(self, D: np.ndarray, rows: np.ndarray, coords, phase: int, step: float,
               coarse: bool) -> tuple[np.ndarray, np.ndarray]:
        """Every single-coordinate move of the runs ``rows`` of ``D``: ``(points, run index)``,
        feasible ones only, the current settings left out."""
        pts, owner = [], []
        base = D[rows]
        for j in coords:
            if phase == 0:
                vals = self.values[j]
                if coarse and self.space.factors[j].kind == "numeric":
                    vals = _COARSE
                vals = np.broadcast_to(vals, (len(rows), len(vals)))
            else:
                vals = np.clip(base[:, j:j + 1] + np.linspace(-step, step, 11)[None, :], -1.0, 1.0)
            m = vals.shape[1]
            block = np.repeat(base, m, axis=0)
            block[:, j] = vals.reshape(-1)
            keep = block[:, j] != np.repeat(base[:, j], m)
            pts.append(block[keep])
            owner.append(np.repeat(rows, m)[keep])
        P = np.vstack(pts) if pts else np.empty((0, D.shape[1]))
        own = np.concatenate(owner) if owner else np.empty(0, dtype=int)
        if self.cons is not None and self.cons and len(P):
            ok = self.cons.feasible_coded(P)
            P, own = P[ok], own[ok]
        return P, own

    def ridge(self, n):
        return 1e-9 * max(n, 1) * np.eye(self.p)

    def score(self, D):
        M = information(D, self.terms) + self.ridge(len(D))
        return float(information_criterion(M, self.crit, self.W))

    def _start(self, D: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """A copy of ``D`` to exchange on, its model rows ``F``, information ``M`` (with the
        small ridge) and criterion value."""
        D = D.copy()
        F = design_matrix(D, self.terms)
        M = F.T @ F + self.ridge(len(D))
        return D, F, M, float(information_criterion(M, self.crit, self.W))

    def _on_grid(self, points: np.ndarray, *rows: np.ndarray) -> tuple[np.ndarray, ...]:
        """``points`` (and the matching ``rows``) with every numeric coordinate at -1, 0 or
        +1, when there are at least two such points; else all of them."""
        on = np.all(np.isin(points[:, self.space.numeric_index], _COARSE), axis=1)
        if on.sum() >= 2:
            return (points[on], *(r[on] for r in rows))
        return (points, *rows)

    def _replace(self, D: np.ndarray, F: np.ndarray, i: int, x: np.ndarray, g: np.ndarray, M: np.ndarray,
                 cur: float) -> tuple[np.ndarray, float] | None:
        """The acceptance step of both exchanges: run ``i`` of ``D`` (model row ``F[i]``;
        information ``M``, criterion ``cur``) is replaced by the point ``x`` (model row ``g``)
        only if the exact criterion of the new information matrix is a real gain (the
        rank-one updates of :meth:`batch` only rank the candidates). On a gain ``D`` and
        ``F`` are updated in place and the new ``(M, criterion)`` returned; else None."""
        M2 = M - np.outer(F[i], F[i]) + np.outer(g, g)
        v2 = float(information_criterion(M2, self.crit, self.W))
        if not is_gain(v2, cur):
            return None
        D[i], F[i] = x, g
        return M2, v2

    def exchange(self, D: np.ndarray, fixed: int = 0, polish: bool = True, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Coordinate exchange on rows ``fixed..`` of ``D`` (earlier rows held); ``coarse``:
        numeric coordinates at -1, 0, +1 only (the levels of the classical designs).

        Each step ranks every single-coordinate move of every run at once
        (:meth:`batch_pairs`) and makes the best one that the exact criterion confirms
        (:meth:`_replace`), until no move gains; phases 1 and 2 (``polish``) then refine the
        numeric coordinates by steps of 0.05 and 0.01."""
        D, F, M, cur = self._start(D)
        n = len(D)
        rows = np.arange(fixed, n)
        num = self.space.numeric_index
        for phase in (0, 1, 2) if polish else (0,):
            coords = range(self.k) if phase == 0 else num
            step = 0.05 / (5 ** (phase - 1)) if phase else 0.0
            # each run's moves and their model rows, remade only for the run that changed
            moves: dict[int, tuple[np.ndarray, np.ndarray]] = {}
            for i in rows:
                Pi = self._moves(D, np.array([i]), coords, phase, step, coarse)[0]
                moves[int(i)] = (Pi, self.rows(Pi))
            for _ in range(100 * max(1, len(rows)) * max(1, len(coords))):
                P = np.vstack([moves[int(i)][0] for i in rows])
                if not len(P):
                    break
                G = np.vstack([moves[int(i)][1] for i in rows])
                own = np.repeat(rows, [len(moves[int(i)][0]) for i in rows])
                v = self.batch_pairs(M, F, own, G)
                got, r = None, -1
                for b in np.argsort(v)[:3]:  # the ranking is rank-one; the exact value decides
                    if not is_gain(v[b], cur):
                        break
                    r = int(own[b])
                    got = self._replace(D, F, r, P[b], G[b], M, cur)
                    if got:
                        break
                if not got:
                    break
                M, cur = got
                Pr = self._moves(D, np.array([r]), coords, phase, step, coarse)[0]
                moves[r] = (Pr, self.rows(Pr))
        return D, cur

    def row_exchange(self, D: np.ndarray, fixed: int = 0, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Replace whole runs by the best candidate point (the feasible pool at every level
        combination), run by run, until no replacement improves the criterion."""
        D, F, M, cur = self._start(D)
        n = len(D)
        cands, G = self._on_grid(self.candidates, self.cand_rows) if coarse else (self.candidates, self.cand_rows)
        for _ in range(50):
            improved = False
            for i in range(fixed, n):
                best_v, best_j = cur, -1
                for lo in range(0, len(G), 2048):
                    v = self.batch(M, F[i], G[lo:lo + 2048])
                    j = int(np.argmin(v))
                    if is_gain(v[j], best_v):
                        best_v, best_j = float(v[j]), lo + j
                if best_j >= 0 and (got := self._replace(D, F, i, cands[best_j], G[best_j], M, cur)):
                    M, cur = got
                    improved = True
            if not improved:
                break
        return D, cur

    def improve(self, D: np.ndarray, fixed: int = 0, polish: bool = False, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Coordinate exchange and row exchange in turn until neither improves."""
        D, v = self.exchange(D, fixed, polish=polish, coarse=coarse)
        for _ in range(10):
            D2, v2 = self.row_exchange(D, fixed, coarse=coarse)
            if not is_gain(v2, v):
                break
            D, v = self.exchange(D2, fixed, polish=polish, coarse=coarse)
        return D, v

    def greedy_start(self, n: int, fixed: np.ndarray | None = None) -> np.ndarray:
        """Sequential build (Dykstra 1971): add, one at a time, the candidate point (numeric
        coordinates at -1, 0, +1 where the pool has them) that most improves the criterion."""
        cands, G = self._on_grid(self.candidates, self.cand_rows)
        rows = [] if fixed is None else list(fixed)
        M = self.ridge(n) * 1e3
        if rows:
            F = design_matrix(np.array(rows), self.terms)
            M = M + F.T @ F
        for _ in range(n):
            v = self.batch(M, None, G)
            j = int(np.argmin(v))
            rows.append(cands[j])
            M = M + np.outer(G[j], G[j])
        return np.array(rows)[0 if fixed is None else len(fixed):]

    def random_start(self, n: int, rng, grid: bool = False) -> np.ndarray:
        src = self._on_grid(self.pool)[0] if grid else self.pool
        idx = rng.integers(0, len(src), size=n)
        D = src[idx].copy()
        for j, f in enumerate(self.space.factors):
            if f.kind == "categoric":
                D[:, j] = rng.integers(0, f.n_levels, size=n)
        return D


def halton(n: int, d: int, seed: int = 0) -> np.ndarray:
    """``n`` points of the ``d``-dimensional Halton sequence in [0, 1)^d (radical inverses in
    the first ``d`` primes, from index 1), shifted modulo 1 by a uniform random vector drawn
    from ``seed`` (Cranley-Patterson rotation): low-discrepancy candidates without SciPy.

    >>> halton(4, 2, seed=None).round(4).tolist()
    [[0.5, 0.3333], [0.25, 0.6667], [0.75, 0.1111], [0.125, 0.4444]]
    """
    primes: list[int] = []
    c = 2
    while len(primes) < d:
        if all(c % q for q in primes):
            primes.append(c)
        c += 1
    out = np.empty((n, d))
    idx = np.arange(1, n + 1)
    for j, b in enumerate(primes):
        x, f, i = np.zeros(n), 1.0 / b, idx.copy()
        while i.any():
            x += f * (i % b)
            i //= b
            f /= b
        out[:, j] = x
    if seed is None:
        return out
    return (out + np.random.default_rng(seed).random(d)) % 1.0


def candidate_pool(space, constraints, n: int = 512, seed: int = 0) -> np.ndarray:
    """Feasible coded candidate points (grid of 21 levels for one or two numeric factors,
    the 3^k / 5^k grid and shifted Halton points otherwise, :func:`halton`); categoric
    columns 0."""
    k = len(space)
    num = space.numeric_index
    kn = len(num)
    parts = []
    levels = GRID if kn <= 2 else (np.linspace(-1, 1, 5) if kn <= 5 else np.array([-1.0, 0.0, 1.0]))
    if len(levels) ** kn <= 20000:
        parts.append(np.array(np.meshgrid(*[levels] * kn)).reshape(kn, -1).T)
    parts.append(halton(n, kn, seed) * 2.0 - 1.0)
    P = np.vstack(parts)
    full = np.zeros((len(P), k))
    full[:, num] = P
    if constraints is not None and constraints:
        full = full[constraints.feasible_coded(full)]
        if not len(full):
            raise thin_region_error(constraints)
    return full


def at_every_level(pool: np.ndarray, space) -> np.ndarray:
    """The coded points of ``pool`` repeated at every combination of the categoric levels
    (the first categoric factor's level changing slowest); ``pool`` itself when there are
    no categoric factors."""
    cats = [i for i, f in enumerate(space.factors) if f.kind == "categoric"]
    if not cats:
        return pool
    import itertools

    reps = []
    for c in itertools.product(*[range(space.factors[i].n_levels) for i in cats]):
        q = pool.copy()
        q[:, cats] = c
        reps.append(q)
    return np.vstack(reps)
