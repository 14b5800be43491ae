"""Goals for a fitted response: minimise, maximise or hit a target (:func:`parse_goal`).

The goal is read on the response's own scale; a fit on a transformed response maps it onto
its scale with :meth:`rsm_lrg.model.build.transform.Transform.goal_on_model_scale`.
"""

from __future__ import annotations

import math
from typing import Any

from ...errors import ParameterError

__all__ = ["parse_goal"]

_GOALS = {"minimize": "minimize", "minimise": "minimize", "min": "minimize",
          "maximize": "maximize", "maximise": "maximize", "max": "maximize"}


def parse_goal(goal: Any) -> tuple[str, float | None]:
    """``("minimize"|"maximize"|"target", T or None)`` from ``"minimize"``, ``"maximize"``,
    ``"target=V"`` or ``("target", V)``.

    >>> parse_goal("target=0.03")
    ('target', 0.03)

    Parameters
    ----------
    goal : str or tuple
        ``"minimize"``, ``"maximize"``, ``"target=V"`` or ``("target", V)``.

    Returns
    -------
    tuple
        ``(kind, T or None)``.
    """
    if isinstance(goal, (tuple, list)) and len(goal) == 2 and str(goal[0]).lower() == "target":
        value = goal[1]
    elif isinstance(goal, str):
        g = goal.strip().lower()
        if g in _GOALS:
            return _GOALS[g], None
        if not g.startswith("target"):
            raise ParameterError("goal", f"goal must be minimize, maximize or target=V, not {goal!r}")
        rest = g[len("target"):].strip()
        if not rest.startswith("="):
            raise ParameterError("goal", f"goal {goal!r}: a target needs a value, e.g. target=0.03")
        value = rest[1:].strip()
    else:
        raise ParameterError("goal", f"goal must be minimize, maximize or target=V, not {goal!r}")
    try:
        t = float(value)
    except (TypeError, ValueError):
        raise ParameterError("goal", f"goal {goal!r}: the target {value!r} is not a number") from None
    if not math.isfinite(t):
        raise ParameterError("goal", f"goal {goal!r}: the target must be a finite number")
    return "target", t
