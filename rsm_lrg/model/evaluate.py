"""Design evaluation before any data (Design-Expert "Evaluation"): how well will this
design estimate the model?

From the coded design matrix X (n runs, p terms; blocks as sum-to-zero contrasts) alone:

* **degrees of freedom**: model, residual, pure error (replicated settings), lack of fit;
* per term: standard error in units of σ, ``√C_jj`` with ``C = (X'X)⁻¹``; the **VIF**
  (diagonal of the inverse correlation matrix of the term columns, as :func:`rsm_lrg.fit`
  reports it); the **power** to detect a coefficient of size σ — an effect of 2σ over the
  coded range [-1, 1], Design-Expert's default signal-to-noise ratio 2 — at α = 0.05: the
  partial F test has noncentrality ``λ = (Δ/2)²/(σ² C_jj) = 1/C_jj`` and
  ``power = P(F'(1, ν, λ) > F(1-α; 1, ν))`` with ν = n - p (the noncentral-F power of a
  linear hypothesis; Searle, *Linear Models*, Sec. 6.6);
* **leverage** of every run, ``h_ii = x_i'(X'X)⁻¹x_i``;
* the **scaled prediction variance** ``SPV(x) = n x'(X'X)⁻¹x`` (Myers, Montgomery &
  Anderson-Cook, *Response Surface Methodology*, 3rd ed., Sec. 8.2.1) at the centre, the
  design points and over the region (the coded cube [-1, 1]^k, or the sphere of the
  design's radius), and the **fraction of design space** curve (Zahran, Anderson-Cook &
  Myers 2003): the sorted unscaled variance ``x'(X'X)⁻¹x`` (Design-Expert's "std error"² of
  the mean) against the fraction of the region where it is not exceeded.

For a Box–Behnken design the intercept is the mean of the centre runs, so
``SPV(0) = n / n0`` exactly (27/3 = 9 for the paper's design).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["evaluate_design", "DesignEvaluation", "FDS_FRACTIONS"]

#: Fractions at which the FDS curve is reported.
FDS_FRACTIONS = tuple(np.round(np.linspace(0.0, 1.0, 11), 2))


@dataclass(frozen=True)
class DesignEvaluation:
    """Evaluation of a design for a model (frozen).

    Attributes
    ----------
    model : str
    n, p : int
        Runs and model parameters (with block contrasts).
    df : dict
        ``{"model", "residual", "lack_of_fit", "pure_error", "blocks"}``.
    terms : pandas.DataFrame
        Index term; columns ``std_error`` [σ], ``vif``, ``power`` [-].
    leverage : ndarray
        h_ii per run (design order).
    spv_center, spv_max_design : float
        SPV at the centre and the largest SPV at a design point [-].
    spv_region : dict
        ``{"min", "mean", "max"}`` of SPV over the region sample [-].
    fds : pandas.DataFrame
        ``fraction, variance, spv``.
    region : str
    alpha, effect_sd : float
        Test level and effect size (in σ over the coded range) of the power column.
    aliased : tuple of str
        Terms the design cannot estimate (then nothing else is computed).
    """

    model: str
    n: int
    p: int
    df: dict
    terms: Any = field(repr=False)
    leverage: np.ndarray = field(repr=False)
    spv_center: float = math.nan
    spv_max_design: float = math.nan
    spv_region: dict = field(default_factory=dict)
    fds: Any = field(default=None, repr=False)
    region: str = "cube"
    alpha: float = 0.05
    effect_sd: float = 2.0
    aliased: tuple = ()
    letters: tuple = ()

    def to_dict(self) -> dict:
        f = lambda v: float(v) if v is not None and math.isfinite(float(v)) else None  # noqa: E731
        return {"model": self.model, "n": self.n, "p": self.p, "df": dict(self.df),
                "terms": {t: {"std_error": f(r.std_error), "vif": f(r.vif), "power": f(r.power)}
                          for t, r in self.terms.iterrows()},
                "leverage": [f(v) for v in self.leverage], "spv_center": f(self.spv_center),
                "spv_max_design": f(self.spv_max_design), "spv_region": {k: f(v) for k, v in self.spv_region.items()},
                "fds": [{"fraction": f(r.fraction), "variance": f(r.variance), "spv": f(r.spv)}
                        for r in self.fds.itertuples(index=False)] if self.fds is not None else [],
                "region": self.region, "power_alpha": self.alpha, "power_effect_sd": self.effect_sd,
                "aliased": list(self.aliased)}

    def summary(self) -> str:
        from .text import _table, format_g

        out = [f"Design evaluation for a {self.model} model: {self.n} runs, {self.p} parameters"]
        out.append("Degrees of freedom: " + ", ".join(f"{k.replace('_', ' ')} {v}" for k, v in self.df.items()))
        if self.aliased:
            out.append("Aliased (not estimable): " + ", ".join(self.aliased))
            return "\n".join(out) + "\n"
        rows = [[t, format_g(r.std_error), format_g(r.vif, 4), "" if not math.isfinite(r.power) else f"{100 * r.power:.1f} %"]
                for t, r in self.terms.iterrows()]
        out += ["", _table(["Term", "Std. error [σ]", "VIF", f"Power ({self.effect_sd:g}σ, α {self.alpha:g})"], rows)]
        out += ["", f"Leverage: min {self.leverage.min():.4f}, max {self.leverage.max():.4f}, mean {self.leverage.mean():.4f}",
                f"Scaled prediction variance n·x'(X'X)⁻¹x: centre {format_g(self.spv_center)}, "
                f"max at a design point {format_g(self.spv_max_design)}; over the {self.region}: "
                f"min {format_g(self.spv_region['min'])}, mean {format_g(self.spv_region['mean'])}, max {format_g(self.spv_region['max'])}",
                "", "Fraction of design space (unscaled variance x'(X'X)⁻¹x)"]
        rows = [[f"{r.fraction:.1f}", format_g(r.variance), format_g(r.spv)] for r in self.fds.itertuples(index=False)]
        out.append(_table(["Fraction", "Variance [σ²]", "SPV"], rows))
        return "\n".join(out) + "\n"

    def __str__(self) -> str:
        return self.summary()


def _region_sample(k: int, region: str, radius: float, m: int, seed: int) -> np.ndarray:
    from scipy.stats import norm, qmc

    u = qmc.Sobol(d=k + (1 if region == "sphere" else 0), scramble=True, seed=seed).random_base2(m)
    if region == "cube":
        return 2.0 * u - 1.0
    z = norm.ppf(np.clip(u[:, :k], 1e-12, 1 - 1e-12))
    z /= np.linalg.norm(z, axis=1, keepdims=True)
    rr = radius * u[:, k] ** (1.0 / k)
    return z * rr[:, None]


def evaluate_design(design, model: str = "quadratic", *, region: str = "cube", alpha: float = 0.05,
                    effect_sd: float = 2.0, n_region: int = 4096, seed: int = 0) -> DesignEvaluation:
    """Evaluate a design for a model before any data (see the module docstring).

    Parameters
    ----------
    design : Design or (n, k) array of coded settings
        A :class:`~rsm_lrg.design.Design` (blocks are used) or coded runs.
    model : {"linear", "2fi", "quadratic", "cubic"}
    region : {"cube", "sphere"}
        Region for the prediction variance: the coded cube [-1, 1]^k, or the ball whose
        radius is the largest design-point distance from the centre.
    alpha : float
        Level of the power calculation.
    effect_sd : float
        Effect to detect, in σ, over the coded range -1..+1 (coefficient = effect_sd / 2 σ).
    n_region : int
        Sobol sample size over the region (rounded up to a power of two).
    """
    import pandas as pd
    from scipy import stats

    from ..factors import letters_for
    from .anova import pure_error
    from .terms import design_matrix, model_terms

    blocks = None
    if hasattr(design, "coded_runs"):
        coded = np.asarray(design.coded_runs, dtype=float)
        letters = list(design.factors.letters)
        blocks = design.blocks
    else:
        coded = np.asarray(design, dtype=float)
        if coded.ndim != 2:
            raise ValueError("coded settings must be an (n, k) array")
        letters = letters_for(coded.shape[1])
    if region not in ("cube", "sphere"):
        raise ValueError(f"region must be 'cube' or 'sphere', not {region!r}")
    if not 0 < alpha < 1:
        raise ValueError(f"alpha must lie between 0 and 1, not {alpha!r}")
    if not (effect_sd > 0 and math.isfinite(effect_sd)):
        raise ValueError(f"effect_sd must be a positive number, not {effect_sd!r}")
    n, k = coded.shape
    terms = model_terms(letters, model)
    Xt = design_matrix(coded, terms)
    nb = 1
    if blocks is not None and len(set(np.asarray(blocks).tolist())) > 1:
        levels = sorted(set(np.asarray(blocks).tolist()))
        nb = len(levels)
        codes = np.searchsorted(levels, blocks)
        Bm = np.zeros((n, nb - 1))
        for j in range(nb - 1):
            Bm[codes == j, j] = 1.0
        Bm[codes == nb - 1, :] = -1.0
        X = np.column_stack([Xt[:, :1], Bm, Xt[:, 1:]])
        keys = np.column_stack([coded, codes])
    else:
        X = Xt
        keys = coded
    p = X.shape[1]
    names = [t.name for t in terms]
    pe = pure_error(keys, np.zeros(n))
    df_res = n - p
    df = {"model": len(terms) - 1, "residual": df_res, "lack_of_fit": max(df_res - pe.df, 0) if df_res >= 0 else 0,
          "pure_error": pe.df, "blocks": nb - 1}
    rank = np.linalg.matrix_rank(X)
    if n < p or rank < p:
        from .fit import _aliased_terms

        bad = _aliased_terms(X, ["Intercept"] + [f"Block{j}" for j in range(nb - 1)] + names[1:]) if n >= p else names[n:]
        empty = pd.DataFrame(columns=["std_error", "vif", "power"])
        return DesignEvaluation(model=model, n=n, p=p, df=df, terms=empty, leverage=np.full(n, np.nan),
                                aliased=tuple(bad) or ("(design has fewer runs than terms)",),
                                letters=tuple(letters), region=region, alpha=alpha, effect_sd=effect_sd)
    C = np.linalg.inv(X.T @ X)
    tidx = np.r_[0, np.arange(nb, p)] if nb > 1 else np.arange(p)
    se = np.sqrt(np.diag(C)[tidx])
    # VIF (same definition as fit())
    cols = tidx[1:]
    vif = np.full(tidx.size, np.nan)
    if cols.size:
        G = (X.T @ X)[np.ix_(cols, cols)]
        mcol = X.mean(axis=0)[cols]
        S = G - n * np.outer(mcol, mcol)
        d = np.sqrt(np.diag(S))
        with np.errstate(divide="ignore", invalid="ignore"):
            try:
                vif[1:] = np.diag(np.linalg.inv(S / np.outer(d, d)))
            except np.linalg.LinAlgError:
                pass
    power = np.full(tidx.size, np.nan)
    if df_res > 0:
        fcrit = stats.f.ppf(1 - alpha, 1, df_res)
        lam = (effect_sd / 2.0) ** 2 / np.diag(C)[tidx]
        power = stats.ncf.sf(fcrit, 1, df_res, lam)
        power[0] = np.nan  # no test of the intercept
    term_frame = pd.DataFrame({"std_error": se, "vif": vif, "power": power}, index=pd.Index(names, name="term"))
    hat = np.einsum("ij,jk,ik->i", X, C, X)
    Ct = C[np.ix_(tidx, tidx)]

    def var(points):
        Z = design_matrix(points, terms)
        return np.einsum("ij,jk,ik->i", Z, Ct, Z)

    v0 = float(var(np.zeros((1, k)))[0])
    vd = var(coded)
    radius = float(np.max(np.linalg.norm(coded, axis=1)))
    m = int(math.ceil(math.log2(max(n_region, 16))))
    pts = _region_sample(k, region, radius if radius > 0 else 1.0, m, seed)
    vr = np.sort(var(pts))
    fr = np.array(FDS_FRACTIONS)
    q = np.quantile(vr, fr)
    fds = pd.DataFrame({"fraction": fr, "variance": q, "spv": n * q})
    return DesignEvaluation(
        model=model, n=n, p=p, df=df, terms=term_frame, leverage=hat, spv_center=n * v0,
        spv_max_design=float(n * vd.max()),
        spv_region={"min": float(n * vr[0]), "mean": float(n * vr.mean()), "max": float(n * vr[-1])},
        fds=fds, region=region, alpha=float(alpha), effect_sd=float(effect_sd), letters=tuple(letters),
    )
