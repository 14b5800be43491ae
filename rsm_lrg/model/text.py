"""The text face of a fit: Design-Expert style tables (the paper's Table 5 layout).

Computes nothing of its own; it formats what :class:`~rsm_lrg.model.fit.FitResult` holds.
"""

from __future__ import annotations

import math

__all__ = ["format_summary", "format_anova", "format_equation", "format_g"]


def format_g(x, digits: int = 4) -> str:
    """A number with ``digits`` significant figures (scientific when small or large)."""
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return ""
    x = float(x)
    if x == 0:
        return "0"
    a = abs(x)
    if 1e-3 <= a < 1e5:
        decimals = max(digits - 1 - int(math.floor(math.log10(a))), 0)
        return f"{x:.{decimals}f}"
    return f"{x:.{digits - 1}e}"


#: Relative size below which a sum of squares or a coefficient is round-off and printed as 0
#: (Design-Expert prints 0.000 for the AB and BC rows of the paper's Table 5).
ROUND_OFF = 1e-12


def _clean(x, scale):
    """``x``, or 0.0 when it is round-off relative to ``scale``."""
    if x is None or not math.isfinite(float(x)) or not math.isfinite(float(scale)):
        return x
    return 0.0 if abs(float(x)) <= ROUND_OFF * abs(float(scale)) else x


def _p(p) -> str:
    if p is None or not math.isfinite(p):
        return ""
    return "< 0.0001" if p < 1e-4 else f"{p:.4f}"


def _table(header, rows, align=None) -> str:
    widths = [max(len(str(h)), *(len(str(r[i])) for r in rows)) for i, h in enumerate(header)]
    align = align or ["<"] + [">"] * (len(header) - 1)
    fmt = "  ".join(f"{{:{a}{w}}}" for a, w in zip(align, widths))
    lines = [fmt.format(*header), "  ".join("-" * w for w in widths)]
    lines += [fmt.format(*map(str, r)) for r in rows]
    return "\n".join(lines)


def format_anova(result, alpha: float = 0.05) -> str:
    """The ANOVA (Type III partial sums of squares) like Table 5, with significance notes."""
    rows = []
    total = result.anova.loc[result.anova["source"] == "Cor Total", "sum_sq"]
    scale = float(total.iloc[0]) if len(total) else 0.0
    for r in result.anova.itertuples(index=False):
        mark = ""
        if r.p == r.p and r.source not in ("Residual", "Pure Error", "Cor Total", "Block"):
            if r.source == "Lack of Fit":
                mark = "not significant" if r.p >= alpha else "significant"
            elif r.source == "Model":
                mark = "significant" if r.p < alpha else "not significant"
            else:
                mark = "*" if r.p < alpha else ""
        ss, ms = _clean(r.sum_sq, scale), _clean(r.mean_sq, scale)
        f = 0.0 if (ss == 0.0 and r.f == r.f) else r.f
        rows.append([r.source, format_g(ss), r.df, format_g(ms), format_g(f), _p(r.p), mark])
    head = ["Source", "Sum of Squares", "df", "Mean Square", "F-value", "p-value", ""]
    return _table(head, rows, ["<", ">", ">", ">", ">", ">", "<"])


def format_equation(result, units: str = "coded") -> str:
    """The fitted equation in ``"coded"`` (letters) or ``"actual"`` (factor names) terms."""
    if units == "coded":
        coefs = dict(zip(result.coefficients.index, result.coefficients["coded"]))
    else:
        coefs = dict(result.actual_coefficients)
    lines = [f"{result.response} ="]
    scale = max((abs(v) for v in coefs.values() if math.isfinite(v)), default=0.0)
    for name, c in coefs.items():
        c = _clean(c, scale)
        if name == "Intercept":
            label = ""
        elif units == "coded":
            label = f" * {name}"
        else:
            from .terms import parse_term

            t = parse_term(name, result.space.letters)
            parts = []
            for p, f in zip(t.powers, result.space.factors):
                if p:
                    parts.append(f.name if p == 1 else f"{f.name}^{p}")
            label = " * " + " * ".join(parts)
        sign = "-" if c < 0 else "+"
        lines.append(f"  {sign} {format_g(abs(c), 6)}{label}")
    return "\n".join(lines)


