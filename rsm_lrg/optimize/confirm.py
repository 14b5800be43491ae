"""Confirmation runs: do n new runs at chosen settings agree with the model?

At the settings ``x0`` (coded row ``x``), the mean ``ȳ`` of ``n`` confirmation runs is
compared with the prediction interval for the mean of n future runs (Design-Expert's
"Confirmation" node; Montgomery, *Design and Analysis of Experiments*, Sec. 11.3.4;
Myers, Montgomery & Anderson-Cook, Eq. 2.40 generalised to a mean of n runs):

    ŷ ± t(1 - α/2, ν) · √( σ² (1/n + x'(X'X)⁻¹x) ),

with σ² the residual mean square on ν df. For a REML fit (split-plot whole plots or random
blocks, :mod:`rsm_lrg.model.engines.mixed`) the n runs are taken to be made in one new whole plot
(block): ``√( x'Φ_A x + σ²_wp + σ²/n )`` with Kenward–Roger's adjusted covariance ``Φ_A``
and ν its den df for the mean at ``x``. The run mean is **inside** when it lies in that
interval. The relative error is ``100 · (ȳ - ŷ) / ŷ`` [%] against the exact prediction,
and against a ``reference`` value when given (a published, rounded prediction).

**Transformed response** (a :class:`~rsm_lrg.model.results.result.FitResult` fitted to
``z = g(y + k)``): as Design-Expert does, the interval is computed on the transformed scale,
``ẑ ± t · √(σ_z² (1/n + x'(X'X)⁻¹x))``, and its ends are back-transformed (swapped for a
decreasing transform); the prediction shown is ``g⁻¹(ẑ)`` (the median on the original scale).
The runs are judged on the same scale: inside when the mean of ``g(y_i + k)`` lies in the
transformed interval, i.e. when ``g⁻¹(mean g(y_i + k))`` (the geometric mean for a log) lies
in the back-transformed one; for a single run this is simply ``y`` in the interval.

Paper check (Sec. 4.3): at the optimum (0.0001 m, 0.04 m, 0.4 m/s, 20 m/s²) one run gave
κ = 0.024 °C/min: 4.35 % above the rounded 0.023, 5.11 % above the exact 0.022833, inside
the 95 % PI 0.0159–0.0298.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError
from ..factors import finite_float
from ..terms import design_matrix

__all__ = ["confirm", "ConfirmationResult", "parse_settings"]


#: A setting at most this many half-ranges from the centre of its factor's range can be
#: predicted (coded values and their squares and cubes stay far from overflow).
MAX_CODED_REACH = 1e6


def _check_reach(f, value: float) -> None:
    """ValueError (``setting for 'x': ...``) when ``value`` lies more than
    :data:`MAX_CODED_REACH` half-ranges from the centre of factor ``f``'s range."""
    with np.errstate(over="ignore", invalid="ignore"):
        reach = abs((np.float64(value) - f.center) / f.half_range)
    if not (np.isfinite(reach) and reach <= MAX_CODED_REACH):
        raise ParameterError("setting", f"setting for {f.name!r}: {value:g} lies too far outside the factor's range "
                         f"{f.low:g} .. {f.high:g} to predict at (more than {MAX_CODED_REACH:g} half-ranges "
                         "from its centre)")


def parse_settings(space, at) -> dict:
    """``{factor name: value}`` (actual units) from a mapping keyed by name or letter or
    from ``["NAME=VALUE", ...]``; every factor must be given exactly once (a categoric
    factor by one of its levels)."""
    items: dict = {}
    if isinstance(at, Mapping):
        pairs = list(at.items())
    else:
        pairs = []
        for s in at or []:
            if "=" not in str(s):
                raise ParameterError("setting", f"setting {s!r}: expected NAME=VALUE")
            k, v = str(s).split("=", 1)
            pairs.append((k.strip(), v.strip()))
    for key, v in pairs:
        try:
            f = space[key]
        except KeyError:
            raise ParameterError("setting", f"setting for {key!r}: no such factor (factors: {', '.join(space.names)})") from None
        val = f.levels[f.index(v)] if f.kind == "categoric" else finite_float(v, f"setting for {f.name!r}")
        if f.kind != "categoric":
            _check_reach(f, val)
        if f.name in items:
            raise ValueError(f"factor {f.name!r} is set more than once")
        items[f.name] = val
    missing = [n for n in space.names if n not in items]
    if missing:
        raise ParameterError("setting", f"no setting for factor(s) {', '.join(map(repr, missing))}; give NAME=VALUE for each")
    return items


