"""What is fitted: :class:`ModelSpec`, one value object for every kind of fit.

A model is an *order* (``linear``, ``2fi``, ``quadratic``, ``cubic``: the standard
Design-Expert models) or an explicit *list of terms* in the JSON term notation (``"A"``,
``"AB"``, ``"A^2"``, ``"A^10"``, ``"A^2B"``, categoric terms such as ``"AE"``), with or
without an intercept; optionally on a transformed response (``log``, ``log10``, ``sqrt``,
``inverse``, ``power=L``, with a constant; :mod:`rsm_lrg.model.build.transform`) and optionally
reduced by hierarchical backward elimination (:class:`ReduceSpec`,
:mod:`rsm_lrg.model.choice.reduce`).

>>> s = ModelSpec.build(terms="A B AB A^2", intercept=False, transform="log")
>>> s.terms, s.intercept, s.transform.name
(('A', 'B', 'AB', 'A^2'), False, 'log')
>>> ModelSpec.build("2fi").order
'2fi'
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, TypeAlias

from ...errors import ParameterError
from ...factors import FactorSpace
from ...terms import MODELS
from .mixture import MIXTURE_MODELS, MIXTURE_ORDERS
from .transform import Transform, parse_transform

__all__ = ["ModelSpec", "ReduceSpec", "SpecError", "FactorsArg", "TermsArg", "ReduceArg", "REDUCE_METHODS",
           "REDUCE_CRITERIA"]

#: The factors of a fit: inferred (None), names or ``"NAME=LOW:HIGH"`` / ``"NAME=cat..."``
#: strings, or a :class:`~rsm_lrg.factors.FactorSpace`.
FactorsArg: TypeAlias = "Sequence[str] | FactorSpace | None"
#: A term list: ``"A B AB A^2"`` (space- or comma-separated) or a sequence of term names.
TermsArg: TypeAlias = "str | Sequence[str] | None"
#: A reduction: None/False (none), True (the defaults), a method name (``"forward"``), a mapping
#: ``{"method": ..., "criterion": ..., "alpha_out": ..., ...}`` or a :class:`ReduceSpec`.
ReduceArg: TypeAlias = "bool | str | Mapping[str, str | float | bool] | ReduceSpec | None"


class SpecError(ParameterError):
    """A bad model specification; ``parameter`` names what was wrong (``"model"``, ``"terms"``,
    ``"transform"``, ``"reduce"``) so a command line can name its own option."""


#: Ways of choosing the terms (:mod:`rsm_lrg.model.choice.reduce`, :mod:`rsm_lrg.model.choice.select`).
REDUCE_METHODS = ("backward", "forward", "stepwise", "all-subsets", "dsd")
#: Criteria of the choice.
REDUCE_CRITERIA = ("p", "aicc", "bic")


@dataclass(frozen=True)
class ReduceSpec:
    """How the terms are chosen, hierarchy kept (unless ``hierarchy=False``).

    ``method``: ``"backward"`` (the default: remove by p-value while the largest removable p
    exceeds ``alpha_out``, ``criterion="p"``; or while AICc, ``"aicc"``, or BIC, ``"bic"``,
    falls), ``"forward"`` (add while the smallest p is below ``alpha_in``, or while the
    criterion falls), ``"stepwise"`` (forward, each addition followed by the removals
    backward elimination would make), ``"all-subsets"`` (every hierarchical sub-model of
    the starting model, the best by AICc or BIC; ``criterion`` defaults to ``"aicc"`` there
    and ``"p"`` elsewhere). See :mod:`rsm_lrg.model.choice.select`.

    Parameters
    ----------
    criterion : {"p", "aicc", "bic"}, optional
        What the selection uses (p-values by default).
    alpha_out : float, default 0.1
        A term leaves above this p-value.
    method : {"backward", "forward", "stepwise", "all-subsets", "dsd"}, default "backward"
        The selection method.
    alpha_in : float, optional
        A term enters below this p-value (forward and stepwise; default 0.1); the threshold
        of both stages of ``"dsd"`` (default 0.05).
    hierarchy : bool, default True
        Keep the model hierarchical.
    """

    criterion: str | None = None
    alpha_out: float = 0.1
    method: str = "backward"
    alpha_in: float = math.nan  # resolved in __post_init__: 0.05 for "dsd", else 0.1
    hierarchy: bool = True

    def __post_init__(self) -> None:
        if self.method not in REDUCE_METHODS:
            raise SpecError("reduce", f"the reduction method must be one of {', '.join(REDUCE_METHODS)}, not "
                                      f"{self.method!r}")
        if self.alpha_in is None or (isinstance(self.alpha_in, float) and math.isnan(self.alpha_in)):
            object.__setattr__(self, "alpha_in", 0.05 if self.method == "dsd" else 0.1)
        if self.criterion is None:
            object.__setattr__(self, "criterion", "aicc" if self.method == "all-subsets" else "p")
        if self.criterion not in REDUCE_CRITERIA:
            raise SpecError("criterion", f"criterion must be 'p', 'aicc' or 'bic', not {self.criterion!r}")
        if self.method == "dsd" and self.criterion != "p":
            raise SpecError("criterion", "the definitive screening analysis tests by p-values (criterion 'p'), not "
                                         f"{self.criterion!r}")
        if self.method == "all-subsets" and self.criterion == "p":
            raise SpecError("criterion", "all-subsets ranks the models by AICc or BIC (criterion 'aicc' or 'bic'), "
                                         "not by p-values")
        for name in ("alpha_out", "alpha_in"):
            a = getattr(self, name)
            if isinstance(a, bool) or not isinstance(a, (int, float)) or not 0.0 < a < 1.0:
                raise SpecError(name if name == "alpha_in" else "reduce",
                                f"{name} must lie between 0 and 1, not {a!r}")
        if self.method == "stepwise" and self.criterion == "p" and self.alpha_in > self.alpha_out:
            raise SpecError("alpha_in", f"stepwise needs alpha_in <= alpha_out (a term entered at p < "
                                        f"{self.alpha_in:g} must not leave at once at p > {self.alpha_out:g})")

    @classmethod
    def build(cls, value: ReduceArg) -> ReduceSpec | None:
        """``None``/``False`` (no reduction), ``True`` (the defaults), a method name
        (``"forward"``), a ReduceSpec, or a mapping ``{"method": ..., "criterion": ...,
        "alpha_out": ..., "alpha_in": ..., "hierarchy": ...}``.

        Parameters
        ----------
        value : None, bool, str, mapping or ReduceSpec
            As described above.

        Returns
        -------
        ReduceSpec or None
            ``None`` for no reduction.
        """
        if value is None or value is False:
            return None
        if value is True:
            return cls()
        if isinstance(value, cls):
            return value
        if isinstance(value, str):
            return cls(method=value.strip().lower(), criterion=None)
        if isinstance(value, dict):
            unknown = set(value) - {"criterion", "alpha_out", "method", "alpha_in", "hierarchy"}
            if unknown:
                raise SpecError("reduce", f"reduce takes method, criterion, alpha_out, alpha_in and hierarchy, not "
                                          f"{', '.join(sorted(unknown))}")
            return cls(**value)
        raise SpecError("reduce", f"reduce must be True, a method name, a mapping or a ReduceSpec, not {value!r}")

    def to_dict(self) -> dict[str, Any]:
        """The reduction as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        out: dict[str, Any] = {"criterion": self.criterion, "alpha_out": self.alpha_out}
        if self.method != "backward" or not self.hierarchy:
            out.update(method=self.method, alpha_in=self.alpha_in, hierarchy=self.hierarchy)
        return out


