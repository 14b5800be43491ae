"""The Gaussian-process (kriging) engine: :func:`fit_gp`, behind ``rsm_lrg.fit(..., model="gp")``.

The response is modelled as ``y(x) = f(x)' beta + Z(x) + e`` on the coded factors ``x``:
``f`` a trend (:mod:`rsm_lrg.model.engines.gp_trend`: constant, linear or quadratic, its
coefficients by generalised least squares), ``Z`` a zero-mean Gaussian process of variance
``sigma2`` whose correlation is an anisotropic tensor-product kernel with one length-scale
per factor (:mod:`rsm_lrg.model.engines.gp_kernels`, parameterised as R ``DiceKriging`` does), and
``e`` a white noise of variance ``tau2``, the nugget (Sacks, Welch, Mitchell & Wynn 1989;
Santner, Williams & Notz 2018; Roustant, Ginsbourger & Deville 2012).

Estimation (:func:`estimate`) maximises the likelihood, the trend coefficients profiled out
(GLS) and, when the nugget is zero or estimated and the variance is not given, the
variance too: ``sigma2 = z' A^-1 z / n`` with ``A = R + g I``, ``g = tau2 / sigma2``, and

    log L = -(n log(2 pi sigma2) + log det A + n) / 2,

DiceKriging's concentrated log-likelihood (``logLik``). The free parameters are the
log length-scales (and ``log g`` for an estimated nugget; ``log sigma2`` when a fixed nugget
keeps the variance from being concentrated out), optimised by L-BFGS-B with the analytic
gradient ``d log L / dp = (w' dA w / sigma2 - tr(A^-1 dA)) / 2``, ``w = A^-1 z``, from
several seeded starting points; the best optimum is kept. Above :data:`MULTISTART_RUNS` runs
the starting points are searched on a seeded random subsample of that many runs and the best
:data:`POLISHED` of those optima are then polished on every run (each evaluation on all runs
costs a Cholesky factorisation and an inverse, O(n³); the kernel and the gradient's trace sums
are compiled O(n² k) passes, :mod:`rsm_lrg.model.engines.gp_compiled`); the notes and the
JSON's ``gp.search`` say so. There, each start's search ends after an iteration that gains
less than :data:`SEARCH_GAIN` in log-likelihood and the polish after one that gains less than
:data:`POLISH_GAIN` (L-BFGS-B's relative ``ftol`` would otherwise spend O(n³) evaluations on
the likelihood's rounding noise); there each factorisation on all runs is made in place
(:func:`~rsm_lrg.model.engines.gp_core.cholesky_in_place`, no copy of the matrix); at most
:data:`MULTISTART_RUNS` runs nothing changes. Bounds: a length-scale between
1e-3 and 10 times the factor's coded range in the data (:data:`THETA_BOUNDS`;
``length_scale_bounds=`` gives others, e.g. :data:`LOOP_THETA_BOUNDS`, R ``km``'s upper bound,
which the loop uses); ``g`` between 1e-10 and 10. The
result keeps the Cholesky factor of the optimiser's last evaluation when that was at the
optimum (:meth:`ProfileLikelihood.factor_at`) instead of factorising again; with the variance
concentrated out, above :data:`MULTISTART_RUNS` runs the factor of ``sigma2 A`` is that of
``A`` scaled (:meth:`~rsm_lrg.model.engines.gp_core.KrigingCore.scaled`, O(n²)), below it is
factorised anew as before.

The nugget: ``nugget="estimate"`` for noisy data; a number fixes it [response units²];
``None`` (the default) estimates it when the data hold runs at the same setting (a
deterministic simulator cannot give two answers there) and otherwise fixes it at zero, so
that the model interpolates the runs. A Cholesky factorisation that fails adds a jitter
(:mod:`rsm_lrg.model.engines.gp_core`); the notes say so, and the result reports the condition
number of the correlation matrix.

>>> import numpy as np, pandas as pd
>>> rng = np.random.default_rng(1)
>>> df = pd.DataFrame({"a": rng.uniform(0, 1, 12), "b": rng.uniform(0, 1, 12)})
>>> df["y"] = np.sin(5 * df.a) + df.b ** 2
>>> r = fit_gp(df, "y", kernel="gauss", seed=3)
>>> bool(np.allclose(r.predict(df[["a", "b"]])["predicted"], df.y, atol=1e-6))
True
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.linalg import solve_triangular

from ...errors import ParameterError
from ..engines.gp_compiled import gradient_sums
from ..engines.gp_core import (
    KrigingCore,
    cholesky_in_place,
    cholesky_jitter,
    core_from_cholesky,
    gls,
    inverse_lower,
    kriging_core,
)
from ..engines.gp_kernels import COMPILED_PAIRS, KERNELS, correlation, log_derivative_theta
from ..engines.gp_trend import TRENDS, trend_matrix, trend_size
from ..results.gp_result import GPResult

__all__ = ["fit_gp", "refuse_options", "estimate", "check_length_scale_bounds", "ProfileLikelihood", "Estimate", "GP_STARTS", "THETA_BOUNDS",
           "LOOP_THETA_BOUNDS",
           "NUGGET_RATIO_BOUNDS", "MULTISTART_RUNS", "POLISHED", "POLISH_GAIN",
           "SEARCH_GAIN"]

#: Number of starting points of the likelihood's maximisation (the first at half the range).
GP_STARTS = 10
#: Length-scale bounds as multiples of the factor's coded range in the data (the default of
#: ``fit(..., length_scale_bounds=)``).
THETA_BOUNDS = (1e-3, 10.0)
#: The length-scale bounds of the GP that chooses runs (``rsm-lrg loop`` and ``rsm-lrg
#: suggest``): the upper one is R ``DiceKriging::km``'s default (``covParametersBounds``: 2 x
#: the design's range per factor, which ``DiceOptim::EGO.nsteps`` keeps at every refit). On the
#: few runs a loop starts from, the likelihood often rises on towards length-scales many times
#: the range, where the runs hardly tell one value from another, and the expected improvement
#: then trusts a surface flatter than the runs can show; on larger designs the wider
#: :data:`THETA_BOUNDS` predicted better (the borehole function on 60 runs: RMSE 2.0 against
#: 3.7 at 100 new points), so they stay ``fit``'s default. (km's lower bound is 1e-10 coded
#: units; 1e-3 x the range has not been reached on the checks.)
LOOP_THETA_BOUNDS = (1e-3, 2.0)
#: Above this many runs the starting points are searched on a random subsample of this size
#: and the best :data:`POLISHED` are then polished on every run (each likelihood evaluation
#: costs O(n³)).
MULTISTART_RUNS = 300
#: Optima of the subsample search polished on every run.
POLISHED = 1
#: The polish on every run ends after an iteration that raises the log-likelihood by less than
#: this. Was 1e-9: 1e-7 saves one evaluation on all runs (an O(n³) Cholesky factorisation and
#: inverse) for -1.6e-10 in log-likelihood on 2,000 runs of Hartmann-6, -8.5e-10 on 1,000
#: runs, -3.5e-10 on 800 noisy runs with the nugget estimated (L-BFGS-B converges
#: superlinearly there: the next iteration gains far less than this one).
POLISH_GAIN = 1e-7
#: The same rule for each start's search on the subsample, whose best optimum is polished
#: afterwards (307 evaluations on the subsample became 227 on 2,000 runs of Hartmann-6, the
#: polished likelihood unchanged).
SEARCH_GAIN = 1e-6
#: Bounds of the nugget-to-variance ratio ``g`` when the nugget is estimated.
NUGGET_RATIO_BOUNDS = (1e-10, 10.0)


@dataclass(frozen=True)
class Estimate:
    """Hyper-parameters at the maximum of the likelihood (or as given).

    Attributes
    ----------
    theta : (k,) ndarray
        Length-scales [coded units].
    variance : float
        Process variance ``sigma2`` [response units²].
    nugget : float
        ``tau2`` [response units²].
    core : KrigingCore
        The factorisation at these values.
    estimated : dict
        Which of ``length_scales``, ``variance``, ``nugget`` were estimated.
    starts : int
        Starting points used (0 when nothing was optimised).
    search : dict
        How the maximum was searched: ``subsample`` (runs the starting points were searched
        on; ``None``: all runs), ``polished`` (optima polished on all runs), and the
        likelihood evaluations on the subsample and on all runs.
    """

    theta: np.ndarray
    variance: float
    nugget: float
    core: KrigingCore
    estimated: dict = field(default_factory=dict)
    starts: int = 0
    search: dict = field(default_factory=dict)


class ProfileLikelihood:
    """Minus the profile log-likelihood and its gradient in the free parameters ``p``
    (calling it gives both; :meth:`unpack` maps ``p`` to the kernel's parameters).

    ``concentrated``: ``Sigma = sigma2 (R + g I)`` with ``sigma2`` profiled out; p = (log theta
    [free], log g [if estimated]). Otherwise ``Sigma = s R + t I``; p = (log theta [free],
    log s [if free], log t [if estimated])."""

    def __init__(self, x: np.ndarray, y: np.ndarray, F: np.ndarray, kernel: str, *, theta: np.ndarray | None,
                 concentrated: bool, scale: float | None, noise: float | str) -> None:
        self.x, self.y, self.F, self.kernel = x, y, F, kernel
        self.theta = theta
        self.concentrated = concentrated
        self.scale = scale  # sigma2 when fixed (not concentrated)
        self.noise = noise  # g or tau2 fixed, or "estimate"
        self.k = x.shape[1]
        self._last: tuple[np.ndarray, np.ndarray, float] | None = None

    def factor_at(self, p: np.ndarray) -> tuple[np.ndarray, float] | None:
        """The Cholesky factor of ``M`` and its relative jitter if the latest evaluation was at
        ``p`` (the optimiser's last point usually is), else None.

        Parameters
        ----------
        p : ndarray
            Free parameters.

        Returns
        -------
        tuple or None
            ``(chol, jitter)``, as :func:`~rsm_lrg.model.engines.gp_core.cholesky_jitter`
            returns them.
        """
        last = self._last
        if last is None or not np.array_equal(last[0], p):
            return None
        return last[1], last[2]

    def unpack(self, p: np.ndarray) -> tuple[np.ndarray, float, float]:
        """``(theta, a, b)`` of ``M = a R + b I``."""
        i = 0
        if self.theta is None:
            theta = np.exp(p[:self.k])
            i = self.k
        else:
            theta = self.theta
        if self.concentrated:
            a = 1.0
        elif self.scale is None:
            a = float(np.exp(p[i]))
            i += 1
        else:
            a = self.scale
        b = float(np.exp(p[i])) if self.noise == "estimate" else float(self.noise)
        return theta, a, b

    def __call__(self, p: np.ndarray) -> tuple[float, np.ndarray]:
        theta, a, b = self.unpack(p)
        x, n = self.x, self.y.size
        R = correlation(x, x, theta, self.kernel)
        m = a * R
        m[np.diag_indices_from(m)] += b
        self._last = None
        try:
            # above MULTISTART_RUNS runs (the polish on every run) factorised in place, no copy;
            # below, as before (the subsample's and small designs' numbers unchanged)
            factor = cholesky_in_place(m) if n > MULTISTART_RUNS else None
            if factor is not None:
                chol, jit = factor, 0.0
            else:
                if n > MULTISTART_RUNS:  # not positive definite: m was overwritten
                    m = a * R
                    m[np.diag_indices_from(m)] += b
                chol, jit = cholesky_jitter(m, a)
            beta, ft, r_f, z = gls(chol, self.F, self.y)
        except (np.linalg.LinAlgError, ValueError):
            return 1e300, np.zeros_like(p)
        self._last = (np.array(p, dtype=float), chol, jit)
        quad = float(z @ z)
        logdet = 2.0 * float(np.sum(np.log(np.diag(chol))))
        if self.concentrated:
            s2 = max(quad / n, 1e-300)
            ll = -0.5 * (n * np.log(2.0 * np.pi * s2) + logdet + n)
            kappa = 1.0 / s2
        else:
            ll = -0.5 * (n * np.log(2.0 * np.pi) + logdet + quad)
            kappa = 1.0
        w = solve_triangular(chol, z, lower=True, trans="T", check_finite=False)
        minv = inverse_lower(chol)  # M^-1, its lower triangle
        grad: list[float] = []
        if n * n >= COMPILED_PAIRS:  # one compiled pass over the pairs i > l (the diagonal's dR is 0)
            sums = np.empty(self.k)
            off = gradient_sums(x, theta, self.kernel, R, minv, w, kappa, sums)
            if self.theta is None:
                grad += list(a * sums)
            g_total = 2.0 * off + float(kappa * (w @ w) - np.trace(minv))  # sum(G), R's diagonal is 1
        else:
            minv = np.tril(minv) + np.tril(minv, -1).T
            G = (kappa * np.outer(w, w) - minv) * R  # so that dL/dp = sum(G * dM/dp elementwise(R-free)) / 2
            if self.theta is None:
                for j in range(self.k):
                    grad.append(0.5 * a * float(np.sum(G * log_derivative_theta(x, x, theta, self.kernel, j))))
            g_total = float(np.sum(G))
        if not self.concentrated and self.scale is None:
            grad.append(0.5 * a * g_total)
        if self.noise == "estimate":
            grad.append(0.5 * b * (kappa * float(w @ w) - float(np.trace(minv))))
        return -float(ll), -np.asarray(grad)


class _PolishStop:
    """L-BFGS-B callback that ends a search after an iteration that raised the log-likelihood
    by less than ``gain`` (used above :data:`MULTISTART_RUNS` runs only): the solver's own rule
    (a relative change below ``ftol``) sits below the rounding of a likelihood of thousands of
    runs, where the line search then spends its evaluations (O(n³) each on every run) on
    rounding noise."""

    def __init__(self, gain: float) -> None:
        self.gain = gain
        self.last: float | None = None

    def __call__(self, intermediate_result: Any) -> None:
        f = float(intermediate_result.fun)
        if self.last is not None and self.last - f < self.gain:
            raise StopIteration
        self.last = f


def _starts(rng: np.random.Generator, lo: np.ndarray, hi: np.ndarray, first: np.ndarray, n: int) -> np.ndarray:
    """``first`` and ``n - 1`` points of a Latin hypercube in the box ``[lo, hi]``."""
    out = [first]
    m = n - 1
    if m > 0:
        u = (np.argsort(rng.random((m, lo.size)), axis=0) + rng.random((m, lo.size))) / m
        out += list(lo + u * (hi - lo))
    return np.array(out)


def estimate(x: np.ndarray, y: np.ndarray, F: np.ndarray, kernel: str, *, length_scales: np.ndarray | None = None,
             variance: float | None = None, nugget: float | str = 0.0, seed: Any = 0,
             starts: int = GP_STARTS, length_scale_bounds: tuple[float, float] = THETA_BOUNDS) -> Estimate:
    """Maximum-likelihood hyper-parameters of a GP (see the module docstring); the ones given
    are held fixed.

    Parameters
    ----------
    x : (n, k) ndarray
        Coded settings.
    y : (n,) ndarray
        Responses.
    F : (n, p) ndarray
        Trend matrix.
    kernel : str
        One of :data:`~rsm_lrg.model.engines.gp_kernels.KERNELS`.
    length_scales : (k,) ndarray, optional
        Fixed length-scales [coded units].
    variance : float, optional
        Fixed process variance [response units²].
    nugget : float or "estimate"
        Fixed nugget [response units²] or ``"estimate"``.
    seed : int or numpy.random.Generator
        Seed of the starting points.
    starts : int
        Number of starting points.
    length_scale_bounds : (float, float)
        Bounds of the estimated length-scales, as multiples of each factor's coded range in
        ``x`` (default :data:`THETA_BOUNDS`).

    Returns
    -------
    Estimate
    """
    from scipy.optimize import minimize

    concentrated = variance is None and (nugget == "estimate" or nugget == 0.0)
    noise: float | str = nugget if not concentrated or nugget == "estimate" else 0.0
    lik = ProfileLikelihood(x, y, F, kernel, theta=length_scales, concentrated=concentrated, scale=variance,
                            noise=noise)
    span = np.ptp(x, axis=0)
    span = np.where(span > 0, span, 2.0)
    lo: list[float] = []
    hi: list[float] = []
    first: list[float] = []
    box_lo: list[float] = []
    box_hi: list[float] = []
    if length_scales is None:
        t_lo, t_hi = np.log(length_scale_bounds[0] * span), np.log(length_scale_bounds[1] * span)
        lo += list(t_lo)
        hi += list(t_hi)
        # the starts inside the bounds (given bounds may exclude the usual box)
        first += list(np.clip(np.log(0.5 * span), t_lo, t_hi))
        b_lo = np.clip(np.log(0.05 * span), t_lo, t_hi)
        b_hi = np.clip(np.log(2.0 * span), t_lo, t_hi)
        box_lo += list(b_lo)
        box_hi += list(np.maximum(b_hi, b_lo))
    vy = float(np.var(y)) if np.var(y) > 0 else 1.0
    if not concentrated and variance is None:
        lo.append(np.log(vy * 1e-6))
        hi.append(np.log(vy * 1e6))
        first.append(np.log(vy))
        box_lo.append(np.log(vy * 0.1))
        box_hi.append(np.log(vy * 10.0))
    if nugget == "estimate":
        base = 1.0 if concentrated else (variance if variance is not None else vy)
        lo.append(np.log(NUGGET_RATIO_BOUNDS[0] * base))
        hi.append(np.log(NUGGET_RATIO_BOUNDS[1] * base))
        first.append(np.log(1e-2 * base))
        box_lo.append(np.log(1e-4 * base))
        box_hi.append(np.log(0.5 * base))
    estimated = {"length_scales": length_scales is None, "variance": variance is None,
                 "nugget": nugget == "estimate"}
    used = 0
    info: dict[str, Any] = {}
    if lo:
        rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
        pts = _starts(rng, np.array(box_lo), np.array(box_hi), np.array(first), max(1, int(starts)))
        bounds = list(zip(lo, hi))
        opts = {"maxiter": 500, "ftol": 1e-14, "gtol": 1e-10}
        search = lik
        if y.size > MULTISTART_RUNS:  # the starts on a random subsample; the best polished on every run
            idx = np.sort(rng.choice(y.size, MULTISTART_RUNS, replace=False))
            search = ProfileLikelihood(x[idx], y[idx], F[idx], kernel, theta=length_scales, concentrated=concentrated,
                                       scale=variance, noise=noise)
        found = sorted((minimize(search, p0, jac=True, method="L-BFGS-B", bounds=bounds, options=opts,
                                 callback=None if search is lik else _PolishStop(SEARCH_GAIN)) for p0 in pts),
                       key=lambda r: r.fun)
        evals = {"subsample": sum(int(r.nfev) for r in found), "all": 0}
        if search is not lik:
            found = sorted((minimize(lik, r.x, jac=True, method="L-BFGS-B", bounds=bounds, options=opts,
                                     callback=_PolishStop(POLISH_GAIN)) for r in found[:POLISHED]),
                           key=lambda r: r.fun)
            evals["all"] = sum(int(r.nfev) for r in found)
        else:
            evals = {"subsample": 0, "all": evals["subsample"]}
        info = {"length_scale_bounds": [float(v) for v in length_scale_bounds] if length_scales is None else None,
                "subsample": MULTISTART_RUNS if search is not lik else None,
                "polished": POLISHED if search is not lik else 0,
                "evaluations_subsample": evals["subsample"], "evaluations_all": evals["all"]}
        used = len(pts)
        p = np.asarray(found[0].x, dtype=float)
    else:
        p = np.zeros(0)
    theta, a, b = lik.unpack(p)
    done = lik.factor_at(p)  # the optimiser's last evaluation: its factor, not a new one
    if concentrated:  # sigma2 = z' A^-1 z / n at the optimum
        core = core_from_cholesky(*done, F, y) if done else kriging_core(x, y, F, kernel, theta, 1.0, b)
        s2 = core.quad / y.size
        sigma2, tau2 = s2, b * s2
        # Sigma = sigma2 A: above MULTISTART_RUNS runs the factor scaled (O(n²)); below,
        # factorised anew as before (the same numbers as earlier versions)
        core = core.scaled(s2) if y.size > MULTISTART_RUNS else kriging_core(x, y, F, kernel, theta, sigma2, tau2)
    else:
        sigma2, tau2 = a, b
        core = core_from_cholesky(*done, F, y) if done else kriging_core(x, y, F, kernel, theta, sigma2, tau2)
    return Estimate(theta=np.asarray(theta, dtype=float), variance=float(sigma2), nugget=float(tau2), core=core,
                    estimated=estimated, starts=used, search=info)


def check_length_scale_bounds(value: Any) -> tuple[float, float]:
    """``length_scale_bounds`` checked (:func:`fit_gp`; ``--length-scale-bounds`` too).

    Parameters
    ----------
    value : pair of numbers
        ``(low, high)``, multiples of each factor's coded range in the data.

    Returns
    -------
    (float, float)
        ``(low, high)`` as floats: finite, ``0 < low < high``.

    Raises
    ------
    ParameterError
        Anything else (``parameter`` is ``"length_scale_bounds"``).
    """
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ParameterError("length_scale_bounds", "length_scale_bounds must be two numbers (low, high), multiples "
                                                    f"of each factor's coded range, not {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise ParameterError("length_scale_bounds", f"length_scale_bounds must satisfy 0 < low < high (finite), not "
                                                    f"({lo:g}, {hi:g})")
    return lo, hi


def _check_choice(name: str, value: Any, allowed: Sequence[str]) -> str:
    if not isinstance(value, str) or value.strip().lower() not in allowed:
        raise ParameterError(name, f"{name} must be one of {', '.join(allowed)}, not {value!r}")
    return value.strip().lower()


def _positive(name: str, value: Any, *, zero: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, f"{name} must be a number, not {value!r}") from None
    if isinstance(value, bool) or not np.isfinite(v) or v < 0 or (v == 0 and not zero):
        what = "a finite number >= 0" if zero else "a finite positive number"
        raise ParameterError(name, f"{name} must be {what}, not {value!r}")
    return v


def fit_gp(data: Any, response: str, factors: Any = None, *, kernel: str = "matern52", trend: str = "constant",
           nugget: Any = None, length_scales: Any = None, variance: Any = None, seed: Any = 0,
           starts: int = GP_STARTS, length_scale_bounds: Any = THETA_BOUNDS) -> GPResult:
    """Fit a Gaussian-process emulator (kriging) on the coded factors.

    Parameters
    ----------
    data : pandas.DataFrame
        One row per run.
    response : str
        Response column.
    factors : None, sequence or FactorSpace
        As for :func:`rsm_lrg.fit` (numeric factors only).
    kernel : {"matern52", "matern32", "gauss"}
        Correlation kernel (tensor product, one length-scale per factor).
    trend : {"constant", "linear", "quadratic"}
        Trend, by generalised least squares.
    nugget : None, "estimate" or float
        ``None``: estimated when runs share a setting, else 0 (interpolation); ``"estimate"``;
        or a fixed value [response units²].
    length_scales : sequence of float, optional
        Fixed length-scales, one per factor [coded units].
    variance : float, optional
        Fixed process variance [response units²].
    seed : int or numpy.random.Generator
        Seed of the likelihood's starting points (the same seed gives the same fit).
    starts : int
        Number of starting points (default :data:`GP_STARTS`).
    length_scale_bounds : (float, float)
        Bounds of the estimated length-scales as multiples of each factor's coded range in the
        data, ``0 < low < high`` (default :data:`THETA_BOUNDS`, 1e-3 and 10;
        :data:`LOOP_THETA_BOUNDS`, 1e-3 and 2, has R ``km``'s default upper bound). Unused when
        ``length_scales`` are given.

    Returns
    -------
    GPResult

    Raises
    ------
    ParameterError
        A bad kernel, trend, nugget, length-scale, length-scale bounds or variance
        (``parameter`` names it);
        categoric factors (``"factors"``); too few runs for the trend (``"trend"``).
    ValueError
        Data errors as for :func:`rsm_lrg.fit`.
    """
    from ...factors import MixtureComponent
    from ..build.inputs import model_inputs

    kernel = _check_choice("kernel", kernel, KERNELS)
    trend = _check_choice("trend", trend, TRENDS)
    if isinstance(starts, bool) or not isinstance(starts, (int, np.integer)) or starts < 1:
        raise ParameterError("starts", f"starts must be a positive whole number, not {starts!r}")
    if nugget is not None and not (isinstance(nugget, str) and nugget.strip().lower() == "estimate"):
        nugget = _positive("nugget", nugget, zero=True)
    elif isinstance(nugget, str):
        nugget = "estimate"
    var = None if variance is None else _positive("variance", variance)
    bounds = check_length_scale_bounds(length_scale_bounds)
    inp = model_inputs(data, response, factors)
    space = inp.space
    if space.has_categoric:
        name = next(iter(space.categoric))
        raise ParameterError("factors", f"factor {name!r} is categoric; a Gaussian process in rsm-lrg takes numeric "
                                        "factors only (fit one GP per level, or a polynomial model)")
    if any(isinstance(f, MixtureComponent) for f in space.factors):
        raise ParameterError("model", "a Gaussian process for mixtures is not available yet")
    x, y = inp.x, inp.y
    n, k = x.shape
    spread = float(np.ptp(y)) if y.size else 0.0
    for name, given in (("nugget", nugget), ("variance", var)):
        # a noise or process variance beyond 1e6 times the response's squared range says every
        # run is noise and leaves the likelihood flat (length-scales at their starts): refused
        if isinstance(given, float) and spread > 0 and given > 1e6 * spread ** 2:
            raise ParameterError(name, f"{name} {given:g} is more than 1e6 times the squared range of the response "
                                       f"({spread:g}², response units²): every run would be noise")
    theta = None
    if length_scales is not None:
        vals = np.atleast_1d(np.asarray(length_scales, dtype=object))
        if vals.ndim != 1 or vals.size != k:
            raise ParameterError("length_scales", f"length_scales needs {k} values (one per factor), "
                                                  f"got {vals.size}")
        theta = np.array([_positive("length_scales", v) for v in vals])
    p = trend_size(k, trend)
    if n < p + 1:
        raise ParameterError("trend", f"a {trend} trend in {k} factor{'s' if k != 1 else ''} has {p} coefficients "
                                      f"and needs at least {p + 1} runs; the data hold {n}")
    notes = list(inp.prep.notes)
    _, first, counts = np.unique(inp.settings, axis=0, return_index=True, return_counts=True)
    replicated = int(np.sum(counts > 1))
    if nugget is None:
        nugget = "estimate" if replicated else 0.0
        notes.append(f"nugget estimated: {replicated} setting(s) hold more than one run (noise)" if replicated else
                     "nugget fixed at 0 (no two runs share a setting: the model interpolates the runs, as for a "
                     "deterministic simulator); give nugget='estimate' (--nugget estimate) for noisy data")
    elif nugget == 0.0 and replicated:
        raise ParameterError("nugget", f"a nugget of 0 interpolates the runs, but {replicated} setting(s) hold more "
                                       "than one run; estimate the nugget (--nugget estimate) or give a value")
    F, names = trend_matrix(x, trend, space.letters)
    try:
        est = estimate(x, y, F, kernel, length_scales=theta, variance=var, nugget=nugget, seed=seed, starts=starts,
                       length_scale_bounds=bounds)
    except ValueError as exc:
        raise ParameterError("trend", str(exc)) from None
    if est.starts and n > MULTISTART_RUNS:
        best = "the best" if POLISHED == 1 else f"the best {POLISHED}"
        notes.append(f"the likelihood's {est.starts} starting points were searched on a random subsample of "
                     f"{MULTISTART_RUNS} runs and {best} polished on all {n}")
    if est.core.jitter:
        notes.append(f"the covariance matrix was singular to working precision: a jitter of {est.core.jitter:.0e} "
                     "times the process variance was added to its diagonal")
    return GPResult(response=response, space=space, kernel=kernel, trend=trend, x=x, y=y, trend_names=names,
                    length_scales=est.theta, variance=est.variance, nugget=est.nugget, core=est.core,
                    estimated=est.estimated, starts=est.starts, search=est.search, seed=seed if isinstance(seed, int) else None,
                    notes=tuple(notes), omitted_rows=tuple(inp.prep.omitted_rows))


def refuse_options(*, block: Any, terms: Any, intercept: bool, transform: Any, reduce: Any, components: Any,
                   whole_plot: Any, random_block: Any, dask: bool, random_effects: Any = None) -> None:
    """ParameterError naming the first option of :func:`rsm_lrg.fit` that a Gaussian process
    does not take (blocks, terms, transforms, reduction, mixtures, random effects, Dask)."""
    given = [("block", block is not None, "blocks"), ("terms", terms is not None, "a list of terms"),
             ("intercept", not intercept, "a model without an intercept"),
             ("transform", transform is not None, "a response transform"),
             ("reduce", reduce not in (None, False), "backward elimination"),
             ("components", components is not None, "mixture components"),
             ("whole_plot", whole_plot is not None, "a whole-plot random effect"),
             ("random_block", random_block is not None, "a random block effect"),
             ("random_effects", random_effects is not None, "random effects"),
             ("data", dask, "a Dask DataFrame (several files)")]
    for name, on, what in given:
        if on:
            raise ParameterError(name, f"a Gaussian process (model 'gp') does not take {what}")
