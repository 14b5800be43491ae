"""The region of a mixture fit: the constrained simplex, crossed with the process box.

A fitted Scheffé model (:mod:`rsm_lrg.model.build.mixture`) codes its components as L-pseudo
components ``z_i = (x_i - L_i) / R`` (``R = T - sum L``) and its process factors as usual
(-1 .. +1). In those coded units the region where an optimum, a trace or a contour plot is
sought is the polytope

    sum_i z_i = 1                        (the blend sums to the total T)
    G x <= h                              (bounds and linear constraints)

where the rows of ``G x <= h`` are each component's bounds ``L_i <= x_i <= U_i`` (the
fit's bounds, tightened by any asked for), each process factor's box and every linear
``--constraint`` (on component names or letters, in real proportions and actual units;
McLean & Anderson 1966, Cornell, *Experiments with Mixtures*, 3rd ed., Sec. 6.2).

:meth:`MixtureRegion.vertices` enumerates the vertices exactly: every choice of ``k - 1``
rows of ``G`` made active together with the sum gives a ``k x k`` linear system; its
solutions that satisfy every row (within ``1e-9``) are the vertices. :meth:`faces` gives
the same active sets of every size, for the optimiser's KKT enumeration
(:mod:`rsm_lrg.optimize.mixture`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from itertools import combinations
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...factors import Factor, FactorSpace, MixtureComponent

__all__ = ["MixtureRegion", "mixture_region", "MAX_ACTIVE_SETS", "FEAS_TOL"]

#: Most active sets (choices of constraint rows) an enumeration tries.
MAX_ACTIVE_SETS = 60000
#: A point satisfies a row when ``g·x - h <= FEAS_TOL * (1 + |h|)`` (coded units).
FEAS_TOL = 1e-9


@dataclass(frozen=True)
class MixtureRegion:
    """The constrained simplex (x the process box) of a mixture fit, in coded units.

    Attributes
    ----------
    space : FactorSpace
        The fit's factors: components (L-pseudo coded) first, then process factors.
    comps : tuple of int
        Indices of the components in ``space``.
    G, h : ndarray
        The rows ``G x <= h`` (coded units): bounds, process box, linear constraints.
    rows : tuple of str
        What each row is (``"A >= 0.1"``, ``"D <= 1 (coded)"``, a constraint's text).
    total : float
        The blend's total T [the components' units].
    limits : dict
        ``{name: (low, high)}`` each component's bounds and each process factor's limits
        [real proportions / actual units], as given (before coding).
    """

    space: FactorSpace
    comps: tuple
    G: np.ndarray
    h: np.ndarray
    rows: tuple
    total: float
    limits: dict = field(default_factory=dict)

    @property
    def k(self) -> int:
        """Number of factors (components and process factors)."""
        return len(self.space)

    @property
    def E(self) -> np.ndarray:
        """The equality row: the L-pseudo components sum to one."""
        e = np.zeros(self.k)
        e[list(self.comps)] = 1.0
        return e

    def contains(self, X: Any, tol: float = FEAS_TOL) -> np.ndarray:
        """Boolean mask: the coded rows of ``X`` lie in the region (within ``tol``)."""
        X = np.atleast_2d(np.asarray(X, dtype=float))
        ok = np.all(X @ self.G.T - self.h <= tol * (1.0 + np.abs(self.h)), axis=1)
        return ok & (np.abs(X @ self.E - 1.0) <= 1e3 * tol)

    def faces(self, max_active: int | None = None) -> Iterator[tuple[int, ...]]:
        """Every choice of at most ``max_active`` (default ``k - 1``) rows of ``G``, smallest first."""
        top = self.k - 1 if max_active is None else max_active
        for s in range(top + 1):
            yield from combinations(range(len(self.h)), s)

    def n_faces(self, max_active: int | None = None) -> int:
        """How many active sets :meth:`faces` yields."""
        top = self.k - 1 if max_active is None else max_active
        return sum(math.comb(len(self.h), s) for s in range(top + 1))

    def vertices(self) -> np.ndarray:
        """The region's vertices (coded units, one per row; duplicates merged).

        Raises
        ------
        ValueError
            The region is empty, or has more choices of active rows than
            :data:`MAX_ACTIVE_SETS`.
        """
        k, m = self.k, len(self.h)
        n_sets = math.comb(m, k - 1)
        if n_sets > MAX_ACTIVE_SETS:
            raise ValueError(f"the region has {m} constraint rows in {k} factors: {n_sets} choices of active rows "
                             f"is more than {MAX_ACTIVE_SETS}")
        out = []
        for S in combinations(range(m), k - 1):
            A = np.vstack([self.E[None, :], self.G[list(S)]])
            rhs = np.concatenate([[1.0], self.h[list(S)]])
            if abs(np.linalg.det(A)) < 1e-12:
                continue
            x = np.linalg.solve(A, rhs)
            if self.contains(x)[0]:
                out.append(x)
        if not out:
            raise ValueError("the region is empty: no blend satisfies the bounds"
                             + (" and the constraints" if any(not r.startswith(("bound", "process")) for r in self.rows)
                                else ""))
        V = np.array(out)
        keep: list[np.ndarray] = []
        for v in V:
            if not any(np.max(np.abs(v - w)) <= 1e-10 for w in keep):
                keep.append(v)
        return np.array(keep)

    def centroid(self) -> np.ndarray:
        """The average of the vertices (McLean and Anderson's overall centroid; the simplex
        centroid when the region is the whole simplex), coded."""
        return self.vertices().mean(axis=0)

    def to_actual(self, x: Any) -> dict:
        """``{name: actual value}`` of the coded point ``x`` (real proportions for the components),
        kept inside each factor's :attr:`limits` (decoding a bound's coded value can land
        ``1e-17`` outside it)."""
        x = np.asarray(x, dtype=float).ravel()
        out = {}
        for f, v in zip(self.space.factors, x):
            a = float(f.decode(v))
            if f.name in self.limits:
                lo, hi = self.limits[f.name]
                a = min(max(a, lo), hi)
            out[f.name] = a
        return out


def _component_limits(space: FactorSpace, comps: Sequence[int], bounds: Mapping[str, tuple[float, float]]) -> dict:
    out = {}
    for j in comps:
        f = space.factors[j]
        assert isinstance(f, MixtureComponent)
        lo, hi = f.lower, min(f.upper, f.total)
        if f.name in bounds:
            a, b = bounds[f.name]
            lo, hi = max(lo, a), min(hi, b)
        out[j] = (lo, hi)
    return out


def mixture_region(space: FactorSpace, bounds: Mapping[str, Any] | Sequence[str] | None = None,
                   constraints: Any = None) -> MixtureRegion:
    """The region of a mixture fit's ``space``.

    Parameters
    ----------
    space : FactorSpace
        A mixture fit's space (``FitResult.space``): components, then process factors.
    bounds : mapping or list of str, optional
        Tighter limits in real proportions / actual units, ``{name or letter: (low, high)}``
        or ``["NAME=LOW:HIGH"]``; a component's limits are intersected with its own bounds.
    constraints : str or list of str, optional
        Linear inequalities on the factors (names or letters, actual units), as for the
        designs (:class:`rsm_lrg.design.constraints.Constraints`): ``"A + B <= 0.6"``.

    Raises
    ------
    ValueError
        A nonlinear constraint, a bound naming no factor or with LOW >= HIGH, a process
        bound outside the factor's range (naming it), or an empty region.
    """
    from ...factors import parse_factor_spec

    comps = tuple(j for j, f in enumerate(space.factors) if isinstance(f, MixtureComponent))
    if not comps:
        raise ValueError("not a mixture: the space has no mixture component")
    f0 = space.factors[comps[0]]
    assert isinstance(f0, MixtureComponent)
    T, R = f0.total, f0.pseudo_range
    items: dict[str, tuple[float, float]] = {}
    if bounds is not None:
        pairs = bounds.items() if isinstance(bounds, Mapping) else []
        if not isinstance(bounds, Mapping):
            for s in bounds:
                name, a, b = parse_factor_spec(str(s))
                if a is None or b is None:
                    raise ParameterError("bound", f"bound {s!r}: expected NAME=LOW:HIGH")
                pairs = [*pairs, (name, (a, b))]
        for key, pair in pairs:
            try:
                f = space[key]
            except KeyError:
                raise ParameterError("bound", f"bound for {key!r}: no such component or factor "
                                 f"(factors: {', '.join(space.names)})") from None
            a, b = (float(v) for v in pair)
            if not (math.isfinite(a) and math.isfinite(b)) or not a < b:
                raise ParameterError("bound", f"bound for {f.name!r}: expected LOW < HIGH, finite (got {a:g}, {b:g})")
            if f.name in items:
                raise ParameterError("bound", f"bound for {f.name!r} is given more than once")
            items[f.name] = (a, b)
    k = len(space)
    G_rows: list[np.ndarray] = []
    h: list[float] = []
    rows: list[str] = []
    limits: dict[str, tuple[float, float]] = {}
    for j, (lo, hi) in _component_limits(space, comps, items).items():
        f = space.factors[j]
        assert isinstance(f, MixtureComponent)
        name = f.name
        if not lo < hi:
            raise ParameterError("bound", f"bound for {name!r}: the region is empty (its limits {lo:g}..{hi:g} leave nothing)")
        e = np.zeros(k)
        e[j] = 1.0
        G_rows += [-e, e]
        h += [-(lo - f.lower) / R, (hi - f.lower) / R]
        rows += [f"bound {name} >= {lo:g}", f"bound {name} <= {hi:g}"]
        limits[name] = (float(lo), float(hi))
    for j, f in enumerate(space.factors):
        if j in comps:
            continue
        if not isinstance(f, Factor):
            raise ValueError(f"process factor {f.name!r} is categoric; a mixture region takes numeric ones")
        lo_c, hi_c = -1.0, 1.0
        if f.name in items:
            a, b = items[f.name]
            lo_c, hi_c = float(f.encode(a)), float(f.encode(b))
            if lo_c < -1.0 - 1e-9 or hi_c > 1.0 + 1e-9:
                raise ParameterError("bound", f"bound for {f.name!r} ({a:g}..{b:g}) reaches outside the design range "
                                 f"{f.low:g}..{f.high:g}")
            lo_c, hi_c = max(lo_c, -1.0), min(hi_c, 1.0)
        e = np.zeros(k)
        e[j] = 1.0
        G_rows += [-e, e]
        h += [-lo_c, hi_c]
        rows += [f"process {f.name} >= {lo_c:g} (coded)", f"process {f.name} <= {hi_c:g} (coded)"]
        limits[f.name] = (float(f.decode(lo_c)), float(f.decode(hi_c)))
    texts = [constraints] if isinstance(constraints, str) else list(getattr(constraints, "expressions", constraints) or [])
    if texts:
        from ...design.constraints import Constraints

        cons = Constraints.parse([str(t) for t in texts], space, check_empty=False)
        for c in cons.items:
            if not c.is_linear:
                raise ParameterError("constraints", f"constraint {c.text!r} is not linear; the region of a mixture is cut by linear "
                                 "constraints on the components (and process factors)")
        Ac, bc = cons.linear_system(coded=True)
        if not (np.all(np.isfinite(Ac)) and np.all(np.isfinite(bc))):
            raise ParameterError("constraints", "constraint: its coefficients are not finite")
        for i, c in enumerate(cons.items):
            if not np.any(Ac[i]):
                raise ParameterError("constraints", f"constraint {c.text!r} holds no factor")
            G_rows.append(Ac[i])
            h.append(float(bc[i]))
            rows.append(c.text)
    region = MixtureRegion(space=space, comps=comps, G=np.array(G_rows), h=np.array(h, dtype=float), rows=tuple(rows),
                           total=float(T), limits=limits)
    try:
        V = region.vertices()
    except ValueError as exc:  # named as the constraints' fault when there are any, else the bounds'
        raise (ParameterError("constraints",
                              f"constraints and bounds leave no blend summing to the total {T:g} (the region is empty)")
               if texts
               else ParameterError("bound", str(exc))) from None
    free = np.linalg.matrix_rank(V[1:] - V[0], tol=1e-9) if len(V) > 1 else 0
    if free < k - 1:
        raise ParameterError("constraints", f"constraints and bounds leave the region no interior (dimension {free} where {k - 1} is needed): the bounds and "
                         "constraints pin some blend or setting")
    return region
