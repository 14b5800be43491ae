"""Constraints on the factor region: inequalities in the factors' actual units.

A design or an optimum often may not use every corner of the factor box. The motion
profile of the paper's rig, for one, reaches the velocity v within the stroke s only when
``s >= v**2 / a``. A constraint is an inequality written in the factors' names (or their
letters) in **actual units**, as Design-Expert takes them::

    "0.5*A + B <= 1.2"                                     linear (letters)
    "velocity_m_s**2/acceleration_m_s2 <= stroke_m"        nonlinear (names)
    "0.45 <= velocity_m_s <= 0.55"                         a chain: two constraints

The text is parsed with Python's :mod:`ast` and only a whitelist is accepted: numbers,
factor names and letters, ``+ - * /``, ``**`` (``^`` is read as a power too), unary minus
and plus, parentheses, the comparisons ``<=``, ``>=``, ``<``, ``>`` (``<`` is taken as
``<=``: the region is closed) and the functions ``sqrt``, ``exp``, ``log``, ``log10``,
``abs``, ``min``, ``max`` (two or more arguments). Nothing is ever passed to ``eval``.
Categoric factors cannot appear in a constraint.

Public API
----------
``Constraints.parse(exprs, space, check_empty=True) -> Constraints``
    ``exprs``: a string or a sequence of strings; ``space``: the
    :class:`~rsm_lrg.factors.FactorSpace`. Raises ``ValueError`` naming the expression for
    bad syntax, an unknown name, a categoric factor, an equality, a constraint with no
    factor in it, and (``check_empty``) a region in which none of about 4 000 points of
    the factor box (corners, centre, Sobol' points) satisfies every constraint.
``c.feasible(actual) -> numpy bool array (n,)``
    ``actual``: a DataFrame with the factor names as columns, a mapping ``{name: value}``,
    or an ``(n, k)`` / ``(k,)`` array in factor order, **actual units**. A point where an
    expression is not a finite number (``log`` of a negative number, division by zero) is
    infeasible. ``tol`` (default 1e-9, relative to the size of the two sides) forgives
    rounding.
``c.feasible_coded(coded)``, ``c.margin_coded(coded)``
    The same for coded settings ``(n, k)`` (a categoric factor's column ignored).
``c.margin(actual) -> numpy array (n, m)``
    ``rhs - lhs`` of each of the m inequalities written as ``lhs <= rhs`` (positive inside,
    0 on the boundary, negative outside; NaN where undefined) [units of the expression].
    This is the form scipy's ``NonlinearConstraint(fun, 0, inf)`` takes.
``c.is_linear``, ``c[j].is_linear``
    Whether every (or the j-th) inequality is linear in the factors.
``c.linear_system(coded=True) -> (A, b)``
    For linear constraints only: the rows ``A @ x <= b`` in coded units (or actual with
    ``coded=False``), ready for ``scipy.optimize.LinearConstraint(A, -inf, b)``.
``c.expressions``, ``len(c)``, ``bool(c)``, ``c.to_list()``
    The inequalities as written (one per chain link).

An empty ``Constraints`` (``Constraints.parse([], space)``) accepts every point.

>>> from rsm_lrg.factors import FactorSpace
>>> sp = FactorSpace.from_ranges([("v", 0.2, 1.0), ("a", 5.0, 20.0), ("s", 0.02, 0.06)])
>>> c = Constraints.parse(["v**2/a <= s"], sp)
>>> c.is_linear, c.feasible([[0.5, 10.0, 0.04], [1.0, 5.0, 0.06]]).tolist()
(False, [True, False])
>>> Constraints.parse("0.5*A + B <= 12", sp).linear_system(coded=False)[0].tolist()
[[0.5, 1.0, 0.0]]
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..factors import FactorSpace

__all__ = ["Constraint", "Constraints", "FUNCTIONS"]

#: Functions a constraint may call.
FUNCTIONS: dict[str, Callable | None] = {
    "sqrt": np.sqrt, "exp": np.exp, "log": np.log, "log10": np.log10, "abs": np.abs,
    "min": None, "max": None,  # n-ary, handled in _compile
}

#: Longest expression accepted [characters].
MAX_LENGTH = 2000

_BINOPS = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply, ast.Div: np.divide,
           ast.Pow: np.power, ast.BitXor: np.power}
_CMP = {ast.LtE: "<=", ast.Lt: "<=", ast.GtE: ">=", ast.Gt: ">="}


def _quote(expr: str) -> str:
    from ..io import quote_user_value

    return quote_user_value(expr, 80)


class _Bad(ValueError):
    pass


def _compile(node: ast.AST, names: Mapping[str, int], expr: str) -> tuple[Callable, int, set]:
    """``(f(X) -> array, degree, factor indices)``; degree 0 constant, 1 linear, 2 otherwise."""
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            raise _Bad(f"{node.value!r} is not a number")
        try:
            v = float(node.value)
        except OverflowError:  # a whole number of hundreds of digits
            raise _Bad(f"the number {str(node.value)[:12]}… ({len(str(node.value))} digits) is too large") from None
        if not math.isfinite(v):
            raise _Bad("numbers must be finite")
        return (lambda X, v=v: v), 0, set()
    if isinstance(node, ast.Name):
        if node.id not in names:
            raise _Bad(f"unknown name {node.id!r}")
        j = names[node.id]
        if j < 0:
            raise _Bad(f"{node.id!r} is a categoric factor; a constraint holds numeric factors only")
        return (lambda X, j=j: X[:, j]), 1, {j}
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        f, d, used = _compile(node.operand, names, expr)
        if isinstance(node.op, ast.USub):
            return (lambda X, f=f: -f(X)), d, used
        return f, d, used
    if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
        fa, da, ua = _compile(node.left, names, expr)
        fb, db, ub = _compile(node.right, names, expr)
        op = _BINOPS[type(node.op)]
        if isinstance(node.op, (ast.Add, ast.Sub)):
            d = max(da, db)
        elif isinstance(node.op, ast.Mult):
            d = 2 if (da and db) else max(da, db)
        elif isinstance(node.op, ast.Div):
            d = 2 if db else da
        else:  # power: linear only when the base is constant or the exponent is exactly 1
            d = 0 if (da == 0 and db == 0) else 2
            if db == 0 and da == 1 and isinstance(node.right, ast.Constant) \
                    and isinstance(node.right.value, (int, float)) and float(node.right.value) == 1.0:
                d = 1
        return (lambda X, fa=fa, fb=fb, op=op: op(fa(X), fb(X))), d, ua | ub
    if isinstance(node, ast.Call):
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            fn = node.func.id if isinstance(node.func, ast.Name) else "this call"
            raise _Bad(f"function {fn!r} is not allowed (allowed: {', '.join(FUNCTIONS)})")
        if node.keywords:
            raise _Bad("keyword arguments are not allowed")
        args = [_compile(a, names, expr) for a in node.args]
        fname = node.func.id
        d = 0 if all(a[1] == 0 for a in args) else 2
        used = set().union(*[a[2] for a in args]) if args else set()
        if fname in ("min", "max"):
            if len(args) < 2:
                raise _Bad(f"{fname}() needs two or more arguments")
            red = np.minimum if fname == "min" else np.maximum
            fs = [a[0] for a in args]

            def mm(X, fs=fs, red=red):
                out = fs[0](X)
                for g in fs[1:]:
                    out = red(out, g(X))
                return out
            return mm, d, used
        if len(args) != 1:
            raise _Bad(f"{fname}() takes one argument")
        func, f0 = FUNCTIONS[fname], args[0][0]
        assert func is not None  # only min and max (above) have no function of their own
        return (lambda X, fn=func, f0=f0: fn(f0(X))), d, used
    what = type(node).__name__
    if isinstance(node, ast.Compare):
        what = "a comparison inside an expression"
    raise _Bad(f"{what} is not allowed here (allowed: numbers, factor names, + - * / **, "
               f"{', '.join(FUNCTIONS)}, and one comparison <= >= < >)")


@dataclass(frozen=True, eq=False)
class Constraint:
    """One inequality ``lhs <= rhs`` (a ``>=`` is stored turned round).

    Attributes
    ----------
    text : str
        The inequality as written (one link of a chain).
    is_linear : bool
        Whether both sides are linear in the factors.
    factors : tuple of int
        Positions of the factors it uses.
    """

    text: str
    lhs: Callable
    rhs: Callable
    is_linear: bool
    factors: tuple

    def margin(self, X: np.ndarray) -> np.ndarray:
        """``rhs - lhs`` at actual settings ``X`` (n, k) [units of the expression]; NaN
        where an expression is undefined."""
        return self._margin_scale(X)[0]

    def _margin_scale(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        with np.errstate(all="ignore"):
            lo = np.broadcast_to(np.asarray(self.lhs(X), dtype=float), (X.shape[0],))
            hi = np.broadcast_to(np.asarray(self.rhs(X), dtype=float), (X.shape[0],))
            m = hi - lo
            scale = np.maximum(np.abs(lo), np.abs(hi))
        m = np.where(np.isfinite(m), m, np.nan)
        return m, scale


class Constraints:
    """A set of inequalities on a factor space (see the module docstring for the API).

    Parameters
    ----------
    items : sequence of Constraint
        The parsed inequalities (use :meth:`parse` to build them from text).
    space : FactorSpace
        The factors they constrain.
    """

    def __init__(self, items: Sequence[Constraint], space: FactorSpace):
        self.items = tuple(items)
        self.space = space

    # -- construction -------------------------------------------------------------------
    @classmethod
    def parse(cls, exprs: str | Sequence[str] | None, space: FactorSpace, *, check_empty: bool = True) -> Constraints:
        """Parse constraint texts on ``space`` (names or letters, actual units).

        Parameters
        ----------
        exprs : str, sequence of str or None
            Inequalities such as ``"v**2/a <= s"`` or ``"0.5*A + B <= 1.2"`` (names or letters,
            actual units).
        space : FactorSpace
            The factors.
        check_empty : bool, default True
            Raise ``ValueError`` when no setting of the box satisfies them all.

        Returns
        -------
        Constraints
            The parsed set (empty for ``None``).
        """
        if exprs is None:
            exprs = []
        if isinstance(exprs, str):
            exprs = [exprs]
        names: dict[str, int] = {}
        for j, f in enumerate(space.factors):
            names.setdefault(f.letter, j if f.kind == "numeric" else -1)
        for j, f in enumerate(space.factors):  # names win over letters
            names[f.name] = j if f.kind == "numeric" else -1
        items = []
        for expr in exprs:
            items.extend(cls._parse_one(expr, names))
        out = cls(items, space)
        if check_empty and items:
            out.check_region()
        return out

    @staticmethod
    def _parse_one(expr: Any, names: Mapping[str, int]) -> list[Constraint]:
        if not isinstance(expr, str) or not expr.strip():
            raise ParameterError("constraints", "empty expression; expected e.g. '0.5*A + B <= 1.2'")
        if len(expr) > MAX_LENGTH:
            raise ParameterError("constraints", f"constraint {_quote(expr)}: longer than {MAX_LENGTH} characters")
        text = expr.strip()
        try:
            tree = ast.parse(text, mode="eval")
        except (SyntaxError, ValueError, MemoryError, RecursionError):
            raise ParameterError("constraints", f"constraint {_quote(expr)}: not a valid expression; expected e.g. "
                             "'0.5*A + B <= 1.2'") from None
        node = tree.body
        if not isinstance(node, ast.Compare):
            raise ParameterError("constraints", f"constraint {_quote(expr)}: needs a comparison <= or >= (e.g. 'A + B <= 1')")
        for op in node.ops:
            if type(op) not in _CMP:
                raise ParameterError("constraints", f"constraint {_quote(expr)}: only <=, >=, <, > are allowed (not "
                                 f"{type(op).__name__}); an equality leaves no region to design in")
        try:
            parts = [_compile(n, names, expr) for n in [node.left, *node.comparators]]
        except _Bad as exc:
            raise ParameterError("constraints", f"constraint {_quote(expr)}: {exc}") from None
        except RecursionError:
            raise ParameterError("constraints", f"constraint {_quote(expr)}: nested too deeply") from None
        out = []
        srcs = [ast.get_source_segment(text, n) or "?" for n in [node.left, *node.comparators]]
        for i, op in enumerate(node.ops):
            (fa, da, ua), (fb, db, ub) = parts[i], parts[i + 1]
            if not (ua | ub):
                raise ParameterError("constraints", f"constraint {_quote(expr)}: no factor in {srcs[i]} {_CMP[type(op)]} "
                                 f"{srcs[i + 1]}")
            link = f"{srcs[i]} {_CMP[type(op)]} {srcs[i + 1]}"
            if _CMP[type(op)] == "<=":
                lhs, rhs = fa, fb
            else:
                lhs, rhs = fb, fa
            out.append(Constraint(link, lhs, rhs, max(da, db) <= 1, tuple(sorted(ua | ub))))
        return out

    # -- views --------------------------------------------------------------------------
    def __len__(self) -> int:
        return len(self.items)

    def __bool__(self) -> bool:
        return bool(self.items)

    def __getitem__(self, j: int) -> Constraint:
        return self.items[j]

    def __repr__(self) -> str:
        return f"Constraints({[c.text for c in self.items]!r})"

    @property
    def expressions(self) -> list[str]:
        """The inequalities as text, as given."""
        return [c.text for c in self.items]

    def to_list(self) -> list[dict]:
        """The inequalities as plain data.

        Returns
        -------
        list of dict
            One entry per inequality: ``{"constraint": text, "linear": bool}``.
        """
        return [{"constraint": c.text, "linear": c.is_linear} for c in self.items]

    @property
    def is_linear(self) -> bool:
        """True when every inequality is linear in the factors (also when there is none)."""
        return all(c.is_linear for c in self.items)

    # -- evaluation ---------------------------------------------------------------------
    def _actual_array(self, actual) -> np.ndarray:
        import pandas as pd

        k = len(self.space)
        if isinstance(actual, pd.DataFrame):
            X = np.full((len(actual), k), np.nan)
            for j, f in enumerate(self.space.factors):
                if f.kind == "numeric":
                    X[:, j] = actual[f.name].to_numpy(dtype=float)
            return X
        if isinstance(actual, Mapping):
            X = np.full((1, k), np.nan)
            for j, f in enumerate(self.space.factors):
                if f.kind == "numeric":
                    X[0, j] = float(actual[f.name])
            return X
        a = np.asarray(actual)
        if a.ndim == 1:
            a = a[None, :]
        if a.ndim != 2 or a.shape[1] != k:
            raise ValueError(f"settings must be an (n, {k}) array in factor order, got shape {a.shape}")
        X = np.full(a.shape, np.nan)
        for j, f in enumerate(self.space.factors):
            if f.kind == "numeric":
                X[:, j] = np.asarray(a[:, j], dtype=float)
        return X

    def _decode(self, coded) -> np.ndarray:
        c = np.asarray(coded, dtype=float)
        if c.ndim == 1:
            c = c[None, :]
        X = np.full(c.shape, np.nan)
        for j, f in enumerate(self.space.factors):
            if f.kind == "numeric":
                X[:, j] = f.center + f.half_range * c[:, j]
        return X

    def _margins(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        n = X.shape[0]
        M = np.empty((n, len(self.items)))
        S = np.empty((n, len(self.items)))
        for i, c in enumerate(self.items):
            M[:, i], S[:, i] = c._margin_scale(X)
        return M, S

    def margin(self, actual) -> np.ndarray:
        """``rhs - lhs`` of each inequality, shape (n, m): positive inside, NaN undefined.

        Parameters
        ----------
        actual : array_like, shape (n, k)
            Settings in actual units (columns in factor order).

        Returns
        -------
        numpy.ndarray, shape (n, m)
            ``rhs - lhs`` per setting and inequality [units of the inequality].
        """
        return self._margins(self._actual_array(actual))[0]

    def margin_coded(self, coded) -> np.ndarray:
        """:meth:`margin` at coded settings.

        Parameters
        ----------
        coded : array_like, shape (n, k)
            Settings in coded units.

        Returns
        -------
        numpy.ndarray, shape (n, m)
            ``rhs - lhs`` per setting and inequality.
        """
        return self._margins(self._decode(coded))[0]

    def _ok(self, X: np.ndarray, tol: float) -> np.ndarray:
        if not self.items:
            return np.ones(X.shape[0], dtype=bool)
        M, S = self._margins(X)
        with np.errstate(invalid="ignore"):
            good = np.isfinite(M) & (M >= -tol * S)
        return np.all(good, axis=1)

    def feasible(self, actual, tol: float = 1e-9) -> np.ndarray:
        """Boolean mask (n,): the settings satisfy every inequality (actual units).

        Parameters
        ----------
        actual : array_like, shape (n, k)
            Settings in actual units.
        tol : float, default 1e-9
            Slack allowed on each inequality.

        Returns
        -------
        numpy.ndarray of bool, shape (n,)
            True where every inequality holds.
        """
        return self._ok(self._actual_array(actual), tol)

    def feasible_coded(self, coded, tol: float = 1e-9) -> np.ndarray:
        """Boolean mask (n,) for coded settings.

        Parameters
        ----------
        coded : array_like, shape (n, k)
            Settings in coded units.
        tol : float, default 1e-9
            Slack allowed on each inequality.

        Returns
        -------
        numpy.ndarray of bool, shape (n,)
            True where every inequality holds.
        """
        return self._ok(self._decode(coded), tol)

    def linear_system(self, coded: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """``(A, b)`` with ``A @ x <= b`` for linear constraints (x coded, or actual with
        ``coded=False``; the columns of categoric factors are 0). ``ValueError`` when a
        constraint is nonlinear.

        Parameters
        ----------
        coded : bool, default True
            ``A`` and ``b`` for coded settings (else actual units).

        Returns
        -------
        tuple of numpy.ndarray
            ``(A, b)``, shapes (m, k) and (m,).
        """
        k = len(self.space)
        if not self.is_linear:
            bad = next(c.text for c in self.items if not c.is_linear)
            raise ParameterError("constraints", f"constraint {_quote(bad)} is not linear")
        A = np.zeros((len(self.items), k))
        b = np.zeros(len(self.items))
        for i, c in enumerate(self.items):
            g = lambda X, c=c: np.asarray(c.lhs(X), dtype=float) - np.asarray(c.rhs(X), dtype=float)  # noqa: E731
            if coded:
                base = np.zeros((1, k))
                g0 = float(np.broadcast_to(g(self._decode(base)), (1,))[0])
                for j in range(k):
                    e = base.copy()
                    e[0, j] = 1.0
                    A[i, j] = float(np.broadcast_to(g(self._decode(e)), (1,))[0]) - g0
            else:
                base = np.zeros((1, k))
                g0 = float(np.broadcast_to(g(base), (1,))[0])
                for j in range(k):
                    e = base.copy()
                    e[0, j] = 1.0
                    A[i, j] = float(np.broadcast_to(g(e), (1,))[0]) - g0
            b[i] = -g0
        for j, f in enumerate(self.space.factors):
            if f.kind != "numeric":
                A[:, j] = 0.0
        return A, b

    # -- the region ---------------------------------------------------------------------
    def region_sample(self, n: int = 4096, seed: int = 0) -> np.ndarray:
        """Coded points of the numeric box (corners when few, centre, Sobol' points);
        categoric columns 0.

        Parameters
        ----------
        n : int, default 4096
            Sobol' points: the power of two at or above n.
        seed : int, default 0
            Seed of the scrambled Sobol' sequence.

        Returns
        -------
        numpy.ndarray, shape (N, k)
            Coded points of the box (not filtered by the constraints).
        """
        from scipy.stats import qmc

        k = len(self.space)
        idx = self.space.numeric_index
        kn = len(idx)
        pts = [np.zeros((1, kn))]
        if kn <= 12:
            pts.append(np.array(np.meshgrid(*[[-1.0, 1.0]] * kn)).reshape(kn, -1).T)
        m = int(math.ceil(math.log2(max(n, 2))))
        pts.append(qmc.Sobol(kn, scramble=True, seed=seed).random_base2(m) * 2.0 - 1.0)
        P = np.vstack(pts)
        out = np.zeros((P.shape[0], k))
        out[:, idx] = P
        return out

    def check_region(self) -> None:
        """``ValueError`` naming the constraints when no sampled point of the box satisfies
        them all (the region is empty, or too thin to design in)."""
        if not self.items:
            return
        P = self.region_sample()
        if self.feasible_coded(P).any():
            return
        M = self.margin_coded(P)
        alone = [c.text for i, c in enumerate(self.items) if not np.any(np.nan_to_num(M[:, i], nan=-1.0) >= 0)]
        if alone:
            raise ParameterError("constraints", f"constraint {_quote(alone[0])}: no setting inside the factor ranges satisfies it "
                             "(the constrained region is empty)")
        raise ParameterError("constraints", f"constraints {'; '.join(_quote(c.text) for c in self.items)}: no setting inside the "
                         "factor ranges satisfies all of them together (the constrained region is empty)")
