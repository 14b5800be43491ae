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

from ..errors import ParameterError
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

#: Most (run, candidate) pairs ranked at once by :meth:`ExchangeProblem.fedorov`; beyond it
#: the exchange goes run by run (:meth:`ExchangeProblem.row_exchange`).
FEDOROV_PAIRS = 2 ** 15

def check_criterion(c: Any) -> str:
    """``c`` as one of :data:`CRITERIA` (upper case), or a ValueError."""
    if not isinstance(c, str) or c.strip().upper() not in CRITERIA:
        raise ParameterError("criterion", f"criterion must be one of {', '.join(CRITERIA)} (got {c!r})")
    return c.strip().upper()


def check_columns(p: int, model: str, k: int) -> None:
    """ValueError when the model is beyond :data:`MAX_COLUMNS` columns."""
    if p > MAX_COLUMNS:
        raise ParameterError("model", f"the {model} model in {k} factors has {p} coefficients, beyond the {MAX_COLUMNS} an optimal "
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


def thin_region_error(constraints) -> ParameterError:
    """The error for a constrained region that holds no point of the search (empty, or too
    thin to design in: ``x + y <= 0`` on ``x, y >= 0`` is one corner)."""
    texts = "; ".join(repr(c.text) for c in getattr(constraints, "items", ()))
    return ParameterError("constraints", f"constraints {texts}: no point of the search satisfies them (the "
                          "constrained region is empty or too thin to design in, e.g. a single point or a line)")


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
    singular design gives 0 (D) or inf (A, I).

    Parameters
    ----------
    coded : numpy.ndarray, shape (n, k)
        The runs in coded units.
    terms : sequence of Term
        The model's terms.
    criterion : {"D", "A", "I"}, default "D"
        The criterion.
    W : numpy.ndarray, optional
        The moment matrix of the region (I only; the cube's by default).

    Returns
    -------
    float
        The criterion's value (0 or inf for a singular design).
    """
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

def _pair_value(crit: str, base: float, gAg: np.ndarray, fAg: np.ndarray, fAf: np.ndarray,
                t11: Any = None, t12: Any = None, t22: Any = None) -> np.ndarray:
    """Criterion (to minimise) of ``M - f f' + g g'`` from the quadratic forms of ``A = M^-1``
    (and of ``K = A W A``, ``A A`` for I, A): ``det`` times ``(1 + g'Ag)(1 - f'Af) + (f'Ag)^2``
    (Fedorov 1972; Meyer & Nachtsheim 1995) and the rank-two Woodbury identity for the traces of
    A and I. ``base`` is ``log det M`` (D) or the current trace (I, A); inf where the exchange
    leaves M singular."""
    with np.errstate(all="ignore"):
        if crit == "D":
            r = (1.0 + gAg) * (1.0 - fAf) + fAg ** 2
            v = -(base + np.log(r))
            ok = r > 0
        else:
            s11, s12, s22 = 1.0 + gAg, fAg, fAf - 1.0
            det = s11 * s22 - s12 ** 2
            v = base - (s22 * t11 - 2.0 * s12 * t12 + s11 * t22) / det
            ok = np.abs(det) > 1e-12
    return np.where(ok & np.isfinite(v), v, np.inf)


def _pair_key(crit: str, base: float, gAg: np.ndarray, fAg: np.ndarray, fAf: np.ndarray,
              t11: Any = None, t12: Any = None, t22: Any = None) -> np.ndarray:
    """A ranking key of the exchanges of :func:`_pair_value` (smaller is better, the same
    order): for D minus the determinant ratio ``(1 + g'Ag)(1 - f'Af) + (f'Ag)^2``, without a
    logarithm per pair (:func:`_key_value` turns one key into the criterion); for I, A the
    criterion itself."""
    if crit != "D":
        return _pair_value(crit, base, gAg, fAg, fAf, t11, t12, t22)
    with np.errstate(all="ignore"):
        r = (1.0 + gAg) * (1.0 - fAf) + fAg ** 2
        return np.where(r > 0, -r, np.inf)


def _key_value(crit: str, base: float, key: float) -> float:
    """The criterion (to minimise) of one exchange from its :func:`_pair_key`."""
    if crit != "D":
        return float(key)
    return -(base + math.log(-key)) if key < 0 and math.isfinite(key) else math.inf


class _Rank2:
    """``A = M^-1`` (and ``K = A W A`` for I, ``A A`` for A) of an information matrix ``M``,
    kept through the exchanges ``M - f f' + g g'`` by the rank-two Woodbury identity (``O(p^2)``
    per exchange, no factorisation), refreshed from ``M`` every :attr:`REFRESH` exchanges. The
    quadratic forms ``x'Ax``, ``x'Ay`` (and with ``K``) of any stored points follow the same
    update in ``O(p)`` per point (:meth:`shift_quad`, :meth:`shift_cross`).

    With ``U = [g, f]``, ``B = A U`` and ``S = [[1 + g'Ag, g'Af], [g'Af, f'Af - 1]]``:
    ``A' = A - B S^-1 B'``, ``det M' = -det S det M``; with ``H = A W B``, ``Q = B' W B``:
    ``K' = K - B S^-1 H' - H S^-1 B' + B S^-1 Q S^-1 B'`` and ``trace(A'W) = trace(AW) -
    trace(S^-1 Q)``.
    """

    REFRESH = 20

    def __init__(self, crit: str, W: np.ndarray | None):
        self.crit, self.W = crit, W
        self.ok = False
        self.A = self.K = np.empty((0, 0))
        self.base = 0.0
        self.age = 0
        self.d: tuple[np.ndarray, np.ndarray | None, np.ndarray, np.ndarray | None] | None = None

    def reset(self, M: np.ndarray) -> bool:
        """Factorise ``M`` afresh; False (and :attr:`ok` False) when it is badly conditioned
        (1-norm condition number 1e8 or more), where the exact criteria must be used."""
        self.age = 0
        self.ok = False
        try:
            A = np.linalg.inv(M)
        except np.linalg.LinAlgError:
            return False
        if not np.all(np.isfinite(A)) or np.abs(M).sum(0).max() * np.abs(A).sum(0).max() >= 1e8:
            return False
        A = 0.5 * (A + A.T)
        self.A, self.ok = A, True
        if self.crit == "D":
            self.base = float(np.linalg.slogdet(M)[1])
        else:
            WA = A if self.crit == "A" else cast(np.ndarray, self.W) @ A
            self.K = A @ WA
            self.base = float(np.trace(WA))
        return True

    def quad(self, X: np.ndarray) -> tuple[np.ndarray, Any]:
        """``(x'Ax, x'Kx)`` of every row x of X (last axis; K part None for D)."""
        XA = X @ self.A
        xax = np.einsum("...j,...j->...", XA, X)
        return xax, (None if self.crit == "D" else np.einsum("...j,...j->...", X @ self.K, X))

    def cross(self, X: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, Any]:
        """``(x'Af, x'Kf)`` of every row x of X against the vector(s) f (broadcast)."""
        Af = f @ self.A
        if f.ndim == 1:  # one f: a matrix-vector product
            return X @ Af, (None if self.crit == "D" else X @ (f @ self.K))
        xaf = np.einsum("...j,...j->...", X, Af)
        return xaf, (None if self.crit == "D" else np.einsum("...j,...j->...", X, f @ self.K))

    def update(self, f: np.ndarray, g: np.ndarray) -> None:
        """Exchange ``f`` for ``g`` in ``M``: update ``A``, ``K`` and the criterion; the
        pieces for the stored quadratic forms are kept in :attr:`d` until the next update."""
        A = self.A
        U = np.array([g, f]).T
        B = A @ U
        S = U.T @ B
        S[0, 0] += 1.0
        S[1, 1] -= 1.0
        det = S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0]
        Si = np.array([[S[1, 1], -S[0, 1]], [-S[1, 0], S[0, 0]]]) / det
        self.A = A - B @ Si @ B.T
        if self.crit == "D":
            self.base += math.log(-det)
            self.d = (B, None, Si, None)
        else:
            H = B if self.crit == "A" else cast(np.ndarray, self.W) @ B
            H = A @ H
            Q = B.T @ (B if self.crit == "A" else cast(np.ndarray, self.W) @ B)
            SQS = Si @ Q @ Si
            BSi = B @ Si
            self.K = self.K - BSi @ H.T - H @ BSi.T + B @ SQS @ B.T
            self.base -= float(np.trace(Si @ Q))
            self.d = (B, H, Si, SQS)
        self.age += 1

    @property
    def stale(self) -> bool:
        """Whether the kept inverse is due for an exact refresh."""
        return not self.ok or self.age >= self.REFRESH

    def projections(self, X: np.ndarray) -> tuple[np.ndarray, Any]:
        """``(X B, X H)`` of the last update (inputs of :meth:`shift_quad`, :meth:`shift_cross`)."""
        B, H, _, _ = cast(tuple, self.d)
        return X @ B, (None if H is None else X @ H)

    def shift_quad(self, xq: list[Any], proj: tuple[np.ndarray, Any]) -> None:
        """Update ``(x'Ax, x'Kx)`` of stored points in place for the last exchange."""
        _, _, Si, SQS = cast(tuple, self.d)
        XB, XH = proj
        XBS = XB @ Si
        xq[0] -= np.einsum("...j,...j->...", XBS, XB)
        if XH is not None:
            xq[1] -= 2.0 * np.einsum("...j,...j->...", XBS, XH) - np.einsum("...j,...j->...", XB @ SQS, XB)

    def shift_cross(self, xq: list[Any], proj: tuple[np.ndarray, Any],
                    fproj: tuple[np.ndarray, Any]) -> None:
        """Update the cross forms ``(x'Af, x'Kf)`` in place (``proj`` of the x, ``fproj`` of
        the f, broadcast against each other) for the last exchange."""
        _, _, Si, SQS = cast(tuple, self.d)
        XB, XH = proj
        FB, FH = fproj
        FBS = FB @ Si
        xq[0] -= np.einsum("...j,...j->...", FBS, XB)
        if XH is not None:
            xq[1] -= (np.einsum("...j,...j->...", FBS, XH) + np.einsum("...j,...j->...", FH @ Si, XB)
                      - np.einsum("...j,...j->...", FB @ SQS, XB))


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
        self._idx: np.ndarray | None = None
        if not space.has_categoric and not any(t.diff for t in terms):
            # all numeric monomials: each a product of gathered columns (fast path)
            factors = [[i + 1 for i, e in enumerate(t.powers) for _ in range(int(e))] for t in terms]
            deg = max(1, max(len(f) for f in factors))
            # column 0 of [1, x] pads the lower-degree monomials
            self._idx = np.array([f + [0] * (deg - len(f)) for f in factors], dtype=np.intp).T
        self.candidates = cands
        self.cand_rows = self.rows(cands)
        # whether the -1/0/+1 grid points of the pool can estimate the model (a cubic cannot: x^3
        # is x there); if not, the grid starts and moves are those of the whole pool
        on = np.all(np.isin(cands[:, space.numeric_index], _COARSE), axis=1)
        Gon = self.cand_rows[on]
        self.grid_ok = bool(on.sum() >= max(2, self.p) and np.linalg.cond(Gon.T @ Gon) < 1e12)
        self._cache_key = None
        self.values = []
        for f in space.factors:
            self.values.append(GRID if f.kind == "numeric" else np.arange(f.n_levels, dtype=float))

    def rows(self, coded: np.ndarray) -> np.ndarray:
        """Model rows of coded points (:func:`rsm_lrg.terms.design_matrix`); all-numeric
        factors: each monomial as a product of gathered columns of ``[1, x]`` (no ``**`` per
        entry; any leading axes)."""
        if self._idx is not None:
            X1 = np.empty(coded.shape[:-1] + (self.k + 1,))
            X1[..., 0] = 1.0
            X1[..., 1:] = coded
            out = X1[..., self._idx[0]]
            for d in range(1, len(self._idx)):
                out *= X1[..., self._idx[d]]
            return out
        return design_matrix(coded, self.terms)

    def _prepared(self, M: np.ndarray):
        """``(A, K, base)`` for ``M`` (cached while ``M`` is the same array), or None when
        ``M`` is badly conditioned."""
        if self._cache_key is not None and self._cache_key[0] is M:
            return self._cache_key[1]
        st = _Rank2(self.crit, self.W)
        out = (st.A, st.K, st.base) if st.reset(M) else None
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
        if self.crit == "D":
            return _pair_value("D", base, gAg, fAg, fAf)
        FK = F @ K
        t11 = np.einsum("ij,ij->i", G @ K, G)
        t12 = np.einsum("ij,ij->i", FK[own], G)
        t22 = np.einsum("ij,ij->i", FK, F)[own]
        return _pair_value(self.crit, base, gAg, fAg, fAf, t11, t12, t22)

    def _slots(self, coords, phase: int, step: float, coarse: bool) -> tuple[np.ndarray, np.ndarray]:
        """The single-coordinate moves of one stage, as slots: ``(factor (s,), value (s,))``.
        Phase 0 tries the factor's levels (-1, 0, +1 with ``coarse``), phases 1 and 2 eleven
        steps of ``step`` around the current setting (``value`` then an offset)."""
        col, val = [], []
        for j in coords:
            if phase == 0:
                v = self.values[j]
                if coarse and self.space.factors[j].kind == "numeric":
                    v = _COARSE
            else:
                v = np.linspace(-step, step, 11)
            col.append(np.full(len(v), j))
            val.append(v)
        return np.concatenate(col), np.concatenate(val)

    def _move_table(self, base: np.ndarray, slots: tuple[np.ndarray, np.ndarray],
                    relative: bool) -> tuple[np.ndarray, np.ndarray]:
        """The moves of each run of ``base`` (m x k) in the slots of :meth:`_slots`: ``(points
        (m, s, k), usable (m, s))``, a slot unusable where it keeps the current setting or
        breaks a constraint (``relative``: the values are offsets, clipped to [-1, 1])."""
        col, val = slots
        m, k = base.shape
        s = len(col)
        P = np.repeat(base[:, None, :], s, axis=1)
        cur = base[:, col]
        new = np.clip(cur + val, -1.0, 1.0) if relative else np.broadcast_to(val, (m, s))
        P[:, np.arange(s), col] = new
        usable = new != cur
        if self.cons is not None and self.cons and P.size:
            usable &= self.cons.feasible_coded(P.reshape(-1, k)).reshape(m, s)
        return P, usable

    def ridge(self, n):
        return 1e-9 * max(n, 1) * np.eye(self.p)

    def score(self, D):
        M = information(D, self.terms) + self.ridge(len(D))
        return float(information_criterion(M, self.crit, self.W))

    def _start(self, D: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """A copy of ``D`` to exchange on, its model rows ``F``, information ``M`` (with the
        small ridge) and criterion value."""
        D = D.copy()
        F = self.rows(D)
        M = F.T @ F + self.ridge(len(D))
        return D, F, M, float(information_criterion(M, self.crit, self.W))

    def _on_grid(self, points: np.ndarray, *rows: np.ndarray) -> tuple[np.ndarray, ...]:
        """``points`` (and the matching ``rows``) with every numeric coordinate at -1, 0 or
        +1, when there are at least two such points and the grid can estimate the model
        (:attr:`grid_ok`); else all of them."""
        on = np.all(np.isin(points[:, self.space.numeric_index], _COARSE), axis=1)
        if on.sum() >= 2 and self.grid_ok:
            return (points[on], *(r[on] for r in rows))
        return (points, *rows)

    def _replace(self, D: np.ndarray, F: np.ndarray, i: int, x: np.ndarray, g: np.ndarray, M: np.ndarray,
                 cur: float) -> tuple[np.ndarray, float] | None:
        """The acceptance step of both exchanges: run ``i`` of ``D`` (model row ``F[i]``;
        information ``M``, criterion ``cur``) is replaced by the point ``x`` (model row ``g``)
        only if the exact criterion of the new information matrix is a real gain (the
        updates of :class:`_Rank2` and :meth:`batch` only rank the candidates). On a gain ``D``
        and ``F`` are updated in place and the new ``(M, criterion)`` returned; else None."""
        M2 = M - np.outer(F[i], F[i]) + np.outer(g, g)
        v2 = float(information_criterion(M2, self.crit, self.W))
        if not is_gain(v2, cur):
            return None
        D[i], F[i] = x, g
        return M2, v2

    def exchange(self, D: np.ndarray, fixed: int = 0, polish: bool = True, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Coordinate exchange on rows ``fixed..`` of ``D`` (earlier rows held); ``coarse``:
        numeric coordinates at -1, 0, +1 only (the levels of the classical designs).

        Each step ranks every single-coordinate move of every run at once and makes the best
        one that the exact criterion confirms (:meth:`_replace`), until no move gains; phases
        1 and 2 (``polish``) then refine the numeric coordinates by steps of 0.05 and 0.01.
        The moves sit in a fixed table (run x slot); ``M^-1`` and the quadratic forms of every
        move are carried from step to step by rank-two updates (:class:`_Rank2`, ``O(p)`` per
        move and step), and only the moved run's slots are remade."""
        D, F, M, cur = self._start(D)
        n = len(D)
        rows = np.arange(fixed, n)
        m = len(rows)
        if not m:
            return D, cur
        num = self.space.numeric_index
        st = _Rank2(self.crit, self.W)
        # off the coarse grid, the -1/0/+1 levels first (few moves a step, most of the climb),
        # then every level
        stages = [(0, True)] + ([] if coarse else [(0, False)]) + ([(1, False), (2, False)] if polish else [])
        for phase, coarse_now in stages:
            coords = range(self.k) if phase == 0 else num
            if not len(coords):
                continue
            step = 0.05 / (5 ** (phase - 1)) if phase else 0.0
            slots = self._slots(coords, phase, step, coarse_now)
            P, usable = self._move_table(D[rows], slots, phase > 0)
            s = P.shape[1]
            G = self.rows(P.reshape(-1, self.k)).reshape(m, s, self.p)
            own = np.repeat(rows, s)
            gq: list[Any] = []
            xq: list[Any] = []
            fq: list[Any] = []
            st.ok = False  # a new table: its forms afresh
            for _ in range(100 * m * len(coords)):
                if st.stale:
                    st.reset(M)
                    if st.ok:
                        gq = list(st.quad(G))
                        Fr = F[rows]
                        fq = list(st.quad(Fr))
                        xq = list(st.cross(G, Fr[:, None, :]))
                if st.ok:
                    t11, t12, t22 = (gq[1], xq[1], fq[1][:, None]) if self.crit != "D" else (None, None, None)
                    v = _pair_key(self.crit, st.base, gq[0], xq[0], fq[0][:, None], t11, t12, t22)
                    crit, base = self.crit, st.base
                else:  # badly conditioned M: exact criteria of every exchange
                    v = self.batch_pairs(M, F, own, G.reshape(m * s, self.p)).reshape(m, s)
                    crit, base = "value", 0.0
                v = np.where(usable, v, np.inf).reshape(-1)
                got, a, b = None, -1, -1
                for _try in range(3):  # the ranking is an update; the exact value decides
                    best = int(np.argmin(v))
                    if not is_gain(_key_value(crit, base, v[best]), cur):
                        break
                    v[best] = np.inf
                    a, b = divmod(best, s)
                    f_old = F[rows[a]].copy()
                    got = self._replace(D, F, int(rows[a]), P[a, b], G[a, b], M, cur)
                    if got:
                        break
                if not got:
                    break
                M, cur = got
                if st.ok:
                    st.update(f_old, F[rows[a]])
                    proj = st.projections(G)
                    st.shift_quad(gq, proj)
                    FB, FH = st.projections(F[rows])
                    st.shift_quad(fq, (FB, FH))
                    st.shift_cross(xq, proj, (FB[:, None, :], None if FH is None else FH[:, None, :]))
                # the moved run's slots remade (its own forms afresh once the inverse is fresh)
                P[a], usable[a] = (t[0] for t in self._move_table(D[rows[a]][None, :], slots, phase > 0))
                G[a] = self.rows(P[a])
                if st.ok and not st.stale:
                    fa = F[rows[a]]
                    for q, (x1, x2) in ((gq, st.quad(G[a])), (xq, st.cross(G[a], fa))):
                        q[0][a] = x1
                        if x2 is not None:
                            q[1][a] = x2
                    f1, f2 = st.quad(fa)
                    fq[0][a] = f1
                    if f2 is not None:
                        fq[1][a] = f2
        return D, cur

    def row_exchange(self, D: np.ndarray, fixed: int = 0, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Replace whole runs by the best candidate point (the feasible pool at every level
        combination), run by run, until no replacement improves the criterion (the modified
        Fedorov exchange, Cook & Nachtsheim 1980). ``M^-1`` and every candidate's ``g'M^-1 g``
        are carried by rank-two updates (:class:`_Rank2`): a run costs ``O(p)`` per candidate."""
        D, F, M, cur = self._start(D)
        n = len(D)
        cands, G = self._on_grid(self.candidates, self.cand_rows) if coarse else (self.candidates, self.cand_rows)
        st = _Rank2(self.crit, self.W)
        gq: list[Any] = []
        for _ in range(50):
            improved = False
            for i in range(fixed, n):
                if st.stale and st.reset(M):
                    gq = list(st.quad(G))
                if st.ok:
                    x1, x2 = st.cross(G, F[i])
                    f1, f2 = st.quad(F[i])
                    v = _pair_key(self.crit, st.base, gq[0], x1, f1, gq[1], x2, f2)
                    j = int(np.argmin(v))
                    vj = _key_value(self.crit, st.base, v[j])
                else:
                    v = np.concatenate([self.batch(M, F[i], G[lo:lo + 2048]) for lo in range(0, len(G), 2048)])
                    j = int(np.argmin(v))
                    vj = float(v[j])
                if not is_gain(vj, cur):
                    continue
                f_old = F[i].copy()
                if got := self._replace(D, F, i, cands[j], G[j], M, cur):
                    M, cur = got
                    improved = True
                    if st.ok:
                        st.update(f_old, G[j])
                        st.shift_quad(gq, st.projections(G))
            if not improved:
                break
        return D, cur

    def fedorov(self, D: np.ndarray, fixed: int = 0, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Fedorov's exchange (Fedorov 1972; AlgDesign's ``optFederov``): each step makes the
        best exchange of any run (rows ``fixed..``) for any candidate point, all ``runs x
        candidates`` pairs ranked at once from ``F A G'`` (one matrix product) with ``A = M^-1``
        and every candidate's ``g'Ag`` carried by rank-two updates (:class:`_Rank2`); the exact
        criterion confirms each exchange (:meth:`_replace`). More pairs than
        :data:`FEDOROV_PAIRS`, or a badly conditioned start, go run by run instead
        (:meth:`row_exchange`)."""
        cands, G = self._on_grid(self.candidates, self.cand_rows) if coarse else (self.candidates, self.cand_rows)
        rows = np.arange(fixed, len(D))
        if len(rows) * len(G) > FEDOROV_PAIRS:
            return self.row_exchange(D, fixed, coarse)
        D, F, M, cur = self._start(D)
        st = _Rank2(self.crit, self.W)
        gq: list[Any] = []
        nc = len(G)
        for _ in range(50 * max(1, len(rows))):
            if st.stale:
                if not st.reset(M):
                    return self.row_exchange(D, fixed, coarse)
                gq = list(st.quad(G))
            Fr = F[rows]
            fAf, t22 = st.quad(Fr)
            fAg = (Fr @ st.A) @ G.T
            if self.crit == "D":
                v = _pair_key("D", st.base, gq[0][None, :], fAg, fAf[:, None])
            else:
                v = _pair_key(self.crit, st.base, gq[0][None, :], fAg, fAf[:, None], gq[1][None, :],
                              (Fr @ st.K) @ G.T, t22[:, None])
            v = v.reshape(-1)
            got, i, j = None, -1, -1
            for _try in range(3):  # the ranking is an update; the exact value decides
                best = int(np.argmin(v))
                if not is_gain(_key_value(self.crit, st.base, v[best]), cur):
                    break
                v[best] = np.inf
                a, j = divmod(best, nc)
                i = int(rows[a])
                f_old = F[i].copy()
                got = self._replace(D, F, i, cands[j], G[j], M, cur)
                if got:
                    break
            if not got:
                break
            M, cur = got
            st.update(f_old, G[j])
            st.shift_quad(gq, st.projections(G))
        return D, cur

    def improve(self, D: np.ndarray, fixed: int = 0, polish: bool = False, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Fedorov exchange (:meth:`fedorov`) and coordinate exchange (:meth:`exchange`) in
        turn until neither improves (``coarse`` only where the -1/0/+1 grid can estimate the
        model, :attr:`grid_ok`)."""
        coarse = coarse and self.grid_ok
        if coarse:  # on the -1/0/+1 grid the candidate-set exchange first, as optFederov
            D, v = self.fedorov(D, fixed, coarse=True)
            D2, v2 = self.exchange(D, fixed, polish=polish, coarse=True)
            if not is_gain(v2, v):
                return D, v
            D, v = D2, v2
        else:
            D, v = self.exchange(D, fixed, polish=polish, coarse=coarse)
        for _ in range(10):
            D2, v2 = self.fedorov(D, fixed, coarse=coarse)
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
