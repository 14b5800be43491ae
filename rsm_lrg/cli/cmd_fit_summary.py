"""``rsm-lrg fit-summary``: sequential model sums of squares, lack of fit per order, suggested model."""

from __future__ import annotations

import argparse

from .errors import about_file
from .options import add_block_option, add_component_option, add_data_response, add_factor_options, add_force, add_json
from .paths import print_notes, print_summary_or_json

NAME = "fit-summary"
HELP = "compare linear, 2FI, quadratic and cubic models; suggest one"
DESCRIPTION = (
    "Design-Expert style fit summary: sequential (Type I) model sums of squares for the mean, "
    "linear, 2FI, quadratic and cubic models (flagged 'Aliased' where the design cannot "
    "estimate every term), the lack-of-fit test of each order, R², adjusted and predicted R² "
    "and PRESS per order, and the suggested model: the highest order that is significant, "
    "not aliased, and without significant lack of fit. With --component (once per mixture "
    "component, --factor then names process factors) the Scheffé models are compared instead: "
    "mixture linear, quadratic, special cubic and cubic (those the distinct blends can fit), "
    "'Linear vs Mean' being the linear model's sum of squares about the mean; the suggested "
    "model is then named as 'fit --model' takes it."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_data_response(parser)
    add_factor_options(parser)
    add_component_option(parser)
    add_block_option(parser, "entered first")
    from .options import probability

    parser.add_argument("--alpha", type=probability, default=0.05, metavar="A",
                        help="significance level for the suggestion (default 0.05)")
    parser.add_argument("--transform", default=None, metavar="log|log10|sqrt|inverse|power=L",
                        help="compare the models of a transformed response (as 'fit --transform')")
    from .options import number

    parser.add_argument("--transform-constant", type=number(), default=0.0, metavar="K",
                        help="add K to the response before transforming (default 0)")
    parser.add_argument("--gp", action="store_true",
                        help="also fit a Gaussian process and compare its closed-form leave-one-out with the "
                             "polynomials' PRESS (JSON key 'loo_comparison'); --kernel, --trend, --nugget, --seed")
    from .gp_fit import add_gp_options

    add_gp_options(parser)
    add_json(parser)
    add_force(parser)


def run(args: argparse.Namespace) -> int:
    from ..io import InputError
    from ..model.build.data import prepare
    from ..model.choice.summary import fit_summary
    from .gp_fit import check_gp_options, gp_keywords
    from .paths import read_input
    from .specs import model_spec

    spec = model_spec(args, order="mixture-linear" if args.component else None)  # a bad --transform: named first
    check_gp_options(args, on=args.gp, flag="--gp")
    if args.gp:
        for opt, attr in (("--component", "component"), ("--block", "block"), ("--transform", "transform")):
            if getattr(args, attr, None):
                raise InputError(f"--gp: not with {opt} (a Gaussian process takes numeric factors, no blocks or "
                                 "transform)")
    data = read_input(args)
    extra: dict = {}
    with about_file(args.data):
        s = fit_summary(data, args.response, factors=args.factor, block=args.block, alpha=args.alpha,
                        transform=spec.transform, components=args.component)
        names = args.factor if not args.component else list(args.component) + list(args.factor or [])
        notes = prepare(data, args.response, names, args.block).notes
        if args.gp:
            from ..model import fit
            from ..model.choice.loo_compare import compare_loo

            cmp = compare_loo(s, fit(data, args.response, factors=args.factor, model="gp", **gp_keywords(args)))
            extra["loo_comparison"] = cmp.to_dict()
    print_notes(notes)  # after the work: a failed command prints one error line only
    print_summary_or_json(args, s, extra=extra)
    if args.gp and args.json != "-":
        print()
        print(cmp.summary(), end="")
    return 0
