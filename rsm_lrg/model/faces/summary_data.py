"""One summary of a fit as data: the tables and the Design-Expert sentences under them.

:func:`summary_data` builds it once from a :class:`~rsm_lrg.model.results.result.FitResult`; the text
face (:func:`rsm_lrg.model.faces.text.format_summary`) and the HTML report
(:mod:`rsm_lrg.report.fit_report`) both render it, so the numbers, the notes, their
thresholds and the round-off rule (:func:`rsm_lrg.present.clean`, applied once by
:func:`rsm_lrg.present.clean_anova` when the ANOVA is built) are the same on every face.

>>> import rsm_lrg
>>> s = summary_data(rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min"))
>>> s.anova_notes[0][:56]
'The Model F-value of 26.03 implies the model is signific'
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from ...present import format_f, format_number, table_records

__all__ = ["SummaryData", "summary_data", "ALPHA", "ALPHA_INSIGNIFICANT"]

#: A term, the model or lack of fit is significant below this p-value (Design-Expert).
ALPHA = 0.05
#: Above this p-value a term is "not significant" (Design-Expert's second threshold).
ALPHA_INSIGNIFICANT = 0.10
#: The Predicted and Adjusted R² agree "reasonably" within this difference (Design-Expert).
R2_AGREEMENT = 0.2
#: Adequate precision above this signals an adequate signal-to-noise ratio (Design-Expert).
ADEQUATE_PRECISION = 4.0


@dataclass(frozen=True)
class SummaryData:
    """A fit's summary as data (frozen): what every face shows.

    Attributes
    ----------
    anova_title : str
        ``"ANOVA for the quadratic model (partial sum of squares - Type III)"``.
    anova : list of dict
        The ANOVA's rows, ``{source, sum_sq, df, mean_sq, f, p}`` each (round-off cleaned
        once, :func:`rsm_lrg.present.clean_anova`; ``result.anova`` is the same as a DataFrame).
    anova_notes : tuple of str
        Design-Expert's sentences on the model, the terms and lack of fit, then the fit's
        own notes (why there is no lack-of-fit test, blocks, ...).
    significant_terms : tuple of str
        The terms with p < :data:`ALPHA`.
    statistics : tuple of (str, float, str)
        ``(label, value, what it is)``: Std. Dev., Mean, C.V. %, R², Adjusted R²,
        Predicted R², PRESS, Adeq Precision.
    statistics_notes : tuple of str
        Design-Expert's sentences on Predicted vs Adjusted R² and adequate precision.
    anova_records : tuple
        The ANOVA's rows as records (:func:`rsm_lrg.present.table_records`), for the faces
        that read them row by row.
    """

    anova_title: str
    anova: Any
    anova_notes: tuple[str, ...]
    significant_terms: tuple[str, ...]
    statistics: tuple[tuple[str, float, str], ...]
    statistics_notes: tuple[str, ...]
    anova_records: tuple = ()


def _chance(p: float) -> str:
    return "less than a 0.01%" if p < 1e-4 else f"a {100 * p:.2f}%"


def _finite(x: Any) -> bool:
    try:
        return math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


def summary_data(result: Any) -> SummaryData:
    """The :class:`SummaryData` of a fit (see the module docstring)."""
    named = {"linear": "linear", "2fi": "2FI", "quadratic": "quadratic", "cubic": "cubic",
             "mixture-linear": "Scheffé linear mixture", "mixture-quadratic": "Scheffé quadratic mixture",
             "special-cubic": "Scheffé special cubic mixture",
             "mixture-cubic": "Scheffé full cubic mixture"}.get(result.model)
    mixture = result.space.has_components
    if mixture and named and any(not hasattr(f, "pseudo_range") for f in result.space.factors):
        named += " crossed with the linear process"
    title = ("ANOVA for the " + (f"{named} model" if named else "model of the terms chosen")
             + (" (Linear Mixture sequential, other terms partial sum of squares - Type III; about the mean)"
                if mixture else " (partial sum of squares - Type III)")
             + ("" if result.intercept or mixture else "; no intercept: the model row and total are uncorrected"))
    title = result.reading.anova_title or title  # a REML fit's: its Kenward-Roger tests
    anova = result.anova_rows
    records = table_records(anova)
    rows = {r.source: r for r in records}
    notes: list[str] = []
    m = rows.get("Model")
    if m is not None and _finite(m.p):
        verdict = "is significant" if m.p < ALPHA else "is not significant relative to the noise"
        notes.append(f"The Model F-value of {format_f(m.f)} implies the model {verdict}. There is "
                     f"{_chance(m.p)} chance that an F-value this large could occur due to noise.")
    names = {t.name for t in result.model_terms}
    terms = [r for r in records if r.source in names]
    sig = tuple(str(r.source) for r in terms if _finite(r.p) and r.p < ALPHA)
    if terms and any(_finite(r.p) for r in terms):
        notes.append(f"P-values less than {ALPHA:.4f} indicate model terms are significant. In this case "
                     + (", ".join(sig) + (" are" if len(sig) > 1 else " is") if sig else "no term is")
                     + f" significant. Values greater than {ALPHA_INSIGNIFICANT:.4f} indicate the model terms "
                       "are not significant.")
    lof = rows.get("Lack of Fit")
    if lof is not None and _finite(lof.p):
        verdict = "not significant" if lof.p >= ALPHA else "significant"
        notes.append(f"The Lack of Fit F-value of {format_f(lof.f)} implies the Lack of Fit is {verdict} "
                     f"relative to the pure error. There is {_chance(lof.p)} chance that a Lack of Fit "
                     "F-value this large could occur due to noise."
                     + (" Non-significant lack of fit is good: the model fits." if lof.p >= ALPHA else ""))
    if result.block:
        notes.append("Block variation is removed first (sequential SS) and kept out of the model.")
    notes.extend(str(n) for n in result.notes)

    s = result.statistics
    stats = (
        ("Std. Dev.", s.std_dev, "√(residual mean square) [response units]"),
        ("Mean", s.mean, "mean response [response units]"),
        ("C.V. %", s.cv_percent, "100 · Std. Dev. / Mean"),
        ("R²", s.r2, "" if result.intercept or result.space.has_components else "uncorrected (no intercept)"),
        ("Adjusted R²", s.adj_r2, ""),
        ("Predicted R²", s.pred_r2, "from PRESS"),
        ("PRESS", s.press, "prediction error sum of squares"),
        ("Adeq Precision", s.adeq_precision, f"signal-to-noise ratio; above {ADEQUATE_PRECISION:g} is desirable"),
    )
    snotes: list[str] = []
    if _finite(s.pred_r2) and _finite(s.adj_r2):
        pr, ar = format_number(s.pred_r2, 4), format_number(s.adj_r2, 4)
        if abs(s.adj_r2 - s.pred_r2) < R2_AGREEMENT:
            snotes.append(f"The Predicted R² of {pr} is in reasonable agreement with the Adjusted R² of {ar}; "
                          f"i.e. the difference is less than {R2_AGREEMENT:g}.")
        else:
            snotes.append(f"The Predicted R² of {pr} is not as close to the Adjusted R² of {ar} as one might "
                          f"expect (difference ≥ {R2_AGREEMENT:g}): this may indicate a large block effect or a "
                          "possible problem with the model and/or data.")
    if _finite(s.adeq_precision):
        ok = "indicates an adequate signal" if s.adeq_precision > ADEQUATE_PRECISION else "indicates an inadequate signal"
        snotes.append(f"Adeq Precision measures the signal-to-noise ratio; a ratio greater than {ADEQUATE_PRECISION:g} "
                      f"is desirable. The ratio of {format_number(s.adeq_precision, 5)} {ok}.")
    return SummaryData(anova_title=title, anova=anova, anova_notes=tuple(notes), significant_terms=sig,
                       statistics=stats, statistics_notes=tuple(snotes), anova_records=tuple(records))
