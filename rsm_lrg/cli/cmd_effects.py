"""``rsm-lrg effects``: effects of a screening experiment, Lenth's PSE and the half-normal plot."""

from __future__ import annotations

import argparse
from contextlib import contextmanager

from .errors import about_file
from .options import (
    add_block_option,
    add_data_response,
    add_factor_options,
    add_force,
    add_json,
    add_plot_option,
    plot_format,
)
from .paths import print_notes

NAME = "effects"
HELP = "effects of a two-level or screening design: Lenth's PSE, ME, SME and the half-normal plot"
DESCRIPTION = (
    "Fit the runs in coded units and list the effect of every one-df term (twice its coded "
    "coefficient: the change from -1 to +1) with its half-normal score and Lenth's (1989) "
    "pseudo standard error, margin of error (ME) and simultaneous margin of error (SME), for "
    "unreplicated designs where the ANOVA has no error to test against. The default --model "
    "saturated fits the largest model the runs estimate: the main effects and, lowest order "
    "first, each interaction orthogonal to them (one term of each alias chain of a fractional "
    "factorial, the chains listed); --model full fits every interaction of the factors (a full "
    "2^k factorial); --term picks the terms. --plot writes the half-normal plot (PNG or SVG by "
    "the file's extension)."
)

#: The models the command fits: the largest the design estimates (main effects and the
#: interactions orthogonal to them), the standard orders up to two-factor interactions, or
#: every interaction of the factors (products of distinct factors).
MODELS = ("saturated", "linear", "2fi", "full")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    from .options import probability

    add_data_response(parser)
    add_factor_options(parser)
    add_block_option(parser)
    parser.add_argument("--model", default="saturated", choices=list(MODELS),
                        help="saturated: the largest model the runs estimate, alias chains named (default); "
                             "linear: main effects; 2fi: + two-factor interactions; full: every interaction")
    parser.add_argument("--term", action="append", default=None, metavar="TERM",
                        help="fit only these terms (repeatable, e.g. --term A --term AB); overrides --model")
    from .options import add_terms_options

    add_terms_options(parser)
    parser.add_argument("--alpha", type=probability, default=0.05, metavar="A",
                        help="level of ME and SME (default 0.05)")
    add_plot_option(parser, "the half-normal plot")
    add_json(parser)
    add_force(parser)


def _check_terms(terms) -> None:
    """An empty ``--term`` is named before any data is read."""
    from ..io import InputError

    for t in terms or []:
        if not str(t).strip():
            raise InputError("--term: an empty term was given; give a term such as A, AB or A^2")


@contextmanager
def _about_terms(terms):
    """A term the fit cannot read (a :class:`~rsm_lrg.errors.ParameterError` for ``terms``) is
    the option's fault: ``--term: cannot read model term ...``."""
    from ..errors import ParameterError
    from ..io import InputError

    try:
        yield
    except ParameterError as exc:
        if terms and exc.parameter == "terms":
            raise InputError(f"--term: {exc}") from None
        raise


def _full_terms(letters) -> list[str]:
    """Every product of distinct factors: ``A, B, ..., AB, ..., ABC...``."""
    from itertools import combinations

    return ["".join(c) for r in range(1, len(letters) + 1) for c in combinations(letters, r)]


def run(args: argparse.Namespace) -> int:
    from ..io import dump_json, write_output
    from ..model import fit
    from ..model.readings.effects import largest_estimable_model, screening_effects
    from .paths import read_input

    fmt = plot_format(args.plot)
    _check_terms(args.term)
    data = read_input(args)
    from .specs import model_spec

    given = model_spec(args, order="2fi").terms if args.terms is not None else ()  # a bad --terms named first
    terms = (args.term or []) + list(given or ()) or None  # --term and --terms together
    with about_file(args.data), _about_terms(args.term):
        model = "2fi" if args.model in ("full", "saturated") else args.model
        aliases: dict = {}
        if terms is None and args.model in ("full", "saturated"):  # the factors as the fit finds them
            first = fit(data, args.response, factors=args.factor, block=args.block, model="linear")
            letters = [f.letter for f in first.space.factors]
            if args.model == "full":
                terms = _full_terms(letters)
                n = first.n
                if n < len(terms) + 1:
                    raise ValueError(f"{n} runs cannot fit the full model (every interaction of {len(letters)} "
                                     f"factors: {len(terms)} effects and the intercept); the default --model "
                                     "saturated fits the effects these runs estimate and names their aliases")
            else:
                n_blocks = len(first.block_levels or {}) or 1
                found = largest_estimable_model(first.coded_runs()[letters].to_numpy(dtype=float), letters,
                                                max_terms=first.n - n_blocks)
                terms, aliases = list(found.terms), found.aliases
        result = fit(data, args.response, factors=args.factor, block=args.block, model=model, terms=terms,
                     intercept=not args.no_intercept)
        eff = screening_effects(result, alpha=args.alpha, aliases=aliases)
    figure = None
    if fmt is not None:  # --plot given
        from ..report.plots import figure_bytes, half_normal_plot

        f = eff.to_frame()
        figure = figure_bytes(half_normal_plot(f["abs_effect"], f["half_normal"], f["term"], me=eff.me, sme=eff.sme,
                                               title=f"Half-normal plot: {args.response}"), fmt)
    print_notes(result.input_notes)
    if figure is not None:
        write_output(args.plot, figure, force=args.force)
    if args.json:
        dump_json(eff.to_dict(), args.json, force=args.force)
    if args.json != "-":
        print(f"Data: {args.data}")
        print(eff.summary(), end="")
    return 0
