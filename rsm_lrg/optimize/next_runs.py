"""Which runs next: :func:`suggest` picks new settings by an acquisition criterion on a
fitted model: a Gaussian process (``rsm_lrg.fit(..., model="gp")``) or a polynomial fitted by
least squares or REML (``model="quadratic"``, a term list, blocks, whole plots), seen through
the prediction contract (:class:`PolynomialEmulator`).

Criteria, each to be maximised over the region (the factor box, ``bounds``, ``constraints``),
with ``m`` and ``s`` the predicted mean and its standard deviation (the kriging sd of a GP; a
polynomial's standard error of the mean, ``sqrt(x' C x)`` with ``C`` the covariance of its
coefficients), on the model's scale, and the goal read as a minimisation (``maximize``
negates the response; ``target=V`` minimises ``|y - V|``):

* ``"ei"``: expected improvement over the incumbent ``b`` (Jones, Schonlau & Welch 1998),
  ``(b - m) Phi(u) + s phi(u)``, ``u = (b - m) / s``; for a target, the expected reduction of
  ``|Y - V|`` below the best distance, in closed form over the normal.
* ``"pi"``: probability of improvement ``Phi(u)`` (for a target, ``P(|Y - V| < b)``).
* ``"lcb"``: ``-(m - 2 s)``, the lower confidence bound (for a target, ``-(|m - V| - 2 s)``).
* ``"variance"``: ``s^2``, pure exploration (space filling by the model).

The incumbent is the best observed response when the runs are deterministic (a GP with nugget
0) and, for noisy runs (a GP with a nugget, every least-squares or REML fit), the best
*predicted mean* at the runs (the plug-in EI that Picheny, Wagner & Ginsbourger 2013 compare;
the noise is not improved upon). A batch of ``runs`` settings is chosen one at a time by the
Kriging Believer (Ginsbourger, Le Riche & Carraro 2010): each chosen setting joins the model
with its predicted mean as response (hyper-parameters, or the polynomial's variances, held),
which shrinks the variance around it, and the next is chosen on that model. For a polynomial
this is the recursive least-squares update of its coefficients' covariance, and
``criterion="variance"`` then adds, one at a time, the setting of largest prediction variance:
Wynn's (1970) sequential D-optimal augmentation. Each choice is a multistart search: the best
points of a scrambled Sobol sample of the region start L-BFGS-B (SLSQP inside constraints,
:mod:`rsm_lrg.optimize.region` giving the feasible starts).

>>> import numpy as np, pandas as pd, rsm_lrg
>>> rng = np.random.default_rng(0)
>>> df = pd.DataFrame({"a": rng.uniform(0, 1, 10)})
>>> df["y"] = (df.a - 0.3) ** 2
>>> s = suggest(rsm_lrg.fit(df, "y", model="gp", kernel="gauss"), "minimize", runs=2, seed=1)
>>> len(s.design), list(s.table.columns)
(2, ['a', 'predicted', 'se_fit', 'criterion'])
>>> df["y"] += rng.normal(0, 0.01, 10)
>>> q = suggest(rsm_lrg.fit(df, "y", model="quadratic"), "minimize", seed=1)
>>> round(float(q.table["a"].iloc[0]), 1)
0.3
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np

from ..errors import ParameterError
from ..model.build.goals import parse_goal

__all__ = ["suggest", "Suggestion", "PolynomialEmulator", "CRITERIA", "LCB_KAPPA", "criterion_values"]

CRITERIA = ("ei", "pi", "lcb", "variance")
#: Multiple of the standard deviation in the confidence-bound criterion.
LCB_KAPPA = 2.0
#: Size of the Sobol sample that seeds every choice, and how many of its best points start a local search.
SAMPLE = 1024
STARTS = 6


@runtime_checkable
class Emulator(Protocol):
    """What :func:`suggest` needs of a model: the mean and its standard deviation at coded
    points (on the model's scale), the runs, the factor space, the noise (``nugget``, 0 for
    deterministic runs) and conditioning on extra runs. A GP fit is one; a least-squares or
    REML fit is read as one by :class:`PolynomialEmulator`."""

    space: Any
    x: np.ndarray
    y: np.ndarray
    nugget: float
    response: str

    def mean_sd(self, coded_points: np.ndarray) -> tuple[np.ndarray, np.ndarray]: ...

    def with_runs(self, points: Any, values: Any, *, coded: bool = False) -> Any: ...


class PolynomialEmulator:
    """A least-squares or REML fit seen as an emulator through the prediction contract: at coded
    settings the predicted mean on the model's scale, ``f(x)' b``, and its standard error,
    ``sqrt(f(x)' C f(x))`` (``C`` the interval form's covariance of the mean, ``C σ²`` for
    least squares, Kenward–Roger's ``Φ_A`` for REML); :meth:`with_runs` conditions both on
    extra runs by recursive least squares, each new run with the variance of a new run
    (``σ²``, or ``σ²_g + σ²`` in a new whole plot or block), the variances held as a GP's
    hyper-parameters are.

    Parameters
    ----------
    fit : FitResult
        A least-squares or REML fit of numeric factors (no categoric factor, no mixture).

    Attributes
    ----------
    x : (n, k) ndarray
        The coded runs (and the runs added by :meth:`with_runs`).
    y : (n,) ndarray
        Their responses on the model's scale (and the values given to :meth:`with_runs`); the
        runs are noisy, so the incumbent is the best predicted mean at ``x``, not the best ``y``.
    nugget : float
        The variance of a new run, ``σ²`` or ``σ²_g + σ²`` [model-scale units²].

    Raises
    ------
    ParameterError
        When the fit has no interval form (a GLM), a categoric factor or a mixture, or no
        residual variance (no residual degrees of freedom: its standard errors are undefined).
    """

    def __init__(self, fit: Any) -> None:
        form = getattr(fit, "interval_form", None)
        if form is None or not hasattr(fit, "coded_runs"):
            raise ParameterError("model", "suggest takes a Gaussian process or a polynomial fitted by least squares "
                                          f"or REML, not {type(fit).__name__}")
        mixture = fit.space.components
        other = [(f.name, "a mixture component" if f in mixture else "categoric") for f in fit.space.factors
                 if f.kind == "categoric" or f in mixture]
        if other:
            raise ParameterError("model", f"suggest searches a box of numeric factors: {other[0][0]!r} is "
                                          f"{other[0][1]}")
        s2 = float(form.s2_new)
        cov = np.asarray(form.cov_mean, dtype=float)
        if not (np.isfinite(s2) and s2 > 0.0 and np.all(np.isfinite(cov))):
            raise ParameterError("model", "the polynomial has no residual variance (no residual degrees of freedom): "
                                          "its standard errors, and so the criterion, are undefined; fit fewer terms "
                                          "or add runs")
        self.fit = fit
        self.space = fit.space
        self.response = fit.response
        self.nugget = s2
        self.x = np.asarray(fit.coded_runs()[fit.space.letters], dtype=float)
        self.y = np.asarray(fit.y, dtype=float)
        self._cov = cov
        self._shift = np.zeros(cov.shape[0])  # the coefficients' change from runs added, b - b_fit

    def _rows(self, X: np.ndarray) -> np.ndarray:
        """The model rows ``f(x)'`` of coded settings (the fit's terms)."""
        from ..terms import design_matrix

        return design_matrix(np.atleast_2d(np.asarray(X, dtype=float)), self.fit.terms)

    def mean_sd(self, coded_points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Predicted mean on the model's scale and its standard error at an (m, k) array of coded
        settings [model-scale units]."""
        X = np.atleast_2d(np.asarray(coded_points, dtype=float))
        F = self._rows(X)
        mean = np.asarray(self.fit.predict_coded(X), dtype=float) + F @ self._shift
        var = np.einsum("ij,jk,ik->i", F, self._cov, F)
        return mean, np.sqrt(np.maximum(var, 0.0))

    def with_runs(self, points: Any, values: Any, *, coded: bool = True) -> PolynomialEmulator:
        """The same model conditioned on extra runs as well: ``values`` [model scale] at the
        coded ``points``, by recursive least squares (each run's variance the variance of a new
        run; the variances held). With the predicted means as values (the believer of a batch)
        the mean is unchanged and the standard errors shrink around the points.

        Parameters
        ----------
        points : (m, k) array_like
            Coded settings.
        values : (m,) array_like
            A response per setting [model-scale units].
        coded : bool, default True
            Must be True (the emulator works in coded units).

        Returns
        -------
        PolynomialEmulator
            A new emulator; this one is unchanged.
        """
        if not coded:
            raise ValueError("PolynomialEmulator.with_runs takes coded settings")
        X = np.atleast_2d(np.asarray(points, dtype=float))
        F = self._rows(X)
        yv = np.atleast_1d(np.asarray(values, dtype=float))
        if yv.shape != (F.shape[0],) or not np.isfinite(yv).all():
            raise ValueError(f"with_runs needs one finite value per point ({F.shape[0]}), got {yv.shape}")
        base = np.asarray(self.fit.predict_coded(X), dtype=float)  # f' b of the fit
        cov, shift = self._cov.copy(), self._shift.copy()
        for f, b0, v in zip(F, base, yv):
            cf = cov @ f
            gain = cf / (self.nugget + float(f @ cf))
            shift = shift + gain * (v - (b0 + float(f @ shift)))
            cov = cov - np.outer(gain, cf)
        out = object.__new__(PolynomialEmulator)
        out.__dict__.update(self.__dict__)
        out._cov, out._shift = cov, shift
        out.x, out.y = np.vstack([self.x, X]), np.r_[self.y, yv]
        return out


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
    fitted : GPResult or FitResult
        A Gaussian-process fit (``rsm_lrg.fit(data, y, model="gp")``) or a polynomial fitted by
        least squares or REML of numeric factors (:class:`PolynomialEmulator`).
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

    emulator = fitted if isinstance(fitted, Emulator) else PolynomialEmulator(fitted)
    if not isinstance(criterion, str) or criterion.strip().lower() not in CRITERIA:
        raise ParameterError("criterion", f"criterion must be one of {', '.join(CRITERIA)}, not {criterion!r}")
    criterion = criterion.strip().lower()
    if isinstance(runs, bool) or not isinstance(runs, (int, np.integer)) or not 1 <= runs <= 1000:
        raise ParameterError("runs", f"runs must be a whole number from 1 to 1000, not {runs!r}")
    parse_goal(goal)  # a goal that is not one is refused before the fit is asked anything
    kind0, target0, kind, target = fitted.goal_on_model_scale(goal)  # the criterion reads the model's scale
    shown = (kind0, target0)
    space = fitted.space
    lo, hi, notes = parse_bounds(space, bounds)
    cons = parse_constraints(constraints, space)
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    int_seed = int(rng.integers(2 ** 31))
    model = emulator
    chosen: list[np.ndarray] = []
    values: list[float] = []
    best0 = _incumbent(emulator, kind, target)
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
        believed = float(model.mean_sd(x[None, :])[0][0])
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
    polynomial = emulator is not fitted
    if emulator.nugget > 0 and criterion in ("ei", "pi"):
        notes.append(("a polynomial fitted to noisy runs" if polynomial else "noisy runs (nugget > 0)")
                     + ": the improvement is measured from the best predicted mean at the runs "
                     "(plug-in EI, Picheny et al. 2013)")
    if polynomial:
        notes.append("the standard deviation is the polynomial's standard error of the mean: it says how well "
                     "the model's coefficients are known, not where the model is wrong")
        if criterion == "variance":
            notes.append("criterion variance on a polynomial: each setting is the one of largest prediction "
                         "variance given the runs and the earlier settings (sequential D-optimal augmentation, "
                         "Wynn 1970)")
    if not fitted.transform.identity and criterion != "variance":
        notes.append(f"the criterion and the incumbent are on the model's scale ({fitted.transform.label})")
    if runs > 1 and criterion != "variance":
        notes.append("batch by the Kriging Believer: each setting is chosen on the model that believes the earlier "
                     "ones at their predicted means")
    return Suggestion(design=design, table=table, response=fitted.response, criterion=criterion,
                      goal=shown, incumbent=best0, notes=tuple(notes))
