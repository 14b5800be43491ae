"""The result of a Gaussian-process fit (:class:`GPResult`): predictions with the kriging
variance, the closed-form leave-one-out check, the gradient, draws of the surface, the JSON
and the text.

Prediction is universal kriging (as R ``DiceKriging::predict.km(type="UK")``): at a new
setting ``x`` with ``r = sigma2 R(x, X)``,

    mean  m(x) = f(x)' beta + r' Sigma^-1 (y - F beta)
    var   s2(x) = sigma2 - r' Sigma^-1 r + u' (F' Sigma^-1 F)^-1 u,   u = f(x) - F' Sigma^-1 r,

``s2`` the variance of the mean surface (``se_fit = sqrt(s2)``); a new run adds the nugget,
``s2 + tau2``. The intervals are normal (``m +- z sqrt(s2)`` and ``m +- z sqrt(s2 + tau2)``),
the hyper-parameters taken as known (plug-in), as in DiceKriging. ``predict.km`` adds the
nugget to its ``sd`` at every new point; its ``sd`` is therefore this result's
``sqrt(se_fit^2 + nugget)``.

Leave-one-out (Dubrule 1983): with ``Q = Sigma^-1 - Sigma^-1 F (F' Sigma^-1 F)^-1 F' Sigma^-1``,
the residual of run ``i`` predicted from the others (trend re-estimated, covariance
parameters fixed) is ``(Q y)_i / Q_ii`` and its variance ``1 / Q_ii``; ``Q y = Sigma^-1 (y -
F beta)`` needs no refit.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from scipy.linalg import solve_triangular

from ...errors import ParameterError
from ...factors import FactorSpace
from ..build.inputs import coded_points
from ..build.transform import Transform
from ..engines.gp_core import KrigingCore, cholesky_jitter, inverse_lower
from ..engines.gp_kernels import COMPILED_PAIRS, DICEKRIGING_NAMES, correlation, log_derivative_x
from ..engines.gp_trend import trend_gradient, trend_matrix

__all__ = ["GPResult", "LeaveOneOut", "PREDICT_CHUNK"]

#: New points predicted at a time (bounds the memory of a prediction to ``chunk x n`` floats).
PREDICT_CHUNK = 2000


def _f(v: Any) -> float | None:
    v = float(v)
    return v if np.isfinite(v) else None


@dataclass(frozen=True)
class LeaveOneOut:
    """Closed-form leave-one-out of a GP (Dubrule 1983).

    Attributes
    ----------
    predicted : (n,) ndarray
        Each run's prediction from the other runs [response units].
    residuals : (n,) ndarray
        ``y - predicted``.
    sd : (n,) ndarray
        Standard deviation of each run about its leave-one-out prediction (nugget included).
    standardized : (n,) ndarray
        ``residuals / sd`` (about N(0, 1) when the model holds).
    q2 : float
        ``1 - sum(residuals²) / sum((y - mean y)²)``.
    rmse : float
        Root mean square of the residuals.
    """

    predicted: np.ndarray
    residuals: np.ndarray
    sd: np.ndarray
    standardized: np.ndarray
    q2: float
    rmse: float

    def to_dict(self) -> dict:
        return {"q2": _f(self.q2), "rmse": _f(self.rmse), "press": _f(float(np.sum(self.residuals ** 2))),
                "residuals": [_f(v) for v in self.residuals],
                "standardized_residuals": [_f(v) for v in self.standardized]}


@dataclass(frozen=True)
class GPResult:
    """A fitted Gaussian process (see :func:`rsm_lrg.model.pipelines.gp.fit_gp`).

    Attributes
    ----------
    response : str
    space : FactorSpace
        The factors and their coding; the GP works on the coded factors.
    kernel, trend : str
    x : (n, k) ndarray
        Coded settings of the runs.
    y : (n,) ndarray
        Responses of the runs.
    trend_names : list of str
        Names of the trend's columns (``Intercept``, ``A``, ``AB``, ``A^2``, ...).
    length_scales : (k,) ndarray
        Length-scales [coded units].
    variance, nugget : float
        Process variance ``sigma2`` and nugget ``tau2`` [response units²].
    core : KrigingCore
        The factorisation at these hyper-parameters.
    estimated : dict
        Which hyper-parameters were estimated (the others were given).
    starts : int
        Starting points of the likelihood's maximisation.
    search : dict
        How the maximum was searched (``length_scale_bounds``: the bounds of the estimated
        length-scales as multiples of each factor's coded range, ``None`` when they were given;
        ``subsample``, ``polished``, likelihood evaluations;
        :class:`rsm_lrg.model.pipelines.gp.Estimate`); empty when nothing was estimated.
    seed : int or None
    notes : tuple of str
    omitted_rows : tuple of int
        1-based data rows without a response.
    """

    response: str
    space: FactorSpace
    kernel: str
    trend: str
    x: np.ndarray
    y: np.ndarray
    trend_names: list
    length_scales: np.ndarray
    variance: float
    nugget: float
    core: KrigingCore
    estimated: dict = field(default_factory=dict)
    starts: int = 0
    search: dict = field(default_factory=dict)
    seed: int | None = None
    notes: tuple = ()
    omitted_rows: tuple = ()

    model = "gp"

    # -- basic numbers -------------------------------------------------------------------
    @property
    def n(self) -> int:
        return int(self.y.size)

    @property
    def input_notes(self) -> tuple:
        """The notes (as a polynomial fit's ``input_notes``)."""
        return self.notes

    @property
    def beta(self) -> np.ndarray:
        """GLS trend coefficients, in the order of :attr:`trend_names` (coded units)."""
        return self.core.beta

    @property
    def log_likelihood(self) -> float:
        """Log-likelihood at these hyper-parameters (at estimated ones, the concentrated
        log-likelihood, DiceKriging's ``logLik``)."""
        return self.core.log_likelihood

    @property
    def length_scales_actual(self) -> np.ndarray:
        """Length-scales in actual units (coded ones times the half-range)."""
        return self.length_scales * np.array([f.half_range for f in self.space.numeric])

    @cached_property
    def condition_number(self) -> float:
        """Condition number (1-norm, LAPACK ``dpocon`` estimate) of the covariance matrix
        ``Sigma`` of the runs."""
        from scipy.linalg.lapack import dpocon

        L = self.core.chol
        # the matrix factorised, L L' = sigma2 R + (tau2 + jitter sigma2) I, rebuilt in O(n^2)
        sigma = self.variance * correlation(self.x, self.x, self.length_scales, self.kernel)
        sigma[np.diag_indices_from(sigma)] += self.nugget + self.core.jitter * self.variance
        anorm = float(np.max(np.sum(np.abs(sigma), axis=0)))
        rcond, _ = dpocon(L, anorm, uplo="L")
        return float(1.0 / rcond) if rcond > 0 else float("inf")

    # -- points ----------------------------------------------------------------------------
    def coded_points(self, points: Any, coded: bool = False) -> np.ndarray:
        """Points as an (m, k) array of coded settings; ``points`` as for :meth:`predict`
        (:func:`rsm_lrg.model.build.inputs.coded_points`)."""
        return coded_points(self.space, points, coded)

    # -- prediction ------------------------------------------------------------------------
    def _cross(self, x: np.ndarray) -> np.ndarray:
        """``sigma2 R(x, X)`` (m x n)."""
        return self.variance * correlation(x, self.x, self.length_scales, self.kernel)

    def _mean(self, x: np.ndarray) -> np.ndarray:
        """The kriging mean alone at coded settings (m x k); from
        :data:`~rsm_lrg.model.engines.gp_kernels.COMPILED_PAIRS` pairs on, in one compiled pass
        that never stores the cross-correlations."""
        c = self.core
        if x.shape[0] * self.n < COMPILED_PAIRS:
            return self._mean_var(x, variance=False)[0]
        from ..engines.gp_compiled import mean

        out = mean(x, self.x, self.length_scales, self.kernel, c.alpha)
        fx, _ = trend_matrix(x, self.trend, self.space.letters)
        return fx @ c.beta + self.variance * out

    def _mean_var(self, x: np.ndarray, variance: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """Mean and kriging variance at coded settings, by chunks of :data:`PREDICT_CHUNK`
        points; with the variance (an O(n²) triangular solve per point, which releases the
        GIL) the chunks run on :func:`~rsm_lrg.model.engines.gp_compiled.threads` threads, each
        chunk's numbers computed by one thread as on one."""
        from ..engines.gp_compiled import run_split, threads

        m = x.shape[0]
        mean = np.empty(m)
        var = np.zeros(m)
        c = self.core

        def chunk(s: int, e: int) -> None:
            xs = x[s:e]
            r = self._cross(xs)
            fx, _ = trend_matrix(xs, self.trend, self.space.letters)
            mean[s:e] = fx @ c.beta + r @ c.alpha
            if not variance:
                return
            v = solve_triangular(c.chol, r.T, lower=True, check_finite=False)  # L^-1 r (n x m)
            u = fx.T - c.ft.T @ v
            w = solve_triangular(c.r_f, u, lower=False, trans="T", check_finite=False)
            var[s:e] = self.variance - np.sum(v * v, axis=0) + np.sum(w * w, axis=0)

        bounds = list(range(0, m, PREDICT_CHUNK)) + [m]
        count = threads(m * self.n) if variance and len(bounds) > 2 else 1
        run_split(chunk, bounds, count)
        return mean, np.maximum(var, 0.0)

    @property
    def transform(self) -> Transform:
        """The response transform: none (a GP is fitted to the response as measured)."""
        return Transform()

    @property
    def label(self) -> str:
        """The model in words: ``"Gaussian process (matern52 kernel, constant trend)"``."""
        return f"Gaussian process ({self.kernel} kernel, {self.trend} trend)"

    def kriging_form(self) -> dict:
        """The predictor as plain data, for a page's script to compute what :meth:`predict`
        does: at a coded setting ``x``, with ``f`` the trend row and ``r = variance *
        R(x, X)`` (``kernel``, ``length_scales`` [coded units], the coded runs ``x``),
        ``mean = f . beta + r . alpha``; ``v = L^-1 r``, ``w = r_f^-T (f - ft' v)``,
        ``var = variance - v . v + w . w`` (the kriging variance of the mean), and a new run
        adds ``nugget``. ``trend`` names the trend's columns (``p``: exponents per factor)."""
        from ..engines.gp_trend import trend_matrix

        k = len(self.space)
        eye = np.eye(k)
        _, names = trend_matrix(np.zeros((1, k)), self.trend, self.space.letters)
        powers = [[0] * k]
        if self.trend in ("linear", "quadratic"):
            powers += [list(map(int, eye[j])) for j in range(k)]
        if self.trend == "quadratic":
            powers += [list(map(int, eye[j] + eye[m])) for j in range(k) for m in range(j + 1, k)]
            powers += [list(map(int, 2 * eye[j])) for j in range(k)]
        c = self.core

        def mat(a: np.ndarray) -> list:
            return [[float(v) for v in row] for row in np.atleast_2d(a)]

        return {"kernel": self.kernel, "length_scales": [float(v) for v in self.length_scales],
                "variance": float(self.variance), "nugget": float(self.nugget), "x": mat(self.x),
                "trend": [{"name": n, "p": p} for n, p in zip(names, powers)],
                "beta": [float(v) for v in c.beta], "alpha": [float(v) for v in c.alpha],
                "L": mat(c.chol), "ft": mat(c.ft), "r_f": mat(c.r_f)}

    def predict_coded(self, coded: np.ndarray) -> np.ndarray:
        """The prediction contract's mean at coded settings (m x k): the kriging mean
        [response units]."""
        return self._mean(np.atleast_2d(np.asarray(coded, dtype=float)))

    def goal_on_model_scale(self, goal: Any) -> tuple[str, float | None, str, float | None]:
        """``(kind, target, kind, target)``: a GP models the response as measured (no
        transform), so the goal is the same on both scales."""
        from ..build.goals import parse_goal

        kind, target = parse_goal(goal)
        return kind, target, kind, target

    def predictive(self, coded: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The prediction contract's predictive distribution of a new run at coded settings
        (m x k): ``(mean, variance, df)`` — the kriging mean, its variance plus the nugget, and
        infinite df (normal) [response units, units², -]."""
        mean, var = self._mean_var(np.atleast_2d(np.asarray(coded, dtype=float)))
        return mean, var + self.nugget, np.full(mean.shape, np.inf)

    def mean_sd(self, coded_points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Predicted mean and kriging standard deviation at an (m, k) array of coded settings,
        as arrays (no checks, no DataFrame: the inner loop of an acquisition search)."""
        mean, var = self._mean_var(np.atleast_2d(np.asarray(coded_points, dtype=float)))
        return mean, np.sqrt(var)

    def predict(self, points: Any, interval: str | None = None, alpha: float = 0.05, *, coded: bool = False) -> Any:
        """Predicted response with the kriging standard deviation and, optionally, intervals.

        Parameters
        ----------
        points : DataFrame, mapping or array
            Settings in actual units: a frame (or ``{name: values}``) with the factor
            columns, or an (m, k) array in factor order. With ``coded=True`` the frame
            columns are the letters and the values coded.
        interval : {None, "confidence", "prediction", "both"}
            ``ci_low/ci_high`` for the mean surface, ``pi_low/pi_high`` for a new run (the
            nugget added).
        alpha : float
            1 - confidence level.

        Returns
        -------
        pandas.DataFrame
            ``predicted`` and ``se_fit`` (the kriging standard deviation of the mean)
            [response units] and the interval bounds (normal quantiles).
        """
        import pandas as pd
        from scipy.special import ndtri

        if interval not in (None, "confidence", "prediction", "both"):
            raise ValueError(f"interval must be None, 'confidence', 'prediction' or 'both', not {interval!r}")
        if isinstance(alpha, bool) or not isinstance(alpha, (int, float)) or not 0.0 < alpha < 1.0:
            raise ParameterError("alpha", f"alpha must lie between 0 and 1, not {alpha!r}")
        index = points.index if isinstance(points, pd.DataFrame) else None
        x = self.coded_points(points, coded)
        mean, var = self._mean_var(x)
        se = np.sqrt(var)
        out = pd.DataFrame({"predicted": mean, "se_fit": se}, index=index)
        z = float(ndtri(1.0 - alpha / 2.0))
        if interval in ("confidence", "both"):
            out["ci_low"] = mean - z * se
            out["ci_high"] = mean + z * se
        if interval in ("prediction", "both"):
            spi = np.sqrt(var + self.nugget)
            out["pi_low"] = mean - z * spi
            out["pi_high"] = mean + z * spi
        return out

    def gradient(self, points: Any, *, coded: bool = False) -> Any:
        """Gradient of the predicted mean with respect to the actual factors [response units
        per factor unit] (with ``coded=True``: per coded unit), one column per factor name.
        """
        import pandas as pd

        x = self.coded_points(points, coded)
        c = self.core
        r = self._cross(x)
        out = {}
        for j, f in enumerate(self.space.numeric):
            d = trend_gradient(x, self.trend, j) @ c.beta
            d = d + (r * log_derivative_x(x, self.x, self.length_scales, self.kernel, j)) @ c.alpha
            out[f.name] = d if coded else d / f.half_range
        return pd.DataFrame(out, index=points.index if isinstance(points, pd.DataFrame) else None)

    def covariance(self, points: Any, *, coded: bool = False) -> np.ndarray:
        """Posterior covariance (universal kriging) of the mean surface at the points (m x m)."""
        x = self.coded_points(points, coded)
        c = self.core
        r = self._cross(x)
        fx, _ = trend_matrix(x, self.trend, self.space.letters)
        v = solve_triangular(c.chol, r.T, lower=True, check_finite=False)
        u = fx.T - c.ft.T @ v
        w = solve_triangular(c.r_f, u, lower=False, trans="T", check_finite=False)
        k = self.variance * correlation(x, x, self.length_scales, self.kernel)
        return k - v.T @ v + w.T @ w

    def draws(self, points: Any, n: int = 1, *, seed: Any = None, coded: bool = False) -> np.ndarray:
        """``n`` draws of the mean surface at the points from the posterior (n x m) [response
        units]; a jitter of up to 1e-4 times the variance keeps the factorisation possible."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ParameterError("n", f"the number of draws must be a positive whole number, not {n!r}")
        rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
        x = self.coded_points(points, coded)
        mean, _ = self._mean_var(x)
        cov = self.covariance(x, coded=True)
        L, _ = cholesky_jitter(0.5 * (cov + cov.T), self.variance)
        return mean[None, :] + rng.standard_normal((int(n), x.shape[0])) @ L.T

    def with_runs(self, points: Any, values: Any, *, coded: bool = False) -> GPResult:
        """The same GP (hyper-parameters held) conditioned on extra runs as well: ``values``
        [response units] at ``points`` (as for :meth:`predict`). With the predicted means as
        values this is the Kriging Believer of a batch (Ginsbourger, Le Riche & Carraro 2010)."""
        from dataclasses import replace

        from ..engines.gp_core import kriging_core

        xn = self.coded_points(points, coded)
        yn = np.atleast_1d(np.asarray(values, dtype=float))
        if yn.shape != (xn.shape[0],) or not np.isfinite(yn).all():
            raise ValueError(f"with_runs needs one finite value per point ({xn.shape[0]}), got {yn.shape}")
        x = np.vstack([self.x, xn])
        y = np.r_[self.y, yn]
        F, _ = trend_matrix(x, self.trend, self.space.letters)
        core = kriging_core(x, y, F, self.kernel, self.length_scales, self.variance, self.nugget)
        return replace(self, x=x, y=y, core=core, estimated={k: False for k in self.estimated}, starts=0,
                       search={})

    # -- leave-one-out ---------------------------------------------------------------------
    @cached_property
    def loo(self) -> LeaveOneOut:
        """Closed-form leave-one-out (Dubrule 1983; see the module docstring)."""
        c = self.core
        minv = inverse_lower(c.chol)
        h = solve_triangular(c.chol, c.ft, lower=True, trans="T", check_finite=False)  # Sigma^-1 F
        g = solve_triangular(c.r_f, h.T, lower=False, trans="T", check_finite=False)  # r_f^-T F' Sigma^-1
        qdiag = np.diag(minv) - np.sum(g * g, axis=0)
        res = c.alpha / qdiag
        sd = 1.0 / np.sqrt(qdiag)
        ss = float(np.sum((self.y - self.y.mean()) ** 2))
        return LeaveOneOut(predicted=self.y - res, residuals=res, sd=sd, standardized=res / sd,
                           q2=1.0 - float(np.sum(res ** 2)) / ss if ss > 0 else float("nan"),
                           rmse=float(np.sqrt(np.mean(res ** 2))))

    # -- faces -----------------------------------------------------------------------------
    def to_dict(self) -> dict:
        """The fit JSON of INTERFACE.md for a GP: ``gp`` and ``loo`` beside the common keys."""
        names = self.space.names
        return {
            "response": self.response,
            "n": self.n,
            "model": "gp",
            "factors": self.space.to_list(),
            "gp": {
                "kernel": self.kernel,
                "dicekriging_covtype": DICEKRIGING_NAMES[self.kernel],
                "length_scales": {"coded": dict(zip(names, map(_f, self.length_scales))),
                                  "actual": dict(zip(names, map(_f, self.length_scales_actual)))},
                "variance": _f(self.variance),
                "nugget": _f(self.nugget),
                "trend": {"type": self.trend, "coefficients": dict(zip(self.trend_names, map(_f, self.beta)))},
                "log_likelihood": _f(self.log_likelihood),
                "estimated": dict(self.estimated),
                "starts": self.starts,
                "search": dict(self.search),
                "seed": self.seed,
                "jitter": _f(self.core.jitter),
                "condition_number": _f(self.condition_number),
            },
            "loo": self.loo.to_dict(),
            "notes": list(self.notes),
            "omitted_rows": list(self.omitted_rows),
        }

    def summary(self) -> str:
        """The text face: hyper-parameters, trend, likelihood, leave-one-out."""
        def how(key: str) -> str:
            return "estimated" if self.estimated.get(key) else "fixed"

        lines = [f"Gaussian process (kriging): {self.response}, {self.n} runs, {len(self.space)} factors",
                 f"Kernel: {self.kernel} (tensor product, one length-scale per factor, on the coded factors); "
                 f"trend: {self.trend} (GLS)", "",
                 f"Length-scales ({how('length_scales')}):",
                 f"  {'factor':<20} {'coded':>12} {'actual':>12}"]
        for f, t, ta in zip(self.space.factors, self.length_scales, self.length_scales_actual):
            lines.append(f"  {f.letter + ': ' + f.name:<20} {t:>12.5g} {ta:>12.5g}")
        lines += ["",
                  f"Process variance ({how('variance')}): {self.variance:.6g}   sd {np.sqrt(self.variance):.6g}",
                  f"Nugget ({how('nugget')}): {self.nugget:.6g}   sd {np.sqrt(self.nugget):.6g}",
                  f"Log-likelihood: {self.log_likelihood:.6f}"
                  + (f" (best of {self.starts} starts, seed {self.seed})" if self.starts else ""),
                  f"Condition number of the covariance matrix: {self.condition_number:.3g}"
                  + (f"; jitter {self.core.jitter:.0e} x variance added" if self.core.jitter else "; no jitter"),
                  "", "Trend coefficients (coded units):"]
        for nm, b in zip(self.trend_names, self.beta):
            lines.append(f"  {nm:<12} {b:>14.6g}")
        lo = self.loo
        lines += ["", f"Leave-one-out (closed form): Q2 {lo.q2:.4f}   RMSE {lo.rmse:.6g}   "
                      f"largest |standardized residual| {np.max(np.abs(lo.standardized)):.3g}"]
        if self.notes:
            lines += [""] + [f"Note: {s}" for s in self.notes]
        return "\n".join(lines) + "\n"
