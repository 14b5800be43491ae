"""Regression diagnostics per run and the Box–Cox plot (Design-Expert "Diagnostics").

Per run, from the one factorisation of :func:`rsm_lrg.fit` (hat diagonal ``h_ii``,
residuals ``e_i``, residual mean square ``σ²`` on ``ν = n - p`` df):

* internally studentized residual ``r_i = e_i / (σ √(1 - h_ii))``;
* externally studentized residual ``t_i = r_i √((ν - 1) / (ν - r_i²))``;
* leverage ``h_ii``; Cook's distance ``D_i = r_i² h_ii / (p (1 - h_ii))``;
* DFFITS ``t_i √(h_ii / (1 - h_ii))``.

Flags ("beyond the usual limits"), all documented in the result:

* |t_i| above the Bonferroni outlier limit ``t(1 - α/(2n), ν - 1)`` (α = 0.05; the
  outlier-t limit Design-Expert draws);
* leverage above ``2p/n`` (twice the average leverage; Belsley, Kuh & Welsch 1980);
* Cook's D above ``F(0.5; p, ν)``, the median of F (Cook & Weisberg 1982; Montgomery,
  *Design and Analysis of Experiments*, Sec. 10.7 — close to 1);
* |DFFITS| above ``2 √(p/n)`` (Belsley, Kuh & Welsch 1980).

Box–Cox (Box & Cox 1964; Montgomery, *DAE*, Sec. 15.1.1): for each λ the model is refitted
to ``y^(λ) = (y^λ - 1) / (λ ẏ^(λ-1))`` (``ẏ ln y`` at λ = 0; ẏ the geometric mean), which
makes the residual sums of squares ``SS(λ)`` comparable across λ; ``-n/2 ln SS(λ)`` is the
profile log-likelihood of λ. Two rules are offered (``rule=``):

* ``"likelihood"`` (default; the exact answer): λ̂ is the maximum-likelihood estimate (the
  minimum of ``SS(λ)``, located to 1e-8 by a bounded search around the best point of a
  0.01 grid on [-3, 3]); the 100(1-α) % interval is the likelihood-ratio interval
  ``n ln(SS(λ)/SS(λ̂)) <= χ²(1-α; 1)`` (Box & Cox 1964, Sec. 4; the interval R's
  ``MASS::boxcox`` draws).
* ``"design-expert"``: Design-Expert's Box–Cox plot (Stat-Ease, "Box-Cox Plot",
  https://www.statease.com/docs/latest/contents/analysis/box-cox-plot/): ``ln(SS(λ))`` on the
  grid λ = -3, -2.99, ..., 3 (the plot's ±3 limits); the "best" λ is the grid point with the
  smallest ``SS``; the interval is where ``ln SS(λ) <= ln SS_min + t²(α/2, ν)/ν`` (ν the
  residual df; the page names the 95 % interval but prints no formula: this t-based form is
  the one Montgomery, *DAE*, Sec. 15.1.1 uses with Design-Expert output, there written
  ``SS* = SS_min (1 + t²/ν)`` whose logarithm is ``ln SS_min + t²/ν`` to first order); ends
  beyond ±3 are not shown.

Both rules recommend as Stat-Ease's page says: the standard λ (1 none, 0.5 square root, 0
natural log, -0.5 inverse square root, -1 inverse) closest to the best λ inside the interval,
else the power at the best λ itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import ParameterError

__all__ = ["diagnostics", "Diagnostics", "box_cox", "box_cox_ss", "box_cox_response", "BoxCox", "STANDARD_LAMBDAS", "BOX_COX_RULES"]

#: Standard power transforms, λ -> name (Stat-Ease's list).
STANDARD_LAMBDAS = {1.0: "none", 0.5: "sqrt", 0.0: "log", -0.5: "inverse sqrt", -1.0: "inverse"}

_ORDER_COLUMNS = ("run_order", "run order", "order", "run")


def _run_order(data) -> np.ndarray:
    import pandas as pd

    lower = {str(c).lower(): c for c in data.columns}
    for key in _ORDER_COLUMNS:
        if key in lower:
            v = pd.to_numeric(data[lower[key]], errors="coerce")
            if not v.isna().any():
                return v.to_numpy(dtype=float)
    return np.arange(1, len(data) + 1, dtype=float)


@dataclass(frozen=True)
class BoxCox:
    """Box–Cox profile of a fit (frozen).

    Attributes
    ----------
    lambdas : ndarray
        Grid of λ [-].
    ss : ndarray
        Scaled residual sum of squares ``SS(λ)`` [response units²].
    lambda_best : float
        λ̂ minimising ``SS(λ)``.
    ci : tuple of float
        (low, high) of the approximate interval for λ (NaN where it leaves [-3, 3]).
    confidence : float
    current : float
        λ of the response as fitted (1: untransformed).
    recommended : str
        ``"none"``, ``"sqrt"``, ``"log"``, ``"inverse sqrt"``, ``"inverse"`` or
        ``"power=λ̂"``.
    recommended_lambda : float
    ratio : float
        max(y) / min(y); a ratio above 10 usually calls for a transform (Stat-Ease) [-].
    rule : {"likelihood", "design-expert"}
        How λ̂ and the interval were found (see the module docstring).
    """

    lambdas: np.ndarray = field(repr=False)
    ss: np.ndarray = field(repr=False)
    lambda_best: float = math.nan
    ci: tuple = (math.nan, math.nan)
    confidence: float = 0.95
    current: float = 1.0
    recommended: str = "none"
    recommended_lambda: float = 1.0
    ratio: float = math.nan
    rule: str = "likelihood"

    @property
    def rule_text(self) -> str:
        """One line saying how λ and its interval were found."""
        pc = f"{100 * self.confidence:g} %"
        if self.rule == "design-expert":
            return (f"λ by Design-Expert's rule (grid -3..3 step 0.01, minimum of ln SS), {pc} CI where "
                    f"ln SS <= ln SS_min + t²/df")
        return f"λ by maximum likelihood (profile log-likelihood), {pc} CI from χ²₁ (likelihood ratio)"

    def to_dict(self) -> dict:
        f = lambda v: float(v) if math.isfinite(v) else None  # noqa: E731
        return {"lambda": f(self.lambda_best), "ci": [f(self.ci[0]), f(self.ci[1])],
                "confidence": self.confidence, "current": self.current, "recommended": self.recommended,
                "recommended_lambda": f(self.recommended_lambda), "ratio_max_min": f(self.ratio),
                "rule": self.rule, "rule_text": self.rule_text}


def box_cox_ss(X, y, lambdas, *, fit=None) -> np.ndarray:
    """Residual SS of the model matrix ``X`` fitted to the scaled Box–Cox response
    ``(y^λ - 1) / (λ ẏ^(λ-1))`` (``ẏ ln y`` at λ = 0), one value per λ [response units²].

    ``-n/2 ln SS(λ)`` is the profile log-likelihood of λ up to a constant (Box & Cox 1964).
    The projections use the factorisation of the regression core (``fit``, a
    :class:`~rsm_lrg.model.engines.least_squares.Regression` of ``X``; factorised here when not given).
    """
    from ..engines.least_squares import least_squares

    X = np.asarray(X, dtype=float)
    y = np.asarray(y, dtype=float)
    ls = fit if fit is not None else least_squares(X, y)
    lny = np.log(y)
    gm = float(np.exp(lny.mean()))
    lams = np.atleast_1d(np.asarray(lambdas, dtype=float))
    Z = np.empty((y.size, lams.size))
    if _has_constant(X):
        # scale-free (the profile, and so λ, must not depend on the response's unit): with u = y / ẏ,
        # (y^λ - 1) / (λ ẏ^(λ-1)) = ẏ (u^λ - 1) / λ + a constant, which the intercept takes; u is
        # near 1 whatever the unit, so u^λ neither overflows nor cancels against the 1 (y = 1e8 y0
        # once moved λ̂ from -2.78 to -1.91)
        lnu = lny - lny.mean()
        for j, lam in enumerate(lams):
            Z[:, j] = lnu if abs(lam) < 1e-12 else np.expm1(lam * lnu) / lam
        return gm * gm * ls.residual_ss_of(X, Z)
    for j, lam in enumerate(lams):
        Z[:, j] = gm * lny if abs(lam) < 1e-12 else (np.exp(lam * lny) - 1.0) / (lam * gm ** (lam - 1.0))
    return ls.residual_ss_of(X, Z)


def _has_constant(X: np.ndarray) -> bool:
    """True when a column of ``X`` is a non-zero constant (the model has an intercept)."""
    if X.shape[0] == 0:
        return False
    return bool(np.any(np.all(X == X[0], axis=0) & (X[0] != 0)))


#: The Box–Cox rules of :func:`box_cox`.
BOX_COX_RULES = ("likelihood", "design-expert")


def _current_lambda(tr) -> float:
    """λ of the transform a model was fitted on (1: none; 0: log, log10 included)."""
    if tr.name == "none":
        return 1.0
    return 0.0 if tr.lam is None else float(tr.lam)


def box_cox_response(result) -> np.ndarray:
    """The response the Box–Cox profile is taken of: as measured, plus the transform's
    constant k (Design-Expert's Box-Cox of ``y + k``), whatever transform the model was
    fitted on (the profile then shows where that transform's λ lies); the model's own
    response for a fit without a transform.

    >>> import rsm_lrg
    >>> fit = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min", transform="log")
    >>> bool((fit.y < 0).all()), bool((box_cox_response(fit) > 0).all())
    (True, True)
    """
    if result.transform.identity or getattr(result, "y_response", None) is None:
        return np.asarray(result.y, dtype=float)
    return np.asarray(result.y_response, dtype=float) + result.transform.constant


def box_cox(result, *, confidence: float = 0.95, lambdas=None, rule: str = "likelihood") -> BoxCox:
    """Box–Cox profile of the fitted model (see the module docstring for both rules).

    Parameters
    ----------
    result : FitResult
        Fit on the untransformed response; every response value must be positive.
    confidence : float
    lambdas : array, optional
        λ grid (default -3 .. 3 by 0.01).
    rule : {"likelihood", "design-expert"}
        ``"likelihood"``: λ̂ by maximum likelihood and the χ²₁ likelihood-ratio interval (the
        exact answer). ``"design-expert"``: the grid minimum and the interval
        ``ln SS <= ln SS_min + t²(α/2, ν)/ν`` of Design-Expert's Box-Cox plot (Stat-Ease,
        https://www.statease.com/docs/latest/contents/analysis/box-cox-plot/).
    """
    from scipy import optimize as so
    from scipy import special

    rule = str(rule).strip().lower().replace("_", "-")
    if rule in ("de", "designexpert", "stat-ease", "statease"):
        rule = "design-expert"
    if rule not in BOX_COX_RULES:
        raise ValueError(f"Box-Cox rule must be 'likelihood' or 'design-expert', not {rule!r}")
    if not 0.0 < confidence < 1.0:
        raise ParameterError("confidence", f"confidence must lie between 0 and 1, not {confidence!r}")
    y = box_cox_response(result)
    if np.any(y <= 0):
        i = int(np.flatnonzero(y <= 0)[0])
        raise ValueError(f"Box-Cox needs a positive response: column {result.response!r}, row {i + 1} holds {y[i]:g}"
                         + (f" (after adding the constant {result.transform.constant:g})" if result.transform.constant else ""))
    X = result.design_matrix
    nu = result.df_resid
    if nu <= 0:
        raise ValueError("Box-Cox needs residual degrees of freedom (the model is saturated)")

    ls = result.least_squares

    def ss_of(lam: float) -> float:
        return float(box_cox_ss(X, y, [lam], fit=ls)[0])

    grid = np.round(np.arange(-3.0, 3.0 + 1e-9, 0.01), 10) if lambdas is None else np.asarray(lambdas, float)
    ss = box_cox_ss(X, y, grid, fit=ls)
    i = int(np.argmin(ss))
    lam = float(grid[i])
    if rule == "likelihood":
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        if hi > lo:
            r = so.minimize_scalar(ss_of, bounds=(lo, hi), method="bounded", options={"xatol": 1e-8})
            if r.fun <= ss[i]:
                lam = float(r.x)
        ss_min = ss_of(lam)
        cut = ss_min * math.exp(special.chdtri(1, 1.0 - confidence) / len(y))
    else:
        ss_min = float(ss[i])
        t = special.stdtrit(nu, 1 - (1 - confidence) / 2)
        cut = math.exp(math.log(ss_min) + t * t / nu)
    a, b = float(min(grid[0], -3.0)), float(max(grid[-1], 3.0))
    g = lambda l: ss_of(l) - cut  # noqa: E731
    low = high = math.nan
    if g(a) > 0 and lam > a:
        low = float(so.brentq(g, a, lam, xtol=1e-10))
    if g(b) > 0 and lam < b:
        high = float(so.brentq(g, lam, b, xtol=1e-10))
    lo_eff = -math.inf if math.isnan(low) else low
    hi_eff = math.inf if math.isnan(high) else high
    inside = [l for l in STANDARD_LAMBDAS if lo_eff <= l <= hi_eff]
    if inside:
        rec_l = min(inside, key=lambda l: (abs(l - lam), -l))
        rec = STANDARD_LAMBDAS[rec_l]
    else:
        rec_l = lam
        rec = f"power={lam:.4g}"
    return BoxCox(lambdas=grid, ss=ss, lambda_best=lam, ci=(low, high), confidence=float(confidence),
                  current=_current_lambda(result.transform), recommended=rec, recommended_lambda=float(rec_l), ratio=float(y.max() / y.min()),
                  rule=rule)


@dataclass(frozen=True)
class Diagnostics:
    """Per-run diagnostics of a fit (frozen).

    Attributes
    ----------
    table : pandas.DataFrame
        One row per run used (data order; ``run`` is its 1-based data row): ``run, run_order, actual, predicted, residual,
        leverage, studentized, externally_studentized, cooks_distance, dffits`` and the
        boolean flags ``flag_outlier, flag_leverage, flag_cooks, flag_dffits`` and ``flagged``.
    limits : dict
        ``{"externally_studentized", "leverage", "cooks_distance", "dffits"}`` limits used.
    box_cox : BoxCox or None
        ``None`` when the response is not all positive or the model is saturated.
    note : str
    """

    table: Any = field(repr=False)
    limits: dict = field(default_factory=dict)
    box_cox: BoxCox | None = None
    note: str = ""

    @property
    def flagged_runs(self) -> list[int]:
        """Run numbers (1-based data rows) with any flag."""
        return [int(r) for r in self.table.loc[self.table["flagged"], "run"]]

    def to_frame(self):
        return self.table.copy()

    def to_dict(self) -> dict:
        rows = []
        for r in self.table.to_dict(orient="records"):
            rows.append({k: (bool(v) if isinstance(v, (bool, np.bool_)) else
                             (float(v) if isinstance(v, (float, np.floating)) and math.isfinite(v) else
                              (None if isinstance(v, (float, np.floating)) else v))) for k, v in r.items()})
        return {"runs": rows, "limits": dict(self.limits),
                "box_cox": None if self.box_cox is None else self.box_cox.to_dict(), "note": self.note or None}

    def summary(self) -> str:
        from ...present import format_g, text_table

        head = ["Run", "Order", "Actual", "Predicted", "Residual", "Leverage", "Ext. stud.", "Cook's D", "DFFITS", "Flag"]
        rows = []
        for r in self.table.itertuples(index=False):
            flags = [n for n, f in (("outlier", r.flag_outlier), ("leverage", r.flag_leverage),
                                    ("Cook", r.flag_cooks), ("DFFITS", r.flag_dffits)) if f]
            order = r.run_order
            order = str(int(order)) if float(order).is_integer() else format_g(order)
            rows.append([r.run, order, format_g(r.actual), format_g(r.predicted), format_g(r.residual),
                         format_g(r.leverage, 3), format_g(r.externally_studentized, 3), format_g(r.cooks_distance, 3),
                         format_g(r.dffits, 3), ",".join(flags)])
        lim = self.limits
        out = ["Diagnostics", text_table(head, rows), "",
               f"Limits: |ext. studentized| > {lim['externally_studentized']:.3f} (Bonferroni, alpha 0.05), "
               f"leverage > {lim['leverage']:.3f} (2p/n), Cook's D > {lim['cooks_distance']:.3f} (F median), "
               f"|DFFITS| > {lim['dffits']:.3f} (2 sqrt(p/n))"]
        if self.box_cox is not None:
            b = self.box_cox
            ci = ", ".join("beyond ±3" if not math.isfinite(v) else format_g(v, 3, trim=True) for v in b.ci)
            out.append(f"Box-Cox: lambda = {format_g(b.lambda_best, 3, trim=True)}, {int(round(100 * b.confidence))} % CI [{ci}], "
                       f"max/min = {format_g(b.ratio, 3, trim=True)}; recommended transform: {b.recommended}")
            out.append(f"  ({b.rule_text})")
        if self.note:
            out.append(f"Note: {self.note}")
        return "\n".join(out) + "\n"


def diagnostics(result, *, alpha: float = 0.05, boxcox_rule: str = "likelihood") -> Diagnostics:
    """Per-run diagnostics and Box–Cox for a :class:`~rsm_lrg.model.fit.FitResult`
    (``boxcox_rule``: ``"likelihood"`` or ``"design-expert"``, see :func:`box_cox`)."""
    import pandas as pd
    from scipy import special

    n = result.n
    p = len(result.column_names)
    nu = result.df_resid
    h = np.asarray(result.hat, dtype=float)
    r = np.asarray(result.studentized_residuals, dtype=float)
    t = np.asarray(result.externally_studentized_residuals, dtype=float)
    cook = np.asarray(result.cooks_distance, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        dffits = t * np.sqrt(h / (1 - h))
    lim_t = float(special.stdtrit(nu - 1, 1 - alpha / (2 * n))) if nu > 1 else math.nan
    lim_h = 2.0 * p / n
    lim_c = float(special.fdtri(p, nu, 0.5)) if nu > 0 else math.nan
    lim_d = 2.0 * math.sqrt(p / n)
    table = pd.DataFrame({
        "run": np.asarray(result.run_rows, dtype=int), "run_order": _run_order(result.data), "actual": result.y,
        "predicted": result.fitted, "residual": result.residuals, "leverage": h, "studentized": r,
        "externally_studentized": t, "cooks_distance": cook, "dffits": dffits,
    })
    with np.errstate(invalid="ignore"):
        table["flag_outlier"] = np.abs(t) > lim_t
        table["flag_leverage"] = h > lim_h
        table["flag_cooks"] = cook > lim_c
        table["flag_dffits"] = np.abs(dffits) > lim_d
    table["flagged"] = table[["flag_outlier", "flag_leverage", "flag_cooks", "flag_dffits"]].any(axis=1)
    note = ""
    bc = None
    mixed = result.mixed
    if mixed is not None:  # REML: both residuals; the leverages and studentized ones are the whitened model's
        at = list(table.columns).index("residual") + 1
        table.insert(at, "marginal_residual", mixed.marginal_residuals)
        table.insert(at, "conditional_residual", mixed.conditional_residuals)
        note = ("REML fit: 'residual' is the conditional residual y - Xb - Zu, 'marginal_residual' y - Xb; leverage, "
                "studentized residuals, Cook's D and DFFITS are those of the whitened model V^-1/2 y = V^-1/2 X b + e; "
                "no Box-Cox (its likelihood is the least-squares one)")
    elif np.all(box_cox_response(result) > 0) and nu > 0:
        bc = box_cox(result, rule=boxcox_rule)
    else:
        note = ("no Box-Cox plot: the response has values <= 0" if nu > 0
                else "no residual degrees of freedom: the limits and Box-Cox are undefined")
    limits = {"externally_studentized": lim_t, "leverage": lim_h, "cooks_distance": lim_c, "dffits": lim_d}
    return Diagnostics(table=table, limits=limits, box_cox=bc, note=note)
