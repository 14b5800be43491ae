"""Optimal designs by coordinate exchange (Meyer & Nachtsheim 1995), D, I or A.

Meyer, R. K. & Nachtsheim, C. J. (1995). The coordinate-exchange algorithm for
constructing exact optimal experimental designs. *Technometrics* 37(1), 60-69.

The model matrix ``X`` (n x p) of a standard model (:func:`rsm_lrg.terms.model_terms`:
linear, 2FI, quadratic, cubic; categoric factors effect-coded) gives the information
matrix ``M = X'X``. The criteria, as Design-Expert and JMP define them:

``D``  maximise ``det(M)``; reported as ``det(M)**(1/p) / n`` (per run);
``A``  minimise ``trace(M^-1)`` (the sum of the coefficient variances / sigma^2);
``I``  minimise the average prediction variance over the region,
       ``trace(M^-1 W)`` with the moment matrix ``W = mean over the region of f(x) f(x)'``
       (exact moments of the uniform measure on the coded cube [-1, 1]^k and uniform weight
       on the levels of categoric factors; on a constrained region the mean over about
       16 000 feasible quasi-random points).

Coordinate exchange: from a random feasible start, each coordinate of each run is set in
turn to the best of a grid of values (21 levels over [-1, 1] for a numeric factor, every
level of a categoric one) among those that keep the run inside the constraints, until a
whole pass changes nothing; a finer local grid then polishes the numeric settings. The
best of ``starts`` random starts is kept; every start comes from ``seed``, so the same seed
gives the same design. The updates are evaluated in batches (``M - f f' + g g'`` for every
candidate ``g``) with a tiny ridge so a singular start can still climb.

Design-Expert's extras: ``lof_points`` runs spread by distance (each the feasible
candidate farthest from every run so far: lack-of-fit points) and ``replicates`` runs that
repeat model points (each the repeat that best improves the criterion). By default, as
Design-Expert: ``p`` model points, 5 lack-of-fit points and 5 replicates; with ``runs=N``
every run is chosen by the criterion unless ``lof_points``/``replicates`` ask for some.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..terms import design_matrix, model_terms, n_columns
from .core import Design, as_factor_space, resolve_seed

__all__ = ["optimal", "criterion_value", "moment_matrix", "CRITERIA", "information"]

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


def _criterion(c: Any) -> str:
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
        raise _thin_region(constraints)
    pts = pts[ok]
    G = np.prod(pts[:, None, :] ** P[None, :, :], axis=2)  # numeric monomial of every column
    return (G.T @ G / G.shape[0]) * C


def _thin_region(constraints) -> ValueError:
    """The error for a constrained region that holds no point of the search (empty, or too
    thin to design in: ``x + y <= 0`` on ``x, y >= 0`` is one corner)."""
    texts = "; ".join(repr(c.text) for c in getattr(constraints, "items", ()))
    return ValueError(f"constraints {texts}: no point of the search satisfies them (the constrained region is "
                      "empty or too thin to design in, e.g. a single point or a line)")


def _value(M: np.ndarray, crit: str, W: np.ndarray | None) -> float:
    """Criterion to minimise (``-log det`` for D), batched over leading axes; inf if singular."""
    if crit == "D":
        sign, logdet = np.linalg.slogdet(M)
        return np.where(sign > 0, -logdet, np.inf)
    try:
        if crit == "A":
            inv = np.linalg.inv(M)
            v = np.trace(inv, axis1=-2, axis2=-1)
        else:
            v = np.trace(np.linalg.solve(M, np.broadcast_to(W, M.shape)), axis1=-2, axis2=-1)
    except np.linalg.LinAlgError:
        return np.full(M.shape[:-2], np.inf) if M.ndim > 2 else np.inf
    return np.where(np.isfinite(v) & (v > 0), v, np.inf)


def criterion_value(coded: np.ndarray, terms, criterion: str = "D", W: np.ndarray | None = None) -> float:
    """The criterion of coded runs as reported: D ``det(X'X)^(1/p) / n``; A
    ``trace((X'X)^-1)``; I ``trace((X'X)^-1 W)`` (``W`` from :func:`moment_matrix`). A
    singular design gives 0 (D) or inf (A, I)."""
    crit = _criterion(criterion)
    coded = np.asarray(coded, dtype=float)
    M = information(coded, terms)
    p = M.shape[0]
    if crit == "D":
        sign, logdet = np.linalg.slogdet(M)
        if sign <= 0 or np.linalg.cond(M) > 1e12:
            return 0.0
        return float(math.exp(logdet / p) / coded.shape[0])
    if np.linalg.cond(M) > 1e12:
        return math.inf
    return float(_value(M, crit, W))


def _gains(v: float, cur: float) -> bool:
    """Whether criterion value ``v`` (to minimise) is a real gain on ``cur`` (more than a
    relative 1e-10, so that rounding never cycles an exchange)."""
    return v < cur - 1e-10 * max(1.0, abs(cur))


class _Problem:
    def __init__(self, space, terms, crit, W, constraints, pool):
        self.space, self.terms, self.crit, self.W, self.cons = space, terms, crit, W, constraints
        self.k = len(space)
        self.p = n_columns(terms)
        self.pool = pool
        cands = _at_every_level(pool, space)
        self._P = None
        if not space.has_categoric:  # all numeric: model rows as products of powers (fast path)
            self._P = np.array([t.powers for t in terms], dtype=int)
        self.candidates = cands
        self.cand_rows = self.rows(cands)
        self._cache_key = None
        self.values = []
        for f in space.factors:
            self.values.append(GRID if f.kind == "numeric" else np.arange(f.n_levels, dtype=float))

    def rows(self, coded: np.ndarray) -> np.ndarray:
        """Model rows of coded points (:func:`rsm_lrg.terms.design_matrix`)."""
        if self._P is not None:
            return np.prod(coded[:, None, :] ** self._P[None, :, :], axis=2)
        return design_matrix(coded, self.terms)

    def _prepared(self, M: np.ndarray):
        """``(A, K, base)`` for ``M`` (cached while ``M`` is the same array), or None when
        ``M`` is badly conditioned."""
        if self._cache_key is not None and self._cache_key[0] is M:
            return self._cache_key[1]
        out = None
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
        prep = self._prepared(M)
        if prep is not None:
            A, K, base = prep
            AG = G @ A
            gAg = np.einsum("ij,ij->i", AG, G)
            fA = A @ f
            fAf = float(fA @ f)
            fAg = G @ fA
            with np.errstate(all="ignore"):
                if self.crit == "D":
                    r = (1.0 + gAg) * (1.0 - fAf) + fAg ** 2
                    v = -(base + np.log(r))
                    ok = r > 0
                else:
                    KG = G @ K
                    t11 = np.einsum("ij,ij->i", KG, G)
                    t12 = KG @ f
                    t22 = float(f @ K @ f)
                    s11, s12, s22 = 1.0 + gAg, fAg, fAf - 1.0
                    det = s11 * s22 - s12 ** 2
                    v = base - (s22 * t11 - 2.0 * s12 * t12 + s11 * t22) / det
                    ok = np.abs(det) > 1e-12
            return np.where(ok & np.isfinite(v), v, np.inf)
        base = M - np.outer(f, f)
        return _value(base[None, :, :] + G[:, :, None] * G[:, None, :], self.crit, self.W)

    def ridge(self, n):
        return 1e-9 * max(n, 1) * np.eye(self.p)

    def score(self, D):
        M = information(D, self.terms) + self.ridge(len(D))
        return float(_value(M, self.crit, self.W))

    def _start(self, D: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """A copy of ``D`` to exchange on, its model rows ``F``, information ``M`` (with the
        small ridge) and criterion value."""
        D = D.copy()
        F = design_matrix(D, self.terms)
        M = F.T @ F + self.ridge(len(D))
        return D, F, M, float(_value(M, self.crit, self.W))

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
        v2 = float(_value(M2, self.crit, self.W))
        if not _gains(v2, cur):
            return None
        D[i], F[i] = x, g
        return M2, v2

    def exchange(self, D: np.ndarray, fixed: int = 0, polish: bool = True, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Coordinate exchange on rows ``fixed..`` of ``D`` (earlier rows held); ``coarse``:
        numeric coordinates at -1, 0, +1 only (the levels of the classical designs)."""
        D, F, M, cur = self._start(D)
        n = len(D)
        num = self.space.numeric_index
        for phase in (0, 1, 2) if polish else (0,):
            coords = range(self.k) if phase == 0 else num
            step = 0.05 / (5 ** (phase - 1)) if phase else 0.0
            for _ in range(100):
                improved = False
                for i in range(fixed, n):
                    for j in coords:
                        if phase == 0:
                            vals = self.values[j]
                            if coarse and self.space.factors[j].kind == "numeric":
                                vals = _COARSE
                        else:
                            vals = np.clip(D[i, j] + np.linspace(-step, step, 11), -1.0, 1.0)
                        cand = np.repeat(D[i:i + 1], len(vals), axis=0)
                        cand[:, j] = vals
                        if self.cons is not None and self.cons:
                            ok = self.cons.feasible_coded(cand)
                            if not ok.any():
                                continue
                            cand = cand[ok]
                        G = self.rows(cand)
                        v = self.batch(M, F[i], G)
                        b = int(np.argmin(v))
                        if _gains(v[b], cur) and (got := self._replace(D, F, i, cand[b], G[b], M, cur)):
                            M, cur = got
                            improved = True
                if not improved:
                    break
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
                    if _gains(v[j], best_v):
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
            if not _gains(v2, v):
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


def _pool(space, constraints, n: int = 512, seed: int = 0) -> np.ndarray:
    """Feasible coded candidate points (grid of 21 levels for one or two numeric factors,
    the 3^k / 5^k grid and Sobol' points otherwise); categoric columns 0."""
    from scipy.stats import qmc

    k = len(space)
    num = space.numeric_index
    kn = len(num)
    parts = []
    levels = GRID if kn <= 2 else (np.linspace(-1, 1, 5) if kn <= 5 else np.array([-1.0, 0.0, 1.0]))
    if len(levels) ** kn <= 20000:
        parts.append(np.array(np.meshgrid(*[levels] * kn)).reshape(kn, -1).T)
    parts.append(qmc.Sobol(kn, scramble=True, seed=seed).random(n) * 2.0 - 1.0)
    P = np.vstack(parts)
    full = np.zeros((len(P), k))
    full[:, num] = P
    if constraints is not None and constraints:
        full = full[constraints.feasible_coded(full)]
        if not len(full):
            raise _thin_region(constraints)
    return full


def _at_every_level(pool: np.ndarray, space) -> np.ndarray:
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


def _lof_points(D: np.ndarray, pool: np.ndarray, space, count: int) -> np.ndarray:
    """``count`` candidates each farthest (coded distance; a categoric mismatch counts 2)
    from every run so far: Design-Expert's lack-of-fit points, spread by distance."""
    num = space.numeric_index
    cat = [i for i in range(len(space)) if i not in num]
    cands = _at_every_level(pool, space)
    out = []
    cur = D.copy()
    for _ in range(count):
        d = np.sqrt(((cands[:, None, num] - cur[None, :, num]) ** 2).sum(-1))
        if cat:
            d = d + 2.0 * (cands[:, None, cat] != cur[None, :, cat]).sum(-1)
        best = int(np.argmax(d.min(axis=1)))
        out.append(cands[best])
        cur = np.vstack([cur, cands[best]])
    return np.array(out).reshape(count, len(space))


def optimal(
    factors: Any,
    model: str = "quadratic",
    criterion: str = "I",
    runs: int | None = None,
    lof_points: int | None = None,
    replicates: int | None = None,
    constraints: Any = None,
    seed: Any = None,
    starts: int | None = None,
    randomize: bool = True,
) -> Design:
    """An exact D-, I- or A-optimal design by coordinate exchange (Meyer & Nachtsheim 1995).

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        Numeric (``"NAME=LOW:HIGH"``) and categoric (``"NAME=cat:L1,L2"``) factors.
    model : {"linear", "2fi", "quadratic", "cubic"}
        The model the design must support (:func:`rsm_lrg.terms.model_terms`).
    criterion : {"D", "I", "A"}, default "I"
        Design-Expert's default for response surfaces is I.
    runs : int or None
        Total runs. ``None``: Design-Expert's default, ``p + lof + replicates`` with
        5 lack-of-fit points and 5 replicates unless given.
    lof_points, replicates : int or None
        Lack-of-fit points (spread by distance) and replicates of model points. With
        ``runs`` given both default to 0; without, to 5.
    constraints : str, list of str or Constraints
        Inequalities in actual units (:mod:`rsm_lrg.design.constraints`); every run
        satisfies every one.
    seed : int, numpy.random.Generator or None
        Seeds the random starts and the run order (``None``: drawn and recorded).
    starts : int or None
        Random starts in the continuous region; twice as many start on the -1/0/+1 grid
        and one more is a sequential build (default 10 for up to 10 model columns, 6 up
        to 21, 3 beyond).
    randomize : bool
        ``False``: run order = standard order (model points, replicates, lof points).

    Returns
    -------
    Design
        ``kind="optimal"``; ``options`` holds the criterion, its value
        (:func:`criterion_value`), the model, the numbers of model points, replicates and
        lack-of-fit points, the constraints and the seed.

    Examples
    --------
    >>> d = optimal(["x=0:1", "y=0:1"], model="quadratic", criterion="D", runs=9, seed=1)
    >>> d.n_runs, round(d.options["criterion_value"], 4)
    (9, 0.4622)
    """
    from .constraints import Constraints

    space = as_factor_space(factors)
    crit = _criterion(criterion)
    terms = model_terms(space.letters, model, space.categoric or None)
    p = n_columns(terms)
    check_columns(p, model, len(space))
    if constraints is not None and not isinstance(constraints, Constraints):
        constraints = Constraints.parse(constraints, space)
    for name, v in (("runs", runs), ("lof_points", lof_points), ("replicates", replicates), ("starts", starts)):
        if v is not None and (isinstance(v, (bool, np.bool_)) or int(v) != v or v < 0):
            raise ValueError(f"{name} must be a whole number >= 0 (got {v!r})")
    if runs is None:
        L = 5 if lof_points is None else int(lof_points)
        R = 5 if replicates is None else int(replicates)
        runs = p + L + R
    else:
        runs = int(runs)
        L = 0 if lof_points is None else int(lof_points)
        R = 0 if replicates is None else int(replicates)
    n_model = runs - L - R
    if n_model < 0:
        raise ValueError(f"{L} lack-of-fit points and {R} replicates are more than the {runs} runs; the {model} "
                         f"model in {len(space)} factors needs at least {p} model points besides them")
    if n_model < p:
        raise ValueError(f"{runs} runs leave {n_model} model points after {L} lack-of-fit points and {R} replicates; "
                         f"the {model} model in {len(space)} factors needs at least {p} (one per coefficient)")
    if runs > MAX_RUNS:
        raise ValueError(f"at most {MAX_RUNS} runs (got {runs})")
    rng, used_seed = resolve_seed(seed)
    W = moment_matrix(space, terms, constraints) if crit == "I" else None
    pool = _pool(space, constraints, seed=int(rng.integers(2 ** 31)))
    prob = _Problem(space, terms, crit, W, constraints, pool)
    if starts is None:
        starts = 10 if p <= 10 else (6 if p <= 21 else 3)
    starts = min(max(1, int(starts)), MAX_STARTS)
    best, best_v = None, math.inf
    # starts on the -1/0/+1 grid (cheap, discrete: the levels of the classical designs), then
    # continuous random starts; the sequential (greedy) build is one more start
    plan = ["greedy"] + ["coarse"] * (2 * starts) + ["continuous"] * starts
    for how in plan:
        if how == "greedy":
            D0 = prob.greedy_start(n_model)
        else:
            D0 = prob.random_start(n_model, rng, grid=how == "coarse")
        D, v = prob.improve(D0, coarse=how != "continuous")
        if v < best_v or best is None:
            best, best_v = D, v
    best, best_v = prob.improve(best, polish=True)
    # replicates: the repeat of a model point that best improves the criterion
    D = best
    for _ in range(R):
        uniq = np.unique(D, axis=0)
        scores = [prob.score(np.vstack([D, u])) for u in uniq]
        D = np.vstack([D, uniq[int(np.argmin(scores))]])
    if L:
        D = np.vstack([D, _lof_points(D, pool, space, L)])
    value = criterion_value(D, terms, crit, W)
    options = {
        "criterion": crit,
        "criterion_value": value,
        "model": model,
        "model_terms": p,
        "model_points": n_model,
        "replicates": R,
        "lof_points": L,
        "starts": starts,
        "constraints": [] if constraints is None else constraints.expressions,
        "algorithm": "coordinate exchange (Meyer & Nachtsheim 1995)",
    }
    return Design.from_standard(space, "optimal", D, seed=rng if used_seed is None else used_seed,
                                randomize=randomize, options=options)
