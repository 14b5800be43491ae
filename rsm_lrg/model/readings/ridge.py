"""Ridge analysis (second order) and the path of steepest ascent/descent (first order).

The algorithm is R ``rsm``'s ``steepest()`` (Lenth, package rsm, file ``R/rsm.R``,
functions ``steepest`` and ``canonical.path``), in coded units, with the coded model
``ŷ = b0 + x'b + x'Bx`` (``B_ii`` the squares, ``B_ij`` half the interactions):

* **first order** (no second-order term): the straight line ``x(r) = ± r b / |b|``
  ("Linear path of steepest ascent");
* **second order** (any interaction or square; R's "order 1.5" counts too): Draper's
  (1963) ridge analysis — the point of maximum (minimum) ŷ on the sphere ``|x| = r`` is
  ``x(γ) = -½ (B - γ I)⁻¹ b`` with the multiplier ``γ > λ_max`` (ascent) or
  ``γ < λ_min`` (descent) chosen so that ``|x(γ)| = r``. R brackets γ from
  ``λ_max + 0.001`` outwards and calls ``uniroot``; here the same root is solved to machine
  precision with Brent's method. When ``b`` has no component along the extreme
  eigenvector (Draper's "degenerate" case, where R's ``uniroot`` fails) the limit point is
  completed along that eigenvector so the radius is still exact.

R rounds the path to 3 decimals before predicting and predicts at the first block level;
here the exact point is reported and ŷ is for the average block (block effects sum to
zero), as everywhere in rsm-lrg. :func:`canonical_path` is R's ``canonical.path``: the
straight line from the stationary point along one eigenvector.

>>> import rsm_lrg
>>> p = ridge(rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min"), goal="minimize", radius=1, step=0.5)
>>> [round(pt["radius"], 3) for pt in p.to_dict()["path"]]
[0.0, 0.5, 1.0]
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...errors import ParameterError

__all__ = ["ridge", "RidgePath", "canonical_path", "ridge_point", "radii"]


def radii(radius: float, step: float) -> np.ndarray:
    """Every multiple of ``step`` from 0 up to ``radius`` (within 1e-9 relative) [coded units].

    >>> radii(1.0, 0.25).tolist()
    [0.0, 0.25, 0.5, 0.75, 1.0]
    """
    for name, v in (("radius", radius), ("step", step)):
        if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
            raise ValueError(f"{name} must be a finite number, not {v!r}")
    if radius < 0:
        raise ParameterError("radius", f"radius must be >= 0 (got {radius:g})")
    if step <= 0:
        raise ParameterError("step", f"step must be > 0 (got {step:g})")
    m = int(math.floor(radius / step * (1 + 1e-9) + 1e-12))
    if m > 100_000:
        raise ParameterError("radius", f"radius/step = {radius / step:.0f} points is too many (at most 100000)")
    return np.round(np.arange(m + 1) * step, 12)


def _parts(result):
    from .canonical import quadratic_parts

    if any(t.order > 2 for t in result.terms):
        raise ValueError("ridge analysis needs a first- or second-order model (the model has cubic terms)")
    coefs = dict(zip(result.coefficients.index, result.coefficients["coded"].to_numpy(dtype=float)))
    return quadratic_parts(coefs, result.terms, len(result.space))


def ridge_point(b: np.ndarray, B: np.ndarray, r: float, descent: bool = False) -> np.ndarray:
    """The point of extreme ŷ on the sphere ``|x| = r`` (Draper 1963) [coded units].

    ``b`` and ``B`` as in the module docstring; ``descent`` for the minimum.
    """
    from scipy import optimize as so

    b = np.asarray(b, float)
    B = np.asarray(B, float)
    k = b.size
    if r <= 0:
        return np.zeros(k)
    s = -1.0 if descent else 1.0
    # work with the maximisation of s*ŷ: b -> s b, B -> s B
    bs, Bs = s * b, s * B
    vals, vecs = np.linalg.eigh(Bs)
    lmax = vals[-1]
    c = vecs.T @ bs  # components of b along the eigenvectors
    scale = max(1.0, float(np.max(np.abs(vals))), float(np.linalg.norm(bs)))

    def x_of(t):  # gamma = lmax + t, t > 0
        return -0.5 * vecs @ (c / (vals - lmax - t))

    def g(t):
        return float(np.linalg.norm(x_of(t))) - r

    t_lo = 1e-3 * scale
    while g(t_lo) < 0 and t_lo > 1e-15 * scale:
        t_lo /= 10.0
    if g(t_lo) >= 0:
        t_hi = 5.0 * scale
        while g(t_hi) > 0:
            t_hi *= 2.0
        t = so.brentq(g, t_lo, t_hi, xtol=1e-15 * scale, rtol=4 * np.finfo(float).eps, maxiter=500)
        return x_of(t)
    # degenerate ("hard") case: b has (almost) no component along the top eigenvector(s)
    top = np.abs(vals - lmax) <= 1e-12 * scale
    rest = ~top
    x0 = -0.5 * vecs[:, rest] @ (c[rest] / (vals[rest] - lmax)) if rest.any() else np.zeros(k)
    x0 = x0 - vecs[:, top] @ (vecs[:, top].T @ x0)
    tau2 = r * r - float(x0 @ x0)
    v = vecs[:, top][:, 0]
    if v[np.argmax(np.abs(v))] < 0:
        v = -v
    return x0 + math.sqrt(max(tau2, 0.0)) * v


@dataclass(frozen=True)
class RidgePath:
    """A ridge or steepest path (frozen).

    Attributes
    ----------
    response : str
    goal : str
        ``"maximize"`` or ``"minimize"``.
    kind : str
        ``"ridge"`` (second-order model) or ``"steepest"`` (first order).
    radius : ndarray
        Distance from the design centre [coded units].
    coded : ndarray (m, k)
        Path points [coded units]; columns follow the factor letters.
    actual : ndarray (m, k)
        The same points [actual units].
    predicted : ndarray
        ŷ along the path (average block) [response units].
    letters, names : tuple of str
    """

    response: str
    goal: str
    kind: str
    radius: np.ndarray = field(repr=False)
    coded: np.ndarray = field(repr=False)
    actual: np.ndarray = field(repr=False)
    predicted: np.ndarray = field(repr=False)
    letters: tuple = ()
    names: tuple = ()

    def to_dict(self) -> dict:
        """The ridge JSON of INTERFACE.md."""
        path = []
        for i in range(self.radius.size):
            path.append({"radius": float(self.radius[i]),
                         "coded": {L: float(v) for L, v in zip(self.letters, self.coded[i])},
                         "actual": {n: float(v) for n, v in zip(self.names, self.actual[i])},
                         "predicted": float(self.predicted[i])})
        return {"response": self.response, "goal": self.goal, "kind": self.kind, "path": path}

    def to_frame(self):
        """``radius``, coded letters, actual names, ``predicted`` (R ``steepest()`` layout)."""
        import pandas as pd

        df = pd.DataFrame({"radius": self.radius})
        for j, L in enumerate(self.letters):
            df[L] = self.coded[:, j]
        for j, n in enumerate(self.names):
            df[n] = self.actual[:, j]
        df["predicted"] = self.predicted
        return df

    def summary(self) -> str:
        from ...present import format_g, text_table

        what = ("Path of steepest {} from ridge analysis" if self.kind == "ridge" else "Linear path of steepest {}")
        what = what.format("ascent" if self.goal == "maximize" else "descent")
        head = ["radius", *self.letters, "|", *self.names, "|", "predicted"]
        rows = [[f"{r:.3f}", *(f"{v:.3f}" for v in c), "|", *(format_g(v, 5) for v in a), "|", format_g(p, 5)]
                for r, c, a, p in zip(self.radius, self.coded, self.actual, self.predicted)]
        return f"{what} for {self.response} (coded radius from the design centre)\n" + text_table(head, rows) + "\n"

    def __str__(self) -> str:
        return self.summary()


def _goal(goal) -> str:
    g = str(goal).strip().lower()
    if g in ("maximize", "maximise", "max", "ascent"):
        return "maximize"
    if g in ("minimize", "minimise", "min", "descent"):
        return "minimize"
    raise ParameterError("goal", f"goal must be maximize or minimize, not {goal!r}")


def _finish(result, goal, kind, r, X) -> RidgePath:
    pred = result.predict(X, coded=True)["predicted"].to_numpy()
    actual = result.space.decode(X)
    return RidgePath(response=result.response, goal=goal, kind=kind, radius=np.asarray(r, float), coded=X,
                     actual=np.asarray(actual, float), predicted=pred, letters=tuple(result.space.letters),
                     names=tuple(result.space.names))


def ridge(result, goal: str = "maximize", radius: float | None = None, step: float = 0.1, level=None) -> RidgePath:
    """Ridge path (second order) or steepest path (first order) from the design centre.

    Parameters
    ----------
    result : FitResult
    goal : {"maximize", "minimize"}
    radius : float, optional
        Largest distance [coded units]; default the largest distance of a design point
        from the centre (√k for a 2^k cube, √2 for a Box–Behnken design).
    step : float
        Spacing of the path points [coded units]; the path has a point at every multiple
        of ``step`` up to ``radius``, 0 included.
    level : mapping, optional
        With categoric factors: the level of each (``{"stage": "rms"}``; the first levels
        by default); the path runs through the numeric factors at that combination.

    Returns
    -------
    RidgePath
        The path: per radius [coded units] the coded and actual settings and the prediction.
    """
    if result.space.has_categoric:  # the path through the numeric factors at one level combination
        from .levels import LevelView

        result = LevelView(result, level or {})
    g = _goal(goal)
    radii(0.0, step)  # validates step
    b0, b, B = _parts(result)
    if radius is None:
        radius = float(np.max(np.linalg.norm(result.coded.to_numpy(dtype=float), axis=1)))
        radius = math.floor(radius / step * (1 + 1e-9)) * step
    r = radii(float(radius), float(step))
    second = bool(np.any(B != 0.0)) or any(t.order == 2 for t in result.terms)
    if not second:
        nb = float(np.linalg.norm(b))
        if nb == 0.0:
            raise ValueError("the first-order model has no slope (all linear coefficients are 0): no steepest path")
        d = b / nb * (1.0 if g == "maximize" else -1.0)
        X = r[:, None] * d[None, :]
        return _finish(result, g, "steepest", r, X)
    X = np.vstack([ridge_point(b, B, float(ri), descent=(g == "minimize")) for ri in r])
    return _finish(result, g, "ridge", r, X)


def canonical_path(result, which: int | None = None, dist=None, descent: bool = False) -> RidgePath:
    """R ``rsm``'s ``canonical.path``: ``x_s + d v_which`` along one eigenvector.

    ``which`` is 1-based (default 1 for ascent, k for descent: eigenvalues decrease);
    ``dist`` default -5 .. 5 by 0.5 [coded units]. ``radius`` in the result holds ``dist``.
    """
    sp = result.stationary_point
    if sp.coded is None or sp.eigenvectors is None:
        raise ValueError(f"no canonical path: {sp.note or 'no stationary point'}")
    k = len(result.space)
    w = (k if descent else 1) if which is None else int(which)
    if not 1 <= w <= k:
        raise ValueError(f"which must be 1..{k}, not {which!r}")
    dist = np.arange(-5.0, 5.0 + 1e-9, 0.5) if dist is None else np.asarray(dist, float)
    xs = np.array([sp.coded[L] for L in result.space.letters])
    X = xs[None, :] + dist[:, None] * sp.eigenvectors[:, w - 1][None, :]
    return _finish(result, "minimize" if descent else "maximize", "canonical", dist, X)
