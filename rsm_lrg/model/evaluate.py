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

#: Boundary search of the SPV maximum: iterations of the stacked L-BFGS-B over all faces, points
#: polished one by one, and the largest k with extra starts per face.
MAXITER, NPOL, EXTRA_K = 100, 32, 3
#: Largest model with fewer runs than terms whose aliased terms are listed one by one; a
#: larger one is refused from its term count.
MAX_ALIAS_LISTED = 200

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
                "spv_max_at": dict(self.spv_max_at), "g_efficiency": f(self.g_efficiency)}

    def not_estimable_message(self) -> str:
        """One sentence naming the aliased terms (empty when the model is estimable)."""
        if self.estimable:
            return ""
        shown = list(self.aliased[:12])
        more = f" and {len(self.aliased) - 12} more" if len(self.aliased) > 12 else ""
        return (f"the {self.model} model is not estimable from this design (rank {self.rank} < {self.p} "
                f"parameters): aliased {', '.join(shown)}{more}; use a smaller --model or add runs")

    def summary(self) -> str:
        from .text import _table, format_g

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
        out += ["", _table(["Term", "Std. error [σ]", "VIF", f"Power ({self.effect_sd:g}σ, α {self.alpha:g})"], rows)]
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
        out.append(_table(["Fraction", "Variance [σ²]", "SPV"], rows))
        return "\n".join(out) + "\n"

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
    from scipy import special

    from ..factors import letters_for
    from .anova import pure_error
    from .least_squares import least_squares
    from .terms import (
        MAX_TERMS,
        check_model_size,
        column_names,
        design_matrix,
        model_matrix,
        model_terms,
        n_model_terms,
    )

    blocks, cats, levels_of = None, {}, {}
    if hasattr(design, "coded_runs"):
        coded = np.asarray(design.coded_runs, dtype=float)
        letters = list(design.factors.letters)
        blocks = design.blocks
        cats = design.factors.categoric  # {position: levels}; their coded value is the level index
        levels_of = cats
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
    # counted before any term is built: far more parameters than runs is refused at once
    # (naming each of thousands of aliased terms would take minutes and help nobody)
    n_par = n_model_terms(k, model, cats)
    if n_par > MAX_TERMS or (n < n_par and n_par > MAX_ALIAS_LISTED):
        check_model_size(n, k, model, categoric=cats)  # raises with the count ("N runs cannot fit P terms ...")
        raise ValueError(f"the {model} model in {k} factors has {n_par} terms and {n} runs cannot estimate "
                         "them; choose a smaller model or add runs")
    terms = model_terms(letters, model, cats)
    nb, codes = 1, None
    if blocks is not None and len(set(np.asarray(blocks).tolist())) > 1:
        levels = sorted(set(np.asarray(blocks).tolist()))
        nb = len(levels)
        codes = np.searchsorted(levels, blocks)
        keys = np.column_stack([coded, codes])
    else:
        keys = coded
    X = model_matrix(coded, terms, codes, nb)
    p = X.shape[1]
    names = column_names(terms)
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
        fcrit = special.fdtri(1, df_res, 1 - alpha)
        lam = (effect_sd / 2.0) ** 2 / np.diag(C)[tidx]
        power = 1.0 - special.ncfdtr(1, df_res, lam, fcrit)
        power[0] = np.nan  # no test of the intercept
    term_frame = pd.DataFrame({"std_error": se, "vif": vif, "power": power}, index=pd.Index(names, name="term"))
    hat = ls.hat
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
    vr = np.sort(vs)
    fr = np.array(FDS_FRACTIONS)
    q = np.quantile(vr, fr)
    q[-1] = vmax  # the curve ends at the exact maximum over the region (boundary search)
    fds = pd.DataFrame({"fraction": fr, "variance": q, "spv": n * q})
    return DesignEvaluation(
        model=model, n=n, p=p, df=df, terms=term_frame, leverage=hat, spv_center=n * v0,
        spv_max_design=float(n * vd.max()),
        spv_region={"min": float(n * vr[0]), "mean": float(n * vr.mean()), "max": float(n * vmax)},
        fds=fds, region=region, alpha=float(alpha), effect_sd=float(effect_sd), letters=tuple(letters),
        spv_max_at={L: (levels_of[i][int(v)] if i in levels_of else float(v)) for i, (L, v) in enumerate(zip(letters, xmax))},
        g_efficiency=float(len(names) / (n * vmax)),
        rank=rank, n_distinct=n_distinct,
    )
