"""Fit statistics as Design-Expert reports them under the ANOVA.

R² and adjusted R² leave block variation out (Design-Expert's convention): with
``SS_adj = SS_total - SS_block``,

    R² = 1 - SS_res / SS_adj,      adj R² = 1 - (SS_res / df_res) / (SS_adj / (df_model + df_res)),
    PRESS = sum (e_i / (1 - h_ii))²,  pred R² = 1 - PRESS / SS_adj,

adequate precision = (max ŷ - min ŷ) / sqrt(mean V(ŷ)) over the design points with
mean V(ŷ) = p σ² / n (p model parameters, σ² the residual mean square), and
C.V. % = 100 · std dev / mean.

The t and F tails of the tests (:func:`stdtr`, :func:`stdtrit`, :func:`fdtrc`, :func:`fdtr`,
with ``scipy.special``'s names and arguments) are computed here from the regularised incomplete
beta function :func:`betainc`, so that a fit does not import SciPy (a fifth of a second of
start-up); they agree with ``scipy.special`` to 1e-12 relative (tests/model/engines/test_least_squares_tails.py).
The modules of a fit import them by name (``from .statistics import stdtrit``); the name
``special`` is kept for ``scipy.special`` itself.
"""

from __future__ import annotations

import functools
import math
from dataclasses import asdict, dataclass

import numpy as np

__all__ = ["FitStatistics", "fit_statistics", "betainc", "stdtr", "stdtrit", "fdtr", "fdtrc"]


@dataclass(frozen=True)
class FitStatistics:
    """Summary statistics of a fit (all floats; NaN where undefined, ``null`` in JSON).

    Attributes
    ----------
    r2, adj_r2, pred_r2 : float
        R², adjusted R², predicted R² (from PRESS) [-].
    press : float
        Prediction error sum of squares [response units²].
    adeq_precision : float
        Signal-to-noise ratio; above 4 is desirable (Design-Expert) [-].
    std_dev : float
        √(residual mean square) [response units].
    mean : float
        Mean response [response units].
    cv_percent : float
        Coefficient of variation, 100 · std_dev / mean [%].
    """

    r2: float
    adj_r2: float
    pred_r2: float
    press: float
    adeq_precision: float
    std_dev: float
    mean: float
    cv_percent: float

    def to_dict(self) -> dict:
        """``{"r2", "adj_r2", "pred_r2", "press", "adeq_precision", "std_dev", "mean", "cv_percent"}``.

        Returns
        -------
        dict
            Plain JSON-safe data (numbers, strings, lists and dicts).
        """
        return asdict(self)

    def __getitem__(self, key: str) -> float:  # dict-style access, stats["r2"]
        return getattr(self, key)

    def keys(self):
        """The statistics' names, as :meth:`to_dict` has them.

        Returns
        -------
        KeysView
            ``r2``, ``adj_r2``, ``pred_r2``, ...
        """
        return self.to_dict().keys()

    # -- faces: read like the CLI's block under the ANOVA ----------------------------------
    _LABELS = (("std_dev", "Std. Dev."), ("mean", "Mean"), ("cv_percent", "C.V. %"), ("press", "PRESS"),
               ("r2", "R²"), ("adj_r2", "Adjusted R²"), ("pred_r2", "Predicted R²"),
               ("adeq_precision", "Adeq Precision"))

    def _cells(self) -> list[tuple[str, str]]:
        from ...present import format_number

        return [(label, format_number(getattr(self, key), 4, missing="n/a")) for key, label in self._LABELS]

    def __str__(self) -> str:
        """Two columns, as the CLI prints the fit statistics (4 significant figures).

        >>> print(FitStatistics(0.96812, 0.93093, 0.81842, 2.079e-4, 18.4626, 1.744e-3, 0.035037, 4.9777))
        Std. Dev.  0.001744   R²              0.9681
        Mean       0.03504    Adjusted R²     0.9309
        C.V. %     4.978      Predicted R²    0.8184
        PRESS      0.0002079  Adeq Precision  18.46
        """
        cells = self._cells()
        left, right = cells[:4], cells[4:]
        wl = max(len(a) for a, _ in left)
        wv = max(len(b) for _, b in left)
        wr = max(len(a) for a, _ in right)
        return "\n".join(f"{a:<{wl}}  {b:<{wv}}  {c:<{wr}}  {d}" for (a, b), (c, d) in zip(left, right))

    def __repr__(self) -> str:
        return "FitStatistics(\n  " + "\n  ".join(str(self).splitlines()) + "\n)"

    def _repr_html_(self) -> str:
        from html import escape

        cells = self._cells()
        rows = "".join(f"<tr><th style='text-align:left'>{escape(a)}</th><td style='text-align:right'>{escape(b)}</td>"
                       f"<th style='text-align:left'>{escape(c)}</th><td style='text-align:right'>{escape(d)}</td></tr>"
                       for (a, b), (c, d) in zip(cells[:4], cells[4:]))
        return f"<table class='rsm-lrg-statistics'><caption>Fit statistics</caption>{rows}</table>"


