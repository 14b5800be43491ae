"""Which runs next: :func:`suggest` picks new settings by an acquisition criterion on a
fitted emulator (a Gaussian process, ``rsm_lrg.fit(..., model="gp")``).

Criteria, each to be maximised over the region (the factor box, ``bounds``, ``constraints``),
with ``m`` and ``s`` the predicted mean and its kriging standard deviation, and the goal read
as a minimisation (``maximize`` negates the response; ``target=V`` minimises ``|y - V|``):

* ``"ei"``: expected improvement over the incumbent ``b`` (Jones, Schonlau & Welch 1998),
  ``(b - m) Phi(u) + s phi(u)``, ``u = (b - m) / s``; for a target, the expected reduction of
  ``|Y - V|`` below the best distance, in closed form over the normal.
* ``"pi"``: probability of improvement ``Phi(u)`` (for a target, ``P(|Y - V| < b)``).
* ``"lcb"``: ``-(m - 2 s)``, the lower confidence bound (for a target, ``-(|m - V| - 2 s)``).
* ``"variance"``: ``s^2``, pure exploration (space filling by the model).

The incumbent is the best observed response when the runs are deterministic (nugget 0) and,
for noisy runs, the best *predicted mean* at the runs (the plug-in EI that Picheny, Wagner &
Ginsbourger 2013 compare; the noise is not improved upon). A batch of ``runs`` settings is
chosen one at a time by the Kriging Believer (Ginsbourger, Le Riche & Carraro 2010): each
chosen setting joins the model with its predicted mean as response (hyper-parameters held),
which shrinks the variance around it, and the next is chosen on that model. Each choice is a
multistart search: the best points of a scrambled Sobol sample of the region start L-BFGS-B
(SLSQP inside constraints, :mod:`rsm_lrg.optimize.region` giving the feasible starts).

>>> import numpy as np, pandas as pd, rsm_lrg
>>> rng = np.random.default_rng(0)
>>> df = pd.DataFrame({"a": rng.uniform(0, 1, 10)})
>>> df["y"] = (df.a - 0.3) ** 2
>>> s = suggest(rsm_lrg.fit(df, "y", model="gp", kernel="gauss"), "minimize", runs=2, seed=1)
>>> len(s.design), list(s.table.columns)
(2, ['a', 'predicted', 'se_fit', 'criterion'])
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np

from ..errors import ParameterError
from ..model.build.goals import parse_goal

__all__ = ["suggest", "Suggestion", "CRITERIA", "LCB_KAPPA", "criterion_values"]

CRITERIA = ("ei", "pi", "lcb", "variance")
#: Multiple of the standard deviation in the confidence-bound criterion.
LCB_KAPPA = 2.0
#: Size of the Sobol sample that seeds every choice, and how many of its best points start a local search.
SAMPLE = 1024
STARTS = 6


@runtime_checkable
class Emulator(Protocol):
    """What :func:`suggest` needs of a fit: predictions with a standard deviation at coded
    points, the runs, the factor space, and conditioning on extra runs."""

    space: Any
    x: np.ndarray
    y: np.ndarray
    nugget: float
    response: str

    def predict(self, points: Any, interval: str | None = None, alpha: float = 0.05, *,
                coded: bool = False) -> Any: ...

    def mean_sd(self, coded_points: np.ndarray) -> tuple[np.ndarray, np.ndarray]: ...

    def with_runs(self, points: Any, values: Any, *, coded: bool = False) -> Any: ...


def _normal(u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    from scipy.special import ndtr

    u = np.clip(u, -40.0, 40.0)  # beyond, Phi is 0 or 1 and phi 0 (a zero sd at a run gives u = +-inf)
    return ndtr(u), np.exp(-0.5 * u * u) / np.sqrt(2.0 * np.pi)


def _interval_moments(m: np.ndarray, s: np.ndarray, a: np.ndarray, b: np.ndarray,
                      c0: np.ndarray, c1: float) -> np.ndarray:
    """``E[(c0 + c1 Y) 1{a <= Y <= b}]`` for ``Y ~ N(m, s^2)``."""
    Pa, pa = _normal((a - m) / s)
    Pb, pb = _normal((b - m) / s)
    return c0 * (Pb - Pa) + c1 * (m * (Pb - Pa) - s * (pb - pa))


def criterion_values(mean: np.ndarray, sd: np.ndarray, kind: str, target: float | None, best: float,
                     criterion: str) -> np.ndarray:
    """The criterion (larger is better) at points with predicted ``mean`` and ``sd``; ``best``
    is the incumbent: the smallest response (``minimize``), the largest (``maximize``) or the
    smallest distance to the target (``target``)."""
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # a zero sd at a run: u = +-inf
        return _criterion(np.asarray(mean, dtype=float), np.asarray(sd, dtype=float), kind, target, best, criterion)


def _criterion(m: np.ndarray, sd: np.ndarray, kind: str, target: float | None, best: float,
               criterion: str) -> np.ndarray:
    s = np.maximum(sd, 1e-300)
    if criterion == "variance":
        return sd ** 2
    if kind == "target":
        assert target is not None
        if criterion == "lcb":
            return -(np.abs(m - target) - LCB_KAPPA * s)
        d = best
        lo, hi = target - d, target + d
        if criterion == "pi":
            return _normal((hi - m) / s)[0] - _normal((lo - m) / s)[0]
        up = _interval_moments(m, s, np.full_like(m, target), np.full_like(m, hi), np.full_like(m, d + target), -1.0)
        dn = _interval_moments(m, s, np.full_like(m, lo), np.full_like(m, target), np.full_like(m, d - target), 1.0)
        return np.maximum(up + dn, 0.0)
    sign = 1.0 if kind == "minimize" else -1.0
    mm, b = sign * m, sign * best
    if criterion == "lcb":
        return -(mm - LCB_KAPPA * s)
    u = (b - mm) / s
    P, p = _normal(u)
    if criterion == "pi":
        return P
    return np.maximum((b - mm) * P + s * p, 0.0)


@dataclass(frozen=True)
class Suggestion:
    """New settings chosen by :func:`suggest`.

    Attributes
    ----------
    design : Design
        The settings as a design (``to_csv`` writes the design CSV the toolkit reads).
    table : pandas.DataFrame
        Per setting: the factors [actual units], ``predicted`` and ``se_fit`` of the fit
        given, and ``criterion``, the criterion's value when it was chosen (on the model
        with the earlier settings of the batch believed).
    response, criterion : str
    goal : tuple
        ``(kind, target)``.
    incumbent : float
        The best response the improvement is measured from (see the module docstring).
    notes : tuple of str
    """

    design: Any
    table: Any
    response: str
    criterion: str
    goal: tuple
    incumbent: float
    notes: tuple = field(default_factory=tuple)

    def to_frame(self) -> Any:
        """The design CSV layout (``std_order``, ``run_order``, ``coded_*``, the factors).

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        return self.design.to_frame()

    def to_dict(self) -> dict:
        """The suggested runs as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        kind, target = self.goal
        return {"response": self.response, "goal": kind, "target": target, "criterion": self.criterion,
                "incumbent": float(self.incumbent),
                "runs": [{k: float(v) for k, v in row.items()} for row in self.table.to_dict(orient="records")],
                "notes": list(self.notes)}

    def summary(self) -> str:
        """A few lines of text for people.

        Returns
        -------
        str
            The text, several lines.
        """
        kind, target = self.goal
        goal = f"target {target:g}" if kind == "target" else kind
        lines = [f"Next runs for {self.response} ({goal}), criterion {self.criterion}: {len(self.table)} setting(s)",
                 f"Incumbent: {self.incumbent:.6g}", ""]
        lines.append(self.table.to_string(index=False, float_format=lambda v: f"{v:.6g}"))
        lines += [f"Note: {n}" for n in self.notes]
        return "\n".join(lines) + "\n"


def _incumbent(model: Any, kind: str, target: float | None) -> float:
    """Best observed response (deterministic runs) or best predicted mean at the runs (noisy)."""
    y = model.y if model.nugget == 0.0 else model.mean_sd(model.x)[0]
    if kind == "minimize":
        return float(np.min(y))
    if kind == "maximize":
        return float(np.max(y))
    return float(np.min(np.abs(y - target)))


def suggest(fitted: Any, goal: Any = "minimize", runs: int = 1, *, criterion: str = "ei", bounds: Any = None,
            constraints: Any = None, seed: Any = 0) -> Suggestion:
    """Choose ``runs`` new settings by ``criterion`` (see the module docstring).

    Parameters
    ----------
    fitted : GPResult
        A Gaussian-process fit (``rsm_lrg.fit(data, y, model="gp")``).
    goal : str or tuple
        ``"minimize"``, ``"maximize"`` or ``"target=V"``.
    runs : int
        Number of settings (a batch, by the Kriging Believer).
    criterion : {"ei", "pi", "lcb", "variance"}
    bounds : mapping or list of str, optional
        Narrower bounds in actual units (``["NAME=LOW:HIGH"]``), inside the factor ranges.
    constraints : str or list of str, optional
        Inequalities on the factors in actual units (as for ``optimize``).
    seed : int or numpy.random.Generator
        Seed of the Sobol samples (the same seed gives the same settings).

    Returns
    -------
    Suggestion
    """
    import pandas as pd
    from scipy.optimize import minimize
    from scipy.stats import qmc

    from ..design.core import Design
    from .region import feasible_mask, parse_constraints, region_starts
    from .single import parse_bounds

    if not isinstance(fitted, Emulator):
        raise ParameterError("model", "suggest needs a Gaussian-process fit (model 'gp'): a polynomial's "
                                      "variance does not say where it is wrong")
    if not isinstance(criterion, str) or criterion.strip().lower() not in CRITERIA:
        raise ParameterError("criterion", f"criterion must be one of {', '.join(CRITERIA)}, not {criterion!r}")
    criterion = criterion.strip().lower()
    if isinstance(runs, bool) or not isinstance(runs, (int, np.integer)) or not 1 <= runs <= 1000:
        raise ParameterError("runs", f"runs must be a whole number from 1 to 1000, not {runs!r}")
    kind, target = parse_goal(goal)
    space = fitted.space
    lo, hi, notes = parse_bounds(space, bounds)
    cons = parse_constraints(constraints, space)
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    int_seed = int(rng.integers(2 ** 31))
    model = fitted
    chosen: list[np.ndarray] = []
    values: list[float] = []
    best0 = _incumbent(fitted, kind, target)
    for _ in range(int(runs)):
        best = _incumbent(model, kind, target)

        def score(X: np.ndarray, model: Any = model, best: float = best) -> np.ndarray:
            m, sd = model.mean_sd(X)
            return criterion_values(m, sd, kind, target, best, criterion)

        sample = lo + qmc.Sobol(d=len(lo), scramble=True, seed=rng).random(SAMPLE) * (hi - lo)
        sample = sample[feasible_mask(sample, cons)]
        starts = list(region_starts(cons, lo, hi, seed=int_seed))
        if sample.size:
            v = score(sample)
            starts = list(sample[np.argsort(-v)[:STARTS]]) + starts
        if not starts:
            raise ValueError("no feasible setting found inside the bounds and the constraints")

        def objective(x: np.ndarray, score: Any = score) -> float:
            return -float(score(np.asarray(x)[None, :])[0])

        cands = list(starts)  # L-BFGS-B on the box, SLSQP inside constraints (their margins >= 0)
        for x0 in starts:
            if cons is None:
                r = minimize(objective, x0, method="L-BFGS-B", bounds=list(zip(lo, hi)),
                             options={"ftol": 1e-10, "gtol": 1e-8, "maxiter": 200})
            else:
                ineq = {"type": "ineq", "fun": lambda x: cons.margin_coded(np.asarray(x)[None, :])[0]}
                r = minimize(objective, x0, method="SLSQP", bounds=list(zip(lo, hi)), constraints=[ineq],
                             options={"ftol": 1e-10, "maxiter": 200})
            cands.append(np.clip(r.x, lo, hi))
        cands = [c for c in cands if cons is None or bool(feasible_mask(c[None, :], cons)[0])]
        if not cands:
            raise ValueError("no feasible setting found inside the bounds and the constraints")
        vals = score(np.array(cands))
        x = np.asarray(cands[int(np.argmax(vals))], dtype=float)
        chosen.append(x)
        values.append(float(np.max(vals)))
        believed = float(model.predict(x[None, :], coded=True)["predicted"].iloc[0])
        model = model.with_runs(x[None, :], [believed], coded=True)
    X = np.array(chosen)
    design = Design(factors=space, kind="suggest", coded_runs=X, std_order=np.arange(1, len(X) + 1),
                    run_order=np.arange(1, len(X) + 1),
                    options={"criterion": criterion, "goal": kind, "target": target, "response": fitted.response,
                             "seed": seed if isinstance(seed, int) else None})
    actual = design.actual
    p = fitted.predict(design.coded_runs, coded=True)
    table = pd.DataFrame({**{c: actual[c].to_numpy() for c in actual.columns},
                          "predicted": p["predicted"].to_numpy(), "se_fit": p["se_fit"].to_numpy(),
                          "criterion": values})
    for i in range(1, len(X)):
        same = np.flatnonzero(np.max(np.abs(X[:i] - X[i]), axis=1) < 1e-9)
        if same.size:
            notes.append(f"setting {i + 1} repeats setting {int(same[0]) + 1}: a replicate (with noisy runs the "
                         "believed run leaves variance, and so improvement, at that setting)")
    if fitted.nugget > 0 and criterion in ("ei", "pi"):
        notes.append("noisy runs (nugget > 0): the improvement is measured from the best predicted mean at the runs "
                     "(plug-in EI, Picheny et al. 2013)")
    if runs > 1 and criterion != "variance":
        notes.append("batch by the Kriging Believer: each setting is chosen on the model that believes the earlier "
                     "ones at their predicted means")
    return Suggestion(design=design, table=table, response=fitted.response, criterion=criterion,
                      goal=(kind, target), incumbent=best0, notes=tuple(notes))
