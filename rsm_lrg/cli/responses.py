"""The several-response fit loop that ``optimize`` and ``report`` share: one factor space for
every response (no response is a factor of another), one fit per response with its own model
options, and the notes on the input said once."""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import TYPE_CHECKING

from .errors import about_response
from .specs import random_effect, random_effect_columns

if TYPE_CHECKING:
    import pandas as pd

    from ..model import FitResult, ModelSpec

__all__ = ["fit_responses"]


def fit_responses(args: argparse.Namespace, data: pd.DataFrame, responses: Sequence[str],
                  specs: Sequence[ModelSpec | str]) -> tuple[dict[str, FitResult], list[str]]:
    """``({response: FitResult}, notes)``: each response of ``responses`` fitted to ``data``
    with its specification ``specs[i]`` (``"gp"``: a Gaussian process) and the command's ``--factor``, ``--block``,
    ``--component`` and random-effect options.

    With several responses and no mixture components, the factors are chosen once
    (:func:`rsm_lrg.factors.choose_factors`, every response excluded) so that every response
    is fitted on the same space; a mixture's components (and process factors) are named, and
    each fit codes them on its own rows. The notes are the choice's, then each fit's own (runs
    left out), prefixed by the response when there are several. An error inside a fit names
    its response (:func:`~rsm_lrg.cli.errors.about_response`).
    """
    from ..factors import COLUMNS_LEFT_OUT, choose_factors
    from ..model import fit

    several = len(responses) > 1
    factors = args.factor
    notes: list[str] = []
    if several and not args.component:
        choice = choose_factors(data, args.factor, exclude=list(responses) + ([args.block] if args.block else [])
                                + random_effect_columns(args))
        factors, notes = choice.space, list(choice.notes)
    fits = {}
    for r, spec in zip(responses, specs):
        with about_response(r, several):
            fits[r] = fit(data, r, factors=factors, block=args.block, model=spec, components=args.component,
                          **random_effect(args))
        notes += [(f"{r}: {x}" if several else x) for x in fits[r].input_notes
                  if x not in notes and (not several or getattr(x, "kind", "") != COLUMNS_LEFT_OUT)]
    return fits, notes
