"""The constrained search shared by the single-response and the desirability optimisers.

A region that is not a box: the coded box ``lo <= x <= hi`` intersected with inequalities on
the factors in actual units (:class:`rsm_lrg.design.constraints.Constraints`, e.g. the motion
profile's ``v**2/a <= s``). Local searches run from the given starts plus feasible points of a
quasi-random sample of the region: L-BFGS-B on the box alone, SLSQP with the constraint
margins as inequality constraints otherwise. Only feasible end points (and feasible starts)
are kept as candidates; none at all is a ``ValueError``.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError

__all__ = ["constraint_texts", "parse_constraints", "region_starts", "local_minima", "feasible_only", "is_feasible"]

#: Message when no candidate satisfies the constraints.
INFEASIBLE = "no feasible setting found inside the bounds and the constraints"


def constraint_texts(constraints) -> list[str]:
    """The constraint expressions as a list of strings (``None``: none)."""
    if constraints is None:
        return []
    if isinstance(constraints, str):
        return [constraints]
    if hasattr(constraints, "expressions"):
        return list(constraints.expressions)
    return [str(c) for c in constraints]


def parse_constraints(constraints, space):
    """:class:`~rsm_lrg.design.constraints.Constraints` on ``space`` or None when there are none
    (a bad expression or an empty region is a ``ValueError`` naming the constraint)."""
    exprs = constraint_texts(constraints)
    if not exprs:
        return None
    from ..design.constraints import Constraints

    return Constraints.parse(exprs, space)


def is_feasible(x, cons) -> bool:
    """Whether the coded point ``x`` satisfies every constraint (always, without any)."""
    return cons is None or bool(cons.feasible_coded(np.asarray(x, dtype=float)[None, :])[0])


def feasible_mask(X, cons) -> np.ndarray:
    """Boolean mask of the coded rows of ``X`` that satisfy the constraints."""
    X = np.atleast_2d(np.asarray(X, dtype=float))
    if cons is None:
        return np.ones(len(X), dtype=bool)
    return cons.feasible_coded(X)


def region_starts(cons, lo, hi, seed: int = 0, n: int = 32) -> list:
    """Up to ``n`` feasible coded points inside the bounds from the region sample (none
    without constraints)."""
    if cons is None:
        return []
    reg = np.asarray(cons.region_sample(256, seed), dtype=float)
    reg = reg[cons.feasible_coded(reg) & np.all((reg >= lo) & (reg <= hi), axis=1)]
    return list(reg[:n])


def local_minima(obj, starts, lo, hi, cons=None, *, jac: bool = False, maxiter: int = 300,
                 keep_starts: bool = True) -> list:
    """End points of local minimisations of ``obj`` from every start, clipped to the box
    (and the starts themselves when ``keep_starts``): L-BFGS-B on the box, SLSQP with the
    constraints' margins (>= 0 when satisfied) when ``cons`` is given. ``jac=True``: ``obj``
    returns ``(value, gradient)``."""
    from scipy import optimize as so

    box = list(zip(lo, hi))
    ineq = None
    if cons is not None:
        ineq = {"type": "ineq", "fun": lambda x: cons.margin_coded(np.asarray(x)[None, :])[0]}
    out = []
    for x0 in starts:
        try:
            if cons is None:
                r = so.minimize(obj, x0, jac=jac, method="L-BFGS-B", bounds=box,
                                options={"ftol": 1e-15, "gtol": 1e-10, "maxiter": maxiter})
            else:
                r = so.minimize(obj, x0, jac=jac, method="SLSQP", bounds=box, constraints=[ineq],
                                options={"ftol": 1e-15, "maxiter": maxiter})
            out.append(np.clip(r.x, lo, hi))
        except (ValueError, FloatingPointError):
            continue
        finally:
            if keep_starts:
                out.append(np.clip(np.asarray(x0, dtype=float), lo, hi))
    return out


def feasible_only(candidates, cons) -> list:
    """The candidates that satisfy the constraints; ``ValueError`` when none does."""
    if cons is None:
        return list(candidates)
    kept = [c for c in candidates if is_feasible(c, cons)]
    if not kept:
        raise ParameterError("constraints", INFEASIBLE)
    return kept
