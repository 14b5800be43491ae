"""Prediction at chosen settings with every interval, the propagation of error and the
simulator: what ``rsm-lrg predict`` prints.

For each setting and each response (one fitted model per response, one factor space): the
back-transformed prediction, the confidence interval for the mean, the prediction interval for
one run and, with ``tolerance=P``, the tolerance interval for a proportion P of runs
(:mod:`rsm_lrg.model.contract.tolerance`: two-sided and one-sided bounds), all at confidence C; with
``factor_sd`` the propagation of error (:mod:`rsm_lrg.optimize.poe`); with ``draws`` the
simulated runs (:mod:`rsm_lrg.optimize.simulator`), per setting from its own block of the seed.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["predict_points", "PredictionReport", "INTERVAL_COLUMNS"]

#: The columns of each prediction, in order (the tolerance ones with ``tolerance``, ``poe``
#: with ``factor_sd``).
INTERVAL_COLUMNS = ("predicted", "se_fit", "ci_low", "ci_high", "pi_low", "pi_high", "ti_low", "ti_high",
                    "ti_one_sided_low", "ti_one_sided_high", "poe")


@dataclass(frozen=True)
class PredictionReport:
    """Predictions at settings for one or several responses (frozen).

    Attributes
    ----------
    points : list of dict
        The settings, ``{factor: value}`` [actual units].
    predictions : dict
        ``{response: [ {column: value} per point ]}`` with the columns of
        :data:`INTERVAL_COLUMNS` that apply (``se_fit`` on the model's scale; the rest in
        response units).
    confidence : float
    tolerance : float or None
        P of the tolerance interval.
    factor_sd : dict
        ``{factor: SD}`` [actual units] of the propagation of error and the simulator.
    models : dict
        ``{response: model label}``.
    simulations : list of SimulationResult
        One per point with ``draws``, else empty.
    """

    points: list
    predictions: dict
    confidence: float
    tolerance: float | None
    factor_sd: dict
    models: dict
    simulations: list = field(default_factory=list)
    notes: tuple = field(default=())

    def to_dict(self) -> dict:
        out: dict[str, Any] = {"confidence": self.confidence, "tolerance": self.tolerance,
                               "factor_sd": dict(self.factor_sd), "models": dict(self.models),
                               "points": [dict(p) for p in self.points],
                               "predictions": {r: [dict(row) for row in rows] for r, rows in self.predictions.items()}}
        if self.simulations:
            out["simulation"] = [s.to_dict() for s in self.simulations]
        out["notes"] = list(self.notes)
        return out

    def summary(self) -> str:
        from ..present import format_g, text_table

        pc = f"{100 * self.confidence:g} %"
        lines = []
        names = list(self.points[0]) if self.points else []
        for r, rows in self.predictions.items():
            head = f"{r} ({self.models.get(r, '')}): prediction, {pc} CI for the mean, {pc} PI for one run"
            if self.tolerance is not None:
                head += f", TI for {100 * self.tolerance:g} % of runs with {pc} confidence"
            if self.factor_sd:
                head += ", POE"
            lines.append(head)
            header = ["point", *names, "predicted", "CI low", "CI high", "PI low", "PI high"]
            if self.tolerance is not None:
                header += ["TI low", "TI high", "1-sided low", "1-sided high"]
            if self.factor_sd:
                header += ["POE"]
            table = []
            for i, (p, row) in enumerate(zip(self.points, rows), start=1):
                cells = [str(i), *[format_g(p[n], 6, trim=True) for n in names]]
                cols = ["predicted", "ci_low", "ci_high", "pi_low", "pi_high"]
                if self.tolerance is not None:
                    cols += ["ti_low", "ti_high", "ti_one_sided_low", "ti_one_sided_high"]
                if self.factor_sd:
                    cols += ["poe"]
                cells += [format_g(row[c], 6) or "-" for c in cols]
                table.append(cells)
            lines.append(text_table(header, table))
            lines.append("")
        for i, s in enumerate(self.simulations, start=1):
            lines.append(f"Point {i}: " + s.summary().rstrip("\n"))
        lines += [f"note: {n}" for n in self.notes]
        return "\n".join(lines).rstrip("\n") + "\n"


def predict_points(fits: Mapping[str, Any], points: Any, *, confidence: float = 0.95, tolerance: float | None = None,
                   factor_sd: Mapping[str, Any] | Sequence[str] | None = None,
                   spec: Mapping[str, Any] | Sequence[str] | None = None, draws: int | None = None,
                   seed: int | None = None, model_uncertainty: bool = True, executor: Any = None,
                   progress: bool | None = None) -> PredictionReport:
    """Predictions with intervals, POE and (with ``draws``) simulated runs at each point.

    Parameters
    ----------
    fits : mapping of response -> FitResult
        One model per response, on the same factors.
    points : pandas.DataFrame
        One row per setting, a column per factor [actual units].
    confidence : float
        C of every interval, in (0, 1).
    tolerance : float, optional
        P of the tolerance interval, in (0, 1).
    factor_sd : mapping or list of str, optional
        ``{factor: SD}`` [actual units]: the POE column and the simulator's factor noise.
    spec : mapping or list of str, optional
        ``{response: (low, high)}`` for the simulator's defect rates (needs ``draws``).
    draws : int, optional
        Runs simulated per point (:func:`rsm_lrg.optimize.simulator.simulate`).
    seed : int, optional
        The simulator's seed (point ``i`` uses ``SeedSequence(seed).spawn`` child ``i``).
    model_uncertainty : bool
        Whether the simulator draws the coefficients from their sampling distribution.
    executor : concurrent.futures.Executor, optional
        Where the simulator's blocks run (the numbers do not depend on it).
    progress : bool, optional
        The simulator's progress bar on stderr (default: for more than
        :data:`rsm_lrg.optimize.simulator.MAX_KEPT` runs).

    Returns
    -------
    PredictionReport
    """
    from .poe import parse_factor_sd, propagation_of_error
    from .simulator import parse_specs, simulate

    if not 0.0 < float(confidence) < 1.0:
        raise ParameterError("confidence", f"confidence must lie strictly between 0 and 1, not {confidence!r}")
    first = next(iter(fits.values()))
    sds = parse_factor_sd(first.space, factor_sd)
    if spec and draws is None:
        raise ParameterError("spec", "spec limits are judged on simulated runs: give draws (--draws N --seed S) too")
    parse_specs(list(fits), spec)
    names = list(first.space.names)
    frame = points[names].reset_index(drop=True)
    predictions: dict[str, list] = {}
    for r, f in fits.items():
        out = f.predict(frame, interval="both", alpha=1.0 - float(confidence), tolerance=tolerance)
        if sds:
            out["poe"] = propagation_of_error(f, frame, sds)
        cols = [c for c in INTERVAL_COLUMNS if c in out.columns]
        predictions[r] = [{c: _finite(out[c].iloc[i]) for c in cols} for i in range(len(out))]
    settings = [{n: _value(frame[n].iloc[i]) for n in names} for i in range(len(frame))]
    sims = []
    if draws is not None:
        children = np.random.SeedSequence(seed).spawn(len(frame))
        for i, s in enumerate(settings):
            res = simulate(fits, s, draws=draws, seed=children[i], factor_sd=sds, spec=spec,
                           model_uncertainty=model_uncertainty, executor=executor, progress=progress)
            sims.append(_with_seed(res, seed))
    return PredictionReport(points=settings, predictions=predictions, confidence=float(confidence),
                            tolerance=None if tolerance is None else float(tolerance), factor_sd=sds,
                            models={r: f.label for r, f in fits.items()}, simulations=sims)


def _with_seed(res: Any, seed: int | None) -> Any:
    import dataclasses

    return dataclasses.replace(res, seed=seed)


def _value(v: Any) -> Any:
    if isinstance(v, (str, bool)):
        return v
    try:
        return float(v)
    except (TypeError, ValueError):
        return str(v)


def _finite(v: Any) -> float | None:
    x = float(v)
    return x if math.isfinite(x) else None