def _nan_div(a, b):
    return a / b if b not in (0, 0.0) and math.isfinite(b) else math.nan


def fit_statistics(*, n, mean, fitted_range, ss_res, df_res, ss_total, ss_block, df_model, n_params,
                   press) -> FitStatistics:
    """Compute :class:`FitStatistics` from the numbers of one fit (see the module docstring).

    ``press`` and the sums of squares come from the regression core
    (:class:`~rsm_lrg.model.engines.least_squares.Regression`); ``fitted_range`` is
    ``max ŷ - min ŷ`` (NaN when not known: no adequate precision).
    """
    ss_adj = ss_total - ss_block
    ms_res = _nan_div(ss_res, df_res)
    r2 = 1.0 - _nan_div(ss_res, ss_adj) if ss_adj > 0 else math.nan
    adj = 1.0 - _nan_div(ms_res, _nan_div(ss_adj, df_model + df_res)) if ss_adj > 0 and df_res > 0 else math.nan
    pred = 1.0 - press / ss_adj if (math.isfinite(press) and ss_adj > 0) else math.nan
    std = math.sqrt(ms_res) if math.isfinite(ms_res) else math.nan
    mean_var = n_params * ms_res / n if math.isfinite(ms_res) else math.nan
    adeq = fitted_range / math.sqrt(mean_var) if (math.isfinite(mean_var) and mean_var > 0) else math.nan
    mean = float(mean)
    cv = 100.0 * std / abs(mean) if mean != 0 and math.isfinite(std) else math.nan
    return FitStatistics(r2=float(r2), adj_r2=float(adj), pred_r2=float(pred), press=float(press),
                         adeq_precision=float(adeq), std_dev=float(std), mean=mean, cv_percent=float(cv))


# ----------------------------------------------------------------------------------------
# t and F tails: the regularised incomplete beta function
# ----------------------------------------------------------------------------------------
_HALF_LOG_2PI = 0.5 * math.log(2.0 * math.pi)
_EPS = 1e-16
_TINY = 1e-300


def _lgamma_correction(z: float) -> float:
    """``delta(z) = ln Gamma(z) - [(z - 1/2) ln z - z + ln(2 pi)/2]`` (Stirling's remainder),
    from its asymptotic series for z >= 10 (error below 1e-17) and from ``math.lgamma`` below."""
    if z >= 10.0:
        r = 1.0 / (z * z)
        return (1.0 / 12 - r * (1.0 / 360 - r * (1.0 / 1260 - r * (1.0 / 1680 - r * (1.0 / 1188 - r * (
            691.0 / 360360 - r / 156.0)))))) / z
    return math.lgamma(z) - ((z - 0.5) * math.log(z) - z + _HALF_LOG_2PI)


def _log_ratio(x: float, y: float, a: float, b: float) -> float:
    """``ln(x (a + b) / a)`` to full precision: by ``log1p`` of ``(x b - y a) / a`` near 1
    (where ``x`` alone would cancel), by ``ln x + log1p(b / a)`` away from it."""
    t = (x * b - y * a) / a
    return math.log1p(t) if abs(t) < 0.5 else math.log(x) + math.log1p(b / a)


def _ibeta_prefix(a: float, b: float, x: float, y: float) -> float:
    """``x^a y^b / B(a, b)`` (``y = 1 - x`` given separately, for its digits) without the
    cancellation of ``ln Gamma`` differences when a or b is large (Stirling form, as DiDonato
    & Morris, ACM TOMS 18 (1992) 360, and Boost's ``ibeta_power_terms`` arrange it)."""
    c = a + b
    la = a * _log_ratio(x, y, a, b)  # a ln(x c / a)
    lb = b * _log_ratio(y, x, b, a)  # b ln(y c / b)
    lg = 0.5 * math.log(a / c * b) - _HALF_LOG_2PI - _lgamma_correction(a) - _lgamma_correction(b) \
        + _lgamma_correction(c)
    return math.exp(la + lb + lg)


