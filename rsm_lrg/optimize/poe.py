"""Propagation of error (POE): how much a response varies at a setting when the factors
themselves vary about it.

Each numeric factor ``i`` varies about its setting with a standard deviation ``s_i`` in actual
units (``--factor-sd NAME=SD``; independent, so ``Σ = diag(s_i²)``); a factor without an SD is
held exactly. With ``g`` the gradient of the **back-transformed** prediction ``ŷ(x)`` with
respect to the factors in actual units, and ``σ²`` the variance of a run about the true mean,
Design-Expert's first-order propagation of error is

    POE(x) = √( g' Σ g + σ² )      [response units].

This module prints exactly that first-order quantity (no second-order term: Design-Expert's
documentation of POE states the first-order formula, and we found no public source that it
adds a curvature term, so none is claimed). ``g`` is computed analytically: the term
derivatives of the coded model (:func:`rsm_lrg.model.build.terms.design_gradient`), divided by each
factor's half range (actual units per coded unit), times the slope ``dy/dη`` of the
back-transform at the prediction.

* **σ²**: the residual mean square (OLS), or ``σ̂²_group + σ̂²`` (REML: both variance
  components: a run made in a new whole plot or block); with a transform, carried to response
  units by the same first-order rule, ``(dy/dη)² σ²_η``. Hence ``POE_y = |dy/dη| · POE_η``.
* **Categoric factors** are held at their level (an SD for one is refused).
* **Mixtures**: the SDs are those of the components' amounts (actual units), and a blend must
  keep its total: the independent deviations ``e`` are replaced by their projection onto the
  blend plane, ``e - mean(e)`` over the components (every component gives up the average
  deviation), i.e. ``Σ → P Σ P`` with ``P = I - 11'/q`` on the q components. The gradient of a
  Scheffé model is then only used along the plane, where it is defined. Process factors of a
  mixture-process model vary freely.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError

#: The largest factor SD accepted, in half ranges of the factor (the coded reach of a prediction).
MAX_SD_HALF_RANGES = 1e6

__all__ = ["MAX_SD_HALF_RANGES", "parse_factor_sd", "factor_covariance", "prediction_gradient", "back_slope", "propagation_of_error"]


def parse_factor_sd(space: Any, items: Mapping[str, Any] | Sequence[str] | None) -> dict[str, float]:
    """``{factor name: SD}`` [actual units] from ``["NAME=SD", ...]`` or a mapping keyed by
    name or letter. A ParameterError (parameter ``factor_sd``) for an unknown or categoric
    factor, a factor given twice, or an SD that is not a finite number >= 0."""
    if not items:
        return {}
    if isinstance(items, Mapping):
        pairs = [(str(k), v) for k, v in items.items()]
    else:
        pairs = []
        for s in items:
            name, sep, value = str(s).partition("=")
            if not sep or not name.strip():
                raise ParameterError("factor_sd", f"factor_sd {s!r}: expected NAME=SD")
            pairs.append((name.strip(), value.strip()))
    out: dict[str, float] = {}
    for key, value in pairs:
        try:
            f = space[key]
        except KeyError:
            raise ParameterError("factor_sd", f"factor_sd for {key!r}: no such factor (factors: "
                                              f"{', '.join(space.names)})") from None
        if f.kind == "categoric":
            raise ParameterError("factor_sd", f"factor_sd for {f.name!r}: a categoric factor is held at its level; "
                                              "give SDs for numeric factors only")
        try:
            sd = float(value)
        except (TypeError, ValueError):
            raise ParameterError("factor_sd", f"factor_sd for {f.name!r}: {value!r} is not a number") from None
        if not (math.isfinite(sd) and sd >= 0.0):
            raise ParameterError("factor_sd", f"factor_sd for {f.name!r}: the SD must be a finite number >= 0, not {sd:g}")
        if sd > MAX_SD_HALF_RANGES * f.half_range:
            raise ParameterError("factor_sd", f"factor_sd for {f.name!r}: {sd:g} is more than {MAX_SD_HALF_RANGES:g} "
                                              f"times the factor's half range ({f.half_range:g}); the model says "
                                              "nothing that far out")
        if f.name in out:
            raise ParameterError("factor_sd", f"factor_sd for {f.name!r} is given more than once")
        out[f.name] = sd
    return out


def mixture_components(space: Any) -> list[int]:
    """Positions of the mixture components among the factors (empty without a mixture)."""
    comps = {id(f) for f in space.components}  # the space says whether its region is a simplex
    return [j for j, f in enumerate(space.factors) if id(f) in comps]


def factor_covariance(space: Any, sds: Mapping[str, float]) -> np.ndarray:
    """The k x k covariance of the factor deviations [actual units²]: ``diag(s_i²)``, projected
    onto the blend plane for the mixture components (``P Σ P``, see the module docstring)."""
    k = len(space)
    s = np.array([float(sds.get(f.name, 0.0)) for f in space.factors])
    cov = np.diag(s**2)
    comps = mixture_components(space)
    if comps:
        P = np.eye(k)
        q = len(comps)
        P[np.ix_(comps, comps)] -= 1.0 / q
        cov = P @ cov @ P.T
    return cov


def back_slope(transform: Any, eta: np.ndarray) -> np.ndarray:
    """``dy/dη`` of the back-transform ``y = g⁻¹(η) - k`` at ``η`` [response units per
    model-scale unit] (1 without a transform)."""
    eta = np.asarray(eta, dtype=float)
    if transform.identity or transform.name == "none":
        return np.ones_like(eta)
    if transform.name == "log10":
        return math.log(10.0) * np.power(10.0, eta)
    lam = transform.lam
    if lam is None or lam == 0.0:
        return np.exp(eta)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(eta > 0, np.abs(eta) ** (1.0 / lam - 1.0) / lam, np.nan)


def _coded(fit: Any, points: Any) -> np.ndarray:
    """The coded settings (n x k) of a frame of actual settings, unrounded."""
    import pandas as pd

    if isinstance(points, Mapping):
        points = pd.DataFrame({k: np.atleast_1d(v) for k, v in points.items()})
    cols = []
    for f in fit.space.factors:
        if f.kind == "categoric":
            cols.append(np.asarray(f.encode(points[f.name].to_numpy(dtype=object)), dtype=float))
        else:
            cols.append((points[f.name].to_numpy(dtype=float) - f.center) / f.half_range)
    return np.column_stack(cols)


def prediction_gradient(fit: Any, points: Any) -> tuple[np.ndarray, np.ndarray]:
    """``(η, dη/dx)`` at each point: the model-scale prediction and its gradient with respect
    to the factors in actual units (n x k; zero along a categoric factor) [model-scale units,
    model-scale units per actual unit]."""
    from ..model.build.terms import design_gradient, design_matrix

    x = _coded(fit, points)
    beta = fit.coefficients["coded"].to_numpy(dtype=float)
    eta = design_matrix(x, fit.terms) @ beta
    half = np.array([1.0 if f.kind == "categoric" else f.half_range for f in fit.space.factors])
    grad = np.array([design_gradient(row, fit.terms).T @ beta for row in x]).reshape(x.shape) / half
    return eta, grad


def propagation_of_error(fit: Any, points: Any, factor_sd: Mapping[str, Any] | Sequence[str] | None) -> np.ndarray:
    """POE at each point (see the module docstring) [response units].

    Parameters
    ----------
    fit : FitResult
        The fitted model (any kind: transformed, categoric, mixture, REML).
    points : DataFrame or mapping
        Settings in actual units, one column per factor (categoric factors at a level).
    factor_sd : mapping or list of str
        ``{name: SD}`` or ``["NAME=SD", ...]`` [actual units]; factors not named are held.

    Returns
    -------
    ndarray
        ``√(g'Σg + σ²)`` per point, with ``g`` the gradient of the back-transformed prediction
        in actual units.
    """
    from ..model.contract.tolerance import new_run_variance

    sds = parse_factor_sd(fit.space, factor_sd)
    cov = factor_covariance(fit.space, sds)
    eta, grad = prediction_gradient(fit, points)
    var_eta = np.einsum("ij,jk,ik->i", grad, cov, grad) + new_run_variance(fit)
    return np.abs(back_slope(fit.transform, eta)) * np.sqrt(var_eta)