def format_summary(result) -> str:
    """The whole text report of a fit."""
    out = []
    sp = result.space
    out.append(f"Response: {result.response}   runs: {result.n}   model: {result.model}"
               + (f"   blocks: {result.block} ({len(result.block_effects)})" if result.block else ""))
    out.append("Factors (coded -1 .. +1):")
    for f in sp.factors:
        out.append(f"  {f.letter}: {f.name}  {format_g(f.low, 6)} .. {format_g(f.high, 6)}")
    out.append("")
    out.append("ANOVA for the " + {"linear": "linear", "2fi": "2FI", "quadratic": "quadratic", "cubic": "cubic"}[result.model]
               + " model (partial sum of squares - Type III)")
    out.append(format_anova(result))
    out.append("")
    m = result.anova.set_index("source")
    notes = []
    if "Model" in m.index and m.loc["Model", "p"] == m.loc["Model", "p"]:
        fm, pm = m.loc["Model", "f"], m.loc["Model", "p"]
        notes.append(f"The Model F-value of {format_g(fm)} implies the model is "
                     + ("significant." if pm < 0.05 else "not significant relative to the noise."))
    notes.append("Terms marked * have p < 0.05 and are significant; p > 0.10 indicates a term is not significant.")
    if "Lack of Fit" in m.index and m.loc["Lack of Fit", "p"] == m.loc["Lack of Fit", "p"]:
        fl, pl = m.loc["Lack of Fit", "f"], m.loc["Lack of Fit", "p"]
        notes.append(f"The Lack of Fit F-value of {format_g(fl)} implies the Lack of Fit is "
                     + ("not significant relative to the pure error." if pl >= 0.05 else "significant."))
    if result.block:
        notes.append("Block variation is removed first (sequential SS) and kept out of the model.")
    notes.extend(result.notes)
    out.extend(notes)
    out.append("")
    s = result.statistics
    stat_rows = [
        ["Std. Dev.", format_g(s.std_dev), "R²", format_g(s.r2)],
        ["Mean", format_g(s.mean), "Adjusted R²", format_g(s.adj_r2)],
        ["C.V. %", format_g(s.cv_percent), "Predicted R²", format_g(s.pred_r2)],
        ["PRESS", format_g(s.press), "Adeq Precision", format_g(s.adeq_precision)],
    ]
    out.append("Fit statistics")
    out.append(_table(["", "", "", ""], stat_rows, ["<", ">", "<", ">"]).split("\n", 2)[2])
    out.append("")
    out.append("Coefficients in terms of coded factors (95 % CI)")
    rows = []
    cscale = float(result.coefficients["coded"].abs().max())
    for name, r in result.coefficients.iterrows():
        rows.append([name, format_g(_clean(r["coded"], cscale)), format_g(r["std_error"]), format_g(r["ci_low"]),
                     format_g(r["ci_high"]), (f"{r['vif']:.2f}" if r["vif"] == r["vif"] else ""), _p(r["p"])])
    out.append(_table(["Term", "Estimate", "Std Error", "95% CI Low", "95% CI High", "VIF", "p-value"], rows))
    if result.block_effects:
        out.append("Block effects (sum to zero): " + ", ".join(
            f"{k} ({result.block_levels[k]}) {format_g(v)}" for k, v in result.block_effects.items()))
    out.append("")
    out.append("Final equation in terms of coded factors")
    out.append(format_equation(result, "coded"))
    out.append("")
    out.append("Final equation in terms of actual factors")
    out.append(format_equation(result, "actual"))
    out.append("")
    sp_ = result.stationary_point
    out.append("Canonical analysis")
    if sp_.eigenvalues is None:
        out.append(f"  {sp_.note}")
    else:
        if sp_.coded is None:
            out.append(f"  {sp_.note}")
        else:
            out.append("  Stationary point (coded):  " + ", ".join(f"{k} = {format_g(v, 6)}" for k, v in sp_.coded.items()))
            out.append("  Stationary point (actual): " + ", ".join(f"{k} = {format_g(v, 6)}" for k, v in sp_.actual.items()))
            out.append(f"  Predicted response there:  {format_g(sp_.predicted, 6)}"
                       + ("" if sp_.inside else "  (outside the coded cube: extrapolation)"))
            out.append(f"  Kind: {sp_.kind}")
        out.append("  Eigenvalues: " + ", ".join(format_g(v, 6) for v in sp_.eigenvalues))
    return "\n".join(out) + "\n"