@dataclass(frozen=True)
class ConfirmationResult:
    """Outcome of confirmation runs (frozen).

    Attributes
    ----------
    response : str
    actual, coded : dict
        Settings [actual units] and [coded units].
    predicted : float
        ŷ at the settings (average block) [response units].
    observed : tuple of float
        The confirmation runs [response units].
    n : int
    mean : float
        Mean of the runs.
    confidence : float
    pi : tuple of float
        Prediction interval for the mean of n runs.
    se_mean : float
        √(σ² (1/n + x'(X'X)⁻¹x)).
    inside : bool
    relative_error_percent : float
        ``100 (mean - ŷ) / ŷ`` [%].
    reference : float or None
    relative_error_vs_reference_percent : float or None
    extrapolation : bool
        Whether a setting lies outside the coded cube [-1, 1].
    transform : str or None
        The response transform of the model (``None``: untransformed).
    predicted_transformed, pi_transformed, se_transformed, mean_transformed
        With a transform: ``ẑ``, its interval, the standard error and the mean of
        ``g(y_i + k)`` on the transformed scale (``se_mean`` is then this standard error).
    mean_back_transformed : float or None
        ``g⁻¹(mean g(y_i + k))``: the run mean on the scale the interval judges.
    """

    response: str
    actual: dict
    coded: dict
    predicted: float
    observed: tuple
    n: int
    mean: float
    confidence: float
    pi: tuple
    se_mean: float
    inside: bool
    relative_error_percent: float
    reference: float | None = None
    relative_error_vs_reference_percent: float | None = None
    extrapolation: bool = False
    warnings: tuple = field(default=())
    transform: str | None = None
    predicted_transformed: float | None = None
    pi_transformed: tuple | None = None
    se_transformed: float | None = None
    mean_transformed: float | None = None
    mean_back_transformed: float | None = None

    def to_dict(self) -> dict:
        return {"response": self.response, "actual": dict(self.actual), "coded": dict(self.coded),
                "predicted": self.predicted, "observed": list(self.observed), "n": self.n, "mean": self.mean,
                "confidence": self.confidence, "pi": [self.pi[0], self.pi[1]], "se_mean": self.se_mean,
                "inside": self.inside, "relative_error_percent": self.relative_error_percent,
                "reference": self.reference,
                "relative_error_vs_reference_percent": self.relative_error_vs_reference_percent,
                "extrapolation": self.extrapolation, "warnings": list(self.warnings),
                "transform": self.transform, "predicted_transformed": self.predicted_transformed,
                "pi_transformed": None if self.pi_transformed is None else list(self.pi_transformed),
                "se_transformed": self.se_transformed, "mean_transformed": self.mean_transformed,
                "mean_back_transformed": self.mean_back_transformed}

    def summary(self) -> str:
        from ..present import format_g

        pc = int(round(100 * self.confidence))
        lines = [f"Confirmation of {self.response} at " + ", ".join(f"{k} = {format_g(v, 6, trim=True)}" for k, v in self.actual.items()),
                 f"  predicted:       {format_g(self.predicted, 6, trim=True)}",
                 f"  observed mean:   {format_g(self.mean, 6, trim=True)}  (n = {self.n})",
                 f"  {pc} % PI for the mean of {self.n} run(s): {format_g(self.pi[0], 6, trim=True)} .. {format_g(self.pi[1], 6, trim=True)}"
                 f"  -> {'inside' if self.inside else 'OUTSIDE'}",
                 f"  relative error:  {self.relative_error_percent:+.2f} % of the prediction"]
        if self.transform is not None and self.pi_transformed is not None:
            lines.insert(1, f"  model fitted to the {self.transform}-transformed response; the interval is computed "
                            "on that scale and back-transformed")
            lines.append(f"  transformed scale: predicted {format_g(self.predicted_transformed, 6, trim=True)}, run mean "
                         f"{format_g(self.mean_transformed, 6, trim=True)}, PI {format_g(self.pi_transformed[0], 6, trim=True)} .. "
                         f"{format_g(self.pi_transformed[1], 6, trim=True)}"
                         + ("" if self.n == 1 else f" (back-transformed run mean {format_g(self.mean_back_transformed, 6, trim=True)})"))
        if self.reference is not None:
            lines.append(f"  relative error:  {self.relative_error_vs_reference_percent:+.2f} % of the reference "
                         f"{format_g(self.reference, 6, trim=True)}")
        lines += [f"  warning: {w}" for w in self.warnings]
        return "\n".join(lines) + "\n"