@dataclass(frozen=True)
class ModelSpec:
    """One fitted model's specification (frozen).

    Attributes
    ----------
    order : str
        ``"linear"``, ``"2fi"``, ``"quadratic"`` or ``"cubic"``, or a Scheffé mixture model
        (``"mixture-linear"``, ``"mixture-quadratic"``, ``"special-cubic"``,
        ``"mixture-cubic"``; :mod:`rsm_lrg.model.build.mixture`): the model when ``terms`` is ``None``; with ``terms``
        it only names the starting point of a reduction (for a mixture order, that the
        terms are Scheffé terms in the components).
    terms : tuple of str or None
        The model's terms (without the intercept), in the JSON term notation.
    intercept : bool
        Whether the model has an intercept (without one the ANOVA's total and R² are
        uncorrected, as R's ``lm`` reports them).
    transform : Transform
        Response transform (the identity when none).
    reduce : ReduceSpec or None
        Backward elimination applied to the model before the final fit.
    """

    order: str = "quadratic"
    terms: tuple[str, ...] | None = None
    intercept: bool = True
    transform: Transform = field(default_factory=Transform)
    reduce: ReduceSpec | None = None

    def __post_init__(self) -> None:
        if self.order not in MODELS and self.order not in MIXTURE_ORDERS:
            raise SpecError("model", f"unknown model {self.order!r}; expected one of "
                                     f"{', '.join(MODELS + MIXTURE_MODELS)}")
        if self.mixture:
            if self.intercept:  # the Scheffé models hold the mean implicitly (sum of components = 1)
                object.__setattr__(self, "intercept", False)
            return
        if not self.intercept and self.terms is None:
            raise SpecError("terms", "a model without an intercept is given as a list of terms "
                                     "(--terms \"A B ...\" with --no-intercept)")

    @classmethod
    def build(cls, model: str | ModelSpec | None = "quadratic", *, terms: TermsArg = None, intercept: bool = True,
              transform: str | Transform | None = None, transform_constant: float = 0.0,
              reduce: ReduceArg = None) -> ModelSpec:
        """The specification from the keyword arguments of :func:`rsm_lrg.fit` (a ModelSpec
        given as ``model`` is returned as it is when nothing else is given).

        Parameters
        ----------
        model : str or ModelSpec or None, default "quadratic"
            ``"linear"``, ``"2fi"``, ``"quadratic"``, ``"cubic"``, a mixture model, or a ModelSpec.
        terms : list of str or str, optional
            Chosen terms (``["A", "B", "AB", "A^2"]`` or ``"A B AB A^2"``) instead of ``model``.
        intercept : bool, default True
            Whether the model has an intercept.
        transform : str or Transform, optional
            A response transform (``"log"``, ``"sqrt"``, ``"power=λ"`` ...).
        transform_constant : float, default 0.0
            k added to the response before transforming [response units].
        reduce : bool, str, mapping or ReduceSpec, optional
            A term selection (see :class:`~rsm_lrg.model.ReduceSpec`).

        Returns
        -------
        ModelSpec
            The checked specification.
        """
        if isinstance(model, ModelSpec):
            if terms is not None or transform is not None or reduce is not None or not intercept:
                raise SpecError("model", "give either a ModelSpec or terms/intercept/transform/reduce, not both")
            return model
        if model is None:
            model = "quadratic"
        if not isinstance(model, str):
            raise SpecError("model", f"model must be one of {', '.join(MODELS + MIXTURE_MODELS)} or a ModelSpec, "
                                     f"not {model!r}")
        order = model.strip().lower()
        parsed_terms = None if terms is None else _term_names(terms)
        try:
            tr = parse_transform(transform, transform_constant)
        except ValueError as exc:
            raise SpecError("transform", str(exc)) from None
        if not math.isfinite(tr.constant):
            raise SpecError("transform", "the transform constant must be a finite number")
        return cls(order=order, terms=parsed_terms, intercept=bool(intercept), transform=tr,
                   reduce=ReduceSpec.build(reduce))

    @property
    def mixture(self) -> bool:
        """Whether this is a Scheffé mixture model (no intercept; ANOVA about the mean)."""
        return self.order in MIXTURE_ORDERS

    def to_dict(self) -> dict[str, Any]:
        """The model specification as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        return {"order": self.order, "terms": None if self.terms is None else list(self.terms),
                "intercept": self.intercept, "transform": self.transform.to_dict(),
                "reduce": None if self.reduce is None else self.reduce.to_dict()}


def _term_names(terms: Any) -> tuple[str, ...]:
    """Term names from ``"A B AB"`` / ``"A,B,AB"`` or a sequence of names (Term objects give
    their names); the intercept is the ``intercept`` flag's business and is dropped here."""
    if isinstance(terms, str):
        items: Sequence[Any] = terms.replace(",", " ").split()
    else:
        try:
            items = list(terms)
        except TypeError:
            raise SpecError("terms", f"terms must be a list of term names, not {terms!r}") from None
    out = []
    for t in items:
        name = getattr(t, "name", t)
        if not isinstance(name, str) or not name.strip():
            raise SpecError("terms", f"a term must be a name such as A, AB or A^2, not {t!r}")
        name = name.strip()
        if name != "Intercept" and name not in out:
            out.append(name)
    if not out:
        raise SpecError("terms", "the term list is empty (give terms such as \"A B AB A^2\")")
    return tuple(out)
