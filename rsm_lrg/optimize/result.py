"""The result of a single-response optimum (:class:`OptimumResult`), in its own module so that
every optimiser (:mod:`rsm_lrg.optimize.single`, :mod:`rsm_lrg.optimize.mixture`) builds it
without importing another optimiser. ``rsm_lrg.optimize.OptimumResult`` and
``rsm_lrg.optimize.single.OptimumResult`` are this class.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

__all__ = ["OptimumResult", "optimum_notes"]


@dataclass(frozen=True)
class OptimumResult:
    """The optimum of a fitted response (frozen).

    Attributes
    ----------
    response : str
    goal : str
        ``"minimize"``, ``"maximize"`` or ``"target"``.
    target : float or None
        The target value for ``goal == "target"`` [response units].
    coded : dict
        ``{letter: value}`` [coded units].
    actual : dict
        ``{factor name: value}`` [actual units].
    predicted : float
        ŷ at the optimum (average block) [response units].
    confidence : float
        Level of ``ci`` and ``pi`` (0.95).
    ci, pi : tuple of float
        Confidence interval of the mean and prediction interval of one new run.
    se_fit : float
        Standard error of ŷ.
    bounds : dict
        ``{factor name: (low, high)}`` searched [actual units].
    warnings : tuple of str
    n_starts : int
        Local searches run (besides the exact enumeration).
    method : str
        ``"exact-faces+multistart"`` or ``"multistart"`` (a mixture: ``"exact-faces"`` or
        ``"multistart"``, :mod:`rsm_lrg.optimize.mixture`).
    total : float or None
        A mixture's total (``actual`` holds the blend in real proportions, ``coded`` its
        L-pseudo components); ``None`` otherwise.
    components : tuple of str
        A mixture's component names (empty otherwise).
    """

    response: str
    goal: str
    target: float | None
    coded: dict
    actual: dict
    predicted: float
    confidence: float
    ci: tuple
    pi: tuple
    se_fit: float = math.nan
    bounds: dict = field(default_factory=dict)
    warnings: tuple = ()
    n_starts: int = 0
    method: str = "multistart"
    by_level: tuple = ()
    total: float | None = None
    components: tuple = ()

    def to_dict(self) -> dict:
        """The optimize JSON of INTERFACE.md (plus ``target``, ``bounds``, ``warnings``).

        Returns
        -------
        dict
            Plain JSON-safe data (numbers, strings, lists and dicts).
        """
        out = {
            "response": self.response,
            "goal": self.goal,
            "coded": dict(self.coded),
            "actual": dict(self.actual),
            "predicted": self.predicted,
            "confidence": self.confidence,
            "ci": [self.ci[0], self.ci[1]],
            "pi": [self.pi[0], self.pi[1]],
        }
        if self.target is not None:
            out["target"] = self.target
        out["bounds"] = {k: (list(v) if isinstance(v, tuple) else v) for k, v in self.bounds.items()}
        out["warnings"] = list(self.warnings)
        if self.by_level:
            out["by_level"] = [dict(r) for r in self.by_level]
        if self.total is not None:
            out["total"] = self.total
        return out

    def to_frame(self):
        """One-row DataFrame: actual settings, coded settings, prediction and intervals.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        import pandas as pd

        row: dict[str, Any] = dict(self.actual)
        row.update({f"coded_{k}": v for k, v in self.coded.items()})
        row.update({"predicted": self.predicted, "ci_low": self.ci[0], "ci_high": self.ci[1],
                    "pi_low": self.pi[0], "pi_high": self.pi[1]})
        return pd.DataFrame([row])

    def summary(self) -> str:
        """A few lines of text.

        Returns
        -------
        str
            Text for people, several lines.
        """
        from ..present import format_g

        g = self.goal if self.target is None else f"target {format_g(self.target, 6, trim=True)}"
        lines = [f"Optimum of {self.response} ({g})"]
        for (L, c), (name, a) in zip(self.coded.items(), self.actual.items()):
            if name in self.components:
                lines.append(f"  {L}: {name} = {format_g(a, 6, trim=True)}   (L-pseudo {format_g(c, 6, trim=True)})")
            elif isinstance(a, str):
                lines.append(f"  {L}: {name} = {a}   (categoric)")
            else:
                lines.append(f"  {L}: {name} = {format_g(a, 6, trim=True)}   (coded {c:+.4f})")
        if self.total is not None:
            lines.append(f"  (the blend sums to the total {format_g(self.total, 6, trim=True)})")
        pc = int(round(self.confidence * 100))
        lines.append(f"  predicted: {format_g(self.predicted, 6, trim=True)}")
        lines.append(f"  {pc} % CI:  {format_g(self.ci[0], 6, trim=True)} .. {format_g(self.ci[1], 6, trim=True)}")
        lines.append(f"  {pc} % PI:  {format_g(self.pi[0], 6, trim=True)} .. {format_g(self.pi[1], 6, trim=True)}")
        lines.extend(f"  warning: {w}" for w in self.warnings)
        if len(self.by_level) > 1:
            lines.append("  best setting per level combination:")
            for r in self.by_level:
                lv = ", ".join(f"{k} = {v}" for k, v in r["level"].items())
                at = ", ".join(f"{k} = {format_g(v, 6, trim=True)}" for k, v in r["actual"].items() if k not in r["level"])
                lines.append(f"    {lv}: {format_g(r['predicted'], 6, trim=True)} at {at}")
        return "\n".join(lines) + "\n"


def optimum_notes(fitted: Any, goal_target: Any, predicted: float, missed_target: bool) -> list[str]:
    """The notes of every single-response optimum: a target that the region cannot reach
    (``missed_target``, judged by the optimiser on the model's scale; ``predicted`` the closest
    value [response units]) and a model fitted to a transformed response."""
    from ..present import format_g

    notes = []
    if missed_target:
        notes.append(f"the target {format_g(goal_target, 6, trim=True)} cannot be reached inside the region: the closest "
                     f"predicted value is {format_g(float(predicted), 6, trim=True)}")
    tr = fitted.transform
    if not tr.identity:
        notes.append(f"model fitted to the {tr.label}-transformed response; prediction and intervals "
                     "back-transformed (standard error on the transformed scale)")
    return notes
