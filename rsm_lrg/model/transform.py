"""Response transformations: fit on ``y' = g(y + k)``, predict back in response units.

``g`` is one of Design-Expert's power-family transforms:

========== ==================== ===============================
name       ``y' = g(y)``          back-transform ``y = g⁻¹(y')``
========== ==================== ===============================
``none``   y                    y'
``log``    ln y                 exp y'
``log10``  log10 y              10^y'
``sqrt``   √y                   y'²
``inverse`` 1 / y               1 / y'
``power=λ`` y^λ (λ ≠ 0; 0 is ln) y'^(1/λ)
========== ==================== ===============================

A constant ``k`` (default 0) may be added first, for responses with zeros. Predictions and
interval ends are back-transformed (the back-transformed mean is the median of the
response on the original scale when the errors are symmetric on the transformed scale);
for decreasing transforms (inverse, negative powers) the interval ends swap.

>>> t = parse_transform("power=0.5")
>>> t.name, t.lam, float(t.inverse(t.forward(9.0)))
('power', 0.5, 9.0)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["Transform", "parse_transform", "TransformedFit", "fit_transformed"]

_NAMES = {"none": ("none", 1.0), "log": ("log", 0.0), "ln": ("log", 0.0), "log10": ("log10", None),
          "sqrt": ("sqrt", 0.5), "inverse": ("inverse", -1.0), "inv": ("inverse", -1.0)}


@dataclass(frozen=True)
class Transform:
    """A response transform (frozen): ``name`` in ``none, log, log10, sqrt, inverse, power``,
    ``lam`` its power (``None`` for log10) and ``constant`` k added before transforming."""

    name: str = "none"
    lam: float | None = 1.0
    constant: float = 0.0

    @property
    def label(self) -> str:
        s = self.name if self.name != "power" else f"power={self.lam:g}"
        return s + (f" ({self.constant:+g})" if self.constant else "")  # (+2), (-0.01)

    @property
    def decreasing(self) -> bool:
        return self.lam is not None and self.lam < 0

    def check(self, y, column: str = "response") -> None:
        """ValueError naming the first row where ``y + k`` is outside the transform's domain
        (positive for log, log10, inverse and negative powers; non-negative for positive powers)."""
        if self.name == "none":
            return
        v = np.asarray(y, dtype=float) + self.constant
        positive_power = self.lam is not None and self.lam > 0
        bad = v < 0 if positive_power else v <= 0
        if np.any(bad):
            i = int(np.flatnonzero(bad)[0])
            need = "non-negative" if positive_power else "positive"
            raise ValueError(f"the {self.label} transform needs {need} values: column {column!r}, row {i + 1} "
                             f"holds {float(np.asarray(y, float)[i]):g}" + ("" if self.constant else " (add a constant)"))

    def forward(self, y):
        v = np.asarray(y, dtype=float) + self.constant
        if self.name == "none":
            return v
        if self.name == "log10":
            return np.log10(v)
        if self.lam == 0.0:
            return np.log(v)
        return np.power(v, self.lam)

    def inverse(self, z):
        z = np.asarray(z, dtype=float)
        if self.name == "none":
            v = z
        elif self.name == "log10":
            v = np.power(10.0, z)
        elif self.lam == 0.0:
            v = np.exp(z)
        else:  # outside the image of the transform (z < 0, or z <= 0 for negative powers) -> NaN
            ok = z >= 0 if self.lam > 0 else z > 0
            with np.errstate(invalid="ignore", divide="ignore"):
                v = np.where(ok, np.abs(z) ** (1.0 / self.lam), np.nan)
        return v - self.constant

    def to_dict(self) -> dict:
        return {"name": self.name, "lambda": self.lam, "constant": self.constant}


def parse_transform(spec, constant: float = 0.0) -> Transform:
    """A :class:`Transform` from ``"log"``, ``"sqrt"``, ``"inverse"``, ``"log10"``, ``"none"``
    or ``"power=λ"`` (also a Transform, returned as is)."""
    if isinstance(spec, Transform):
        return spec
    if spec is None:
        return Transform(constant=float(constant))
    s = str(spec).strip().lower()
    if s in _NAMES:
        name, lam = _NAMES[s]
        return Transform(name, lam, float(constant))
    if s.startswith("power"):
        rest = s[len("power"):].strip()
        if not rest.startswith("="):
            raise ValueError(f"transform {spec!r}: a power needs a value, e.g. power=0.5")
        try:
            lam = float(rest[1:])
        except ValueError:
            raise ValueError(f"transform {spec!r}: the power {rest[1:].strip()!r} is not a number") from None
        if not math.isfinite(lam):
            raise ValueError(f"transform {spec!r}: the power must be finite")
        if lam == 1.0:
            return Transform("none", 1.0, float(constant))
        if lam == 0.0:
            return Transform("log", 0.0, float(constant))
        return Transform("power", lam, float(constant))
    raise ValueError(f"transform must be none, log, log10, sqrt, inverse or power=LAMBDA, not {spec!r}")


@dataclass(frozen=True)
class TransformedFit:
    """A fit on the transformed response with back-transformed predictions (frozen).

    Attributes
    ----------
    fit : FitResult
        The fit of ``g(y + k)`` (its coefficients, ANOVA and statistics are on that scale).
    transform : Transform
    response : str
        The original response column.
    """

    fit: Any = field(repr=False)
    transform: Transform = Transform()
    response: str = ""

    def __getattr__(self, name):  # delegate the FitResult interface (terms, space, anova, ...)
        if name in ("fit", "transform", "response"):
            raise AttributeError(name)
        return getattr(self.fit, name)

    def predict(self, points, interval=None, alpha: float = 0.05, *, coded: bool = False):
        """Predictions in response units (back-transformed), with the transformed-scale
        prediction in ``predicted_transformed``; interval ends are back-transformed too."""
        out = self.fit.predict(points, interval=interval, alpha=alpha, coded=coded)
        tr = self.transform
        out["predicted_transformed"] = out["predicted"]
        out["predicted"] = tr.inverse(out["predicted"].to_numpy())
        for lo, hi in (("ci_low", "ci_high"), ("pi_low", "pi_high")):
            if lo in out:
                a, b = tr.inverse(out[lo].to_numpy()), tr.inverse(out[hi].to_numpy())
                out[lo], out[hi] = np.fmin(a, b), np.fmax(a, b)
        return out

    def to_dict(self) -> dict:
        d = self.fit.to_dict()
        d["response"] = self.response
        d["transform"] = self.transform.to_dict()
        return d

    def summary(self) -> str:
        return (f"Response {self.response} transformed: {self.transform.label} "
                f"(coefficients and ANOVA on the transformed scale)\n" + self.fit.summary())

    def __str__(self) -> str:
        return self.summary()


def fit_transformed(data, response: str, transform, *, constant: float = 0.0, **fit_kwargs) -> TransformedFit:
    """Fit ``g(response + constant)`` with :func:`rsm_lrg.fit` (keyword arguments passed on)."""
    from ..factors import _numeric
    from .fit import fit

    tr = parse_transform(transform, constant)
    if response not in data.columns:
        raise ValueError(f"response column {response!r} not found (columns: {', '.join(map(str, data.columns))})")
    y = _numeric(data, response).to_numpy(dtype=float)
    tr.check(y, response)
    df = data.copy()
    df[response] = tr.forward(y)
    res = fit(df, response, **fit_kwargs)
    return TransformedFit(fit=res, transform=tr, response=response)
