"""The interactive report: a prediction profiler, an overlay (sweet-spot) plot and rotatable
3-D surfaces of one or several fitted responses, in one self-contained HTML page.

The page carries the fitted models themselves as data (per response: the model terms, the
coded coefficients b and the fit's interval form, :class:`rsm_lrg.model.contract.prediction.IntervalForm`),
and a small script computes, at the setting of the factor controls, exactly what
:meth:`rsm_lrg.model.FitResult.predict` computes with ``interval="both"``, whatever the kind
of model (OLS, blocked, categoric, mixture, transformed, REML whole plot or random block)::

    x  = row of the model matrix at the coded setting (rsm_lrg.terms.design_matrix)
    ŷ  = x · b          se = √(x' cov_se x)
    CI = ŷ ± t √(x' cov_mean x)          PI = ŷ ± t √(x' cov_mean x + s2_new)

with ``t`` the quantile at the fit's residual df (OLS, embedded) or at the Kenward–Roger df
of ``x`` (REML: the page computes ``2 / A₂(x)`` and the quantile itself)
(back-transformed, interval ends sorted, for a fit of a transformed response, as
:meth:`rsm_lrg.model.results.result.FitResult.predict` does). The figures are drawn with Plotly
(plotly.js from the ``plotly`` Python package, inlined so the page works offline); the page's
Content-Security-Policy allows its two scripts by their SHA-256 hash and nothing else: no
network, no other script, no ``eval``. Every piece of user text (column names, levels, file
names, the title) reaches the page escaped: through Jinja2's autoescaping, as JSON with
``<``, ``>`` and ``&`` written as ``\\u003c``..., through ``textContent`` in the script, and
with its markup escaped for Plotly's labels.

The page contract (stable; ../shared/INTERFACE.md): every factor control has
``data-factor="NAME"`` (``<input type="range">`` in actual units, or ``<select>`` of the
levels of a categoric factor) and reacts to ``input``/``change``; every displayed prediction
has ``data-prediction``, ``data-response="COL"`` and the unrounded ``data-value``,
``data-ci-low``, ``data-ci-high``, ``data-pi-low``, ``data-pi-high``.

The only arithmetic here is presentation: the optimum of each response and the
desirability optimum (from :mod:`rsm_lrg.optimize`) and the default overlay limits (the
observed range of each response) are computed once, in Python, and embedded.
"""

from __future__ import annotations

import base64
import hashlib
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["model_data", "interactive_html", "write_interactive_report", "Profiler", "profiler",
           "plotly_js", "notebook_reset", "PAGE_IDS"]

#: ``id`` of the page-wide sections of an interactive report, in page order (each response
#: then has a section ``response-<i>`` with its own tables and diagnostics).
PAGE_IDS = ("summary", "profiler", "overlay", "surfaces-3d", "data")

_TITLES = {"summary": "Summary", "profiler": "Prediction profiler", "overlay": "Overlay (sweet spot)",
           "surfaces-3d": "3-D surfaces and contours", "data": "Data"}
#: The titles that change on a mixture page (the figures are ternary plots and the trace).
_MIXTURE_TITLES = {"overlay": "Overlay on the ternary (sweet spot)",
                   "surfaces-3d": "Ternary contour, 3-D surface and trace"}


# -- the numbers the page computes with --------------------------------------------------------

