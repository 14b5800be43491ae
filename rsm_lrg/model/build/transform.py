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
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import ParameterError

__all__ = ["Transform", "parse_transform", "GOAL_KINDS"]

#: What a goal asks of a response: the three kinds of :meth:`Transform.goal_on_model_scale`.
GOAL_KINDS = ("minimize", "maximize", "target")

_NAMES = {"none": ("none", 1.0), "log": ("log", 0.0), "ln": ("log", 0.0), "log10": ("log10", None),
          "sqrt": ("sqrt", 0.5), "inverse": ("inverse", -1.0), "inv": ("inverse", -1.0)}


@dataclass(frozen=True)
class Transform:
    """A response transform (frozen): ``name`` in ``none, log, log10, sqrt, inverse, power``,
    ``lam`` its power (``None`` for log10) and ``constant`` k added before transforming.

    Parameters
    ----------
    name : str, default "none"
        ``none``, ``log``, ``log10``, ``sqrt``, ``inverse`` or ``power``.
    lam : float or None, default 1.0
        The power λ (0 for log, ``None`` for log10).
    constant : float, default 0.0
        k added to the response before transforming [response units].
    """

    name: str = "none"
    lam: float | None = 1.0
    constant: float = 0.0

    @property
    def label(self) -> str:
        """The transform as text: ``"log"``, ``"power=0.5"``, with the constant when there is one (``"log (+2)"``).
        """
        s = self.name if self.name != "power" else f"power={self.lam:g}"
        return s + (f" ({self.constant:+g})" if self.constant else "")  # (+2), (-0.01)

    @property
    def decreasing(self) -> bool:
        """Whether ``g`` is decreasing (inverse and negative powers): maxima become minima."""
        return self.lam is not None and self.lam < 0

    @property
    def identity(self) -> bool:
        """No transform and no constant: the model's scale is the response's."""
        return self.name == "none" and self.constant == 0.0

    def goal_on_model_scale(self, kind: str, target: float | None = None) -> tuple[str, float | None]:
        """The goal on the scale the model is fitted on: the one mapping of a goal every
        consumer (optimize, desirability, the report) uses.

        A decreasing transform swaps ``"minimize"`` and ``"maximize"``; a target ``T`` becomes
        ``g(T + k)`` (a ValueError when ``T`` is outside the transform's domain).

        >>> Transform("inverse", -1.0).goal_on_model_scale("maximize")
        ('minimize', None)
        >>> Transform("log", 0.0).goal_on_model_scale("target", 1.0)
        ('target', 0.0)

        Parameters
        ----------
        kind : {"minimize", "maximize", "target"}
            The goal.
        target : float, optional
            The target [response units], for ``"target"``.

        Returns
        -------
        tuple
            ``(kind, target)`` on the model's scale.
        """
        if kind not in GOAL_KINDS:
            raise ParameterError("goal", f"goal must be minimize, maximize or target, not {kind!r}")
        if self.identity:
            return kind, target
        if kind == "target":
            if target is None:
                raise ValueError("a target goal needs its value")
            self.check([target], "target")
            return "target", float(self.forward([target])[0])
        if self.decreasing:
            return ("minimize" if kind == "maximize" else "maximize"), None
        return kind, None

    def back(self, predicted: Any, low: Any = None, high: Any = None) -> tuple[Any, Any, Any]:
        """Predictions and interval ends back-transformed to response units; the ends are
        ordered (a decreasing transform swaps them).

        Parameters
        ----------
        predicted : array_like
            Predictions on the model's scale.
        low, high : array_like, optional
            Interval ends on the model's scale.

        Returns
        -------
        tuple
            ``(predicted, low, high)`` in response units (``None`` for ends not given).
        """
        pred = self.inverse(predicted)
        if low is None or high is None:
            return pred, None, None
        a, b = self.inverse(low), self.inverse(high)
        return pred, np.fmin(a, b), np.fmax(a, b)

    def check(self, y: Any, column: str = "response") -> None:
        """ValueError naming the first row where ``y + k`` is outside the transform's domain
        (positive for log, log10, inverse and negative powers; non-negative for positive powers).

        Parameters
        ----------
        y : array_like
            The responses [response units].
        column : str, default "response"
            The column's name, for the message.
        """
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
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            z = self.forward(y)
        lost = np.isfinite(v) & ~np.isfinite(z)
        if self.lam is not None and self.lam != 0.0:  # a power that underflows a nonzero value to 0
            lost |= np.isfinite(v) & (v != 0) & (z == 0)
        if np.any(lost):  # the power is at fault, not the cell: name the option's value
            i = int(np.flatnonzero(lost)[0])
            how = "overflows" if not np.isfinite(z[i]) else "underflows"
            raise ParameterError("transform", f"transform {self.label}: the transformed response {how} (column {column!r}, "
                             f"row {i + 1}: {float(np.asarray(y, float)[i]):g} becomes {float(z[i]):g}); "
                             "choose a power nearer 0")

    def forward(self, y: Any) -> np.ndarray:
        """The transform ``g(y + k)``.

        Parameters
        ----------
        y : array_like
            Responses [response units].

        Returns
        -------
        numpy.ndarray
            The transformed values (the model's scale).
        """
        v = np.asarray(y, dtype=float) + self.constant
        if self.name == "none":
            return v
        if self.name == "log10":
            return np.log10(v)
        lam = self.lam
        assert lam is not None  # only log10 has no power
        if lam == 0.0:
            return np.log(v)
        return np.power(v, lam)

    def inverse(self, z: Any) -> np.ndarray:
        """The inverse transform: ``g⁻¹(z) - k``.

        Parameters
        ----------
        z : array_like
            Values on the model's scale.

        Returns
        -------
        numpy.ndarray
            Responses [response units]; NaN outside the transform's image.
        """
        z = np.asarray(z, dtype=float)
        if self.name == "none":
            v = z
        elif self.name == "log10":
            v = np.power(10.0, z)
        elif self.lam is None or self.lam == 0.0:  # only log10 (above) has no power
            v = np.exp(z)
        else:  # outside the image of the transform (z < 0, or z <= 0 for negative powers) -> NaN
            lam = self.lam
            ok = z >= 0 if lam > 0 else z > 0
            with np.errstate(invalid="ignore", divide="ignore"):
                v = np.where(ok, np.abs(z) ** (1.0 / lam), np.nan)
        return v - self.constant

    def to_dict(self) -> dict[str, Any]:
        """The transform as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        return {"name": self.name, "lambda": self.lam, "constant": self.constant}


def parse_transform(spec: Any, constant: float = 0.0) -> Transform:
    """A :class:`Transform` from ``"log"``, ``"sqrt"``, ``"inverse"``, ``"log10"``, ``"none"``
    or ``"power=λ"`` (also a Transform, returned as is).

    Parameters
    ----------
    spec : str or Transform
        The transform.
    constant : float, default 0.0
        k added to the response before transforming [response units].

    Returns
    -------
    Transform
        The transform.
    """
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
            raise ParameterError("transform", f"transform {spec!r}: a power needs a value, e.g. power=0.5")
        try:
            lam = float(rest[1:])
        except ValueError:
            raise ParameterError("transform", f"transform {spec!r}: the power {rest[1:].strip()!r} is not a number") from None
        if not math.isfinite(lam):
            raise ParameterError("transform", f"transform {spec!r}: the power must be finite")
        if lam == 1.0:
            return Transform("none", 1.0, float(constant))
        if lam == 0.0:
            return Transform("log", 0.0, float(constant))
        return Transform("power", lam, float(constant))
    raise ParameterError("transform", f"transform must be none, log, log10, sqrt, inverse or power=LAMBDA, not {spec!r}")
