"""The spread beside the mean: a model of ln s over the replicated settings.

Where runs are replicated, the standard deviation of the replicates of each distinct setting,
``s = sqrt(Σ (y - ȳ)² / (m - 1))`` over the ``m ≥ 2`` runs of that setting, measures the
run-to-run spread there; ``ln s`` is modelled by ordinary least squares on the settings (one
row per setting, coded as the mean's fit codes the factors), as Design-Expert and JMP model
the standard deviation of replicated runs ("log-variance" / dispersion models; Bartlett &
Kendall 1946: ln s is nearly normal with a variance that depends only on ``m``). The
coefficients, ANOVA and R² are those of ``lm(log(s) ~ ...)`` on the table of settings.

Settings run once have no ``s``, and settings whose replicates are all equal have ``s = 0``
(``ln s = -∞``): both are left out, and the result says which (nothing is dropped silently).
Settings are "distinct" as the mean's fit counts pure-error groups: their coded values equal
after rounding (:func:`rsm_lrg.model.build.inputs.model_inputs`). The blocks and random effects of
the mean's model play no part here: ``s`` is taken within a setting whatever its block.

The result holds an ordinary :class:`~rsm_lrg.model.results.result.FitResult` of the response
``s(Y)`` [response units] fitted under the ``log`` transform, so its coefficients and ANOVA are
on the ln s scale and its predictions back-transform to ``s``; the desirability optimiser
takes it beside the mean's fit (``minimize`` the spread).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["DispersionFit", "fit_dispersion", "dispersion_name"]


def dispersion_name(response: str) -> str:
    """The response name of the spread model of ``response``: ``"s(Y)"``."""
    return f"s({response})"


@dataclass(frozen=True)
class DispersionFit:
    """A model of ln s (frozen; see the module docstring).

    Attributes
    ----------
    response : str
        The response whose spread is modelled.
    result : FitResult
        The fit of ``s(Y)`` under the natural-log transform (coefficients, ANOVA and R² on
        the ln s scale; ``result.predict`` gives ``s`` [response units]).
    settings : pandas.DataFrame
        The settings used: the factor columns (actual units), ``runs`` (m), ``mean`` (ȳ),
        ``s`` and ``ln_s``.
    left_out : list of dict
        Each setting left out: its factor values, ``runs`` and ``reason``
        (``"unreplicated"`` or ``"replicates equal (s = 0)"``).
    """

    response: str
    result: Any
    settings: Any
    left_out: list = field(default_factory=list)

    @property
    def name(self) -> str:
        """The spread model's response name, ``s(Y)``."""
        return dispersion_name(self.response)

    def predict_s(self, X: Any) -> np.ndarray:
        """The predicted standard deviation ``exp(ln s)`` at the settings ``X``.

        Parameters
        ----------
        X : pandas.DataFrame
            The factor columns, actual units.

        Returns
        -------
        numpy.ndarray
            The predicted s at each row [response units].
        """
        return np.asarray(self.result.predict(X)["predicted"], dtype=float)

    def to_dict(self) -> dict:
        """The JSON ``dispersion`` block.

        Returns
        -------
        dict
            The model of ln s (terms, coefficients, standard errors, ANOVA, statistics with R²)
            and the settings used and left out.
        """
        d = self.result.to_dict()
        return {
            "response": self.response,
            "scale": "ln s",
            "name": self.name,
            "model": d.get("model"),
            "terms": d.get("terms"),
            "coefficients": d.get("coefficients"),
            "std_errors": d.get("std_errors"),
            "anova": d.get("anova"),
            "statistics": d.get("statistics"),
            "r2": float(self.result.statistics.r2),
            "settings_used": int(len(self.settings)),
            "settings_left_out": [dict(s) for s in self.left_out],
            "settings": [{k: _plain(v) for k, v in row.items()} for row in self.settings.to_dict("records")],
        }

    def summary(self) -> str:
        """The spread model as text.

        Returns
        -------
        str
            What was used and left out, then the fit of ln s.
        """
        lines = [f"Dispersion model: ln s of {self.response} at {len(self.settings)} replicated settings "
                 f"(runs per setting {int(self.settings['runs'].min())}..{int(self.settings['runs'].max())})"]
        unrep = [s for s in self.left_out if s["reason"] == "unreplicated"]
        zero = [s for s in self.left_out if s["reason"] != "unreplicated"]
        if unrep:
            lines.append(f"Left out: {len(unrep)} unreplicated setting(s): " + "; ".join(_where(s) for s in unrep[:6])
                         + (" ..." if len(unrep) > 6 else ""))
        if zero:
            lines.append(f"Left out: {len(zero)} setting(s) whose replicates are equal (s = 0, ln s undefined): "
                         + "; ".join(_where(s) for s in zero[:6]) + (" ..." if len(zero) > 6 else ""))
        lines.append(f"R² (ln s) = {self.result.statistics.r2:.4f}")
        return "\n".join(lines) + "\n" + self.result.summary()