def _finite_or_none(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def model_data(result, confidence: float = 0.95) -> dict:
    """The fitted model of one response as plain JSON-safe data, for the page's script.

    Parameters
    ----------
    result : FitResult
    confidence : float
        Level of the CI and PI (the t quantile embedded is ``t(1 - α/2, df_resid)``).

    Returns
    -------
    dict
        ``response``, ``factors`` (``name``, ``letter``, ``kind``, ``low``/``high`` or
        ``levels``), ``terms`` (``p``: numeric exponents, ``cat``: ``[[factor index, number of
        levels], ...]``, ``combos``: level indices of each column, ``diff``: ``[i, j]`` for a
        Scheffé full-cubic term, whose column is also multiplied by ``x_i - x_j``), ``b`` (coded
        coefficients), ``interval`` (the fit's
        :class:`~rsm_lrg.model.contract.prediction.IntervalForm` as data: the covariances of ``se_fit``
        and of the mean without block rows/columns, the variance of a new run, the df, and for
        a REML fit the Kenward–Roger parts from which the page computes the df of each
        point), ``df_text``, ``t`` (the quantile at a constant df; None for Kenward–Roger),
        ``transform`` (``None`` or ``name``/``lam``/``constant``) and ``coded_decimals`` (the
        rounding of :meth:`Factor.encode`).
    """
    from scipy import special

    from ..factors import CODED_DECIMALS

    if not 0.0 < confidence < 1.0:
        raise ParameterError("confidence", f"confidence must lie between 0 and 1, not {confidence!r}")
    fit = result
    tr = None if result.transform.identity else result.transform
    space = fit.space
    if not hasattr(fit, "interval_form") and hasattr(fit, "kriging_form"):
        return _kriging_data(fit, confidence)
    factors = []
    for f in space.factors:
        if getattr(f, "kind", "numeric") == "categoric":
            factors.append({"name": str(f.name), "letter": f.letter, "kind": "categoric",
                            "levels": [str(v) for v in f.levels]})
        else:
            factors.append({"name": str(f.name), "letter": f.letter, "kind": "numeric",
                            "low": float(f.low), "high": float(f.high)})
    terms = []
    for t in fit.terms:
        cat = [[int(i), len(lv)] for i, lv in t.cat]
        terms.append({"name": t.name, "p": [int(p) for p in t.numeric_powers], "cat": cat,
                      "diff": [int(i) for i in getattr(t, "diff", ())],  # a full-cubic AB(A-B): times x_i - x_j
                      "combos": [list(map(int, c)) for c in t.level_combinations()] if cat else []})
    b = fit.coefficients["coded"].to_numpy(dtype=float)
    form = fit.interval_form
    n_cols = sum(max(1, len(t["combos"])) for t in terms)
    if n_cols != len(b) or form.cov_mean.shape != (len(b), len(b)):
        raise ValueError(f"response {fit.response!r}: {len(b)} coefficients but {n_cols} model columns")
    df = form.df
    tq = float(special.stdtrit(df, 1 - (1 - confidence) / 2)) if df > 0 else float("nan")
    return {
        "response": str(fit.response),
        "factors": factors,
        "terms": terms,
        "b": [float(v) for v in b],
        "interval": form.to_dict(),
        "df_text": "Kenward–Roger df" if form.kenward_roger else f"{int(df) if df > 0 else 0} residual df",
        "t": _finite_or_none(tq),
        "confidence": float(confidence),
        "transform": None if tr is None else {"name": tr.name, "lam": tr.lam, "constant": float(tr.constant)},
        "coded_decimals": int(CODED_DECIMALS),
        "model": str(fit.model),
    }


def _factors_data(space) -> list[dict]:
    return [{"name": str(f.name), "letter": f.letter, "kind": "numeric", "low": float(f.low), "high": float(f.high)}
            for f in space.factors]


def _kriging_data(fit, confidence: float) -> dict:
    """:func:`model_data` of a Gaussian process: the trend as ``terms`` with ``b`` its GLS
    coefficients, and ``kriging`` (``GPResult.kriging_form``: kernel, length-scales, the runs,
    the weights and the factors the variance needs); ``t`` is the normal quantile, the codes
    are not rounded (``coded_decimals`` None), as ``GPResult.predict`` codes."""
    from scipy import special

    form = fit.kriging_form()
    terms = [{"name": t["name"], "p": t["p"], "cat": [], "diff": [], "combos": []} for t in form["trend"]]
    return {
        "response": str(fit.response), "factors": _factors_data(fit.space), "terms": terms,
        "b": form["beta"], "interval": None, "kriging": form,
        "df_text": "normal quantiles (kriging)",
        "t": float(special.ndtri(1 - (1 - confidence) / 2)), "confidence": float(confidence),
        "transform": None, "coded_decimals": None, "model": str(fit.label),
    }


def _json_for_script(obj) -> str:
    """JSON that is inert inside ``<script type="application/json">`` (``<``, ``>``, ``&``
    and the line separators written as escapes; NaN refused)."""
    text = json.dumps(obj, allow_nan=False, ensure_ascii=False, separators=(",", ":"))
    for ch, esc in (("<", "\\u003c"), (">", "\\u003e"), ("&", "\\u0026"), ("\u2028", "\\u2028"),
                    ("\u2029", "\\u2029")):
        text = text.replace(ch, esc)
    return text


def plotly_js() -> str:
    """plotly.js as shipped inside the ``plotly`` Python package (read, never imported).

    Raises ImportError with the install line when the package is missing.
    """
    import importlib.util

    spec = importlib.util.find_spec("plotly")
    if spec is None or spec.origin is None:
        raise ImportError("the interactive report needs plotly.js from the 'plotly' package: "
                          "pip install 'rsm-lrg[report]' (or pip install plotly), or write a static "
                          "report (--static)")
    path = Path(spec.origin).parent / "package_data" / "plotly.min.js"
    if not path.exists():
        raise ImportError(f"the plotly package has no {path.name} (looked in {path.parent})")
    return _read_cached(str(path))


_CACHE: dict = {}


def _read_cached(path: str) -> str:
    if path not in _CACHE:
        text = Path(path).read_text(encoding="utf-8")
        if "</script" in text.lower():  # would end the inline script early
            raise ValueError(f"{path}: contains '</script', cannot be inlined")
        _CACHE[path] = text
    return _CACHE[path]


def _app_js() -> str:
    from importlib import resources

    return resources.files("rsm_lrg.report").joinpath("templates", "profiler.js").read_text(encoding="utf-8")


def _sha256(text: str) -> str:
    return "'sha256-" + base64.b64encode(hashlib.sha256(text.encode("utf-8")).digest()).decode("ascii") + "'"


# -- optima --------------------------------------------------------------------------------------

def _optima(specs, optima=None):
    """The optima to show: those given (computed by the caller in the optimise layer,
    :func:`rsm_lrg.optimize.study.report_optima`), else found the same way here."""
    if optima is not None:
        return optima
    from ..optimize.study import report_optima

    return report_optima({str(s.result.response): s.result for s in specs},
                         {str(s.result.response): s.goal for s in specs},
                         {str(s.result.response): s.limits for s in specs})


def _setting_json(actual: Mapping) -> dict:
    out = {}
    for k, v in actual.items():
        out[str(k)] = v if isinstance(v, str) else float(v)
    return out


# -- the page ------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ResponseSpec:
    """One response of an interactive report: its fit, goal, overlay limits and label."""

    result: Any
    goal: Any = "minimize"
    limits: tuple | None = None
    label: str = ""
    extra: dict = field(default_factory=dict)


def _as_specs(results, goals, limits, labels) -> list[ResponseSpec]:
    if isinstance(results, Mapping):
        items = list(results.items())
    elif isinstance(results, (list, tuple)):
        items = [(str(getattr(r, "response", i)), r) for i, r in enumerate(results)]
    else:
        items = [(str(results.response), results)]
    if not items:
        raise ValueError("give at least one fitted response")
    names = [n for n, _ in items]
    if len(set(names)) != len(names):
        raise ValueError("each response may appear once in a report")

    def per(x, name, default):
        if x is None:
            return default
        if isinstance(x, Mapping):
            return x.get(name, default)
        if isinstance(x, (list, tuple)) and not (len(x) == 2 and all(isinstance(v, (int, float)) for v in x)):
            return x[names.index(name)] if names.index(name) < len(x) else default
        return x

    specs = []
    for name, r in items:
        lim = per(limits, name, None)
        if lim is not None:
            lo, hi = (None if v is None else float(v) for v in lim)
            if lo is not None and hi is not None and not lo <= hi:
                raise ParameterError("limits", f"limits of response {name!r}: low {lo:g} is above high {hi:g}")
            lim = (lo, hi)
        specs.append(ResponseSpec(result=r, goal=per(goals, name, "minimize"), limits=lim,
                                  label=str(per(labels, name, "") or "")))
    first = specs[0].result.space
    for s in specs[1:]:
        sp = s.result.space
        if list(sp.names) != list(first.names):
            raise ValueError(f"response {s.result.response!r} has factors {list(sp.names)}, but "
                             f"{specs[0].result.response!r} has {list(first.names)}: one report needs one factor set")
    return specs


def _controls(specs, mixture: dict | None = None) -> list[dict]:
    """One control per factor: a range slider over the union of the responses' factor ranges
    (actual units), or a level picker; a mixture component's slider spans the range the
    component takes in the region (starting at the reference blend, ``"component": true``)."""
    spaces = [s.result.space for s in specs]
    comps = {c["name"]: c for c in (mixture or {}).get("components", [])}
    out = []
    for j, f in enumerate(spaces[0].factors):
        if str(f.name) in comps:
            c = comps[str(f.name)]
            out.append({"name": str(f.name), "letter": f.letter, "kind": "numeric", "component": True,
                        "low": c["low"], "high": c["high"], "value": c["reference"], "center": c["reference"],
                        "step": "any"})
            continue
        if getattr(f, "kind", "numeric") == "categoric":
            out.append({"name": str(f.name), "letter": f.letter, "kind": "categoric",
                        "levels": [str(v) for v in f.levels], "value": str(f.levels[0])})
            continue
        lo = min(float(sp.factors[j].low) for sp in spaces)
        hi = max(float(sp.factors[j].high) for sp in spaces)
        out.append({"name": str(f.name), "letter": f.letter, "kind": "numeric", "low": lo, "high": hi,
                    "value": (lo + hi) / 2.0, "step": "any"})
    return out


def _observed(result) -> np.ndarray:
    """The finite observed responses, on the response's own scale (back-transformed when
    the fit is on a transformed scale)."""
    y = result.transform.inverse(np.asarray(result.y, dtype=float))
    return y[np.isfinite(y)]


def _observed_range(result) -> tuple[float, float]:
    y = _observed(result)
    return (float(y.min()), float(y.max())) if y.size else (float("nan"), float("nan"))


def _default_limits(result, goal, lo_obs: float, hi_obs: float) -> tuple:
    """Overlay limits when none are given: for ``minimize`` at most the observed median (the
    better half of the runs; no lower limit), for ``maximize`` at least the median,
    otherwise the observed range."""
    y = _observed(result)
    med = float(np.median(y)) if y.size else float("nan")
    g = str(goal).strip().lower() if goal is not None else ""
    if g.startswith("min"):
        return (None, med)
    if g.startswith("max"):
        return (med, None)
    return (lo_obs, hi_obs)


def page_data(specs, *, confidence: float = 0.95, desirability=True, optima=None) -> tuple[dict, list[str]]:
    """The JSON the page's script reads, and notes for the page (optima that could not be found).
    ``optima`` (:class:`rsm_lrg.optimize.study.ReportOptima`) are shown as given."""
    notes = []
    models, shown = [], {}
    opt = _optima(specs, optima)
    for s in specs:
        m = model_data(s.result, confidence)
        lo_obs, hi_obs = _observed_range(s.result)
        lim = s.limits or _default_limits(s.result, s.goal, lo_obs, hi_obs)
        m["limits"] = [_finite_or_none(v) if v is not None else None for v in lim]
        m["observed"] = [_finite_or_none(lo_obs), _finite_or_none(hi_obs)]
        m["goal"] = str(s.goal)
        m["label"] = s.label or m["response"]
        models.append(m)
        best = opt.single.get(m["response"])
        if best is None:
            notes.append(f"No optimum of {m['response']}: {opt.missing.get(m['response'], 'not computed')}")
        else:
            shown[m["response"]] = {"setting": _setting_json(best.actual), "predicted": float(best.predicted),
                                    "goal": str(best.goal)}
    desir = None
    if desirability and len(specs) > 1 and all(s.goal is not None for s in specs):
        d = opt.desirability
        if d is not None:
            desir = {"setting": _setting_json(d.actual), "desirability": float(d.desirability),
                     "predicted": {k: float(v) for k, v in d.predicted.items()}}
        elif opt.desirability_missing:
            notes.append(f"No desirability optimum: {opt.desirability_missing}")
    mix = mixture_data(specs)
    data = {"models": models, "controls": _controls(specs, mix), "optima": shown, "desirability": desir,
            "mixture": mix}
    return data, notes


def mixture_data(specs) -> dict | None:
    """What the page needs to keep a blend on the simplex and draw the ternary and trace plots
    (``None`` when the fits are not mixture fits): the total, each component's bounds and the
    range it takes in the region (:func:`rsm_lrg.optimize.mixture.limits_of`), the region's
    rows ``G x <= h`` in coded units, the reference blend (the region's centroid), each run's
    blend, and per response the trace along the Cox direction from the reference
    (:func:`rsm_lrg.model.readings.mixture_trace.mixture_trace`). Ordered things are arrays of
    records, never objects keyed by a name."""
    first = specs[0].result
    if not first.space.has_components:
        return None
    from ..model.build.mixture_region import mixture_region
    from ..model.readings.mixture_trace import mixture_trace
    from ..optimize.mixture import limits_of

    region = mixture_region(first.space)
    ranges = limits_of(region)
    ref = region.to_actual(region.centroid())
    comps = [first.space.factors[j] for j in region.comps]
    traces = []
    for s in specs:
        tr = mixture_trace(s.result)
        traces.append({"response": str(s.result.response), "direction": tr.direction,
                       "curves": [{"name": str(c.name), "letter": c.letter,
                                   "deviation": [float(v) for v in tr.deviation[c.name]],
                                   "predicted": [_finite_or_none(v) for v in tr.predicted[c.name]],
                                   "effect": float(tr.effects[c.name]), "gradient": float(tr.gradients[c.name]),
                                   "low": float(tr.low[c.name]), "high": float(tr.high[c.name])} for c in comps]})
    names = [str(c.name) for c in comps]
    data = first.data
    points = [[float(v) for v in row] for row in np.asarray(data[[c.name for c in comps]], dtype=float)]
    return {"total": float(region.total),
            "components": [{"name": str(c.name), "letter": c.letter, "lower": float(c.lower),
                            "upper": float(min(c.upper, c.total)),
                            "low": ranges[c.name][0], "high": ranges[c.name][1], "reference": ref[c.name]}
                           for c in comps],
            "process": [str(f.name) for j, f in enumerate(first.space.factors) if j not in region.comps],
            "reference": [ref[n] for n in names],
            "G": [[float(v) for v in row] for row in region.G], "h": [float(v) for v in region.h],
            "rows": list(region.rows), "points": points, "traces": traces}


def _response_sections(specs, source_name, static: bool = False, hold: str = "center", optima=None) -> list[dict]:
    """Per response: the static tables and diagnostics of today's report; the static 3-D
    surfaces and contours of every pair only with ``static`` (the live page draws them)."""
    from .fit_report import diagnostics_section, optimum_section, surface_figures, table_sections

    found = _optima(specs, optima)
    out = []
    for i, s in enumerate(specs, start=1):
        fit = s.result
        best = found.single.get(str(fit.response))
        why = found.missing.get(str(fit.response), "not computed")
        ctx = table_sections(fit, source_name, None)
        diag, diag_note = diagnostics_section(fit)
        opt, opt_missing = optimum_section(fit, best) if best is not None else (None, why)
        tr = None if fit.transform.identity else fit.transform
        surfaces, surfaces_note = surface_figures(fit, hold, best) if static else ([], "")
        out.append(ctx | {"surfaces": surfaces, "surfaces_note": surfaces_note,
            "index": i, "response": str(s.result.response), "diagnostics": diag, "diagnostics_note": diag_note,
            "optimum": opt, "optimum_missing": opt_missing,
            "transform_note": (f"Fitted to the {tr.label}-transformed response: ANOVA, coefficients and "
                               "equations are on that scale; predictions and intervals in the profiler are "
                               "back-transformed.") if tr is not None else "",
        })
    return out


def _start(data: dict, start: str) -> None:
    """Put the controls' first values at the centre or at the optimum (the desirability
    optimum with several responses, else the first response's optimum)."""
    if start not in ("center", "optimum"):
        raise ValueError(f"start must be 'center' or 'optimum', not {start!r}")
    if start == "center":
        return
    opt = (data["desirability"] or {}).get("setting") or next(
        (o["setting"] for o in data["optima"].values()), None)
    if not opt:
        return
    for c in data["controls"]:
        if c["name"] in opt:
            c["value"] = opt[c["name"]] if c["kind"] == "categoric" else float(opt[c["name"]])


def interactive_context(results, *, goals=None, limits=None, labels=None, title: str | None = None,
                        source_name: str | None = None, confidence: float = 0.95, tables: bool = True,
                        start: str = "center", static: bool = False, optima=None, region=None,
                        loo=None) -> dict:
    """Everything the interactive page shows (plain values), the scripts not included;
    ``optima``, ``region`` and ``loo`` as for :func:`interactive_html`."""
    from .fit_report import data_table, run_numbers

    specs = _as_specs(results, goals, limits, labels)
    optima = _optima(specs, optima)  # found once for the page and the response sections
    data, notes = page_data(specs, confidence=confidence, optima=optima)
    if tables and not all(hasattr(s.result, "anova") for s in specs):
        tables = False  # ANOVA, coefficients, equations and residual diagnostics are a polynomial's
        notes.append("No ANOVA, coefficient or diagnostic tables: a Gaussian process has none (its "
                      "hyper-parameters and leave-one-out check: rsm-lrg fit --model gp)")
    if region:
        data["region"] = region
    _start(data, start)
    names = [m["response"] for m in data["models"]]
    first = specs[0].result
    space = first.space
    numeric = [c for c in data["controls"] if c["kind"] == "numeric" and not c.get("component")]
    mixture = data["mixture"]
    summary = [("Responses", ", ".join(names)), ("Data", source_name or "a DataFrame"),
               ("Runs", str(first.n)),
               ("Factors", ", ".join(f"{f.letter} = {f.name}" for f in space.factors))]
    if region:
        summary.append(("Region (optima, overlay and deepest setting keep to it)", "; ".join(region["text"])))
    for m in data["models"]:
        summary.append((f"Model of {m['response']}", f"{m['model']}, {len(m['b'])} coefficients, "
                                                     f"{m['df_text']}"
                        + (f", {m['transform']['name']} transform" if m["transform"] else "")))
    _, runs_from = run_numbers(first)
    return {
        "title": title or ("Interactive response surface report: " + ", ".join(names)),
        "subtitle": (f"{len(names)} response{'s' if len(names) > 1 else ''} over {len(space)} factors from "
                     f"{first.n} runs" + (f" ({source_name})" if source_name else "") + "."),
        "toc": [(sid, _MIXTURE_TITLES.get(sid, _TITLES[sid]) if mixture else _TITLES[sid]) for sid in PAGE_IDS
                if not (static and sid in ("profiler", "overlay", "surfaces-3d"))]
        + [(f"response-{i}", f"Response {n}") for i, n in enumerate(names, start=1)],
        "summary": summary,
        "controls": data["controls"],
        "numeric_controls": numeric,
        "models": data["models"],
        "optima": data["optima"],
        "desirability": data["desirability"],
        "notes": notes,
        "confidence_pct": f"{100 * confidence:g}",
        "data_json": _json_for_script(data),
        "data": data_table(first, runs_from) if tables else None,
        "responses": _response_sections(specs, source_name, static, start, optima) if tables else [],
        "static": bool(static),
        "mixture": mixture,
        "effects": _effects_rows(mixture) if mixture else [],
        "loo": [{"response": str(r), **c.to_dict()} for r, c in (loo or {}).items()],
    }


def _effects_rows(mixture: dict) -> list[dict]:
    """The effects table of the mixture section: per response and component, the total
    effect and the slope along the Cox direction from the reference blend."""
    rows = []
    for tr in mixture["traces"]:
        for c in tr["curves"]:
            rows.append({"response": tr["response"], "component": f"{c['letter']}: {c['name']}",
                         "reference": next(m["reference"] for m in mixture["components"] if m["name"] == c["name"]),
                         "low": c["low"], "high": c["high"], "effect": c["effect"], "gradient": c["gradient"]})
    return rows


def interactive_html(results, *, goals=None, limits=None, labels=None, title: str | None = None,
                     source_name: str | None = None, confidence: float = 0.95, tables: bool = True,
                     start: str = "center", static: bool = False, optima=None, region=None, loo=None) -> str:
    """The interactive report of one or several fitted responses (a string).

    Parameters
    ----------
    results : FitResult, a list of them, or ``{response: fit}``
        The fitted responses; they must share the factors (each its own model: order,
        reduced terms, transform).
    goals : str, list or mapping, optional
        Goal per response (``"minimize"``, ``"maximize"``, ``"target=V"``; default
        minimize) for the jump-to-optimum buttons and the desirability optimum;
        ``None`` for a response: no optimum.
    limits : (low, high), list or mapping, optional
        Overlay (and desirability) limits per response [response units]; default the
        observed range. Editable in the page.
    labels : mapping, optional
        Display labels per response.
    title, source_name : str, optional
    confidence : float
        Level of the CI and PI shown (0.95).
    tables : bool
        Include each response's ANOVA, statistics, coefficients, equations and diagnostics.
    start : {"center", "optimum"}
        Where the profiler starts (the optimum: the desirability optimum with several
        responses); with ``static``, where the factors off a surface's axes are held.
    static : bool
        A page without scripts (no profiler, overlay or live figures) with a static 3-D
        surface and contour of every pair of factors per response, for printing and archives.
    optima : rsm_lrg.optimize.study.ReportOptima, optional
        The optima to show, computed by the caller (``rsm-lrg report`` does); when not given
        they are found by :func:`rsm_lrg.optimize.study.report_optima` from ``goals``.
    region : dict, optional
        The region the page keeps to (:func:`rsm_lrg.report.region.region_data`: ``report
        --constraint/--bound``): "deepest inside every limit" and the overlay's shading stay
        inside it; pass ``optima`` found inside it too.
    loo : mapping, optional
        ``{response: LooComparison}`` (:func:`rsm_lrg.model.choice.loo_compare.compare_with_polynomials`):
        a Gaussian process's leave-one-out beside the polynomial orders' PRESS on the same runs,
        shown in the summary (``rsm-lrg report --model gp`` gives it).

    Returns
    -------
    str
        The page (HTML).
    """
    ctx = interactive_context(results, goals=goals, limits=limits, labels=labels, title=title,
                              source_name=source_name, confidence=confidence, tables=tables, start=start,
                              optima=optima, static=static, region=region, loo=loo)
    return _render(ctx)


_CSP_REST = "worker-src 'none'; connect-src 'none'; base-uri 'none'; form-action 'none'; object-src 'none'"


def _render(ctx: dict) -> str:
    """The whole page of :func:`interactive_context`'s ``ctx``: plotly.js and the page's
    script inlined, allowed by their hashes."""
    from markupsafe import Markup

    from .. import __version__
    from .html import render_page

    if ctx["static"]:
        csp = ("default-src 'none'; img-src data:; style-src 'unsafe-inline'; script-src 'none'; "
               "base-uri 'none'; form-action 'none'")
        return render_page("interactive.html.j2", **ctx, csp=csp, lib_js="", app_js="", assets_json="",
                           inline_css=True,
                           footer=f"Made by rsm-lrg {__version__}. Self-contained: no scripts, no network requests.")
    lib, app = plotly_js(), _app_js()
    csp = ("default-src 'none'; img-src data: blob:; style-src 'unsafe-inline'; "
           f"script-src {_sha256(lib)} {_sha256(app)}; {_CSP_REST}")
    ctx = dict(ctx, data_json=Markup(ctx["data_json"]))  # already inert (see _json_for_script)
    return render_page("interactive.html.j2", **ctx, csp=csp, lib_js=Markup(lib), app_js=Markup(app),
                       assets_json="", inline_css=True,
                       footer=f"Made by rsm-lrg {__version__}. Self-contained: plotly.js is inlined; "
                              "the page makes no network requests.")


def _template_text(name: str) -> str:
    from importlib import resources

    text = resources.files("rsm_lrg.report").joinpath("templates", name).read_text(encoding="utf-8")
    if "</script" in text.lower() or "<!--" in text:  # would end (or confuse) an inline script block
        raise ValueError(f"templates/{name}: contains '</script' or '<!--', cannot be inlined")
    return text


def _page_css() -> str:
    return _template_text("report.css") + "\n" + _template_text("interactive.css")


def _render_notebook(ctx: dict) -> tuple[str, tuple[tuple[str, str, str], ...]]:
    """The page of ``ctx`` for a notebook frame, without its heavy parts, and those parts.

    Returns ``(page, assets)``: ``assets`` are ``(kind, sha256 hex, text)`` for the page's
    style, plotly.js and the page's script, in the order the frame inserts them; the page
    carries a small loader that asks the notebook page (its parent) for them by hash, and a
    Content-Security-Policy that lets a script run only when its text has the expected
    SHA-256 (plotly.js, the page's script, the loader).
    """
    from markupsafe import Markup

    from .. import __version__
    from .html import render_page

    lib, app, css = plotly_js(), _app_js(), _page_css()
    assets = (("css", hashlib.sha256(css.encode("utf-8")).hexdigest(), css),
              ("js", hashlib.sha256(lib.encode("utf-8")).hexdigest(), lib),
              ("js", hashlib.sha256(app.encode("utf-8")).hexdigest(), app))
    loader = _template_text("notebook_loader.js")
    csp = ("default-src 'none'; img-src data: blob:; style-src 'unsafe-inline'; "
           f"script-src {_sha256(lib)} {_sha256(app)} {_sha256(loader)}; {_CSP_REST}")
    ctx = dict(ctx, data_json=Markup(ctx["data_json"]))
    page = render_page("interactive.html.j2", **ctx, csp=csp, inline_css=False, lib_js=Markup(loader), app_js="",
                       assets_json=Markup(_json_for_script([[k, h] for k, h, _ in assets])),
                       footer=f"Made by rsm-lrg {__version__}. plotly.js and the page's script come from "
                              "the notebook page, checked by their SHA-256; .save(path) writes a "
                              "self-contained page.")
    return page, assets


def write_interactive_report(results, path, *, force: bool = False, **kwargs) -> Path:
    """Write :func:`interactive_html` to ``path`` atomically (refuses to overwrite unless
    ``force``). Returns the path written.

    Parameters
    ----------
    results : FitResult, list or mapping
        A fit, a list of them, or ``{response: fit}``.
    path : str or pathlib.Path
        The page to write.
    force : bool, default False
        Replace an existing file.
    **kwargs
        As for :func:`interactive_html`.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    from ..io import check_output, write_output

    p = Path(path)
    check_output(p, force=force)
    return write_output(p, interactive_html(results, **kwargs), force=force)


# -- notebook --------------------------------------------------------------------------------------

#: SHA-256 (hex) of the shared assets this kernel session has already carried into the
#: notebook page (see :meth:`Profiler._repr_html_`).
_SENT: set[str] = set()


def notebook_reset() -> None:
    """Make the next displayed :class:`Profiler` carry plotly.js (and the page's script and
    style) into the notebook again: after the output that carried them was cleared, or in a
    notebook reopened without them."""
    _SENT.clear()


def _srcdoc(page: str) -> str:
    """``page`` as the value of a single-quoted ``srcdoc`` attribute (``&`` and ``'`` escaped:
    the only characters that end or change a single-quoted attribute value)."""
    return page.replace("&", "&amp;").replace("'", "&#39;")


@dataclass(frozen=True)
class Profiler:
    """The interactive page of one or several fits, for a notebook.

    ``_repr_html_`` shows the page in a sandboxed ``<iframe srcdoc>`` (its scripts run inside
    the frame under the page's own Content-Security-Policy; no server, no network). plotly.js
    (4.8 MB) and the page's script and style travel into the notebook once per kernel
    session: the first profiler displayed carries them as inert text blocks
    (``<script type="text/plain" data-rsm-lrg-asset="SHA-256">``) with a small script that
    hands them to any profiler frame asking for them by hash (``postMessage``); every
    profiler's frame (a few kB of page: its controls and model numbers) asks and inserts
    them, and its policy runs a script only when its SHA-256 is the expected one. A saved
    notebook keeps the blocks in the first profiler's output. :func:`notebook_reset` makes
    the next display carry them again. :meth:`save` writes the whole self-contained page.

    Attributes
    ----------
    html : str
        The whole page (:func:`interactive_html`).
    height : int
        Height of the notebook frame [px].
    notebook : str
        The page for the notebook frame, without the shared assets (empty: the frame shows
        ``html``).
    assets : tuple of (kind, sha256 hex, text)
        The shared assets ``notebook`` asks for.
    """

    html: str = field(repr=False)
    height: int = 900
    notebook: str = field(default="", repr=False)
    assets: tuple = field(default=(), repr=False)

    def _repr_html_(self) -> str:
        frame = (f"<iframe srcdoc='{_srcdoc(self.notebook or self.html)}' style='width: 100%; "
                 f"height: {int(self.height)}px; border: 1px solid #ccc' "
                 "sandbox='allow-scripts allow-downloads'></iframe>")
        if not self.notebook:
            return frame
        blocks = []
        for _kind, sha, text in self.assets:
            if sha not in _SENT:
                blocks.append(f'<script type="text/plain" data-rsm-lrg-asset="{sha}">{text}</script>')
        _SENT.update(sha for _, sha, _ in self.assets)
        return "".join(blocks) + f"<script>{_template_text('notebook_host.js')}</script>" + frame

    def save(self, path, *, force: bool = False) -> Path:
        """Write the page to ``path`` (atomically; an existing file only with ``force``)."""
        from ..io import write_output

        return write_output(Path(path), self.html, force=force)


def profiler(results, *, height: int = 900, tables: bool = False, **kwargs) -> Profiler:
    """A :class:`Profiler` of ``results`` (see :func:`interactive_html`; the per-response
    tables are left out unless ``tables=True``, to keep the notebook light).

    This is ``FitResult.profiler()``.

    Parameters
    ----------
    results : FitResult, list or mapping
        A fit, a list of them, or ``{response: fit}``.
    height : int, default 900
        The frame's height in the notebook [px].
    tables : bool, default False
        Add the per-response tables.
    **kwargs
        As for :func:`interactive_html`.

    Returns
    -------
    Profiler
        Shown inline by a notebook; ``.save(path)`` writes the page.
    """
    ctx = interactive_context(results, tables=tables, **kwargs)
    if ctx["static"]:
        return Profiler(html=_render(ctx), height=height)
    notebook, assets = _render_notebook(ctx)
    return Profiler(html=_render(ctx), height=height, notebook=notebook, assets=assets)
