"""The optima a report shows, computed here (the optimise layer) and handed to the report,
which only presents them: each response's optimum for its goal (or why there is none) and,
with several responses, the Derringer–Suich desirability optimum of all.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

__all__ = ["ReportOptima", "report_optima"]


@dataclass(frozen=True)
class ReportOptima:
    """Optima for a report (frozen).

    Attributes
    ----------
    single : dict
        ``{response: OptimumResult}`` for every response whose optimum was found.
    missing : dict
        ``{response: reason}`` for the others (no goal, a target outside the transform's
        domain, ...).
    desirability : DesirabilityResult or None
        The overall desirability optimum (several responses, each with a goal).
    desirability_missing : str
        Why there is none (empty when there is one or it was not asked for).
    """

    single: dict = field(default_factory=dict)
    missing: dict = field(default_factory=dict)
    desirability: Any = None
    desirability_missing: str = ""


def report_optima(fits: Mapping[str, Any], goals: Mapping[str, Any], limits: Mapping[str, Any] | None = None, *,
                  desirability: bool = True, bounds=None, constraints=None) -> ReportOptima:
    """The optima of ``fits`` (``{response: FitResult}``) for ``goals`` (``{response: goal or
    None}``; goals on the response's own scale), and with several responses the desirability
    optimum within ``limits`` (``{response: (low, high) or None}``, default the observed
    range). ``bounds`` and ``constraints`` (as for :func:`rsm_lrg.optimize`: ``["NAME=LOW:HIGH"]``,
    inequalities in actual units) keep every optimum inside the region. A failure is recorded as
    a reason, never raised."""
    from .desirability import optimize_desirability, parse_response_goal
    from .single import optimize

    single, missing = {}, {}
    for name, fit in fits.items():
        goal = goals.get(name)
        if goal is None:
            missing[name] = "no goal given"
            continue
        try:
            single[name] = optimize(fit, goal=goal, bounds=bounds, constraints=constraints)
        except (ValueError, NotImplementedError, TypeError) as exc:
            missing[name] = str(exc)
    desir, why = None, ""
    if desirability and len(fits) > 1 and all(goals.get(n) is not None for n in fits):
        try:
            specs = []
            for name in fits:
                g = parse_response_goal(str(name), str(goals[name]))
                lo, hi = (limits or {}).get(name) or (None, None)
                specs.append(dataclasses.replace(g, **({"low": lo} if lo is not None else {}),
                                                 **({"high": hi} if hi is not None else {})))
            desir = optimize_desirability(dict(fits), specs, bounds=bounds, constraints=constraints)
        except (ValueError, NotImplementedError, TypeError) as exc:
            why = str(exc)
    return ReportOptima(single=single, missing=missing, desirability=desir, desirability_missing=why)