def confirm(result, at, observed, *, confidence: float = 0.95, reference: float | None = None) -> ConfirmationResult:
    """Check confirmation runs against the prediction interval (see the module docstring).

    Parameters
    ----------
    result : FitResult
        The model (reduced or transformed as fitted; a fit of a transformed response gives
        the interval on the transformed scale, back-transformed).
    at : mapping or list of str
        Settings in actual units, ``{name or letter: value}`` or ``["NAME=VALUE", ...]``.
    observed : float or sequence of float
        The confirmation run(s) [response units].
    confidence : float
        Level of the interval (0.95).
    reference : float, optional
        A published prediction to compare against as well (e.g. the rounded 0.023).

    Returns
    -------
    ConfirmationResult
        The prediction and its interval at ``at``, the mean of the observed runs and whether it
        falls inside the interval.
    """
    from scipy.special import stdtrit  # the t quantile (scipy.stats costs a second to import)

    if not 0.0 < confidence < 1.0:
        raise ParameterError("confidence", f"confidence must lie between 0 and 1, not {confidence!r}")
    obs = np.atleast_1d(np.asarray(observed, dtype=float)) if not isinstance(observed, str) else None
    if obs is None or obs.size == 0 or obs.ndim != 1:
        raise ParameterError("observed", "give at least one observed value")
    if not np.all(np.isfinite(obs)):
        raise ParameterError("observed", "observed values must be finite numbers")
    if result.df_resid <= 0:
        raise ValueError("the model has no residual degrees of freedom: no prediction interval")
    space = result.space
    settings = parse_settings(space, at)
    x_act = np.array([[settings[n] for n in space.names]], dtype=object if space.has_categoric else float)
    x = np.asarray(space.encode(x_act), dtype=float)
    tr = result.transform
    pr = result.predict(x, coded=True).iloc[0]
    n = int(obs.size)
    # the mean of n new runs (in one new whole plot or block): var_mean + s2_group + s2/n, the fit's df
    var, df = result.interval_form.mean_of_new_runs(design_matrix(x, result.terms), n)
    se = math.sqrt(float(var[0]))
    t = float(stdtrit(float(df[0]), 1 - (1 - confidence) / 2))
    mean = float(np.sum(obs / n))  # no overflow on the way: the mean of 1e308 and 1e308 is 1e308
    tinfo = {}
    if not tr.identity:  # interval on the transformed scale, ends back-transformed
        tr.check(obs, "observed")
        zhat = float(pr["predicted_transformed"])
        zlo, zhi = zhat - t * se, zhat + t * se
        a, b = (float(v) for v in tr.inverse(np.array([zlo, zhi])))
        lo, hi = (a, b) if a <= b else (b, a)
        if not (math.isfinite(lo) and math.isfinite(hi)):
            raise ValueError(f"the {tr.label} prediction interval {zlo:g} .. {zhi:g} cannot be back-transformed")
        yhat = float(tr.inverse(np.array([zhat]))[0])
        zbar = float(np.mean(tr.forward(obs)))
        mean_bt = float(tr.inverse(np.array([zbar]))[0])
        inside = bool(zlo <= zbar <= zhi)
        tinfo = {"transform": tr.label, "predicted_transformed": zhat, "pi_transformed": (zlo, zhi),
                 "se_transformed": se, "mean_transformed": zbar, "mean_back_transformed": mean_bt}
    else:
        yhat = float(pr["predicted"])
        lo, hi = yhat - t * se, yhat + t * se
        inside = bool(lo <= mean <= hi)
    with np.errstate(over="ignore"):
        rel = float(100.0 * ((np.float64(mean) - yhat) / yhat)) if yhat != 0 else math.nan
    if math.isinf(rel):  # a number the report would print as "+inf %"
        raise ParameterError("observed", f"the run mean {mean:.6g} is beyond any relative error from the prediction "
                                         f"{yhat:.6g} (over 1e308 %): check the observed values and their units")
    rel_ref = None
    if reference is not None:
        reference = float(reference)
        if reference == 0 or not math.isfinite(reference):
            raise ParameterError("reference", "reference must be a finite non-zero number")
        with np.errstate(over="ignore"):
            rel_ref = float(100.0 * ((np.float64(mean) - reference) / reference))
        if math.isinf(rel_ref):
            raise ParameterError("observed", f"the run mean {mean:.6g} is beyond any relative error from the "
                                             f"reference {reference:.6g} (over 1e308 %)")
    extra = bool(np.any(np.abs(x[:, space.numeric_index]) > 1 + 1e-9))
    warns = ("the settings lie outside the design range: the prediction is an extrapolation",) if extra else ()
    return ConfirmationResult(
        response=result.response, actual=dict(settings), coded={f.letter: (settings[f.name] if f.kind == "categoric" else float(v))
                                                       for f, v in zip(space.factors, x[0])},
        predicted=yhat, observed=tuple(float(v) for v in obs), n=n, mean=mean, confidence=float(confidence),
        pi=(lo, hi), se_mean=se, inside=inside, relative_error_percent=rel, reference=reference,
        relative_error_vs_reference_percent=rel_ref, extrapolation=extra, warnings=warns, **tinfo,
    )