def _ibeta_fraction(a: float, b: float, x: float, y: float) -> float:
    """The continued fraction ``F`` with ``I_x(a, b) = x^a y^b / (B(a, b) F)``, written with
    ``y = 1 - x`` where ``1 - x`` would cancel (Boost's ``ibeta_fraction2``, after DiDonato &
    Morris), evaluated by the modified Lentz method."""
    f = a * (a * y - b * x + 1.0) / (a + 1.0)
    f = f if f != 0.0 else _TINY
    c, d = f, 0.0
    for m in range(1, 1_000_000):
        den = a + 2 * m - 1
        an = (m * (a + m - 1) / den) * ((a + b + m - 1) / den) * (b - m) * x * x
        bn = m + (m * (b - m) * x) / den + ((a + m) * (a * y - b * x + 1.0 + m * (2.0 - x))) / (a + 2 * m + 1)
        d = bn + an * d
        d = 1.0 / (d if d != 0.0 else _TINY)
        c = bn + an / c
        c = c if c != 0.0 else _TINY
        step = c * d
        f *= step
        if abs(step - 1.0) <= _EPS:
            return f
    raise ArithmeticError(f"the incomplete beta continued fraction did not converge (a={a}, b={b}, x={x})")


def _ibeta_tails(a: float, b: float, x: float, y: float) -> tuple[float, float]:
    """``(I_x(a, b), 1 - I_x(a, b))``, the smaller of the two to full relative precision."""
    if x <= 0.0:
        return 0.0, 1.0
    if y <= 0.0:
        return 1.0, 0.0
    if (a + b) * x < a:  # left of the mean a / (a + b): the fraction for the lower tail converges
        lower = _ibeta_prefix(a, b, x, y) / _ibeta_fraction(a, b, x, y)
        return lower, 1.0 - lower
    upper = _ibeta_prefix(b, a, y, x) / _ibeta_fraction(b, a, y, x)
    return 1.0 - upper, upper


def _elementwise(f):
    """``f`` on floats, applied elementwise (NumPy broadcasting); a NumPy float for scalars."""
    nargs = f.__code__.co_argcount
    uf = np.frompyfunc(f, nargs, 1)

    def g(*args):
        if len(args) == nargs and all(type(a) is float or type(a) is int or type(a) is np.float64 for a in args):
            return np.float64(f(*(float(a) for a in args)))  # one value: what the ufunc gives it, without the arrays
        with np.errstate(all="ignore"):  # the scalar code handles infinities itself
            out = np.asarray(uf(*(np.asarray(a, dtype=float) for a in args)), dtype=float)
        return out[()] if out.ndim == 0 else out

    g.__name__, g.__qualname__, g.__doc__ = f.__name__.lstrip("_"), f.__qualname__.lstrip("_"), f.__doc__
    return g


def _betainc(a: float, b: float, x: float) -> float:
    """Regularised incomplete beta function ``I_x(a, b)`` [-] (``scipy.special.betainc``)."""
    if not (a > 0 and b > 0 and 0.0 <= x <= 1.0):
        return math.nan
    return _ibeta_tails(a, b, x, 1.0 - x)[0]


def _t_lower(df: float, t: float) -> float:
    """``P(T <= -|t|)`` of Student's t with ``df`` degrees of freedom, to full relative precision."""
    t = abs(t)
    if math.isinf(df):
        return 0.5 * math.erfc(t / math.sqrt(2.0))
    if math.isinf(t):
        return 0.0
    s = t / math.sqrt(df)
    if s > 1e100:  # x = 1 / (1 + s^2) < 1e-200 may underflow: I_x(a, 1/2) = x^a / (a B(a, 1/2)) (1 + O(x))
        a = 0.5 * df
        return 0.5 * math.exp(-2.0 * a * math.log(s) + math.lgamma(a + 0.5) - math.lgamma(a) - math.lgamma(0.5)) / a
    x, y = _t_xy(df, t)
    return 0.5 * _ibeta_tails(0.5 * df, 0.5, x, y)[0]


def _t_xy(df: float, t: float) -> tuple[float, float]:
    """``(df / (df + t^2), t^2 / (df + t^2))`` without overflow for ``t`` up to 1.8e308."""
    s = t / math.sqrt(df)
    if s > 1.0:
        u = 1.0 / (s * s)
        return u / (1.0 + u), 1.0 / (1.0 + u)
    ss = s * s
    return 1.0 / (1.0 + ss), ss / (1.0 + ss)


