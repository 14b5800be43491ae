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

Design criteria (JMP's *Design Diagnostics*; the same criteria the optimal designs use,
:mod:`rsm_lrg.design.optimal`), with X the full model matrix (block contrasts included):

* **D-efficiency** ``det(X'X)^(1/p) / n`` (1 for an orthogonal ±1 design);
* **A-efficiency** ``p / (n trace((X'X)⁻¹))``;
* **G-efficiency** ``p / max SPV`` over the region (above);
* **I**: the average prediction variance ``trace((X'X)⁻¹ W)`` over the region (model terms,
  average block), ``W`` the region moment matrix (exact moments of the uniform measure on
  the coded cube, :func:`rsm_lrg.design.optimal.moment_matrix`; over the sphere the mean of
  the region sample), and the average SPV ``n I``. The I-optimal design of a region is known
  only by search, so there is no absolute I-efficiency: :func:`compare_designs` reports the
  relative I-efficiency ``min_j(n_j I_j) / (n I)`` among the designs compared (and the
  relative D-, A- and G-efficiencies likewise, each per run).

The **alias map**: with the fitted model X1 and the *potential* terms X2 of the next bigger
model (linear → 2FI → quadratic → cubic), the alias matrix ``A = (X1'X1)⁻¹ X1'X2`` (the
bias ``E[b1] = β1 + A β2`` when the potential terms are active: Box & Draper's alias
matrix, as :func:`rsm_lrg.design.screening.alias_matrix` computes it for screening designs)
and the correlation map of every model and potential column
(intercept left out, columns centred: JMP's *Color Map on Correlations*).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["evaluate_design", "DesignEvaluation", "FDS_FRACTIONS", "compare_designs", "DesignComparison",
           "POTENTIAL", "design_model", "DesignModel", "ols_power"]

#: The potential terms of each model: the next bigger model's (cubic: none).
POTENTIAL = {"linear": "2fi", "2fi": "quadratic", "quadratic": "cubic", "cubic": None}

#: Boundary search of the SPV maximum: iterations of the stacked L-BFGS-B over all faces, points
#: polished one by one, and the largest k with extra starts per face.
MAXITER, NPOL, EXTRA_K = 100, 32, 3
#: Largest model with fewer runs than terms whose aliased terms are listed one by one; a
#: larger one is refused from its term count.
MAX_ALIAS_LISTED = 200

#: Most columns (model and potential terms) of an alias map; beyond, ``potential="auto"`` gives none.
MAX_ALIAS_COLUMNS = 200

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
        Terms the design cannot estimate (then nothing else is computed and the model,
        residual and lack-of-fit df are ``None``).
    alias_relations : tuple of str
        For each aliased term, the combination of earlier terms it equals (``"A^2 = Intercept"``).
    rank : int
        Rank of the design matrix (the number of parameters the design can estimate).
    n_distinct : int
        Distinct factor settings (with blocks).
    spv_max_at : dict
        Coded point where the SPV over the region is largest (exact boundary search).
    g_efficiency : float
        ``p / max SPV`` over the region (Myers, Montgomery & Anderson-Cook, Sec. 8.2.1) [-].
    d_efficiency, a_efficiency : float
        ``det(X'X)^(1/p) / n`` and ``p / (n trace((X'X)⁻¹))`` [-].
    i_average : float
        Average prediction variance ``trace((X'X)⁻¹ W)`` over the region [σ²]; ``n i_average``
        is the average SPV.
    potential : str or None
        The model whose extra terms are the potential terms of the alias map.
    alias_matrix : pandas.DataFrame or None
        Rows the model columns, columns the potential columns: ``(X1'X1)⁻¹ X1'X2``.
    correlation : pandas.DataFrame or None
        Correlations of the model and potential columns (intercept left out; NaN for a
        constant column).
    fds_curve : pandas.DataFrame or None
        The FDS curve at 101 fractions 0, 0.01, ..., 1 (``fraction, variance, spv``), for plots.
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
    alias_relations: tuple = ()
    rank: int = 0
    n_distinct: int = 0
    spv_max_at: dict = field(default_factory=dict)
    g_efficiency: float = math.nan
    d_efficiency: float = math.nan
    a_efficiency: float = math.nan
    i_average: float = math.nan
    potential: str | None = None
    alias_matrix: Any = field(default=None, repr=False)
    correlation: Any = field(default=None, repr=False)
    fds_curve: Any = field(default=None, repr=False)
    split_plot: dict | None = None

    @property
    def estimable(self) -> bool:
        """Whether the design can estimate every term of the model."""
        return not self.aliased

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
                "aliased": list(self.aliased), "alias_relations": list(self.alias_relations),
                "estimable": self.estimable, "rank": self.rank, "n_distinct": self.n_distinct,
                "spv_max_at": dict(self.spv_max_at), "g_efficiency": f(self.g_efficiency),
                "d_efficiency": f(self.d_efficiency), "a_efficiency": f(self.a_efficiency),
                "i_average": f(self.i_average), "spv_average": f(self.n * self.i_average),
                "potential": self.potential,
                "alias_matrix": _frame_dict(self.alias_matrix, f),
                "correlation": _frame_dict(self.correlation, f),
                **({"split_plot": self.split_plot} if self.split_plot is not None else {})}

    def not_estimable_message(self) -> str:
        """One sentence naming the aliased terms (empty when the model is estimable)."""
        if self.estimable:
            return ""
        shown = list(self.aliased[:12])
        more = f" and {len(self.aliased) - 12} more" if len(self.aliased) > 12 else ""
        return (f"the {self.model} model is not estimable from this design (rank {self.rank} < {self.p} "
                f"parameters): aliased {', '.join(shown)}{more}; use a smaller --model or add runs")

    def summary(self) -> str:
        from ..present import format_g, text_table

        out = [f"Design evaluation for a {self.model} model: {self.n} runs, {self.p} parameters"]
        if self.aliased:
            out.append(f"Not estimable: the design matrix has rank {self.rank} < {self.p} parameters "
                       f"({self.n} runs, {self.n_distinct} distinct settings).")
            out.append("Aliased terms (each equals a combination of earlier terms):")
            out += [f"  {r}" for r in self.alias_relations]
            out.append("Choose a smaller model or add runs.")
            return "\n".join(out) + "\n"
        out.append("Degrees of freedom: " + ", ".join(f"{k.replace('_', ' ')} {v}" for k, v in self.df.items()))
        rows = [[t, format_g(r.std_error), format_g(r.vif, 4), "" if not math.isfinite(r.power) else f"{100 * r.power:.1f} %"]
                for t, r in self.terms.iterrows()]
        out += ["", text_table(["Term", "Std. error [σ]", "VIF", f"Power ({self.effect_sd:g}σ, α {self.alpha:g})"], rows)]
        out += ["", f"Leverage: min {self.leverage.min():.4f}, max {self.leverage.max():.4f}, mean {self.leverage.mean():.4f}",
                f"Scaled prediction variance n·x'(X'X)⁻¹x: centre {format_g(self.spv_center)}, "
                f"max at a design point {format_g(self.spv_max_design)}; over the {self.region}: "
                f"min {format_g(self.spv_region['min'])}, mean {format_g(self.spv_region['mean'])}, max {format_g(self.spv_region['max'])}",
                ("  (maximum by exact search of every face, edge and vertex; at coded "
                 if not any(isinstance(v, str) for v in self.spv_max_at.values()) else
                 "  (maximum of the region sample, categoric levels drawn evenly; at coded ")
                + ", ".join(f"{L} {v}" if isinstance(v, str) else f"{L} {v:+.4g}" for L, v in self.spv_max_at.items())
                + f"; G-efficiency p/max SPV = {100 * self.g_efficiency:.1f} %)",
                "", "Fraction of design space (unscaled variance x'(X'X)⁻¹x)"]
        rows = [[f"{r.fraction:.1f}", format_g(r.variance), format_g(r.spv)] for r in self.fds.itertuples(index=False)]
        out.append(text_table(["Fraction", "Variance [σ²]", "SPV"], rows))
        out += ["", f"Efficiencies: D {100 * self.d_efficiency:.1f} %, A {100 * self.a_efficiency:.1f} %, "
                    f"G {100 * self.g_efficiency:.1f} %; I (average prediction variance over the {self.region}) "
                    f"{format_g(self.i_average)} σ², average SPV {format_g(self.n * self.i_average)}"]
        out += self._alias_lines()
        out += self.split_plot_lines()
        return "\n".join(out) + "\n"

    def split_plot_lines(self, name: str | None = None) -> list[str]:
        """The GLS criteria of a split-plot design for people (none without whole plots);
        ``name`` (a design's name) begins the first sentence."""
        from ..present import format_g

        g = self.split_plot
        if g is None:
            return []
        if "strata" in g:
            parts = [f"{k} {v['groups']} groups ({v['sizes'][0]}" + (f" to {v['sizes'][1]}" if v['sizes'][1] != v['sizes'][0]
                     else "") + f" runs), η {format_g(v['variance_ratio'], 6, trim=True)}" for k, v in g["strata"].items()]
            return ["", (f"{name}: " if name else "") + "Random strata: " + "; ".join(parts) + ". The figures above "
                    "treat the runs as independent (OLS, X'X);",
                    "under generalised least squares with V = I + Σ η_k Z_k Z_k' (η = σ²_k/σ², --variance-ratio, "
                    "--variance-ratio-of):",
                    f"  D-efficiency det(X'V⁻¹X)^(1/p)/n {100 * g['d_efficiency']:.1f} %, A-efficiency "
                    f"{100 * g['a_efficiency']:.1f} %, I (average prediction variance over the cube) "
                    f"{format_g(g['i_average'])} σ²"]
        lo, hi = g["plot_sizes"]
        size = f"{lo} runs each" if lo == hi else f"{lo} to {hi} runs"
        eta = format_g(g["variance_ratio"], 6, trim=True)
        return ["", (f"{name}: " if name else "") + f"Split-plot design: {g['whole_plots']} whole plots ({size}). The "
                "figures above treat the runs as independent (OLS, X'X);",
                f"under generalised least squares with V = I + η J per whole plot, η = σ²_wp/σ² = {eta} "
                "(--variance-ratio):",
                f"  D-efficiency det(X'V⁻¹X)^(1/p)/n {100 * g['d_efficiency']:.1f} %, A-efficiency "
                f"{100 * g['a_efficiency']:.1f} %, I (average prediction variance over the cube) "
                f"{format_g(g['i_average'])} σ²"]

    def _alias_lines(self, tol: float = 1e-9, most: int = 12) -> list[str]:
        """The alias matrix's non-zero entries per model term and the largest correlations."""
        from .faces.text import format_g

        if self.alias_matrix is None or self.potential is None:
            return []
        A = self.alias_matrix
        out = ["", f"Alias matrix (model terms biased by the {self.potential} model's extra terms; "
                   "non-zero entries):"]
        any_ = False
        for term, row in A.iterrows():
            nz = [(c, v) for c, v in row.items() if abs(v) > tol]
            if nz:
                any_ = True
                text = " ".join(f"{'+' if v > 0 else '-'} {format_g(abs(v), 4)} {c}" for c, v in nz[:most])
                out.append(f"  [{term}] = {term} {text}{' ...' if len(nz) > most else ''}")
        if not any_:
            out.append("  none: no potential term biases a model term")
        R = self.correlation
        cols = list(R.columns)
        fitted = set(A.index)  # pairs of two potential terms say nothing about the fitted model
        pairs = [(abs(R.iat[i, j]), cols[i], cols[j], R.iat[i, j]) for i in range(len(cols))
                 for j in range(i + 1, len(cols)) if (cols[i] in fitted or cols[j] in fitted)
                 and np.isfinite(R.iat[i, j]) and abs(R.iat[i, j]) > tol]
        pairs.sort(key=lambda z: (-z[0], z[1], z[2]))
        out.append("Largest correlations of model columns (with each other and with potential columns)"
                   + (":" if pairs else ": none (all orthogonal)"))
        out += [f"  {a} ~ {b}: {r:+.3f}" for _, a, b, r in pairs[:most]]
        return out

    def __str__(self) -> str:
        return self.summary()


def _region_sample(k: int, region: str, radius: float, m: int, seed: int) -> np.ndarray:
    from scipy.special import ndtri
    from scipy.stats import qmc

    u = qmc.Sobol(d=k + (1 if region == "sphere" else 0), scramble=True, seed=seed).random_base2(m)
    if region == "cube":
        return 2.0 * u - 1.0
    z = ndtri(np.clip(u[:, :k], 1e-12, 1 - 1e-12))
    z /= np.linalg.norm(z, axis=1, keepdims=True)
    rr = radius * u[:, k] ** (1.0 / k)
    return z * rr[:, None]


def _rows_and_jacobian(P: np.ndarray, E: np.ndarray):
    """Model rows ``F`` (m x p) and their derivatives ``J`` (k x p x m: ``J[i, j, r]`` is
    d f_j / d x_i at point r) at the points ``P`` (m x k) for the monomials with exponents
    ``E`` (p x k)."""
    m, k = P.shape
    emax = int(E.max()) if E.size else 0
    pw = np.empty((emax + 1, m, k))
    pw[0] = 1.0
    for e in range(1, emax + 1):
        pw[e] = pw[e - 1] * P
    G = [pw[E[:, i], :, i] for i in range(k)]  # factor i of every monomial, (p, m)
    D = [E[:, i, None] * pw[np.maximum(E[:, i] - 1, 0), :, i] for i in range(k)]  # its derivative
    F = np.ones((E.shape[0], m))
    for g in G:
        F = F * g
    J = np.empty((k, E.shape[0], m))
    for i in range(k):
        Ji = D[i]
        for j in range(k):
            if j != i:
                Ji = Ji * G[j]
        J[i] = Ji
    return F.T, J


def _face_starts(k: int):
    """Starts and fixed masks for every face of the cube [-1, 1]^k (all 3^k faces: vertices,
    edges, ..., the cube itself): the face centre, and for k <= 3 also ±0.5 along each free
    axis and the two free-diagonal points ±0.5. Returns ``(starts, fixed)``."""
    import itertools

    starts, fixed = [], []
    for code in itertools.product((-1, 0, 1), repeat=k):
        c = np.array(code, dtype=float)
        fx = c != 0
        free = np.flatnonzero(~fx)
        starts.append(c)
        fixed.append(fx)
        if k <= EXTRA_K and free.size:
            for j in free:
                for s in (-0.5, 0.5):
                    x = c.copy()
                    x[j] = s
                    starts.append(x)
                    fixed.append(fx)
            for s in (-0.5, 0.5):
                x = c.copy()
                x[free] = s
                starts.append(x)
                fixed.append(fx)
    return np.array(starts), np.array(fixed)


def _max_variance_cube(E: np.ndarray, Ct: np.ndarray, k: int, seed: int = 0):
    """Exact maximum of the unscaled prediction variance ``v(x) = f(x)'Ct f(x)`` over the
    coded cube [-1, 1]^k, with its location.

    ``v`` is a polynomial, so its maximum over the cube lies at a vertex or at a stationary
    point inside some face. Every face of every dimension (3^k of them for k <= 8: fixed
    coordinates at ±1, the rest free in [-1, 1]) is searched by L-BFGS-B from its centre (and,
    for k <= 3, from a few more starts); the vertices are evaluated exactly (they are the
    0-dimensional faces). All faces are optimised in one bounded L-BFGS-B call on the stacked
    (separable) problem, then the best 32 points are polished one by one over the whole cube.
    For k > 8 the faces are replaced by the vertices' neighbourhood of 4096 Sobol starts.
    """
    from scipy import optimize as so
    from scipy.stats import qmc

    def value_grad(P):
        F, J = _rows_and_jacobian(P, E)
        CF = F @ Ct
        v = np.einsum("ij,ij->i", F, CF)
        CFt = CF.T
        g = 2.0 * np.stack([np.einsum("pm,pm->m", Ji, CFt) for Ji in J], axis=1)
        return v, g

    if k <= 8:
        S, fixed = _face_starts(k)
    else:
        S = 2.0 * qmc.Sobol(d=k, scramble=True, seed=seed).random_base2(12) - 1.0
        fixed = np.zeros_like(S, dtype=bool)
    lo = np.where(fixed, S, -1.0)
    hi = np.where(fixed, S, 1.0)
    m = S.shape[0]
    v0, _ = value_grad(S)
    scale = float(np.max(v0)) or 1.0

    def joint(z):
        P = z.reshape(m, k)
        v, g = value_grad(P)
        return -float(v.sum()) / scale, -(g / scale).ravel()

    r = so.minimize(joint, S.ravel(), jac=True, method="L-BFGS-B",
                    bounds=list(zip(lo.ravel(), hi.ravel())),
                    options={"maxiter": MAXITER, "ftol": 1e-15, "gtol": 1e-12, "maxcor": 20})
    P = np.clip(r.x.reshape(m, k), lo, hi)
    vP, _ = value_grad(P)
    cand = np.vstack([P, S])
    vc = np.concatenate([vP, v0])
    order = np.argsort(-vc, kind="stable")[:NPOL]

    def single(x):
        v, g = value_grad(x[None, :])
        return -float(v[0]) / scale, -g[0] / scale

    best_x, best_v = cand[order[0]].copy(), float(vc[order[0]])
    for i in order:
        rr = so.minimize(single, cand[i], jac=True, method="L-BFGS-B", bounds=[(-1.0, 1.0)] * k,
                         options={"maxiter": 500, "ftol": 1e-16, "gtol": 1e-13})
        x = np.clip(rr.x, -1.0, 1.0)
        x = np.where(np.abs(np.abs(x) - 1.0) <= 1e-9, np.sign(x), x)
        v = float(value_grad(x[None, :])[0][0])
        if v > best_v:
            best_x, best_v = x, v
    return best_v, best_x


def _max_variance_ball(E: np.ndarray, Ct: np.ndarray, k: int, radius: float, sample: np.ndarray,
                       vsample: np.ndarray):
    """Maximum of ``f(x)'Ct f(x)`` over the ball ``|x| <= radius``: SLSQP from the 32 largest
    sample points, the axis points ±r e_i, the centre and (k <= 8) the scaled cube vertices."""
    import itertools

    from scipy import optimize as so

    def vg(x):
        F, J = _rows_and_jacobian(np.atleast_2d(x), E)
        CF = F @ Ct
        return float(F[0] @ CF[0]), 2.0 * J[:, :, 0] @ CF[0]

    starts = [sample[i] for i in np.argsort(-vsample)[:32]] + [np.zeros(k)]
    for i in range(k):
        for s in (-1.0, 1.0):
            e = np.zeros(k)
            e[i] = s * radius
            starts.append(e)
    if k <= 8:
        starts += [radius * np.array(v) / math.sqrt(k) for v in itertools.product((-1.0, 1.0), repeat=k)]
    scale = max(float(np.max(vsample)), 1e-300)
    cons = [{"type": "ineq", "fun": lambda x: radius ** 2 - x @ x, "jac": lambda x: -2.0 * x}]
    best_v, best_x = -math.inf, None
    for x0 in starts:
        r = so.minimize(lambda x: tuple(-t / scale for t in vg(x)), x0, jac=True, method="SLSQP",
                        constraints=cons, options={"maxiter": 300, "ftol": 1e-15})
        x = r.x
        nx = float(np.linalg.norm(x))
        if nx > radius:
            x = x * (radius / nx)
        v = vg(x)[0]
        if v > best_v:
            best_v, best_x = v, x
    return best_v, best_x



def ols_power(c_diag, df_residual: int, alpha: float, effect_sd: float) -> np.ndarray:
    """Exact power of the OLS test of single coefficients: ``P(F'(1, ν, λ) > F(1-α; 1, ν))``
    with ``λ = (effect_sd / 2)² / C_jj`` (the module docstring).

    Parameters
    ----------
    c_diag : array_like
        Diagonal entries ``C_jj`` of ``(X'X)⁻¹`` of the coefficients [1/σ² units].
    df_residual : int
        Residual degrees of freedom ν (> 0).
    alpha : float
        Level of the test.
    effect_sd : float
        Effect over the coded range -1..+1, in σ (coefficient ``effect_sd / 2``).

    Returns
    -------
    ndarray
        The power of each coefficient's test [-].
    """
    from scipy import special

    fcrit = special.fdtri(1, df_residual, 1 - alpha)
    lam = (effect_sd / 2.0) ** 2 / np.asarray(c_diag, dtype=float)
    return np.asarray(1.0 - special.ncfdtr(1, df_residual, lam, fcrit), dtype=float)


@dataclass(frozen=True)
class DesignModel:
    """The model matrix of a design, before any data (:func:`design_model`).

    Attributes
    ----------
    coded : (n, k) ndarray
        Coded settings (a categoric factor's value is its level index).
    letters : tuple of str
        The factors' letters.
    categoric : dict
        ``{position: levels}`` of the categoric factors.
    blocks, whole_plots : ndarray or None
        Block and whole-plot labels of the runs, as the design holds them.
    terms : tuple of Term
        The model's terms.
    X : (n, p) ndarray
        Model matrix: intercept, the block contrasts (sum to zero), then the term columns.
    names : tuple of str
        The names of the intercept and term columns (without the block contrasts).
    n_blocks : int
        Number of blocks (1 without blocks).
    block_codes : ndarray or None
        Block index 0..n_blocks-1 of each run (None with one block).
    """

    coded: np.ndarray = field(repr=False)
    letters: tuple
    categoric: dict
    blocks: Any = field(repr=False)
    whole_plots: Any = field(repr=False)
    terms: tuple
    X: np.ndarray = field(repr=False)
    names: tuple
    n_blocks: int = 1
    block_codes: Any = field(default=None, repr=False)

    @property
    def term_columns(self) -> np.ndarray:
        """Index in ``X`` of the intercept and term columns (block contrasts left out), as ``names``.

        Returns
        -------
        ndarray of int
        """
        p = self.X.shape[1]
        return np.r_[0, np.arange(self.n_blocks, p)] if self.n_blocks > 1 else np.arange(p)


def design_model(design, model: str = "quadratic", *, terms=None, intercept: bool = True) -> DesignModel:
    """The model matrix of a design for ``model`` (or a list of ``terms``), as :func:`evaluate_design`
    and :func:`rsm_lrg.model.power.simulate_power` evaluate it.

    Parameters
    ----------
    design : Design or (n, k) array of coded settings
        A :class:`~rsm_lrg.design.Design` (blocks and whole plots are kept) or coded runs.
    model : {"linear", "2fi", "quadratic", "cubic"}
    terms : list of str or str, optional
        A list of term names (``"A B AB A^2"``) instead of ``model``.
    intercept : bool
        Whether the model has an intercept (with ``terms``).

    Returns
    -------
    DesignModel
        ``ValueError`` when far more parameters than runs are asked for.
    """
    from ..factors import letters_for
    from .build.terms import MAX_TERMS, check_model_size, column_names, model_matrix, model_terms, n_model_terms

    blocks, cats = None, {}
    if hasattr(design, "coded_runs"):
        coded = np.asarray(design.coded_runs, dtype=float)
        letters = list(design.factors.letters)
        blocks = design.blocks
        cats = design.factors.categoric  # {position: levels}; their coded value is the level index
    else:
        coded = np.asarray(design, dtype=float)
        if coded.ndim != 2:
            raise ValueError("coded settings must be an (n, k) array")
        letters = letters_for(coded.shape[1])
    plots = getattr(design, "whole_plots", None)
    n, k = coded.shape
    # counted before any term is built: far more parameters than runs is refused at once
    # (naming each of thousands of aliased terms would take minutes and help nobody)
    n_par = n_model_terms(k, model, cats) if terms is None else 0
    if n_par > MAX_TERMS or (n < n_par and n_par > MAX_ALIAS_LISTED):
        check_model_size(n, k, model, categoric=cats)  # raises with the count ("N runs cannot fit P terms ...")
        raise ValueError(f"the {model} model in {k} factors has {n_par} terms and {n} runs cannot estimate "
                         "them; choose a smaller model or add runs")
    if terms is None:
        terms = model_terms(letters, model, cats)
    else:
        from .build.inputs import chosen_terms
        from .build.spec import ModelSpec

        terms = list(chosen_terms(list(ModelSpec.build(model, terms=terms, intercept=intercept).terms or ()),
                                  letters, cats, intercept=intercept))
    nb, codes = 1, None
    if blocks is not None and len(set(np.asarray(blocks).tolist())) > 1:
        levels = sorted(set(np.asarray(blocks).tolist()))
        nb = len(levels)
        codes = np.searchsorted(levels, blocks)
    X = model_matrix(coded, terms, codes, nb)
    return DesignModel(coded=coded, letters=tuple(letters), categoric=dict(cats), blocks=blocks, whole_plots=plots,
                       terms=tuple(terms), X=X, names=tuple(column_names(terms)), n_blocks=nb, block_codes=codes)


def evaluate_design(design, model: str = "quadratic", *, region: str = "cube", alpha: float = 0.05,
                    effect_sd: float = 2.0, n_region: int = 4096, seed: int = 0,
                    potential: str | None = "auto", terms=None, intercept: bool = True,
                    variance_ratio: float | None = None,
                    variance_ratios: dict | None = None) -> DesignEvaluation:
    """Evaluate a design for a model before any data (see the module docstring).

    ``terms`` (a list of term names, or ``"A B AB A^2"``) evaluates that model instead of
    ``model`` (``intercept=False``: without an intercept); the alias map's potential terms
    are then those of the next order above ``model``.

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
    potential : str or None
        Model whose extra terms are the potential terms of the alias map (``"auto"``: the
        next bigger model, :data:`POTENTIAL`, when the map has at most
        :data:`MAX_ALIAS_COLUMNS` columns; ``None``: no alias map).
    variance_ratio : float, optional
        For a split-plot design (a :class:`~rsm_lrg.design.Design` with whole plots):
        ``η = σ²_wp / σ²`` of the GLS criteria (default 1); the evaluation's ``split_plot``
        holds them (:func:`rsm_lrg.design.split_plot.gls_criteria`) beside the OLS figures.
        Refused for a design without whole plots. With further strata (a split-split-plot
        design's ``subplot``, a strip-plot design's ``strip_row`` and ``strip_column``) it is
        the ratio of every stratum, and the criteria come from
        :func:`rsm_lrg.design.multi_stratum.stratum_criteria`.
    variance_ratios : dict, optional
        ``η`` [-] of single strata by group column (``{"subplot": 0.5}``), over
        ``variance_ratio``.

    Returns
    -------
    DesignEvaluation
        VIFs, leverages, the prediction-variance summary and FDS curve, power per term and the
        alias matrix, before any data.
    """
    import pandas as pd

    from ..design.multi_stratum import stratum_criteria
    from ..design.split_plot import gls_criteria
    from .build.terms import (
        design_matrix,
        model_terms,
        n_model_terms,
    )
    from .engines.least_squares import least_squares
    from .readings.anova import pure_error

    if region not in ("cube", "sphere"):
        raise ParameterError("region", f"region must be 'cube' or 'sphere', not {region!r}")
    if not 0 < alpha < 1:
        raise ParameterError("alpha", f"alpha must lie between 0 and 1, not {alpha!r}")
    if not (effect_sd > 0 and math.isfinite(effect_sd)):
        raise ParameterError("effect_sd", f"effect_sd must be a positive number, not {effect_sd!r}")
    given_terms = terms is not None
    dm = design_model(design, model, terms=terms, intercept=intercept)
    coded, letters, blocks, cats, plots, terms = dm.coded, list(dm.letters), dm.blocks, dm.categoric, dm.whole_plots, \
        list(dm.terms)
    levels_of = cats
    strata = dict(getattr(design, "strata", None) or {})
    if variance_ratios and not strata and plots is None:
        raise ParameterError("variance_ratios", "the design has no random strata")
    if strata and blocks is not None:
        raise ValueError("a design with both blocks and random strata is not evaluated under GLS here")
    if variance_ratio is not None and plots is None and not strata:
        raise ParameterError("variance_ratio", "the design has no whole plots (no whole_plot column; name the "
                                               "whole-plot column with --whole-plot COL)")
    if plots is not None and blocks is not None:
        raise ValueError("a design with both blocks and whole plots is not evaluated under GLS here; "
                         "drop the block column or the whole-plot column")
    n, k = coded.shape
    auto = potential == "auto"
    if auto:
        potential = POTENTIAL.get(model)
    potential_terms = None
    if potential is not None:
        if potential not in POTENTIAL:
            raise ParameterError("potential", f"potential must be one of {', '.join(POTENTIAL)} (got {potential!r})")
        n_all = n_model_terms(k, potential, cats)
        if n_all > MAX_ALIAS_COLUMNS:  # a map of thousands of columns helps nobody (and is slow)
            if not auto:
                raise ParameterError("potential", f"potential {potential!r}: the alias map would have {n_all} columns, beyond the "
                                 f"{MAX_ALIAS_COLUMNS} shown; choose a smaller potential model")
            potential = None
        else:
            have = {t.name for t in terms}
            potential_terms = [t for t in model_terms(letters, potential, cats) if t.name not in have]
            if not potential_terms:
                raise ParameterError("potential", f"potential {potential!r} adds no term to the {model} model; choose a bigger model")
    nb, codes, X, names = dm.n_blocks, dm.block_codes, dm.X, list(dm.names)
    keys = coded if codes is None else np.column_stack([coded, codes])
    p = X.shape[1]
    # pure error as fit() splits it: residual of (blocks +) one mean per distinct setting
    pe = pure_error(coded, np.zeros(n), codes if nb > 1 else None)
    df_res = n - p
    # the regression core on a zero response: (X'X)^-1, leverage, VIF and the aliased columns
    ls = least_squares(X, np.zeros(n), ["Intercept"] + [f"Block{j + 1}" for j in range(nb - 1)] + names[1:])
    rank = ls.rank
    n_distinct = int(np.unique(keys, axis=0).shape[0])
    if n < p or rank < p:
        # not estimable: no negative or meaningless degrees of freedom; name every aliased term
        relations = ls.alias_relations()
        bad = ls.aliased
        df = {"model": None, "residual": None, "lack_of_fit": None, "pure_error": pe.df, "blocks": nb - 1}
        empty = pd.DataFrame(columns=["std_error", "vif", "power"])
        return DesignEvaluation(model=model, n=n, p=p, df=df, terms=empty, leverage=np.full(n, np.nan),
                                aliased=bad or ("(unidentified)",), alias_relations=tuple(relations), rank=rank,
                                n_distinct=n_distinct, letters=tuple(letters), region=region, alpha=alpha,
                                effect_sd=effect_sd)
    df = {"model": len(names) - 1, "residual": df_res, "lack_of_fit": df_res - pe.df,
          "pure_error": pe.df, "blocks": nb - 1}
    C = ls.cov_unscaled
    tidx = np.r_[0, np.arange(nb, p)] if nb > 1 else np.arange(p)
    se = np.sqrt(np.diag(C)[tidx])
    vif = np.r_[np.nan, ls.vif(tidx[1:])]  # the same definition as fit()
    power = np.full(tidx.size, np.nan)
    if df_res > 0:  # noncentral F: P(F'(1, ν, λ) > F(1-α; 1, ν))
        power = ols_power(np.diag(C)[tidx], df_res, alpha, effect_sd)
        power[0] = np.nan  # no test of the intercept
    term_frame = pd.DataFrame({"std_error": se, "vif": vif, "power": power}, index=pd.Index(names, name="term"))
    hat = ls.hat
    assert hat is not None  # least_squares on arrays makes the second pass
    Ct = C[np.ix_(tidx, tidx)]

    def var(points):
        Z = design_matrix(points, terms)
        return np.einsum("ij,jk,ik->i", Z, Ct, Z)

    v0 = float(var(np.zeros((1, k)))[0])
    vd = var(coded)
    radius = float(np.max(np.linalg.norm(coded, axis=1)))
    m = int(math.ceil(math.log2(max(n_region, 16))))
    pts = _region_sample(k, region, radius if radius > 0 else 1.0, m, seed)
    if cats:  # categoric factors: their levels drawn evenly; the maximum is that of the sample
        for i, lv in cats.items():
            u = (pts[:, i] + 1.0) / 2.0 if region == "cube" else np.random.default_rng(seed + i).random(len(pts))
            pts[:, i] = np.minimum(np.floor(np.clip(u, 0.0, 1.0) * len(lv)), len(lv) - 1)
        v0 = float(np.mean([var(np.array([[j if q in cats else 0.0 for q in range(k)]]))[0]
                            for j in range(min(len(lv) for lv in cats.values()))]))
    vs = var(pts)
    E = np.array([t.powers for t in terms], dtype=int)
    if cats:
        i_max = int(np.argmax(vs))
        vmax, xmax = float(vs[i_max]), pts[i_max]
    elif region == "cube":
        vmax, xmax = _max_variance_cube(E, Ct, k, seed)
    else:
        vmax, xmax = _max_variance_ball(E, Ct, k, radius if radius > 0 else 1.0, pts, vs)
    if float(vs.max()) > vmax:  # never below the sample
        vmax, xmax = float(vs.max()), pts[int(np.argmax(vs))]
    # the design criteria (module docstring)
    sign, logdet = np.linalg.slogdet(X.T @ X)
    d_eff = float(math.exp(logdet / p) / n) if sign > 0 else 0.0
    a_eff = float(p / (n * np.trace(C)))
    if region == "cube":
        i_avg = float(np.trace(Ct @ _cube_moments(design, letters, terms)))
    else:
        i_avg = float(vs.mean())
    alias, corr = None, None
    if potential is not None:
        alias, corr = _alias_map(coded, terms, potential_terms, X, tidx, names)
    vr = np.sort(vs)
    fr = np.array(FDS_FRACTIONS)
    q = np.quantile(vr, fr)
    q[-1] = vmax  # the curve ends at the exact maximum over the region (boundary search)
    fds = pd.DataFrame({"fraction": fr, "variance": q, "spv": n * q})
    fr2 = np.linspace(0.0, 1.0, 101)
    q2 = np.quantile(vr, fr2)
    q2[-1] = vmax
    fds_curve = pd.DataFrame({"fraction": fr2, "variance": q2, "spv": n * q2})
    return DesignEvaluation(
        model=model, n=n, p=p, df=df, terms=term_frame, leverage=hat, spv_center=n * v0,
        spv_max_design=float(n * vd.max()),
        spv_region={"min": float(n * vr[0]), "mean": float(n * vr.mean()), "max": float(n * vmax)},
        fds=fds, region=region, alpha=float(alpha), effect_sd=float(effect_sd), letters=tuple(letters),
        spv_max_at={L: (levels_of[i][int(v)] if i in levels_of else float(v)) for i, (L, v) in enumerate(zip(letters, xmax))},
        g_efficiency=float(len(names) / (n * vmax)),
        rank=rank, n_distinct=n_distinct,
        d_efficiency=d_eff, a_efficiency=a_eff, i_average=i_avg,
        potential=potential, alias_matrix=alias, correlation=corr, fds_curve=fds_curve,
        split_plot=stratum_criteria(
            design, terms=list(terms) if given_terms else None, model=model,
            variance_ratios={**dict.fromkeys(([] if plots is None else ["whole_plot"]) + list(strata),
                                             1.0 if variance_ratio is None else variance_ratio),
                             **(variance_ratios or {})}) if strata or variance_ratios else None if plots is None
        else gls_criteria(
            design, terms=list(terms) if given_terms else None, model=model,
            variance_ratio=1.0 if variance_ratio is None else variance_ratio),
    )


def _frame_dict(frame, f) -> dict | None:
    """``{row: {column: value}}`` of a DataFrame (None stays None)."""
    if frame is None:
        return None
    return {str(r): {str(c): f(v) for c, v in row.items()} for r, row in frame.iterrows()}


def _cube_moments(design, letters, terms) -> np.ndarray:
    """Region moment matrix W of the model terms over the coded cube (uniform on the cube,
    categoric levels equally weighted): the I criterion's, from the optimal designs."""
    from ..design.optimal import moment_matrix
    from ..factors import FactorSpace

    space = design.factors if hasattr(design, "factors") else FactorSpace.from_ranges(
        [(f"x{i + 1}", -1.0, 1.0) for i in range(len(letters))])
    return moment_matrix(space, terms)


def _alias_map(coded, terms, potential_terms, X, tidx, names):
    """Alias matrix (model columns x potential columns) and the correlation map."""
    import pandas as pd

    from .build.terms import column_names, design_matrix

    X2 = design_matrix(coded, potential_terms)
    pnames = column_names(potential_terms)
    A = np.linalg.pinv(X.T @ X) @ X.T @ X2
    A = A[tidx]
    A[np.abs(A) < 1e-12] = 0.0
    alias = pd.DataFrame(A + 0.0, index=pd.Index(names, name="term"), columns=pnames)
    Z = np.column_stack([X[:, tidx[1:]], X2])
    Z = Z - Z.mean(axis=0)
    norm = np.sqrt((Z ** 2).sum(axis=0))
    with np.errstate(invalid="ignore", divide="ignore"):
        R = (Z.T @ Z) / np.outer(norm, norm)
    R[:, norm < 1e-12] = np.nan
    R[norm < 1e-12, :] = np.nan
    R[np.abs(R) < 1e-12] = 0.0
    allnames = list(names[1:]) + pnames
    return alias, pd.DataFrame(R + 0.0, index=allnames, columns=allnames)


@dataclass(frozen=True)
class DesignComparison:
    """Two or more designs evaluated for the same model, side by side (frozen).

    Attributes
    ----------
    names : tuple of str
        The designs' names (file names on the command line).
    evaluations : tuple of DesignEvaluation
    table : pandas.DataFrame
        One row per design: ``runs, parameters, d_efficiency, a_efficiency, g_efficiency,
        i_average`` [σ²], ``spv_average, spv_max`` and the relative efficiencies
        ``rel_d, rel_a, rel_g, rel_i`` (each per run, 1 for the best design compared).
    """

    names: tuple
    evaluations: tuple = field(repr=False)
    table: Any = field(repr=False)

    def to_frame(self):
        """The criteria table (a copy)."""
        return self.table.copy()

    def to_dict(self) -> dict:
        f = lambda v: float(v) if v is not None and math.isfinite(float(v)) else None  # noqa: E731
        rows = []
        for name, row in self.table.iterrows():
            r = {"design": str(name)}
            r.update({c: (int(v) if c in ("runs", "parameters") else f(v)) for c, v in row.items()})
            rows.append(r)
        out = {"model": self.evaluations[0].model, "region": self.evaluations[0].region,
               "designs": list(self.names), "criteria": rows,
               "evaluations": [e.to_dict() for e in self.evaluations]}
        if any(e.split_plot is not None for e in self.evaluations):  # GLS criteria per design
            out["split_plot"] = {n: e.split_plot for n, e in zip(self.names, self.evaluations)}
        return out

    def summary(self) -> str:
        from ..present import format_g, text_table

        e0 = self.evaluations[0]
        out = [f"Design comparison for a {e0.model} model over the {e0.region} ({len(self.names)} designs)"]
        heads = ["Design", "Runs", "p", "D-eff", "A-eff", "G-eff", "I [σ²]", "avg SPV", "max SPV",
                 "rel D", "rel A", "rel G", "rel I"]
        pc = lambda v: f"{100 * v:.1f} %"  # noqa: E731
        rows = [[str(n), str(int(r.runs)), str(int(r.parameters)), pc(r.d_efficiency), pc(r.a_efficiency),
                 pc(r.g_efficiency), format_g(r.i_average, 4), format_g(r.spv_average, 4), format_g(r.spv_max, 4),
                 f"{r.rel_d:.3f}", f"{r.rel_a:.3f}", f"{r.rel_g:.3f}", f"{r.rel_i:.3f}"]
                for n, r in self.table.iterrows()]
        out += ["", text_table(heads, rows), "",
                "Efficiencies per run (D det(X'X)^(1/p)/n, A p/(n tr((X'X)^-1)), G p/max SPV); I the average "
                "prediction variance; rel: each divided by the best of the designs compared (I: best n*I / n*I).",
                "", "Fraction of design space (unscaled variance x'(X'X)⁻¹x [σ²])"]
        fr = self.evaluations[0].fds["fraction"].to_numpy()
        rows = [[f"{x:.1f}"] + [format_g(e.fds["variance"].iat[i], 4) for e in self.evaluations]
                for i, x in enumerate(fr)]
        out.append(text_table(["Fraction"] + [str(n) for n in self.names], rows))
        for n, e in zip(self.names, self.evaluations):
            out += e.split_plot_lines(str(n))
        return "\n".join(out) + "\n"

    def __str__(self) -> str:
        return self.summary()


def compare_designs(designs, model: str = "quadratic", *, names=None, region: str = "cube", **kwargs) -> DesignComparison:
    """Evaluate two or more designs for ``model`` and tabulate their criteria side by side.

    Parameters
    ----------
    designs : sequence of Design or (n, k) arrays
        At least two; all with the same number of factors (and the same categoric factors).
    model : str
    names : sequence of str, optional
        Their names (default ``design 1``, ``design 2``, ...).
    region, **kwargs
        As :func:`evaluate_design`.

    Returns
    -------
    DesignComparison
        ``ValueError`` naming the design when one cannot estimate the model or has other
        factors than the first.
    """
    import pandas as pd

    designs = list(designs)
    if len(designs) < 2:
        raise ValueError("compare at least two designs")
    names = [f"design {i + 1}" for i in range(len(designs))] if names is None else [str(n) for n in names]
    if len(names) != len(designs):
        raise ValueError(f"{len(names)} names for {len(designs)} designs")
    if len(set(names)) != len(names):
        raise ValueError("each design needs its own name")

    def shape(d):
        if hasattr(d, "factors"):
            return len(d.factors), sorted((i, tuple(v)) for i, v in d.factors.categoric.items())
        return np.asarray(d).shape[1], []

    k0 = shape(designs[0])
    eta = kwargs.pop("variance_ratio", None)
    with_plots = [getattr(d, "whole_plots", None) is not None or bool(getattr(d, "strata", None)) for d in designs]
    if eta is not None and not any(with_plots):
        raise ParameterError("variance_ratio", "the designs have no whole plots (no whole_plot column; name the "
                                               "whole-plot column with --whole-plot COL)")
    evs = []
    for name, d, plots in zip(names, designs, with_plots):
        if shape(d) != k0:
            raise ValueError(f"{name}: has {shape(d)[0]} factors (categoric {shape(d)[1] or 'none'}), {names[0]} has "
                             f"{k0[0]} (categoric {k0[1] or 'none'}); compare designs for the same factors")
        e = evaluate_design(d, model, region=region, variance_ratio=eta if plots else None, **kwargs)
        if not e.estimable:
            raise ValueError(f"{name}: {e.not_estimable_message()}")
        evs.append(e)
    t = pd.DataFrame({
        "runs": [e.n for e in evs], "parameters": [e.p for e in evs],
        "d_efficiency": [e.d_efficiency for e in evs], "a_efficiency": [e.a_efficiency for e in evs],
        "g_efficiency": [e.g_efficiency for e in evs], "i_average": [e.i_average for e in evs],
        "spv_average": [e.n * e.i_average for e in evs], "spv_max": [e.spv_region["max"] for e in evs],
    }, index=pd.Index(names, name="design"))
    for c, col in (("rel_d", "d_efficiency"), ("rel_a", "a_efficiency"), ("rel_g", "g_efficiency")):
        t[c] = t[col] / t[col].max()
    t["rel_i"] = t["spv_average"].min() / t["spv_average"]
    return DesignComparison(names=tuple(names), evaluations=tuple(evs), table=t)
