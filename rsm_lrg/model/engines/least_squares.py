"""The regression core: one least-squares factorisation, every statistic derived from it.

A fit is summarised by the triangular factor of the column-scaled model matrix with the
response appended, ``[X S^-1 | y - c] = Q [[R, z], [0, rho]]`` (Householder QR; ``S`` the
column norms, ``c`` a shift near the mean so that a response of 1e9 + small variation
loses no digits). ``R`` (p x p), ``z = Q'(y - c)`` and ``rho`` are all a fit needs:

* coefficients ``b = S^-1 R^-1 z`` (``c`` added back to the intercept) and their unscaled
  covariance ``(X'X)^-1 = S^-1 R^-1 R^-T S^-1``;
* the sequential (Type I) sum of squares of a column is ``z_j^2`` (columns in model
  order), the partial (Type III) one of a group ``S`` is ``b_S' (C_SS)^-1 b_S``;
* the residual sum of squares of the model is ``rho^2``; that of a sub-model (any subset
  of the columns, e.g. a nested model or a step of backward elimination) comes from the QR
  of the small matrix ``[R_cols | z]``, never from the n rows again;
* the hat diagonal ``h_i = |x_i S^-1 R^-1|^2``, the residuals and PRESS
  ``sum (e_i / (1 - h_ii))^2`` need a second pass over the rows;
* the VIF of a term is ``C_jj`` of the model without blocks times the centred sum of
  squares of its column, ``sum_{i>0} R_ij^2`` (the intercept being column 0): the diagonal
  of the inverse correlation matrix (Design-Expert's definition) without forming it.

Rank deficiency is decided here and only here: a column is *aliased* when its distance
from the span of the estimable columns before it is at most :data:`ALIAS_TOL` of its
length (the test R's ``lm`` makes with its pivoting QR, ``tol = 1e-7``, here ``1e-9``).

The factor can be accumulated over chunks of rows (TSQR: the factor so far is stacked on
the next chunk and re-factorised; :class:`Accumulator`), so a fit of 10^6 runs never holds
its n x p model matrix, and accumulators of separate chunks merge (a tree reduction over
the partitions of a Dask DataFrame). The second pass (hat diagonal, residuals) goes over
the same chunks again.

>>> import numpy as np
>>> X = np.column_stack([np.ones(4), [-1.0, -1.0, 1.0, 1.0]])
>>> fit = least_squares(X, np.array([1.0, 2.0, 3.0, 5.0]), names=["Intercept", "A"])
>>> fit.params.round(12).tolist(), round(fit.ss_res, 12), fit.hat.round(12).tolist()
([2.75, 1.25], 2.5, [0.5, 0.5, 0.5, 0.5])
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from ...present import format_g
from ..build.data import CHUNK_ROWS
from ..contract.prediction import IntervalForm

__all__ = ["Regression", "Accumulator", "PassSums", "least_squares", "factorise", "partial_ss", "ALIAS_TOL", "CHUNK_ROWS"]

#: A column is aliased when its distance from the span of the estimable columns before it
#: is at most this fraction of its length.
ALIAS_TOL = 1e-9

Chunks = Callable[[], Iterable[tuple[np.ndarray, np.ndarray]]]


def _qr_r(A: np.ndarray) -> np.ndarray:
    """Square upper-triangular factor (q x q) of ``A`` (m x q), zero rows added when m < q
    (Householder QR, LAPACK ``dgeqrf`` through ``numpy.linalg.qr``: the same factorisation as
    ``scipy.linalg.qr``, without importing SciPy)."""
    A = np.asarray(A, dtype=float)
    q = A.shape[1]
    if A.shape[0] == 0:
        return np.zeros((q, q))
    # numpy's stub types every mode as QRResult; mode="r" returns the array R itself
    R: np.ndarray = np.linalg.qr(A, mode="r")  # type: ignore[assignment]
    if R.shape[0] < q:
        R = np.vstack([R, np.zeros((q - R.shape[0], q))])
    return R


#: Rows of ``R`` solved together by :func:`_solve_r` (the rest of the work is matrix products).
_SOLVE_BLOCK = 16


def _solve_r(R: np.ndarray, B: np.ndarray, trans: bool = False) -> np.ndarray:
    """``R^-1 B`` (``R^-T B`` with ``trans``) for upper-triangular ``R`` (p x p) and ``B`` (p,)
    or (p, m): blocked back (forward) substitution, as LAPACK's ``dtrtrs``/BLAS ``dtrsm``
    arrange it: each block of rows is solved row by row, the rows below (above) it are
    updated by one matrix product."""
    B = np.asarray(B, dtype=float)
    vec = B.ndim == 1
    X = np.array(B.reshape(B.shape[0], -1), dtype=float, order="C")  # a copy: solved in place
    p, nb = R.shape[0], _SOLVE_BLOCK
    if not trans:
        for e in range(p, 0, -nb):
            s = max(0, e - nb)
            if e < p:
                X[s:e] -= R[s:e, e:] @ X[e:]
            for i in range(e - 1, s - 1, -1):
                if i + 1 < e:
                    X[i] -= R[i, i + 1:e] @ X[i + 1:e]
                X[i] /= R[i, i]
    else:
        for s in range(0, p, nb):
            e = min(p, s + nb)
            if s:
                X[s:e] -= R[:s, s:e].T @ X[:s]
            for i in range(s, e):
                if i > s:
                    X[i] -= R[s:i, i] @ X[s:i]
                X[i] /= R[i, i]
    return X[:, 0] if vec else X


def _independent_columns(R: np.ndarray, tol: float = ALIAS_TOL) -> tuple:
    """Columns of ``R`` (the factor of ``X``: ``R'R = X'X``) farther than ``tol`` of their
    length from the span of the independent columns before them, in order."""
    p = R.shape[1]
    norms = np.sqrt(np.einsum("ij,ij->j", R, R))
    d = np.abs(np.diag(R))
    if np.all(norms > 0) and np.all(d > tol * norms):
        return tuple(range(p))
    basis = np.zeros((R.shape[0], 0))
    kept = []
    for j in range(p):
        if not norms[j] > 0:
            continue
        v = R[:, j].copy()
        for _ in range(2):  # Gram-Schmidt twice is enough
            v -= basis @ (basis.T @ v)
        nv = float(np.linalg.norm(v))
        if nv > tol * norms[j]:
            basis = np.column_stack([basis, v / nv])
            kept.append(j)
    return tuple(kept)


# ----------------------------------------------------------------------------------------
# first pass: the triangular factor, accumulated over chunks
# ----------------------------------------------------------------------------------------
@dataclass
class Accumulator:
    """Triangular factor of ``[X | y - shift]`` accumulated over chunks of rows (TSQR).

    ``add`` stacks the factor so far on a chunk and re-factorises; ``merge`` combines two
    accumulators of separate rows (same ``shift``), so partitions can be reduced in a tree.
    """

    p: int
    shift: float | None = None
    n: int = 0
    raug: np.ndarray | None = None
    col_ss: np.ndarray | None = None
    col_sum: np.ndarray | None = None
    y_sums: list = field(default_factory=list)
    intercept: bool = True

    def add(self, X: np.ndarray, y: np.ndarray) -> Accumulator:
        X = np.asarray(X, dtype=float)
        y = np.asarray(y, dtype=float).ravel()
        m, p = X.shape
        if p != self.p or y.size != m:
            raise ValueError(f"a chunk of {m} x {p} rows and {y.size} responses does not fit a {self.p}-column model")
        if m == 0:
            return self
        ones = bool(np.all(X[:, 0] == 1.0))
        if self.shift is None:
            self.shift = math.fsum(y) / m if ones else 0.0
            self.intercept = ones
        elif self.intercept and not ones:
            if self.shift != 0.0:
                raise ValueError("the first column is all ones in one chunk and not in another")
            self.intercept = False
        top = 0 if self.raug is None else self.p + 1
        A = np.empty((m + top, p + 1), order="F")
        if top:
            A[:top] = self.raug
        A[top:, :p] = X
        A[top:, p] = y - self.shift
        self.raug = _qr_r(A)
        ss = np.einsum("ij,ij->j", X, X)
        sm = X.sum(axis=0)
        self.col_ss = ss if self.col_ss is None else self.col_ss + ss
        self.col_sum = sm if self.col_sum is None else self.col_sum + sm
        self.y_sums.append(math.fsum(y))
        self.n += m
        return self

    def merge(self, other: Accumulator) -> Accumulator:
        """The accumulator of the rows of both (they must share ``shift``)."""
        if other.n == 0:
            return self
        if self.n == 0:
            return other
        if self.shift != other.shift:
            raise ValueError("accumulators with different shifts cannot be merged")
        # both hold rows (n > 0), so add() has set their factors and column sums
        assert self.raug is not None and self.col_ss is not None and self.col_sum is not None
        assert other.raug is not None and other.col_ss is not None and other.col_sum is not None
        raug = _qr_r(np.vstack([self.raug, other.raug]))
        return Accumulator(p=self.p, shift=self.shift, n=self.n + other.n, raug=raug,
                           col_ss=self.col_ss + other.col_ss, col_sum=self.col_sum + other.col_sum,
                           y_sums=self.y_sums + other.y_sums, intercept=self.intercept and other.intercept)

    def result(self, names: Sequence[str] | None = None) -> Regression:
        """The :class:`Regression` of the rows added (first pass only: no hat diagonal yet)."""
        if self.n == 0:
            raise ValueError("no rows to fit")
        assert self.raug is not None and self.col_ss is not None and self.col_sum is not None  # set by add()
        assert self.shift is not None
        p = self.p
        names = tuple(names) if names is not None else tuple(f"x{j}" for j in range(p))
        norms = np.sqrt(self.col_ss)
        scale = np.where(norms > 0, norms, 1.0)
        R = self.raug[:p, :p] / scale
        kept = _independent_columns(R)
        return Regression(R=R, qty=self.raug[:p, p].copy(), rho=abs(float(self.raug[p, p])), scale=scale,
                          shift=float(self.shift), n=int(self.n), col_sum=self.col_sum.copy(),
                          y_sum=math.fsum(self.y_sums), names=names, kept=kept, intercept=self.intercept)


def factorise(chunks: Chunks, p: int, names: Sequence[str] | None = None, *, shift: float | None = None) -> Regression:
    """First pass over ``chunks()`` (an iterable of ``(X_chunk, y_chunk)``): the factor."""
    acc = Accumulator(p=p, shift=shift)
    for X, y in chunks():
        acc.add(X, y)
    return acc.result(names)


def _array_chunks(X: np.ndarray, y: np.ndarray, rows: int) -> Chunks:
    n = X.shape[0]
    return lambda: ((X[s:s + rows], y[s:s + rows]) for s in range(0, max(n, 1), rows))


def least_squares(X: np.ndarray, y: np.ndarray, names: Sequence[str] | None = None, *,
                  chunk_rows: int = CHUNK_ROWS) -> Regression:
    """Least squares of ``y`` on the columns of ``X``: both passes (see the module docstring).

    ``X`` is taken in chunks of ``chunk_rows`` rows; the result does not depend on the
    chunk size beyond round-off. When ``X`` is rank deficient only the first pass is done
    (``aliased`` names the columns; :meth:`Regression.require_full_rank` raises).
    """
    X = np.asarray(X, dtype=float)
    y = np.asarray(y, dtype=float).ravel()
    if X.ndim != 2 or X.shape[0] != y.size:
        raise ValueError(f"X ({X.shape}) and y ({y.size}) do not match")
    chunks = _array_chunks(X, y, int(chunk_rows))
    intercept = X.shape[0] > 0 and bool(np.all(X[:, 0] == 1.0))
    reg = factorise(chunks, X.shape[1], names, shift=(math.fsum(y) / y.size) if intercept else 0.0)
    return reg.second_pass(chunks) if reg.full_rank else reg


# ----------------------------------------------------------------------------------------
# the result
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Regression:
    """One least-squares factorisation and everything derived from it (frozen).

    Attributes
    ----------
    R : (p, p) ndarray
        Upper-triangular factor of the column-scaled model matrix ``X S^-1`` (``R'R = S^-1 X'X S^-1``).
    qty : (p,) ndarray
        ``Q'(y - shift)`` [response units].
    rho : float
        Norm of the residual from the factorisation [response units].
    scale : (p,) ndarray
        Column norms ``S`` of ``X`` (1 for a zero column).
    shift : float
        Value subtracted from y before factorising (the mean, or that of the first chunk;
        0 without an intercept) [response units].
    n : int
    col_sum : (p,) ndarray
        Column sums of ``X``.
    y_sum : float
        Sum of y [response units].
    names : tuple of str
        Column names.
    kept : tuple of int
        The estimable columns (all of them when the matrix has full rank).
    intercept : bool
        Column 0 is all ones.
    hat, residuals, fitted : ndarray or None
        From the second pass (:meth:`second_pass`); ``None`` for a sub-model, and for a
        second pass that keeps sums only (a Dask DataFrame's partitions).
    ss_total : float
        ``sum (y - ybar)^2`` from the second pass (NaN before it) [response units^2].
    pass_sums : PassSums or None
        The sums of the second pass: residual SS, PRESS, range of the fitted values.
    """

    R: np.ndarray = field(repr=False)
    qty: np.ndarray = field(repr=False)
    rho: float
    scale: np.ndarray = field(repr=False)
    shift: float
    n: int
    col_sum: np.ndarray = field(repr=False)
    y_sum: float
    names: tuple
    kept: tuple = field(repr=False)
    intercept: bool = True
    hat: np.ndarray | None = field(default=None, repr=False)
    residuals: np.ndarray | None = field(default=None, repr=False)
    fitted: np.ndarray | None = field(default=None, repr=False)
    ss_total: float = math.nan
    pass_sums: PassSums | None = field(default=None, repr=False)

    # -- shape and rank ------------------------------------------------------------------
    @property
    def p(self) -> int:
        """The number of model columns."""
        return int(self.R.shape[1])

    @property
    def rank(self) -> int:
        """The rank of the model matrix."""
        return len(self.kept)

    @property
    def full_rank(self) -> bool:
        """Whether every column is estimable."""
        return self.rank == self.p

    @property
    def aliased(self) -> tuple:
        """Names of the columns that are (numerically) combinations of earlier columns."""
        kept = set(self.kept)
        return tuple(nm for j, nm in enumerate(self.names) if j not in kept)

    def require_full_rank(self, what: str = "model") -> None:
        """Raise the one rank-deficiency message, naming the aliased columns.

        Parameters
        ----------
        what : str, default "model"
            What the message calls the model.
        """
        if not self.full_rank:
            raise ValueError(f"the {what} cannot be estimated from this design: term(s) {', '.join(self.aliased)} "
                             f"are aliased with earlier terms (the design matrix has rank {self.rank} < {self.p})")

    def alias_relations(self) -> list[str]:
        """For each aliased column, the combination of earlier estimable columns it equals
        (``"A^2 = Intercept"``; coefficients shown when not 1; ``"= 0"`` for a zero column).

        Returns
        -------
        list of str
            One relation per aliased column.
        """
        kept = set(self.kept)
        out = []
        for j in range(self.p):
            if j in kept:
                continue
            before = [i for i in self.kept if i < j]
            col = self.R[:, j]
            if before and np.linalg.norm(col) > 0:
                cs, *_ = np.linalg.lstsq(self.R[:, before], col, rcond=None)
                coef = cs * self.scale[j] / self.scale[before]
            else:
                coef = np.zeros(0)
            rhs = ""
            for c, i in zip(coef, before):
                if abs(c) <= 1e-9:
                    continue
                mag = format_g(abs(c), 6, trim=True)
                term = self.names[i] if mag == "1" else f"{mag}·{self.names[i]}"
                rhs += (("-" if c < 0 else "") + term) if not rhs else ((" - " if c < 0 else " + ") + term)
            out.append(f"{self.names[j]} = {rhs or '0'}")
        return out

    def _need_full_rank(self) -> None:
        if not self.full_rank:
            self.require_full_rank()

    # -- coefficients and covariance -----------------------------------------------------
    @cached_property
    def _rinv(self) -> np.ndarray:
        self._need_full_rank()
        return _solve_r(self.R, np.eye(self.p))

    @cached_property
    def _bs(self) -> np.ndarray:
        """Coefficients of the scaled columns (on the shifted response)."""
        self._need_full_rank()
        return _solve_r(self.R, self.qty)

    @cached_property
    def params(self) -> np.ndarray:
        """Least-squares coefficients of the columns of ``X`` [response units / column units]."""
        b = self._bs / self.scale
        if self.intercept:
            b[0] += self.shift
        return b

    @cached_property
    def _cov_scaled(self) -> np.ndarray:
        return self._rinv @ self._rinv.T

    @cached_property
    def cov_unscaled(self) -> np.ndarray:
        """``(X'X)^-1`` (p x p)."""
        return self._cov_scaled / np.outer(self.scale, self.scale)

    @property
    def ybar(self) -> float:
        """The mean response [response units]."""
        return self.y_sum / self.n

    @property
    def df_resid(self) -> int:
        """Residual degrees of freedom, n - rank."""
        return int(self.n - self.rank)

    @cached_property
    def ss_res(self) -> float:
        """Residual sum of squares [response units^2] (from the residuals after the second
        pass, else from the factorisation)."""
        if self.pass_sums is not None:
            return self.pass_sums.ss_res
        return self.rho ** 2

    @property
    def sigma2(self) -> float:
        """Residual mean square (NaN without residual degrees of freedom) [response units^2]."""
        return self.ss_res / self.df_resid if self.df_resid > 0 else math.nan

    def interval_form(self, columns: np.ndarray) -> IntervalForm:
        """The prediction contract's :class:`~rsm_lrg.model.contract.prediction.IntervalForm` of the
        model columns ``columns`` (OLS): ``C σ²`` for ``se_fit`` and the mean, ``σ²`` for a new
        run, ``n - p`` df (NaN without residual df).

        Parameters
        ----------
        columns : numpy.ndarray, shape (n, p)
            Model-matrix rows.

        Returns
        -------
        IntervalForm
            The prediction contract's interval form.
        """
        cov = np.asarray(self.cov_unscaled, dtype=float)[np.ix_(columns, columns)] * self.sigma2
        return IntervalForm(cov_se=cov, cov_mean=cov, s2_residual=self.sigma2,
                            df=float(self.df_resid) if self.df_resid > 0 else math.nan)

    def tests(self, names: Sequence[str], groups: Sequence[Sequence[int]]) -> list:
        """Separate F tests of a GLS fit's terms: none for least squares, whose ANOVA holds them.

        Parameters
        ----------
        names : sequence of str
            The terms' names.
        groups : sequence of sequence of int
            The terms' columns.

        Returns
        -------
        list
            Empty for least squares.
        """
        return []

    def contrast_tests(self, hypotheses: Sequence[tuple[str, np.ndarray]]) -> list:
        """Separate F tests of hypotheses ``L b = 0``: none for least squares, whose ANOVA holds them.

        Parameters
        ----------
        hypotheses : sequence of (str, numpy.ndarray)
            The name of each test and its L.

        Returns
        -------
        list
            Empty for least squares.
        """
        return []

    @property
    def random_effect(self) -> dict:
        """The random effect that refits the model (:meth:`rsm_lrg.model.engines.mixed.MixedModel.random_effect`): none."""
        return {}

    @property
    def std_errors(self) -> np.ndarray:
        """The coefficients' standard errors [response units per unit of each column]."""
        return np.sqrt(np.diag(self.cov_unscaled) * self.sigma2)

    # -- sums of squares -----------------------------------------------------------------
    def sequential_ss(self, cols: Sequence[int] | np.ndarray | int) -> float:
        """Sequential (Type I) sum of squares of the columns ``cols`` given every column
        before them: ``sum z_j^2`` [response units^2].

        Parameters
        ----------
        cols : int or sequence of int
            Model-matrix column indices.

        Returns
        -------
        float
            The sequential SS [response units²].
        """
        self._need_full_rank()
        idx = np.atleast_1d(np.asarray(cols, dtype=int))
        return float(np.sum(self.qty[idx] ** 2))

    def partial_ss(self, cols: Sequence[int] | np.ndarray | int) -> float:
        """Partial (Type III) sum of squares of the columns ``cols`` jointly (the extra sum of
        squares of dropping them): ``b_S' (C_SS)^-1 b_S`` [response units^2].

        Parameters
        ----------
        cols : int or sequence of int
            Model-matrix column indices.

        Returns
        -------
        float
            The partial SS [response units²].
        """
        return partial_ss(self._bs, self._cov_scaled, cols)  # scaled: the same number, better conditioned

    def residual_ss_after(self, k: int) -> float:
        """Residual sum of squares of the model of the first ``k`` columns (nested models in
        column order), from the factor: ``rho^2 + sum_{j>=k} z_j^2`` [response units^2].

        Parameters
        ----------
        k : int
            The number of leading columns.

        Returns
        -------
        float
            The residual SS [response units²].
        """
        self._need_full_rank()
        return float(self.rho ** 2 + np.sum(self.qty[k:] ** 2))

    @cached_property
    def press(self) -> float:
        """PRESS, ``sum (e_i / (1 - h_ii))^2`` (NaN when a run has leverage 1) [response units^2]."""
        if self.pass_sums is None:
            raise ValueError("PRESS needs the second pass over the rows")
        return self.pass_sums.press

    def vif(self, cols: Sequence[int] | np.ndarray) -> np.ndarray:
        """Variance inflation factors of the columns ``cols`` among themselves (the other
        columns but the intercept, e.g. blocks, left out): the diagonal of the inverse
        correlation matrix of those columns [-].

        Parameters
        ----------
        cols : sequence of int
            The columns.

        Returns
        -------
        numpy.ndarray
            One VIF per column [-].
        """
        cols = [int(c) for c in cols]
        if not cols:
            return np.zeros(0)
        if not self.intercept:
            raise ValueError("VIF needs the intercept in column 0")
        sub = self if cols == list(range(1, self.p)) else self.submodel([0, *cols])
        pos = np.arange(1, len(cols) + 1)
        centred = np.einsum("ij,ij->j", sub.R[1:, pos], sub.R[1:, pos])  # sum (x - mean)^2, scaled
        return np.diag(sub._cov_scaled)[pos] * centred

    def gvif(self, groups: Sequence[Sequence[int]]) -> np.ndarray:
        """Generalised variance inflation factors (Fox & Monette 1992, JASA 87:178) of groups
        of columns (a categoric term's effect columns), among the columns of all the groups
        (the intercept in column 0; other columns, e.g. blocks, left out):
        ``GVIF_S = det(R_SS) det(R^-1_SS)`` with ``R`` the correlation matrix of those
        columns; for a single column it is the VIF [-].

        Parameters
        ----------
        groups : sequence of sequence of int
            Column indices per group.

        Returns
        -------
        numpy.ndarray
            One GVIF per group [-].
        """
        groups = [[int(c) for c in g] for g in groups]
        cols = sorted({c for g in groups for c in g})
        if not cols:
            return np.zeros(0)
        sub = self.submodel([0, *cols])
        pos = {c: i + 1 for i, c in enumerate(cols)}
        M = sub.R[1:, 1:].T @ sub.R[1:, 1:]  # centred cross-products of the scaled columns
        C = sub._cov_scaled[1:, 1:]
        out = []
        for g in groups:
            ix = [pos[c] - 1 for c in g]
            out.append(float(np.linalg.det(M[np.ix_(ix, ix)]) * np.linalg.det(C[np.ix_(ix, ix)])))
        return np.array(out)

    # -- sub-models ----------------------------------------------------------------------
    def submodel(self, cols: Sequence[int] | np.ndarray) -> Regression:
        """The least-squares fit of the columns ``cols`` only, from the p x p factor (no pass
        over the rows; no hat diagonal).

        Parameters
        ----------
        cols : sequence of int
            The columns kept.

        Returns
        -------
        Regression
            The fit of those columns.
        """
        cols = [int(c) for c in cols]
        q, p = len(cols), self.p
        A = np.zeros((p + 1, q + 1))
        A[:p, :q] = self.R[:, cols]
        A[:p, q] = self.qty
        A[p, q] = self.rho
        Ra = _qr_r(A)
        R = Ra[:q, :q]
        return Regression(R=R, qty=Ra[:q, q].copy(), rho=abs(float(Ra[q, q])), scale=self.scale[cols],
                          shift=self.shift, n=self.n, col_sum=self.col_sum[cols], y_sum=self.y_sum,
                          names=tuple(self.names[c] for c in cols), kept=_independent_columns(R),
                          intercept=self.intercept and bool(cols) and cols[0] == 0, ss_total=self.ss_total)

    # -- second pass ---------------------------------------------------------------------
    def q_factor(self, X: np.ndarray) -> np.ndarray:
        """``Q = X S^-1 R^-1`` for rows ``X`` of the model matrix (orthonormal columns when
        ``X`` is the whole matrix).

        Parameters
        ----------
        X : numpy.ndarray, shape (n, p)
            Model-matrix rows.

        Returns
        -------
        numpy.ndarray, shape (n, p)
            ``Q``.
        """
        self._need_full_rank()
        return _solve_r(self.R, (np.asarray(X, dtype=float) / self.scale).T, trans=True).T

    def _pass_chunk(self, X, y):
        Xs = np.asarray(X, dtype=float) / self.scale
        W = _solve_r(self.R, Xs.T, trans=True)  # (p, m): Q' of the chunk
        h = np.einsum("ij,ij->j", W, W)
        fc = Xs @ self._bs
        y = np.asarray(y, dtype=float)
        r = (y - self.shift) - fc
        f = self.shift + fc
        dy = y - self.ybar
        one = 1.0 - h
        ok = one > 1e-10
        sums = PassSums(ss_res=float(r @ r), press=float(np.sum((r[ok] / one[ok]) ** 2)) if ok.all() else math.nan,
                        fitted_min=float(f.min()) if f.size else math.inf,
                        fitted_max=float(f.max()) if f.size else -math.inf, ss_total=float(dy @ dy))
        return h, r, f, sums

    def pass_sums_of(self, chunks: Iterable[tuple[np.ndarray, np.ndarray]]) -> PassSums:
        """The second-pass sums of some chunks of rows (one partition), without the per-run arrays.

        Parameters
        ----------
        chunks : iterable of tuple of numpy.ndarray
            ``(X, y)`` chunks of rows.

        Returns
        -------
        PassSums
            The sums.
        """
        return PassSums.combine([self._pass_chunk(X, y)[3] for X, y in chunks])

    def with_pass_sums(self, sums: Sequence[PassSums]) -> Regression:
        """The fit completed by second-pass sums gathered elsewhere (e.g. over partitions).

        Parameters
        ----------
        sums : sequence of PassSums
            The sums per partition.

        Returns
        -------
        Regression
            The completed fit.
        """
        total = PassSums.combine(sums)
        return replace(self, pass_sums=total, ss_total=total.ss_total)

    def second_pass(self, chunks: Chunks, keep: bool = True) -> Regression:
        """The same fit with the hat diagonal, residuals, fitted values (``keep``), the total
        sum of squares, the residual sum of squares and PRESS from a pass over the same chunks.

        Parameters
        ----------
        chunks : iterable
            The same rows as the first pass, in chunks ``(X, y)``.
        keep : bool, default True
            Keep the per-run arrays (hat diagonal, residuals, fitted values).

        Returns
        -------
        Regression
            The completed fit.
        """
        self._need_full_rank()
        hs, rs, fs, sums = [], [], [], []
        for X, y in chunks():
            h, r, f, sm = self._pass_chunk(X, y)
            sums.append(sm)
            if keep:
                hs.append(h)
                rs.append(r)
                fs.append(f)
        out = self.with_pass_sums(sums)
        return replace(out, hat=_cat(hs), residuals=_cat(rs), fitted=_cat(fs)) if keep else out

    def rescaled(self, k: float) -> Regression:
        """The same fit of the response multiplied by ``k`` (a fit of a standardised response
        brought back to the response's unit): the coefficients, residuals, fitted values and
        ``rho`` times ``k``, the sums of squares times ``k²``; ``R`` and the leverages unchanged.

        Parameters
        ----------
        k : float
            The factor [response units per unit of the fitted response].

        Returns
        -------
        Regression
            The fit in the response's unit.
        """
        k = float(k)
        k2 = k * k

        def times(a: np.ndarray | None) -> np.ndarray | None:
            return None if a is None else np.asarray(a, dtype=float) * k

        ps = self.pass_sums
        if ps is not None:
            ps = PassSums(ss_res=ps.ss_res * k2, press=ps.press * k2, fitted_min=ps.fitted_min * k,
                          fitted_max=ps.fitted_max * k, ss_total=ps.ss_total * k2)
        return replace(self, qty=self.qty * k, rho=self.rho * k, shift=self.shift * k, y_sum=self.y_sum * k,
                       residuals=times(self.residuals), fitted=times(self.fitted), ss_total=self.ss_total * k2,
                       pass_sums=ps)

    def nested_press(self, chunks: Chunks, ends: Sequence[int]) -> list[tuple[float, float]]:
        """For the nested models of the first ``k`` columns (``k`` in ``ends``): the residual
        sum of squares and PRESS from one pass over ``chunks`` (full-matrix rows).

        Parameters
        ----------
        chunks : iterable
            The rows of the full model matrix, in chunks ``(X, y)``.
        ends : sequence of int
            The column counts of the nested models.

        Returns
        -------
        list of tuple of float
            ``(residual SS, PRESS)`` per model [response units²].
        """
        self._need_full_rank()
        ends = [int(k) for k in ends]
        ss: list[list[float]] = [[] for _ in ends]
        pr: list[list[float]] = [[] for _ in ends]
        bad = [False] * len(ends)
        for X, y in chunks():
            W = self.q_factor(X)
            yc = np.asarray(y, dtype=float) - self.shift
            h2 = np.cumsum(W * W, axis=1)
            for i, k in enumerate(ends):
                r = yc - W[:, :k] @ self.qty[:k]
                one = 1.0 - h2[:, k - 1]
                ss[i].append(float(r @ r))
                ok = one > 1e-10
                bad[i] |= not ok.all()
                pr[i].append(float(np.sum((r[ok] / one[ok]) ** 2)))
        return [(math.fsum(s), math.nan if b else math.fsum(p)) for s, p, b in zip(ss, pr, bad)]

    def residual_ss_of(self, X: np.ndarray, Z: np.ndarray) -> np.ndarray:
        """Residual sums of squares of other responses ``Z`` (n x m) on the same model
        matrix ``X`` (e.g. the Box–Cox transforms), by projection on ``Q`` [units^2].

        Parameters
        ----------
        X : numpy.ndarray, shape (n, p)
            The model matrix.
        Z : numpy.ndarray, shape (n, m)
            Other responses.

        Returns
        -------
        numpy.ndarray, shape (m,)
            Their residual SS [their units²].
        """
        Q = self.q_factor(X)
        Z = np.asarray(Z, dtype=float)
        Z = Z[:, None] if Z.ndim == 1 else Z
        Rz = Z - Q @ (Q.T @ Z)
        return np.einsum("ij,ij->j", Rz, Rz)


def partial_ss(beta: np.ndarray, cov_unscaled: np.ndarray, idx: Sequence[int] | np.ndarray | int) -> float:
    """Partial (Type III) sum of squares ``b_S' (C_SS)^-1 b_S`` of the columns ``idx``
    [response units^2], from coefficients ``beta`` (p,) and ``cov_unscaled = (X'X)^-1``.

    Parameters
    ----------
    beta : numpy.ndarray, shape (p,)
        Coefficients.
    cov_unscaled : numpy.ndarray, shape (p, p)
        ``(X'X)^-1``.
    idx : int or sequence of int
        The columns.

    Returns
    -------
    float
        The partial SS [response units²].
    """
    cols = np.atleast_1d(np.asarray(idx, dtype=int))
    b = beta[cols]
    if cols.size == 1:
        c = cov_unscaled[cols[0], cols[0]]
        return float(b[0] ** 2 / c)
    return float(b @ np.linalg.solve(cov_unscaled[np.ix_(cols, cols)], b))


@dataclass(frozen=True)
class PassSums:
    """Sums of the second pass over some rows (they add up over chunks and partitions).

    ``press`` is NaN when a run has leverage 1 (within 1e-10); ``fitted_min``/``fitted_max``
    give the range of the fitted values (adequate precision) [response units]."""

    ss_res: float
    press: float
    fitted_min: float
    fitted_max: float
    ss_total: float

    @staticmethod
    def combine(parts: Sequence[PassSums]) -> PassSums:
        parts = list(parts)
        return PassSums(ss_res=math.fsum(p.ss_res for p in parts), press=math.fsum(p.press for p in parts),
                        fitted_min=min((p.fitted_min for p in parts), default=math.inf),
                        fitted_max=max((p.fitted_max for p in parts), default=-math.inf),
                        ss_total=math.fsum(p.ss_total for p in parts))


def _cat(parts: list) -> np.ndarray:
    return np.concatenate(parts) if parts else np.zeros(0)