def _stdtr(df: float, t: float) -> float:
    """Student's t distribution function ``P(T <= t)`` with ``df`` degrees of freedom [-]
    (``scipy.special.stdtr``)."""
    if not df > 0 or math.isnan(t):
        return math.nan
    lo = _t_lower(df, t)
    return lo if t <= 0 else 1.0 - lo


def _t_density(df: float, t: float) -> float:
    if math.isinf(df):
        return math.exp(-0.5 * t * t) / math.sqrt(2.0 * math.pi)
    a = 0.5 * df
    # ln[Gamma(a + 1/2) / (Gamma(a) sqrt(pi df))] in Stirling form
    lnorm = a * math.log1p(0.5 / a) - 0.5 - _HALF_LOG_2PI + _lgamma_correction(a + 0.5) - _lgamma_correction(a)
    s = abs(t) / math.sqrt(df)
    l1p = 2.0 * math.log(s) + math.log1p(1.0 / (s * s)) if s > 1.0 else math.log1p(s * s)  # ln(1 + t^2/df)
    return math.exp(lnorm - 0.5 * (df + 1.0) * l1p)


def _stdtrit(df: float, p: float) -> float:
    """The ``p`` quantile of Student's t with ``df`` degrees of freedom
    (``scipy.special.stdtrit``): ``stdtr(df, t) = p``; remembered for the last 1,024
    ``(df, p)`` pairs (every coefficient of a fit asks for the same quantile)."""
    return _stdtrit_solved(float(df), float(p))


@functools.lru_cache(maxsize=1024)
def _stdtrit_solved(df: float, p: float) -> float:
    """:func:`_stdtrit`'s root search (pure: a function of the two floats only)."""
    if not (df > 0 and 0.0 <= p <= 1.0):
        return math.nan
    if p == 0.0:
        return -math.inf
    if p == 1.0:
        return math.inf
    if p == 0.5:
        return 0.0
    q = p if p < 0.5 else 1.0 - p  # exact for p >= 1/2
    sign = -1.0 if p < 0.5 else 1.0
    lq = math.log(q)
    # bracket [lo, hi] on |t| with P(T <= -|t|) falling from 1/2 to 0; Newton on ln P, kept in the bracket
    lo, hi = 0.0, 1.0
    while _t_lower(df, hi) > q:
        lo, hi = hi, hi * 4.0
        if math.isinf(hi):
            return sign * math.inf
    t = 0.5 * (lo + hi)
    for _ in range(200):
        lower = _t_lower(df, t)
        if lower == 0.0:
            hi = t
            t = 0.5 * (lo + hi)
            continue
        g = math.log(lower) - lq
        if g > 0:
            lo = t
        else:
            hi = t
        dens = _t_density(df, t)
        t_new = t + g * lower / dens if dens > 0 else 0.5 * (lo + hi)  # d ln P / dt = -dens / P
        if not lo < t_new < hi:
            t_new = 0.5 * (lo + hi)
        if abs(t_new - t) <= 4e-16 * t or hi - lo <= 4e-16 * hi:
            t = t_new
            break
        t = t_new
    return sign * t


def _f_tails(dfn: float, dfd: float, f: float) -> tuple[float, float]:
    """``(P(F > f), P(F <= f))`` for the F distribution with ``dfn`` and ``dfd`` degrees of
    freedom [-], from the incomplete beta function at ``dfd / (dfd + dfn f)``."""
    if not (dfn > 0 and dfd > 0) or math.isnan(f) or f < 0:
        return math.nan, math.nan
    if math.isinf(f):
        return 0.0, 1.0
    u = dfn * f
    return _ibeta_tails(0.5 * dfd, 0.5 * dfn, dfd / (dfd + u), u / (dfd + u))


def _fdtrc(dfn: float, dfd: float, f: float) -> float:
    """Upper tail ``P(F > f)`` of the F distribution with ``dfn`` and ``dfd`` degrees of
    freedom [-] (``scipy.special.fdtrc``; the p-value of an F test)."""
    return _f_tails(dfn, dfd, f)[0]


def _fdtr(dfn: float, dfd: float, f: float) -> float:
    """Distribution function ``P(F <= f)`` of the F distribution [-] (``scipy.special.fdtr``)."""
    return _f_tails(dfn, dfd, f)[1]


betainc = _elementwise(_betainc)
stdtr = _elementwise(_stdtr)
stdtrit = _elementwise(_stdtrit)
fdtrc = _elementwise(_fdtrc)
fdtr = _elementwise(_fdtr)
