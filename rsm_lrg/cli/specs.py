"""The model options as a specification (:func:`model_spec`, :func:`random_effect`) and the checks
of those options before any data are read."""

from __future__ import annotations

import argparse
from typing import Any

from ..io import InputError, quote_user_value
from .errors import option_error
from .options import MIXTURE_MODEL_NAMES


def random_effect(args: argparse.Namespace) -> dict:
    """The ``whole_plot=``/``random_block=`` (and ``hard_to_change=``) keywords of
    :func:`rsm_lrg.fit` from the options."""
    out = {}
    if getattr(args, "whole_plot", None) is not None:
        out["whole_plot"] = args.whole_plot
    if getattr(args, "random_block", None) is not None:
        out["random_block"] = args.random_block
    if getattr(args, "random_effect", None):
        out["random_effects"] = list(args.random_effect)
    if getattr(args, "hard_to_change", None) is not None:
        if out.get("whole_plot") is None:
            raise InputError("--hard-to-change: give --whole-plot COL too (the factors are checked against the whole "
                             "plots)")
        out["hard_to_change"] = list(args.hard_to_change)
    return out


def random_effect_columns(args: argparse.Namespace) -> list[str]:
    """The whole-plot, random-block and random-effect columns named on the command line, kept out
    of the inferred factors (the columns of an ``A:B`` interaction too when no ``--factor`` is
    given, as :func:`rsm_lrg.fit` keeps them out)."""
    cols = [c for c in (getattr(args, "whole_plot", None), getattr(args, "random_block", None)) if c is not None]
    for c in getattr(args, "random_effect", None) or []:
        cols += [c] + (c.split(":") if ":" in c and not getattr(args, "factor", None) else [])
    return cols


def check_option_specs(args: argparse.Namespace) -> None:
    """Check the ``--factor`` and ``--bound NAME=LOW:HIGH`` values before any data is read, so
    that an error names the option rather than the data file (categoric ``NAME=cat...`` specs
    are left to the library)."""
    for dest, label in (getattr(args, "_path_labels", None) or {}).items():
        value = getattr(args, dest, None)
        for v in value if isinstance(value, list) else [value]:
            if isinstance(v, str) and not v.strip():
                raise InputError(f"{label}: an empty path was given")
    for dest in ("factor", "bound"):
        for spec in getattr(args, dest, None) or []:
            if not isinstance(spec, str):
                continue
            rest = spec.split("=", 1)[1].strip().lower() if "=" in spec else ""
            if rest.startswith("cat") and dest == "factor":
                continue
            if dest == "bound" and rest and ":" not in rest:
                continue  # NAME=LEVEL[,LEVEL]: a categoric factor held at its level(s), checked with the data
            from ..factors import parse_factor_spec  # only when there is a spec: it loads numpy

            try:
                if parse_factor_spec(spec)[1] is None and dest == "bound":
                    raise ValueError("expected NAME=LOW:HIGH")
            except ValueError as exc:
                raise InputError(f"--{dest} {quote_user_value(spec)}: {exc}") from None


def model_spec(opts: argparse.Namespace, *, order: str | None = None):
    """The :class:`~rsm_lrg.model.build.spec.ModelSpec` of a command's model options (``--model``,
    ``--terms``, ``--no-intercept``, ``--transform``, ``--transform-constant``, ``--reduce``,
    ``--alpha-out``, ``--criterion``; those a command lacks take their defaults). A bad value
    is an InputError naming its option, before any data is read."""
    from ..model.build.spec import ModelSpec, SpecError

    how = getattr(opts, "reduce", False)
    reduce: dict[str, str | float] | None = None
    if how:
        reduce = {"alpha_out": getattr(opts, "alpha_out", 0.1), "method": how if isinstance(how, str) else "backward"}
        if getattr(opts, "alpha_in", None) is not None:  # else the method's default (0.1; dsd 0.05)
            reduce["alpha_in"] = opts.alpha_in
        if getattr(opts, "criterion", None) is not None:
            reduce["criterion"] = opts.criterion
    if (order is None and getattr(opts, "model", None) is None and getattr(opts, "component", None)
            and getattr(opts, "terms", None) is not None):
        order = "mixture-quadratic"  # --terms names the Scheffé model; the order only starts a reduction
    mixture = str(order or getattr(opts, "model", None) or "quadratic") in MIXTURE_MODEL_NAMES
    if getattr(opts, "component", None) and not mixture:
        raise InputError("--model: mixture components (--component) need a Scheffé model: "
                         + "|".join(MIXTURE_MODEL_NAMES))
    if mixture and not getattr(opts, "component", None):
        raise InputError(f"--model {getattr(opts, 'model', order)}: a mixture model needs its components "
                         "(--component NAME, once per component)")
    check_terms_option(getattr(opts, "terms", None))
    try:
        return ModelSpec.build(order or getattr(opts, "model", None) or "quadratic", terms=getattr(opts, "terms", None),
                               intercept=not getattr(opts, "no_intercept", False),
                               transform=getattr(opts, "transform", None),
                               transform_constant=getattr(opts, "transform_constant", 0.0), reduce=reduce)
    except SpecError as exc:
        raise option_error(exc, opts) from None


#: The highest degree of a term given with ``--terms`` (``A^20``, ``A^10B^10``): far beyond any
#: response surface (Design-Expert stops at 6), and the exact conversion of the coefficients to
#: actual units costs time growing with the degree (``A^99999`` ran for ever).
MAX_TERM_DEGREE = 20


def check_terms_option(terms: Any) -> None:
    """Refuse a ``--terms`` list holding a term of degree above :data:`MAX_TERM_DEGREE` (its
    letters counted once each, plus their powers), naming the term.

    >>> check_terms_option("A B AB A^2 A^3B^2")
    >>> check_terms_option("A^99999")
    Traceback (most recent call last):
    ...
    rsm_lrg.io.InputError: --terms: the term 'A^99999' has degree 99999; at most 20 ...
    """
    import re

    if not isinstance(terms, str):
        return
    for tok in terms.replace(",", " ").split():
        if tok == "Intercept":
            continue
        degree = 0
        for m in re.finditer(r"[A-Z](?:\^(\d+))?", tok):
            power = m.group(1)
            degree += 1 if power is None else (int(power) if len(power) < 10 else 10**10)
        if degree > MAX_TERM_DEGREE:
            shown = degree if degree < 10**10 else "beyond 10^10"
            raise InputError(f"--terms: the term {quote_user_value(tok)} has degree {shown}; at most "
                             f"{MAX_TERM_DEGREE} (a polynomial of such degree fits noise, and its actual-unit "
                             "coefficients would take for ever)")


def check_transform_option(opts: argparse.Namespace) -> None:
    """The model options are checked (and a bad one named) before any data is read."""
    model_spec(opts)