def _plain(v: Any) -> Any:
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.floating,)):
        return float(v)
    return v


def _where(s: dict) -> str:
    return ", ".join(f"{k}={_plain(v):g}" if isinstance(v, (int, float, np.number)) else f"{k}={v}"
                     for k, v in s.items() if k not in ("runs", "reason"))


def fit_dispersion(data: Any, response: str, factors: Any = None, model: Any = "linear", *,
                   terms: Any = None) -> DispersionFit:
    """Model ln s of the replicated settings of ``data`` beside the mean.

    Parameters
    ----------
    data : pandas.DataFrame
        One row per run; rows with an empty response are left out as for every fit.
    response : str
        The response column [response units].
    factors : None, sequence or FactorSpace
        As for :func:`rsm_lrg.fit` (pass the mean's ``result.space`` to code the spread
        model exactly as the mean).
    model : str, default "linear"
        The model order of ln s (``"linear"``, ``"2fi"``, ``"quadratic"``, ...).
    terms : str or sequence of str, optional
        An explicit term list of ln s instead of ``model``.

    Returns
    -------
    DispersionFit

    Raises
    ------
    ParameterError
        ``factors`` for mixture components (not available yet); ``response`` when fewer than
        three replicated settings with s > 0 remain (naming how many); ``dispersion_model``
        when the ln s model cannot be fitted on them (fewer settings than terms, a factor
        constant over the replicated settings, ...).
    """
    import pandas as pd

    from .build.inputs import model_inputs
    from .fit import fit

    inp = model_inputs(data, response, factors)
    space = inp.space
    if space.has_components:
        raise ParameterError("factors", "a dispersion (ln s) model of a mixture is not available yet")
    keys = np.asarray(inp.keys, dtype=float)
    y = np.asarray(inp.y_response, dtype=float)
    frame = inp.prep.data.reset_index(drop=True)
    _, first, group, counts = np.unique(keys, axis=0, return_index=True, return_inverse=True, return_counts=True)
    group = np.asarray(group).ravel()
    names = list(space.names)
    rows, left = [], []
    for g in np.argsort(first):  # the settings in the order of their first run
        at = {n: _plain(frame.loc[int(first[g]), n]) for n in names}
        m = int(counts[g])
        if m < 2:
            left.append(dict(at, runs=m, reason="unreplicated"))
            continue
        vals = y[group == g]
        s = float(np.std(vals, ddof=1))
        if not s > 0.0:
            left.append(dict(at, runs=m, reason="replicates equal (s = 0)"))
            continue
        rows.append(dict(at, runs=m, mean=float(np.mean(vals)), s=s, ln_s=float(np.log(s))))
    table = pd.DataFrame(rows, columns=names + ["runs", "mean", "s", "ln_s"])
    what = f"terms {terms!r}" if terms is not None else f"model {model!r}"
    if len(table) < 3:
        raise ParameterError("response", f"response {response!r}: {len(table)} replicated setting(s) with s > 0 "
                                         f"(of {len(first)} distinct settings): too few to model ln s")
    sname = dispersion_name(response)
    if sname in names:
        raise ParameterError("response", f"a factor is named {sname!r}, the spread model's response name")
    agg = table[names].copy()
    agg[sname] = table["s"].to_numpy()
    try:
        res = fit(agg, sname, factors=space, model=model, terms=terms, transform="log")
    except ParameterError:
        raise
    except ValueError as exc:
        raise ParameterError("dispersion_model", f"the ln s model ({what}) on {len(table)} replicated settings of "
                                                 f"{response!r}: {exc}") from None
    return DispersionFit(response=response, result=res, settings=table, left_out=left)
