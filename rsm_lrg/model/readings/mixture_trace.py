"""Reading a fitted mixture model: component effects along the Cox (or Piepel) direction, the
trace plot's curves and the ternary slice.

A blend's components are not free (they sum to the total ``T``), so "the effect of a
component" is taken along a direction that keeps the total: from a reference blend ``s``,
component ``i`` moves by ``Δ`` and every other component gives way in proportion to its own
share (Cox 1971; Cornell, *Experiments with Mixtures*, 3rd ed., Sec. 5.9):

    x_i = s_i + Δ,        x_j = s_j - Δ s_j / (T - s_i)   (j ≠ i)          [Cox direction]

The **Piepel direction** is the same move in L-pseudo components (``z = (x - L)/R`` with
total 1; Piepel 1982, as Design-Expert's trace plot offers it): it keeps the lower bounds'
share fixed. Along the direction ``Δ`` runs over the interval where the blend stays in the
region (the components' bounds and linear constraints: :mod:`rsm_lrg.model.build.mixture_region`);
the **total effect** of component ``i`` is ``ŷ(Δ_max) - ŷ(Δ_min)`` (Cornell's "total
effect", Eq. 5.38; Piepel 1982), its **gradient** the slope ``dŷ/dΔ`` at the reference. The
trace plot (Snee & Marquardt 1976; Piepel 1982) draws ``ŷ`` against ``Δ`` for every component
on one figure. The default reference blend is the region's centroid (the average of its
vertices; the simplex centroid when the components are bounded only by the simplex).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...factors import MixtureComponent
from ..build.mixture_region import MixtureRegion, mixture_region

__all__ = ["MixtureTrace", "mixture_trace", "cox_direction", "along_direction", "ternary_slice", "DIRECTIONS"]

#: The directions a trace follows.
DIRECTIONS = ("cox", "piepel")


@dataclass(frozen=True)
class MixtureTrace:
    """The trace of a mixture fit (frozen; :func:`mixture_trace`).

    Attributes
    ----------
    response : str
    direction : {"cox", "piepel"}
    reference : dict
        ``{name: value}`` of the reference blend [real proportions] (and the process
        factors' values [actual units]).
    deviation : dict
        ``{component: array}`` Δ along the direction [real proportions for ``cox``,
        L-pseudo units for ``piepel``], from ``low`` to ``high`` (0 is the reference).
    predicted : dict
        ``{component: array}`` ŷ at each Δ [response units].
    blends : dict
        ``{component: (n, k) array}`` the settings of each point [actual units].
    low, high : dict
        ``{component: Δ}`` the ends of the range inside the region.
    effects : dict
        ``{component: ŷ(high) - ŷ(low)}`` the total effect [response units].
    gradients : dict
        ``{component: dŷ/dΔ at the reference}`` [response units per unit of Δ].
    """

    response: str
    direction: str
    reference: dict
    deviation: dict
    predicted: dict
    blends: dict = field(repr=False, default_factory=dict)
    low: dict = field(default_factory=dict)
    high: dict = field(default_factory=dict)
    effects: dict = field(default_factory=dict)
    gradients: dict = field(default_factory=dict)

    def to_frame(self) -> Any:
        """The effects as a DataFrame: one row per component (``low``, ``high``,
        ``effect``, ``gradient``, ``reference``).

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        import pandas as pd

        return pd.DataFrame({"reference": [self.reference[c] for c in self.effects],
                             "low": list(self.low.values()), "high": list(self.high.values()),
                             "effect": list(self.effects.values()), "gradient": list(self.gradients.values())},
                            index=pd.Index(list(self.effects), name="component"))

    def to_dict(self) -> dict:
        """Plain data: the direction, the reference blend, per component the effect, the
        gradient, the range and the curve (``deviation``, ``predicted``).

        Returns
        -------
        dict
            Plain JSON-safe data (numbers, strings, lists and dicts).
        """
        return {"response": self.response, "direction": self.direction, "reference": dict(self.reference),
                "components": {c: {"effect": self.effects[c], "gradient": self.gradients[c],
                                   "low": self.low[c], "high": self.high[c],
                                   "deviation": [float(v) for v in self.deviation[c]],
                                   "predicted": [float(v) for v in self.predicted[c]]} for c in self.effects}}

    def summary(self) -> str:
        """A few lines of text: the reference blend and each component's effect.

        Returns
        -------
        str
            Text for people, several lines.
        """
        from ...present import format_g

        units = "real proportion" if self.direction == "cox" else "L-pseudo units"
        ref = ", ".join(f"{k} = {format_g(v, 6, trim=True)}" for k, v in self.reference.items())
        lines = [f"Component effects on {self.response} along the {self.direction.capitalize()} direction",
                 f"  reference blend: {ref}",
                 f"  {'component':<14} {'range of Δ (' + units + ')':>34} {'total effect':>14} {'slope at ref':>14}"]
        for c in self.effects:
            rng = f"{format_g(self.low[c], 4, trim=True)} .. {format_g(self.high[c], 4, trim=True)}"
            lines.append(f"  {c:<14} {rng:>34} {format_g(self.effects[c], 5, trim=True):>14} "
                         f"{format_g(self.gradients[c], 5, trim=True):>14}")
        return "\n".join(lines) + "\n"


def cox_direction(reference: np.ndarray, i: int, total: float) -> np.ndarray:
    """The direction of the Cox move of component ``i`` from ``reference`` (one row of
    proportions summing to ``total``): +1 for ``i``, ``-s_j / (T - s_i)`` for the others
    (the move keeps the total and the others' ratios).

    >>> cox_direction(np.array([0.2, 0.3, 0.5]), 0, 1.0).round(6).tolist()
    [1.0, -0.375, -0.625]
    """
    s = np.asarray(reference, dtype=float)
    rest = total - s[i]
    if not rest > 1e-12 * total:
        raise ValueError(f"the reference blend is the pure component {i + 1}: the other components cannot give way")
    d = -s / rest
    d[i] = 1.0
    return d


def along_direction(region: MixtureRegion, x0: np.ndarray, d: np.ndarray) -> tuple[float, float]:
    """``(t_low, t_high)``: the interval of ``t`` with ``x0 + t d`` in the region (coded units)."""
    gd = region.G @ d
    slack = region.h - region.G @ x0
    lo, hi = -np.inf, np.inf
    for a, s in zip(gd, slack):
        if a > 1e-15:
            hi = min(hi, s / a)
        elif a < -1e-15:
            lo = max(lo, s / a)
    return float(min(lo, 0.0)), float(max(hi, 0.0))


def _coded_reference(fit: Any, region: MixtureRegion, reference: Mapping[str, float] | None) -> np.ndarray:
    x = region.centroid()
    if reference:
        for name, v in reference.items():
            try:
                f = fit.space[name]
            except KeyError:
                raise ValueError(f"reference: no component or factor {name!r} (factors: {', '.join(fit.space.names)})") from None
            x[fit.space.names.index(f.name)] = float(f.encode(float(v)))
        comps = list(region.comps)
        if abs(float(np.sum(x[comps])) - 1.0) > 1e-9:
            f0 = fit.space.factors[comps[0]]
            got = f0.lower_sum + float(np.sum(x[comps])) * f0.pseudo_range
            raise ValueError(f"reference: the blend sums to {got:.12g}, not the total {f0.total:.12g} (give every "
                             "component)")
        if not region.contains(x, tol=1e-9)[0]:
            raise ValueError("reference: the blend lies outside the region (the components' bounds and constraints)")
    return x


def mixture_trace(fit: Any, reference: Mapping[str, float] | None = None, direction: str = "cox", n: int = 51,
                  bounds: Any = None, constraints: Any = None) -> MixtureTrace:
    """The trace and the total effects of a mixture fit's components.

    Parameters
    ----------
    fit : FitResult
        A Scheffé mixture fit.
    reference : mapping, optional
        The reference blend ``{name: real proportion}`` (every component; process factors
        may be given too, in actual units, default their centre). Default: the region's
        centroid.
    direction : {"cox", "piepel"}
        Cox: the move in real proportions; Piepel: in L-pseudo components.
    n : int
        Points per curve (>= 3).
    bounds, constraints
        Tighter limits and linear constraints of the region (as for
        :func:`rsm_lrg.model.build.mixture_region.mixture_region`).

    Returns
    -------
    MixtureTrace
    """
    from ..build.terms import design_gradient

    if not fit.space.has_components:
        raise ValueError("a trace needs a mixture fit (components and a Scheffé model)")
    direction = str(direction).lower()
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {', '.join(DIRECTIONS)}, not {direction!r}")
    if int(n) < 3:
        raise ValueError(f"n must be at least 3, not {n!r}")
    region = mixture_region(fit.space, bounds, constraints)
    x0 = _coded_reference(fit, region, reference)
    comps = list(region.comps)
    f0 = fit.space.factors[comps[0]]
    assert isinstance(f0, MixtureComponent)
    R, T = f0.pseudo_range, f0.total
    beta = fit.coefficients["coded"].to_numpy(dtype=float)
    out: dict[str, dict] = {k: {} for k in ("dev", "pred", "blend", "low", "high", "eff", "grad")}
    for i_pos, j in enumerate(comps):
        name = fit.space.factors[j].name
        d = np.zeros(len(fit.space))
        if direction == "cox":  # Δ in real proportions; the coded (pseudo) direction is the real one / R
            s = np.array([float(fit.space.factors[c].decode(x0[c])) for c in comps])
            d[comps] = cox_direction(s, i_pos, T) / R
        else:  # Δ in L-pseudo units
            d[comps] = cox_direction(x0[comps], i_pos, 1.0)
        t_lo, t_hi = along_direction(region, x0, d)
        ts = np.linspace(t_lo, t_hi, int(n))
        X = x0[None, :] + ts[:, None] * d[None, :]
        X[:, comps] = X[:, comps] / X[:, comps].sum(axis=1, keepdims=True)
        y = fit.predict(X, coded=True)["predicted"].to_numpy()
        ends = fit.predict(np.vstack([x0 + t_lo * d, x0 + t_hi * d]), coded=True)["predicted"].to_numpy()
        g = float(design_gradient(x0, fit.terms).T @ beta @ d)
        if not fit.transform.identity:  # slope on the response's scale: finite difference of the back-transform
            h = 1e-6 * max(t_hi - t_lo, 1e-12)
            yy = fit.predict(np.vstack([x0 - h * d, x0 + h * d]), coded=True)["predicted"].to_numpy()
            g = float((yy[1] - yy[0]) / (2 * h))
        dev = ts  # component i moves by t (real proportion for cox: d_i = 1/R coded; pseudo for piepel)
        out["dev"][name] = dev
        out["pred"][name] = y
        out["blend"][name] = np.column_stack([f.decode(X[:, c]) for c, f in enumerate(fit.space.factors)])
        out["low"][name], out["high"][name] = float(dev[0]), float(dev[-1])
        out["eff"][name] = float(ends[1] - ends[0])
        out["grad"][name] = g
    return MixtureTrace(response=str(fit.response), direction=direction, reference=region.to_actual(x0),
                        deviation=out["dev"], predicted=out["pred"], blends=out["blend"], low=out["low"],
                        high=out["high"], effects=out["eff"], gradients=out["grad"])


def ternary_slice(fit: Any, components: Sequence[str] | None = None, held: Mapping[str, float] | None = None,
                  n: int = 40) -> dict:
    """Predictions over the triangle of three components, the others (and the process
    factors) held: the data of a ternary contour plot.

    The three components share what the held ones leave, ``S = T - sum held``; the points are
    the lattice ``(a, b, c) = S (i, j, n - i - j) / n`` (only those inside the components'
    bounds are predicted; the rest are ``nan``).

    Returns
    -------
    dict
        ``components`` (the three names), ``held`` (``{name: value}``), ``share`` (S),
        ``fractions`` ((m, 3) array of a/S, b/S, c/S), ``settings`` ((m, k) actual),
        ``inside`` (mask), ``predicted`` ((m,) array, nan outside).
    """
    space = fit.space
    comps = [f.name for f in space.factors if isinstance(f, MixtureComponent)]
    if len(comps) < 3:
        raise ValueError("a ternary plot needs at least three components")
    tri = list(components) if components is not None else comps[:3]
    if len(tri) != 3 or len(set(tri)) != 3 or any(c not in comps for c in tri):
        raise ValueError(f"a ternary plot takes three different components of {', '.join(comps)}")
    region = mixture_region(space)
    ref = region.to_actual(region.centroid())
    held_v = {nm: float((held or {}).get(nm, ref[nm])) for nm in space.names if nm not in tri}
    f0 = space[comps[0]]
    assert isinstance(f0, MixtureComponent)
    share = f0.total - sum(held_v[c] for c in comps if c not in tri)
    if not share > 0:
        raise ValueError("the held components leave nothing for the three plotted ones")
    fr = np.array([(i, j, n - i - j) for i in range(n + 1) for j in range(n + 1 - i)], dtype=float) / n
    X = np.zeros((len(fr), len(space)))
    for c, nm in enumerate(tri):
        X[:, space.names.index(nm)] = share * fr[:, c]
    for nm, v in held_v.items():
        X[:, space.names.index(nm)] = v
    coded = np.column_stack([f.encode(X[:, c]) for c, f in enumerate(space.factors)])
    inside = region.contains(coded, tol=1e-9)
    pred = np.full(len(fr), np.nan)
    if inside.any():
        pred[inside] = fit.predict(X[inside])["predicted"].to_numpy()
    return {"components": tri, "held": held_v, "share": float(share), "fractions": fr, "settings": X,
            "inside": inside, "predicted": pred}
